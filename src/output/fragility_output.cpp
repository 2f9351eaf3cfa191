#include "topple/output/fragility_output.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <boost/math/special_functions/erf.hpp>
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

namespace {

/// A CSV field as RFC 4180 writes it: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string q = "\"";
  for (char ch : text) q += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return q + "\"";
}

}  // namespace

nlohmann::ordered_json fragility_surface_json(const FragilitySurfaceFit& fit, double g_m_s2) {
  nlohmann::ordered_json j;
  j["form"] = std::string(kFragilitySurfaceForm);
  j["theta_ref_g"] = std::exp(fit.ln_theta_ref) / g_m_s2;
  j["ln_theta_ref_g"] = fit.ln_theta_ref - std::log(g_m_s2);
  j["gamma"] = fit.gamma;
  j["beta"] = fit.beta;
  j["v_ref_s"] = fit.v_ref_s;
  j["se_ln_theta_ref"] = fit.se_ln_theta_ref;
  j["se_gamma"] = fit.se_gamma;
  j["se_beta"] = fit.se_beta;
  nlohmann::ordered_json cov = nlohmann::ordered_json::array();
  for (const auto& row : fit.covariance) cov.push_back({row[0], row[1], row[2]});
  j["covariance"] = cov;
  j["covariance_of"] = {"ln_theta_ref", "gamma", "beta"};
  j["log_likelihood"] = fit.log_likelihood;
  j["records"] = fit.records;
  j["failures"] = fit.failures;
  j["iterations"] = fit.iterations;
  return j;
}

nlohmann::ordered_json as_recorded_json(const AsRecordedResult& res, const std::vector<std::string>& motions,
                                        double g_m_s2) {
  nlohmann::ordered_json j;
  j["mode"] = "as-recorded";
  j["g_m_s2"] = g_m_s2;
  j["runs"] = res.runs;
  nlohmann::ordered_json records = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < res.pga_m_s2.size(); ++i) {
    nlohmann::ordered_json r;
    r["motion"] = i < motions.size() ? motions[i] : std::string();
    r["pga_g"] = res.pga_m_s2[i] / g_m_s2;
    r["pgv_m_s"] = res.pgv_m_s[i];
    r["pgv_over_pga_s"] = res.pgv_m_s[i] / res.pga_m_s2[i];
    for (const auto& c : res.curves) r[c.name + "_failed"] = static_cast<bool>(c.failed[i]);
    records.push_back(std::move(r));
  }
  j["records"] = std::move(records);
  nlohmann::ordered_json curves = nlohmann::ordered_json::array();
  for (const auto& c : res.curves) {
    nlohmann::ordered_json cj;
    cj["curve"] = c.name;
    cj["failures"] = std::count(c.failed.begin(), c.failed.end(), true);
    if (c.fit) {
      cj["surface"] = fragility_surface_json(*c.fit, g_m_s2);
    } else {
      cj["surface"] = nullptr;
      cj["fit_note"] = c.fit_note;
    }
    curves.push_back(std::move(cj));
  }
  j["curves"] = std::move(curves);
  return j;
}

void write_as_recorded_csv(std::ostream& out, const AsRecordedResult& res, const std::vector<std::string>& motions,
                           double g_m_s2) {
  out << "motion,pga_g,pgv_m_s,pgv_over_pga_s";
  for (const auto& c : res.curves) out << "," << c.name << "_failed," << c.name << "_probability";
  out << "\n";
  for (std::size_t i = 0; i < res.pga_m_s2.size(); ++i) {
    const double v = res.pgv_m_s[i] / res.pga_m_s2[i];
    out << csv_field(i < motions.size() ? motions[i] : std::string())
        << fmt::format(",{},{},{}", res.pga_m_s2[i] / g_m_s2, res.pgv_m_s[i], v);
    for (const auto& c : res.curves) {
      out << "," << (c.failed[i] ? 1 : 0) << ",";
      if (c.fit) out << fmt::format("{}", c.fit->probability(res.pga_m_s2[i], v));
    }
    out << "\n";
  }
}

plot::MapFigure fragility_surface_figure(const AsRecordedResult& res, std::size_t curve, double g_m_s2,
                                         const std::string& title) {
  plot::MapFigure f;
  f.title = title;
  f.xlabel = "PGV/PGA (s)";
  f.ylabel = "PGA (g)";
  f.log_x = true;
  f.log_y = true;
  f.tics_125 = true;
  const AsRecordedCurve& c = res.curves.at(curve);
  f.zlabel = fmt::format("P({})", c.name == "overturn" ? "overturn" : "slide > threshold");
  double v_lo = std::numeric_limits<double>::infinity();
  double v_hi = 0.0;
  double a_lo = v_lo;
  double a_hi = 0.0;
  for (std::size_t i = 0; i < res.pga_m_s2.size(); ++i) {
    const double v = res.pgv_m_s[i] / res.pga_m_s2[i];
    const double a = res.pga_m_s2[i] / g_m_s2;
    v_lo = std::min(v_lo, v);
    v_hi = std::max(v_hi, v);
    a_lo = std::min(a_lo, a);
    a_hi = std::max(a_hi, a);
  }
  v_lo /= 1.3;
  v_hi *= 1.3;
  a_lo /= 1.3;
  a_hi *= 1.3;
  constexpr std::size_t kCells = 60;
  for (std::size_t k = 0; k < kCells; ++k) {
    const double t = (static_cast<double>(k) + 0.5) / static_cast<double>(kCells);
    f.x.push_back(v_lo * std::pow(v_hi / v_lo, t));
    f.y.push_back(a_lo * std::pow(a_hi / a_lo, t));
  }
  for (double a : f.y) {
    for (double v : f.x) f.z.push_back(c.fit ? c.fit->probability(a * g_m_s2, v) : 0.0);
  }
  if (c.fit) {
    // The P contour: ln PGA = ln theta_ref + gamma ln(v / v_ref) + beta Phi^-1(P), a straight line on log axes.
    const std::array<std::pair<double, const char*>, 3> levels{{{0.1, "#2ca02c"}, {0.5, "#d62728"}, {0.9, "#9467bd"}}};
    for (const auto& [p, color] : levels) {
      const double z = std::sqrt(2.0) * boost::math::erf_inv(2.0 * p - 1.0);  // Phi^-1(p)
      plot::Series s{fmt::format("P = {:g}", p), {}, {}, "lines", color, 2.0};
      for (double v : {v_lo, v_hi}) {
        s.x.push_back(v);
        s.y.push_back(c.fit->median_pga_m_s2(v) * std::exp(c.fit->beta * z) / g_m_s2);
      }
      f.overlay.push_back(std::move(s));
    }
  }
  plot::Series fell{c.name == "overturn" ? "overturned" : "slid past the threshold", {}, {}, "points pt 7 ps 1.0",
                    "#000000", 1.0};
  plot::Series stood{c.name == "overturn" ? "standing" : "within the threshold", {}, {}, "points pt 6 ps 1.0",
                     "#e67e22", 1.5};
  for (std::size_t i = 0; i < res.pga_m_s2.size(); ++i) {
    plot::Series& s = c.failed[i] ? fell : stood;
    s.x.push_back(res.pgv_m_s[i] / res.pga_m_s2[i]);
    s.y.push_back(res.pga_m_s2[i] / g_m_s2);
  }
  f.overlay.push_back(std::move(fell));
  f.overlay.push_back(std::move(stood));
  return f;
}

}  // namespace topple::io
