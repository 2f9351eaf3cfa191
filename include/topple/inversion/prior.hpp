#pragma once
// The prior on (PGA, predominant frequency) of the inversion ([inversion] prior; docs/method.md, "Priors").
//
// "log-uniform" (the default): uniform in ln PGA and ln f over the grid; log_prior is empty and the posterior is
// today's to the bit.
// "earthquake": p(ln A, ln f) = E_{M,R}[ N(ln A; mu_A(M, R, Vs30), sigma_A) N(ln f; -ln Tm(M, R), sigma_T) ] with the
// event known, E_{M,R}[ N(ln f; -ln Tm(M, R), sigma_T) ] without it (see below), where
//   - mu_A, sigma_A: BSSA14 for PGA (motion/bssa14.hpp) at R_JB = R; Vs30 the site's (vs30_m_s or site_class), else
//     760 m/s (BSSA14's reference rock). BSSA14 predicts RotD50; it is used for the one-component PGA axis as is
//     (the median of a single horizontal component and RotD50 differ by a few per cent: an approximation).
//   - Tm: the mean period of Rathje, Abrahamson & Bray (1998) as used by Bray & Rathje (1998) for rock sites and by
//     USGS SLAMMER (Jibson et al. 2013): Tm = 0.411 + 0.0837 (min(M, 7.25) - 6) + 0.00208 r (s, r in km), sigma_ln
//     0.437. The axis is the peak f_p of the smoothed Fourier spectrum, Tm the spectrum-weighted mean period: on the
//     25 real records of shared/records f_p Tm has a geometric mean 0.70 and sigma_ln 0.33 (docs/verification.md,
//     measured with spectra.hpp's own f_p and Tm), so ln f_p ~ N(ln 0.70 - ln Tm, sqrt(0.437^2 + 0.33^2)).
//   - ln A and ln f independent given (M, R) (their residual correlation is neglected).
//   - Without the event: the frequency part alone (uniform in ln A), mixed over M uniform on [4.5, 7.5] (no
//     Gutenberg-Richter weighting: a survey follows an earthquake large enough to move things, which a b = 1
//     weighting towards small events ignores) and R log-uniform on [5, 200] km, by the midpoint rule (31 x 41 nodes).
//     The PGA part is left out because those weak priors know nothing of why the survey was made: measured on the
//     real-record recovery test (docs/verification.md), with it the PGA medians fell from 0.93 to 0.76 of the truth.
//   - With [event] magnitude: both parts, M fixed; with the site's epicentral distance too, R fixed: R_JB =
//     epicentral distance (a point source), r = hypocentral distance for Tm; without a distance, R as above.
//   Evaluated at the cell centres (the grid's values): the grid is log-spaced, so a density in (ln A, ln f) at the
//   centre is the cell's mass up to the common cell area and the error of the centre rule.
#include <optional>
#include <string>
#include <vector>

#include "topple/survey/survey.hpp"

namespace topple {

/// Median mean period Tm (s) and its sigma_ln (Bray & Rathje 1998; see above). magnitude M, distance_km r >= 0.
struct MeanPeriodModel {
  double median_s = 0.0;
  double sigma_ln = 0.0;
};
[[nodiscard]] MeanPeriodModel mean_period_rathje(double magnitude, double distance_km);

/// The weak priors on M and R without the event, and the Vs30 used when a site gives none.
inline constexpr double kPriorMagnitudeMin = 4.5;
inline constexpr double kPriorMagnitudeMax = 7.5;
inline constexpr double kPriorDistanceMinKm = 5.0;
inline constexpr double kPriorDistanceMaxKm = 200.0;
inline constexpr double kPriorDefaultVs30MS = 760.0;
/// f_p Tm on the 25 real records of shared/records (geometric mean) and its sigma_ln (see above).
inline constexpr double kFpTmRatio = 0.70;
inline constexpr double kFpTmRatioSigmaLn = 0.33;

/// The earthquake prior's natural log per cell (index i_pga * freq_hz.size() + j_freq), its maximum 0, at the cells'
/// centres pga_g (g) x freq_hz (Hz). site gives vs30_m_s and epicentral_distance_km; event, the magnitude and depth.
[[nodiscard]] std::vector<double> earthquake_log_prior(const std::vector<double>& pga_g,
                                                       const std::vector<double>& freq_hz, const Site& site,
                                                       const std::optional<EventSource>& event);

/// The prior the settings ask for: empty for log-uniform (InversionResult::log_prior's convention).
[[nodiscard]] std::vector<double> log_prior_for(const std::vector<double>& pga_g, const std::vector<double>& freq_hz,
                                                const Site& site, const InversionSettings& settings);

/// A short sentence saying which prior was used and on what (for the notes).
[[nodiscard]] std::string prior_description(const Site& site, const InversionSettings& settings);

}  // namespace topple
