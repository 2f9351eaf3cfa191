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

}  // namespace topple::io
