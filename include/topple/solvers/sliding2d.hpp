#pragma once
// Bidirectional sliding: a rigid block on level or inclined ground with isotropic Coulomb friction, driven by both horizontal
// components of the ground acceleration and, optionally, the vertical.
//
// Model. Frame: x east, y north, z up; azimuths in degrees clockwise from north (east = 90). The ground accelerates
// with a(t) = (a_x, a_y) horizontally and a_v(t) vertically (positive up); the effective gravity is
// g_e = g + a_v. u is the block's displacement relative to the ground (the physical direction it moved on its
// support; an observer on the ground sees the block go to u) and w = u' its relative velocity. Per unit mass:
//   stuck  (w = 0)   while |a(t)| <= mu_s g_e(t)                                             (static friction)
//   slip   (w != 0)  w' = -a(t) - mu_k g_e^+(t) w / |w|,   g_e^+ = max(g_e, 0)                (kinetic friction)
// Friction opposes the two-dimensional relative velocity with magnitude mu_k m g_e (isotropic Coulomb friction; the
// coupled two-component Newmark block of Kramer & Lindwall 2004, J. Geotech. Geoenviron. Eng. 130(3)). A block that
// leaves the ground (g_e < 0) carries no friction; contact_lost_time_s says when, as the 1-D solver does.
// Slip starts from rest in the direction of the inertial load -a (the limit of w / |w| as w -> 0). On one axis this
// is the 1-D two-way solver of sliding.hpp with d = -u . e, e the axis (sliding.hpp's d is positive where a positive
// a_h pushes the block, i.e. opposite to the component's axis): tested to 1e-9.
//
// Method (docs/method.md, "Bidirectional sliding"). Each component is piecewise linear between its samples (the
// components and the vertical are merged exactly on one grid, input_grid.hpp). Stuck: |a(t)| - mu_s g_e(t) is convex
// on a step (a norm of a linear function minus a linear function), so a step whose two ends pass the stick test
// passes it throughout: the stuck path is one comparison |a_i|^2 <= (mu_s g_e,i)^2 per sample. The onset inside a
// step is the root of the quadratic |a(t)|^2 - (mu_s g_e(t))^2, in closed form (cancellation-free). Slip: the
// direction turns continuously and there is no closed form; the 7-state ODE (u, w, path length, input work,
// friction work) is integrated by Dormand-Prince 5(4) with error control and its 4th-order dense output (Boost.Odeint
// runge_kutta_dopri5), steps ending on every sample (where the input's slope jumps). The stop |w| = 0 is a touch-down
// of |w|^2, not a sign change: within a step the friction direction is continued through w = 0 as
// sign(w . w_ref) w / |w| (w_ref the velocity at the step's start), which makes e(t) = w(t) . w_ref change sign at the
// stop; TOMS 748 finds it on the dense output. At the stop the block sticks if |a| <= mu_s g_e, else slips on in the
// new direction -a. Collinear motion is then integrated exactly (DP5 is exact for the quadratic velocity), so the
// 1-D solver's exactness carries over. After the record the ground is still and a sliding block runs out in a
// straight line to rest (closed form).
//
// Low speeds (method.md, "stiffness"). The direction of w relaxes toward -a at the rate |a| / |w|: stiff near every
// onset and stop. Below the velocity tolerance the integration cannot resolve the direction, so (1) until the speed
// first exceeds the launch speed r_L = max(sqrt(abs_tol x 0.1 m/s), 1000 abs_tol) (3.2e-5 m/s by default) after an
// onset, and while the quasi-static lag r psi'/|a| stays below 1e-3 rad, the velocity is slaved to the quasi-static
// direction -a / |a| (w = r n, n = -a / |a|, r' = |a| - mu_k g_e; method.md eq S5', where its error is estimated);
// (2) a sliding block that slows to 0.03 r_L has stopped (the remaining run-in, extrapolated along its direction, is
// added); (3) a block decelerating below the launch speed along -a is slaved to it again to its stop (the landing).
// The stiff phases still cost ~80 DP5 tries per slip episode at the default tolerances (below 1e-3 m/s: 54 % of the
// tries for 19 % of the slip time): with 5-15 % of a record slipping the 2-D solver runs at 15-32 M samples/s,
// ~35-55x slower than the 1-D one (docs/performance.md, with what bounds it).
//
// Incline (method.md eq S11). On a plane inclined at beta (SlidingBlock::slope_rad) whose fall line runs toward
// slope_azimuth_deg, with e_d the horizontal unit vector of that azimuth and a = a_d e_d + a_c (a_c across the slope):
// u and w are measured in the plane, the downslope in-plane axis carried on e_d (so a residual toward the slope's
// azimuth is a distance down the plane, as sliding.hpp's d), friction is isotropic in the plane with the normal force
//   N = g_e cos(beta) + a_d sin(beta),   w' = -a_c + (g_e sin(beta) - a_d cos(beta)) e_d - mu_k N+ w/|w|,
// i.e. the level equations with a -> a_c + (a_d cos(beta) - g_e sin(beta)) e_d and g_e -> N (both still linear on a
// step, so stick test, onset and method are unchanged; input_work_J_kg then includes gravity's work). On the fall line
// this is sliding.hpp's two-way incline (a_h = -a_d): tested to 1e-9. After the record the run-out on the still slope
// curves toward the fall line; it is integrated like the record (a still tail), to its stop. A slope steeper than the
// kinetic friction angle (tan(beta) >= mu_k) lets a sliding block never stop: at_rest_at_end = false.
//
// Scope. Two-way sliding only (one-way, down the fall line only, has no meaning for a block free to move across it).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"  // ComponentAzimuths
#include "topple/solvers/sliding.hpp"

namespace topple {

/// Integration tolerances of the slip phases (stick phases and onsets are exact).
struct Sliding2dOptions {
  /// Relative tolerance per step on each state (dimensionless, default 1e-7); > 0.
  double rel_tol = 1e-7;
  /// Absolute tolerance per step (m for displacements, m/s for velocities, m^2/s^2 for work per mass; default
  /// 1e-8); > 0. It also sets the launch speed and the velocity noise floor (3.2e-5 and 9.5e-7 m/s by default; see
  /// the header's "Low speeds").
  ///
  /// The defaults are set by a stated accuracy (docs/method.md, "Accuracy of the defaults"): residual displacement
  /// and max |u| within 1e-6 of max |u| (plus 1e-9 m), path length within 1e-6 of itself, of a tight-tolerance run;
  /// measured <= 7.8e-7 on four record pairs at seven mu (tests: Sliding2d.DefaultsMeetTheStatedAccuracy*). kSliding2dTight gives the old, ~100x tighter
  /// run (rel_tol 1e-9, abs_tol 1e-10) at about twice the cost.
  double abs_tol = 1e-8;
  /// Cap on integrator steps (accepted and rejected) over the run: a sign of an input outside the model.
  std::size_t max_steps = 100'000'000;

  /// Throws InputError naming the field for a non-finite or non-positive tolerance or a zero cap.
  void validate() const;
};
/// The tight tolerances (the defaults before the accuracy statement): ~100x smaller errors, ~2x the steps.
inline constexpr Sliding2dOptions kSliding2dTight{.rel_tol = 1e-9, .abs_tol = 1e-10};

struct Sliding2dSummary {
  double residual_east_m = 0.0;            ///< u_x when the block has come to rest after the record
  double residual_north_m = 0.0;           ///< u_y, same
  double residual_displacement_m = 0.0;    ///< |u| at rest
  std::optional<double> residual_azimuth_deg;  ///< direction of u at rest, degrees clockwise from north in [0, 360);
                                               ///< none when the block never moved
  double max_abs_displacement_m = 0.0;     ///< max |u| over the response (to the integration tolerance)
  double max_displacement_time_s = 0.0;    ///< first time |u| reaches it (record start when never slipping)
  double path_length_m = 0.0;              ///< integral of |w| dt: the length of the block's track on the ground
  double max_abs_velocity_m_s = 0.0;       ///< peak relative speed max |w|
  int slip_episodes = 0;                   ///< slip starts from relative rest
  std::optional<double> first_slip_time_s;
  double total_slip_duration_s = 0.0;
  double end_time_s = 0.0;                 ///< when the block came to rest (>= record end when it slid past it)
  bool at_rest_at_end = true;              ///< false only when mu_k = 0 and it still slides at the record's end
  std::optional<double> contact_lost_time_s;  ///< first time g_e <= 0 (on a slope: the normal force N <= 0): the
                                              ///< block leaves the ground
  double input_work_J_kg = 0.0;            ///< integral of -a . w dt: work of the inertial load on the block, per mass
                                           ///< (on a slope: of the in-plane load, gravity's included)
  double friction_work_J_kg = 0.0;         ///< integral of mu_k g_e^+ |w| dt: energy dissipated by friction, per mass
  std::size_t integrator_steps = 0;        ///< Dormand-Prince steps taken, rejected ones included
};

/// History on the merged grid's points plus every event (slip start and stop); at an event the row carries the
/// state after it. On a slope the record's end appears twice (the ground turning still) and the run-out's events
/// follow it.
struct Sliding2dHistory {
  std::vector<double> time_s;
  std::vector<double> east_m;        ///< u_x
  std::vector<double> north_m;       ///< u_y
  std::vector<double> east_m_s;      ///< w_x
  std::vector<double> north_m_s;     ///< w_y
  std::vector<std::uint8_t> slipping;  ///< 1 while slipping, 0 stuck
};

struct Sliding2dResult {
  Sliding2dSummary summary;
  Sliding2dHistory history;
};

/// Full response with history. `first` and `second` are the horizontal components (m/s^2, positive toward their
/// azimuths), `vertical` (optional) the vertical, positive up; any grids (merged exactly). `block` must be two-way
/// (level or inclined, the slope's azimuth in `azimuths`): InputError otherwise, as for azimuths that are not finite
/// and perpendicular (to 1e-6 deg).
[[nodiscard]] Sliding2dResult slide_2d(const GroundMotion& first, const GroundMotion& second,
                                       const ComponentAzimuths& azimuths, const SlidingBlock& block,
                                       const GroundMotion* vertical = nullptr, const Sliding2dOptions& options = {});

/// Summary only (no history stored): the fast path.
[[nodiscard]] Sliding2dSummary slide_2d_summary(const GroundMotion& first, const GroundMotion& second,
                                                const ComponentAzimuths& azimuths, const SlidingBlock& block,
                                                const GroundMotion* vertical = nullptr,
                                                const Sliding2dOptions& options = {});

/// Closed-form oracle (docs/method.md): the steady sliding state under a ground acceleration of constant magnitude
/// A rotating at constant angular speed omega on level ground, with mu g < A. In the frame turning with the ground
/// acceleration the relative velocity is constant: its magnitude is V = sqrt(A^2 - (mu g)^2) / omega and it lags the
/// inertial load -a by delta = arccos(mu g / A) (behind it in the sense of rotation); u runs on a circle of radius
/// V / omega, and input and friction power both equal mu g V.
struct RotatingSteadySliding {
  double speed_m_s = 0.0;      ///< V
  double lag_rad = 0.0;        ///< delta
  double radius_m = 0.0;       ///< V / omega
  double power_W_kg = 0.0;     ///< mu g V
};
/// Throws InputError unless A > mu g >= 0 and omega > 0, all finite.
[[nodiscard]] RotatingSteadySliding rotating_steady_sliding(double accel_m_s2, double omega_rad_s, double mu,
                                                            double g_m_s2 = kStandardGravity);

}  // namespace topple
