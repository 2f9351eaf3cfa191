// Asymmetric rocking bodies (RockingBody::general_asymmetric): b1 (CM to the pivot O-, theta < 0) != b2 (CM to O+,
// theta > 0). The limit b1 = b2, mirror symmetry, the uplift threshold of each side, the impact law against a
// hand-derived closed form (an L-shaped body), and energy between impacts. Equations: docs/method.md, "Asymmetric
// bodies".
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include <gtest/gtest.h>

#include "support/noise_record.hpp"
#include "topple/closed_forms/rocking.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {
namespace {

constexpr double kG = 9.81;

GroundMotion noisy_record(unsigned seed, std::size_t n, double dt, double pga_m_s2) {
  return test::noise_record({.seed = seed, .samples = n, .dt_s = dt, .pga_m_s2 = pga_m_s2, .resonance_hz = 2.5,
                             .pole_radius = 0.97, .envelope_peak_s = 0.2 * static_cast<double>(n) * dt});
}

GroundMotion negated(const GroundMotion& m) {
  std::vector<double> a(m.accel_m_s2().begin(), m.accel_m_s2().end());
  for (double& x : a) x = -x;
  if (m.is_uniform()) return GroundMotion::uniform(a, m.dt_s(), m.start_time_s());
  std::vector<double> t(m.size());
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = m.time_s(i);
  return GroundMotion::irregular(t, a);
}

GroundMotion sine_pulse(double amplitude_m_s2, double period_s) {
  return make_pulse({.kind = PulseKind::sine, .amplitude_m_s2 = amplitude_m_s2, .duration_s = period_s,
                     .tail_s = 3.0, .dt_s = 0.002});
}

/// The L-shaped body of the impact test, in units of u = 0.1 m: rectangle A = [0, 2] x [0, 1] and rectangle B =
/// [0, 1] x [1, 3], equal areas, uniform density; contact corners (0, 0) (O-) and (2, 0) (O+). By hand:
/// CM = ((1 + 0.5) / 2, (0.5 + 2) / 2) = (0.75, 1.25), so b1 = 0.75 u, b2 = 1.25 u, h = 1.25 u; each rectangle has
/// (w^2 + H^2) / 12 = 5/12 u^2 about its own centre and lies 0.625 u^2 (squared offset) from the CM, so
/// I_cm / m = 5/12 + 5/8 = 25/24 u^2.
constexpr double kU = 0.1;
RockingBody l_shaped() { return RockingBody::general_asymmetric(0.75 * kU, 1.25 * kU, 1.25 * kU, 25.0 / 24.0 * kU * kU); }

// ---------------------------------------------------------------------------------------------------------------

TEST(AsymmetricBody, FactoryAndValidation) {
  const RockingBody b = l_shaped();
  EXPECT_FALSE(b.symmetric());
  EXPECT_DOUBLE_EQ(b.pivot_b_m(-1), 0.075);
  EXPECT_DOUBLE_EQ(b.pivot_b_m(1), 0.125);
  // Parallel axes: D+ = 25/24 + 1.25^2 + 1.25^2 = 200/48 u^2, D- = 25/24 + 0.75^2 + 1.25^2 = 152/48 u^2.
  EXPECT_NEAR(b.pivot_D_m2(1), 200.0 / 48.0 * kU * kU, 1e-16);
  EXPECT_NEAR(b.pivot_D_m2(-1), 152.0 / 48.0 * kU * kU, 1e-16);
  EXPECT_TRUE(RockingBody::block(0.2, 1.0).symmetric());
  const auto field_of = [](auto f) {
    try {
      (void)f();
    } catch (const InputError& e) {
      return e.where().field;
    }
    ADD_FAILURE() << "no InputError";
    return std::string{};
  };
  EXPECT_EQ(field_of([] { return RockingBody::general_asymmetric(0.0, 0.1, 0.5, 0.01); }), "b1");
  EXPECT_EQ(field_of([] { return RockingBody::general_asymmetric(0.1, -1.0, 0.5, 0.01); }), "b2");
  EXPECT_EQ(field_of([] { return RockingBody::general_asymmetric(0.1, 0.1, 0.0, 0.01); }), "h");
  EXPECT_EQ(field_of([] { return RockingBody::general_asymmetric(0.1, 0.1, 0.5, -0.01); }), "inertia");
  // make_rocking_body: {b1, b2, h, inertia} or {a, h, D}, not a mixture.
  BodyDimensions d;
  d.b1_m = 0.1;
  d.b2_m = 0.2;
  d.h_m = 0.5;
  d.inertia_m2 = 0.02;
  const RockingBody m = make_rocking_body(RockingBody::Shape::general, d);
  EXPECT_EQ(m.pivot_b_m(-1), 0.1);
  EXPECT_EQ(m.pivot_b_m(1), 0.2);
  EXPECT_EQ(m.D_m2, 0.02 + 0.2 * 0.2 + 0.5 * 0.5);
  d.a_m = 0.1;
  EXPECT_EQ(field_of([&] { return make_rocking_body(RockingBody::Shape::general, d); }), "a");
  d.a_m.reset();
  d.inertia_m2.reset();
  EXPECT_EQ(field_of([&] { return make_rocking_body(RockingBody::Shape::general, d); }), "inertia");
  // A body whose two pivots disagree on I_cm / m is refused by the engine.
  RockingBody bad = l_shaped();
  bad.negative_pivot->D_m2 *= 1.5;
  EXPECT_EQ(field_of([&] { return rock_summary(sine_pulse(kG, 0.5), bad); }), "inertia");
}

TEST(AsymmetricBody, RestitutionOfTheLShapedBodyIsTheHandDerivedValue) {
  // Angular momentum about the new pivot (docs/method.md): e = (k2 + h^2 - b_old b_new) / (k2 + b_new^2 + h^2).
  // Onto O- (b_new = 0.75, b_old = 1.25): (25/24 + 25/16 - 15/16) / (25/24 + 9/16 + 25/16) = (80/48) / (152/48)
  // = 10/19; onto O+ (b_new = 1.25): (80/48) / (200/48) = 2/5. Tolerance: a few ulps of the arithmetic.
  const RockingBody b = l_shaped();
  EXPECT_NEAR(housner_restitution(b, -1), 10.0 / 19.0, 4e-16);
  EXPECT_NEAR(housner_restitution(b, 1), 2.0 / 5.0, 4e-16);
  // Housner's rectangle, e = 1 - (3/2) sin^2(alpha), as an asymmetric body with b1 = b2: exact to round-off.
  const double w = 0.3;
  const double H = 1.1;
  const RockingBody sym = RockingBody::general_asymmetric(w / 2, w / 2, H / 2, (w * w + H * H) / 12.0);
  const double alpha = std::atan(w / H);
  for (const int onto : {-1, 1}) {
    EXPECT_NEAR(housner_restitution(sym, onto), 1.0 - 1.5 * std::sin(alpha) * std::sin(alpha), 1e-15);
  }
  EXPECT_EQ(housner_restitution(RockingBody::block(w, H), 1), housner_restitution(RockingBody::block(w, H)));

  // The engine applies them: free rocking from theta0 > 0 about O+, impacts alternate onto O- and O+.
  RockingOptions o;
  o.g_m_s2 = kG;
  o.initial_theta_rad = 0.5 * std::atan(1.25 / 1.25);
  const RockingResult r = rock(GroundMotion::uniform(std::vector<double>(2, 0.0), 0.01), b, o);
  std::vector<RockingEvent> impacts;
  for (const auto& ev : r.events) {
    if (ev.kind == RockingEventKind::impact) impacts.push_back(ev);
  }
  ASSERT_GE(impacts.size(), 2u);
  EXPECT_NEAR(impacts[0].theta_dot_after_rad_s / impacts[0].theta_dot_before_rad_s, 10.0 / 19.0, 1e-15);
  EXPECT_NEAR(impacts[1].theta_dot_after_rad_s / impacts[1].theta_dot_before_rad_s, 2.0 / 5.0, 1e-15);
  EXPECT_LT(impacts[0].theta_dot_before_rad_s, 0.0);  // returning from theta > 0
  EXPECT_NEAR(r.summary.e, 0.4, 4e-16);
  EXPECT_NEAR(r.summary.e_onto_negative, 10.0 / 19.0, 4e-16);
}

TEST(AsymmetricBody, FreeRockingMatchesEnergyClosedFormsOnEachSide) {
  // Released at theta0 on O+ with e = 1 given: the first impact comes after a quarter of the exact period of the
  // O+ side (rocking about O+ involves that pivot only), and the swing onto O- peaks where energy about O- says:
  // g R- cos(alpha- - theta_m) = g h + D- w^2 / 2, w = e+ * (impact speed about O+) with e the given 1.
  const RockingBody b = l_shaped();
  const RockingBody pos = b.side_body(1);
  const RockingBody neg = b.side_body(-1);
  // theta0 small enough that the swing onto O- (smaller alpha) does not fall: 0.2 alpha+ leaves 0.14 g u of kinetic
  // energy about O- against the 0.21 g u needed to lift the CM over O- (u = 0.1 m).
  const double theta0 = 0.2 * pos.alpha_rad();
  RockingOptions o;
  o.g_m_s2 = kG;
  o.restitution = RestitutionMode::given;
  o.e = 1.0;
  o.rel_tol = 1e-11;
  o.abs_tol = 1e-14;
  o.initial_theta_rad = theta0;
  o.max_run_out_s = 0.0;
  // A still record long enough for the first swing onto O- and back.
  const RockingResult r = rock(GroundMotion::uniform(std::vector<double>(1001, 0.0), 0.001), b, o);
  std::vector<RockingEvent> impacts;
  for (const auto& ev : r.events) {
    if (ev.kind == RockingEventKind::impact) impacts.push_back(ev);
  }
  ASSERT_GE(impacts.size(), 1u);
  // The period from Gauss-Kronrod (1e-14) and the event time to a few ulps: 1e-9 s covers rel_tol 1e-11.
  EXPECT_NEAR(impacts[0].time_s, free_rocking_period_s(pos, theta0, kG) / 4.0, 1e-9);
  const double w = free_rocking_impact_speed_rad_s(pos, theta0, kG);
  EXPECT_NEAR(std::abs(impacts[0].theta_dot_before_rad_s), w, 1e-9 * w);
  const double cos_m = (kG * b.h_m + 0.5 * neg.D_m2 * w * w) / (kG * neg.R_m());
  const double theta_m = neg.alpha_rad() - std::acos(cos_m);
  EXPECT_NEAR(r.summary.max_rotation_negative_rad, theta_m, 1e-9);
  EXPECT_DOUBLE_EQ(r.summary.max_rotation_positive_rad, theta0);  // theta0 / alpha * alpha: round-off
  EXPECT_NEAR(r.summary.max_rotation_over_alpha_negative, theta_m / neg.alpha_rad(), 1e-8);
  EXPECT_DOUBLE_EQ(r.summary.alpha_negative_rad, neg.alpha_rad());
}

TEST(AsymmetricBody, Rk4ConvergesAtFourthOrderAcrossAnImpact) {
  // The thesis' fixed-step RK4 on the asymmetric equations: the amplitude of the swing onto O- after one impact
  // (closed form from energy, as above) converges at order 4 in the step: halving the step divides the error by
  // 2^4 = 16 (accepted between 11 and 22: the event location and the asymptotic range blur the ratio).
  const RockingBody b = l_shaped();
  const RockingBody pos = b.side_body(1);
  const RockingBody neg = b.side_body(-1);
  const double theta0 = 0.2 * pos.alpha_rad();
  RockingOptions o;
  o.g_m_s2 = kG;
  o.restitution = RestitutionMode::given;
  o.e = 1.0;
  o.method = RockingMethod::rk4;
  o.initial_theta_rad = theta0;
  o.max_run_out_s = 0.0;
  const double w = free_rocking_impact_speed_rad_s(pos, theta0, kG);
  const double theta_m =
      neg.alpha_rad() - std::acos((kG * b.h_m + 0.5 * neg.D_m2 * w * w) / (kG * neg.R_m()));
  const GroundMotion still = GroundMotion::uniform(std::vector<double>(51, 0.0), 0.02);
  std::vector<double> errors;
  for (const int n : {1, 2, 4}) {
    o.rk4_substeps = n;
    errors.push_back(std::abs(rock_summary(still, b, o).max_rotation_negative_rad - theta_m));
  }
  for (std::size_t k = 1; k < errors.size(); ++k) {
    const double ratio = errors[k - 1] / errors[k];
    EXPECT_GT(ratio, 11.0) << k;
    EXPECT_LT(ratio, 22.0) << k;
  }
}

TEST(AsymmetricBody, EnergyIsConservedBetweenImpacts) {
  // Free rocking with Housner's impacts: between impacts E = D_s theta'^2 / 2 + g R_s cos(alpha_s - |theta|) (J/kg)
  // is constant. Tolerance 1e-8 of g h: rel_tol 1e-10 per step on theta and theta' over a few hundred steps.
  const RockingBody b = RockingBody::general_asymmetric(0.09, 0.11, 0.4, 0.02);
  RockingOptions o;
  o.g_m_s2 = kG;
  o.rel_tol = 1e-10;
  o.initial_theta_rad = 0.3 * b.side_body(1).alpha_rad();  // small enough not to fall on the O- side
  const RockingResult r = rock(GroundMotion::uniform(std::vector<double>(1001, 0.0), 0.005), b, o);
  const auto energy = [&](double theta, double w) {
    const int s = theta > 0.0 ? 1 : -1;
    const RockingBody side = b.side_body(s);
    return 0.5 * side.D_m2 * w * w + kG * side.R_m() * std::cos(side.alpha_rad() - std::abs(theta));
  };
  const double scale = kG * b.h_m;
  std::size_t phases = 0;
  double e_start = 0.0;
  RockingState prev = RockingState::rest;
  double worst = 0.0;
  const auto& h = r.history;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    if (h.state[i] != RockingState::rocking_positive && h.state[i] != RockingState::rocking_negative) {
      prev = h.state[i];
      continue;
    }
    if (h.theta_rad[i] == 0.0) continue;  // an impact row: the state after it, not yet on the new side's curve
    if (h.state[i] != prev) {
      e_start = energy(h.theta_rad[i], h.theta_dot_rad_s[i]);
      prev = h.state[i];
      ++phases;
    }
    worst = std::max(worst, std::abs(energy(h.theta_rad[i], h.theta_dot_rad_s[i]) - e_start));
  }
  EXPECT_GE(phases, 4u);
  EXPECT_LT(worst, 1e-8 * scale);
  // The run ends at rest (E = g h): all the energy above it was lost in impacts and to the rest rule.
  EXPECT_EQ(r.summary.end_state, RockingState::rest);
  const double e0 = energy(o.initial_theta_rad, 0.0);
  EXPECT_NEAR(r.summary.energy_lost_j_per_kg, e0 - scale, 1e-8 * scale);
}

TEST(AsymmetricBody, StaticUpliftThresholdOfEachSide) {
  // A slow ramp: a_h = -c t throws the body toward +x, so it lifts about O+ when c t = g b2 / h; a_h = +c t lifts it
  // about O- at c t = g b1 / h. The input is linear on each sample, so the instant is the root of a linear function:
  // 1e-12 s (round-off of t = 10 s and the threshold).
  const RockingBody b = RockingBody::general_asymmetric(0.05, 0.12, 0.5, 0.03);
  const double c = 0.1 * kG;  // m/s^3: the ramp passes g b2 / h = 0.24 g at 2.4 s
  std::vector<double> ramp(1001);
  for (std::size_t i = 0; i < ramp.size(); ++i) ramp[i] = -c * 0.01 * static_cast<double>(i);
  const GroundMotion toward_plus = GroundMotion::uniform(ramp, 0.01);
  RockingOptions o;
  o.g_m_s2 = kG;
  o.max_run_out_s = 0.0;
  const RockingResult rp = rock(toward_plus, b, o);
  ASSERT_TRUE(rp.summary.uplift_time_s);
  EXPECT_NEAR(*rp.summary.uplift_time_s, kG * 0.12 / 0.5 / c, 1e-12);
  EXPECT_GT(rp.summary.max_rotation_positive_rad, 0.0);
  EXPECT_EQ(rp.summary.max_rotation_negative_rad, 0.0);
  const RockingResult rm = rock(negated(toward_plus), b, o);
  ASSERT_TRUE(rm.summary.uplift_time_s);
  EXPECT_NEAR(*rm.summary.uplift_time_s, kG * 0.05 / 0.5 / c, 1e-12);
  EXPECT_GT(rm.summary.max_rotation_negative_rad, 0.0);
  EXPECT_EQ(rm.summary.max_rotation_positive_rad, 0.0);
  // Past the threshold the ramp keeps pushing: both fall, each to its own side.
  EXPECT_EQ(rp.summary.overturned_side, 1);
  EXPECT_EQ(rm.summary.overturned_side, -1);
}

/// The response of (b1, b2) under a and of (b2, b1) under -a are mirror images, bit for bit: the state's scale is
/// symmetric in the two pivots and every operation of the engine is odd or even in theta.
void expect_mirror(const GroundMotion& motion, const RockingOptions& o, bool both_sides) {
  const RockingBody b = RockingBody::general_asymmetric(0.07, 0.13, 0.45, 0.025);
  const RockingBody m = RockingBody::general_asymmetric(0.13, 0.07, 0.45, 0.025);
  const RockingResult r = rock(motion, b, o);
  const RockingResult q = rock(negated(motion), m, o);
  ASSERT_EQ(r.history.time_s.size(), q.history.time_s.size());
  for (std::size_t i = 0; i < r.history.time_s.size(); ++i) {
    ASSERT_EQ(r.history.time_s[i], q.history.time_s[i]) << i;
    ASSERT_EQ(r.history.theta_rad[i], -q.history.theta_rad[i]) << i;
    ASSERT_EQ(r.history.theta_dot_rad_s[i], -q.history.theta_dot_rad_s[i]) << i;
  }
  EXPECT_EQ(r.summary.impacts, q.summary.impacts);
  EXPECT_EQ(r.summary.overturned, q.summary.overturned);
  EXPECT_EQ(r.summary.overturned_side, -q.summary.overturned_side);
  EXPECT_EQ(r.summary.exceeded_alpha_side, -q.summary.exceeded_alpha_side);
  EXPECT_EQ(r.summary.max_rotation_positive_rad, q.summary.max_rotation_negative_rad);
  EXPECT_EQ(r.summary.max_rotation_negative_rad, q.summary.max_rotation_positive_rad);
  EXPECT_EQ(r.summary.max_rotation_over_alpha, q.summary.max_rotation_over_alpha);
  EXPECT_EQ(r.summary.energy_lost_j_per_kg, q.summary.energy_lost_j_per_kg);
  // Not a trivial pass: the body rocked on both sides, or fell.
  if (both_sides) {
    EXPECT_GT(r.summary.max_rotation_positive_rad, 0.0);
    EXPECT_GT(r.summary.max_rotation_negative_rad, 0.0);
    EXPECT_GT(r.summary.impacts, 2u);
  } else {
    EXPECT_TRUE(r.summary.overturned);
  }
}

TEST(AsymmetricBody, MirrorBodyUnderNegatedInputMirrorsTheResponseExactly) {
  RockingOptions o;
  o.g_m_s2 = kG;
  expect_mirror(noisy_record(7, 3000, 0.005, 0.35 * kG), o, true);
  expect_mirror(sine_pulse(0.45 * kG, 0.6), o, false);
  o.method = RockingMethod::rk4;
  expect_mirror(noisy_record(7, 3000, 0.005, 0.35 * kG), o, true);
}

/// b1 = b2 through the asymmetric path against the symmetric body of the same D: the same verdict, impacts and
/// max theta / alpha to round-off (only the energy bookkeeping is formed differently; 1e-12 relative).
void expect_same_as_symmetric(const GroundMotion& motion, bool want_overturn) {
  const double b = 0.09;
  const double h = 0.42;
  const double k2 = 0.02;
  const RockingBody asym = RockingBody::general_asymmetric(b, b, h, k2);
  const RockingBody sym = RockingBody::general(b, h, k2 + b * b + h * h);
  for (const auto method : {RockingMethod::adaptive, RockingMethod::rk4}) {
    RockingOptions o;
    o.g_m_s2 = kG;
    o.method = method;
    o.mu = 0.6;
    const RockingSummary a = rock_summary(motion, asym, o);
    const RockingSummary s = rock_summary(motion, sym, o);
    EXPECT_EQ(a.overturned, s.overturned);
    EXPECT_EQ(s.overturned, want_overturn);
    if (!want_overturn) {
      EXPECT_GT(s.impacts, 0u);
    }
    EXPECT_EQ(a.impacts, s.impacts);
    EXPECT_EQ(a.uplifts, s.uplifts);
    EXPECT_NEAR(a.max_rotation_over_alpha, s.max_rotation_over_alpha, 1e-12 * s.max_rotation_over_alpha);
    EXPECT_NEAR(a.energy_lost_j_per_kg, s.energy_lost_j_per_kg, 1e-12 * s.energy_lost_j_per_kg + 1e-300);
    EXPECT_EQ(a.e, s.e);
    EXPECT_EQ(a.e_onto_negative, s.e);
    EXPECT_EQ(a.onset_mode, s.onset_mode);
  }
}

TEST(AsymmetricBody, EqualPivotsReproduceTheSymmetricBody) {
  expect_same_as_symmetric(sine_pulse(0.5 * kG, 0.8), true);
  expect_same_as_symmetric(noisy_record(11, 4000, 0.005, 0.22 * kG), false);
}

TEST(AsymmetricBody, SymmetricBodiesReportPerSideFieldsConsistently) {
  // For a symmetric body the old field keeps its meaning: max |theta| / alpha, equal to the larger side ratio.
  RockingOptions o;
  o.g_m_s2 = kG;
  const RockingSummary s = rock_summary(noisy_record(5, 3000, 0.005, 0.3 * kG), RockingBody::block(0.2, 1.0), o);
  EXPECT_EQ(s.max_rotation_over_alpha, s.max_abs_rotation_rad / s.alpha_rad);
  EXPECT_EQ(s.max_abs_rotation_rad, std::max(s.max_rotation_positive_rad, s.max_rotation_negative_rad));
  EXPECT_EQ(s.max_rotation_over_alpha,
            std::max(s.max_rotation_over_alpha_positive, s.max_rotation_over_alpha_negative));
  EXPECT_EQ(s.alpha_negative_rad, s.alpha_rad);
  EXPECT_EQ(s.e_onto_negative, s.e);
  EXPECT_GT(s.impacts, 0u);
}

}  // namespace
}  // namespace topple
