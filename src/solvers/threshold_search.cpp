// The first overturning amplitude of a family of motions (scan, then bisection): see threshold_search.hpp.
#include "topple/solvers/threshold_search.hpp"

#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple {

ThresholdResult first_overturning_amplitude(const std::function<GroundMotion(double)>& motion_for,
                                            const RockingBody& body, const RockingOptions& options,
                                            OverturnCriterion criterion, const ThresholdSearch& search) {
  if (!std::isfinite(search.start) || !std::isfinite(search.max) || search.max < search.start) {
    throw parameter_error("search", fmt::format("scan range [{}, {}] is empty or not finite", search.start, search.max));
  }
  require_positive(search.step, "search.step", "scan step");
  require_positive(search.rel_tol, "search.rel_tol", "relative tolerance");
  RockingOptions o = options;
  o.stop_when_alpha_exceeded = criterion == OverturnCriterion::exceeds_alpha;
  ThresholdResult result;
  const auto overturns = [&](double amplitude) {
    if (++result.runs > search.max_runs) {
      throw SearchLimitError(fmt::format("first_overturning_amplitude: more than max_runs = {} runs (scan {} to {} "
                                         "by {}, rel_tol = {:.3g}): raise max_runs or narrow the scan",
                                         search.max_runs, search.start, search.max, search.step, search.rel_tol));
    }
    const RockingSummary s = rock_summary(motion_for(amplitude), body, o);
    return criterion == OverturnCriterion::falls ? s.overturned : s.exceeded_alpha_time_s.has_value();
  };
  double below = search.start;
  bool have_below = false;
  std::optional<double> above;
  for (std::size_t k = 0;; ++k) {
    const double amplitude = search.start + static_cast<double>(k) * search.step;
    if (amplitude > search.max * (1.0 + 1e-12)) break;
    if (overturns(amplitude)) {
      above = amplitude;
      break;
    }
    below = amplitude;
    have_below = true;
  }
  if (!above) {
    result.below = below;
    return result;
  }
  if (!have_below) {  // the first amplitude tried already overturns
    result.amplitude = above;
    result.below = *above;
    return result;
  }
  double hi = *above;
  double lo = below;
  while (hi - lo > search.rel_tol * std::abs(hi)) {
    const double mid = 0.5 * (lo + hi);
    if (overturns(mid)) {
      hi = mid;
    } else {
      lo = mid;
    }
  }
  result.amplitude = hi;
  result.below = lo;
  return result;
}

}  // namespace topple

