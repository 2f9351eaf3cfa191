// The coupled slide-rock model on an inclined base (slide_rock.hpp, "Inclined base"; docs/method.md): the sliding
// solver's incline (Goodman & Seed 1966) when the body cannot lift, the tilted onset thresholds in closed form, rest
// without drift, the energy with the potential along the slope, and the rocking engine under the resolved loads.
#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/error.hpp"
#include "topple/io/read.hpp"
#include "topple/rocking.hpp"
#include "topple/slide_rock.hpp"
#include "topple/sliding.hpp"

namespace topple {
namespace {

constexpr double kG = kStandardGravity;

/// A half-sine pulse of amplitude A m/s^2 toward -x (positive a_h: down-slope load), T s, sampled at dt, then `tail` s
/// of still ground.
GroundMotion half_sine(double A, double T, double dt, double tail) {
  const auto n = static_cast<std::size_t>(std::lround(T / dt));
  const auto m = static_cast<std::size_t>(std::lround(tail / dt));
  std::vector<double> a(n + 1 + m, 0.0);
  for (std::size_t i = 0; i <= n; ++i) a[i] = A * std::sin(kPi * static_cast<double>(i) / static_cast<double>(n));
  return GroundMotion::uniform(std::move(a), dt);
}

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
  std::vector<GroundMotion> motions{half_sine(0.5 * kG, 0.4, 0.005, 1.0), sine(0.45 * kG, 0.5, 4.0, 0.01)};
  if (const auto rec = shared_motion("RSN6_IMPVALL.I_I-ELC180.AT2")) motions.push_back(*rec);
  const auto block = SlidingBlock::make(0.3, 0.25, beta, SlidingMode::two_way);
  for (const auto& motion : motions) {
    const auto s = slide_summary(motion, block);
    ASSERT_GT(s.max_abs_displacement_m, 1e-3);  // it does slide
    std::vector<double> work;
    for (const bool kernel : {true, false}) {
      SlideRockOptions o = on_slope(beta);
      o.sliding_kernel = kernel;
      const auto c = slide_rock(motion, body, o).summary;
      EXPECT_EQ(c.used_sliding_kernel, kernel);
      // d = -u: down-slope is -x (slide_rock.hpp)
      EXPECT_NEAR(c.residual_slide_m, -s.residual_displacement_m, 1e-9 * s.max_abs_displacement_m) << kernel;
      EXPECT_NEAR(c.max_abs_slide_m, s.max_abs_displacement_m, 1e-9 * s.max_abs_displacement_m) << kernel;
      EXPECT_EQ(c.slip_episodes, s.slip_episodes) << kernel;
      EXPECT_DOUBLE_EQ(c.max_rotation_over_alpha, 0.0);
      EXPECT_EQ(c.impacts, 0u);
      work.push_back(c.friction_energy_j_per_kg);
    }
    // friction work mu_k n |d'| with n = g cos(beta) - a_h sin(beta): Simpson on cubic pieces (kernel) vs the
    // engine's closed form, both exact: round-off (1e-9 relative)
    EXPECT_NEAR(work[0], work[1], 1e-9 * work[1]);
    EXPECT_GT(work[1], 0.0);
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
  // The level energy test's release (20 x 60 cm, mu_s = 0.45, mu_k = 0.35, theta' = 0.6 rad/s, u' = 0.3 m/s) on a
  // 0.1 rad slope (tan = 0.10 < mu_s, < b1/h = 1/3), still ground. E = T + g cos(b) (Y - h) + g sin(b) X can only fall
  // (friction and impacts dissipate); between rows it may rise by the integration error only (rel_tol 1e-10: 1e-8 of
  // E0 is wide). The body ends at rest at X = u_end, so friction + impact losses = E0 - g sin(b) u_end (1e-6
  // relative: the friction integral is the ODE's, global error ~1e-8).
  const double beta = 0.1;
  const auto still = GroundMotion::uniform(std::vector<double>(501, 0.0), 0.01);
  const auto body = SlideRockBody::block(0.2, 0.6, 0.45, 0.35);
  SlideRockOptions o = on_slope(beta, 1e-10);
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
  const double e_end = kG * std::sin(beta) * s.residual_slide_m;
  EXPECT_NEAR(E.back(), e_end, 1e-12);  // at rest only the potential along the slope is left
  EXPECT_NEAR(s.friction_energy_j_per_kg + s.impact_energy_j_per_kg, e0 - e_end, 1e-6 * e0);
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
    const auto motion = half_sine(amp, 0.3, 0.005, 6.0);
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
    EXPECT_EQ(c.overturned, r.overturned) << amp;
    EXPECT_EQ(c.overturned_side, r.overturned_side) << amp;
    EXPECT_EQ(c.impacts, r.impacts) << amp;
    EXPECT_NEAR(c.max_rotation_over_alpha_positive, r.max_rotation_over_alpha_positive,
                1e-6 * std::max(1.0, r.max_rotation_over_alpha_positive)) << amp;
    EXPECT_NEAR(c.max_rotation_over_alpha_negative, r.max_rotation_over_alpha_negative,
                1e-6 * std::max(1.0, r.max_rotation_over_alpha_negative)) << amp;
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
