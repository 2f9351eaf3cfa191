// The pulses, and the exact sliding solver against the closed-form responses to them (thesis section 3.2); the
// closed forms against the thesis' printed tables: tests/closed_forms/test_sliding_pulses.cpp.
#include <cmath>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/closed_forms/sliding_pulses.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple {
namespace {

constexpr double kThesisG = 9.81;  // the thesis computes with g = 981 cm/s^2

SlidingSummary slide_pulse(PulseKind kind, double amp_g, double t0, double mu, double g) {
  PulseSpec spec{kind, amp_g * g, t0, 0.0, 0.0};
  return slide_summary(make_pulse(spec), SlidingBlock::make(mu, mu, 0.0, SlidingMode::two_way, g));
}

// The solver is exact on piecewise-linear input; closed form and solver differ only by round-off. 1e-9 relative
// leaves a factor ~1e6 over double precision for the few hundred operations involved.
constexpr double kExact = 1e-9;

TEST(PulseClosedForms, RectangularPulseSolverMatchesNewmark) {
  for (const auto& [a, t0, mu] : {std::tuple{2.0, 0.1, 0.3}, {1.0, 0.2, 0.3}, {0.5, 0.4, 0.3}, {3.0, 0.05, 0.7}}) {
    const auto cf = rectangular_pulse_sliding(a, t0, mu, kThesisG);
    const auto s = slide_pulse(PulseKind::rectangular, a, t0, mu, kThesisG);
    EXPECT_NEAR(s.max_abs_displacement_m, cf.max_displacement_m, kExact * cf.max_displacement_m);
    EXPECT_NEAR(s.residual_displacement_m, cf.max_displacement_m, kExact * cf.max_displacement_m);
    EXPECT_NEAR(s.end_time_s, cf.stop_time_s, kExact * cf.stop_time_s);
    EXPECT_EQ(s.slip_episodes, 1);
    EXPECT_DOUBLE_EQ(*s.first_slip_time_s, 0.0);
  }
}

TEST(PulseClosedForms, RectangularPulseStateAtPulseEnd) {
  PulseSpec spec{PulseKind::rectangular, 2.0 * kThesisG, 0.1, 0.0, 0.0};
  const auto r = slide(make_pulse(spec), SlidingBlock::make(0.3, 0.3, 0.0, SlidingMode::two_way, kThesisG));
  const auto cf = rectangular_pulse_sliding(2.0, 0.1, 0.3, kThesisG);
  // the row at t0 (the jump's second sample carries the state at t0)
  bool found = false;
  for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
    if (r.history.time_s[i] == 0.1) {
      EXPECT_NEAR(r.history.displacement_m[i], cf.end_displacement_m, kExact * cf.end_displacement_m);
      EXPECT_NEAR(r.history.velocity_m_s[i], cf.end_velocity_m_s, kExact * cf.end_velocity_m_s);
      found = true;
    }
  }
  EXPECT_TRUE(found);
}

TEST(PulseClosedForms, TriangularPulseSolverMatchesEquations31To34) {
  for (const auto& [a, t0, mu] : {std::tuple{4.0, 0.05, 0.3}, {2.0, 0.1, 0.3}, {1.0, 0.2, 0.3}, {0.5, 0.4, 0.3}}) {
    const auto cf = triangular_pulse_sliding(a, t0, mu, kThesisG);
    const auto s = slide_pulse(PulseKind::triangular, a, t0, mu, kThesisG);
    EXPECT_NEAR(s.max_abs_displacement_m, cf.max_displacement_m, kExact * cf.max_displacement_m) << a;
    EXPECT_NEAR(*s.first_slip_time_s + s.total_slip_duration_s, cf.stop_time_s, kExact * cf.stop_time_s);
    EXPECT_NEAR(*s.first_slip_time_s, mu * t0 / (2.0 * a), 1e-15);
  }
}

TEST(PulseClosedForms, DoubleTriangularPulseSolverMatchesAtEveryPhase) {
  const double a = 2.0;
  const double t0 = 0.2;
  const double mu = 0.3;
  const auto r = slide(make_pulse({PulseKind::double_triangular, a * kThesisG, t0, 0.5, 0.0}),
                       SlidingBlock::make(mu, mu, 0.0, SlidingMode::two_way, kThesisG));
  int checked = 0;
  for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
    const double t = r.history.time_s[i];
    const auto cf = double_triangular_pulse_sliding(a, t0, mu, t, kThesisG);
    EXPECT_NEAR(r.history.displacement_m[i], cf.displacement_m, kExact * 0.25) << "t = " << t;
    EXPECT_NEAR(r.history.velocity_m_s[i], cf.velocity_m_s, kExact * 1.4) << "t = " << t;
    ++checked;
  }
  EXPECT_GE(checked, 8);
  // Events: slip start, stop at ~0.30547 s with an immediate back slip, final stop after the pulse.
  EXPECT_EQ(r.summary.slip_episodes, 2);
}

TEST(Pulses, ShapesAndNames) {
  const auto rect = make_pulse({PulseKind::rectangular, 2.0, 0.1, 1.0, 0.0});
  EXPECT_DOUBLE_EQ(rect.accel_at(0.05), 2.0);
  EXPECT_DOUBLE_EQ(rect.accel_at(0.1), 0.0);
  EXPECT_DOUBLE_EQ(rect.duration_s(), 1.1);
  const auto sine = make_pulse({PulseKind::sine, 1.0, 1.0, 0.0, 0.001});
  EXPECT_NEAR(sine.accel_at(0.25), 1.0, 1e-12);
  EXPECT_NEAR(sine.accel_at(0.75), -1.0, 1e-12);
  const auto cosine = make_pulse({PulseKind::cosine, 1.0, 2.0, 0.0, 0.001});
  EXPECT_NEAR(cosine.accel_at(0.0), 1.0, 1e-12);
  EXPECT_NEAR(cosine.accel_at(1.0), -1.0, 1e-12);
  const auto ricker = make_pulse({PulseKind::ricker, 1.0, 1.0, 0.0, 0.001});
  EXPECT_NEAR(ricker.accel_at(1.5), 1.0, 1e-12);
  EXPECT_NEAR(ricker.pga_m_s2(), 1.0, 1e-12);
  for (auto k : {PulseKind::rectangular, PulseKind::triangular, PulseKind::double_triangular, PulseKind::sine,
                 PulseKind::cosine, PulseKind::ricker}) {
    EXPECT_EQ(parse_pulse_kind(pulse_kind_name(k)), k);
  }
  EXPECT_THROW((void)parse_pulse_kind("square"), InputError);
  EXPECT_THROW((void)make_pulse({PulseKind::sine, 1.0, 0.0, 0.0, 0.0}), InputError);
}

}  // namespace
}  // namespace topple
