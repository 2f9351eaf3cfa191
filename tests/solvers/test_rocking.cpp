// The rocking engine against the closed forms and reference numbers of shared/references/rocking.md (R1-R8, P1,
// S1, section 4), its invariants, and the adaptive solver against the thesis' fixed-step RK4.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/noise_record.hpp"
#include "support/shared_data.hpp"
#include "support/rocking_references.hpp"
#include "topple/closed_forms/rocking.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/threshold_search.hpp"

namespace topple {
namespace {

using test::block_alpha_p;
using test::kG;
using test::kPrinted6;
using test::r4_block;

GroundMotion still_ground(double duration_s, double dt_s = 0.01) {
  const auto n = static_cast<std::size_t>(std::llround(duration_s / dt_s)) + 1;
  return GroundMotion::uniform(std::vector<double>(n, 0.0), dt_s);
}

RockingOptions with_e(double e, double g = kG) {
  RockingOptions o;
  o.g_m_s2 = g;
  o.restitution = RestitutionMode::given;
  o.e = e;
  return o;
}

RockingOptions housner(double g = kG) {
  RockingOptions o;
  o.g_m_s2 = g;
  return o;
}

std::vector<RockingEvent> events_of(const RockingResult& r, RockingEventKind kind) {
  std::vector<RockingEvent> out;
  for (const auto& ev : r.events) {
    if (ev.kind == kind) out.push_back(ev);
  }
  return out;
}

/// A reproducible broadband motion (tests/support): resonator-filtered noise near 2.5 Hz under a rise-and-decay
/// envelope peaking at a fifth of the record.
GroundMotion noisy_record(unsigned seed, std::size_t n, double dt, double pga_m_s2) {
  return test::noise_record({.seed = seed, .samples = n, .dt_s = dt, .pga_m_s2 = pga_m_s2, .resonance_hz = 2.5,
                             .pole_radius = 0.97, .envelope_peak_s = 0.2 * static_cast<double>(n) * dt});
}

// ---------------------------------------------------------------------------------------------------------------
// Bodies and validation

TEST(RockingBody, ShapesGiveTheThesisMomentsOfInertia) {
  const auto b = RockingBody::block(0.04, 0.20);  // thesis object A, 4 x 20 cm
  EXPECT_DOUBLE_EQ(b.a_m, 0.02);
  EXPECT_DOUBLE_EQ(b.h_m, 0.10);
  EXPECT_DOUBLE_EQ(b.D_m2, (16.0 * 0.02 * 0.02 + 16.0 * 0.10 * 0.10) / 12.0);  // thesis eq 3.14
  EXPECT_DOUBLE_EQ(b.alpha_rad(), std::atan(0.2));
  const auto c = RockingBody::cylinder(0.04, 0.20);
  EXPECT_DOUBLE_EQ(c.D_m2, (15.0 * 0.02 * 0.02 + 16.0 * 0.10 * 0.10) / 12.0);  // thesis eq 3.13
  const auto g = RockingBody::general(0.02, 0.10, 0.011);
  EXPECT_EQ(g.shape, RockingBody::Shape::general);
  // D = a^2 + h^2 exactly (all the mass at the CM) is a real, if extreme, body.
  EXPECT_NO_THROW((void)RockingBody::general(0.3, 0.4, 0.25));
}

TEST(RockingBody, R4GeometryAndFrequencyParameter) {
  // rocking.md R4: H = 4.933155 m, R = 2.516745 m, p = 1.709801 rad/s (printed to 6 decimals).
  const auto b = r4_block();
  EXPECT_NEAR(2.0 * b.h_m, 4.933155, kPrinted6);
  EXPECT_NEAR(b.R_m(), 2.516745, kPrinted6);
  EXPECT_NEAR(b.p_rad_s(kG), 1.709801, kPrinted6);
  // Block: p = sqrt(3 g / (4 R)) (section 0), to round-off.
  EXPECT_NEAR(b.p_rad_s(kG), std::sqrt(3.0 * kG / (4.0 * b.R_m())), 1e-14);
}

TEST(RockingBody, InvalidGeometryIsAnInputErrorNamingTheField) {
  const auto expect_field = [](auto make, const std::string& field) {
    try {
      (void)make();
      FAIL() << "expected InputError for " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, field) << e.what();
    }
  };
  expect_field([] { return RockingBody::block(0.0, 0.2); }, "width");
  expect_field([] { return RockingBody::block(-0.04, 0.2); }, "width");
  expect_field([] { return RockingBody::block(0.04, std::nan("")); }, "height");
  expect_field([] { return RockingBody::cylinder(0.04, -1.0); }, "height");
  expect_field([] { return RockingBody::cylinder(INFINITY, 1.0); }, "diameter");
  expect_field([] { return RockingBody::general(0.0, 0.1, 0.1); }, "a");
  expect_field([] { return RockingBody::general(0.1, 0.0, 0.1); }, "h");
  // D below a^2 + h^2 = 0.02 is no real body.
  expect_field([] { return RockingBody::general(0.1, 0.1, 0.0199); }, "D");
  try {
    (void)RockingBody::general(0.1, 0.1, 0.0199);
    FAIL() << "expected InputError for D";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a^2 + h^2"), std::string::npos) << e.what();
  }
}

TEST(RockingOptions, InvalidOptionsAreInputErrors) {
  const auto b = RockingBody::block(0.04, 0.20);
  const auto m = still_ground(1.0);
  const auto expect_field = [&](RockingOptions o, const std::string& field) {
    try {
      (void)rock_summary(m, b, o);
      FAIL() << "expected InputError for " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, field) << e.what();
    }
  };
  expect_field(with_e(1.2), "e");
  expect_field(with_e(-0.1), "e");
  expect_field(with_e(std::nan("")), "e");
  auto o = housner();
  o.g_m_s2 = 0.0;
  expect_field(o, "g");
  o = housner();
  o.mu = -0.5;
  expect_field(o, "mu");
  o = housner();
  o.rel_tol = 0.0;
  expect_field(o, "rel_tol");
  o = housner();
  o.initial_theta_rad = 2.0;
  expect_field(o, "initial_theta_rad");
  // Housner's e is negative for a block with alpha > 54.7 deg: no silent clamp, the caller must give e.
  const auto squat = RockingBody::block(1.0, 0.5);
  try {
    (void)rock_summary(m, squat, housner());
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "e");
  }
  EXPECT_NO_THROW((void)rock_summary(m, squat, with_e(0.0)));
  // A vertical input that cancels gravity would lift the body off: refused, naming the input.
  const auto down = GroundMotion::uniform({-1.1 * kG, -1.1 * kG}, 1.0);
  try {
    (void)rock_summary(m, b, housner(), &down);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "vertical");
  }
}

TEST(RockingLimits, MaxStepsIsAStepLimitErrorQuotingTheLimitAndTheBody) {
  // A sine pulse that rocks the block needs hundreds of steps; a cap of 10 is reached, for either method.
  const auto b = RockingBody::block(0.04, 0.20);
  PulseSpec spec;
  spec.kind = PulseKind::sine;
  spec.amplitude_m_s2 = 0.5 * kG;
  spec.duration_s = 0.5;
  const auto pulse = make_pulse(spec);
  for (const auto method : {RockingMethod::adaptive, RockingMethod::rk4}) {
    auto o = housner();
    o.method = method;
    ASSERT_GT(rock_summary(pulse, b, o).steps, 10u);
    o.max_steps = 10;
    try {
      (void)rock_summary(pulse, b, o);
      FAIL() << "expected StepLimitError";
    } catch (const StepLimitError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("max_steps = 10"), std::string::npos) << what;
      EXPECT_NE(what.find("a = 0.02 m, h = 0.1 m"), std::string::npos) << what;
      EXPECT_NE(what.find("raise max_steps"), std::string::npos) << what;
    }
    // The typed error is a SolverError (exit status 3 in the CLI).
    EXPECT_THROW((void)rock(pulse, b, o), SolverError);
  }
  auto o = housner();
  o.max_steps = 0;
  EXPECT_THROW((void)rock_summary(pulse, b, o), InputError);
}

TEST(RockingLimits, ThresholdSearchMaxRunsIsASearchLimitError) {
  const auto b = RockingBody::block(0.04, 0.20);
  const auto motion_for = [](double amp_g) {
    PulseSpec spec;
    spec.kind = PulseKind::sine;
    spec.amplitude_m_s2 = amp_g * kG;
    spec.duration_s = 0.5;
    return make_pulse(spec);
  };
  ThresholdSearch search;
  search.start = 0.1;
  search.step = 0.1;
  search.max = 3.0;
  search.max_runs = 2;
  try {
    (void)first_overturning_amplitude(motion_for, b, housner(), OverturnCriterion::falls, search);
    FAIL() << "expected SearchLimitError";
  } catch (const SearchLimitError& e) {
    EXPECT_NE(std::string(e.what()).find("max_runs = 2"), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------------
// R2, R3: Housner's impact law

TEST(RockingRestitution, R2RectangleTable) {
  // e = 1 - 1.5 sin^2(alpha) and r = e^2, rocking.md R2 table (6 decimals).
  const double alphas[] = {5, 10, 15, 20, 30, 45};
  const double e_tab[] = {0.988606, 0.954769, 0.899519, 0.824533, 0.625000, 0.250000};
  const double r_tab[] = {0.977341, 0.911585, 0.809135, 0.679855, 0.390625, 0.062500};
  for (int i = 0; i < 6; ++i) {
    const auto b = RockingBody::block(2.0 * std::sin(deg_to_rad(alphas[i])), 2.0 * std::cos(deg_to_rad(alphas[i])));
    const double e = housner_restitution(b);
    EXPECT_NEAR(e, e_tab[i], kPrinted6) << alphas[i];
    EXPECT_NEAR(e * e, r_tab[i], kPrinted6) << alphas[i];
    // The pure formula, to a few ulps (the body is built from sin and cos of alpha).
    EXPECT_NEAR(e, 1.0 - 1.5 * std::pow(std::sin(deg_to_rad(alphas[i])), 2), 1e-12);
  }
  // Exact values at 30 and 45 degrees (sin^2 = 1/4, 1/2).
  EXPECT_NEAR(housner_restitution(RockingBody::block(1.0, std::sqrt(3.0))), 0.625, 1e-12);
  EXPECT_NEAR(housner_restitution(RockingBody::block(1.0, 1.0)), 0.25, 1e-12);
}

TEST(RockingRestitution, R3CylinderTable) {
  // e_cyl = 1 - 24 a^2 / (15 a^2 + 16 h^2), p sqrt(R) in sqrt(m)/s, rocking.md R3 (g = 9.81).
  const double ratio[] = {1.0, 0.5, 0.25};
  const double alpha_tab[] = {0.785398, 0.463648, 0.244979};
  const double e_cyl[] = {0.225806, 0.696203, 0.911439};
  const double e_rect[] = {0.250000, 0.700000, 0.911765};
  const double p_cyl[] = {2.75587, 2.72958, 2.71747};
  for (int i = 0; i < 3; ++i) {
    const double h = 1.0;
    const double a = ratio[i] * h;
    const auto c = RockingBody::cylinder(2.0 * a, 2.0 * h);
    const auto r = RockingBody::block(2.0 * a, 2.0 * h);
    EXPECT_NEAR(c.alpha_rad(), alpha_tab[i], kPrinted6);
    EXPECT_NEAR(housner_restitution(c), e_cyl[i], kPrinted6);
    EXPECT_NEAR(housner_restitution(r), e_rect[i], kPrinted6);
    // Two algebraic routes to the same number (1 - 2a^2/D vs the cylinder's form): round-off.
    EXPECT_NEAR(housner_restitution(c), 1.0 - 24.0 * a * a / (15.0 * a * a + 16.0 * h * h), 1e-12);
    EXPECT_NEAR(c.p_rad_s(kG) * std::sqrt(c.R_m()), p_cyl[i], 5e-6);  // printed to 5 decimals
    EXPECT_NEAR(r.p_rad_s(kG) * std::sqrt(r.R_m()), 2.71247, 5e-6);
  }
  // a/h = 1: e_cyl = 1 - 24/31 = 7/31 exactly.
  EXPECT_NEAR(housner_restitution(RockingBody::cylinder(2.0, 2.0)), 7.0 / 31.0, 1e-15);
  // General body: e = 1 - 2 a^2 / D.
  EXPECT_NEAR(housner_restitution(RockingBody::general(0.1, 0.3, 0.2)), 0.9, 1e-15);
}

TEST(RockingImpact, IntegratedImpactScalesVelocityByEAndEnergyByESquared) {
  // Free rocking of the R4 block from theta0 = 0.5 alpha: at every impact theta'_after / theta'_before = e and the
  // velocity keeps its sign (the body continues onto the other edge). The ratio is applied at the located instant,
  // so it holds to round-off; 1e-6 is rocking.md's tolerance for an integrated impact.
  const auto b = r4_block();
  for (double e : {0.5, 0.75, housner_restitution(b)}) {
    auto o = with_e(e);
    o.initial_theta_rad = 0.5 * b.alpha_rad();
    const auto r = rock(still_ground(8.0), b, o);
    const auto impacts = events_of(r, RockingEventKind::impact);
    ASSERT_GE(impacts.size(), 3u) << e;
    for (const auto& ev : impacts) {
      // The law is applied exactly; 1e-6 is the reference's printed precision (rocking.md R2), kept as the bound.
      EXPECT_NEAR(ev.theta_dot_after_rad_s / ev.theta_dot_before_rad_s, e, 1e-6);
      EXPECT_GT(ev.theta_dot_after_rad_s * ev.theta_dot_before_rad_s, 0.0);
    }
    // Energy per impact: D theta'^2 / 2 is multiplied by e^2.
    const double lost = 0.5 * b.D_m2 * std::pow(impacts[0].theta_dot_before_rad_s, 2) * (1.0 - e * e);
    const double ke_after = 0.5 * b.D_m2 * std::pow(impacts[0].theta_dot_after_rad_s, 2);
    EXPECT_NEAR(ke_after / (0.5 * b.D_m2 * std::pow(impacts[0].theta_dot_before_rad_s, 2)), e * e, 1e-12);
    EXPECT_GT(lost, 0.0);
  }
}

// ---------------------------------------------------------------------------------------------------------------
// R1: rocking starts only above g tan(alpha)

TEST(RockingOnset, R1ConstantAccelerationBelowAndAboveThreshold) {
  const auto b = RockingBody::block(2.0 * 0.29, 2.0 * 1.18);  // rocking.md R1: b = 0.29 m, h = 1.18 m
  EXPECT_NEAR(b.p_rad_s(kG), 2.460689, kPrinted6);
  const double threshold = kG * 0.29 / 1.18;
  // 0.95 g tan(alpha) for 3 s: theta stays exactly 0 (boolean check, rocking.md).
  const auto below = rock(GroundMotion::uniform({-0.95 * threshold, -0.95 * threshold}, 3.0), b, housner());
  EXPECT_EQ(below.summary.max_abs_rotation_rad, 0.0);
  EXPECT_EQ(below.summary.uplifts, 0u);
  EXPECT_FALSE(below.summary.uplift_time_s);
  for (double th : below.history.theta_rad) EXPECT_EQ(th, 0.0);
  // 1.15 g tan(alpha) for 3 s overturns.
  const auto above = rock(GroundMotion::uniform({-1.15 * threshold, -1.15 * threshold}, 3.0), b, housner());
  EXPECT_TRUE(above.summary.overturned);
  ASSERT_TRUE(above.summary.overturn_time_s);
  EXPECT_LT(*above.summary.overturn_time_s, 3.0);
  EXPECT_EQ(above.summary.end_state, RockingState::fallen);
  EXPECT_EQ(above.history.state.back(), RockingState::fallen);
  // Sign convention: a ground acceleration toward -x drives theta > 0 (rotation about the +x edge).
  EXPECT_GT(above.history.theta_rad.back(), 0.0);
  EXPECT_NEAR(above.history.theta_rad.back(), kPi / 2.0, 1e-12);
  const auto mirrored = rock(GroundMotion::uniform({1.15 * threshold, 1.15 * threshold}, 3.0), b, housner());
  EXPECT_LT(mirrored.history.theta_rad.back(), 0.0);
  // Mirror symmetry: same fall time, to round-off of the event location.
  EXPECT_NEAR(*mirrored.summary.overturn_time_s, *above.summary.overturn_time_s, 1e-12);
}

TEST(RockingOnset, UpliftIsLocatedExactlyOnThePiecewiseLinearInput) {
  // Triangular pulse 0 -> A at t0/2 -> 0: |a| = g tan(alpha) at t = (g tan(alpha) / A) t0 / 2, the root of a linear
  // function, found to round-off.
  const auto b = RockingBody::block(0.04, 0.20);
  const double A = 0.5 * kG;
  const double t0 = 0.4;
  PulseSpec spec;
  spec.kind = PulseKind::triangular;
  spec.amplitude_m_s2 = A;
  spec.duration_s = t0;
  const auto r = rock_summary(make_pulse(spec), b, housner());
  ASSERT_TRUE(r.uplift_time_s);
  // The uplift is the root of a linear function, located exactly: round-off on t ~ 0.08 s.
  EXPECT_NEAR(*r.uplift_time_s, kG * 0.2 / A * t0 / 2.0, 1e-14);
  EXPECT_GE(r.uplifts, 1u);
}

TEST(RockingOnset, VerticalAccelerationScalesTheThreshold) {
  // A constant a_v = -g/2 halves the effective gravity: 0.6 g tan(alpha) rocks the body with it, not without it.
  const auto b = RockingBody::block(0.04, 0.20);
  const double thr = kG * 0.2;
  const auto h = GroundMotion::uniform({-0.6 * thr, -0.6 * thr}, 0.5);
  const auto v = GroundMotion::uniform({-0.5 * kG, -0.5 * kG}, 0.5);
  EXPECT_FALSE(rock_summary(h, b, housner()).uplift_time_s);
  const auto with_v = rock_summary(h, b, housner(), &v);
  ASSERT_TRUE(with_v.uplift_time_s);
  EXPECT_EQ(*with_v.uplift_time_s, 0.0);
  EXPECT_GT(with_v.max_abs_rotation_rad, 0.0);
  // A vertical record of zeros on another grid changes nothing (the union of grids is exact): same response to
  // within the tolerance-level differences of the different step sequence it implies (rel_tol 1e-8 -> 1e-6).
  const auto rec = noisy_record(11, 600, 0.01, 0.25 * kG);
  const auto zeros = GroundMotion::uniform(std::vector<double>(400, 0.0), 0.015);
  const auto plain = rock_summary(rec, b, housner());
  const auto merged = rock_summary(rec, b, housner(), &zeros);
  ASSERT_GT(plain.impacts, 0u);
  EXPECT_NEAR(merged.max_abs_rotation_rad, plain.max_abs_rotation_rad, 1e-6 * plain.max_abs_rotation_rad);
  EXPECT_EQ(merged.uplift_time_s, plain.uplift_time_s);
  // The union keeps the jumps of a rectangular pulse: same fall with and without a zero vertical record.
  PulseSpec spec;
  spec.kind = PulseKind::rectangular;
  spec.amplitude_m_s2 = -0.5 * kG;
  spec.duration_s = 0.4;
  const auto rect = make_pulse(spec);
  const auto alone = rock_summary(rect, b, housner());
  const auto with_zeros = rock_summary(rect, b, housner(), &zeros);
  ASSERT_TRUE(alone.overturned);
  ASSERT_TRUE(with_zeros.overturned);
  // The zero record extends the grid past the pulse (steps then stop at its samples instead of running free):
  // the integration error at rel_tol 1e-8 over ~1 s of motion, ~1e-10 s, with a margin of 10.
  EXPECT_NEAR(*with_zeros.overturn_time_s, *alone.overturn_time_s, 1e-9);
}

TEST(RockingOnset, ConstantVerticalEqualsScaledGravity) {
  // The equation of motion holds g only through g + a_v: a constant a_v over the whole response is the same body
  // under g' = g + a_v. A vertical record on another grid (every 0.07 s, to 5 s, past the end of the motion) must
  // give that response: the shared input grid keeps the sine pulse's samples and adds the vertical's.
  const auto b = RockingBody::block(0.04, 0.20);
  const double av = -0.2 * kG;
  PulseSpec spec;
  spec.kind = PulseKind::sine;
  spec.amplitude_m_s2 = 0.3 * kG;
  spec.duration_s = 0.5;
  const auto pulse = make_pulse(spec);
  const auto vertical = GroundMotion::uniform(std::vector<double>(72, av), 0.07);
  auto o = housner();
  o.rel_tol = 1e-11;
  auto o_scaled = housner(kG + av);
  o_scaled.rel_tol = 1e-11;
  const auto with_v = rock_summary(pulse, b, o, &vertical);
  const auto scaled = rock_summary(pulse, b, o_scaled);
  ASSERT_TRUE(scaled.uplift_time_s);
  ASSERT_TRUE(with_v.uplift_time_s);
  ASSERT_GT(scaled.impacts, 0u);
  // Uplift is the root of a linear function: round-off (1e-15 s on t ~ 0.1 s).
  EXPECT_NEAR(*with_v.uplift_time_s, *scaled.uplift_time_s, 1e-15);
  // The two runs scale the state by p and p' (error control differs), so they agree to the integration tolerance:
  // rel_tol 1e-11 per step, a few hundred steps -> 1e-8 relative leaves a margin of 10.
  EXPECT_NEAR(with_v.max_abs_rotation_rad, scaled.max_abs_rotation_rad, 1e-8 * scaled.max_abs_rotation_rad);
}

// ---------------------------------------------------------------------------------------------------------------
// R4-R6: free rocking

TEST(RockingFree, R4PeriodOfFreeRockingWithoutLoss) {
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  // The closed forms against rocking.md (T_lin = 3.080962 s, T = 3.084580 s): tests/closed_forms/.
  // Integrated with e = 1 from rest at theta0: impacts at T/4, 3T/4, 5T/4, ... Tolerance 1e-6 relative
  // (rocking.md); rel_tol 1e-10 puts the integration error two orders below it.
  auto o = with_e(1.0);
  o.initial_theta_rad = theta0;
  o.rel_tol = 1e-10;
  const auto r = rock(still_ground(10.0), b, o);
  const auto impacts = events_of(r, RockingEventKind::impact);
  ASSERT_GE(impacts.size(), 5u);
  const double T = free_rocking_period_s(b, theta0, kG);
  EXPECT_NEAR(impacts[0].time_s, T / 4.0, 1e-6 * T);
  EXPECT_NEAR(impacts[2].time_s - impacts[0].time_s, T, 1e-6 * T);
  EXPECT_NEAR(impacts[4].time_s - impacts[2].time_s, T, 1e-6 * T);
  // The nonlinear period is longer than Housner's linearised one by ~0.12% at alpha = 0.2 (rocking.md: do not test
  // the nonlinear solver against T_lin tighter than ~0.2%).
  EXPECT_NEAR(impacts[2].time_s - impacts[0].time_s, linearized_free_rocking_period_s(b, theta0, kG), 2e-3 * T);
}

TEST(RockingConvergence, Rk4IsFourthOrderInItsStep) {
  // Free rocking from rest at theta0 (R4 body, e = 1): the first impact is at T/4, T from the quadrature (1e-14).
  // Classical RK4 with step h = dt / n (its dense output is an RK4 step of the partial length, also of order 4):
  // halving h must divide the impact-time error by 2^4 = 16. Observed orders within 0.2 of 4: at p h = 0.2 ... 0.025
  // the next term of the error still shows (3.85, 3.92, 3.96 measured); the smallest error, ~5e-8 s, is far above
  // round-off.
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  const double T = free_rocking_period_s(b, theta0, kG);
  std::vector<double> errors;
  for (const int n : {2, 4, 8, 16}) {
    auto o = with_e(1.0);
    o.initial_theta_rad = theta0;
    o.method = RockingMethod::rk4;
    o.rk4_substeps = n;
    const auto impacts = events_of(rock(still_ground(1.0, 0.25), b, o), RockingEventKind::impact);
    ASSERT_FALSE(impacts.empty());
    errors.push_back(std::abs(impacts[0].time_s - T / 4.0));
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double order = std::log2(errors[k] / errors[k + 1]);
    EXPECT_NEAR(order, 4.0, 0.2) << "h = dt/" << (2 << k) << ", error " << errors[k] << " s";
  }
}

TEST(RockingConvergence, AdaptiveErrorFollowsItsTolerance) {
  // Dormand-Prince 5(4) with error per step controlled to rel_tol: steps scale as rel_tol^(1/5) and the propagated
  // 5th-order solution's error as (rel_tol^(1/5))^5 = rel_tol, so a 100x tighter tolerance gives a ~100x smaller
  // impact-time error (slope 1 in log-log). Observed slopes within 0.25 of 1 (0.88 and 0.96 measured: the
  // controller's safety factors make it approach 1 from below at loose tolerances).
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  const double T = free_rocking_period_s(b, theta0, kG);
  const std::vector<double> tols{1e-5, 1e-7, 1e-9};
  std::vector<double> errors;
  for (const double tol : tols) {
    auto o = with_e(1.0);
    o.initial_theta_rad = theta0;
    o.rel_tol = tol;
    o.abs_tol = 1e-3 * tol;
    const auto impacts = events_of(rock(still_ground(1.0, 1.0), b, o), RockingEventKind::impact);
    ASSERT_FALSE(impacts.empty());
    errors.push_back(std::abs(impacts[0].time_s - T / 4.0));
  }
  for (std::size_t k = 0; k + 1 < errors.size(); ++k) {
    const double slope = std::log10(errors[k] / errors[k + 1]) / std::log10(tols[k] / tols[k + 1]);
    EXPECT_NEAR(slope, 1.0, 0.25) << "rel_tol " << tols[k] << ", error " << errors[k] << " s";
  }
}

TEST(RockingFree, CylinderAndGeneralBodiesFollowTheSameClosedFormsInPAndAlpha) {
  // The equation of motion depends on the body through alpha and p only (and e), so the free-rocking period of a
  // cylinder and of a general body obeys the same quadrature. 1e-6 relative as in R4.
  for (const auto& b : {RockingBody::cylinder(0.3, 1.2), RockingBody::general(0.2, 0.9, 1.1)}) {
    const double theta0 = 0.6 * b.alpha_rad();
    auto o = with_e(1.0);
    o.initial_theta_rad = theta0;
    o.rel_tol = 1e-10;
    const double T = free_rocking_period_s(b, theta0, kG);
    const auto r = rock(still_ground(3.5 * T), b, o);
    const auto impacts = events_of(r, RockingEventKind::impact);
    ASSERT_GE(impacts.size(), 3u);
    EXPECT_NEAR(impacts[2].time_s - impacts[0].time_s, T, 1e-6 * T);
    // Energy closed form; rel_tol 1e-10 integration leaves ~1e-9 rad/s, 1e-7 is the printed-digit scale of R5.
    EXPECT_NEAR(std::abs(impacts[0].theta_dot_before_rad_s), free_rocking_impact_speed_rad_s(b, theta0, kG), 1e-7);
  }
}

TEST(RockingFree, R5SpeedAtFirstImpact) {
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  EXPECT_NEAR(housner_restitution(b), 0.940796, kPrinted6);
  auto o = housner();
  o.initial_theta_rad = theta0;
  o.rel_tol = 1e-10;
  const auto r = rock(still_ground(3.0), b, o);
  const auto impacts = events_of(r, RockingEventKind::impact);
  ASSERT_FALSE(impacts.empty());
  // Released at theta0 > 0 it falls back with theta' < 0 and continues onto the other edge: both speeds negative.
  EXPECT_NEAR(impacts[0].theta_dot_before_rad_s, -0.295529, 1e-6);
  EXPECT_NEAR(impacts[0].theta_dot_after_rad_s, -0.278033, 1e-6);
}

TEST(RockingFree, R6AmplitudeDecayFollowsTheExactRecursion) {
  const auto b = r4_block();
  const double alpha = b.alpha_rad();
  const double theta0 = 0.5 * alpha;
  const double e = housner_restitution(b);
  // The recursion against rocking.md R6's nonlinear column: tests/closed_forms/.
  auto o = housner();
  o.initial_theta_rad = theta0;
  o.rel_tol = 1e-10;
  const auto r = rock(still_ground(12.0), b, o);
  // Peaks between impacts: the n-th peak after the start is the amplitude after n impacts. 1e-6 (rocking.md).
  const auto peaks = events_of(r, RockingEventKind::peak);
  ASSERT_GE(peaks.size(), 6u);
  for (int n = 1; n <= 6; ++n) {
    EXPECT_NEAR(std::abs(peaks[static_cast<std::size_t>(n - 1)].theta_rad) / alpha,
                free_rocking_amplitude_rad(b, theta0, e, n) / alpha, 1e-6)
        << n;
  }
  EXPECT_NEAR(r.summary.max_abs_rotation_rad, theta0, 1e-15);  // the start is the largest rotation
}

TEST(RockingFree, LosslessRockingConservesEnergyOver100Impacts) {
  // e = 1: every impact happens at the same speed. 1e-9 relative (rocking.md) needs the integration error per
  // quarter period well below it: rel_tol = abs_tol = 1e-13 (the dense-output location of theta = 0 adds
  // ~rel_tol).
  const auto b = r4_block();
  auto o = with_e(1.0);
  o.initial_theta_rad = 0.5 * b.alpha_rad();
  o.rel_tol = 1e-13;
  o.abs_tol = 1e-13;
  const double T = free_rocking_period_s(b, o.initial_theta_rad, kG);
  const auto r = rock(still_ground(52.0 * T, 0.05), b, o);
  const auto impacts = events_of(r, RockingEventKind::impact);
  ASSERT_GE(impacts.size(), 100u);
  const double w0 = free_rocking_impact_speed_rad_s(b, o.initial_theta_rad, kG);
  // e = 1 conserves energy; at rel_tol 1e-13 the drift over 100 impacts stays below 1e-9 (measured ~1e-11).
  for (std::size_t k = 0; k < 100; ++k) {
    EXPECT_NEAR(std::abs(impacts[k].theta_dot_before_rad_s) / w0, 1.0, 1e-9) << k;
  }
  EXPECT_NEAR(r.summary.energy_lost_j_per_kg, 0.0, 1e-15);  // e = 1: (1 - e^2) is exactly 0; only round-off
}

TEST(RockingFree, ZenoRockingComesToRestByTheRestRule) {
  // With e < 1 the half-cycles shrink geometrically (Zeno). The rest rule stops the sequence; all the energy above
  // the upright position, g R (cos(alpha - theta0) - cos(alpha)), is then lost (to the rest fraction 1e-8 and the
  // tolerance of the integration).
  const auto b = r4_block();
  auto o = housner();
  o.initial_theta_rad = 0.5 * b.alpha_rad();
  const auto r = rock(still_ground(5.0), b, o);
  EXPECT_EQ(r.summary.end_state, RockingState::rest);
  EXPECT_FALSE(r.summary.still_rocking_at_end);
  EXPECT_FALSE(r.summary.overturned);
  EXPECT_GT(r.summary.impacts, 50u);
  EXPECT_EQ(events_of(r, RockingEventKind::rest).size(), 1u);
  const double alpha = b.alpha_rad();
  const double e0 = kG * b.R_m() * (std::cos(alpha - o.initial_theta_rad) - std::cos(alpha));
  // All the initial energy is lost by the rest; integration error at the default rel_tol (1e-8) over > 50 impacts.
  EXPECT_NEAR(r.summary.energy_lost_j_per_kg / e0, 1.0, 1e-6);
  EXPECT_EQ(r.history.state.back(), RockingState::rest);
  // Time history rows are ordered in time.
  EXPECT_TRUE(std::is_sorted(r.history.time_s.begin(), r.history.time_s.end()));
}

// ---------------------------------------------------------------------------------------------------------------
// R7, R8: pulse and impulse thresholds

TEST(RockingThreshold, R7RectangularPulse) {
  const double p = 2.0;
  const double alpha = 0.2;
  const auto b = block_alpha_p(alpha, p);
  // The linearised closed form against rocking.md's R7 table: tests/closed_forms/.
  // Nonlinear with Housner impacts, falls at pi/2: [INDEP] row to 1e-3 (rocking.md). Subset p t1 = 0.5, 1, 2.
  const double tan_a = std::tan(alpha);
  const double rows[][2] = {{0.5, 2.546213}, {1.0, 1.582274}, {2.0, 1.155740}};
  for (const auto& row : rows) {
    const double t1 = row[0] / p;
    const auto motion = [&](double x) {
      PulseSpec spec;
      spec.kind = PulseKind::rectangular;
      spec.amplitude_m_s2 = x * kG * tan_a;
      spec.duration_s = t1;
      return make_pulse(spec);
    };
    ThresholdSearch search;
    search.start = 1.0;
    search.step = 0.02;
    search.max = 6.0;
    search.rel_tol = 1e-6;
    const auto found = first_overturning_amplitude(motion, b, housner(), OverturnCriterion::falls, search);
    ASSERT_TRUE(found.amplitude) << row[0];
    EXPECT_NEAR(*found.amplitude / row[1], 1.0, 1e-3) << "p t1 = " << row[0];
  }
}

TEST(RockingThreshold, R8VelocityImpulse) {
  // The closed form against rocking.md's R8 table (and dv = 1.168890 m/s for this block): tests/closed_forms/.
  const auto b = r4_block();
  const double dv = velocity_impulse_threshold_m_s(b, kG);
  // Integrated from the impulse's angular velocity theta'_0 = dv p^2 cos(alpha) / g, 0.01% either side of the
  // threshold: the energy margin (2e-4) is far above the integration error (rel_tol 1e-10).
  const double p = b.p_rad_s(kG);
  for (double f : {0.9999, 1.0001}) {
    auto o = housner();
    o.rel_tol = 1e-10;
    o.initial_theta_dot_rad_s = f * dv * p * p * std::cos(b.alpha_rad()) / kG;
    const auto s = rock_summary(still_ground(1.0), b, o);
    EXPECT_EQ(s.overturned, f > 1.0) << f;
  }
  // The same threshold from a short rectangular pulse (tau = 1e-5 s, amplitude dv / tau) found by the search:
  // gravity acts during the pulse for g tan(alpha) tau / dv ~ 2e-5 of the impulse, so 1e-3 is ample.
  const double tau = 1e-5;
  const auto motion = [&](double x) {
    PulseSpec spec;
    spec.kind = PulseKind::rectangular;
    spec.amplitude_m_s2 = x / tau;
    spec.duration_s = tau;
    return make_pulse(spec);
  };
  ThresholdSearch search;
  search.start = 0.5;
  search.step = 0.05;
  search.max = 3.0;
  search.rel_tol = 1e-7;
  const auto found = first_overturning_amplitude(motion, b, housner(), OverturnCriterion::falls, search);
  ASSERT_TRUE(found.amplitude);
  EXPECT_NEAR(*found.amplitude / dv, 1.0, 1e-3);
}

// ---------------------------------------------------------------------------------------------------------------
// P1 and section 4: one-cycle pulses

/// One full cycle of a sine or cosine pulse of amplitude x * unit and circular frequency w (rad/s), sampled at
/// T / 2000 (make_pulse's default): the piecewise-linear model differs from the smooth pulse by ~(w dt)^2 / 8 ~
/// 1e-6 relative, far below the tolerances used here.
auto one_cycle(PulseKind kind, double w, double unit) {
  return [=](double x) {
    PulseSpec spec;
    spec.kind = kind;
    spec.amplitude_m_s2 = x * unit;
    spec.duration_s = 2.0 * kPi / w;
    return make_pulse(spec);
  };
}

TEST(RockingThreshold, P1OneCycleCosinePulse) {
  // wshwwl rock.md: p = 2 rad/s, alpha = 15 deg, a_g = a_p cos(pi t) for 0 <= t <= 2 s, e = Housner; critical
  // a_p = 0.315034 g for |theta| >= alpha; the first toppling amplitude (pi/2) is the same. Tolerance 1e-4 relative.
  const double alpha = deg_to_rad(15.0);
  const auto b = block_alpha_p(alpha, 2.0);
  ThresholdSearch search;
  search.start = std::tan(alpha);  // no uplift below g tan(alpha)
  search.step = 0.02 * std::tan(alpha);
  search.max = 1.0;
  search.rel_tol = 1e-7;
  const auto motion = one_cycle(PulseKind::cosine, kPi, kG);
  const auto exceed = first_overturning_amplitude(motion, b, housner(), OverturnCriterion::exceeds_alpha, search);
  ASSERT_TRUE(exceed.amplitude);
  EXPECT_NEAR(*exceed.amplitude / 0.315034034, 1.0, 1e-4);
  const auto falls = first_overturning_amplitude(motion, b, housner(), OverturnCriterion::falls, search);
  ASSERT_TRUE(falls.amplitude);
  EXPECT_NEAR(*falls.amplitude / 0.315034034, 1.0, 1e-4);
  // Just above it the body passes alpha after the pulse has ended and falls freely: the run-out matters.
  const auto s = rock_summary(motion(*falls.amplitude * 1.0001), b, housner());
  EXPECT_TRUE(s.overturned);
  EXPECT_GT(*s.overturn_time_s, 2.0);
}

struct Section4Row {
  PulseKind kind;
  double w_over_p;
  OverturnCriterion criterion;
  double expected;  // a_p / (g tan(alpha))
};

class RockingSection4 : public ::testing::TestWithParam<Section4Row> {};

TEST_P(RockingSection4, FirstOverturningAmplitude) {
  // rocking.md section 4 [INDEP]: p = 2 rad/s, alpha = 0.25 rad, Housner e; upward scan in steps of 0.02 g tan(alpha)
  // then bisection. Suggested tolerance 2e-3 relative (the independent values are stable to 0.1%).
  const Section4Row row = GetParam();
  const double alpha = 0.25;
  const double p = 2.0;
  const auto b = block_alpha_p(alpha, p);
  ThresholdSearch search;
  search.start = 1.0;
  search.step = 0.02;
  search.max = 6.0;
  search.rel_tol = 1e-6;
  const auto found = first_overturning_amplitude(one_cycle(row.kind, row.w_over_p * p, kG * std::tan(alpha)), b,
                                                 housner(), row.criterion, search);
  ASSERT_TRUE(found.amplitude);
  EXPECT_NEAR(*found.amplitude / row.expected, 1.0, 2e-3);
}

INSTANTIATE_TEST_SUITE_P(
    Rows, RockingSection4,
    ::testing::Values(Section4Row{PulseKind::sine, 1.0, OverturnCriterion::falls, 1.13097},
                      Section4Row{PulseKind::cosine, 1.0, OverturnCriterion::exceeds_alpha, 1.11226},
                      Section4Row{PulseKind::sine, 2.0, OverturnCriterion::exceeds_alpha, 1.22372},
                      // The two criteria differ here: the cosine row at w/p = 2 tests both.
                      Section4Row{PulseKind::cosine, 2.0, OverturnCriterion::exceeds_alpha, 1.40117},
                      Section4Row{PulseKind::cosine, 2.0, OverturnCriterion::falls, 1.40803},
                      Section4Row{PulseKind::sine, 4.0, OverturnCriterion::falls, 1.78856},
                      Section4Row{PulseKind::cosine, 4.0, OverturnCriterion::exceeds_alpha, 3.41999},
                      Section4Row{PulseKind::cosine, 4.0, OverturnCriterion::falls, 3.41999},
                      Section4Row{PulseKind::sine, 6.0, OverturnCriterion::falls, 4.63791}));

TEST(RockingThreshold, Section4CosineAtSixTimesPDoesNotOverturnUpTo12) {
  // rocking.md section 4: one-cosine pulse at w_p = 6 p: "no overturn up to 12" g tan(alpha), both criteria.
  const double alpha = 0.25;
  const auto b = block_alpha_p(alpha, 2.0);
  ThresholdSearch search;
  search.start = 1.0;
  search.step = 0.02;
  search.max = 12.0;
  const auto motion = one_cycle(PulseKind::cosine, 12.0, kG * std::tan(alpha));
  EXPECT_FALSE(first_overturning_amplitude(motion, b, housner(), OverturnCriterion::falls, search).amplitude);
  EXPECT_FALSE(first_overturning_amplitude(motion, b, housner(), OverturnCriterion::exceeds_alpha, search).amplitude);
}

TEST(RockingThreshold, OverturningIsNotMonotoneInAmplitude) {
  // P1 block and pulse: it falls at 0.3155 g, survives at 0.33 g and 0.35 g, and falls again at 0.36 g. A bisection
  // between 0.3 g and 0.6 g that assumed monotonicity could end anywhere among these changes (rocking.md P1 reports
  // 0.351088 g found that way); the scan-then-bisect search returns the first one.
  const double alpha = deg_to_rad(15.0);
  const auto b = block_alpha_p(alpha, 2.0);
  const auto motion = one_cycle(PulseKind::cosine, kPi, kG);
  EXPECT_TRUE(rock_summary(motion(0.3155), b, housner()).overturned);
  EXPECT_FALSE(rock_summary(motion(0.33), b, housner()).overturned);
  EXPECT_FALSE(rock_summary(motion(0.35), b, housner()).overturned);
  EXPECT_TRUE(rock_summary(motion(0.36), b, housner()).overturned);
}

TEST(RockingThreshold, ScanReportsNoOverturnWhenNothingFalls) {
  // Tiny range below the uplift threshold: nothing rocks, so nothing falls; the result says so.
  const auto b = block_alpha_p(0.25, 2.0);
  ThresholdSearch search;
  search.start = 0.5;
  search.step = 0.1;
  search.max = 0.9;
  const auto found = first_overturning_amplitude(one_cycle(PulseKind::sine, 2.0, kG * std::tan(0.25)), b, housner(),
                                                 OverturnCriterion::falls, search);
  EXPECT_FALSE(found.amplitude);
  EXPECT_EQ(found.runs, 5u);
}

// ---------------------------------------------------------------------------------------------------------------
// S1: Shenton's onset modes

TEST(RockingShenton, S1CriticalFrictionTable) {
  // mu_crit(A) = [A (4 beta^2 + 1) + 3 beta] / [(beta^2 + 4) + 3 A beta] for a block (rocking.md S1, 6 decimals).
  const double betas[] = {1.0 / 3.0, 0.2};
  const double table[2][4] = {{0.373494, 0.478261, 0.636364, 1.444444}, {0.271889, 0.379310, 0.557252, 1.933333}};
  for (int i = 0; i < 2; ++i) {
    const double beta = betas[i];
    const auto b = RockingBody::block(2.0 * beta, 2.0);
    EXPECT_NEAR(shenton_critical_mu(b, beta), beta, 1e-15);  // mu_crit(beta) = beta
    const double As[] = {0.5, 1.0, 2.0};
    for (int j = 0; j < 3; ++j) {
      const double A = As[j];
      const double mu = shenton_critical_mu(b, A);
      EXPECT_NEAR(mu, table[i][j], kPrinted6) << beta << " " << A;
      // The general form reduces to the block form, to round-off (1e-9, rocking.md).
      EXPECT_NEAR(mu, (A * (4 * beta * beta + 1) + 3 * beta) / ((beta * beta + 4) + 3 * A * beta), 1e-9);
    }
    // Limit A -> infinity: (4 beta^2 + 1) / (3 beta).
    EXPECT_NEAR(shenton_critical_mu(b, 1e12), table[i][3], kPrinted6);
  }
  // Exact fraction: beta = 1/3, A = 1/2 gives 31/83.
  EXPECT_NEAR(shenton_critical_mu(RockingBody::block(2.0 / 3.0, 2.0), 0.5), 31.0 / 83.0, 1e-9);
  // mu_crit rises with A.
  const auto b = RockingBody::block(0.4, 2.0);
  EXPECT_LT(shenton_critical_mu(b, 0.3), shenton_critical_mu(b, 0.6));
}

TEST(RockingShenton, OnsetModes) {
  const auto b = RockingBody::block(0.4, 2.0);  // beta = 0.2
  EXPECT_EQ(shenton_onset_mode(b, 0.1, 0.5), OnsetMode::rest);
  EXPECT_EQ(shenton_onset_mode(b, 0.15, 0.1), OnsetMode::slide);  // mu < beta: slides first
  EXPECT_EQ(shenton_onset_mode(b, 0.25, 0.5), OnsetMode::rock);
  EXPECT_EQ(shenton_onset_mode(b, 1.0, 0.3), OnsetMode::slide_rock);  // mu_crit(1) = 0.379
  EXPECT_THROW((void)shenton_onset_mode(b, 0.5, -1.0), InputError);
  EXPECT_THROW((void)shenton_critical_mu(b, std::nan("")), InputError);

  // In a response: mu below a/h warns that rocking-only is not valid; a large mu gives "rock".
  const auto rec = noisy_record(5, 500, 0.01, 0.5 * kG);
  auto o = housner();
  o.mu = 0.1;
  const auto slide = rock_summary(rec, b, o);
  EXPECT_EQ(slide.onset_mode, OnsetMode::slide);
  ASSERT_FALSE(slide.warnings.empty());
  EXPECT_NE(slide.warnings.front().find("slides"), std::string::npos);
  o.mu = 0.8;
  const auto rocking = rock_summary(rec, b, o);
  EXPECT_EQ(rocking.onset_mode, OnsetMode::rock);
  ASSERT_TRUE(rocking.critical_mu);
  EXPECT_NEAR(*rocking.critical_mu, 0.2, 1e-9);  // continuous input: lift-off at A = a/h exactly
  EXPECT_TRUE(rocking.warnings.empty());
  // A rectangular pulse jumps straight to A = 1: mu = 0.3 < mu_crit(1) = 0.379 is slide-rock.
  PulseSpec spec;
  spec.kind = PulseKind::rectangular;
  spec.amplitude_m_s2 = -kG;
  spec.duration_s = 0.05;
  o.mu = 0.3;
  const auto sr = rock_summary(make_pulse(spec), b, o);
  EXPECT_EQ(sr.onset_mode, OnsetMode::slide_rock);
  EXPECT_NEAR(*sr.onset_accel_ratio, 1.0, 1e-12);  // |a_h| / g of a -g pulse: one division, round-off
  o.mu.reset();
  EXPECT_EQ(rock_summary(rec, b, o).onset_mode, OnsetMode::unchecked);
}

// ---------------------------------------------------------------------------------------------------------------
// History, invariants, methods

TEST(RockingHistory, SamplesPlusEventsWithStates) {
  const auto b = RockingBody::block(0.04, 0.20);
  const auto rec = noisy_record(11, 600, 0.01, 0.25 * kG);
  const auto r = rock(rec, b, housner());
  ASSERT_GT(r.summary.impacts, 2u);
  // Every record sample is a row; the other rows are events.
  std::size_t on_samples = 0;
  for (double t : r.history.time_s) {
    const double k = t / 0.01;
    if (std::abs(k - std::round(k)) < 1e-9 && t <= rec.end_time_s() + 1e-12) ++on_samples;
  }
  EXPECT_GE(on_samples, rec.size());
  EXPECT_TRUE(std::is_sorted(r.history.time_s.begin(), r.history.time_s.end()));
  EXPECT_EQ(r.history.time_s.size(), r.history.state.size());
  for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
    const double th = r.history.theta_rad[i];
    switch (r.history.state[i]) {
      case RockingState::rest: EXPECT_EQ(th, 0.0); break;
      case RockingState::rocking_positive: EXPECT_GE(th, -1e-12); break;
      case RockingState::rocking_negative: EXPECT_LE(th, 1e-12); break;
      case RockingState::fallen: break;
    }
    EXPECT_LE(std::abs(th), r.summary.max_abs_rotation_rad + 1e-15);
  }
  EXPECT_EQ(events_of(r, RockingEventKind::impact).size(), r.summary.impacts);
  EXPECT_EQ(events_of(r, RockingEventKind::uplift).size(), r.summary.uplifts);
  // The summary-only path gives the same summary.
  const auto s = rock_summary(rec, b, housner());
  EXPECT_EQ(s.impacts, r.summary.impacts);
  EXPECT_EQ(s.max_abs_rotation_rad, r.summary.max_abs_rotation_rad);
  EXPECT_EQ(s.energy_lost_j_per_kg, r.summary.energy_lost_j_per_kg);
}

TEST(RockingHistory, SummaryPathSkipsOnlyTurningPointsThatChangeNothing) {
  // The summary path does not locate a turning point whose bound stays below the largest |theta| so far (and below
  // alpha and the fall level, with no impact after it), nor a trough that stays above 0 (rocking.cpp,
  // turning_point_is_moot). The history path locates them all. Under 15 Hz shaking at dt = 0.0025 s (the inversion's
  // high-frequency columns) a small block chatters: many turning points below the running maximum. Both paths take
  // the same steps, so every summary field must be bit-identical; a skipped peak that mattered would change the
  // maximum or its time.
  const auto b = RockingBody::block(0.05, 0.30);
  const auto rec = test::noise_record({.seed = 3, .samples = 4000, .dt_s = 0.0025, .pga_m_s2 = 0.45 * kG,
                                       .resonance_hz = 15.0, .pole_radius = 0.97, .envelope_peak_s = 2.0});
  const auto r = rock(rec, b, housner());
  const auto s = rock_summary(rec, b, housner());
  // Peaks below the maximum reached before them: the ones the summary path may skip.
  std::size_t below = 0;
  double running = 0.0;
  for (const auto& ev : r.events) {
    if (ev.kind == RockingEventKind::peak && std::abs(ev.theta_rad) < running) ++below;
    if (ev.kind == RockingEventKind::peak) running = std::max(running, std::abs(ev.theta_rad));
  }
  ASSERT_GT(below, 20u) << "the case must have turning points that change nothing";
  ASSERT_FALSE(r.summary.overturned);
  EXPECT_EQ(s.steps, r.summary.steps);
  EXPECT_EQ(s.impacts, r.summary.impacts);
  EXPECT_EQ(s.uplifts, r.summary.uplifts);
  EXPECT_EQ(s.max_abs_rotation_rad, r.summary.max_abs_rotation_rad);
  EXPECT_EQ(s.max_rotation_time_s, r.summary.max_rotation_time_s);
  EXPECT_EQ(s.max_abs_theta_dot_rad_s, r.summary.max_abs_theta_dot_rad_s);
  EXPECT_EQ(s.exceeded_alpha_time_s, r.summary.exceeded_alpha_time_s);
  EXPECT_EQ(s.energy_lost_j_per_kg, r.summary.energy_lost_j_per_kg);
  EXPECT_EQ(s.end_time_s, r.summary.end_time_s);
  EXPECT_EQ(s.end_state, r.summary.end_state);
}

TEST(RockingHistory, RestScanInBlocksStopsAtTheSampleThatLifts) {
  // The summary path scans rest in blocks of 8 samples (rocking.cpp, kRestBlock; issue 32), the history path one
  // sample at a time. One spike above the uplift threshold g a/h = 0.2 g, at every sample 1 to 20 in turn (every
  // position within the first blocks), in shaking below it: both paths must lift off in the interval before the
  // spike, at the same time, with the same uplifts and steps.
  const auto b = RockingBody::block(0.08, 0.40);
  for (std::size_t spike = 1; spike <= 20; ++spike) {
    SCOPED_TRACE(spike);
    std::vector<double> a(400);
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = 0.1 * kG * std::sin(0.05 * static_cast<double>(i));
    a[spike] = 0.5 * kG;
    const auto rec = GroundMotion::uniform(a, 0.005);
    const auto r = rock(rec, b, housner());
    const auto s = rock_summary(rec, b, housner());
    ASSERT_TRUE(s.uplift_time_s.has_value());
    EXPECT_EQ(*s.uplift_time_s, *r.summary.uplift_time_s);
    EXPECT_GT(*s.uplift_time_s, 0.005 * static_cast<double>(spike - 1));
    EXPECT_LE(*s.uplift_time_s, 0.005 * static_cast<double>(spike));
    EXPECT_EQ(s.uplifts, r.summary.uplifts);
    EXPECT_EQ(s.steps, r.summary.steps);
    EXPECT_EQ(s.max_abs_rotation_rad, r.summary.max_abs_rotation_rad);
  }
}

TEST(RockingHistory, PolarityFlipMirrorsTheResponse) {
  // The equation is odd in (theta, a_h): the flipped record gives -theta. Same operations with flipped signs, so
  // equal to round-off of sin/cos symmetry (1e-12 relative).
  const auto b = RockingBody::block(0.04, 0.20);
  const auto rec = noisy_record(11, 600, 0.01, 0.25 * kG);
  const auto up = rock_summary(rec, b, housner());
  const auto down = rock_summary(rec.inverted(), b, housner());
  ASSERT_GT(up.impacts, 0u);
  EXPECT_EQ(up.impacts, down.impacts);
  EXPECT_NEAR(up.max_abs_rotation_rad, down.max_abs_rotation_rad, 1e-12 * up.max_abs_rotation_rad);
}

TEST(RockingMethod, AdaptiveAgreesWithFixedStepRk4) {
  // Fixed-step RK4 at dt/1000 (thesis method, refined) against the adaptive solver at rel_tol 1e-10: max |theta|
  // to 1e-6 relative (the brief's tolerance; RK4's error at h = 1e-5 s is ~(p h)^4 ~ 1e-18 per unit time, and both
  // locate events on 4th-order extensions). A short window keeps the rocking sequence before chaotic divergence
  // amplifies round-off.
  const auto b = RockingBody::block(0.04, 0.20);
  const auto rec = noisy_record(11, 600, 0.01, 0.25 * kG);
  auto adaptive = housner();
  adaptive.rel_tol = 1e-10;
  auto rk4 = housner();
  rk4.method = RockingMethod::rk4;
  rk4.rk4_substeps = 1000;
  rk4.max_run_out_s = 0.0;
  adaptive.max_run_out_s = 0.0;
  const auto a = rock_summary(rec, b, adaptive);
  const auto r = rock_summary(rec, b, rk4);
  ASSERT_GT(a.impacts, 2u);
  // Two independent integrators, both converged far below it: 1e-6 is the precision the comparison is meant to show.
  EXPECT_NEAR(r.max_abs_rotation_rad / a.max_abs_rotation_rad, 1.0, 1e-6);
  // The thesis' own step (dt/4 on a 0.01 s record) is visibly coarser but still within a few percent.
  rk4.rk4_substeps = 4;
  const auto coarse = rock_summary(rec, b, rk4);
  EXPECT_NEAR(coarse.max_abs_rotation_rad / a.max_abs_rotation_rad, 1.0, 5e-2);
}

// ---------------------------------------------------------------------------------------------------------------
// Real records (shared/records, read by topple::io)

std::optional<GroundMotion> shared_motion(const std::string& name) {
  if (!test::have_shared()) return std::nullopt;
  return io::read_motion(test::shared_record(name));
}

TEST(RockingRecord, AdaptiveAgreesWithFixedStepRk4OnElCentro) {
  // El Centro 1940 (RSN6 ELC180, PGA 0.28 g), 1.5-4.5 s, thesis object A (4 x 20 cm): adaptive at rel_tol 1e-10
  // against RK4 at dt/1000 (h = 1e-5 s): max |theta| to 1e-6 relative (brief), where they agree to ~1e-11.
  const auto full = shared_motion("RSN6_IMPVALL.I_I-ELC180.AT2");
  if (!full) GTEST_SKIP() << "shared/records not found";
  const auto window = full->trimmed(1.5, 4.5);
  const auto b = RockingBody::block(0.04, 0.20);
  for (double e : {0.5, 0.75}) {
    auto adaptive = with_e(e);
    adaptive.rel_tol = 1e-10;
    adaptive.max_run_out_s = 0.0;
    auto rk4 = adaptive;
    rk4.method = RockingMethod::rk4;
    rk4.rk4_substeps = 1000;
    const auto a = rock_summary(window, b, adaptive);
    const auto r = rock_summary(window, b, rk4);
    ASSERT_GT(a.impacts, 10u) << e;
    EXPECT_EQ(a.impacts, r.impacts) << e;
    EXPECT_NEAR(r.max_abs_rotation_rad / a.max_abs_rotation_rad, 1.0, 1e-6) << e;
  }
  // With Housner's e the block falls: same fall instant to 1e-6 s.
  auto adaptive = housner();
  adaptive.rel_tol = 1e-10;
  auto rk4 = adaptive;
  rk4.method = RockingMethod::rk4;
  rk4.rk4_substeps = 1000;
  const auto a = rock_summary(window, b, adaptive);
  const auto r = rock_summary(window, b, rk4);
  ASSERT_TRUE(a.overturned);
  ASSERT_TRUE(r.overturned);
  EXPECT_NEAR(*r.overturn_time_s, *a.overturn_time_s, 1e-6);  // as above: two converged integrators, 1e-6 s
}

TEST(RockingRecord, ThesisChapter5ObjectsOnTheSharedRecords) {
  // Mittal (1971) section 5.2 analysed blocks A (4 x 20 cm, a/h = 0.20) and B (4 x 12 cm, a/h = 0.33) under the
  // Koyna record (not among the shared records) with e = 0.5 and 0.75: neither fell. Here: the same blocks under
  // the shared records, with the thesis' e values and Housner's. Printed for the record; the checks are the
  // invariants that hold whatever the outcome.
  if (!test::have_shared()) GTEST_SKIP() << "shared/records not found";
  const char* records[] = {"RSN6_IMPVALL.I_I-ELC180.AT2", "Rinaldi228.AT2", "ARL360.at2", "CPM000.AT2",
                           "RSN763_LOMAP_GIL067.AT2", "Kobe_1995_TAK-090.csv", "0111a.smc"};
  std::printf("%-28s %-8s %-7s %-9s %-10s %-8s\n", "record", "block", "e", "PGA (g)", "max|th|/a", "fell");
  for (const char* name : records) {
    const GroundMotion m = io::read_motion(test::shared_record(name));
    for (const auto& [label, body] : {std::pair{"A 4x20", RockingBody::block(0.04, 0.20)},
                                      std::pair{"B 4x12", RockingBody::block(0.04, 0.12)}}) {
      for (double e : {0.5, 0.75, -1.0}) {
        const RockingOptions o = e < 0.0 ? RockingOptions{} : [&] {
          RockingOptions g;
          g.restitution = RestitutionMode::given;
          g.e = e;
          return g;
        }();
        const auto s = rock_summary(m, body, o);
        std::printf("%-28s %-8s %-7.3f %-9.3f %-10.4f %-8s\n", name, label, s.e, m.pga_m_s2() / kStandardGravity,
                    s.max_rotation_over_alpha, s.overturned ? "yes" : "no");
        // Below a/h of PGA nothing moves; a fall means |theta| reached pi/2; otherwise the block came to rest.
        if (m.pga_m_s2() <= kStandardGravity * body.a_m / body.h_m) {
          EXPECT_EQ(s.max_abs_rotation_rad, 0.0);
        }
        if (s.overturned) {
          EXPECT_NEAR(s.max_abs_rotation_rad, kPi / 2.0, 1e-12);  // the fall is recorded at pi/2: round-off of alpha
        } else {
          EXPECT_LT(s.max_abs_rotation_rad, kPi / 2.0);
          EXPECT_FALSE(s.still_rocking_at_end);
        }
      }
    }
  }
}

}  // namespace
}  // namespace topple
