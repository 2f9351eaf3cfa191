#pragma once
// Sliding of a rigid block on a plane with Coulomb friction, driven by ground acceleration.
//
// Model (Newmark 1965; Goodman & Seed 1966; Mittal 1971, eqs 2.1-2.4 and 3.9-3.10). A rigid block rests on a plane
// inclined at beta (0 = level ground). The ground accelerates horizontally in the vertical plane of the slope's fall
// line, with acceleration a_h(t), and optionally vertically with a_v(t) (positive up), so that the effective gravity
// is g_e(t) = g + a_v(t).
//
// Sign convention. The relative displacement d of the block with respect to the ground is positive in the direction
// in which a positive a_h pushes the block: the block's inertial load per unit mass is a_h along +d (d = y - x for a
// level block, y the ground's and x the block's absolute displacement along the acceleration axis). On a slope, +d is
// downslope, so a positive a_h is a ground acceleration toward the uphill side. SLAMMER's rigid-block convention is
// the same: its record as given (normal polarity) slides the block downslope when a > k_y g.
//
// Per unit mass, along the slope (+ downslope) and normal to it:
//   driving  f_t = a_h cos(beta) + g_e sin(beta),        normal  n = g_e cos(beta) - a_h sin(beta)
// Stick while |f_t| <= mu_s n. Sliding in direction s = +1 (down) or -1 (up), kinetic friction opposes it:
//   d'' = f_t - s mu_k n = P_s a_h + Q_s g_e,  P_s = cos(beta) + s mu_k sin(beta),  Q_s = sin(beta) - s mu_k cos(beta)
// which gives the Goodman-Seed yield accelerations (thesis eq 2.2) for g_e = g:
//   downslope  a_h > g tan(phi - beta),   upslope  a_h < -g tan(phi + beta),   tan(phi) = mu.
// On level ground with mu_s = mu_k = mu this is thesis eq 3.9: d'' = a_h - mu g sgn(d').
//
// Method. The input is piecewise linear, so within a step d'' is linear in time, d' quadratic and d cubic: the
// solver integrates exactly. Slip start is the root of a linear function (the stick condition at the step's ends),
// slip stop the smallest root of the quadratic d'(t) = 0, solved in closed form (TOMS 748 on the bracket guards the
// rare case where round-off puts the closed-form root outside it). There is no sub-step and no tolerance: results
// depend on the record only. After the record ends the ground is still (a_h = a_v = 0) and a block that is still
// sliding decelerates to rest, so residual displacements include that run-out.
//
// Modes. two_way: slips both ways. one_way: only downslope (+d) slip is allowed; upslope slip is suppressed, as in
// SLAMMER's rigid-block analysis of slopes and Newmark's one-directional sliding.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

namespace topple {

enum class SlidingMode : std::uint8_t { two_way, one_way };
[[nodiscard]] std::string_view sliding_mode_name(SlidingMode mode);  ///< "two-way", "one-way"
/// "two-way" or "one-way"; throws InputError naming `field` otherwise.
[[nodiscard]] SlidingMode parse_sliding_mode(std::string_view name, const std::string& field = "mode");

/// A friction block. Use make() to validate.
struct SlidingBlock {
  double mu_static = 0.0;       ///< static friction coefficient (dimensionless, typical 0.2-0.7)
  double mu_kinetic = 0.0;      ///< kinetic friction coefficient, 0 <= mu_kinetic <= mu_static
  double slope_rad = 0.0;       ///< plane inclination beta, 0 <= beta < pi/2 (0 = level)
  SlidingMode mode = SlidingMode::two_way;
  double g_m_s2 = kStandardGravity;

  /// Validated block; no mu_kinetic means "equal to mu_static" (the thesis' assumption). Throws InputError for
  /// non-finite values, mu_s < 0, mu_k outside [0, mu_s], slope outside [0, 90) deg, slope + friction angle >= 90
  /// deg, g <= 0.
  [[nodiscard]] static SlidingBlock make(double mu_static, std::optional<double> mu_kinetic = std::nullopt,
                                         double slope_rad = 0.0,
                                         SlidingMode mode = SlidingMode::two_way, double g_m_s2 = kStandardGravity);

  /// Yield accelerations for g_e = g: a_h above yield_down starts downslope slip, below yield_up upslope slip
  /// (m/s^2; yield_up is negative, and -infinity in one-way mode).
  [[nodiscard]] double yield_down_m_s2() const noexcept;
  [[nodiscard]] double yield_up_m_s2() const noexcept;
};

enum class SlipState : std::int8_t { slipping_up = -1, stuck = 0, slipping_down = 1 };

/// Time history on the record's samples plus every event instant (slip start and stop). At an event instant the
/// row carries the state after the event.
struct SlidingHistory {
  std::vector<double> time_s;
  std::vector<double> displacement_m;  ///< d, relative to the ground
  std::vector<double> velocity_m_s;    ///< d'
  std::vector<SlipState> state;
};

struct SlidingSummary {
  double max_abs_displacement_m = 0.0;  ///< max |d| over the response (exact: d is monotone while slipping)
  double max_displacement_time_s = 0.0; ///< first time |d| reaches its maximum (record start when never slipping)
  double residual_displacement_m = 0.0; ///< signed d when the block has come to rest after the record
  double max_abs_velocity_m_s = 0.0;
  int slip_episodes = 0;                ///< number of slip starts from relative rest (a reversal through d' = 0
                                        ///< counts as a new episode)
  std::optional<double> first_slip_time_s;
  double total_slip_duration_s = 0.0;
  double slip_path_m = 0.0;             ///< distance slid, sum over slip episodes of |change of d| (m); on a level
                                        ///< base without vertical input, times mu_k g: the work of friction (J/kg)
  double end_time_s = 0.0;              ///< when the block came to rest (>= record end when it slid past it)
  bool at_rest_at_end = true;           ///< false only when the block can never stop (slope steeper than friction)
  std::optional<double> contact_lost_time_s; ///< first time the normal force n <= 0 (vertical or slope input made
                                             ///< the block leave the plane: the model is not valid after it)
};

struct SlidingResult {
  SlidingSummary summary;
  SlidingHistory history;
};

/// Full response with time history. `vertical` (optional) is the vertical ground acceleration, positive up; it may
/// be sampled on another grid (the union of both grids is used, which is exact for piecewise-linear inputs).
[[nodiscard]] SlidingResult slide(const GroundMotion& horizontal, const SlidingBlock& block,
                                  const GroundMotion* vertical = nullptr);

/// Summary only (no history is stored: this is the fast path for spectra and sweeps).
[[nodiscard]] SlidingSummary slide_summary(const GroundMotion& horizontal, const SlidingBlock& block,
                                           const GroundMotion* vertical = nullptr);

/// Sliding displacement spectrum kernel: the summary for each friction coefficient (mu_s = mu_k = mu) on one
/// record, level or inclined, in the given mode. Equivalent to calling slide_summary per mu, but shares the input
/// stream and skips stick phases by blocks.
[[nodiscard]] std::vector<SlidingSummary> slide_summaries(const GroundMotion& horizontal, std::span<const double> mu,
                                                          double slope_rad = 0.0,
                                                          SlidingMode mode = SlidingMode::two_way,
                                                          double g_m_s2 = kStandardGravity);

}  // namespace topple
