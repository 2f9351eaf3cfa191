// The independent check of issue 29 ("Bodies in three dimensions"): a Siconos simulation of a box on a rigid plane
// (tests/support/siconos_rigid3d.hpp: Moreau-Jean time stepping, 4 base corners, Newton impact, Coulomb friction)
// against topple's trusted planar engines and a closed form. docs/verification.md, "Independent check: Siconos",
// gives the numbers. Moreau-Jean is first order at events (an impact or a stick-slip change is resolved at the end
// of the step that contains it), so each tolerance below is stated in terms of the step h and checked to shrink
// with h: these tests say the reference converges to topple's answer, not merely that it is close at one h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "support/siconos_rigid3d.hpp"
#include "topple/bodies/rocking_body.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"

namespace {

using topple::GroundMotion;
using topple::test::SiconosBox;
using topple::test::SiconosGroundMotion;
using topple::test::SiconosOptions;
using topple::test::SiconosResult;
using topple::test::simulate_siconos_box;

constexpr double kG = 9.80665;  // the planar engines' default g (kStandardGravity); the reference uses the same

/// One cycle of a sine, A sin(2 pi t / T) for 0 <= t <= T, then zero up to `total`, sampled every dt.
std::vector<double> sine_pulse(double amplitude, double period_s, double dt_s, double total_s) {
  std::vector<double> a;
  const auto n = static_cast<std::size_t>(std::lround(total_s / dt_s));
  for (std::size_t i = 0; i <= n; ++i) {
    const double t = static_cast<double>(i) * dt_s;
    a.push_back(t <= period_s + 1e-12 ? amplitude * std::sin(2.0 * std::numbers::pi * t / period_s) : 0.0);
  }
  return a;
}

/// |theta| of the planar history at t (linear between its rows; the rows are dense: every sample and event).
double planar_abs_theta_at(const topple::RockingResult& r, double t) {
  const auto& ts = r.history.time_s;
  const auto& th = r.history.theta_rad;
  const auto it = std::upper_bound(ts.begin(), ts.end(), t);
  if (it == ts.begin()) return std::abs(th.front());
  if (it == ts.end()) return std::abs(th.back());
  const auto j = static_cast<std::size_t>(it - ts.begin());
  const double f = (t - ts[j - 1]) / (ts[j] - ts[j - 1]);
  return std::abs(th[j - 1] + f * (th[j] - th[j - 1]));
}

/// First time the planar |theta| reaches `level` (linear between rows); negative when never.
double planar_crossing_time(const topple::RockingResult& r, double level) {
  const auto& ts = r.history.time_s;
  const auto& th = r.history.theta_rad;
  for (std::size_t i = 1; i < th.size(); ++i) {
    const double a0 = std::abs(th[i - 1]), a1 = std::abs(th[i]);
    if (a0 < level && a1 >= level) return ts[i - 1] + (level - a0) / (a1 - a0) * (ts[i] - ts[i - 1]);
  }
  return -1.0;
}

// The rocking box: 0.2 m wide (x), 0.3 m deep (y), 1.0 m tall: alpha = atan(0.1 / 0.5) = 0.197 rad, rocking in the
// x-z plane, its plane of symmetry. e = 0 at the corners and mu = 10 (no sliding).
//
// Why Newton's e = 0 at the corners is Housner's law here (and the comparison runs through the impacts): Housner
// (1963) derives his e = 1 - 2 a^2 / D from an impact that is perfectly plastic at the landing edge (no rebound, no
// slip) and carries no impulse at the old pivot, which lifts off; angular momentum about the landing edge is then
// conserved. In Moreau-Jean with Newton e = 0 at all four corners, the post-impact velocity is the one closest to the
// pre-impact one (in the kinetic metric) with no corner moving into the ground; Housner's post-impact motion (rotation
// about the new edge at e_H times the old rate) has the landing corners at rest and the old ones rising, with an
// impulse at the landing corners only, so it satisfies the impact law's complementarity at every corner and is that
// solution, as long as e_H >= 0 (alpha < 54.7 deg) and friction holds the landing edge. Here e_H = 0.943.
constexpr double kRockA = 0.1, kRockB = 0.15, kRockC = 0.5;

struct RockingComparison {
  SiconosResult reference;
  topple::RockingResult planar;
};

RockingComparison run_rocking(double amplitude_g, double period_s, double total_s, double step_s) {
  const double dt = 0.005;
  // Toward -x: the inertial load pushes the box toward +x; the planar engine's theta > 0 (rocking about O+).
  const auto a = sine_pulse(-amplitude_g * kG, period_s, dt, period_s);
  SiconosOptions options;
  options.step_s = step_s;
  options.duration_s = total_s;
  RockingComparison out;
  out.reference = simulate_siconos_box(SiconosBox{kRockA, kRockB, kRockC, 1.0, 0.0, 10.0},
                                       SiconosGroundMotion{dt, a, {}, {}}, options);
  topple::RockingOptions ro;  // Housner's restitution (the default)
  ro.max_run_out_s = total_s - period_s;
  out.planar = topple::rock(GroundMotion::uniform(a, dt), topple::RockingBody::block(2 * kRockA, 2 * kRockC), ro);
  return out;
}

// (1a) A pulse that rocks the box through many impacts without overturning it: the verdict, the max tilt (reached
// after the first impacts) and the free-rocking phase before the first impact agree with the planar engine.
// Tolerances. Free rocking before the first impact: the uplift is resolved at a step's end, a time shift of at most
// h, hence a tilt error up to max|theta'| h; allowed 2 max|theta'| h (measured 0.24x and 0.27x that bound at h = 1 and
// 0.5 ms). Max tilt: each impact adds such a shift; allowed 1 % at h = 0.5 ms (measured 0.14 %; 0.73 % at 1 ms), the error
// must not grow when h halves, and the time of the max tilt agrees to 5 ms.
TEST(SiconosReference, RockingInItsPlaneOfSymmetryMatchesThePlanarEngine) {
  double previous_error = 0.0;
  for (const double h : {1e-3, 5e-4}) {
    const auto run = run_rocking(0.45, 0.2, 3.0, h);
    const auto& planar = run.planar.summary;
    ASSERT_FALSE(planar.overturned);
    ASSERT_GT(planar.impacts, 5u);  // the comparison really runs through impacts
    EXPECT_FALSE(run.reference.overturned);
    EXPECT_TRUE(run.reference.unconverged_step_times_s.empty()) << "h = " << h;

    double first_impact_s = 1e9;
    for (const auto& e : run.planar.events)
      if (e.kind == topple::RockingEventKind::impact) {
        first_impact_s = e.time_s;
        break;
      }
    double free_phase_error = 0.0;
    const auto& hist = run.reference.history;
    for (std::size_t i = 0; i < hist.time_s.size() && hist.time_s[i] < first_impact_s - 2 * h; ++i)
      free_phase_error = std::max(free_phase_error, std::abs(hist.tilt_rad[i] - planar_abs_theta_at(run.planar,
                                                                                                    hist.time_s[i])));
    const double bound = 2.0 * planar.max_abs_theta_dot_rad_s * h;
    const double max_error = std::abs(run.reference.max_tilt_rad - planar.max_abs_rotation_rad);
    std::printf("rocking 0.45 g, 0.2 s, h = %g: max tilt %.6f (planar %.6f, %zu impacts), error %.2e (%.3f %%); "
                "free phase to %.4f s: error %.2e, bound 2 max|theta'| h = %.2e\n",
                h, run.reference.max_tilt_rad, planar.max_abs_rotation_rad, planar.impacts, max_error,
                100 * max_error / planar.max_abs_rotation_rad, first_impact_s, free_phase_error, bound);
    EXPECT_LE(free_phase_error, bound) << "h = " << h;
    if (h < 1e-3) {
      EXPECT_LE(max_error, 0.01 * planar.max_abs_rotation_rad);
      EXPECT_LE(max_error, previous_error) << "the error must not grow as the step shrinks";
    }
    EXPECT_NEAR(run.reference.max_tilt_time_s, planar.max_rotation_time_s, 0.005);
    // It rocks in its plane of symmetry: the tilt across it stays below 0.1 % of the tilt (measured 0.009 % at 1 ms:
    // the Gauss-Seidel contact solver sweeps the four corners in a fixed order, which is not symmetric).
    EXPECT_LT(std::abs(run.reference.max_tilt_axis[1]), 1e-3);
    previous_error = max_error;
  }
}

// (1b) A long pulse that overturns it: both say overturned, and the reference reaches 80 deg (its overturn flag)
// when the planar |theta| does. Tolerance 1 % of that time: the time error is a few steps' shift at the uplift and at each
// impact on the way (the planar engine counts them), 0.5 ms each: measured 0.3 ms on 1.45 s (0.02 %).
TEST(SiconosReference, OverturningUnderALongPulseMatchesThePlanarVerdictAndTime) {
  const auto run = run_rocking(0.5, 0.5, 3.0, 5e-4);
  ASSERT_TRUE(run.planar.summary.overturned);
  ASSERT_TRUE(run.reference.overturned);
  const double planar_80 = planar_crossing_time(run.planar, 80.0 * std::numbers::pi / 180.0);
  ASSERT_GT(planar_80, 0.0);
  std::printf("overturning 0.5 g, 0.5 s: reference reaches 80 deg at %.4f s, planar at %.4f s (falls at %.4f s)\n",
              *run.reference.overturn_time_s, planar_80, run.planar.summary.overturn_time_s.value_or(-1));
  EXPECT_NEAR(*run.reference.overturn_time_s, planar_80, 0.01 * planar_80);
  // The CM leaves the base's footprint when the planar |theta| first exceeds alpha (same tolerance and reason).
  ASSERT_TRUE(run.planar.summary.exceeded_alpha_time_s.has_value());
  ASSERT_TRUE(run.reference.cm_past_base_time_s.has_value());
  const auto& unconverged = run.reference.unconverged_step_times_s;
  std::printf("  CM past the base at %.4f s, planar |theta| > alpha at %.4f s; %zu unconverged contact steps, from "
              "%.4f s\n", *run.reference.cm_past_base_time_s, *run.planar.summary.exceeded_alpha_time_s,
              unconverged.size(), unconverged.empty() ? -1.0 : unconverged.front());
  EXPECT_NEAR(*run.reference.cm_past_base_time_s, *run.planar.summary.exceeded_alpha_time_s,
              0.01 * *run.planar.summary.exceeded_alpha_time_s);
  // NSGS leaves a few steps unconverged late in the fall (measured: 4, from 1.42 s, tilt above 70 deg, the two
  // pivot corners carrying the whole weight at a grazing angle); none before the CM passed the base, after which
  // the pulse is over and the fall is decided.
  for (const double t : unconverged) EXPECT_GT(t, *run.reference.cm_past_base_time_s);
  // The fall is on the planar engine's side (+1: toward +x), in the plane of the input.
  ASSERT_NE(run.planar.summary.overturned_side, 0);
  EXPECT_NEAR(run.reference.max_tilt_axis[0], run.planar.summary.overturned_side, 1e-6);
}

// (2) A low wide box (1.0 x 0.8 x 0.1 m: a/h = 10, it cannot uplift below 10 g) under two horizontal components
// slides as the 2-D sliding solver's block (mu = 0.3). Moreau-Jean is first order here (each slip onset and stop is
// resolved at a step's end): the residual's error must halve with h (ratio in [1.6, 2.4]; measured 1.99), and the
// Richardson extrapolation 2 u(h/2) - u(h), which removes the O(h) term, must agree with topple to 1 % of |u|
// (measured 0.14 %, 3e-6 m on 2.4 mm). No tilt, no yaw.
TEST(SiconosReference, ABoxThatCannotUpliftSlidesAsTheTwoDimensionalSlidingSolver) {
  const double dt = 0.005, mu = 0.3;
  const auto ax = sine_pulse(0.6 * kG, 0.4, dt, 0.4);
  const auto ay = sine_pulse(-0.4 * kG, 0.3, dt, 0.4);
  const auto topple_2d = topple::slide_2d_summary(GroundMotion::uniform(ax, dt), GroundMotion::uniform(ay, dt),
                                                  topple::ComponentAzimuths{90.0, 0.0, 0.0},
                                                  topple::SlidingBlock::make(mu));
  ASSERT_LT(topple_2d.end_time_s, 1.4);  // at rest before the reference's run ends
  const double ux = topple_2d.residual_east_m, uy = topple_2d.residual_north_m;
  const double u = std::hypot(ux, uy);
  ASSERT_GT(u, 1e-3);

  std::array<std::array<double, 2>, 2> residual{};
  std::array<double, 2> error{};
  const std::array<double, 2> steps{1e-3, 5e-4};
  for (std::size_t k = 0; k < 2; ++k) {
    SiconosOptions options;
    options.step_s = steps[k];
    options.duration_s = 1.5;
    const auto r = simulate_siconos_box(SiconosBox{0.5, 0.4, 0.05, 1.0, 0.0, mu}, SiconosGroundMotion{dt, ax, ay, {}},
                                        options);
    residual[k] = r.final_displacement_m;
    error[k] = std::hypot(residual[k][0] - ux, residual[k][1] - uy);
    EXPECT_LT(r.max_tilt_rad, 1e-4) << "h = " << steps[k];
    EXPECT_LT(std::abs(r.final_yaw_rad), 1e-5) << "h = " << steps[k];
    EXPECT_TRUE(r.unconverged_step_times_s.empty()) << "h = " << steps[k];
  }
  const double ex = 2 * residual[1][0] - residual[0][0], ey = 2 * residual[1][1] - residual[0][1];
  const double extrapolated_error = std::hypot(ex - ux, ey - uy);
  std::printf("sliding: topple (%.6f, %.6f) m; reference h = 1 ms (%.6f, %.6f), 0.5 ms (%.6f, %.6f); error ratio "
              "%.3f; extrapolated (%.6f, %.6f), error %.2e m (%.3f %%)\n",
              ux, uy, residual[0][0], residual[0][1], residual[1][0], residual[1][1], error[0] / error[1], ex, ey,
              extrapolated_error, 100 * extrapolated_error / u);
  EXPECT_GE(error[0] / error[1], 1.6);
  EXPECT_LE(error[0] / error[1], 2.4);
  EXPECT_LE(extrapolated_error, 0.01 * u);
}

// (3) A box 0.2 x 0.12 x 0.8 m under a constant load along its base diagonal pivots on the far corner; the onset
// is the corner's static threshold A / g = d / c, d = sqrt(a^2 + b^2) the horizontal distance from the CM to the
// corner and c the CM height (the resultant of weight and inertial load leaves the base through the corner). The
// load is applied as a step at t = 0, so below the threshold a rigid box stays put and above it the pivot grows.
// Tolerances. Below (0.98 of the threshold): Moreau-Jean's velocity-level contact lets a gap drift O(h^2): measured
// 7.3e-5 m at h = 1 ms and 2.8e-6 m at h = 0.2 ms (the 25x of h^2); allowed 1e-5 m at 0.2 ms. Above (1.02): the
// three other corners rise by more than 5e-4 m in 0.4 s (measured 0.6-2.4 mm), the pivot corner by less than 1e-6 m,
// and the tilt points along the diagonal within 2 deg (measured 0.6 deg: the corner's inertia tensor is not
// isotropic, so the tilt axis leans slightly off the perpendicular to the diagonal). The edge threshold a / c (0.25)
// lies below the corner one (0.29) here, so a load along the diagonal at 1.02 x the edge threshold must not lift:
// the onset is the corner's, not the edge's. The same with a vertical ground acceleration (g -> g + a_v).
TEST(SiconosReference, ALoadAlongTheDiagonalPivotsOnACornerAtTheCornersStaticThreshold) {
  const double a = 0.1, b = 0.06, c = 0.4;
  const double d = std::hypot(a, b);
  const double corner_threshold = d / c;  // A / g
  auto run = [&](double ratio, double vertical_g = 0.0) {
    const double A = ratio * kG;
    const double dt = 0.005;
    // Ground acceleration toward -diagonal: the inertial load pushes the box toward the +x+y corner.
    std::vector<double> ax(101, -A * a / d), ay(101, -A * b / d), az(101, vertical_g * kG);
    SiconosOptions options;
    options.step_s = 2e-4;
    options.duration_s = 0.4;
    return simulate_siconos_box(SiconosBox{a, b, c, 1.0, 0.0, 10.0}, SiconosGroundMotion{dt, ax, ay, az}, options);
  };
  const auto below = run(0.98 * corner_threshold);
  const auto above = run(1.02 * corner_threshold);
  const auto edge = run(1.02 * a / c);
  const auto max_lift = [](const SiconosResult& r) {
    return *std::max_element(r.max_corner_z_m.begin(), r.max_corner_z_m.end());
  };
  const double direction_deg = std::atan2(above.max_tilt_axis[1], above.max_tilt_axis[0]) * 180 / std::numbers::pi;
  const double diagonal_deg = std::atan2(b, a) * 180 / std::numbers::pi;
  std::printf("corner: threshold A/g = %.4f; max lift at 0.98x %.2e m, at 1.02x %.2e m (pivot corner %.1e m, tilt "
              "toward %.2f deg, diagonal %.2f deg); at 1.02x the edge threshold %.2e m\n",
              corner_threshold, max_lift(below), max_lift(above), above.max_corner_z_m[0], direction_deg,
              diagonal_deg, max_lift(edge));
  EXPECT_LT(max_lift(below), 1e-5);
  EXPECT_LT(max_lift(edge), 1e-5);
  EXPECT_LT(above.max_corner_z_m[0], 1e-6);  // the +x+y corner: the pivot
  for (std::size_t i = 1; i < 4; ++i) EXPECT_GT(above.max_corner_z_m[i], 5e-4) << "corner " << i;
  EXPECT_NEAR(direction_deg, diagonal_deg, 2.0);
  EXPECT_FALSE(above.overturned);
  for (const auto& r : {below, above, edge}) EXPECT_TRUE(r.unconverged_step_times_s.empty());

  // With a vertical ground acceleration a_v (up) the effective gravity is g + a_v and the threshold A = (g + a_v)
  // d / c: under a_v = -0.3 g the box lifts at 1.02 x 0.7 of the static threshold and not at 0.98 x 0.7.
  const auto below_v = run(0.98 * 0.7 * corner_threshold, -0.3);
  const auto above_v = run(1.02 * 0.7 * corner_threshold, -0.3);
  std::printf("corner with a_v = -0.3 g: max lift at 0.98x %.2e m, at 1.02x %.2e m\n", max_lift(below_v),
              max_lift(above_v));
  EXPECT_LT(max_lift(below_v), 1e-5);
  EXPECT_GT(max_lift(above_v), 5e-4);
  EXPECT_LT(above_v.max_corner_z_m[0], 1e-6);
}

}  // namespace
