#pragma once
// The main job: from observed objects to bounds and a likelihood map of PGA x predominant frequency.
//
// Method (docs/method.md, "Inversion", has the equations):
// 1. Static bounds (thesis section 1.1). An object that slid needs PGA > mu g / amplification; one that rocked or
//    overturned needs PGA > g a/h / amplification (uplift). An object that did not slide gives PGA <= mu g /
//    amplification. The bounds are the largest lower and the smallest upper bound, with the objects that set them;
//    a lower bound above an upper bound is a contradiction, reported with both objects.
// 2. Dynamic inversion. On a grid of PGA (log-spaced) x predominant frequency (log-spaced), every object is
//    simulated under N motions of the family per cell. The motions of a frequency column are generated once (seeds
//    1..N: common random numbers across cells), time-scaled so that each one's *measured* predominant frequency
//    (spectra.hpp: peak of the Konno-Ohmachi smoothed Fourier amplitude spectrum) is the column's frequency, and
//    scaled to each row's PGA. Uncertain parameters (mu, e, amplification) are drawn per (motion k, object), the same
//    draw in every cell. Each run gives a match m in [0, 1] with the observed outcome (0/1 for categorical outcomes,
//    a Gaussian kernel of the residual displacement for a measured sliding distance).
//    Likelihood: every object saw the same motion, so a cell's likelihood is the average over its motions of the
//    product over objects of q = eps + (1 - 2 eps) m, eps the chance that the observation itself is wrong (0.02
//    certain, 0.10 likely, 0.25 reported: evidence_error_rate). Averaging products keeps the correlation the shared
//    motion induces between objects (assuming independent objects given the cell made the intervals too narrow:
//    26/30 coverage of the 95 % region in the recovery test, against 30/30 now), and eps keeps one unreproduced
//    observation from erasing a cell. The runs of the 3 x 3 neighbouring cells are pooled (weights 4/2/1) to cut
//    the Monte Carlo noise. The prior is uniform in log PGA and log frequency, i.e. the same for every cell of the
//    log grid. Posterior = likelihood x prior, normalised over the grid. Each object's own probability of its
//    observation, P = (sum m + 1/2) / (N + 1) over the same neighbourhood, is reported and drawn as a contour.
// 3. Estimates. Best: the maximum-likelihood cell. Median and equal-tailed 68 % and 95 % credible intervals from each
//    marginal posterior, with the mass of a cell spread uniformly in log over its extent (cell edges at the
//    geometric midpoints of the grid values). An interval end that falls in the first or last cell is reported as
//    unconstrained (null): the observations do not move it off the grid's edge.
// All runs go through the ensemble engine (ensemble.hpp), so a survey uses every core.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "topple/ground_motion.hpp"
#include "topple/survey.hpp"

namespace topple {

struct StaticBound {
  double pga_g = 0.0;
  std::string object_id;
  std::string reason;  ///< e.g. "slid: PGA > mu g = 0.40 g"
};

struct StaticBounds {
  std::optional<double> lower_g;        ///< largest lower bound (none: no object moved)
  std::optional<double> upper_g;        ///< smallest upper bound (none: every object moved)
  std::vector<StaticBound> lower;       ///< every object's lower bound
  std::vector<StaticBound> upper;       ///< every object's upper bound
  std::vector<std::string> contradictions;  ///< "bowl-2 (slid: PGA > 0.45 g) vs box-1 (did not slide: PGA <= 0.30 g)"
};

/// The static bounds of a site (g used for nothing but the wording; bounds are in g).
[[nodiscard]] StaticBounds static_bounds(const Site& site);

/// A marginal estimate; interval ends are null when unconstrained (see the header).
struct Estimate {
  double best = 0.0;    ///< at the maximum-likelihood cell
  double median = 0.0;
  std::optional<double> ci68_low, ci68_high, ci95_low, ci95_high;
};

struct ObjectReport {
  std::string id;
  Outcome outcome = Outcome::not_overturned;
  std::vector<double> probability;  ///< P(observation | cell), per cell (index = i_pga * freq_count + j_freq)
  double probability_at_best = 0.0;
  double max_probability = 0.0;
  bool reproduced_anywhere = true;  ///< some run in some cell matched the observation
};

struct InversionResult {
  std::string site;
  std::vector<double> pga_g;     ///< grid rows
  std::vector<double> freq_hz;   ///< grid columns
  std::vector<double> measured_freq_hz;  ///< mean measured predominant frequency of each column's motions
  std::vector<double> log_likelihood;    ///< per cell, index = i_pga * freq_hz.size() + j_freq
  std::vector<double> posterior;         ///< normalised, same indexing
  std::vector<double> marginal_pga;      ///< sums to 1
  std::vector<double> marginal_freq;
  std::size_t best_cell = 0;
  Estimate pga;                 ///< in g
  Estimate freq;                ///< in Hz
  StaticBounds bounds;
  std::vector<ObjectReport> objects;
  std::vector<std::string> notes;  ///< honesty: what the observations cannot constrain, contradictions
  std::size_t runs = 0;
  double seconds = 0.0;
};

struct InversionOptions {
  int threads = 0;  ///< 0: all cores
};

/// The motions of one frequency column (PGA scaling is applied per row): synthetic motions (seeds 1..N) or the
/// survey's records (both polarities), each time-scaled to the column's measured predominant frequency. Exposed for
/// tests and for the report's example motion. Motions have PGA 1 m/s^2.
[[nodiscard]] std::vector<GroundMotion> family_motions(const InversionSettings& settings, double freq_hz);

/// The inversion of one site.
[[nodiscard]] InversionResult invert_site(const Site& site, const InversionSettings& settings,
                                          const InversionOptions& options = {});

/// Whether (pga_g, freq_hz) lies in the highest-posterior-density region of the given probability (e.g. 0.95):
/// the smallest set of cells, taken by decreasing posterior, whose mass reaches `level`; the point belongs to the cell
/// whose log extent contains it (points outside the grid belong to no cell).
[[nodiscard]] bool in_credible_region(const InversionResult& result, double pga_g, double freq_hz, double level);

/// Per-run match of an object's observation (exposed for tests): simulate `object` with the given parameters under
/// `motion` (already scaled to the cell's PGA) and compare with the observation.
struct DrawnParameters {
  double mu = 0.0;
  double e = 0.0;  ///< used when !object.e_housner
  double amplification = 1.0;
};
[[nodiscard]] double observation_match(const ObservedObject& object, const DrawnParameters& parameters,
                                       const GroundMotion& motion, double g_m_s2);

/// The drawn parameters of object o for motion k (deterministic in seed, k, o; uniform in each range).
[[nodiscard]] DrawnParameters draw_parameters(const ObservedObject& object, std::uint64_t seed, std::size_t k,
                                              std::size_t o);

}  // namespace topple
