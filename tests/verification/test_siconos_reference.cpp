// The independent check of issue 29 ("Bodies in three dimensions"): a Siconos simulation of a box on a rigid plane
// (tests/support/siconos_rigid3d.hpp: Moreau-Jean time stepping, 4 base corners, Newton impact, Coulomb friction)
// against topple's trusted planar engines and a closed form. docs/verification.md, "Independent check: Siconos",
// gives the numbers. Moreau-Jean is first order at events (an impact or a stick-slip change is resolved at the end
// of the step that contains it), so each tolerance below is stated in terms of the step h and checked to shrink
// with h: these tests say the reference converges to topple's answer, not merely that it is close at one h.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <numbers>
#include <vector>

#include <gtest/gtest.h>

#include "support/siconos_rigid3d.hpp"
#include "topple/bodies/rocking_body.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rigid3d.hpp"
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


// ---------------------------------------------------------------------------------------------------------------
// (4)-(6) topple's three-dimensional engine (rigid3d.hpp) against the reference, where the planar engine cannot
// follow: a corner pivot, a load that turns in plan, an oblique overturn.
//
// Impact laws. rock3d's impact (rigid3d.hpp, docs/method.md "Impact law") is perfectly plastic and sticking, a small
// linear complementarity problem over the corners down at the instant: the contacts that carry an impulse end at
// rest, every other corner down moves up or stays, every vertical impulse is >= 0. Moreau-Jean with Newton's e = 0
// at the corners and mu = 10 solves the same conditions, at the end of each step, over the corners whose gap closes
// within it. So the two agree after impacts too, with two provisos the tests below measure: impacts closer in time
// than the reference's step are one impact to it (rock3d joins the corners within simultaneous_contact = 1e-5 of the
// size of the ground, a base within ~1e-5 rad of flat: one impact as well), and the reference's positions drift
// O(h) at each impact, so its whole-run numbers converge to rock3d's as h halves.

/// The body's z axis in the ground frame, R(q) e_z, of a unit quaternion (w, x, y, z).
std::array<double, 3> z_axis_of(const std::array<double, 4>& q) {
  return {2.0 * (q[1] * q[3] + q[0] * q[2]), 2.0 * (q[2] * q[3] - q[0] * q[1]),
          1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2])};
}

double tilt_of(const std::array<double, 4>& q) { return std::acos(std::clamp(z_axis_of(q)[2], -1.0, 1.0)); }

/// Azimuth clockwise from north of a plan direction (east, north), degrees in (-180, 180].
double azimuth_deg_of(double east, double north) { return std::atan2(east, north) * 180.0 / std::numbers::pi; }

/// Height of base vertex (vx, vy) of rock3d's body (its frame's origin at the base) in history row i: p_z + (R v)_z.
double rigid3d_vertex_z(const topple::Rigid3DHistory& h, std::size_t i, double vx, double vy) {
  const auto& q = h.orientation[i];
  return h.position_m[i][2] + 2.0 * (q[1] * q[3] - q[0] * q[2]) * vx + 2.0 * (q[2] * q[3] + q[0] * q[1]) * vy;
}

/// rock3d's history at t, linear between its rows (every sample of the 1 ms record and every event): the body's z
/// axis and the heights of the base corners in the reference's order (+x+y, -x+y, -x-y, +x-y).
struct Rigid3DState {
  std::array<double, 3> z_axis{};
  std::array<double, 4> corner_z_m{};
};
Rigid3DState rigid3d_state_at(const topple::Rigid3DResult& r, double t, double a, double b) {
  const auto& h = r.history;
  auto it = std::upper_bound(h.time_s.begin(), h.time_s.end(), t);
  std::size_t j = it == h.time_s.end() ? h.time_s.size() - 1 : static_cast<std::size_t>(it - h.time_s.begin());
  j = std::max<std::size_t>(j, 1);
  const double f = std::clamp((t - h.time_s[j - 1]) / (h.time_s[j] - h.time_s[j - 1]), 0.0, 1.0);
  Rigid3DState s;
  const auto z0 = z_axis_of(h.orientation[j - 1]), z1 = z_axis_of(h.orientation[j]);
  for (std::size_t k = 0; k < 3; ++k) s.z_axis[k] = (1 - f) * z0[k] + f * z1[k];
  const std::array<std::array<double, 2>, 4> corners{{{a, b}, {-a, b}, {-a, -b}, {a, -b}}};
  for (std::size_t k = 0; k < 4; ++k)
    s.corner_z_m[k] = (1 - f) * rigid3d_vertex_z(h, j - 1, corners[k][0], corners[k][1]) +
                      f * rigid3d_vertex_z(h, j, corners[k][0], corners[k][1]);
  return s;
}

/// Time of rock3d's first impact: the first mode change after the uplift that is not rocking -> pivot (that one is
/// a contact force vanishing at an end of the edge, no impact); +inf when none.
double first_impact_time(const topple::Rigid3DSummary& s) {
  for (std::size_t i = 2; i < s.modes.size(); ++i) {
    const auto prev = s.modes[i - 1].mode, cur = s.modes[i].mode;
    if (prev == topple::Rigid3DMode::rest) continue;
    if (prev == topple::Rigid3DMode::rocking && cur == topple::Rigid3DMode::pivot) continue;
    if (cur == topple::Rigid3DMode::fallen) continue;
    return s.modes[i].time_s;
  }
  return std::numeric_limits<double>::infinity();
}

/// Largest |angular velocity| in rock3d's history before t_end (rad/s).
double max_rate(const topple::Rigid3DResult& r, double t_end) {
  double w = 0.0;
  for (std::size_t i = 0; i < r.history.time_s.size() && r.history.time_s[i] <= t_end; ++i) {
    const auto& v = r.history.angular_velocity_rad_s[i];
    w = std::max(w, std::hypot(v[0], v[1], v[2]));
  }
  return w;
}

constexpr double kLift_m = 1e-4;  // a corner "has left the ground" above this height (both simulations alike)

struct Comparison3D {
  SiconosResult reference;
  topple::Rigid3DResult engine;
  double compare_until_s = 0.0;  ///< rock3d's first impact (or the end), less 2 h
  /// max over the reference's steps before compare_until_s of |z_ref - z_rock3d| (the body's z axis: the tilt and
  /// its direction at once), and of the corner heights' differences
  double axis_error = 0.0;
  double corner_error_m = 0.0;
  double bound_axis = 0.0;       ///< 2 max|w| h: a time shift of h at the uplift, twice
  /// per corner (reference order), the first time above kLift_m before compare_until_s (-1: never)
  std::array<double, 4> lift_time_ref{-1, -1, -1, -1}, lift_time_engine{-1, -1, -1, -1};
  /// the largest tilt before compare_until_s, its azimuth (deg from north) and time, in each
  double max_tilt_ref = 0.0, max_tilt_engine = 0.0, az_ref = 0.0, az_engine = 0.0, t_ref = 0.0, t_engine = 0.0;
};

/// Both simulations of the box (half-widths a, b, c) under the record (ax, ay) sampled every dt, for total_s.
/// The comparison runs to rock3d's first impact, its first loss of vertical contact force (flight, which rock3d does
/// not model) or its fall, less 2 h; or to `until_s` when given.
Comparison3D compare_3d(double a, double b, double c, const std::vector<double>& ax, const std::vector<double>& ay,
                        double dt, double total_s, double step_s, double until_s = -1.0) {
  Comparison3D out;
  SiconosOptions options;
  options.step_s = step_s;
  options.duration_s = total_s;
  out.reference = simulate_siconos_box(SiconosBox{a, b, c, 1.0, 0.0, 10.0}, SiconosGroundMotion{dt, ax, ay, {}},
                                       options);
  topple::Rigid3DOptions o;  // Housner's law generalised (the default)
  o.g_m_s2 = kG;
  o.record_history = true;
  o.max_run_out_s = std::max(0.0, total_s - dt * static_cast<double>(ax.size() - 1));
  const auto mx = GroundMotion::uniform(ax, dt);
  const auto my = GroundMotion::uniform(ay, dt);
  out.engine = topple::rock3d(mx, &my, nullptr, topple::RigidBody3D::box(2 * a, 2 * b, 2 * c), o);
  const auto& s = out.engine.summary;
  out.compare_until_s = std::min({first_impact_time(s), s.flight_time_s.value_or(s.end_time_s),
                                  s.overturn_time_s.value_or(s.end_time_s)}) - 2 * step_s;
  if (until_s > 0.0) out.compare_until_s = until_s - 2 * step_s;
  const auto& hist = out.reference.history;
  for (std::size_t i = 0; i < hist.time_s.size() && hist.time_s[i] < out.compare_until_s; ++i) {
    const double t = hist.time_s[i];
    const auto e = rigid3d_state_at(out.engine, t, a, b);
    const auto zr = z_axis_of(hist.quaternion[i]);
    out.axis_error = std::max(out.axis_error, std::hypot(zr[0] - e.z_axis[0], zr[1] - e.z_axis[1],
                                                         zr[2] - e.z_axis[2]));
    for (std::size_t k = 0; k < 4; ++k) {
      out.corner_error_m = std::max(out.corner_error_m, std::abs(hist.corner_z_m[i][k] - e.corner_z_m[k]));
      if (out.lift_time_ref[k] < 0 && hist.corner_z_m[i][k] > kLift_m) out.lift_time_ref[k] = t;
    }
    const double tilt_ref = hist.tilt_rad[i];
    if (tilt_ref > out.max_tilt_ref) {
      out.max_tilt_ref = tilt_ref;
      out.az_ref = azimuth_deg_of(zr[0], zr[1]);
      out.t_ref = t;
    }
  }
  const auto& h = out.engine.history;
  for (std::size_t i = 0; i < h.time_s.size() && h.time_s[i] < out.compare_until_s; ++i) {
    const auto z = z_axis_of(h.orientation[i]);
    const double tilt = std::acos(std::clamp(z[2], -1.0, 1.0));
    if (tilt > out.max_tilt_engine) {
      out.max_tilt_engine = tilt;
      out.az_engine = azimuth_deg_of(z[0], z[1]);
      out.t_engine = h.time_s[i];
    }
    // lift times located on the history rows (1 ms apart: a resolution of 1 ms, as the reference's steps)
    const std::array<std::array<double, 2>, 4> corners{{{a, b}, {-a, b}, {-a, -b}, {a, -b}}};
    for (std::size_t k = 0; k < 4; ++k)
      if (out.lift_time_engine[k] < 0 && rigid3d_vertex_z(h, i, corners[k][0], corners[k][1]) > kLift_m)
        out.lift_time_engine[k] = h.time_s[i];
  }
  out.bound_axis = 2.0 * max_rate(out.engine, out.compare_until_s) * step_s;
  return out;
}

std::string modes_text(const topple::Rigid3DSummary& s) {
  std::string text;
  for (const auto& m : s.modes) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " %.4f:%s(%d,%d)", m.time_s, std::string(topple::rigid3d_mode_name(m.mode)).c_str(),
                  m.vertex_a, m.vertex_b);
    text += buf;
  }
  return text;
}

void print_comparison(const char* name, double h, const Comparison3D& r) {
  const auto& s = r.engine.summary;
  std::printf("%s, h = %g: compared to %.4f s (rock3d's first impact or fall, less 2 h): axis error %.2e (bound 2 "
              "max|w| h = %.2e), corner heights %.2e m; max tilt %.6f rad toward %.2f deg at %.4f s (rock3d %.6f "
              "toward %.2f deg at %.4f s); lift times (+x+y, -x+y, -x-y, +x-y) reference %.3f %.3f %.3f %.3f, rock3d "
              "%.3f %.3f %.3f %.3f; %zu unconverged; rock3d: %zu impacts, flight %.4f\n  whole run: reference max "
              "tilt %.6f toward %.2f deg at %.4f s, rock3d %.6f toward %.2f deg at %.4f s; modes:%s\n",
              name, h, r.compare_until_s, r.axis_error, r.bound_axis, r.corner_error_m, r.max_tilt_ref, r.az_ref,
              r.t_ref, r.max_tilt_engine, r.az_engine, r.t_engine, r.lift_time_ref[0], r.lift_time_ref[1],
              r.lift_time_ref[2], r.lift_time_ref[3], r.lift_time_engine[0], r.lift_time_engine[1],
              r.lift_time_engine[2], r.lift_time_engine[3], r.reference.unconverged_step_times_s.size(), s.impacts,
              s.flight_time_s.value_or(-1), r.reference.max_tilt_rad,
              azimuth_deg_of(r.reference.max_tilt_axis[0], r.reference.max_tilt_axis[1]), r.reference.max_tilt_time_s,
              s.max_tilt_rad, s.max_tilt_azimuth_deg, s.max_tilt_time_s, modes_text(s).c_str());
}

/// A change of the corner the box pivots on: the corner (the reference's order: +x+y, -x+y, -x-y, +x-y) and when the
/// impact that made it happened.
struct PivotChange {
  int corner = -1;
  double time_s = 0.0;
};

/// The reference's pivots over the whole run: a corner is down below kDown_m (its positions drift O(h^2) per step
/// into the ground; a lifted corner is far above); each time exactly one corner is down and it is not the last
/// pivot, a change, timed when that corner came down (the impact's step).
std::vector<PivotChange> reference_pivots(const SiconosResult& r) {
  constexpr double kDown_m = 1e-5;
  std::vector<PivotChange> out;
  std::array<double, 4> down_since{0.0, 0.0, 0.0, 0.0};
  std::array<bool, 4> was_down{true, true, true, true};
  const auto& h = r.history;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    int count = 0, only = -1;
    for (int k = 0; k < 4; ++k) {
      const bool down = h.corner_z_m[i][static_cast<std::size_t>(k)] < kDown_m;
      if (down && !was_down[static_cast<std::size_t>(k)]) down_since[static_cast<std::size_t>(k)] = h.time_s[i];
      was_down[static_cast<std::size_t>(k)] = down;
      if (down) {
        ++count;
        only = k;
      }
    }
    if (count == 1 && (out.empty() || out.back().corner != only))
      out.push_back({only, down_since[static_cast<std::size_t>(only)]});
  }
  return out;
}

/// rock3d's pivots: each pivot mode on a corner other than the last (box vertices (-a,-b), (a,-b), (a,b), (-a,b) are
/// the reference's corners 2, 3, 0, 1), timed at the mode's start (the impact, or the uplift for the first).
std::vector<PivotChange> rigid3d_pivots(const topple::Rigid3DSummary& s) {
  constexpr std::array<int, 4> kCorner{2, 3, 0, 1};
  std::vector<PivotChange> out;
  for (const auto& m : s.modes)
    if (m.mode == topple::Rigid3DMode::pivot && (out.empty() || out.back().corner != kCorner[static_cast<std::size_t>(m.vertex_a)]))
      out.push_back({kCorner[static_cast<std::size_t>(m.vertex_a)], m.time_s});
  return out;
}

/// The whole run compared: the max tilt, its direction and time, and the pivots (the corners in order, and the
/// largest difference of the change times before until_s, the first change, an uplift, excluded).
struct WholeRun {
  double tilt_error = 0.0, azimuth_error_deg = 0.0, time_error_s = 0.0, change_time_error_s = 0.0;
  bool same_pivots = false;
  std::size_t changes = 0;
};
WholeRun compare_whole_run(const Comparison3D& r, double until_s) {
  WholeRun w;
  const auto& s = r.engine.summary;
  w.tilt_error = std::abs(r.reference.max_tilt_rad - s.max_tilt_rad);
  const double az_ref = azimuth_deg_of(r.reference.max_tilt_axis[0], r.reference.max_tilt_axis[1]);
  w.azimuth_error_deg = std::abs(std::remainder(az_ref - s.max_tilt_azimuth_deg, 360.0));
  w.time_error_s = std::abs(r.reference.max_tilt_time_s - s.max_tilt_time_s);
  const auto ref = reference_pivots(r.reference);
  const auto eng = rigid3d_pivots(s);
  w.same_pivots = ref.size() == eng.size();
  for (std::size_t i = 0; w.same_pivots && i < ref.size(); ++i) {
    w.same_pivots = ref[i].corner == eng[i].corner;
    if (i > 0 && eng[i].time_s < until_s)
      w.change_time_error_s = std::max(w.change_time_error_s, std::abs(ref[i].time_s - eng[i].time_s));
  }
  w.changes = eng.empty() ? 0 : eng.size() - 1;
  std::string text;
  for (std::size_t i = 0; i < std::max(ref.size(), eng.size()); ++i) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " [%d %.4f | %d %.4f]", i < ref.size() ? ref[i].corner : -1,
                  i < ref.size() ? ref[i].time_s : -1.0, i < eng.size() ? eng[i].corner : -1,
                  i < eng.size() ? eng[i].time_s : -1.0);
    text += buf;
  }
  std::printf("  whole run: max tilt error %.2e rad (%.3f %%), direction %.3f deg, time %.4f s; pivots (reference | "
              "rock3d)%s; %s, change times to %.1f s within %.4f s\n", w.tilt_error,
              100 * w.tilt_error / s.max_tilt_rad, w.azimuth_error_deg, w.time_error_s, text.c_str(),
              w.same_pivots ? "the same corners" : "DIFFERENT corners", until_s, w.change_time_error_s);
  return w;
}

// (4) A box 0.2 x 0.12 x 0.8 m (as in (3)) under one sine cycle along its base diagonal, 0.45 g (1.5 x the corner's
// threshold d / c = 0.29), 0.3 s: it pivots on the +x+y corner (rock3d: pivot from 0.0337 s; the other three corners
// leave the ground in both at 0.063-0.081 s, within 1 ms) and rocks back.
// Then the box comes back down nearly flat at 0.2118 s: the -x+y corner touches, the -x-y corner 17 us later,
// +x-y a few us after that. rock3d joins the corners within simultaneous_contact (1e-5 of the size: here 4 um) of
// the ground, so it lands flat, one impact over all four corners, and pivots on the far corner -x-y; Moreau-Jean at
// any step above ~10 us does the same (the landings fall in one step). Before the impact law's fix rock3d took two
// successive impacts (an edge, then the opposite edge: max tilt 0.048 rad toward 180 deg against the reference's
// 0.077 toward -121). The whole run (2 s, 12 impacts) is then compared: the same corners pivoted on in the same
// order, and the max tilt 0.077023 rad toward -121.15 deg at 0.4297 s; the reference's error falls as h halves
// (measured 5.4e-4 -> 8.1e-5 rad, 0.70 % -> 0.11 %; the times of the pivots' changes before 1 s 6.3 -> 3.3 ms),
// allowed 0.2 % at 0.5 ms, halving, the direction to 0.1 deg (measured 0.004), the time to 2 h. (With
// simultaneous_contact = 0 the impacts are successive and the reference agrees with that at h <= 5 us:
// DISABLED_Rigid3DSuccessiveImpactsAtMicrosecondSteps, figures in docs/verification.md.)
// Tolerances before the impact: the body's z axis (tilt and direction at once) within 2 max|w| h of rock3d's (an
// uplift shifted by up to h, as in (1a); measured 0.25x that bound at 1 ms, 0.26x at 0.5 ms), and the error must
// shrink as h halves (measured 2.25e-4 -> 1.22e-4); the pivot's largest tilt to 0.1 % at 0.5 ms (measured 0.01 %),
// its direction to 0.1 deg (measured < 0.01) and its time to 2 h.
TEST(SiconosReference, Rigid3DPivotOnACornerUnderADiagonalPulse) {
  const double a = 0.1, b = 0.06, c = 0.4, dt = 0.001;
  const double phi = std::atan2(b, a);
  const auto base = sine_pulse(0.45 * kG, 0.3, dt, 0.3);
  std::vector<double> ax, ay;
  for (const double v : base) {
    ax.push_back(-v * std::cos(phi));  // toward -diagonal: the inertial load pushes toward the +x+y corner
    ay.push_back(-v * std::sin(phi));
  }
  double previous_error = 0.0, max_tilt = 0.0;
  std::array<WholeRun, 2> whole{};
  for (const double h : {1e-3, 5e-4}) {
    const auto r = compare_3d(a, b, c, ax, ay, dt, 2.0, h);
    print_comparison("diagonal pulse", h, r);
    for (const double t : r.reference.unconverged_step_times_s) std::printf("  unconverged step at %.4f s\n", t);
    const auto& modes = r.engine.summary.modes;
    ASSERT_GE(modes.size(), 3u);
    EXPECT_EQ(modes[1].mode, topple::Rigid3DMode::pivot);
    EXPECT_EQ(modes[1].vertex_a, 2);  // (+a, +b)
    EXPECT_GT(r.compare_until_s, 0.2);  // the comparison covers the pivot and its return
    EXPECT_LE(r.axis_error, r.bound_axis) << "h = " << h;
    // the pivot corner stays down, the three others rise, in both, at the same times within 2 h
    EXPECT_LT(r.lift_time_ref[0], 0.0);
    EXPECT_LT(r.lift_time_engine[0], 0.0);
    for (std::size_t k = 1; k < 4; ++k) {
      ASSERT_GT(r.lift_time_ref[k], 0.0) << k;
      EXPECT_NEAR(r.lift_time_ref[k], r.lift_time_engine[k], 2 * h + 1e-9) << "corner " << k;
    }
    EXPECT_NEAR(r.az_ref, r.az_engine, 0.1);
    EXPECT_NEAR(r.t_ref, r.t_engine, 2 * h + 1e-9);
    if (h < 1e-3) {
      EXPECT_NEAR(r.max_tilt_ref, r.max_tilt_engine, 1e-3 * r.max_tilt_engine);
      EXPECT_LT(r.axis_error, 0.75 * previous_error) << "the error must shrink as the step halves";
    }
    // NSGS leaves at most the step of the uplift unconverged (measured: none at 1 ms, the step ending at 0.0340 s at
    // 0.5 ms, rock3d's uplift at 0.0337 s); the bound above holds through it.
    EXPECT_LE(std::count_if(r.reference.unconverged_step_times_s.begin(), r.reference.unconverged_step_times_s.end(),
                            [&](double t) { return t < r.compare_until_s; }), 1);
    previous_error = r.axis_error;
    // after the impacts: the whole run
    const WholeRun w = compare_whole_run(r, 1.0);
    whole[h < 1e-3 ? 1 : 0] = w;
    EXPECT_FALSE(r.engine.summary.overturned);
    EXPECT_FALSE(r.reference.overturned);
    EXPECT_TRUE(w.same_pivots) << "h = " << h;
    EXPECT_GE(w.changes, 10u);  // the comparison runs through many impacts
    EXPECT_LE(w.azimuth_error_deg, 0.1) << "h = " << h;
    EXPECT_LE(w.time_error_s, 2 * h + 1e-9) << "h = " << h;
    max_tilt = r.engine.summary.max_tilt_rad;
  }
  EXPECT_LE(whole[1].tilt_error, 2e-3 * max_tilt);
  EXPECT_LT(whole[1].tilt_error, 0.5 * whole[0].tilt_error) << "the error must fall as the step halves";
  EXPECT_LT(whole[1].change_time_error_s, 0.75 * whole[0].change_time_error_s) << "the error must fall as h halves";
}

// (4b) A measurement, not run by default (minutes: ~10^5 reference steps each; --gtest_also_run_disabled_tests):
// the landing of (4) with successive impacts (simultaneous_contact = 0: -x+y alone, pivot on it, then -x-y 17 us
// later) against the reference at steps below that gap, where Moreau-Jean resolves the landings one by one too.
// Measured (docs/verification.md): rock3d 0.083091 rad toward 232.34 deg (-127.66) at 0.4400 s; the reference
// 0.083086 and 0.083094 rad toward -127.66 deg at 0.4400 s at h = 5 and 2.5 us (0.077023 toward -121.15, the
// simultaneous landing, at h >= 10 us). Allowed 0.05 % on the tilt, 0.1 deg, 2 ms (the records' sample: the max tilt
// falls on a 1 ms row in rock3d's history).
TEST(SiconosReference, DISABLED_Rigid3DSuccessiveImpactsAtMicrosecondSteps) {
  const double a = 0.1, b = 0.06, c = 0.4, dt = 0.001;
  const double phi = std::atan2(b, a);
  const auto base = sine_pulse(0.45 * kG, 0.3, dt, 0.3);
  std::vector<double> ax, ay;
  for (const double v : base) {
    ax.push_back(-v * std::cos(phi));
    ay.push_back(-v * std::sin(phi));
  }
  topple::Rigid3DOptions o;
  o.g_m_s2 = kG;
  o.simultaneous_contact = 0.0;
  o.max_run_out_s = 0.2;
  const auto mx = GroundMotion::uniform(ax, dt);
  const auto my = GroundMotion::uniform(ay, dt);
  const auto s = topple::rock3d(mx, &my, nullptr, topple::RigidBody3D::box(2 * a, 2 * b, 2 * c), o).summary;
  std::printf("successive impacts: rock3d max tilt %.6f rad toward %.2f deg at %.4f s;%s\n", s.max_tilt_rad,
              s.max_tilt_azimuth_deg, s.max_tilt_time_s, modes_text(s).c_str());
  for (const double h : {5e-6, 2.5e-6}) {
    SiconosOptions options;
    options.step_s = h;
    options.duration_s = 0.5;
    const auto r = simulate_siconos_box(SiconosBox{a, b, c, 1.0, 0.0, 10.0}, SiconosGroundMotion{dt, ax, ay, {}},
                                        options);
    const double az = azimuth_deg_of(r.max_tilt_axis[0], r.max_tilt_axis[1]);
    std::printf("  reference h = %g: max tilt %.6f rad toward %.2f deg at %.4f s\n", h, r.max_tilt_rad, az,
                r.max_tilt_time_s);
    EXPECT_NEAR(r.max_tilt_rad, s.max_tilt_rad, 5e-4 * s.max_tilt_rad) << "h = " << h;
    EXPECT_NEAR(std::remainder(az - s.max_tilt_azimuth_deg, 360.0), 0.0, 0.1) << "h = " << h;
    EXPECT_NEAR(r.max_tilt_time_s, s.max_tilt_time_s, 0.002) << "h = " << h;
  }
}

// (5) Two horizontal components turning in plan: a = A w(t) (cos 2 pi t / T, sin 2 pi t / T), w = sin^2(pi t / D) a
// smooth window of D = 0.8 s, T = 0.4 s, A = 0.5 g, on the same box: as the load turns the box lifts on its +x edge
// (rock3d: rocking about (+x-y, +x+y) from 0.2000 s), then the load's turn moves it onto the +x+y corner (pivot from
// 0.2320 s: the +x-y corner leaves the ground at 0.275-0.276 s in both) until the -x+y corner lands (0.3089 s).
// Compared up to that first impact, with the tolerances of (4) (measured 0.06x and 0.07x the bound, 6.6e-5 ->
// 3.9e-5 as h halves; every corner's lift-off within 1 ms).
// After it: the -x+y corner lands next to the pivot +x+y, and the impact law (the impulse at the new corner only,
// the old one's velocity after it >= 0) pivots the box on -x+y, the old pivot lifting at once: above 0.1 mm at
// 0.315 s in both (before the fix rock3d took an edge impact there, the old pivot down until 0.362 s, and the z axes
// differed by 0.034 rad at 0.62 s at both steps). The whole run (2.5 s, 9 impacts): the same corners in the same
// order, the max tilt 0.125452 rad toward 157.29 deg at 0.9448 s; the reference's error falls as h halves (measured
// 6.1e-4 -> 1.1e-4 rad, 0.49 % -> 0.085 %; the pivots' change times before 1 s 1.0 -> 0.4 ms), allowed 0.2 % at
// 0.5 ms, halving; the direction within 0.5 deg (measured 0.23 and 0.27 deg: not yet falling at these steps, 0.03
// deg at 62.5 us, docs/verification.md), the time to 2 h.
TEST(SiconosReference, Rigid3DRotatingLoadPivotsAndChangesContact) {
  const double a = 0.1, b = 0.06, c = 0.4, dt = 0.001, A = 0.5 * kG, T = 0.4, D = 0.8;
  std::vector<double> ax, ay;
  for (int i = 0; i <= static_cast<int>(std::lround(D / dt)); ++i) {
    const double t = i * dt;
    const double w = std::pow(std::sin(std::numbers::pi * t / D), 2);
    ax.push_back(A * w * std::cos(2 * std::numbers::pi * t / T));
    ay.push_back(A * w * std::sin(2 * std::numbers::pi * t / T));
  }
  double previous_error = 0.0, max_tilt = 0.0;
  std::array<WholeRun, 2> whole{};
  for (const double h : {1e-3, 5e-4}) {
    const auto r = compare_3d(a, b, c, ax, ay, dt, 2.5, h);
    print_comparison("rotating load", h, r);
    const auto& modes = r.engine.summary.modes;
    ASSERT_GE(modes.size(), 4u);
    EXPECT_EQ(modes[1].mode, topple::Rigid3DMode::rocking);  // the +x edge
    EXPECT_EQ(modes[2].mode, topple::Rigid3DMode::pivot);    // then its +x+y end
    EXPECT_EQ(modes[2].vertex_a, 2);
    EXPECT_GT(r.compare_until_s, modes[2].time_s + 0.05);   // the comparison covers the change of contact
    EXPECT_LE(r.axis_error, r.bound_axis) << "h = " << h;
    EXPECT_LT(r.lift_time_ref[0], 0.0);  // +x+y: the corner it ends pivoting on
    for (std::size_t k = 1; k < 4; ++k) {
      ASSERT_GT(r.lift_time_ref[k], 0.0) << k;
      EXPECT_NEAR(r.lift_time_ref[k], r.lift_time_engine[k], 2 * h + 1e-9) << "corner " << k;
    }
    // the +x-y corner leaves after the pivot began: the change of contact is in the reference too
    EXPECT_GT(r.lift_time_ref[3], modes[2].time_s);
    if (h < 1e-3) {
      EXPECT_LT(r.axis_error, 0.75 * previous_error) << "the error must shrink as the step halves";
    }
    EXPECT_TRUE(r.reference.unconverged_step_times_s.empty());
    previous_error = r.axis_error;
    // after the impacts: the whole run
    const WholeRun w = compare_whole_run(r, 1.0);
    whole[h < 1e-3 ? 1 : 0] = w;
    EXPECT_FALSE(r.engine.summary.overturned);
    EXPECT_FALSE(r.reference.overturned);
    EXPECT_TRUE(w.same_pivots) << "h = " << h;
    EXPECT_GE(w.changes, 8u);  // the comparison runs through many impacts
    EXPECT_LE(w.azimuth_error_deg, 0.5) << "h = " << h;
    EXPECT_LE(w.time_error_s, 2 * h + 1e-9) << "h = " << h;
    // The old pivot +x+y lifts at once after the -x+y corner lands next to it (the impulse at the new corner only;
    // before this fix rock3d kept it down, an edge impact, until 0.362 s): above kLift_m within 2 h of each other.
    ASSERT_GE(modes.size(), 5u);
    ASSERT_EQ(modes[3].mode, topple::Rigid3DMode::pivot);
    EXPECT_EQ(modes[3].vertex_a, 3);  // (-a, +b): the new corner
    const double t_land = modes[3].time_s;
    double lift_ref = -1.0, lift_engine = -1.0;
    const auto& rh = r.reference.history;
    for (std::size_t i = 0; i < rh.time_s.size() && lift_ref < 0; ++i)
      if (rh.time_s[i] > t_land && rh.corner_z_m[i][0] > kLift_m) lift_ref = rh.time_s[i];
    const auto& eh = r.engine.history;
    for (std::size_t i = 0; i < eh.time_s.size() && lift_engine < 0; ++i)
      if (eh.time_s[i] > t_land && rigid3d_vertex_z(eh, i, a, b) > kLift_m) lift_engine = eh.time_s[i];
    std::printf("  the old pivot +x+y above %.0e m after the landing at %.4f s: reference %.4f s, rock3d %.4f s\n",
                kLift_m, t_land, lift_ref, lift_engine);
    ASSERT_GT(lift_ref, 0.0);
    EXPECT_NEAR(lift_engine, lift_ref, 2 * h + 1e-9);
    max_tilt = r.engine.summary.max_tilt_rad;
  }
  EXPECT_LE(whole[1].tilt_error, 2e-3 * max_tilt);
  EXPECT_LT(whole[1].tilt_error, 0.5 * whole[0].tilt_error) << "the error must fall as the step halves";
  EXPECT_LT(whole[1].change_time_error_s, 0.75 * whole[0].change_time_error_s) << "the error must fall as h halves";
}

// (6) A large oblique pulse overturns the box: one half-sine of 1.0 g, 0.5 s, pushing it toward azimuth 60 deg (30
// deg off its x axis). rock3d: rocking about the +x edge at 0.0466 s, pivot on the +x+y corner at 0.0486 s, the
// vertical contact force vanishes at 0.4243 s (rock3d keeps the contact and its corner fixed: a stated limit,
// rigid3d.hpp), falls at 0.5900 s toward 56.79 deg.
// Tolerances. Up to that instant: the z axis as in (4) (measured 0.18x the bound, 1.64e-3 -> 8.26e-4 as h halves).
// The vanishing force is real in the reference: its pivot corner, fixed until then, never rises (< 1e-6 m) but its
// friction force vanishes with the normal force and it slips (above 0.01 mm from 0.428 s at both steps, 4 cm by the
// fall), within 10 ms after rock3d's instant. After it the models differ (a slipping corner against a fixed one), so
// the fall is compared on the verdict and its direction: both overturn, the direction of the tilt when it reaches 80
// deg (the reference's overturn flag) agrees to 1 deg (measured 0.26 deg), and the time of 80 deg to 3 % (measured
// 10 ms on 0.57 s, 1.8 %, the same at both steps: the slip, not the step).
TEST(SiconosReference, Rigid3DOverturnVerdictAndAzimuthUnderAnObliquePulse) {
  const double a = 0.1, b = 0.06, c = 0.4, dt = 0.001, A = 1.0 * kG, T = 0.5;
  const double phi = 30.0 * std::numbers::pi / 180.0;
  std::vector<double> ax, ay;
  for (int i = 0; i <= static_cast<int>(std::lround(T / dt)); ++i) {
    const double v = A * std::sin(std::numbers::pi * i * dt / T);
    ax.push_back(-v * std::cos(phi));
    ay.push_back(-v * std::sin(phi));
  }
  double previous_error = 0.0;
  for (const double h : {1e-3, 5e-4}) {
    const auto r = compare_3d(a, b, c, ax, ay, dt, 2.5, h);
    print_comparison("oblique overturn", h, r);
    const auto& s = r.engine.summary;
    ASSERT_TRUE(s.overturned);
    ASSERT_TRUE(r.reference.overturned);
    ASSERT_TRUE(s.flight_time_s.has_value());
    EXPECT_GT(r.compare_until_s, 0.4);
    EXPECT_LE(r.axis_error, r.bound_axis) << "h = " << h;
    if (h < 1e-3) {
      EXPECT_LT(r.axis_error, 0.75 * previous_error) << "the error must shrink as the step halves";
    }
    previous_error = r.axis_error;
    // rock3d's time and direction at 80 deg (the reference's overturn flag)
    const auto& hist = r.engine.history;
    double t80 = -1, az80 = 0;
    const double level = 80.0 * std::numbers::pi / 180.0;
    for (std::size_t i = 1; i < hist.time_s.size(); ++i) {
      const double t0 = tilt_of(hist.orientation[i - 1]), t1 = tilt_of(hist.orientation[i]);
      if (t0 < level && t1 >= level) {
        t80 = hist.time_s[i - 1] + (level - t0) / (t1 - t0) * (hist.time_s[i] - hist.time_s[i - 1]);
        const auto z = z_axis_of(hist.orientation[i]);
        az80 = azimuth_deg_of(z[0], z[1]);
        break;
      }
    }
    // The reference's pivot corner (+x+y, body (a, b, -c) from the CM): its height and its horizontal slip from
    // (a, b) over the run.
    const auto& rh = r.reference.history;
    double corner_max_z = 0.0, slip_max = 0.0, slip_start = -1.0;
    for (std::size_t i = 0; i < rh.time_s.size(); ++i) {
      const auto& q = rh.quaternion[i];
      const double w = q[0], x = q[1], y = q[2], z = q[3];
      const std::array<std::array<double, 3>, 3> R{{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                                                    {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                                                    {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
      std::array<double, 3> p{};
      for (std::size_t k = 0; k < 3; ++k) p[k] = rh.position_m[i][k] + R[k][0] * a + R[k][1] * b - R[k][2] * c;
      const double slip = std::hypot(p[0] - a, p[1] - b);
      corner_max_z = std::max(corner_max_z, p[2]);
      slip_max = std::max(slip_max, slip);
      if (slip_start < 0 && slip > 1e-5) slip_start = rh.time_s[i];
    }
    const double ref_az = azimuth_deg_of(r.reference.max_tilt_axis[0], r.reference.max_tilt_axis[1]);
    std::printf("  contact force vanishes: rock3d %.4f s; the reference's pivot corner slips (> 0.01 mm) from %.4f s, "
                "%.4f m by the end, rises at most %.1e m; 80 deg: reference at %.4f s toward %.2f deg, rock3d at %.4f s "
                "toward %.2f deg (falls at %.4f s toward %.2f deg)\n",
                *s.flight_time_s, slip_start, slip_max, corner_max_z, r.reference.overturn_time_s.value_or(-1), ref_az, t80, az80,
                s.overturn_time_s.value_or(-1), s.overturn_azimuth_deg);
    EXPECT_LT(corner_max_z, 1e-6);
    EXPECT_GE(slip_start, *s.flight_time_s - 2 * h);
    EXPECT_LE(slip_start, *s.flight_time_s + 0.01);
    ASSERT_GT(t80, 0.0);
    EXPECT_NEAR(ref_az, az80, 1.0);
    EXPECT_NEAR(*r.reference.overturn_time_s, t80, 0.03 * t80);
    EXPECT_NEAR(s.overturn_azimuth_deg, 60.0, 5.0);  // toward the load's direction, leaning to the corner (59 deg)
  }
}

}  // namespace

// (6) Slide-rock in three dimensions with Coulomb friction (rigid3d_contact.cpp): a box 0.6 x 0.4 x 0.8 m, mu = 0.55
// (mu_s = mu_k: Siconos' Coulomb law has one coefficient), under an oblique load that turns (x, and y at 0.8 of it a
// radian ahead, 0.7 g, two 0.5 s cycles): it lifts about an edge and its contact slips while it rocks and pivots, so it
// slides and twists. The reference (Moreau-Jean, e = 0: plastic impacts) at h = 1 ms and 0.5 ms: the residual slide
// vector (error falling as h halves, within 5 %), the max tilt (2 %) and the verdict against topple's.
TEST(SiconosReference, ObliqueSlideRockWithFrictionSlidesAndTwistsAsTheReference) {
  const double dt = 0.004, period = 0.5, amp = 0.7 * kG;
  const auto n = static_cast<std::size_t>(std::lround(2.0 * period / dt)) + 1;
  std::vector<double> ax(n), ay(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    ax[i] = amp * std::sin(2.0 * std::numbers::pi * t / period);
    ay[i] = 0.8 * amp * std::sin(2.0 * std::numbers::pi * t / period + 1.0);
  }
  const double mu = 0.55;
  topple::Rigid3DOptions o;
  o.mu_s = mu;
  o.mu_k = mu;
  const GroundMotion gx = GroundMotion::uniform(ax, dt), gy = GroundMotion::uniform(ay, dt);
  const auto r = topple::rock3d(gx, &gy, nullptr, topple::RigidBody3D::box(0.6, 0.4, 0.8), o).summary;
  ASSERT_TRUE(r.slide_rock_time_s.has_value());
  ASSERT_LT(r.end_time_s, 2.4);
  const double ux = r.residual_slide_east_m, uy = r.residual_slide_north_m;
  const double yaw = r.residual_yaw_deg * std::numbers::pi / 180.0;
  std::array<double, 2> err_u{}, err_yaw{}, tilt{};
  const std::array<double, 2> steps{1e-3, 5e-4};
  for (std::size_t k = 0; k < 2; ++k) {
    SiconosOptions options;
    options.step_s = steps[k];
    options.duration_s = 2.5;
    const auto s = simulate_siconos_box(SiconosBox{0.3, 0.2, 0.4, 1.0, 0.0, mu}, SiconosGroundMotion{dt, ax, ay, {}},
                                        options);
    EXPECT_EQ(s.overturned, r.overturned);
    err_u[k] = std::hypot(s.final_displacement_m[0] - ux, s.final_displacement_m[1] - uy);
    err_yaw[k] = std::abs(s.final_yaw_rad - yaw);
    tilt[k] = s.max_tilt_rad;
    std::printf("slide-rock 3-D: h = %.1e: residual (%.6f, %.6f) m vs topple (%.6f, %.6f); yaw %.6f vs %.6f rad; "
                "max tilt %.5f vs %.5f rad\n",
                steps[k], s.final_displacement_m[0], s.final_displacement_m[1], ux, uy, s.final_yaw_rad, yaw,
                s.max_tilt_rad, r.max_tilt_rad);
  }
  const double u = std::hypot(ux, uy);
  ASSERT_GT(u, 1e-3);
  // Measured: residual error 1.0e-3 m (h = 1 ms), 7.1e-4 m (0.5 ms) of |u| = 16.3 mm (4.3 %); max tilt 2.38e-3 rad
  // against 2.37e-3 (0.4 %). The yaw is small in both (0.13 deg Siconos, 0.34 deg topple) and NOT within a tolerance:
  // a known difference (the twist hangs on how the friction is shared between the two ends of a sticking edge, which
  // topple sets by a stated rule and Moreau-Jean by its solver, and on the impact law), held only to its sign and
  // size here.
  EXPECT_LT(err_u[1], err_u[0]);
  EXPECT_LT(err_u[1], 0.05 * u);
  EXPECT_NEAR(tilt[1], r.max_tilt_rad, 0.02 * r.max_tilt_rad);
  (void)err_yaw;
  EXPECT_GT(yaw, 0.0);
  EXPECT_LT(yaw, 0.01);
}
