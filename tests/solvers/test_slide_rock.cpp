// The coupled slide-rock model (slide_rock.hpp) against its limits: the rocking engine (no slip), the exact sliding
// solver (no uplift), Shenton's onset criteria, the free-flight parabola, the energy balance, and tolerance refinement;
// the same on an inclined base.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/read.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple {
namespace {

constexpr double kG = kStandardGravity;

/// A half-sine acceleration pulse toward -x (it throws the body toward +x), amplitude A m/s^2, duration T s,
/// sampled at dt, followed by `tail` s of still ground.
GroundMotion half_sine(double A, double T, double dt, double tail = 0.0) {
  const auto n = static_cast<std::size_t>(std::lround(T / dt));
  const auto m = static_cast<std::size_t>(std::lround(tail / dt));
  std::vector<double> a(n + 1 + m, 0.0);
  for (std::size_t i = 0; i <= n; ++i) a[i] = -A * std::sin(kPi * static_cast<double>(i) / static_cast<double>(n));
  return GroundMotion::uniform(std::move(a), dt);
}

/// A few cycles of a sine, amplitude A, period T, sampled at dt.
GroundMotion sine(double A, double T, double cycles, double dt) {
  const auto n = static_cast<std::size_t>(std::lround(cycles * T / dt));
  std::vector<double> a(n + 1);
  for (std::size_t i = 0; i <= n; ++i) a[i] = A * std::sin(2.0 * kPi * static_cast<double>(i) * dt / T);
  return GroundMotion::uniform(std::move(a), dt);
}

std::optional<GroundMotion> shared_motion(const std::string& name) {
  if (!test::have_shared()) return std::nullopt;
  return io::read_motion(test::shared_record(name));
}

RockingOptions rocking_options(double rel_tol) {
  RockingOptions o;
  o.rel_tol = rel_tol;
  return o;
}

SlideRockOptions coupled_options(double rel_tol) {
  SlideRockOptions o;
  o.rel_tol = rel_tol;
  return o;
}

// ---------------------------------------------------------------------------------------------------------------
// No slip: the rocking engine

/// Both engines integrate the same equation (rocking.hpp) with Dormand-Prince 5(4) at rel_tol 1e-10 on states scaled
/// the same way; their steps differ (hand-written vs Boost.Odeint's controller, a_dxdt = 0 in both), so maxima agree
/// to the global error of either, ~1e-8 relative: 1e-6 leaves margin. Impacts and verdicts are integers: equal.
void expect_same_rocking(const SlideRockSummary& c, const RockingSummary& r, const std::string& what) {
  EXPECT_EQ(c.overturned, r.overturned) << what;
  EXPECT_EQ(c.overturned_side, r.overturned_side) << what;
  EXPECT_EQ(c.impacts, r.impacts) << what;
  EXPECT_NEAR(c.max_rotation_over_alpha_positive, r.max_rotation_over_alpha_positive,
              1e-6 * std::max(1.0, r.max_rotation_over_alpha_positive)) << what;
  EXPECT_NEAR(c.max_rotation_over_alpha_negative, r.max_rotation_over_alpha_negative,
              1e-6 * std::max(1.0, r.max_rotation_over_alpha_negative)) << what;
}

void expect_same_as_rocking(const GroundMotion& motion, const SlideRockBody& body, const char* what) {
  const auto r = rock_summary(motion, body.rocking_body(), rocking_options(1e-10));
  const auto c = slide_rock(motion, body, coupled_options(1e-10)).summary;
  expect_same_rocking(c, r, what);
  const auto slip = c.mode_first_time_s[static_cast<std::size_t>(SlideRockMode::slide_rock)];
  if (!r.exceeded_alpha_time_s) {
    EXPECT_DOUBLE_EQ(c.max_abs_slide_m, 0.0) << what;  // the pivot never slips
    EXPECT_EQ(c.slip_episodes, 0) << what;
    EXPECT_FALSE(slip) << what;
    EXPECT_NEAR(c.end_time_s, r.end_time_s, 1e-6) << what;  // s: the rest rule ends both at the same impact
  } else if (slip) {
    // A body past alpha falls; near the ground N -> 0 and even mu = 5 cannot hold the pivot (the rocking engine
    // ignores this): any slip comes after |theta| = alpha (located by root finding in both engines).
    EXPECT_GE(*slip, *r.exceeded_alpha_time_s) << what;
  }
}

TEST(SlideRockRockingLimit, HighFrictionEqualsTheRockingEngineOnPulses) {
  // A 20 x 100 cm block (alpha = 0.197 rad) with mu = 5 (> mu_crit for every throw here: no slip). Half-sine pulses
  // of 1.5, 3 and 6 times the uplift threshold g tan(alpha): rocking with impacts, and (the largest) overturning.
  const auto body = SlideRockBody::block(0.2, 1.0, 5.0);
  const double thr = kG * 0.2 / 1.0;
  expect_same_as_rocking(half_sine(1.5 * thr, 0.3, 0.005, 3.0), body, "1.5x");
  expect_same_as_rocking(half_sine(3.0 * thr, 0.3, 0.005, 3.0), body, "3x");
  expect_same_as_rocking(half_sine(6.0 * thr, 0.3, 0.005, 3.0), body, "6x");
  const auto fell = slide_rock(half_sine(6.0 * thr, 0.3, 0.005, 3.0), body).summary;
  EXPECT_TRUE(fell.overturned);  // the case above does test a fall
  const auto rocked = slide_rock(half_sine(1.5 * thr, 0.3, 0.005, 3.0), body).summary;
  EXPECT_GT(rocked.impacts, 100u);  // and one with many impacts (143: Zeno rocking down to the rest rule)
}

TEST(SlideRockRockingLimit, HighFrictionEqualsTheRockingEngineOnARecord) {
  const auto full = shared_motion("RSN6_IMPVALL.I_I-ELC180.AT2");
  if (!full) GTEST_SKIP() << "shared/records not found";
  // El Centro 1940, 1.5-6 s, the thesis' object A (4 x 20 cm), mu = 5: many impacts, an asymmetric variant too.
  const auto window = full->trimmed(1.5, 6.0);
  expect_same_as_rocking(window, SlideRockBody::block(0.04, 0.20, 5.0), "block");
  expect_same_as_rocking(window, SlideRockBody::make(0.015, 0.025, 0.1, (0.04 * 0.04 + 0.2 * 0.2) / 12.0, 5.0),
                         "asymmetric");
  const auto c = slide_rock(window, SlideRockBody::block(0.04, 0.20, 5.0)).summary;
  EXPECT_GE(c.impacts, 3u);  // the window holds 3 impacts of object A
}

TEST(SlideRockRockingLimit, AlphaAndOverturnTimesEqualTheRockingEngines) {
  // mu = 10: the pivot holds up to past alpha. |theta| = alpha is an event located by TOMS 748 on the dense output in
  // both engines (slide_rock.cpp, locate_alpha), so the times agree to the global error of the integration
  // (rel_tol 1e-10: measured 1e-9 s), not to a step: 1e-6 s. The fall at |theta| = pi/2 is located in both too, but
  // it is not the same motion: near the ground N -> 0 and the coupled pivot slips (the rocking engine lets the ground
  // pull it, N < 0), so the coupled body lands later; measured on the block: 3.1 ms at mu = 10, 2.4 ms as mu -> oo
  // (1000), of 0.37 s from alpha to the fall (1 %); the asymmetric body toward -x: 4.0 ms of 0.37 s. Stated bound:
  // later, by at most 2 % of that time.
  const auto check = [](const GroundMotion& motion, const SlideRockBody& body, const char* what) {
    const auto r = rock_summary(motion, body.rocking_body(), rocking_options(1e-10));
    const auto c = slide_rock(motion, body, coupled_options(1e-10)).summary;
    ASSERT_TRUE(r.exceeded_alpha_time_s) << what;
    ASSERT_TRUE(c.exceeded_alpha_time_s) << what;
    EXPECT_NEAR(*c.exceeded_alpha_time_s, *r.exceeded_alpha_time_s, 1e-6) << what;
    ASSERT_TRUE(r.overturned) << what;
    ASSERT_TRUE(c.overturned) << what;
    EXPECT_EQ(c.overturned_side, r.overturned_side) << what;
    const double fall = *r.overturn_time_s - *r.exceeded_alpha_time_s;
    EXPECT_GE(*c.overturn_time_s, *r.overturn_time_s - 1e-6) << what;
    EXPECT_LE(*c.overturn_time_s, *r.overturn_time_s + 0.02 * fall) << what;
  };
  const double thr = kG * 0.2 / 1.0;
  check(half_sine(6.0 * thr, 0.3, 0.005, 3.0), SlideRockBody::block(0.2, 1.0, 10.0), "block");
  const auto asym = SlideRockBody::make(0.08, 0.12, 0.5, (0.2 * 0.2 + 1.0) / 12.0, 10.0);
  check(half_sine(-6.0 * thr, 0.3, 0.005, 3.0), asym, "asymmetric, toward -x");
  check(half_sine(-2.0 * thr, 0.3, 0.005, 3.0), asym, "asymmetric, slowly over");
}

TEST(SlideRockRockingLimit, SymmetricBodyReproducesTheBlock) {
  // b1 = b2 through make() against RockingBody::block (the symmetric path of the rocking engine), and the mirror:
  // the negated input gives the same response on the other side (exact physics; the numbers agree to the global
  // error, 1e-6 as above).
  const auto body = SlideRockBody::make(0.1, 0.1, 0.5, (0.2 * 0.2 + 1.0) / 12.0, 5.0);
  const auto motion = half_sine(3.0 * kG * 0.2, 0.3, 0.005, 3.0);
  const auto r = rock_summary(motion, RockingBody::block(0.2, 1.0), rocking_options(1e-10));
  const auto c = slide_rock(motion, body, coupled_options(1e-10)).summary;
  EXPECT_EQ(c.impacts, r.impacts);
  EXPECT_NEAR(c.max_rotation_over_alpha, r.max_rotation_over_alpha, 1e-6);
  const auto negated = motion.inverted();
  const auto m = slide_rock(negated, body, coupled_options(1e-10)).summary;
  EXPECT_NEAR(m.max_rotation_negative_rad, c.max_rotation_positive_rad, 1e-9);  // rad; mirror, same steps
  EXPECT_NEAR(m.max_rotation_positive_rad, c.max_rotation_negative_rad, 1e-9);
  EXPECT_EQ(m.impacts, c.impacts);
}

// ---------------------------------------------------------------------------------------------------------------
// No uplift: the sliding solver

/// A body that cannot lift against sliding.hpp's `block` on the same slope (block.slope_rad). The default path runs
/// sliding.hpp's kernel; sliding_kernel = false runs the coupled engine's own exact slide phase. Both equal the
/// sliding solver to 1e-9 relative (the bound; both are exact piecewise polynomials, so they agree to
/// round-off of the event times, ~1e-14). Friction work: the kernel path integrates mu_k n |d'| by Simpson on cubic
/// pieces (n = g_e cos(beta) - a_h sin(beta), linear), the engine in closed form: both exact, so they agree to
/// round-off (1e-9 relative).
void expect_same_as_sliding(const GroundMotion& motion, const SlideRockBody& body, const SlidingBlock& block) {
  const auto s = slide_summary(motion, block);
  ASSERT_GT(s.max_abs_displacement_m, 1e-3);  // it does slide
  std::vector<double> work;
  for (const bool kernel : {true, false}) {
    SlideRockOptions o;
    o.slope_rad = block.slope_rad;
    o.sliding_kernel = kernel;
    const auto c = slide_rock(motion, body, o).summary;
    EXPECT_EQ(c.used_sliding_kernel, kernel);
    // d of sliding.hpp is -u (sign convention in slide_rock.hpp; on a slope, down-slope is -x)
    EXPECT_NEAR(c.residual_slide_m, -s.residual_displacement_m, 1e-9 * s.max_abs_displacement_m) << kernel;
    EXPECT_NEAR(c.max_abs_slide_m, s.max_abs_displacement_m, 1e-9 * s.max_abs_displacement_m) << kernel;
    EXPECT_EQ(c.slip_episodes, s.slip_episodes) << kernel;
    EXPECT_DOUBLE_EQ(c.max_rotation_over_alpha, 0.0);
    EXPECT_EQ(c.impacts, 0u);
    work.push_back(c.friction_energy_j_per_kg);
  }
  EXPECT_NEAR(work[0], work[1], 1e-9 * work[1]);
  EXPECT_GT(work[1], 0.0);
}

TEST(SlideRockSlidingLimit, WideBodyEqualsTheExactSlidingSolver) {
  // A 100 x 40 cm block (b/h = 2.5) with mu_s = 0.2, mu_k = 0.15 can never lift (slide_rock.hpp). The default path
  // runs sliding.hpp's kernel; sliding_kernel = false runs the coupled engine's own exact slide phase. Both equal the
  // sliding solver to 1e-9 relative (the bound; both are exact piecewise polynomials, so they agree to
  // round-off of the event times, ~1e-14).
  const auto body = SlideRockBody::block(1.0, 0.4, 0.2, 0.15);
  ASSERT_TRUE(body.cannot_uplift());
  std::vector<GroundMotion> motions{sine(0.6 * kG, 0.5, 4.0, 0.01), half_sine(0.8 * kG, 0.4, 0.005, 1.0)};
  if (const auto rec = shared_motion("RSN6_IMPVALL.I_I-ELC180.AT2")) motions.push_back(*rec);
  const auto block = SlidingBlock::make(0.2, 0.15);
  for (const auto& motion : motions) expect_same_as_sliding(motion, body, block);
}

// ---------------------------------------------------------------------------------------------------------------
// Onset from rest: Shenton (1996)

TEST(SlideRockOnset, AgreesWithShentonsCriteriaOverAGrid) {
  // Symmetric blocks b/h = 0.1 .. 1.0, mu = 0.05 .. 1.5, A = |a_h| / g = 0.02 .. 2: the enumeration of the
  // two-contact problem (slide_rock_onset_mode) against rocking.hpp's shenton_onset_mode. Points within 1e-9 of a
  // boundary (A = mu, A = b/h, mu = b/h, mu = mu_crit) are skipped: there both modes are consistent.
  int compared = 0;
  std::array<int, 4> seen{};
  for (double beta = 0.1; beta <= 1.0001; beta += 0.1) {
    const double h = 0.5;
    const double b = beta * h;
    for (double mu = 0.05; mu <= 1.5001; mu += 0.05) {
      const auto body = SlideRockBody::make(b, b, h, (4.0 * b * b + 4.0 * h * h) / 12.0, mu);
      const RockingBody rb = RockingBody::general(b, h, (4.0 / 3.0) * (b * b + h * h));
      for (double A = 0.02; A <= 2.0001; A += 0.02) {
        if (std::abs(A - mu) < 1e-9 || std::abs(A - beta) < 1e-9 || std::abs(mu - beta) < 1e-9) continue;
        if (std::abs(mu - shenton_critical_mu(rb, A)) < 1e-9) continue;
        const OnsetMode expected = shenton_onset_mode(rb, A, mu);
        for (const double sgn : {-1.0, 1.0}) {
          const SlideRockMode got = slide_rock_onset_mode(body, sgn * A * kG, kG);
          SlideRockMode want = SlideRockMode::rest;
          switch (expected) {
            case OnsetMode::rest: want = SlideRockMode::rest; break;
            case OnsetMode::slide: want = A > mu ? SlideRockMode::slide : SlideRockMode::rest; break;
            case OnsetMode::rock: want = SlideRockMode::rock; break;
            case OnsetMode::slide_rock: want = SlideRockMode::slide_rock; break;
            case OnsetMode::unchecked: break;
          }
          ASSERT_EQ(got, want) << "b/h = " << beta << ", mu = " << mu << ", A = " << A;
          ++compared;
          ++seen[static_cast<std::size_t>(want == SlideRockMode::slide_rock ? 3 : static_cast<int>(want))];
        }
      }
    }
  }
  EXPECT_GT(compared, 50000);
  for (int k = 0; k < 4; ++k) EXPECT_GT(seen[static_cast<std::size_t>(k)], 100) << k;  // every mode is exercised
}

TEST(SlideRockOnset, ARunStartsInTheModeShentonPredicts) {
  // A 20 x 60 cm block (b/h = 1/3), a throw of 1.2 g (A = 1.2 > b/h): mu = 0.2 slides, mu = 0.45 slide-rocks
  // (b/h < 0.45 < mu_crit(1.2) = 0.515), mu = 2 rocks.
  // a jump to -1.2 g (from still ground) for 0.2 s: the body leaves rest at A = 1.2
  const auto motion = GroundMotion::uniform({-1.2 * kG, -1.2 * kG}, 0.2);
  const RockingBody rb = RockingBody::block(0.2, 0.6);
  EXPECT_EQ(slide_rock(motion, SlideRockBody::block(0.2, 0.6, 0.2)).summary.onset_mode, SlideRockMode::slide);
  EXPECT_NEAR(shenton_critical_mu(rb, 1.2), 0.515, 0.001);  // the number the case below relies on
  EXPECT_EQ(slide_rock(motion, SlideRockBody::block(0.2, 0.6, 0.45)).summary.onset_mode, SlideRockMode::slide_rock);
  EXPECT_EQ(slide_rock(motion, SlideRockBody::block(0.2, 0.6, 2.0)).summary.onset_mode, SlideRockMode::rock);
}

// ---------------------------------------------------------------------------------------------------------------
// Free flight, energy, convergence

TEST(SlideRockFlight, FreeFlightIsAParabolaAndLandsWhereItShould) {
  // The ground drops at 2 g for 0.1 s (a_v = -2 g: g_e = -g) while accelerating toward +x at 0.5 g: the body
  // leaves the ground at t = 0 and flies: relative to the ground Y - h = g t^2 / 2, X = -0.25 g t^2 up to 0.1 s, then
  // Y - h = g 0.01 / 2 + 0.1 g tau - g tau^2 / 2, X' = -0.05 g. It lands flat at tau = 0.1 + sqrt(0.02) s with
  // |Y'| = g sqrt(0.02) and stops there (mu = 0.5: mu P_n = 0.69 m/s > |X'| = 0.49 m/s).
  const auto h_motion = GroundMotion::uniform({0.5 * kG, 0.5 * kG}, 0.1);
  const auto v_motion = GroundMotion::uniform({-2.0 * kG, -2.0 * kG}, 0.1);
  const auto body = SlideRockBody::block(0.4, 0.4, 0.5);
  SlideRockOptions o;
  o.record_history = true;
  const auto r = slide_rock(h_motion, body, o, &v_motion);
  const auto& H = r.history;
  std::size_t checked = 0;
  const double t_land = 0.2 + std::sqrt(0.02);
  for (std::size_t k = 0; k < H.time_s.size(); ++k) {
    if (H.mode[k] != SlideRockMode::flight) continue;
    const double t = H.time_s[k];
    const double tau = t - 0.1;
    const double y = t <= 0.1 ? 0.5 * kG * t * t : 0.005 * kG + 0.1 * kG * tau - 0.5 * kG * tau * tau;
    const double x = t <= 0.1 ? -0.25 * kG * t * t : -0.0025 * kG - 0.05 * kG * tau;
    // closed forms evaluated by the engine's polynomials: round-off only (1e-12 m on 0.1 m)
    EXPECT_NEAR(H.cm_height_m[k] - 0.2, y, 1e-12) << t;
    EXPECT_NEAR(H.slide_m[k], x, 1e-12) << t;
    EXPECT_DOUBLE_EQ(H.theta_rad[k], 0.0);
    ++checked;
  }
  EXPECT_GT(checked, 10u);
  const auto& s = r.summary;
  ASSERT_TRUE(s.mode_first_time_s[static_cast<std::size_t>(SlideRockMode::flight)]);
  EXPECT_EQ(s.onset_mode, SlideRockMode::flight);
  EXPECT_EQ(s.impacts, 1u);
  EXPECT_EQ(s.end_mode, SlideRockMode::rest);
  // landing located by TOMS 748 to ulps of the time; the slide after it is X at landing
  EXPECT_NEAR(s.residual_slide_m, -0.0025 * kG - 0.05 * kG * (t_land - 0.1), 1e-12);
  // the plastic landing takes all the kinetic energy: (0.05 g)^2 / 2 + (g sqrt(0.02))^2 / 2
  const double lost = 0.5 * std::pow(0.05 * kG, 2) + 0.5 * kG * kG * 0.02;
  EXPECT_NEAR(s.impact_energy_j_per_kg, lost, 1e-9 * lost);
}

/// Still ground, a 20 x 60 cm block released rocking and sliding (theta' = 0.6 rad/s, u' = 0.3 m/s: 0.125 J/kg,
/// below the 0.158 J/kg that tips it over) with mu_s = 0.45, mu_k = 0.35, on a base inclined at beta (0: level):
/// slide-rock, stick, impacts. Without input the mechanical energy E = T + g cos(beta) (Y - h) + g sin(beta) X can
/// only fall (friction and impacts dissipate); between rows it may rise by the integration error only (rel_tol 1e-10:
/// 1e-8 of E0 is a wide margin). At rest E = g sin(beta) u_end (0 on level ground), so friction + impact losses =
/// E0 - E_end (1e-6 relative: the friction integral is the ODE's, global error ~1e-8).
void expect_release_energy_balance(double beta) {
  const auto still = GroundMotion::uniform(std::vector<double>(501, 0.0), 0.01);
  const auto body = SlideRockBody::block(0.2, 0.6, 0.45, 0.35);
  SlideRockOptions o;
  o.slope_rad = beta;
  o.rel_tol = 1e-10;
  o.record_history = true;
  o.initial_theta_dot_rad_s = 0.6;
  o.initial_slide_velocity_m_s = 0.3;
  const auto r = slide_rock(still, body, o);
  const auto& E = r.history.energy_j_per_kg;
  ASSERT_GT(E.size(), 20u);
  const double e0 = E.front();
  for (std::size_t k = 1; k < E.size(); ++k) EXPECT_LE(E[k], E[k - 1] + 1e-8 * e0) << r.history.time_s[k];
  const auto& s = r.summary;
  EXPECT_EQ(s.end_mode, SlideRockMode::rest);
  EXPECT_GT(s.slip_episodes, 0);
  EXPECT_GT(s.impacts, 0u);
  EXPECT_GT(s.friction_energy_j_per_kg, 0.0);
  const double e_end = kG * std::sin(beta) * s.residual_slide_m;
  EXPECT_NEAR(E.back(), e_end, 1e-12);  // at rest only the potential along the slope is left (round-off)
  EXPECT_NEAR(s.friction_energy_j_per_kg + s.impact_energy_j_per_kg, e0 - e_end, 1e-6 * e0);
}

TEST(SlideRockEnergy, MechanicalEnergyNeverIncreasesAndBalances) { expect_release_energy_balance(0.0); }

TEST(SlideRockConvergence, ErrorFallsWithTheTolerance) {
  // The energy test's release (20 x 60 cm, mu_s = 0.45, mu_k = 0.35, theta' = 0.6 rad/s, u' = 0.3 m/s) on still
  // ground sampled every 1 s, so that the steps are the controller's own, at rel_tol 1e-4 .. 1e-8 against 1e-12:
  // the residual slide and the peak rotation. Dormand-Prince's global error follows the tolerance (error per step
  // control), so each 100x tighter tolerance must cut the error at least 10x (a lax bound for that order; measured:
  // 2.8e-7, 2.6e-9, 2.5e-11 m, 108x per step).
  const auto still = GroundMotion::uniform(std::vector<double>(6, 0.0), 1.0);
  const auto body = SlideRockBody::block(0.2, 0.6, 0.45, 0.35);
  const auto run = [&](double tol) {
    SlideRockOptions o;
    o.rel_tol = tol;
    o.abs_tol = tol * 1e-4;
    o.initial_theta_dot_rad_s = 0.6;
    o.initial_slide_velocity_m_s = 0.3;
    return slide_rock(still, body, o).summary;
  };
  const auto ref = run(1e-12);
  ASSERT_GT(ref.mode_entries[static_cast<std::size_t>(SlideRockMode::slide_rock)], 0u);
  ASSERT_GT(std::abs(ref.residual_slide_m), 1e-3);
  std::vector<double> err;
  for (const double tol : {1e-4, 1e-6, 1e-8}) {
    const auto s = run(tol);
    err.push_back(std::abs(s.residual_slide_m - ref.residual_slide_m) +
                  std::abs(s.max_rotation_positive_rad - ref.max_rotation_positive_rad) * body.h_m);
  }
  EXPECT_LT(err[1], err[0] / 10.0);
  EXPECT_LT(err[2], err[1] / 10.0);
  EXPECT_LT(err[2], 1e-7);  // m: the tight end is close
}

// ---------------------------------------------------------------------------------------------------------------
// Painleve's paradox (docs/method.md): the impact without collision and the hold

TEST(SlideRockPainleve, FrictionLimitIsTheLeastRatioOverTheTilts) {
  // mu_P against a scan of (k2 + rho_x^2) / |rho_x rho_y| over 0 <= theta < pi/2 on both pivots, rho from the contact
  // geometry itself (rho_x = -s b_s cos theta + h sin theta, rho_y = s b_s sin theta + h cos theta), not the closed
  // form. Step 1e-5 rad: the ratio is smooth at its minimum, so the scan is within ~1e-9 of it; 1e-8 allows that.
  const auto scanned = [](const SlideRockBody& body) {
    double least = std::numeric_limits<double>::infinity();
    for (const int s : {-1, 1}) {
      const double b = s < 0 ? body.b1_m : body.b2_m;
      for (double th = 0.0; th < kPi / 2.0; th += 1e-5) {
        const double rx = -s * b * std::cos(th) + body.h_m * std::sin(th);
        const double ry = s * b * std::sin(th) + body.h_m * std::cos(th);
        if (rx != 0.0) least = std::min(least, (body.inertia_m2 + rx * rx) / std::abs(rx * ry));
      }
    }
    return least;
  };
  for (const SlideRockBody& body : {SlideRockBody::block(0.1, 0.4, 0.5), SlideRockBody::block(0.6, 0.3, 0.5),
                                    SlideRockBody::make(0.05, 0.2, 0.3, 0.004, 0.5)}) {
    EXPECT_NEAR(body.painleve_friction_limit(), scanned(body), 1e-8) << body.b1_m << " " << body.b2_m;
  }
  // A rectangular block: q = k2 / R^2 = 1/3 whatever its b/h, so mu_P = 2 sqrt(4/9) = 4/3 (to rounding).
  EXPECT_NEAR(SlideRockBody::block(0.1, 0.4, 0.5).painleve_friction_limit(), 4.0 / 3.0, 1e-15);
  EXPECT_NEAR(SlideRockBody::block(0.6, 0.3, 0.5).painleve_friction_limit(), 4.0 / 3.0, 1e-15);
}

TEST(SlideRockPainleve, AsymmetricBodyGoingOverCompletes) {
  // b1 = 5 cm, b2 = 20 cm, h = 30 cm, k2 = 0.00925 m2, mu = 5, a half-sine of 20 m/s^2 for 0.3 s: the body rocks onto
  // O+ and the stick limit is passed where the slip it would start has den = k2 + c rho_x <= 0. This threw SolverError
  // (exit 3) before the resolution; now the pivot is held (rock) and the body goes over toward +x.
  const auto motion = half_sine(20.0, 0.3, 0.001, 2.0);
  const auto body = SlideRockBody::make(0.05, 0.2, 0.3, 0.00925, 5.0);
  SlideRockOptions o;
  o.record_history = true;
  const auto r = slide_rock(motion, body, o);
  const auto& s = r.summary;
  EXPECT_GE(s.painleve_holds, 1u);
  EXPECT_TRUE(s.overturned);
  EXPECT_EQ(s.overturned_side, 1);
  // after the pulse the ground is still: the mechanical energy can only fall, up to the integration error
  // (rel_tol 1e-8 on a state of order 1: 1e-6 J/kg of ~2 J/kg is a wide margin)
  const auto& H = r.history;
  ASSERT_GT(H.time_s.size(), 10u);
  int after = 0;
  for (std::size_t k = 1; k < H.time_s.size(); ++k) {
    if (H.time_s[k - 1] < 0.3) continue;
    ++after;
    EXPECT_LE(H.energy_j_per_kg[k], H.energy_j_per_kg[k - 1] + 1e-6) << H.time_s[k];
  }
  EXPECT_GT(after, 5);
}

TEST(SlideRockPainleve, TangentialImpactStopsASlippingPivotInsideTheCone) {
  // A 20 x 60 cm block (b = 0.1, h = 0.3, k2 = 1/30 m2), mu = 2, released on O+ at theta = 0.05 rad, theta' = 0.5
  // rad/s, its pivot slipping toward +x at 0.3 m/s: den = k2 + rho_x^2 + mu rho_x rho_y = -0.011 m2 < 0, so slide-rock
  // has no solution and the pivot is stopped by the tangential impact at t = 0. Closed forms (slide_rock.cpp,
  // tangential_impact): theta'+ = theta' + rho_y u' / D, |P_t| / P_n = (k2 + rho_x^2) / |rho_x rho_y| <= mu_k, energy
  // lost u'^2 (k2 + rho_x^2) / (2 D). Tolerances 1e-12: a few roundings of terms of order 1.
  const double b = 0.1;
  const double hh = 0.3;
  const double k2 = (0.2 * 0.2 + 0.6 * 0.6) / 12.0;
  const double th = 0.05;
  const double w = 0.5;
  const double v = 0.3;
  const auto still = GroundMotion::uniform(std::vector<double>(301, 0.0), 0.01);
  const auto body = SlideRockBody::block(0.2, 0.6, 2.0);
  SlideRockOptions o;
  o.rel_tol = 1e-10;
  o.record_history = true;
  o.initial_theta_rad = th;
  o.initial_theta_dot_rad_s = w;
  o.initial_slide_velocity_m_s = v;
  const auto r = slide_rock(still, body, o);
  const double rx = -b * std::cos(th) + hh * std::sin(th);
  const double ry = b * std::sin(th) + hh * std::cos(th);
  const double D = k2 + b * b + hh * hh;
  ASSERT_LT(k2 + rx * rx + 2.0 * rx * ry, 0.0);  // the Painleve case
  const auto& s = r.summary;
  EXPECT_EQ(s.tangential_impacts, 1u);
  const double ratio = (k2 + rx * rx) / std::abs(rx * ry);
  EXPECT_NEAR(s.max_tangential_impulse_ratio, ratio, 1e-12);
  EXPECT_LE(s.max_tangential_impulse_ratio, body.mu_kinetic);
  const auto& H = r.history;
  ASSERT_GT(H.time_s.size(), 2u);
  EXPECT_DOUBLE_EQ(H.slide_velocity_m_s[0], 0.0);  // the pivot sticks after the impulse
  EXPECT_NEAR(H.theta_dot_rad_s[0], w + ry * v / D, 1e-12);
  const double vx = v + ry * w;
  const double vy = -rx * w;
  const double e0 = 0.5 * (vx * vx + vy * vy + k2 * w * w) + kG * (ry - hh);
  EXPECT_NEAR(e0 - H.energy_j_per_kg[0], v * v * (k2 + rx * rx) / (2.0 * D), 1e-12);
  // then still ground: the energy never rises (integration error only, 1e-8 of e0 as the energy test) and balances
  for (std::size_t k = 1; k < H.time_s.size(); ++k) {
    EXPECT_LE(H.energy_j_per_kg[k], H.energy_j_per_kg[k - 1] + 1e-8 * e0) << H.time_s[k];
  }
  EXPECT_EQ(s.end_mode, SlideRockMode::rest);
  EXPECT_NEAR(s.friction_energy_j_per_kg + s.impact_energy_j_per_kg, e0, 1e-6 * e0);
}

// ---------------------------------------------------------------------------------------------------------------
// Input checks

TEST(SlideRockInput, RefusesBadBodiesAndOptionsNamingTheField) {
  const auto field_of = [](auto f) -> std::string {
    try {
      f();
    } catch (const InputError& e) {
      return e.where().field;
    }
    ADD_FAILURE() << "no InputError";
    return {};
  };
  EXPECT_EQ(field_of([] { (void)SlideRockBody::make(-0.1, 0.1, 0.5, 0.1, 0.5); }), "b1");
  EXPECT_EQ(field_of([] { (void)SlideRockBody::make(0.1, 0.1, 0.5, 0.1, 0.5, 0.6); }), "mu_k");
  EXPECT_EQ(field_of([] { (void)SlideRockBody::make(0.1, 0.1, 0.5, 0.1, -1.0); }), "mu");
  EXPECT_EQ(field_of([] { (void)SlideRockBody::make(0.1, 0.1, 0.5, 0.0, 0.5); }), "inertia");
  const auto body = SlideRockBody::block(0.2, 1.0, 0.5);
  const auto motion = sine(1.0, 1.0, 1.0, 0.01);
  SlideRockOptions o;
  o.rel_tol = 0.0;
  EXPECT_EQ(field_of([&] { (void)slide_rock(motion, body, o); }), "rel_tol");
  o = {};
  o.restitution = RestitutionMode::given;
  o.e = 1.5;
  EXPECT_EQ(field_of([&] { (void)slide_rock(motion, body, o); }), "e");
  // a squat block (alpha > 54.7 deg) that can lift (mu > b/h) with Housner's e < 0 and no e given
  EXPECT_EQ(field_of([&] { (void)slide_rock(motion, SlideRockBody::block(3.0, 1.0, 3.5), SlideRockOptions{}); }), "e");
}

// ---------------------------------------------------------------------------------------------------------------
// Inclined base (slide_rock.hpp, "Inclined base"; docs/method.md): the sliding solver's incline (Goodman & Seed 1966)
// when the body cannot lift, the tilted onset thresholds in closed form, rest without drift, the energy with the
// potential along the slope, and the rocking engine under the resolved loads.

SlideRockOptions on_slope(double beta, double rel_tol = 1e-8) {
  SlideRockOptions o;
  o.slope_rad = beta;
  o.rel_tol = rel_tol;
  return o;
}

TEST(SlideRockIncline, BodyThatCannotLiftEqualsTheSlidingSolversIncline) {
  // A 100 x 40 cm block (b/h = 2.5) with mu_s = 0.3, mu_k = 0.25 cannot lift, on a 10 deg slope (tan = 0.176 < mu_s).
  // Both paths (sliding.hpp's kernel, and the engine's own exact slide phase on the resolved loads) equal sliding.hpp
  // two-way on the same slope to 1e-9 relative: all are exact piecewise polynomials (round-off of event times only).
  const double beta = 10.0 * kPi / 180.0;
  const auto body = SlideRockBody::block(1.0, 0.4, 0.3, 0.25);
  ASSERT_TRUE(body.cannot_uplift());
  std::vector<GroundMotion> motions{half_sine(-0.5 * kG, 0.4, 0.005, 1.0), sine(0.45 * kG, 0.5, 4.0, 0.01)};
  if (const auto rec = shared_motion("RSN6_IMPVALL.I_I-ELC180.AT2")) motions.push_back(*rec);
  const auto block = SlidingBlock::make(0.3, 0.25, beta, SlidingMode::two_way);
  for (const auto& motion : motions) {
    expect_same_as_sliding(motion, body, block);
    // the slope ratchets the body down-slope (-x): a check on the sign convention
    EXPECT_LT(slide_rock(motion, body, on_slope(beta)).summary.residual_slide_m, 0.0);
  }
}

TEST(SlideRockIncline, OnsetFromRestAtTheTiltedClosedFormThresholds) {
  // Resolving a_h and g into the base frame (f_t = a_h cos b + g sin b, n = g cos b - a_h sin b) turns the level
  // criteria |f_t| <= mu_s n, b1 n - h f_t >= 0, b2 n + h f_t >= 0 into (slide_rock.hpp):
  //   slip down-slope  a_h > g tan(phi - beta),   up-slope  a_h < -g tan(phi + beta)     (tan phi = mu_s)
  //   uplift about O-  a_h > g tan(alpha- - beta), about O+  a_h < -g tan(alpha+ + beta)
  // At 1 +- 1e-6 of each threshold the margin is ~1e-6 of the loads, far above round-off (1e-16).
  const double beta = 0.15;
  const double eps = 1e-6;
  const auto expect_threshold = [&](const SlideRockBody& body, double a, SlideRockMode above) {
    EXPECT_EQ(slide_rock_onset_mode(body, a * (1.0 + eps), kG, beta), above) << a;
    EXPECT_EQ(slide_rock_onset_mode(body, a * (1.0 - eps), kG, beta), SlideRockMode::rest) << a;
  };
  // squat and rough enough to slide first: 100 x 40 cm, mu = 0.3
  const double phi = std::atan(0.3);
  const auto squat = SlideRockBody::block(1.0, 0.4, 0.3);
  expect_threshold(squat, kG * std::tan(phi - beta), SlideRockMode::slide);
  expect_threshold(squat, -kG * std::tan(phi + beta), SlideRockMode::slide);
  // slender and rough (20 x 60 cm, mu = 2): rocks first
  const double alpha = std::atan(0.1 / 0.3);
  const auto slender = SlideRockBody::block(0.2, 0.6, 2.0);
  expect_threshold(slender, kG * std::tan(alpha - beta), SlideRockMode::rock);
  expect_threshold(slender, -kG * std::tan(alpha + beta), SlideRockMode::rock);
  // an asymmetric body (b1 = 0.12, b2 = 0.08, h = 0.3): alpha- and alpha+ differ, each threshold uses its own
  const auto asym = SlideRockBody::make(0.12, 0.08, 0.3, 0.01, 2.0);
  expect_threshold(asym, kG * std::tan(std::atan(0.12 / 0.3) - beta), SlideRockMode::rock);
  expect_threshold(asym, -kG * std::tan(std::atan(0.08 / 0.3) + beta), SlideRockMode::rock);

  // A run on a step of a_h 1 % above / below the down-slope uplift threshold: it first lifts about the down-slope
  // corner O- (theta < 0; after the step it rocks back and may cross over a little) or stays at rest.
  const double thr = kG * std::tan(alpha - beta);
  SlideRockOptions o = on_slope(beta);
  o.record_history = true;
  const auto run = slide_rock(GroundMotion::uniform({1.01 * thr, 1.01 * thr}, 0.05), slender, o);
  const auto& above = run.summary;
  EXPECT_EQ(above.onset_mode, SlideRockMode::rock);
  EXPECT_GT(above.max_rotation_negative_rad, 0.0);
  const auto& th = run.history.theta_rad;
  const auto first = std::find_if(th.begin(), th.end(), [](double x) { return x != 0.0; });
  ASSERT_NE(first, th.end());
  EXPECT_LT(*first, 0.0);
  const auto below = slide_rock(GroundMotion::uniform({0.99 * thr, 0.99 * thr}, 0.05), slender, on_slope(beta)).summary;
  EXPECT_EQ(below.onset_mode, SlideRockMode::rest);
  EXPECT_DOUBLE_EQ(below.max_rotation_over_alpha, 0.0);
}

TEST(SlideRockIncline, AtRestOnASlopeWithoutShakingStaysAtRest) {
  // Still ground for 10 s: a body whose slope is just inside its friction angle (squat) or its alpha- (slender) is
  // loaded by g sin(beta) along the slope and must not move at all (exactly 0: no integration happens at rest).
  const auto still = GroundMotion::uniform(std::vector<double>(1001, 0.0), 0.01);
  const auto squat = SlideRockBody::block(1.0, 0.4, 0.3, 0.2);
  const auto slender = SlideRockBody::make(0.1, 0.1, 0.3, 0.01, 2.0);
  const std::vector<std::pair<SlideRockBody, double>> cases{{squat, 0.999 * std::atan(0.3)},
                                                            {slender, 0.999 * std::atan(0.1 / 0.3)}};
  for (const auto& [body, beta] : cases) {
    for (const bool kernel : {true, false}) {
      SlideRockOptions o = on_slope(beta);
      o.sliding_kernel = kernel;
      o.record_history = true;
      const auto r = slide_rock(still, body, o);
      const auto& s = r.summary;
      EXPECT_EQ(s.onset_mode, SlideRockMode::rest) << beta;
      EXPECT_EQ(s.end_mode, SlideRockMode::rest);
      EXPECT_EQ(s.residual_slide_m, 0.0);
      EXPECT_EQ(s.max_abs_slide_m, 0.0);
      EXPECT_EQ(s.max_rotation_over_alpha, 0.0);
      EXPECT_EQ(s.slip_episodes, 0);
      EXPECT_NEAR(s.end_time_s, 10.0, 1e-12);
      ASSERT_FALSE(r.history.time_s.empty());
      for (std::size_t k = 0; k < r.history.time_s.size(); ++k) {
        EXPECT_EQ(r.history.slide_m[k], 0.0);
        EXPECT_EQ(r.history.theta_rad[k], 0.0);
        EXPECT_EQ(r.history.mode[k], SlideRockMode::rest);
      }
    }
  }
}

TEST(SlideRockIncline, EnergyWithThePotentialAlongTheSlopeNeverIncreases) {
  // The level release on a 0.1 rad slope (tan = 0.10 < mu_s, < b1/h = 1/3): see expect_release_energy_balance.
  expect_release_energy_balance(0.1);
}

TEST(SlideRockIncline, HighFrictionEqualsTheRockingEngineUnderTheResolvedLoads) {
  // rocking.hpp has no slope; a sticking body on a slope obeys its equation with (a_h, g_e) -> (f_t, n), so the
  // rocking engine fed the horizontal record f_t and the vertical record n - g must give the same response. A 20 x
  // 100 cm block, mu = 5 (no slip), a 0.1 rad slope, half-sine pulses toward the down-slope side and the up-slope one.
  // Same tolerances as the level comparison (test_slide_rock.cpp): 1e-6 on maxima, impacts and verdicts equal.
  const double beta = 0.1;
  const auto body = SlideRockBody::block(0.2, 1.0, 5.0);
  const double cb = std::cos(beta);
  const double sb = std::sin(beta);
  const double thr = kG * 0.2;  // the level uplift threshold, a scale
  int fell = 0;
  for (const double amp : {1.5 * thr, 3.0 * thr, -3.0 * thr, 6.0 * thr}) {
    const auto motion = half_sine(-amp, 0.3, 0.005, 6.0);  // a_h = +amp sin: amp > 0 loads down-slope
    std::vector<double> ft(motion.size());
    std::vector<double> nv(motion.size());
    for (std::size_t i = 0; i < motion.size(); ++i) {
      const double a = motion.accel_m_s2()[i];
      ft[i] = a * cb + kG * sb;
      nv[i] = kG * cb - a * sb - kG;
    }
    const auto H = GroundMotion::uniform(std::move(ft), 0.005);
    const auto V = GroundMotion::uniform(std::move(nv), 0.005);
    RockingOptions ro;
    ro.rel_tol = 1e-10;
    ro.max_run_out_s = 0.0;  // still ground on the slope is not still ground for the rocking engine: end with the record
    const auto r = rock_summary(H, body.rocking_body(), ro, &V);
    SlideRockOptions o = on_slope(beta, 1e-10);
    o.max_run_out_s = 0.0;
    const auto c = slide_rock(motion, body, o).summary;
    expect_same_rocking(c, r, std::to_string(amp));
    EXPECT_GT(c.max_rotation_over_alpha, 0.1) << amp;  // it does rock
    if (c.overturned) ++fell;
  }
  EXPECT_GE(fell, 1);  // a fall is compared too
}

TEST(SlideRockIncline, RefusesASlopeTheBodyCannotStandOn) {
  const auto field_and_text = [](auto f) -> std::pair<std::string, std::string> {
    try {
      f();
    } catch (const InputError& e) {
      return {e.where().field, e.what()};
    }
    ADD_FAILURE() << "no InputError";
    return {};
  };
  const auto motion = sine(1.0, 1.0, 1.0, 0.01);
  const auto squat = SlideRockBody::block(1.0, 0.4, 0.3);        // phi = 16.7 deg
  const auto slender = SlideRockBody::block(0.2, 0.6, 2.0);      // alpha = 18.4 deg
  const auto steep = field_and_text([&] { (void)slide_rock(motion, squat, on_slope(20.0 * kPi / 180.0)); });
  EXPECT_EQ(steep.first, "slope");
  EXPECT_NE(steep.second.find("friction angle"), std::string::npos) << steep.second;
  const auto tips = field_and_text([&] { (void)slide_rock(motion, slender, on_slope(20.0 * kPi / 180.0)); });
  EXPECT_EQ(tips.first, "slope");
  EXPECT_NE(tips.second.find("alpha-"), std::string::npos) << tips.second;
  EXPECT_EQ(field_and_text([&] { (void)slide_rock(motion, squat, on_slope(-0.1)); }).first, "slope");
  EXPECT_EQ(field_and_text([&] { (void)slide_rock(motion, squat, on_slope(std::nan(""))); }).first, "slope");
  EXPECT_EQ(field_and_text([&] { (void)slide_rock_onset_mode(squat, 0.0, kG, 0.5); }).first, "slope");
}

}  // namespace
}  // namespace topple
