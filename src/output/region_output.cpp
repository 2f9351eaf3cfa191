// The regional fit as JSON and CSV (region_output.hpp).
#include "topple/output/region_output.hpp"

#include <cmath>

#include <fmt/format.h>

#include "topple/core/output_file.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json summary(const Interval95& v) {
  return {{"median", v.median}, {"ci68", {v.ci68_low, v.ci68_high}}, {"ci95", {v.ci95_low, v.ci95_high}}};
}

nlohmann::ordered_json opt(const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

nlohmann::ordered_json independent(const InversionResult* r, bool frequency = false) {
  if (r == nullptr) return nullptr;
  const Estimate& e = frequency ? r->freq_estimate_hz : r->pga_estimate_g;
  return {{"median", e.median}, {"ci68", {opt(e.ci68_low), opt(e.ci68_high)}}, {"ci95", {opt(e.ci95_low), opt(e.ci95_high)}}};
}

std::string csv_name(const std::string& name) {
  if (name.find_first_of(",\"\n") == std::string::npos) return name;
  std::string q = "\"";
  for (char c : name) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

const std::vector<double>& contour_levels_g() {
  static const std::vector<double> levels{0.05, 0.1, 0.2, 0.4};
  return levels;
}

nlohmann::ordered_json region_json(const RegionalResult& fit, const Survey& survey,
                                   const std::vector<const InversionResult*>& results, const RegionalSettings& st) {
  nlohmann::ordered_json j;
  j["model"] = "ln PGA_s = c0 - c1 ln sqrt(R_s^2 + c2^2) + delta_s, delta_s ~ N(0, tau^2); PGA in g, R hypocentral km";
  const Interval95 a_ref{std::exp(fit.ln_a_ref.median), std::exp(fit.ln_a_ref.ci68_low), std::exp(fit.ln_a_ref.ci68_high),
                         std::exp(fit.ln_a_ref.ci95_low), std::exp(fit.ln_a_ref.ci95_high)};
  j["relation"] = {{"c0_ln_g", summary(fit.c0)},
                   {"c1", summary(fit.c1)},
                   {"c2_km", fit.c2_km},
                   {"c2_fixed", true},
                   {"tau_ln", summary(fit.tau)},
                   {"reference_distance_km", fit.reference_distance_km},
                   {"pga_at_reference_g", summary(a_ref)}};
  j["priors"] = {{"ln_pga_at_reference_g", {st.ln_a_ref_min, st.ln_a_ref_max}},
                 {"c1", {st.c1_min, st.c1_max}},
                 {"tau_ln", {st.tau_min, st.tau_max}},
                 {"kind", "uniform on the box"},
                 {"instrument_sigma_ln", st.instrument_sigma_ln}};
  j["method"] = "grid integration over (ln PGA at the reference distance, c1, tau); each site's PGA integrated in "
                "closed form against its own likelihood (docs/method.md, Regional joint inversion)";
  j["grid_points"] = fit.grid_points;
  if (fit.frequency) {
    const FrequencyRelation& f = *fit.frequency;
    const Interval95 f_ref{std::exp(f.ln_f_ref.median), std::exp(f.ln_f_ref.ci68_low), std::exp(f.ln_f_ref.ci68_high),
                           std::exp(f.ln_f_ref.ci95_low), std::exp(f.ln_f_ref.ci95_high)};
    j["frequency_relation"] = {
        {"model", "ln f_s = d0 + d1 ln sqrt(R_s^2 + c2^2) + eps_s, eps_s ~ N(0, tau_f^2); f in Hz, R hypocentral km, c2 as "
                  "the PGA relation's; against the constant model ln f_s = ln f_c + eps_s"},
        {"d0_ln_hz", summary(f.d0)},
        {"d1", summary(f.d1)},
        {"tau_f_ln", summary(f.tau)},
        {"frequency_at_reference_hz", summary(f_ref)},
        {"constant_model", {{"f_c_hz", summary(f.constant_f_hz)}, {"tau_f_ln", summary(f.constant_tau)}}},
        {"ln_evidence_relation", f.log_evidence_relation},
        {"ln_evidence_constant", f.log_evidence_constant},
        {"ln_bayes_factor", f.ln_bayes_factor},
        {"bayes_factor_threshold", st.frequency_bayes_factor},
        {"supported", f.supported},
        {"rule", "supported when Z(relation) / Z(constant) >= the threshold (Kass & Raftery 1995: 3 is the lower end of "
                 "positive evidence); only then are the sites' frequencies pooled"},
        {"sites_with_frequency", f.sites_with_frequency},
        {"priors", {{"ln_frequency_at_reference_hz", {st.ln_f_ref_min, st.ln_f_ref_max}},
                    {"d1", {st.d1_min, st.d1_max}},
                    {"tau_f_ln", {st.tau_f_min, st.tau_f_max}},
                    {"kind", "uniform on the box"}}},
        {"notes", f.notes}};
  } else {
    j["frequency_relation"] = nullptr;
  }
  nlohmann::ordered_json sites = nlohmann::ordered_json::array();
  for (const PooledSite& p : fit.sites) {
    const Site& site = survey.sites[p.site_index];
    const InversionResult* r = results.at(p.site_index);
    nlohmann::ordered_json sj;
    sj["site"] = p.name;
    sj["survey_index"] = p.site_index;
    sj["lat"] = opt(site.lat_deg);
    sj["lon"] = opt(site.lon_deg);
    sj["hypocentral_distance_km"] = p.distance_km;
    sj["instrument_pga_g"] = opt(p.instrument_pga_g);
    sj["objects"] = site.objects.size();
    sj["pooled_pga_g"] = summary(p.pga_g);
    sj["relation_pga_g"] = summary(p.relation_pga_g);
    sj["independent_pga_g"] = independent(r);
    sj["independent_freq_hz"] = independent(r, true);
    sj["pooled_freq_hz"] = p.freq_hz ? summary(*p.freq_hz) : nlohmann::ordered_json(nullptr);
    sj["relation_freq_hz"] = p.relation_freq_hz ? summary(*p.relation_freq_hz) : nlohmann::ordered_json(nullptr);
    if (r != nullptr && p.instrument_pga_g) {
      sj["calibration"] = {{"objects_agree", objects_agree_with_instrument(r->pga_estimate_g, *p.instrument_pga_g)},
                           {"test", "the instrument's PGA inside the objects' own 95 % interval (open ends count as open)"}};
    } else {
      sj["calibration"] = nullptr;
    }
    sites.push_back(sj);
  }
  j["sites"] = sites;
  j["contour_levels_g"] = contour_levels_g();
  j["notes"] = fit.notes;
  return j;
}

void write_region_csv(const std::filesystem::path& path, const RegionalResult& fit,
                      const std::vector<const InversionResult*>& results) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  const auto cell = [](const std::optional<double>& v) { return v ? fmt::format("{}", *v) : std::string(); };
  out << "site,hypocentral_distance_km,instrument_pga_g,independent_median_g,independent_ci95_low_g,"
         "independent_ci95_high_g,pooled_median_g,pooled_ci68_low_g,pooled_ci68_high_g,pooled_ci95_low_g,"
         "pooled_ci95_high_g,relation_median_g\n";
  for (const PooledSite& p : fit.sites) {
    const InversionResult* r = results.at(p.site_index);
    const std::optional<double> med = r ? std::optional<double>(r->pga_estimate_g.median) : std::nullopt;
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}\n", csv_name(p.name), p.distance_km,
                       cell(p.instrument_pga_g), cell(med), cell(r ? r->pga_estimate_g.ci95_low : std::nullopt),
                       cell(r ? r->pga_estimate_g.ci95_high : std::nullopt), p.pga_g.median, p.pga_g.ci68_low,
                       p.pga_g.ci68_high, p.pga_g.ci95_low, p.pga_g.ci95_high, p.relation_pga_g.median);
  }
  file.commit();
}

void write_contours_geojson(const std::filesystem::path& path, const std::vector<Contour>& contours,
                            const PooledField& field) {
  nlohmann::ordered_json fc;
  fc["type"] = "FeatureCollection";
  fc["features"] = nlohmann::ordered_json::array();
  for (const Contour& c : contours) {
    nlohmann::ordered_json lines = nlohmann::ordered_json::array();
    for (const auto& line : c.lines) {
      nlohmann::ordered_json l = nlohmann::ordered_json::array();
      for (const auto& p : line) l.push_back({p[0], p[1]});
      lines.push_back(l);
    }
    nlohmann::ordered_json f;
    f["type"] = "Feature";
    f["geometry"] = {{"type", "MultiLineString"}, {"coordinates", lines}};
    f["properties"] = {{"pga_g", c.level_g},
                       {"field", "relation at the posterior medians + simple-kriged site residuals"},
                       {"correlation", "exp(-3 h / range_km), Jayaram & Baker (2009)"},
                       {"range_km", field.range_km}};
    fc["features"].push_back(f);
  }
  write_file_atomically(path, fc.dump() + "\n");
}

}  // namespace topple::io
