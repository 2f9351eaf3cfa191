#pragma once
// Object spectra: the response of a family of objects to one motion, as a function of the object's parameter.
//
// Sliding displacement spectrum (Newmark 1965; Franklin & Chang 1977; Mittal 1971, ch. 3). For one record and a
// list of friction coefficients mu (mu_s = mu_k = mu), the maximum |d| and the residual d of a friction block
// (sliding.hpp, its sign convention and modes). The yield acceleration of the block for downslope slip is
//   k_y g = g tan(phi - beta),  tan(phi) = mu            (thesis eq 2.2; level ground: k_y = mu)
// and the spectrum is also expressed against k_y g / PGA (the abscissa of Newmark-type charts). mu_for_yield_ratio
// inverts that relation: mu = tan(beta + atan(r PGA / g)). The spectrum runs slide_summaries (the many-mu kernel of
// sliding.hpp), which equals one slide_summary per mu.
//
// Overturning map (Housner 1963; Makris & Roussos 2000; Mittal 1971, section 3.5). A family of bodies of one shape
// and fixed slenderness alpha = atan(a / h), of varying size: full height H = 2h, so that h = H / 2, a = h tan(alpha),
// R = h / cos(alpha) and p = sqrt(g R / D) falls as the body grows (a larger body of the same alpha is more stable,
// Housner's scale effect). The motion is scaled to each PGA of a grid, and each (PGA, size) pair is run with
// rock_summary (rocking.hpp). The result is the boolean map overturned(PGA, size) and, for each size, the
// first-overturn PGA: the smallest PGA of the grid at which the body falls. Overturning is not monotone in the
// amplitude (a stronger motion can throw the body onto its other edge at a time when the next pulse brings it back),
// so the map is kept and each size also reports whether some PGA above its first-overturn PGA leaves it standing.
// A body cannot lift off while PGA <= g tan(alpha) (rocking.hpp, uplift condition), so no grid point below that
// overturns. Runs are spread over all cores by the ensemble engine (ensemble.hpp); a run ends when the body falls.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "topple/ground_motion.hpp"
#include "topple/progress.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"
#include "topple/units.hpp"

namespace topple {

// ---- Sliding displacement spectrum ----

struct SlidingSpectrumPoint {
  double mu = 0.0;                        ///< friction coefficient (static = kinetic)
  double yield_accel_g = 0.0;             ///< downslope yield acceleration k_y (in g): tan(phi - beta)
  double yield_over_pga = 0.0;            ///< k_y g / PGA (dimensionless)
  double max_abs_displacement_m = 0.0;    ///< max |d|, m
  double residual_displacement_m = 0.0;   ///< signed d at rest after the record, m
  int slip_episodes = 0;
  double total_slip_duration_s = 0.0;
  bool at_rest_at_end = true;             ///< false when the slope is steeper than friction (block never stops)
};

struct SlidingSpectrum {
  double pga_m_s2 = 0.0;  ///< of the motion as run
  double slope_rad = 0.0;
  SlidingMode mode = SlidingMode::two_way;
  double g_m_s2 = kStandardGravity;
  std::vector<SlidingSpectrumPoint> points;  ///< in the order of the mu given
};

/// The spectrum over `mu` (each finite, >= 0, and with atan(mu) + slope < 90 deg). Throws InputError naming "mu"
/// (with the offending value) or "slope", and for an empty list.
[[nodiscard]] SlidingSpectrum sliding_spectrum(const GroundMotion& motion, std::span<const double> mu,
                                               double slope_rad = 0.0, SlidingMode mode = SlidingMode::two_way,
                                               double g_m_s2 = kStandardGravity);

/// The friction coefficient whose downslope yield acceleration is `ratio` x PGA: tan(beta + atan(ratio PGA / g)).
/// Throws InputError naming "ky_over_pga" when ratio < 0 or not finite, or the angle reaches 90 deg.
[[nodiscard]] double mu_for_yield_ratio(double ratio, double pga_m_s2, double slope_rad = 0.0,
                                        double g_m_s2 = kStandardGravity);

// ---- Overturning map ----

/// A body family: shape (block or cylinder), slenderness and sizes. Heights are full heights (2h), m.
struct BodyFamily {
  RockingBody::Shape shape = RockingBody::Shape::block;  ///< block or cylinder (general is refused)
  double alpha_rad = 0.0;           ///< slenderness atan(a / h), in (0, pi/2); typical 0.1-0.4
  std::vector<double> heights_m;    ///< full heights 2h, > 0 (any order; reported in the given order)

  /// The body of size index i: block of width 2a and height 2h, or cylinder of diameter 2a and height 2h.
  [[nodiscard]] RockingBody body(std::size_t i) const;
};

struct OverturningMapOptions {
  RockingOptions rocking;  ///< solver options for every run (g is rocking.g_m_s2)
  int threads = 0;         ///< 0: every core (ensemble engine)
  ProgressCallback progress{};  ///< runs done / to do (progress.hpp); empty: none
};

/// Per size of the family.
struct OverturningSize {
  double height_m = 0.0;   ///< full height 2h
  double width_m = 0.0;    ///< full width 2a (diameter for a cylinder)
  double R_m = 0.0;
  double p_rad_s = 0.0;
  std::optional<double> first_overturn_pga_m_s2;  ///< smallest grid PGA that overturns it (none: never on the grid)
  bool standing_above_first = false;  ///< some grid PGA above the first-overturn PGA leaves the body standing
  std::size_t overturn_count = 0;     ///< grid PGAs that overturn it
};

struct OverturningMap {
  std::vector<double> pga_m_s2;       ///< the amplitude grid, ascending
  std::vector<OverturningSize> sizes; ///< in the family's order
  /// overturned[s * pga_m_s2.size() + k]: size s under PGA k.
  std::vector<std::uint8_t> overturned;
  /// max |theta| / alpha of each run, same layout (>= 1 where the CM passed over the pivot).
  std::vector<double> max_rotation_over_alpha;
  double alpha_rad = 0.0;
  RockingBody::Shape shape = RockingBody::Shape::block;
  double g_m_s2 = kStandardGravity;

  [[nodiscard]] bool at(std::size_t size_index, std::size_t pga_index) const {
    return overturned[size_index * pga_m_s2.size() + pga_index] != 0;
  }
};

/// Runs the motion scaled to every PGA of `pga_m_s2` (> 0; sorted ascending in the result) on every body of the
/// family. Throws InputError naming "alpha", "height", "pga", "shape", or the RockingOptions field, and for a
/// motion that is identically zero.
[[nodiscard]] OverturningMap overturning_map(const GroundMotion& motion, const BodyFamily& family,
                                             std::span<const double> pga_m_s2,
                                             const OverturningMapOptions& options = {});

/// Grids: n values from lo to hi, evenly (linear) or geometrically (log) spaced; n = 1 gives {lo}. Throws
/// InputError naming `field` for n < 1, lo > hi, non-finite ends, or lo <= 0 on a log grid.
[[nodiscard]] std::vector<double> linear_grid(double lo, double hi, std::size_t n, const char* field = "grid");
[[nodiscard]] std::vector<double> log_grid(double lo, double hi, std::size_t n, const char* field = "grid");

}  // namespace topple
