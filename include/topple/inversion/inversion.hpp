#pragma once
// The main job: from observed objects to bounds and a likelihood map of PGA x predominant frequency.
//
// Method (docs/method.md, "Inversion", has the equations):
// 1. Static thresholds (thesis section 1.1). An object that slid needs PGA > mu g / amplification; one that rocked
//    or overturned needs PGA > g a/h / amplification (uplift); on a flexible support the amplification is also
//    multiplied by max_peak_amplification(zeta_low) (flexible.hpp), the most such a support can raise any peak (and
//    it gives no upper threshold). An object that did not slide gives PGA <= mu g / amplification. The "bounds" are the largest lower and the smallest upper threshold, with the objects that set
//    them; a lower threshold above an upper one is a contradiction, reported with both objects.
//    Hard and soft: a lower threshold is hard (the physics forbids the observation below it: no slip while
//    |a| <= mu g, no uplift while |a| <= g a/h); the upper threshold of an object that did not slide *visibly* is
//    soft: the ground may pass mu g for an instant and slip the object less than the visible 2 mm (kVisibleSlipM),
//    so a dynamic estimate may lie above it. Only the observation being wrong (the evidence model) crosses a hard one.
// 2. Dynamic inversion. On a grid of PGA (log-spaced) x predominant frequency (log-spaced), every object is
//    simulated under N motions of the family per cell. The motions of a frequency column are generated once (seeds
//    1..N: common random numbers across cells), time-scaled so that each one's *measured* predominant frequency
//    (spectra.hpp: peak of the Konno-Ohmachi smoothed Fourier amplitude spectrum) is the column's frequency, and
//    scaled to each row's PGA. Uncertain parameters (mu, e, amplification, a flexible support's frequency and damping)
//    are drawn per (motion k, object), the same draw in every cell. An object on a flexible support (survey.hpp:
//    SupportFilter) is simulated on the support's absolute acceleration (flexible.hpp: support_motion) of the cell's
//    motion: the filter is linear, so common random numbers hold across cells as for rigid supports. Each run gives a match m in [0, 1] with the observed outcome (0/1 for categorical outcomes,
//    a Gaussian kernel of the residual displacement for a measured sliding distance).
//    Likelihood: every object saw the same motion, so a cell's likelihood is the average over its motions of the
//    product over objects of q = eps + (1 - 2 eps) m, eps the chance that the observation itself is wrong (0.02
//    certain, 0.10 likely, 0.25 reported: evidence_error_rate). Averaging products keeps the correlation the shared
//    motion induces between objects (assuming independent objects given the cell made the intervals too narrow:
//    26/30 coverage of the 95 % region in the recovery test, against 30/30 now), and eps keeps one unreproduced
//    observation from erasing a cell. The runs of the 3 x 3 neighbouring cells are pooled (weights 4/2/1) to cut
//    the Monte Carlo noise. The prior ([inversion] prior): "log-uniform" (the default), uniform in log PGA and log
//    frequency, i.e. the same for every cell of the log grid; "earthquake", a seismological prior (prior.hpp,
//    docs/method.md "Priors"). Posterior = likelihood x prior, normalised over the grid. Each object's own probability
//    of its observation, P = (sum m + 1/2) / (N + 1) over the same neighbourhood, is reported and drawn as a contour.
// 3. Estimates. Best: the maximum-likelihood cell (it moves with the seed: a diagnostic, not the headline). Median and equal-tailed 68 % and 95 % credible intervals from each
//    marginal posterior, with the mass of a cell spread uniformly in log over its extent (cell edges at the
//    geometric midpoints of the grid values). An interval end that falls in the first or last cell is reported as
//    unconstrained (null): the observations do not move it off the grid's edge.
// 4. Objects (assess_objects). Each object's posterior-predictive probability of its observation,
//    P_pp = sum over cells of posterior(c) x (the share of the cell's runs that match it, sum m / N); below kMisfitProbability the
//    object is a misfit: the answer does not explain it, and the notes and the summary name it. Each object's
//    constraint: the information its observation adds to the others', the Kullback-Leibler divergence (bits) of the
//    posterior from the posterior without that object (its eps set to 1/2, which makes its factor a constant).
// All runs go through the ensemble engine (ensemble.hpp), so a survey uses every core.
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "topple/inversion/direction.hpp"
#include "topple/inversion/matching.hpp"
#include "topple/core/progress.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// One object's static threshold on PGA (g). The names say "bound" for the old readers; a soft one is not a bound.
struct StaticBound {
  double pga_g = 0.0;
  std::string object_id;
  std::string reason;  ///< e.g. "slid: PGA > mu g = 0.40 g", with the amplification used when not 1
  bool hard = false;   ///< hard: physics forbids the observation on the other side; soft: see the header, item 1
};

struct StaticBounds {
  std::optional<double> lower_g;        ///< largest lower threshold, hard or soft (none: no object moved)
  std::optional<double> upper_g;        ///< smallest upper threshold, hard or soft (none: every object moved)
  std::optional<double> hard_lower_g;   ///< largest hard lower threshold (none: no hard evidence from below)
  std::optional<double> hard_upper_g;   ///< smallest hard upper threshold (no outcome gives one today)
  std::vector<StaticBound> lower;       ///< every object's lower threshold
  std::vector<StaticBound> upper;       ///< every object's upper threshold
  std::vector<std::string> contradictions;  ///< "bowl-2 (slid: PGA > 0.45 g) vs box-1 (did not slide: PGA <= 0.30 g)"
};

/// The static bounds of a site (g used for nothing but the wording; bounds are in g).
[[nodiscard]] StaticBounds static_bounds(const Site& site);

/// A marginal estimate. Every value is in the unit of the axis it estimates, named by the member that holds it:
/// InversionResult::pga_estimate_g (g) and InversionResult::freq_estimate_hz (Hz). Interval ends are null when
/// unconstrained (see the header).
struct Estimate {
  double best = 0.0;    ///< the axis value of the maximum-likelihood cell (g or Hz, see above)
  double median = 0.0;  ///< the marginal posterior's median (g or Hz)
  std::optional<double> ci68_low, ci68_high, ci95_low, ci95_high;  ///< equal-tailed credible intervals (g or Hz)
  /// -1 / +1 when the median (best) lies in the grid's first / last cell: then it is no estimate, only "below" or
  /// "above the grid"; 0 inside.
  int median_edge = 0;
  int best_edge = 0;
};

/// The posterior-predictive probability below which an object's observation counts as a misfit (dimensionless): the
/// answer gives it less than a 1-in-20 chance. A measured sliding distance scores the Gaussian kernel (1 at the
/// observed distance, 0.61 one sigma off), so the level is low enough for it too.
inline constexpr double kMisfitProbability = 0.05;

struct ObjectReport {
  std::string id;
  Outcome outcome = Outcome::not_overturned;
  ObjectModel model = ObjectModel::rock;  ///< the model it was simulated with (survey.hpp, object_model)
  std::vector<double> probability;  ///< P(observation | cell), dimensionless; index i_pga * freq_count + j_freq
  double probability_at_best = 0.0;  ///< dimensionless
  double max_probability = 0.0;      ///< dimensionless
  bool reproduced_anywhere = true;  ///< some run in some cell matched the observation
  double posterior_predictive = 0.0;  ///< sum_c posterior(c) (sum_k m / N in cell c), dimensionless (header, item 4)
  bool misfit = false;                ///< posterior_predictive < kMisfitProbability
  double constraint_bits = 0.0;       ///< KL divergence of the posterior from the one without this object, bits
};

/// The PGA that the objects need at one frequency column (the ridge, docs/method.md "The objects' own evidence"): the
/// likelihood of that column alone, normalised over the PGA axis (no prior), its median and 68 % interval (g). None
/// where the column holds a negligible share of the likelihood (kRidgeNegligibleShare of the largest column's).
struct PgaGivenFreq {
  double freq_hz = 0.0;              ///< the column, Hz
  double likelihood_share = 0.0;     ///< the column's likelihood mass / the largest column's (dimensionless)
  std::optional<Estimate> pga_g;     ///< median and 68 % / 95 % interval ends (g); none: negligible column
};

/// A column whose likelihood mass is below this share of the largest column's gives no ridge point (dimensionless):
/// the objects say nothing about PGA there beyond "not this frequency".
inline constexpr double kRidgeNegligibleShare = 1e-3;

/// One more object worth looking for (evidence.hpp, suggest_next_objects): the expected information gain of seeing
/// what happened to a catalogue object, on PGA and on frequency (bits; docs/method.md, "What to look for next").
struct NextObject {
  std::string object;       ///< the catalogue's name, e.g. "wine bottle"
  std::string description;  ///< its size and base, e.g. "cylinder 6 cm x 30 cm on wood (mu 0.25-0.5)"
  std::string look_for;     ///< what to check: "whether it fell or rocked" / "whether it slid"
  double bits_pga = 0.0;    ///< EIG on the PGA marginal, bits (>= 0)
  double bits_freq = 0.0;   ///< EIG on the frequency marginal, bits (>= 0)
};

/// A population's observation and what the model says of it (docs/method.md, "Populations of objects").
struct PopulationReport {
  std::string id;
  int count = 0;
  int overturned = 0;
  std::optional<int> rocked, slid;
  std::size_t members = 0;             ///< K, the representative members simulated
  std::string member_rule;             ///< how they were chosen ("the measured sample", "stratified quantiles ...")
  double observed_fraction = 0.0;      ///< overturned / count
  /// The model's overturned fraction per cell (mean over the cell's motions and the K members), dimensionless; index
  /// i_pga * freq_count + j_freq.
  std::vector<double> model_fraction;
  double model_fraction_at_estimate = 0.0;  ///< model_fraction at the cell of the median PGA and median frequency
  double posterior_predictive_fraction = 0.0;  ///< sum_c posterior(c) model_fraction(c)
};

/// family = "mixture" (docs/method.md, "A mixture of the two families"): one member family's prior weight w_f and
/// posterior weight P(f | data) = w_f Z_f / sum_g w_g Z_g, Z_f = sum_c prior(c) L_f(c) the family's evidence over
/// the grid (Hoeting, Madigan, Raftery & Volinsky 1999, eq. 2), both dimensionless.
struct FamilyWeight {
  std::string family;          ///< the member's name ("synthetic", "boore2003")
  double prior_weight = 0.0;   ///< w_f
  double posterior_weight = 0.0;  ///< P(f | data); the members' sum to 1
};

struct InversionResult {
  std::string site;
  /// The motion family that made the likelihood (survey.hpp, motion_family_name).
  std::string family = "synthetic";
  /// family = "mixture": each member's prior and posterior weight (FamilyWeight); empty for a single family.
  std::vector<FamilyWeight> family_weights;
  std::vector<double> pga_g;     ///< grid rows, g
  std::vector<double> freq_hz;   ///< grid columns, Hz
  std::vector<double> measured_freq_hz;  ///< mean measured predominant frequency of each column's motions, Hz
  std::vector<double> log_likelihood;    ///< natural log, per cell, index = i_pga * freq_hz.size() + j_freq
  /// The prior, natural log per cell up to a constant, same indexing as log_likelihood; empty: uniform over the log
  /// grid (prior = "log-uniform"). inversion/prior.hpp computes it; the posterior is likelihood x exp(log_prior).
  std::vector<double> log_prior;
  std::string prior = "log-uniform";     ///< which prior made the posterior (survey.hpp, inversion_prior_name)
  std::vector<double> posterior;         ///< normalised (dimensionless), same indexing
  std::vector<double> marginal_pga;      ///< sums to 1
  std::vector<double> marginal_freq;     ///< sums to 1
  std::size_t best_cell = 0;
  Estimate pga_estimate_g;      ///< PGA, in g
  Estimate freq_estimate_hz;    ///< predominant frequency, in Hz
  StaticBounds bounds;
  std::vector<ObjectReport> objects;
  std::vector<PopulationReport> populations;  ///< the site's populations (empty: none, and no "populations" key)
  std::vector<std::string> notes;  ///< honesty: what the observations cannot constrain, contradictions
  std::size_t runs = 0;
  double seconds = 0.0;         ///< wall-clock time of the inversion, s
  /// [inversion] components = 3 (inversion_3c.hpp): the PGA axis is RotD50, and the direction of strongest shaking;
  /// none for the one-component model.
  std::optional<ThreeComponentResult> three_component;
  /// components = 3: the static thresholds on RotD100 PGA, the axis on which they hold (inversion_3c.hpp, item 6);
  /// `bounds` then holds their exact, weaker consequence on RotD50, the PGA axis of the estimates. None: one component.
  std::optional<StaticBounds> rotd100_bounds;
  /// The objects' own evidence (docs/method.md, "The objects' own evidence"): the likelihood normalised over the grid
  /// (the posterior under the log-uniform prior), its marginals (each sums to 1) and estimates (g, Hz). Equal to the
  /// posterior's when log_prior is empty.
  std::vector<double> marginal_pga_likelihood;
  std::vector<double> marginal_freq_likelihood;
  Estimate pga_likelihood_g;
  Estimate freq_likelihood_hz;
  /// The ridge: per frequency column, the PGA the objects need there (PgaGivenFreq).
  std::vector<PgaGivenFreq> pga_given_freq;
  /// What to look for next, ranked by bits_pga + bits_freq (evidence.hpp); empty when not computed (components = 3,
  /// or InversionOptions::next_objects false).
  std::vector<NextObject> next_objects;
};

struct InversionOptions {
  int threads = 0;  ///< worker threads, >= 0 (0: all cores)
  /// Runs done / to do of the simulation step (progress.hpp), per site; empty: none.
  ProgressCallback progress{};
  /// Rank the household catalogue by the information one more observation would add (evidence.hpp); it costs runs
  /// of the catalogue objects in the posterior's cells (CLI: --no-next-objects turns it off).
  bool next_objects = true;
};

/// Checks options before any work: InputError naming "--threads" for a negative thread count.
void validate_inversion_options(const InversionOptions& options);

/// Checks settings before any work: InputError naming the field ("inversion.pga_g", "inversion.freq_hz",
/// "inversion.motions_per_cell", "inversion.duration_s", "inversion.g_m_s2", "inversion.records"). For the synthetic
/// family, both ends of the frequency axis must be frequencies the synthesis can make (synthesis.hpp: 0.2 to 20 Hz)
/// with the family's own step and duration. io::read_survey calls it and adds the file and line.
void validate_inversion_settings(const InversionSettings& settings);

/// The motions of one frequency column (PGA scaling is applied per row): synthetic motions (seeds 1..N) or the
/// survey's records (settings.record_motions, loaded at the edge by io::read_survey: the core reads no file), each
/// with both polarities and each time-scaled to the column's measured predominant frequency. Exposed for tests and for
/// the report's example motion. Motions have PGA 1 m/s^2.
[[nodiscard]] std::vector<GroundMotion> family_motions(const InversionSettings& settings, double freq_hz);

/// The inversion of one site: family, runs, likelihood, estimates and notes (the steps below, in that order). One
/// pipeline for one and three components: three components (inversion_3c.hpp) differ in the family (a motion set)
/// and the runs (one match table per direction bin); the steps after the runs are the same.
[[nodiscard]] InversionResult invert_site(const Site& site, const InversionSettings& settings,
                                          const InversionOptions& options = {});

/// Every site of a survey with the same settings: the family (the same motions for every site) is built once and
/// shared, which gives the same results as invert_site per site without synthesising the motions again.
[[nodiscard]] std::vector<InversionResult> invert_sites(const std::vector<Site>& sites,
                                                        const InversionSettings& settings,
                                                        const InversionOptions& options = {});

// ---- The steps of invert_site (each exposed for its own tests) ----

/// Step 1, the family: the motions of every frequency column, shared read-only by the runs, and each column's mean
/// measured predominant frequency (Hz; a check of the time scaling).
struct FamilyGrid {
  std::vector<std::vector<std::shared_ptr<const GroundMotion>>> motions;  ///< [column j][motion k]
  std::vector<double> freq_hz;                                            ///< the columns' frequencies, Hz
  std::vector<double> measured_freq_hz;                                   ///< per column, Hz
  /// family = "mixture": per motion k of a column (the same in every column), the member family it comes from and
  /// the index its uncertain parameters are drawn with (draw_parameters), the member's own motion index, so that
  /// each member's runs are those of that family alone with motions_per_cell / 2. Empty for a single family: motion k
  /// is drawn with k.
  std::vector<MotionFamily> member;
  std::vector<std::size_t> draw_index;
  [[nodiscard]] std::size_t motions_per_column() const noexcept { return motions.empty() ? 0 : motions.front().size(); }
  [[nodiscard]] std::size_t draw_of(std::size_t k) const { return draw_index.empty() ? k : draw_index[k]; }
};
[[nodiscard]] FamilyGrid build_family(const InversionSettings& settings, const std::vector<double>& freq_hz,
                                      const InversionOptions& options = {});

/// The match m in [0, 1] of every run (dimensionless): cell c = i_pga * freq_count + j_freq, motion k, object o.
struct MatchTable {
  std::size_t pga_count = 0, freq_count = 0, motions = 0, objects = 0;
  std::vector<double> match;  ///< index ((c * motions) + k) * objects + o
  [[nodiscard]] std::size_t cells() const noexcept { return pga_count * freq_count; }
  [[nodiscard]] double at(std::size_t cell, std::size_t k, std::size_t o) const {
    return match[(cell * motions + k) * objects + o];
  }
};

/// Step 2, the plan and its runs: every object of `site` under every motion of `family` scaled to every PGA of
/// `pga_g` (g), with the parameters drawn per (motion k, object) by draw_parameters: the same draw in every cell.
[[nodiscard]] MatchTable simulate_matches(const Site& site, const InversionSettings& settings,
                                          const std::vector<double>& pga_g, const FamilyGrid& family,
                                          const InversionOptions& options = {});

/// Step 3, the likelihood reduction (header, item 2): per cell, the log of the average over the 3 x 3 neighbourhood's
/// motions (weights 4/2/1) of the product over objects of eps_o + (1 - 2 eps_o) m; and per object its smoothed
/// probability of the observation (sum m + 1/2) / (N + 1) over the same neighbourhood. `error_rates` holds eps_o of
/// each object (evidence_error_rate). Fills log_likelihood and objects[o].probability / max_probability /
/// reproduced_anywhere (ids and outcomes are the caller's).
struct LikelihoodReduction {
  std::vector<double> log_likelihood;  ///< per cell (natural log)
  std::vector<std::vector<double>> probability;  ///< [object][cell], dimensionless
  std::vector<double> max_probability;           ///< per object
  std::vector<bool> reproduced_anywhere;         ///< per object: some run of some cell matched (m > 0)
};
[[nodiscard]] LikelihoodReduction reduce_likelihood(const MatchTable& matches, const std::vector<double>& error_rates);

/// Step 4, the posterior (uniform prior over the log grid), its marginals, the best cell and the estimates, from
/// result.log_likelihood, result.pga_g and result.freq_hz.
void fill_posterior_and_estimates(InversionResult& result);

/// Step 4b (header, item 4): each object's posterior_predictive, misfit and constraint_bits, from the posterior, the
/// objects' probabilities and the likelihood without each object (reduce_likelihood with its eps set to 1/2).
void assess_objects(InversionResult& result, const MatchTable& matches, const std::vector<double>& error_rates);

/// The objects that constrain the answer most: up to three, by decreasing constraint_bits, each at least 0.1 bit
/// (a tenth of what one yes/no answer can carry); indices into result.objects.
[[nodiscard]] std::vector<std::size_t> most_constraining_objects(const InversionResult& result);

/// The plain sentence that opens every summary (CLI, JSON "summary", report): the median PGA and frequency with their
/// 68 % and 95 % intervals (an open end or an edge cell said as "below/above the grid"), the objects that constrain
/// it most, and the misfits by name. The maximum-likelihood cell is not in it.
[[nodiscard]] std::string inversion_summary(const InversionResult& result);

/// Step 5, the notes: what the observations cannot constrain (no static lower/upper bound, interval ends at the grid's
/// edges), static contradictions, observations no run reproduced, misfits (assess_objects) by name, and observations
/// that contradict each other in every cell. Needs result.bounds, estimates, objects and best_cell.
[[nodiscard]] std::vector<std::string> inversion_notes(const InversionResult& result, const MatchTable& matches);

/// Whether (pga_g, freq_hz) lies in the highest-posterior-density region of the given probability (e.g. 0.95):
/// the smallest set of cells, taken by decreasing posterior, whose mass reaches `level`; the point belongs to the cell
/// whose log extent contains it (points outside the grid belong to no cell).
[[nodiscard]] bool in_credible_region(const InversionResult& result, double pga_g, double freq_hz, double level);

}  // namespace topple
