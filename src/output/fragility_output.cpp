#include "topple/output/fragility_output.hpp"

#include <fmt/format.h>

#include "topple/output/write.hpp"

namespace topple {

const std::array<Field<FragilityFitShown>, 8> kFragilityFitFields{{
    {"theta", [](const FragilityFitShown& f) -> FieldValue { return f.fit.theta * f.display_factor; }},
    {"theta_unit", [](const FragilityFitShown& f) -> FieldValue { return std::string(f.unit); }},
    {"beta", [](const FragilityFitShown& f) -> FieldValue { return f.fit.beta; }},
    {"se_ln_theta", [](const FragilityFitShown& f) -> FieldValue { return f.fit.se_ln_theta; }},
    {"se_beta", [](const FragilityFitShown& f) -> FieldValue { return f.fit.se_beta; }},
    {"cov_ln_theta_beta", [](const FragilityFitShown& f) -> FieldValue { return f.fit.cov_ln_theta_beta; }},
    {"log_likelihood", [](const FragilityFitShown& f) -> FieldValue { return f.fit.log_likelihood; }},
    {"beta_at_bound", [](const FragilityFitShown& f) -> FieldValue { return f.fit.beta_at_bound; }},
}};

}  // namespace topple

namespace topple::io {

std::string fragility_im_column(const FragilityResult& result) {
  return result.rotd50 ? "im_rotd50_pga_g" : std::string(intensity_measure_column(result.im));
}

nlohmann::ordered_json fragility_json(const FragilityResult& res, const FragilityJsonContext& context) {
  const std::string im_column = fragility_im_column(res);
  const double k = intensity_measure_display_factor(res.im, context.g_m_s2);
  const std::string_view unit = intensity_measure_unit(res.im);
  nlohmann::ordered_json j;
  j["im"] = context.im;
  j["im_unit"] = std::string(unit);
  if (res.rotd50) {
    j["im_definition"] = "RotD50 PGA of each pair (Boore 2010): every pair scaled as a whole to each level";
    j["bearing"] = context.bearing_rule;
    j["bearings_deg"] = res.bearings_deg;
  }
  j["g_m_s2"] = context.g_m_s2;
  j["motions"] = context.motions;
  j["runs"] = res.runs;
  j["band_level"] = context.band_level;
  j["band_method"] = "delta method on the probit scale, observed information";
  auto& curves = j["curves"] = nlohmann::ordered_json::array();
  for (const auto& c : res.curves) {
    nlohmann::ordered_json cj;
    cj["curve"] = c.name;
    nlohmann::ordered_json lv = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < c.data.im.size(); ++i) {
      lv.push_back({{im_column, c.data.im[i] * k}, {"trials", c.data.trials[i]}, {"failures", c.data.failures[i]}});
    }
    cj["levels"] = lv;
    if (c.fit) {
      cj["fit"] = fields_json(kFragilityFitFields, FragilityFitShown{*c.fit, k, unit});
    } else {
      cj["fit"] = nullptr;
      cj["fit_note"] = c.fit_note;
    }
    curves.push_back(cj);
  }
  return j;
}

void write_fragility_csv(std::ostream& out, const FragilityResult& res, double g_m_s2, double band_level) {
  const double k = intensity_measure_display_factor(res.im, g_m_s2);
  out << "curve," << fragility_im_column(res) << ",trials,failures,fraction,fitted_probability,band_lower,band_upper\n";
  for (const auto& c : res.curves) {
    for (std::size_t j = 0; j < c.data.im.size(); ++j) {
      out << fmt::format("{},{},{},{},{}", c.name, c.data.im[j] * k, c.data.trials[j], c.data.failures[j],
                         static_cast<double>(c.data.failures[j]) / c.data.trials[j]);
      if (c.fit) {
        const auto [lo, hi] = c.fit->band(c.data.im[j], band_level);
        out << fmt::format(",{},{},{}\n", c.fit->probability(c.data.im[j]), lo, hi);
      } else {
        out << ",,,\n";
      }
    }
  }
}

}  // namespace topple::io
