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
// Bidirectional sliding spectrum. Under a pair of horizontal components (and an optional vertical) the block slides
// in two dimensions (sliding2d.hpp): for each mu (level ground, two-way, mu_s = mu_k = mu) the spectrum is
// slide_2d_summary on the set, the same call `topple slide H1 --h2 H2 --mu mu` makes, so each point equals that run
// exactly. The yield acceleration is mu g in every direction; its abscissa k_y g / PGA uses the pair's RotD50 PGA
// (Boore 2010, rotd.hpp; the orientation-independent PGA `topple info H1 H2` reports and `synth --components 2`
// scales to). Beside each point, each horizontal component run alone by the 1-D solver with the same block and the
// vertical (slide_summary): how much a one-component analysis of either record misses or overstates.
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

#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/core/progress.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/core/units.hpp"

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

/// One friction coefficient of the bidirectional sliding spectrum.
struct SlidingSpectrum2dPoint {
  double mu = 0.0;                   ///< friction coefficient (static = kinetic)
  double yield_accel_g = 0.0;        ///< k_y = mu (level ground), in g
  double yield_over_rotd50_pga = 0.0;  ///< mu g / RotD50 PGA (dimensionless; 0 for a zero pair)
  Sliding2dSummary bidirectional;    ///< the 2-D run (slide_2d_summary)
  SlidingSummary first_alone;        ///< the first component alone, 1-D (slide_summary, with the vertical)
  SlidingSummary second_alone;       ///< the second component alone, same
};

struct SlidingSpectrum2d {
  double rotd50_pga_m_s2 = 0.0;      ///< the pair's RotD50 PGA (rotd.hpp), the spectrum's PGA axis
  double first_pga_m_s2 = 0.0;       ///< each component's own PGA
  double second_pga_m_s2 = 0.0;
  ComponentAzimuths azimuths;        ///< the components' azimuths, degrees clockwise from north
  bool with_vertical = false;
  double g_m_s2 = kStandardGravity;
  std::vector<SlidingSpectrum2dPoint> points;  ///< in the order of the mu given
};

/// The bidirectional spectrum over `mu` (each finite, >= 0) of a set with two horizontal components and known
/// azimuths. Throws InputError naming "mu" (with the value; also for an empty list), "g", or "second" / "azimuths"
/// for a set without them.
[[nodiscard]] SlidingSpectrum2d sliding_spectrum_2d(const MotionSet& set, std::span<const double> mu,
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
