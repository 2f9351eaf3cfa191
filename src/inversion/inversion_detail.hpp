#pragma once
// Internals of the inversion shared by inversion.cpp (one component) and inversion_3c.cpp (three components).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/inversion/matching.hpp"
#include "topple/inversion/inversion_3c.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/survey/population.hpp"

namespace topple::detail {

/// A 64-bit hash of two numbers (SplitMix64 of a * golden + b): the seeds of motion k and object o.
[[nodiscard]] std::uint64_t mix(std::uint64_t a, std::uint64_t b);

/// The synthesis of motion k of a synthetic family's column (inversion.hpp): 20 samples per period of the column's
/// frequency (at most 0.01 s), at least 8 periods, seed mix(settings.seed, k + 1) in every column.
[[nodiscard]] SynthesisSpec family_spec(const InversionSettings& settings, double freq_hz, int k);

/// The three-component synthesis of motion k (inversion_3c.hpp, item 1): family_spec with a step of 1 / (20 f_v)
/// (at most 0.01 s), the survey's coherence, components called east (first) and north (second), a vertical.
[[nodiscard]] SynthesisSetSpec family_set_spec(const InversionSettings& settings, double freq_hz, int k);

/// tan(alpha) of a body's uplift threshold g tan(alpha) in a static threshold: an asymmetric body's smaller one for a
/// lower threshold (it rocked), its larger one for an upper threshold (it did not), the weaker claim.
[[nodiscard]] double uplift_tan_alpha(const RockingBody& body, bool lower);
/// Fills the aggregates of the per-object thresholds b.lower and b.upper: lower_g, upper_g, their hard ones, and the
/// contradictions (a lower threshold above an upper one).
void settle_static_bounds(StaticBounds& b);

/// The marginal estimate of an axis (inversion.hpp, item 3): median and equal-tailed intervals from a marginal over
/// the log cells of `values`, `best` the axis value of the maximum-likelihood cell.
[[nodiscard]] Estimate marginal_estimate(const std::vector<double>& values, const std::vector<double>& marginal,
                                         double best);

/// The 3 x 3 neighbourhood of a cell with weights 4/2/1 (inversion.hpp, item 2).
[[nodiscard]] std::vector<std::pair<std::size_t, double>> neighbourhood(std::size_t c, std::size_t np,
                                                                        std::size_t nf);

// ---- The one pipeline (invert_sites, inversion.cpp) ----

/// The grid's PGA rows (g) and frequency columns (Hz): log-spaced over the settings' ranges.
[[nodiscard]] std::vector<double> pga_axis(const InversionSettings& settings);
[[nodiscard]] std::vector<double> freq_axis(const InversionSettings& settings);
/// eps_o of every object of the site (survey.hpp, evidence_error_rate), in the site's order.
[[nodiscard]] std::vector<double> evidence_error_rates(const Site& site);

/// Outcomes of "what to look for next" (evidence.hpp, suggest_next_objects) that the survey's runs already computed
/// (performance only: the same numbers, fewer runs). A catalogue object whose run is the same computation as a survey
/// object's (same_rocking_run: the same body, restitution, no support filter, factor 1) under a bit-identical motion
/// (the survey's motion scaled_to_pga(target) equals the ranking's scaled(target) when target / peak == target) has
/// the survey run's outcome category recorded here, so the ranking does not run it again.
struct CatalogueShare {
  std::size_t cells = 0;  ///< the grid's cells
  std::size_t nk = 0;     ///< motions k < nk of each cell are recorded (kCatalogueMotions or fewer)
  /// Per catalogue object x (household_catalogue()): the index of its block in `outcome`, or -1 when not shared.
  std::vector<std::ptrdiff_t> block;
  /// outcome[(block * cells + c) * nk + k]: catalogue_outcome's category, or kNotRecorded.
  std::vector<std::uint8_t> outcome;
  static constexpr std::uint8_t kNotRecorded = 255;
  [[nodiscard]] std::uint8_t at(std::size_t x, std::size_t c, std::size_t k) const {
    if (x >= block.size() || block[x] < 0 || k >= nk) return kNotRecorded;
    return outcome[(static_cast<std::size_t>(block[x]) * cells + c) * nk + k];
  }
};

/// True when the rocking run of `a` with parameters pa is the same computation as that of `b` with pb (both the rigid
/// rocking model, no support filter, rocking_plane_factor 1, equal bodies and restitution): then the two objects'
/// summaries under one motion are identical.
[[nodiscard]] bool same_rocking_run(const ObservedObject& a, const DrawnParameters& pa, const ObservedObject& b,
                                    const DrawnParameters& pb, double g_m_s2);

/// simulate_matches, recording the catalogue outcomes it can share into *share (null: none recorded).
[[nodiscard]] MatchTable simulate_matches(const Site& site, const InversionSettings& settings,
                                          const std::vector<double>& pga_g, const FamilyGrid& family,
                                          const InversionOptions& options, CatalogueShare* share);

/// suggest_next_objects with the outcomes of `share` used instead of runs where recorded (null: every run made).
[[nodiscard]] std::vector<NextObject> suggest_next_objects(const InversionResult& result,
                                                           const InversionSettings& settings,
                                                           const FamilyGrid& family, const InversionOptions& options,
                                                           const CatalogueShare* share);

/// What the runs of a motion family give the pipeline for one site. The direction axis: one component has one bin;
/// three components (inversion_3c.hpp) have settings.directions bins and the family's own facts.
struct SiteRuns {
  StaticBounds bounds;                         ///< the static thresholds on the PGA axis of the estimates
  std::optional<StaticBounds> rotd100_bounds;  ///< components = 3: the thresholds on RotD100, where they hold
  std::vector<MatchTable> bins;                ///< the matches of every direction bin
  std::vector<ObjectModel> models;             ///< per object: the model its runs used (matching.hpp)
  std::size_t runs = 0;                        ///< solver runs done
  /// components = 3: the family's facts (ratios, coherence, rho, kappa); the pipeline adds the direction estimate.
  std::optional<ThreeComponentResult> three_component;
  std::vector<double> direction_bins_deg;      ///< components = 3: the bins' centres, deg
  std::vector<std::string> notes;              ///< the family's own notes, after the common ones
  /// The prior (prior.hpp): ln per cell, empty for log-uniform; and its name (survey.hpp, inversion_prior_name).
  std::vector<double> log_prior;
  std::string prior = "log-uniform";
  /// The site's populations (population_likelihood.cpp): per (bin b, cell c, motion k), index
  /// (b * cells + c) * motions + k, the log of the populations' multinomial likelihoods (eq. P1, docs/method.md; with
  /// three components, their fall directions too, eq. P2), added to each run's product over objects; empty: no
  /// population. And their reports, model_fraction filled.
  std::vector<double> population_run_log;
  std::vector<PopulationReport> populations;
  /// The catalogue objects' outcomes that the survey's own runs gave on the way (CatalogueShare).
  CatalogueShare catalogue_share;
  /// family = "mixture": the member family of each motion k (FamilyGrid::member); empty for a single family.
  std::vector<MotionFamily> member;
};

// ---- family = "mixture" (family_mixture.cpp; docs/method.md, "A mixture of the two families") ----

/// A member's prior weight w_f (1/2 for each of synthetic and boore2003).
[[nodiscard]] double mixture_prior_weight(MotionFamily member);
/// The mixture's own rule: an even motions_per_cell (N/2 motions of each member) and a grid both members accept
/// (each member's validate_inversion_settings with N/2 motions).
void validate_mixture_settings(const InversionSettings& settings);
/// The column's motions: member k % 2's motion k / 2 (synthetic, boore2003, synthetic, ...), each as family_motions
/// makes it for that member with N/2 motions.
[[nodiscard]] std::vector<GroundMotion> mixture_family_motions(const InversionSettings& settings, double freq_hz);
/// Fills family.member and family.draw_index for the alternation above (draw index k / 2).
void label_mixture_members(FamilyGrid& family);
/// Each member's prior and posterior weight (inversion.hpp, FamilyWeight) from the mixture's match table of one bin:
/// member f's likelihood L_f(c) is reduce_likelihood over its motions alone, Z_f = sum_c prior(c) L_f(c) with the
/// prior normalised over the grid (log_prior; empty: uniform), P(f | data) = w_f Z_f / sum_g w_g Z_g.
[[nodiscard]] std::vector<FamilyWeight> mixture_family_weights(const MatchTable& matches,
                                                               const std::vector<MotionFamily>& member,
                                                               const std::vector<double>& error_rates,
                                                               const double* population_run_log,
                                                               const std::vector<double>& log_prior);
/// The note that says what the mixture was and what the objects made of its members.
[[nodiscard]] std::string mixture_note(const std::vector<FamilyWeight>& weights);

// ---- Populations (population_likelihood.cpp; docs/method.md, "Populations of objects") ----


/// The runs of every population's members: per population its member count K and the members' shares in each
/// category per (cell, motion), index ((c * motions + k) * 4 + category); run_log the sum over populations of
/// population_log_likelihood per (cell, motion).
struct PopulationRuns {
  std::size_t motions = 0;
  std::vector<std::size_t> members;
  std::vector<std::vector<double>> shares;
  std::vector<double> run_log;
  std::size_t runs = 0;
};
[[nodiscard]] PopulationRuns simulate_populations(const Site& site, const InversionSettings& settings,
                                                  const std::vector<double>& pga_g, const FamilyGrid& family,
                                                  const InversionOptions& options);
/// The populations' reports with model_fraction (the mean over each cell's motions of the overturned share).
[[nodiscard]] std::vector<PopulationReport> population_reports(const Site& site, const PopulationRuns& runs,
                                                               std::size_t cells);
/// The reports' fractions at the estimate and posterior-predictive, once the posterior is known.
void finish_population_reports(InversionResult& result);

/// Steps 2 of one component: static_bounds and simulate_matches (one bin).
[[nodiscard]] SiteRuns simulate_site(const Site& site, const InversionSettings& settings,
                                     const std::vector<double>& pga_g, const FamilyGrid& family,
                                     const InversionOptions& options);
/// Steps 2 of three components (inversion_3c.cpp): static_bounds_3c and the runs at every direction bin.
[[nodiscard]] SiteRuns simulate_site_3c(const Site& site, const InversionSettings& settings,
                                        const std::vector<double>& pga_g, const FamilyGrid3c& family,
                                        const InversionOptions& options);

/// Steps 3-5 for either: per bin reduce_likelihood; the cell's log-likelihood, log of the bins' mean; the objects'
/// probabilities (the bins' mean); fill_posterior_and_estimates; assess_objects over the joint (cell, bin) posterior;
/// the notes; with three components the direction estimate (inversion_3c.hpp, item 5). Not `seconds`.
[[nodiscard]] InversionResult infer_site(const Site& site, const std::vector<double>& pga_g,
                                         const std::vector<double>& freq_hz,
                                         const std::vector<double>& measured_freq_hz, SiteRuns runs);

/// Step 4b (inversion.hpp, item 4) over the direction axis: posterior_predictive = sum over (cell, bin) of the
/// posterior times the share of the cell's runs that match; constraint_bits the KL divergence, over (cell, bin), from
/// the posterior without the object. ll_joint and posterior_joint: index c * bins + b.
void assess_objects(InversionResult& result, const std::vector<MatchTable>& bins,
                    const std::vector<double>& error_rates, const std::vector<double>& ll_joint,
                    const std::vector<double>& posterior_joint,
                    const std::vector<double>* population_run_log = nullptr);

/// reduce_likelihood (inversion.hpp, step 3) with the populations' log-likelihood per (cell, motion) as one more
/// factor of every run (none: nullptr, the public function).
[[nodiscard]] LikelihoodReduction reduce_likelihood(const MatchTable& matches, const std::vector<double>& error_rates,
                                                    const double* population_run_log);

}  // namespace topple::detail
