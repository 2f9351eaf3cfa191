#pragma once
// The objects' own evidence beside the prior, the trade-off between PGA and frequency, and what to look for next
// (issue 32; docs/method.md, "The objects' own evidence", "The ridge", "What to look for next").
//
// 1. The likelihood estimate: exp(log_likelihood) normalised over the grid is the posterior under the log-uniform
//    prior; its marginals and Estimates (median, 68/95 % intervals, the same rules as the posterior's) say what the
//    objects alone say. With log_prior empty they equal the posterior's exactly.
// 2. The ridge (pga_given_freq): per frequency column j, the likelihood of that column normalised over PGA,
//    L(i | j) = L(i, j) / sum_i L(i, j), and its median and 68 % / 95 % intervals: the PGA the outcomes need if the
//    frequency is known to be f_j. A column whose likelihood mass sum_i L(i, j) is below kRidgeNegligibleShare of the
//    largest column's gives none.
// 3. What to look for next: for a catalogue object x with outcomes y (overturned / rocked / stood; slid / not),
//    EIG_axis(x) = H(p_axis) - sum_y P(y) H(p_axis | y), the mutual information between y and the axis' marginal
//    (Lindley 1956, "On a measure of the information provided by an experiment", Ann. Math. Statist. 27, eq. for
//    the expected gain), with P(y) = sum_c p(c) P(y | c) and p(c | y) = p(c) P(y | c) / P(y), p the posterior over
//    the cells holding 99.9 % of its mass (renormalised), P(y | c) from the catalogue object's runs under the family's
//    first kCatalogueMotions motions of each cell (parameters drawn per motion), pooled over the 3 x 3 neighbourhood
//    (weights 4/2/1) as the likelihood is, smoothed (share N + 1/2) / (N + K/2). Entropies in bits over the grid's
//    cells of the axis.
#include <cstddef>
#include <string>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// The marginals of a per-cell distribution over an np x nf grid (index i * nf + j): over PGA (size np) and over
/// frequency (size nf).
[[nodiscard]] std::vector<double> marginal_over_pga(const std::vector<double>& cells, std::size_t np, std::size_t nf);
[[nodiscard]] std::vector<double> marginal_over_freq(const std::vector<double>& cells, std::size_t np,
                                                     std::size_t nf);

/// The prior normalised over the grid from result.log_prior (uniform when empty), per cell.
[[nodiscard]] std::vector<double> prior_cells(const InversionResult& result);

/// Item 1 and 2: fills marginal_*_likelihood, pga_likelihood_g, freq_likelihood_hz and pga_given_freq from
/// result.log_likelihood and the axes.
void fill_likelihood_estimates(InversionResult& result);

/// The ridge alone (item 2), from a log-likelihood over the grid (index i * nf + j).
[[nodiscard]] std::vector<PgaGivenFreq> ridge_pga_given_freq(const std::vector<double>& log_likelihood,
                                                             const std::vector<double>& pga_g,
                                                             const std::vector<double>& freq_hz);

/// Expected information gain (bits) of an observation with outcomes y on each axis' marginal (item 3).
struct InformationGain {
  double bits_pga = 0.0;
  double bits_freq = 0.0;
};
/// posterior: per cell (index i * nf + j), sums to 1; outcome_probability[y][c] = P(y | c), summing to 1 over y in
/// every cell. Never negative (rounding below 0 is returned as 0).
[[nodiscard]] InformationGain expected_information_gain(const std::vector<double>& posterior, std::size_t np,
                                                        std::size_t nf,
                                                        const std::vector<std::vector<double>>& outcome_probability);

/// An entry of the household catalogue (catalogue.cpp): a body and a friction range from the documentation's tables
/// (the row cited in `source`), observed either as a rocking body (overturned / rocked / stood still) or as a sliding
/// one (slid / not), on a rigid support with amplification 1.
struct CatalogueObject {
  std::string name;         ///< "wine bottle"
  std::string description;  ///< size and base in words
  ObservedObject object;    ///< shape, dimensions, mu range, model (rock or slide); the outcome is not used
  std::string source;       ///< the documentation row it comes from
};
[[nodiscard]] const std::vector<CatalogueObject>& household_catalogue();

/// The outcome categories of a catalogue object for one run: rocking 0 overturned, 1 rocked visibly and stood,
/// 2 stood without visible rocking; sliding 0 slid visibly (>= 2 mm), 1 not. `motion` is scaled to the cell's PGA.
/// A model = "3d" object runs the three-dimensional engine (rigid3d.hpp; a cylinder the rim engine, rigid3d_disc.hpp)
/// with the motion along its +x axis, its tilt in place of |theta|.
[[nodiscard]] std::size_t catalogue_outcome(const ObservedObject& object, const DrawnParameters& parameters,
                                            const GroundMotion& motion, double g_m_s2);
[[nodiscard]] std::size_t catalogue_outcome_count(const ObservedObject& object);

/// The motions per cell that the catalogue objects are run under (the family's first ones; fewer if it has fewer).
inline constexpr std::size_t kCatalogueMotions = 10;

/// Item 3 for every catalogue object, ranked by bits_pga + bits_freq (largest first): the runs of each object under
/// the family's motions in the cells holding 99.9 % of result.posterior.
[[nodiscard]] std::vector<NextObject> suggest_next_objects(const InversionResult& result,
                                                           const InversionSettings& settings,
                                                           const FamilyGrid& family,
                                                           const InversionOptions& options = {});

/// The summary's clause on the objects' own evidence ("; the objects alone: ...") when the likelihood's median or
/// 68 % interval differs from the posterior's by more than the two digits the summary shows; empty otherwise.
[[nodiscard]] std::string likelihood_summary_clause(const InversionResult& result);
/// The summary's clause on what to look for next; empty when no object adds 0.05 bit.
[[nodiscard]] std::string next_objects_summary_clause(const InversionResult& result);

}  // namespace topple
