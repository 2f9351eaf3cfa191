#pragma once
// The first overturning amplitude of a family of ground motions (e.g. a pulse of growing amplitude): a scan, then a
// bisection on the rocking engine's summary (rocking.hpp). Overturning is not monotone in the amplitude, so the search
// brackets the first change of outcome only.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>

#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {

enum class OverturnCriterion : std::uint8_t {
  exceeds_alpha,  ///< |theta| >= alpha at some time (the CM passes over the pivot)
  falls,          ///< |theta| reaches pi/2
};

struct ThresholdSearch {
  double start = 0.0;          ///< first amplitude tried (caller's unit, e.g. m/s^2 or a multiple of g tan(alpha))
  double step = 0.0;           ///< scan increment (> 0): windows of survival narrower than this may be missed
  double max = 0.0;            ///< last amplitude of the scan (>= start)
  double rel_tol = 1e-7;       ///< bisection stops when the bracket is narrower than rel_tol * amplitude
  std::size_t max_runs = 100000;  ///< cap on response computations; throws past it
};

struct ThresholdResult {
  std::optional<double> amplitude;  ///< first overturning amplitude (upper end of the final bracket); none if
                                    ///< nothing up to max overturns
  double below = 0.0;               ///< largest amplitude known not to overturn just below it
  std::size_t runs = 0;
};

/// The smallest amplitude that overturns by the criterion: scan upward from start in increments of step to the
/// first amplitude that overturns, then bisect between it and the previous scan point. Bisection only keeps a
/// bracket whose ends differ in outcome, so it needs no monotonicity: it converges to a change of outcome inside
/// the first scan interval that overturns. `motion_for(amplitude)` builds the horizontal motion.
[[nodiscard]] ThresholdResult first_overturning_amplitude(const std::function<GroundMotion(double)>& motion_for,
                                                          const RockingBody& body, const RockingOptions& options,
                                                          OverturnCriterion criterion, const ThresholdSearch& search);

}  // namespace topple
