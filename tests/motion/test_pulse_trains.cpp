// Pulses added for synthesis and the thesis' section 3.4: continuous triangular and trapezoidal trains (Figs 3.5,
// 3.6) and the Mavroeidis-Papageorgiou (2003) near-fault pulse.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple {
namespace {

constexpr double kThesisG = 9.81;

PulseSpec train(PulseKind kind, double amp, double period, int cycles) {
  PulseSpec s{kind, amp, period, 0.0, 0.0};
  s.cycles = cycles;
  return s;
}

TEST(PulseTrains, TriangularTrainShape) {
  const GroundMotion m = make_pulse(train(PulseKind::triangular_train, 2.0, 0.4, 3));
  EXPECT_DOUBLE_EQ(m.end_time_s(), 1.2);
  EXPECT_EQ(m.size(), 1U + 4U * 3U);  // start, then four corners per cycle
  for (int c = 0; c < 3; ++c) {
    const double t = 0.4 * c;
    EXPECT_NEAR(m.accel_at(t + 0.1), 2.0, 1e-12);   // +A at T/4
    EXPECT_NEAR(m.accel_at(t + 0.2), 0.0, 1e-12);   // 0 at T/2
    EXPECT_NEAR(m.accel_at(t + 0.3), -2.0, 1e-12);  // -A at 3T/4
    EXPECT_NEAR(m.accel_at(t + 0.05), 1.0, 1e-12);  // linear between
    EXPECT_NEAR(m.accel_at(t + 0.35), -1.0, 1e-12);
  }
  // Whole cycles of a symmetric wave: the ground velocity returns to zero after each cycle.
  const auto vd = integrate_ground(m);
  EXPECT_NEAR(vd.velocity_m_s.back(), 0.0, 1e-15);
  EXPECT_THROW((void)make_pulse(train(PulseKind::triangular_train, 2.0, 0.4, 0)), InputError);
  EXPECT_EQ(parse_pulse_kind("tri-train"), PulseKind::triangular_train);
  EXPECT_EQ(pulse_kind_name(PulseKind::trapezoidal_train), "trap-train");
}

TEST(PulseTrains, TrapezoidalTrainShape) {
  PulseSpec s = train(PulseKind::trapezoidal_train, 1.5, 0.6, 2);  // r = 1/3: ramps and plateau 0.1 s each
  const GroundMotion m = make_pulse(s);
  EXPECT_EQ(m.size(), 1U + 6U * 2U);
  EXPECT_NEAR(m.accel_at(0.05), 0.75, 1e-12);
  EXPECT_NEAR(m.accel_at(0.1), 1.5, 1e-12);
  EXPECT_NEAR(m.accel_at(0.2), 1.5, 1e-12);
  EXPECT_NEAR(m.accel_at(0.3), 0.0, 1e-12);
  EXPECT_NEAR(m.accel_at(0.45), -1.5, 1e-12);
  EXPECT_NEAR(m.accel_at(0.6 + 0.15), 1.5, 1e-12);
  // r = 1/2 is the triangular train.
  s.trapezoid_ramp_fraction = 0.5;
  const GroundMotion tri = make_pulse(s);
  const GroundMotion ref = make_pulse(train(PulseKind::triangular_train, 1.5, 0.6, 2));
  for (double t = 0.0; t <= 1.2; t += 0.01) EXPECT_NEAR(tri.accel_at(t), ref.accel_at(t), 1e-12) << t;
  s.trapezoid_ramp_fraction = 0.0;
  EXPECT_THROW((void)make_pulse(s), InputError);
}

/// Per-cycle maximum and minimum of the relative displacement under a train.
std::vector<std::pair<double, double>> cycle_extremes(const SlidingHistory& h, double period, int cycles) {
  std::vector<std::pair<double, double>> out(static_cast<std::size_t>(cycles), {-1e300, 1e300});
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const auto c = static_cast<int>(std::floor(h.time_s[i] / period * (1.0 - 1e-12)));
    if (c < 0 || c >= cycles) continue;
    auto& [hi, lo] = out[static_cast<std::size_t>(c)];
    hi = std::max(hi, h.displacement_m[i]);
    lo = std::min(lo, h.displacement_m[i]);
  }
  return out;
}

TEST(PulseTrains, SlidingUnderTheTriangularTrainReachesASteadyOscillation) {
  // Thesis section 3.4: "the rigid object attains a stable position of vibratory motion about a centre of
  // oscillation after two or three cycles of the ground pulse" (mu = 0.4, Fig. 3.5). The cycle-to-cycle change of
  // the displacement extremes shrinks geometrically; by the fourth cycle it is below 1 % of the oscillation's
  // amplitude when A <= 2.5 mu (the thesis' case: at 1 g it is 2e-5 after two cycles); stronger trains converge
  // more slowly (factor 5 per cycle at 1.5 g, 3 at 2 g) but monotonically, below 1 % after 12 cycles.
  // The centre of oscillation is offset from zero.
  for (const auto& [amp_g, period] : {std::pair{1.0, 0.24}, {0.7, 0.5}, {1.5, 0.3}, {2.0, 0.2}}) {
    const int cycles = 12;
    const auto r = slide(make_pulse(train(PulseKind::triangular_train, amp_g * kThesisG, period, cycles)),
                         SlidingBlock::make(0.4, 0.4, 0.0, SlidingMode::two_way, kThesisG));
    const auto ex = cycle_extremes(r.history, period, cycles);
    const double amplitude = ex.back().first - ex.back().second;
    ASSERT_GT(amplitude, 0.0);
    std::vector<double> change;
    for (std::size_t c = 1; c < ex.size(); ++c) {
      change.push_back(std::abs(ex[c].first - ex[c - 1].first) + std::abs(ex[c].second - ex[c - 1].second));
    }
    if (amp_g <= 1.0) {
      EXPECT_LT(change[2], 0.01 * amplitude) << amp_g << " g: cycle 3 -> 4 change " << change[2] / amplitude;
    }
    EXPECT_LT(change.back(), 0.01 * amplitude) << amp_g << " g: last change " << change.back() / amplitude;
    for (std::size_t c = 3; c < change.size(); ++c) {
      // Contracting to the periodic state (until round-off, 1e-12 of the amplitude).
      EXPECT_LE(change[c], std::max(change[c - 1], 1e-12 * amplitude)) << amp_g << " g, cycle " << c;
    }
    const double centre = 0.5 * (ex.back().first + ex.back().second);
    EXPECT_GT(std::abs(centre), 0.05 * amplitude) << "the oscillation is about an offset centre";
  }
}

TEST(PulseTrains, Figure35CaptionWithInferredAmplitudeAndPeriod) {
  // Fig. 3.5's caption prints max relative displacement 1.48 cm and residual 0.0895 cm; the figure's amplitude and
  // period are not in the text. The ratio max/residual depends only on A/mu (displacements scale as g T^2): a
  // search over A found that A = 1 g gives the printed ratio (16.5; topple 16.8), and T = 0.24 s then gives
  // 1.48 cm. The residual is the check: 0.0882 cm against 0.0895 printed (1.5 %, the precision of a 1971 plot
  // reading). These are our inferred parameters, not the thesis'; the sign of the residual depends on the
  // polarity of the first half cycle, which the caption does not show.
  const auto s = slide_summary(make_pulse(train(PulseKind::triangular_train, 1.0 * kThesisG, 0.24, 5)),
                               SlidingBlock::make(0.4, 0.4, 0.0, SlidingMode::two_way, kThesisG));
  EXPECT_NEAR(s.max_abs_displacement_m * 100.0, 1.48, 0.01);
  EXPECT_NEAR(std::abs(s.residual_displacement_m) * 100.0, 0.0895, 0.002);
}

// ---- Mavroeidis & Papageorgiou (2003) ----

TEST(PulseMavroeidis, PeakVelocityAndClosedForms) {
  const MavroeidisPapageorgiouPulse mp{0.8, 1.25, 0.0, 2.0};  // A = 0.8 m/s, f_p = 1.25 Hz, nu = 0, gamma = 2
  // nu = 0: the velocity peaks at the envelope centre with v = A (eq. 1: (A/2)(1 + 1) cos 0).
  EXPECT_DOUBLE_EQ(mp.velocity_m_s(mp.centre_time_s()), 0.8);
  double vmax = 0.0;
  for (double t = 0.0; t <= mp.duration_s(); t += 1e-4) vmax = std::max(vmax, std::abs(mp.velocity_m_s(t)));
  EXPECT_NEAR(vmax, 0.8, 1e-12);
  // The sampled acceleration integrates back to the closed-form velocity and displacement: chords of a smooth
  // curve at 4000 samples per pulse leave O((2 pi f_p dt)^2) ~ 1e-6 relative.
  const double dt = mp.duration_s() / 4000.0;
  const GroundMotion m = make_mavroeidis_papageorgiou_pulse(mp, dt, 0.5);
  const auto vd = integrate_ground(m);
  for (std::size_t i = 0; i < m.size(); i += 250) {
    const double t = m.time_s(i);
    EXPECT_NEAR(vd.velocity_m_s[i], mp.velocity_m_s(t), 2e-6 * 0.8) << t;
    EXPECT_NEAR(vd.displacement_m[i], mp.displacement_m(t), 2e-6 * 0.2) << t;
  }
  // The acceleration is the derivative of eq. 1 (central differences, O(h^2) = 1e-8 relative).
  for (double t : {0.1, 0.5, 0.8, 1.3}) {
    const double h = 1e-5;
    const double numeric = (mp.velocity_m_s(t + h) - mp.velocity_m_s(t - h)) / (2.0 * h);
    EXPECT_NEAR(mp.acceleration_m_s2(t), numeric, 1e-6 * std::abs(numeric) + 1e-8) << t;
  }
  EXPECT_EQ(m.accel_m_s2()[0], 0.0);
  // The sampled pulse's PGA is the closed form's peak (dense search, 1e-6 s), to the sampling's O((w dt)^2 / 8).
  double amax = 0.0;
  for (double t = 0.0; t <= mp.duration_s(); t += 1e-6) amax = std::max(amax, std::abs(mp.acceleration_m_s2(t)));
  EXPECT_NEAR(m.pga_m_s2(), amax, 1e-5 * amax);
  EXPECT_LT(amax, 2.0 * kPi * 1.25 * 0.8);  // below the carrier's 2 pi f_p A: the envelope tapers it
}

TEST(PulseMavroeidis, VelocityAtAPointWithPhase) {
  // nu = pi/3, gamma = 1.5: at t = t0 + 1 / (8 f_p), u = pi/4: v = (A/2)(1 + cos(pi/6)) cos(pi/4 + pi/3).
  const MavroeidisPapageorgiouPulse mp{1.2, 0.5, kPi / 3.0, 1.5};
  const double t = mp.centre_time_s() + 1.0 / (8.0 * 0.5);
  const double expected = 0.6 * (1.0 + std::cos(kPi / 6.0)) * std::cos(kPi / 4.0 + kPi / 3.0);
  EXPECT_NEAR(mp.velocity_m_s(t), expected, 1e-15);
  EXPECT_EQ(mp.velocity_m_s(-0.1), 0.0);
  EXPECT_EQ(mp.velocity_m_s(mp.duration_s() + 0.1), 0.0);
  const GroundMotion m = make_mavroeidis_papageorgiou_pulse(mp, 0.0005);
  const auto vd = integrate_ground(m);
  const auto i = static_cast<std::size_t>(std::lround(t / 0.0005));
  EXPECT_NEAR(vd.velocity_m_s[i], mp.velocity_m_s(m.time_s(i)), 1e-6);
}

TEST(PulseMavroeidis, InvalidParametersNameTheField) {
  try {
    (void)make_mavroeidis_papageorgiou_pulse({1.0, 1.0, 0.0, 1.0});
    ADD_FAILURE() << "gamma = 1 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "gamma");
  }
  EXPECT_THROW((void)make_mavroeidis_papageorgiou_pulse({1.0, 0.0, 0.0, 2.0}), InputError);
}

}  // namespace
}  // namespace topple
