#pragma once
// The regional picture: many sites, one earthquake (issue 17; docs/method.md, "Regional joint inversion").
//
// Model. Every site s (objects, an instrument, or both) saw a PGA a_s (g) that follows an attenuation relation with
// hypocentral distance R_s (km) and a between-site scatter:
//     ln a_s = c0 - c1 ln sqrt(R_s^2 + c2^2) + delta_s,   delta_s ~ N(0, tau^2) independent,       (R1)
// c2 (km, the near-source saturation term) fixed at RegionalSettings::c2_km: a dozen sites scattered by tau ~ 0.5
// cannot resolve it (it moves ln a by less than tau beyond R = 2 c2). The fit is parametrised by the PGA at a
// reference distance, ln a_ref = c0 - c1 ln rho_ref (rho_ref = geometric mean of the sites' sqrt(R^2 + c2^2)), which
// makes the two parameters nearly uncorrelated; c0 = ln a_ref + c1 ln rho_ref is reported.
// Priors (weak, stated): uniform on the box ln a_ref in [ln 0.001, ln 10] (g), c1 in [0, 3], tau in [0.02, 1.5].
//
// Each site's evidence. A site with objects enters through its own likelihood over its PGA grid (what invert_site
// computes), marginalised over its frequency axis with its own prior (uniform in log frequency): L_i = mean_j
// exp(log_likelihood_ij), constant in ln a over the cell i (edges at the geometric midpoints of the grid values; the
// edge cells extended to 0 and infinity: beyond its grid a site's likelihood is taken as its edge cell's). A
// measured PGA (an instrument station) is a lognormal observation, ln a_obs ~ N(ln a_s, sigma_i^2), sigma_i =
// RegionalSettings::instrument_sigma_ln (0.05: the record's instrument and processing). A station with objects carries
// both (they are independent observations of one PGA). A macroseismic intensity (intensity.hpp, issue 30) is the same
// kind of lognormal observation, its median and sigma from the conversion (WGRW12 and ShakeMap's few-reports term,
// eqs. I2-I3); a site with an instrument and an intensity carries their product, one normal in ln a with the
// precision-weighted mean and 1 / sigma^2 = 1 / sigma_instrument^2 + 1 / sigma_intensity^2 (the factor that does not
// depend on a_s is dropped: it moves no posterior).
//
// Method: grid integration. Given (mu_s, tau) with mu_s = ln a_ref - c1 (ln rho_s - ln rho_ref), each site's marginal
// likelihood integral over ln a_s is closed form (normal CDFs over its cells; docs/method.md eq. R3), so the joint
// posterior over (ln a_ref, c1, tau) is evaluated on a grid: a coarse pass over the whole prior box finds where the
// posterior lives (log posterior within 20 of the maximum), a fine pass covers that box. Intervals are equal-tailed
// from the fine grid's marginals. Each site's pooled PGA posterior, p(a_s | all sites), is the posterior average of
// its conditional p(a_s | theta, own evidence), computed as a CDF on a fine ln a grid over draws of theta taken from
// the fine grid by systematic resampling (deterministic).
//
// Frequency (docs/method.md eqs. F1-F3). The predominant period grows with distance (Rathje, Abrahamson & Bray 1998;
// Rathje, Faraj, Russell & Bray 2004: their mean and predominant periods rise with R at a given magnitude), so the
// sites' predominant frequencies f_s (Hz) may follow
//     ln f_s = d0 + d1 ln sqrt(R_s^2 + c2^2) + eps_s,   eps_s ~ N(0, tau_f^2) independent,           (F1)
// (the PGA relation's geometric term, where Rathje et al. use a term linear in R: over 5-100 km the two differ by less
// than the scatter). Each site with objects enters through its likelihood over its frequency cells, PGA marginalised
// with the inversion's own prior (uniform in log PGA) (F2). The two relations are fitted separately: the coupling of
// PGA and frequency inside a site's likelihood is not carried between them (an approximation). F1 is fitted with the
// same grid integration as R1 over (ln f_ref, d1, tau_f), uniform priors on RegionalSettings' box, and compared with
// the constant model (d1 = 0) by the Bayes factor B = Z1 / Z0 of their marginal likelihoods Z = (1 / V_prior)
// integral L dtheta (F3, trapezoid rule on the fine grid). The relation is "supported" when B >= 3 (Kass & Raftery
// 1995); only then are the sites' frequencies pooled through it. Z1 carries the Occam factor of d1's prior width (4).
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/region/intensity.hpp"

namespace topple {

/// What the joint fit needs from one site.
struct SiteEvidence {
  std::string name;
  double distance_km = 0.0;  ///< hypocentral distance R_s, km
  /// Cell edges in ln(PGA / g), size cells + 1 (first -inf, last +inf); empty: no objects (an instrument only).
  std::vector<double> ln_edges;
  std::vector<double> likelihood;  ///< per cell, dimensionless, scaled so that its maximum is 1
  std::optional<double> instrument_pga_g;  ///< a measured PGA, g
  std::optional<IntensityPga> intensity;   ///< a macroseismic intensity through its conversion (intensity.hpp)
  /// The same over ln(frequency / Hz), PGA marginalised (header, "Frequency"); empty: no objects (flat).
  std::vector<double> ln_freq_edges;
  std::vector<double> freq_likelihood;  ///< per frequency cell, dimensionless, maximum 1
};

/// A site's evidence from its inversion (frequency marginalised, header) and/or its instrument.
[[nodiscard]] SiteEvidence site_evidence(const std::string& name, double distance_km, const InversionResult* objects,
                                         std::optional<double> instrument_pga_g,
                                         const std::optional<SiteIntensity>& intensity = std::nullopt);

struct RegionalSettings {
  double c2_km = 6.0;                ///< fixed saturation distance, km (header)
  double ln_a_ref_min = -6.907755278982137, ln_a_ref_max = 2.302585092994046;  ///< prior box, ln(g): 0.001-10 g
  double c1_min = 0.0, c1_max = 3.0;    ///< prior box, dimensionless
  double tau_min = 0.02, tau_max = 1.5;  ///< prior box, natural-log units
  double instrument_sigma_ln = 0.05;     ///< a measured PGA's lognormal sigma
  int fine_points = 41;                  ///< fine grid points per parameter
  int draws = 1000;                      ///< theta draws for the pooled site posteriors
  /// The frequency relation's prior box (header, "Frequency"): ln f_ref in ln(0.1 Hz)..ln(50 Hz), d1 in [-2, 2],
  /// tau_f in [0.02, 1.5] (natural-log units).
  double ln_f_ref_min = -2.302585092994046, ln_f_ref_max = 3.912023005428146;
  double d1_min = -2.0, d1_max = 2.0;
  double tau_f_min = 0.02, tau_f_max = 1.5;
  /// The Bayes factor B = Z(relation) / Z(constant) from which the frequency relation counts as supported: 3, the
  /// lower end of "positive" evidence in Kass & Raftery (1995, section 3.2).
  double frequency_bayes_factor = 3.0;
};

/// A posterior summary: median and equal-tailed 68 % / 95 % intervals, in the unit of the quantity.
struct Interval95 {
  double median = 0.0, ci68_low = 0.0, ci68_high = 0.0, ci95_low = 0.0, ci95_high = 0.0;
  [[nodiscard]] bool holds95(double x) const noexcept { return ci95_low <= x && x <= ci95_high; }
};

/// The frequency relation (header, "Frequency"): ln f_s = d0 + d1 ln sqrt(R_s^2 + c2^2) + eps_s, eps_s ~ N(0, tau_f^2),
/// against the constant model ln f_s = ln f_c + eps_s, by their marginal likelihoods (Bayes factor).
struct FrequencyRelation {
  Interval95 d0;        ///< ln(Hz)
  Interval95 d1;        ///< dimensionless (negative: the frequency falls with distance)
  Interval95 tau;       ///< tau_f, natural-log units
  Interval95 ln_f_ref;  ///< ln(Hz) at RegionalResult::reference_distance_km
  Interval95 constant_f_hz;  ///< the constant model's frequency f_c, Hz
  Interval95 constant_tau;   ///< the constant model's tau_f, natural-log units
  double log_evidence_relation = 0.0;  ///< ln Z(relation): ln of the prior-averaged likelihood (dimensionless ratio)
  double log_evidence_constant = 0.0;  ///< ln Z(constant)
  double ln_bayes_factor = 0.0;        ///< ln Z(relation) - ln Z(constant)
  bool supported = false;              ///< ln_bayes_factor >= ln RegionalSettings::frequency_bayes_factor
  std::size_t sites_with_frequency = 0;  ///< sites whose objects give a frequency likelihood over > 1 cell
  std::vector<std::string> notes;        ///< a parameter against its prior's edge
};

struct PooledSite {
  std::string name;
  std::size_t site_index = 0;        ///< index into Survey::sites (fit_survey_region) or into the evidence (fit_region)
  double distance_km = 0.0;          ///< hypocentral, km
  Interval95 pga_g;                  ///< the pooled PGA posterior, g
  Interval95 relation_pga_g;         ///< the relation's median prediction exp(mu_s) at this distance, g
  std::optional<double> instrument_pga_g;
  std::optional<IntensityPga> intensity;  ///< the site's intensity and its PGA through the conversion, if any
  /// The pooled frequency posterior and the frequency relation's prediction, Hz: only when the relation is supported.
  std::optional<Interval95> freq_hz;
  std::optional<Interval95> relation_freq_hz;
};

struct RegionalResult {
  Interval95 c0;        ///< ln(g)
  Interval95 c1;        ///< dimensionless
  Interval95 tau;       ///< natural-log units
  Interval95 ln_a_ref;  ///< ln(g) at reference_distance_km
  double c2_km = 0.0;   ///< fixed, km
  double reference_distance_km = 0.0;  ///< rho_ref = geometric mean of sqrt(R^2 + c2^2), km
  std::vector<PooledSite> sites;       ///< in the order of the evidence
  std::vector<std::string> notes;      ///< what the data cannot constrain (a parameter against its prior's edge)
  /// The frequency relation and its comparison with a constant frequency (header); none when fewer than 3 sites
  /// have a frequency likelihood over more than one frequency (a note says so).
  std::optional<FrequencyRelation> frequency;
  /// The relation's median PGA exp(mu(R)) with its posterior intervals on 40 log-spaced distances from 1 km (or the
  /// nearest site) to 1.5 x the farthest: the attenuation figure's band.
  std::vector<double> curve_distance_km;
  std::vector<Interval95> curve_pga_g;
  std::size_t grid_points = 0;         ///< fine-grid points evaluated
};

/// The joint fit (header). Needs at least 3 sites; InputError naming "region" otherwise.
[[nodiscard]] RegionalResult fit_region(const std::vector<SiteEvidence>& sites, const RegionalSettings& settings = {});

/// The relation's median PGA (g) at hypocentral distance R (km) for given parameters: exp(c0 - c1 ln sqrt(R^2+c2^2)).
[[nodiscard]] double relation_pga_g(double c0, double c1, double c2_km, double distance_km) noexcept;

/// A calibration site: does the instrument's PGA lie inside the objects' own 95 % interval (an unconstrained end
/// counts as open)?
[[nodiscard]] bool objects_agree_with_instrument(const Estimate& objects_pga_g, double instrument_pga_g) noexcept;

}  // namespace topple
