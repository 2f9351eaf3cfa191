#pragma once
// Coupled sliding and rocking of a rigid body in the vertical plane on a level or inclined rigid base (issue 15; docs/method.md,
// "Coupled slide-rock model").
//
// Model. A rigid body of mass m (results are per unit mass and do not depend on m) touches the level ground at two
// base corners: O- at horizontal distance b1 to the -x side of the centre of mass (CM), O+ at b2 to the +x side; the
// CM is at height h; k2 = I_cm / m. Coulomb friction at the corners: static mu_s, kinetic mu_k <= mu_s. The ground
// accelerates horizontally (a_h, positive toward +x) and vertically (a_v, positive up); g_e = g + a_v.
//
// Sign convention (the rocking engine's, rocking.hpp): theta > 0 is a rotation about O+ (the top moves toward +x),
// theta < 0 about O-. The slide u is the horizontal displacement, relative to the ground, of the corner on the side
// sgn(theta) (the pivot; either corner at theta = 0), positive toward +x:
//   X = u + s b_s (1 - cos(theta)) + h sin(theta),  s = sgn(theta),
// X the CM's horizontal displacement (u = X at theta = 0). NOTE: the sliding solver (sliding.hpp) measures d positive in the direction a
// positive a_h pushes the block, i.e. toward -x: on a level base d = -u.
//
// Equations (per unit mass, in the ground's frame: inertial load -a_h along x, weight -g_e along y). With the CM
// seen from the pivot s, rho = (rho_x, rho_y) = (-s b_s cos(theta) + h sin(theta), s b_s sin(theta) + h cos(theta)),
// D_s = k2 + b_s^2 + h^2, and contact forces F (tangential, +x) and N (normal) at the pivot:
//   rest      u' = theta = theta' = 0; F = a_h, N+ = (b1 g_e - h a_h) / (b1 + b2), N- = (b2 g_e + h a_h) / (b1 + b2)
//   slide     theta = 0, both corners: u'' = -a_h - sigma mu_k g_e (sigma = sgn u'); the normal forces
//             N+ = g_e (b1 + sigma mu_k h) / (b1 + b2), N- = g_e (b2 - sigma mu_k h) / (b1 + b2) do not depend on a_h
//   rock      pivot sticks (u' = 0): theta'' = (rho_x g_e - rho_y a_h) / D_s  (Housner 1963, rocking.hpp's equation)
//             F = rho_y theta'' - rho_x theta'^2 + a_h,  N = g_e - rho_x theta'' - rho_y theta'^2
//   slide-rock pivot slips (sigma = sgn u'), F = -sigma mu_k N:
//             theta'' = c (g_e - rho_y theta'^2) / (k2 + c rho_x),  c = rho_x + sigma mu_k rho_y
//             N = g_e - rho_x theta'' - rho_y theta'^2,  u'' = -a_h - sigma mu_k N - rho_y theta'' + rho_x theta'^2
//   flight    X'' = -a_h, Y'' = -g_e, theta'' = 0 (Y the CM height)
// Transitions (the two-contact complementarity problem, solved by enumeration in the order rest, slide, rock,
// slide-rock, flight: the first mode whose forces satisfy N >= 0, |F| <= mu_s N, and whose accelerations point the way
// the mode assumes). From rest this is Shenton (1996)'s onset criteria (rocking.hpp, shenton_onset_mode). Events are
// located by root finding on the dense output: contact force N -> 0 (flight), stick limit |F| = mu_s N (slip
// starts), slip velocity u' -> 0 (stick or reverse), theta -> 0 (impact), |theta| -> pi/2 (overturned), and, for the
// summary, theta' -> 0 (peaks) and the first |theta| = alpha_s (exact in flight, theta being linear there).
//
// Painleve's paradox (docs/method.md): where slide-rock's k2 + c rho_x <= 0, Coulomb friction has no or two
// solutions for the slipping pivot. A slipping pivot is then stopped by a tangential impact (the "impact without
// collision": the stick impulse, inside the friction cone exactly there) and decided again at zero slip; a sticking
// pivot past the stick limit whose slip has k2 + c rho_x <= 0 is held (rock) until the slip has a solution or the stick
// limit holds again (the solution continuous with sticking). Counted in tangential_impacts and painleve_holds.
//
// A body with mu_s < min(b1, b2) / h can never lift off (sliding starts before rocking, Shenton 1996, and the normal
// forces while sliding stay positive whatever a_h): the run is then the exact sliding solver (sliding.hpp) itself,
// unless SlideRockOptions::sliding_kernel is false.
//
// Impact law (docs/method.md). When theta reaches 0 the other corner strikes; a landing from flight is a strike of
// the lower corner. The impulse (P_t, P_n) acts at the striking corner only (the other corner lifts off, as in Housner
// 1963), the normal impact is plastic (the corner's normal velocity after is 0), and the tangential impulse is
// Coulomb's (Brogliato 1999, "Nonsmooth Mechanics", 2nd ed., sec. 4.2; Shenton & Jones 1991, J. Eng. Mech. 117(10)):
// stick (corner velocity 0 after) when the impulse needed has |P_t| <= mu_s P_n, which conserves the angular momentum
// about the corner and is exactly Housner's law, e = 1 - b_new (b_old + b_new) / D_new, after pure rocking; otherwise
// slip with P_t = -sigma mu_k P_n, sigma the sign of the corner's tangential velocity before (or against the stick
// impulse when it is 0), kept over the impact (no slip reversal within the impulse). A given e (RestitutionMode::
// given) replaces Housner's ratio on a stick impact after pure rocking (theta'+ = e theta'-), as in the rocking engine.
// The rest rule after an impact is the rocking engine's (rest_energy_fraction of the energy to lift the CM over the
// landing pivot).
//
// Inclined base (SlideRockOptions::slope_rad = beta >= 0; docs/method.md, "Inclined base"). The base is a plane
// inclined at beta in the plane of shaking; x runs along it, y normal to it. Down-slope is -x (the base rises toward
// +x), so that sliding.hpp's d = -u is down-slope positive as there, and a positive a_h (the ground accelerating
// toward the uphill side) pushes the body down-slope. The frame is the ground's (translating): gravity and the
// ground's acceleration resolve into per-unit-mass loads as in sliding.hpp (Goodman & Seed 1966),
//   tangential  f_t = a_h cos(beta) + g_e sin(beta)  (toward -x),   normal  n = g_e cos(beta) - a_h sin(beta),
// and every equation above holds with (a_h, g_e) -> (f_t, n): contact forces, Coulomb's law, the enumeration, the
// events and the impacts are unchanged in the base frame (u along the slope, theta from the slope's normal, Y normal
// to it). Still ground is f_t = g sin(beta), n = g cos(beta); the energy's potential is g sin(beta) X + g cos(beta)
// (Y - h). The body must stand at rest on the slope: tan(beta) <= mu_s (else it slides away) and beta <= alpha- =
// atan(b1 / h) (else it tips over the down-slope corner O-) are required, else InputError "slope". Onset from rest
// without vertical input (the level thresholds tilted by beta): slip down-slope at a_h > g tan(phi - beta), up-slope
// at a_h < -g tan(phi + beta) (tan(phi) = mu_s); uplift about O- at a_h > g tan(alpha- - beta), about O+ at
// a_h < -g tan(alpha+ + beta).
//
// Method. Rock and slide-rock: Boost.Odeint's controlled Dormand-Prince 5(4) (runge_kutta_dopri5, error control on
// the state scaled as (u / (h alpha), u' / (p h alpha), theta / alpha, theta' / (p alpha))), with its 4th-order dense
// output (calc_state); steps end on every sample instant of the input; events are roots of the event functions on
// the dense output (TOMS 748). Rest: one test per sample (the rest region is convex in (a_h, g_e), so an interval
// whose ends are inside stays inside); the exit is the root of a linear function. Slide: exact (the input is
// piecewise linear, so u'' is linear in each interval; the stop is the first root of a quadratic). Flight: exact
// (parabola, theta linear in time); the strike is located by TOMS 748 on 16 sub-intervals of each sample interval
// (two strikes within one sub-interval would be missed: stated in docs/method.md).
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/core/units.hpp"

namespace topple {

/// The body: two pivots, CM height, inertia, friction. Build with make(), which validates.
struct SlideRockBody {
  double b1_m = 0.0;        ///< CM to the corner O- (the -x edge), horizontal, m (a 20 cm wide block: 0.10)
  double b2_m = 0.0;        ///< CM to the corner O+ (the +x edge), m
  double h_m = 0.0;         ///< CM height above the base, m
  double inertia_m2 = 0.0;  ///< k2 = I_cm / m, m^2 (block w x H: (w^2 + H^2) / 12)
  double mu_static = 0.0;   ///< static friction coefficient (dimensionless, typical 0.2-0.8)
  double mu_kinetic = 0.0;  ///< kinetic friction coefficient, 0 <= mu_kinetic <= mu_static

  /// Throws InputError naming "b1", "b2", "h", "inertia" (as RockingBody::general_asymmetric), "mu" or "mu_k".
  /// No mu_kinetic: equal to mu_static.
  [[nodiscard]] static SlideRockBody make(double b1_m, double b2_m, double h_m, double inertia_m2, double mu_static,
                                          std::optional<double> mu_kinetic = std::nullopt);
  /// A rectangular block of full width and height (m), symmetric: b1 = b2 = w/2, h = H/2, k2 = (w^2 + H^2) / 12.
  [[nodiscard]] static SlideRockBody block(double width_m, double height_m, double mu_static,
                                           std::optional<double> mu_kinetic = std::nullopt);
  /// The planar body of a rocking body (any shape: b1 = b2 = a for a symmetric one, k2 = D - a^2 - h^2), with
  /// friction. Throws InputError as make().
  [[nodiscard]] static SlideRockBody from_rocking(const RockingBody& body, double mu_static,
                                                  std::optional<double> mu_kinetic = std::nullopt);
  /// The rocking engine's body for the same geometry (RockingBody::general_asymmetric(b1, b2, h, k2)).
  [[nodiscard]] RockingBody rocking_body() const;
  /// True when mu_s < min(b1, b2) / h: the body slides before it can lift and never lifts while sliding.
  [[nodiscard]] bool cannot_uplift() const noexcept;
  /// mu_P, the Painleve limit (dimensionless; docs/method.md, "Painleve's paradox"): the least kinetic friction
  /// coefficient at which slide-rock's den = k2 + rho_x^2 + sigma mu_k rho_x rho_y reaches 0 at some tilt
  /// |theta| < pi/2 on either pivot, i.e. mu_P = min over the pivots of min_theta (k2 + rho_x^2) / |rho_x rho_y|
  /// = min_s 2 sqrt(q_s (q_s + 1)), q_s = k2 / (b_s^2 + h^2). A rectangular block: 4/3 whatever its b/h. With
  /// mu_kinetic >= mu_P the run may meet the paradox, which the solver resolves (tangential impacts, holds).
  [[nodiscard]] double painleve_friction_limit() const noexcept;
};

enum class SlideRockMode : std::uint8_t { rest, slide, rock, slide_rock, flight, fallen };
inline constexpr std::size_t kSlideRockModes = 6;
/// "rest", "slide", "rock", "slide-rock", "flight", "fallen"
[[nodiscard]] std::string_view slide_rock_mode_name(SlideRockMode mode);

struct SlideRockOptions {
  double g_m_s2 = kStandardGravity;                  ///< gravity, m/s^2
  /// Inclination beta of the base, rad, in [0, pi/2) (0: level; a ledge: 0.1-0.3); down-slope is -x (see the header).
  /// Needs tan(beta) <= mu_s and beta <= atan(b1 / h): the body stands on the slope (InputError "slope" otherwise).
  double slope_rad = 0.0;
  RestitutionMode restitution = RestitutionMode::housner;
  double e = 1.0;                                    ///< restitution when restitution == given, in [0, 1]
  double rel_tol = 1e-8;   ///< relative error per step on the scaled state (see the header)
  double abs_tol = 1e-12;  ///< absolute error per step on the scaled state (dimensionless)
  double rest_energy_fraction = 1e-8;  ///< the rocking engine's rest rule after an impact (dimensionless, (0, 1))
  double max_run_out_s = 60.0;         ///< longest run after the record on still ground, s (>= 0)
  double initial_theta_rad = 0.0;      ///< state at the record's start (|theta| < pi/2); default: at rest
  double initial_theta_dot_rad_s = 0.0;
  double initial_slide_velocity_m_s = 0.0;  ///< u' at the start (the pivot's slip velocity), m/s
  bool sliding_kernel = true;  ///< run sliding.hpp's exact solver when the body cannot lift (cannot_uplift)
  bool record_history = false; ///< fill SlideRockResult::history (slide_rock() only)
  std::size_t max_steps = 100'000'000;  ///< cap on integrator steps (accepted + rejected); throws past it
};

/// Time history on the record's samples, at every integrator step end and at every event (the row after an event
/// carries the state after it).
struct SlideRockHistory {
  std::vector<double> time_s;
  std::vector<double> slide_m;          ///< u
  std::vector<double> slide_velocity_m_s;
  std::vector<double> theta_rad;
  std::vector<double> theta_dot_rad_s;
  std::vector<double> cm_height_m;      ///< Y, height of the CM above the ground (h at rest)
  std::vector<double> energy_j_per_kg;  ///< kinetic energy in the ground's frame + g (Y - h), J/kg
  std::vector<SlideRockMode> mode;
};

/// A change of mode: the time and the mode entered.
struct SlideRockTransition {
  double time_s = 0.0;
  SlideRockMode mode = SlideRockMode::rest;
};

struct SlideRockSummary {
  double alpha_positive_rad = 0.0;       ///< atan(b2 / h)
  double alpha_negative_rad = 0.0;       ///< atan(b1 / h)
  bool overturned = false;
  int overturned_side = 0;               ///< +1: toward +x (about O+), -1: toward -x, 0: did not fall
  std::optional<double> overturn_time_s;
  double max_rotation_positive_rad = 0.0;        ///< max theta over theta > 0
  double max_rotation_negative_rad = 0.0;        ///< max -theta over theta < 0
  double max_rotation_over_alpha_positive = 0.0; ///< / alpha+
  double max_rotation_over_alpha_negative = 0.0; ///< / alpha-
  double max_rotation_over_alpha = 0.0;          ///< the larger of the two
  std::optional<double> exceeded_alpha_time_s;   ///< first |theta| = alpha of its side (located by root finding)
  double residual_slide_m = 0.0;         ///< u at the end of the run (toward +x)
  double max_abs_slide_m = 0.0;          ///< max |u| at step ends, events and stops
  int slip_episodes = 0;                 ///< entries into slide or slide-rock from a sticking state
  std::size_t impacts = 0;               ///< corner strikes (rocking and landings from flight)
  std::size_t uplifts = 0;               ///< lift-offs from full contact
  /// Painleve's paradox (docs/method.md): tangential impacts ("impacts without collision") that stopped a slipping
  /// pivot where slide-rock had no solution, and holds of a sticking pivot where every slip had none.
  std::size_t tangential_impacts = 0;
  std::size_t painleve_holds = 0;
  double max_tangential_impulse_ratio = 0.0;  ///< max |P_t| / P_n over the tangential impacts (<= mu_k: Coulomb)
  SlideRockMode onset_mode = SlideRockMode::rest;  ///< the first mode left rest for (rest: never moved)
  /// Per mode (index: SlideRockMode): how many times it was entered, and the first time (unset: never).
  std::array<std::size_t, kSlideRockModes> mode_entries{};
  std::array<std::optional<double>, kSlideRockModes> mode_first_time_s{};
  double friction_energy_j_per_kg = 0.0;  ///< dissipated by kinetic friction, J/kg
  double impact_energy_j_per_kg = 0.0;    ///< lost in impacts and to the rest rule, J/kg
  double end_time_s = 0.0;
  SlideRockMode end_mode = SlideRockMode::rest;
  bool moving_at_end = false;             ///< the run-out cap ended a run still in motion
  bool used_sliding_kernel = false;       ///< the run was sliding.hpp's solver (cannot_uplift)
  std::size_t steps = 0;                  ///< integrator steps (accepted and rejected)
  std::vector<std::string> warnings;
};

struct SlideRockResult {
  SlideRockSummary summary;
  SlideRockHistory history;                       ///< empty unless options.record_history
  std::vector<SlideRockTransition> transitions;  ///< every change of mode
};

/// The coupled response. `vertical` (optional, positive up) is merged with the horizontal record on one grid
/// (input_grid.hpp). Throws InputError for invalid options (named as in SlideRockOptions) or a body with a negative
/// Housner e and no e given ("e"); SolverError subclasses at the limits (steps, events, root finding). The Painleve
/// case k2 + c rho_x <= 0 of slide-rock is resolved, not thrown (see above; docs/method.md).
[[nodiscard]] SlideRockResult slide_rock(const GroundMotion& horizontal, const SlideRockBody& body,
                                         const SlideRockOptions& options = {},
                                         const GroundMotion* vertical = nullptr);

/// The mode a body at rest enters under a_h and g_e = g + a_v (m/s^2), by the enumeration of the header: rest, slide,
/// rock, slide-rock or flight (g_e <= 0). For a symmetric body and mu_k = mu_s this is Shenton (1996)'s criteria.
/// On a base inclined at slope_rad (validated as SlideRockOptions::slope_rad), the loads f_t, n of the header.
[[nodiscard]] SlideRockMode slide_rock_onset_mode(const SlideRockBody& body, double a_h_m_s2, double g_e_m_s2,
                                                  double slope_rad = 0.0);

/// The coupled model's options from the rocking model's (one conversion for the inversion, `topple rock --model
/// coupled` and Python's slide_rock): gravity, restitution and e, rel_tol, max_run_out_s and max_steps; the rest at
/// SlideRockOptions' defaults (the rocking-only choices, method and rk4 substeps, have no coupled counterpart).
[[nodiscard]] SlideRockOptions slide_rock_options(const RockingOptions& rocking);

}  // namespace topple
