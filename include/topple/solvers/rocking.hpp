#pragma once
// Rocking and overturning of a rigid body on a level base that does not slide.
//
// Model (Housner 1963, "The behavior of inverted pendulum structures during earthquakes", BSSA 53(2); Mittal 1971,
// thesis section 3.5, eqs 3.11-3.14). A rigid body stands on a level, rigid base and rocks about one base edge
// (pivot O+, on the +x side) or the other (O-). Friction is large enough that it never slides (check with
// shenton_onset_mode). Geometry, all about the pivot:
//   a = horizontal distance from the centre of mass (CM) to the pivot edge, m     (block: half the width)
//   h = height of the CM above the base, m                                          (block: half the height)
//   D = I_O / m, the pivot moment of inertia per unit mass, m^2
//   R = sqrt(a^2 + h^2)   alpha = atan(a / h) (slenderness)   p = sqrt(g R / D) (frequency parameter, rad/s)
// Shapes: rectangular block, width 2a, height 2h: D = (4/3)(a^2 + h^2) (thesis eq 3.14);
//         solid cylinder standing on its end, diameter 2a, height 2h, rocking about a rim point:
//         D = (15 a^2 + 16 h^2) / 12 (thesis eq 3.13);  general body: a, h, D given (D >= a^2 + h^2).
//
// Sign convention. theta is the rotation of the body from upright, positive when it rotates about O+ (the top
// moves toward +x), negative about O-. The horizontal ground acceleration a_h is positive toward +x, the vertical
// a_v positive up. A ground acceleration toward -x (a_h < 0) throws the body toward +x and drives theta > 0.
// (The thesis measures theta >= 0 from the base on whichever edge is the pivot, so its eq 3.12 carries a minus
// sign that this convention does not need.)
//
// Equation of motion while rocking about the pivot s = sgn(theta) (Housner 1963; thesis eq 3.11 with
// a cos(theta) - h sin(theta) = R sin(alpha - theta) and h cos(theta) + a sin(theta) = R cos(alpha - theta),
// generalised to both pivots and to vertical input, g -> g + a_v):
//   theta'' = -(R / D) [ (g + a_v) sin(s alpha - theta) + a_h cos(s alpha - theta) ]
// At rest (theta = theta' = 0) the body stays in full contact while |a_h| <= (g + a_v) tan(alpha) = (g + a_v) a / h
// (thesis section 3.5, "y'' > (a/h) g"); it lifts off about O+ when -a_h > (g + a_v) tan(alpha) and about O-
// when a_h > (g + a_v) tan(alpha). The input is piecewise linear, so the uplift instant is the root of a linear
// function inside a sample interval and is located exactly.
//
// Impact. When theta returns to 0 the body lands on the other edge and continues rocking about it; the angular
// velocity keeps its sign and is multiplied by the coefficient of restitution e (Housner 1963). Housner's e
// follows from conservation of angular momentum about the new pivot:
//   e = 1 - 2 m R^2 sin^2(alpha) / I_O = 1 - 2 a^2 / D
//   (block: 1 - 1.5 sin^2(alpha); cylinder: 1 - 24 a^2 / (15 a^2 + 16 h^2)); the kinetic energy is multiplied by e^2.
// A body so squat that Housner's e < 0 (block alpha > 54.7 deg) cannot continue onto the other edge; e must then be
// given explicitly.
//
// Rest rule (the free rocking of a body with e < 1 has infinitely many impacts in finite time: Zeno behaviour; the
// half-cycles shrink geometrically with the amplitude, Housner 1963). After an impact, when the kinetic energy left,
// D theta'^2 / 2, is below
// RockingOptions::rest_energy_fraction (default 1e-8) times the energy needed to lift the CM over the pivot,
// g R (1 - cos(alpha)), the body is put in full contact at rest (theta = theta' = 0; the energy dropped is counted as
// lost). It then waits for the next uplift. With the default the motion dropped would have had an amplitude of
// about 5e-9 alpha. (The thesis' overturning program has the same kind of rule: after an impact it sets the velocity
// to zero when it is below an input limit VL.)
//
// Overturning. The body has fallen when |theta| reaches pi/2 (its side hits the ground; the thesis' program stops at
// 1.57 rad). The first time |theta|
// exceeds alpha (the CM passes over the pivot: without further input the body then falls) is reported as well. After
// the last sample the ground is still (a_h = a_v = 0) and the integration runs on until the body is at rest, has
// fallen, or RockingOptions::max_run_out_s has passed, so that a body past alpha at the end of the record falls.
// Overturning is not monotone in the amplitude of the input: a larger motion may leave the body standing.
//
// Asymmetric bodies (general_asymmetric; docs/method.md, "Asymmetric bodies"). b1 = CM to O- (theta < 0), b2 = CM to
// O+ (theta > 0), h, k2 = I_cm / m; about pivot s: D_s = k2 + b_s^2 + h^2, alpha_s = atan(b_s / h), R_s. The equation
// above holds with (alpha_s, R_s, D_s) of the current pivot; uplift about O+ when -a_h > (g + a_v) b2 / h, about O-
// when a_h > (g + a_v) b1 / h; exceeded alpha when |theta| passes alpha_s on its side. At impact onto O_new from
// O_old, angular momentum about O_new: D_new theta'+ = (k2 + h^2 - b1 b2) theta'-, i.e.
//   e_new = 1 - b_new (b_old + b_new) / D_new   (symmetric: 1 - 2 a^2 / D).
//
// Onset mode (Shenton 1996): shenton.hpp. Closed forms of free rocking and of the overturning thresholds (library
// oracles): closed_forms/rocking.hpp. The first overturning amplitude of a family of motions: threshold_search.hpp.
//
// Method. Adaptive: Dormand-Prince 5(4) (Dormand & Prince 1980) with error control and its 4th-order dense output
// (Hairer, Norsett & Wanner 1993, II.5-II.6), written out for the two components (the tableau of numerics/dp5.hpp, the
// error norm and step-size law of Boost.Odeint's controlled runge_kutta_dopri5; src/solvers/rocking_steppers.hpp), state scaled as (theta / alpha, theta' / (p alpha)) so that
// one tolerance fits both. Steps end on every sample instant of the input (its derivative jumps there) and never
// straddle one. Events (uplift aside) are roots of the dense output, a degree-5 polynomial in the step fraction,
// found by Newton's method kept inside the sign-change bracket (bisection when a Newton step leaves it): impact
// (theta = 0), turning points (theta' = 0), |theta| = alpha, |theta| = pi/2. The summary-only path (rock_summary)
// skips locating a turning point that cannot change the summary: a peak whose bound on the step (from the
// polynomial's coefficients) stays below the largest |theta| so far, alpha and pi/2 with no impact after it, or a
// trough that stays above theta = 0; rock() locates them all and gives the same summary. While the body is at rest
// nothing is integrated: each sample interval costs a comparison of |a_h| with the uplift threshold. RK4: the
// thesis' fixed-step classical Runge-Kutta with step dt/n inside each sample interval (dt the record's sample
// interval, n = rk4_substeps), kept for comparison; its events are located by TOMS 748 (Alefeld, Potra & Shi 1995;
// Boost.Math toms748_solve) on the RK4 step of variable length from the start of the step (a 4th-order continuous
// extension), where the thesis cut the step to a fifth and interpolated linearly.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/bodies/rocking_body.hpp"
#include "topple/solvers/shenton.hpp"  // OnsetMode, the Shenton criteria (declared here before the split)
#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

namespace topple {

/// Housner's coefficient of restitution e = 1 - 2 a^2 / D (angular-velocity ratio at impact; may be negative for a
/// squat body, see the header). An asymmetric body: the landing on O+ (housner_restitution(body, 1)).
[[nodiscard]] double housner_restitution(const RockingBody& body) noexcept;
/// Housner's law for an asymmetric body landing on the pivot of side `onto` (+1: O+, -1: O-) from the other one,
/// by conservation of angular momentum about the new pivot (docs/method.md, "Asymmetric bodies"):
///   e = 1 - b_new (b_old + b_new) / D_new   (= 1 - 2 a^2 / D when symmetric, bit for bit).
[[nodiscard]] double housner_restitution(const RockingBody& body, int onto) noexcept;

/// What to do when housner_restitution is negative (a block wider than about 1.41 times its height, alpha > 54.7
/// deg): Housner's angular-momentum argument then says the body cannot rock onto its other edge at all, so e must be
/// given. Said in every message that refuses such a body (docs/survey.md, "Squat objects").
inline constexpr std::string_view kSquatBodyAdvice =
    "give e explicitly: e = 0 (it stops at its first impact, the consistent limit of Housner's argument) or a "
    "range such as [0, 0.3] when unsure; such a body is a weak rocking witness (docs/survey.md, \"Squat objects\")";

enum class RestitutionMode : std::uint8_t { housner, given };
enum class RockingMethod : std::uint8_t { adaptive, rk4 };
[[nodiscard]] std::string_view restitution_mode_name(RestitutionMode mode);  ///< "housner", "given"
[[nodiscard]] std::string_view rocking_method_name(RockingMethod method);    ///< "adaptive", "rk4"
/// "adaptive" or "rk4"; throws InputError naming `field` otherwise.
[[nodiscard]] RockingMethod parse_rocking_method(std::string_view name, const std::string& field = "method");

/// The restitution choice as users write it: "housner" (e = 1 - 2 a^2 / D) or a number (the given e). Returns the
/// mode and, for `given`, the number (its range [0, 1] is checked by the solvers). Throws InputError naming `field`
/// for anything else.
struct RestitutionChoice {
  RestitutionMode mode = RestitutionMode::housner;
  double e = 1.0;  ///< when mode == given
};
[[nodiscard]] RestitutionChoice parse_restitution(std::string_view text, const std::string& field = "e");

struct RockingOptions {
  double g_m_s2 = kStandardGravity;                  ///< gravity, m/s^2
  RestitutionMode restitution = RestitutionMode::housner;
  double e = 1.0;                                    ///< restitution when restitution == given, in [0, 1]
  std::optional<double> mu;                          ///< friction coefficient for the Shenton onset check (none:
                                                     ///< onset_mode is "unchecked")
  RockingMethod method = RockingMethod::adaptive;
  double rel_tol = 1e-8;   ///< adaptive: relative error per step on (theta/alpha, theta'/(p alpha))
  double abs_tol = 1e-12;  ///< adaptive: absolute error per step on the same scaled state (dimensionless)
  int rk4_substeps = 10;   ///< rk4: steps per sample interval (the thesis used dt = 0.005 s on a 0.02 s record)
  double rest_energy_fraction = 1e-8;  ///< rest rule threshold, see the header (dimensionless, > 0 and < 1)
  double max_run_out_s = 60.0;         ///< longest integration after the record on still ground, s (>= 0)
  double initial_theta_rad = 0.0;      ///< state at the record's start (|theta| < pi/2); default: at rest
  double initial_theta_dot_rad_s = 0.0;
  bool stop_when_alpha_exceeded = false;  ///< end the run when |theta| first exceeds alpha (threshold searches)
  std::size_t max_steps = 100'000'000;    ///< cap on integrator steps (accepted + rejected); throws past it
};

enum class RockingState : std::int8_t { rocking_negative = -1, rest = 0, rocking_positive = 1, fallen = 2 };
[[nodiscard]] std::string_view rocking_state_name(RockingState state);  ///< "rocking-", "rest", "rocking+", "fallen"

/// Time history on the record's samples (and, after the record, on the same spacing, or max_run_out_s / 1e5 if
/// coarser, until the run ends) plus every event instant. At an event the row carries the state after the event.
/// The history ends when the body falls.
struct RockingHistory {
  std::vector<double> time_s;
  std::vector<double> theta_rad;
  std::vector<double> theta_dot_rad_s;
  std::vector<RockingState> state;
};

enum class RockingEventKind : std::uint8_t {
  uplift,          ///< the body leaves full contact (theta' = 0)
  impact,          ///< theta = 0: theta_dot_before -> theta_dot_after = e * theta_dot_before
  rest,            ///< rest rule applied after an impact (theta_dot_after = 0), or lift-off that did not happen
  peak,            ///< turning point theta' = 0 while rocking (a local maximum of |theta|)
  exceeded_alpha,  ///< |theta| = alpha, first time only
  overturned,      ///< |theta| = pi/2
};
[[nodiscard]] std::string_view rocking_event_name(RockingEventKind kind);

struct RockingEvent {
  RockingEventKind kind = RockingEventKind::uplift;
  double time_s = 0.0;
  double theta_rad = 0.0;
  double theta_dot_before_rad_s = 0.0;
  double theta_dot_after_rad_s = 0.0;
};

struct RockingSummary {
  double alpha_rad = 0.0;
  double R_m = 0.0;
  double p_rad_s = 0.0;
  double e = 0.0;                           ///< restitution used (asymmetric body: on landing on O+)
  double e_onto_negative = 0.0;             ///< restitution on landing on O- (symmetric body: e)
  double g_m_s2 = 0.0;
  double max_abs_rotation_rad = 0.0;        ///< max |theta| (turning points located on the dense output)
  double max_rotation_over_alpha = 0.0;     ///< max |theta| / alpha (>= 1: the CM passed over the pivot)
  double max_rotation_time_s = 0.0;
  // Per side (theta > 0: about O+, the +x edge; theta < 0: about O-). For an asymmetric body
  // max_rotation_over_alpha is the larger of the two ratios below (>= 1 still means the CM passed over a pivot);
  // for a symmetric one it is max |theta| / alpha as before (the same number: division by alpha is monotone).
  double max_rotation_positive_rad = 0.0;       ///< max theta over theta > 0 (>= 0)
  double max_rotation_negative_rad = 0.0;       ///< max -theta over theta < 0 (>= 0)
  double max_rotation_over_alpha_positive = 0.0;  ///< max_rotation_positive_rad / alpha+
  double max_rotation_over_alpha_negative = 0.0;  ///< max_rotation_negative_rad / alpha-
  double alpha_negative_rad = 0.0;          ///< alpha- = atan(b1 / h) (symmetric: alpha_rad)
  int exceeded_alpha_side = 0;              ///< +1 / -1: the side on which |theta| first passed its alpha; 0: never
  int overturned_side = 0;                  ///< +1: fell toward +x (about O+), -1: toward -x; 0: did not fall
  double max_abs_theta_dot_rad_s = 0.0;     ///< at step ends and events
  std::size_t impacts = 0;
  std::size_t uplifts = 0;                  ///< lift-offs from full contact
  std::optional<double> uplift_time_s;      ///< first lift-off
  std::optional<double> exceeded_alpha_time_s;
  bool overturned = false;
  std::optional<double> overturn_time_s;
  double energy_lost_j_per_kg = 0.0;        ///< kinetic energy lost in impacts and to the rest rule, J/kg
  double end_time_s = 0.0;                  ///< when the run ended (rest after the record, fall, or run-out cap)
  RockingState end_state = RockingState::rest;
  bool still_rocking_at_end = false;        ///< the run-out cap ended a run that was still rocking
  OnsetMode onset_mode = OnsetMode::unchecked;
  std::optional<double> onset_accel_ratio;  ///< A = |a_h| / (g + a_v) at the first lift-off (or first slip)
  std::optional<double> critical_mu;        ///< Shenton's mu_crit at that A (when mu is given and rocking starts)
  std::size_t steps = 0;                    ///< integrator steps taken (accepted and rejected)
  std::vector<std::string> warnings;        ///< e.g. "mu = 0.15 < a/h = 0.2: the body slides before it rocks ..."
};

struct RockingResult {
  RockingSummary summary;
  RockingHistory history;
  std::vector<RockingEvent> events;
};

/// Full response with history and events. `vertical` (optional, positive up) may have another sampling grid (the
/// union of both grids is used; it is zero outside its own record). Throws InputError for an invalid option (field
/// named as in RockingOptions: "e", "mu", "g", "rel_tol", ...) or a vertical input with g + a_v <= 0 ("vertical").
[[nodiscard]] RockingResult rock(const GroundMotion& horizontal, const RockingBody& body,
                                 const RockingOptions& options = {}, const GroundMotion* vertical = nullptr);

/// Summary only, no history nor events stored (the fast path for sweeps and threshold searches).
[[nodiscard]] RockingSummary rock_summary(const GroundMotion& horizontal, const RockingBody& body,
                                          const RockingOptions& options = {}, const GroundMotion* vertical = nullptr);

}  // namespace topple
