#pragma once
// The output of a fragility analysis (fragility.hpp), one writer for every front end: the field table of a fitted
// curve (kFragilityFitFields, as kSlidingFields is a solver summary's), the JSON object `topple fragility --json`
// prints, and the CSV table of `topple fragility --out`. Python's topple.fragility builds its dict from the same
// result (its FragilityFit properties are the table's names, checked by python/tests/test_docstrings.py).
#include <array>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "topple/core/field.hpp"
#include "topple/fragility/fragility.hpp"
#include "topple/output/plot.hpp"

namespace topple {

/// A curve's fit as it is shown: theta in the IM's display unit (g for PGA), with that unit.
struct FragilityFitShown {
  const LognormalFragilityFit& fit;
  double display_factor;  ///< intensity_measure_display_factor: SI to the display unit
  std::string_view unit;  ///< intensity_measure_unit
};

/// theta, theta_unit, beta, se_ln_theta, se_beta, cov_ln_theta_beta, log_likelihood, beta_at_bound: the "fit"
/// object of a curve, in this order.
extern const std::array<Field<FragilityFitShown>, 8> kFragilityFitFields;

}  // namespace topple

namespace topple::io {

/// What the fragility's JSON says besides the result: the IM as asked, gravity, the ensemble's names, the band's
/// level and (pairs) how the bearings were chosen.
struct FragilityJsonContext {
  std::string im;                  ///< the IM's name as given (pga, pgv, pgd, cav)
  double g_m_s2 = kStandardGravity;
  std::vector<std::string> motions;
  double band_level = 0.95;
  std::string bearing_rule;        ///< pairs only
};

/// The IM's column and key name: im_rotd50_pga_g for pairs, else intensity_measure_column.
[[nodiscard]] std::string fragility_im_column(const FragilityResult& result);

/// The object `topple fragility --json` prints: im, im_unit, (pairs: im_definition, bearing, bearings_deg), g_m_s2,
/// motions, runs, band_level, band_method, curves [{curve, levels [{<im column>, trials, failures}], fit
/// (kFragilityFitFields) or null with fit_note}].
[[nodiscard]] nlohmann::ordered_json fragility_json(const FragilityResult& result, const FragilityJsonContext& context);

/// The table of `topple fragility --out`: curve,<im column>,trials,failures,fraction,fitted_probability,band_lower,
/// band_upper, one row per curve and level (the last three empty without a fit).
void write_fragility_csv(std::ostream& out, const FragilityResult& result, double g_m_s2, double band_level);

// ---- As recorded (fragility.hpp, "As recorded"): `topple fragility --as-recorded` ----

/// The functional form of the surface, in words, as the JSON and the text state it.
inline constexpr std::string_view kFragilitySurfaceForm =
    "P = Phi((ln PGA - ln theta(v)) / beta), ln theta(v) = ln theta_ref + gamma ln(v / v_ref), v = PGV/PGA: a probit "
    "in ln PGA whose median moves as a power of PGV/PGA (the variables of Purvance, Anooshehpoor & Brune 2008, EESD "
    "37), maximum likelihood on the binary outcomes";

/// A surface fit as JSON: form, theta_ref_g, ln_theta_ref_g, gamma, beta, v_ref_s, se_ln_theta_ref, se_gamma,
/// se_beta, covariance (of ln theta_ref, gamma, beta), log_likelihood, records, failures, iterations.
[[nodiscard]] nlohmann::ordered_json fragility_surface_json(const FragilitySurfaceFit& fit, double g_m_s2);

/// The object `topple fragility --as-recorded --json` prints: mode "as-recorded", g_m_s2, runs, records [{motion,
/// pga_g, pgv_m_s, pgv_over_pga_s, <curve>_failed...}], curves [{curve, failures, surface (fragility_surface_json)
/// or null with fit_note}].
[[nodiscard]] nlohmann::ordered_json as_recorded_json(const AsRecordedResult& result,
                                                      const std::vector<std::string>& motions, double g_m_s2);

/// The table of `topple fragility --as-recorded --out`: motion,pga_g,pgv_m_s,pgv_over_pga_s, then per curve
/// <curve>_failed (0/1) and <curve>_probability (the fitted surface at the record; empty without a fit).
void write_as_recorded_csv(std::ostream& out, const AsRecordedResult& result, const std::vector<std::string>& motions,
                           double g_m_s2);

/// The surface of `result.curves[curve]`: P over PGV/PGA x PGA (log axes, the records' range widened by 1.3 each
/// way), its 10, 50 and 90 % contours (straight lines on these axes) and the records as points, failed or not.
/// Without a fit, the points only over P = 0.
[[nodiscard]] plot::MapFigure fragility_surface_figure(const AsRecordedResult& result, std::size_t curve,
                                                       double g_m_s2, const std::string& title);

}  // namespace topple::io
