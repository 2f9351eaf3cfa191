#pragma once
// Populations of similar objects (survey.hpp, Population; docs/survey.md "Populations"; docs/method.md "Populations of
// objects"): the checks of a population's counts and sizes, and the K representative members the inversion simulates.
#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "topple/survey/survey.hpp"

namespace topple {

/// The most representative members a population may ask for (`members`): each costs the runs of one object.
inline constexpr int kMaxPopulationMembers = 200;

/// The category of a member's run: stayed, rocked (visibly, stood), slid (visibly, stood; coupled model), overturned
/// (docs/method.md, "Populations of objects").
enum class PopulationCategory { stayed = 0, rocked = 1, slid = 2, overturned = 3 };
inline constexpr std::size_t kPopulationCategories = 4;

/// ln P(counts | shares) (eq. P1, docs/method.md): the multinomial over overturned, rocked (if counted), slid (if
/// counted) and the rest, the model's share f_j of each (`share`, indexed by PopulationCategory; the rest takes
/// 1 - the counted ones' shares) floored by the population's evidence error rate eps: p_j = eps + (1 - J eps) f_j.
[[nodiscard]] double population_log_likelihood(const Population& population, std::span<const double> share);

/// Checks a population read by io::read_survey: counts (count >= 1; overturned, rocked, slid >= 0; their sum <= count),
/// fallen azimuths (at most `overturned`, each in [0, 360)), sizes (a range or a sample for each dimension the shape
/// needs, every size positive, a sample's sizes inside the stated ranges when both are given, a sample not empty),
/// members in [1, kMaxPopulationMembers]. Throws parameter_error(field, problem), field the survey key ("overturned",
/// "sample[3].height", ...).
void check_population(const Population& population);

/// The K representative members of a population as objects (the prototype with the member's body; outcome
/// overturned), by the stated deterministic rule (docs/method.md, "Populations of objects"):
///  - a measured sample of n <= K members: the sample itself;
///  - a sample of n > K: sorted by slenderness b/h (width or diameter over height, the quantity that sets the
///    overturning threshold g b/h), the member at the middle of each of K equal strata (index floor((i + 1/2) n / K));
///  - stated ranges: K stratified quantiles (i + 1/2) / K of the height's range, and of the width's (diameter's) at
///    the permuted stratum (i * s) mod K, s the stride nearest 0.618 K coprime to K (a fixed Latin hypercube: every
///    stratum of each dimension once, the pairs spread over the square rather than along its diagonal).
[[nodiscard]] std::vector<ObservedObject> population_members(const Population& population);

/// The smallest slenderness b/h (width or diameter over height) in the class: of the sample when measured, else the
/// smallest base over the largest height of the ranges. g b/h is the lowest uplift threshold of any member (Housner).
[[nodiscard]] double population_min_slenderness(const Population& population);

/// The rule population_members used, in words (for the JSON and the report).
[[nodiscard]] std::string population_member_rule(const Population& population);

}  // namespace topple
