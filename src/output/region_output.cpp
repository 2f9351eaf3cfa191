// The regional fit as JSON and CSV, a survey's inversion as JSON, grids and map files (region_output.hpp).
#include "topple/output/region_output.hpp"

#include <algorithm>
#include <array>
#include <type_traits>
#include <variant>

#include <fmt/format.h>

#include "topple/core/output_file.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/output/write.hpp"
#include "topple/region/fields.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json summary(const Interval95& v) {
  return {{"median", v.median}, {"ci68", {v.ci68_low, v.ci68_high}}, {"ci95", {v.ci95_low, v.ci95_high}}};
}

nlohmann::ordered_json opt(const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

/// A value of the regional tables (fields.hpp) as JSON.
nlohmann::ordered_json value_json(const RegionalValue& value) {
  return std::visit(
      [](const auto& v) -> nlohmann::ordered_json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, FieldValue>) {
          return field_json(v);
        } else if constexpr (std::is_same_v<T, std::optional<Interval95>>) {
          return v ? summary(*v) : nlohmann::ordered_json(nullptr);
        } else {  // a site's own estimate: an unconstrained end is null
          if (!v) return nullptr;
          return {{"median", v->median}, {"ci68", {opt(v->ci68_low), opt(v->ci68_high)}},
                  {"ci95", {opt(v->ci95_low), opt(v->ci95_high)}}};
        }
      },
      value);
}

/// The table's fields into `j`, in the table's order.
template <class Row, std::size_t N>
void put_fields(nlohmann::ordered_json& j, const std::array<RegionalField<Row>, N>& table, const Row& row) {
  for (const RegionalField<Row>& f : table) j[f.name] = value_json(f.get(row));
}

std::string csv_name(const std::string& name) {
  if (name.find_first_of(",\"\n") == std::string::npos) return name;
  std::string q = "\"";
  for (char c : name) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// A site's intensity and its PGA through the conversion (issue 30; region/intensity.hpp).
nlohmann::ordered_json intensity_json(const IntensityPga& i) {
  nlohmann::ordered_json j;
  j["value"] = i.intensity.value;
  j["scale"] = std::string(intensity_scale_name(i.intensity.scale));
  j["reports"] = i.intensity.reports ? nlohmann::ordered_json(*i.intensity.reports) : nlohmann::ordered_json(nullptr);
  j["mmi"] = i.mmi;
  j["pga_g"] = {{"median", i.pga_g}, {"ci95", {i.ci95_low_g(), i.ci95_high_g()}}};
  j["sigma_ln"] = i.sigma_ln;
  j["sigma_intensity"] = i.sigma_intensity;
  j["extrapolated"] = i.extrapolated;
  return j;
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
  j["relation"] = nlohmann::ordered_json::object();
  put_fields(j["relation"], kRelationFields, fit);
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
    nlohmann::ordered_json fj;
    fj["model"] = "ln f_s = d0 + d1 ln sqrt(R_s^2 + c2^2) + eps_s, eps_s ~ N(0, tau_f^2); f in Hz, R hypocentral km, c2 as "
                  "the PGA relation's; against the constant model ln f_s = ln f_c + eps_s";
    put_fields(fj, kFrequencyRelationFields, f);
    fj["constant_model"] = nlohmann::ordered_json::object();
    put_fields(fj["constant_model"], kConstantModelFields, f);
    put_fields(fj, kFrequencyComparisonFields, FrequencyComparisonRow{f, st});
    fj["priors"] = {{"ln_frequency_at_reference_hz", {st.ln_f_ref_min, st.ln_f_ref_max}},
                    {"d1", {st.d1_min, st.d1_max}},
                    {"tau_f_ln", {st.tau_f_min, st.tau_f_max}},
                    {"kind", "uniform on the box"}};
    fj["notes"] = f.notes;
    j["frequency_relation"] = fj;
  } else {
    j["frequency_relation"] = nullptr;
  }
  // Intensity sites (issue 30): the keys appear only when some site has an intensity, so that the JSON of a survey
  // without one is unchanged.
  const bool any_intensity =
      std::any_of(fit.sites.begin(), fit.sites.end(), [](const PooledSite& p) { return p.intensity.has_value(); });
  if (any_intensity) j["intensity_conversion"] = std::string(kIntensityConversion);
  nlohmann::ordered_json sites = nlohmann::ordered_json::array();
  for (const PooledSite& p : fit.sites) {
    const InversionResult* r = results.at(p.site_index);
    nlohmann::ordered_json sj = nlohmann::ordered_json::object();
    put_fields(sj, kRegionalSiteFields, RegionalSiteRow{p, survey.sites[p.site_index], r});
    if (r != nullptr && p.instrument_pga_g) {
      sj["calibration"] = {{"objects_agree", objects_agree_with_instrument(r->pga_estimate_g, *p.instrument_pga_g)},
                           {"test", "the instrument's PGA inside the objects' own 95 % interval (open ends count as open)"}};
    } else {
      sj["calibration"] = nullptr;
    }
    if (any_intensity) {
      sj["intensity"] = p.intensity ? intensity_json(*p.intensity) : nlohmann::ordered_json(nullptr);
      if (r != nullptr && p.intensity) {
        sj["intensity_check"] = {{"objects_agree", objects_agree_with_intensity(r->pga_estimate_g, *p.intensity)},
                                 {"test", std::string(kIntensityAgreementTest)}};
      } else {
        sj["intensity_check"] = nullptr;
      }
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
         "pooled_ci95_high_g,relation_median_g,"
         // Issue 30: the site's macroseismic intensity, appended so that the columns before keep their positions.
         "intensity,intensity_scale,intensity_reports,intensity_pga_median_g,intensity_pga_ci95_low_g,"
         "intensity_pga_ci95_high_g,intensity_objects_agree\n";
  for (const PooledSite& p : fit.sites) {
    const InversionResult* r = results.at(p.site_index);
    const std::optional<double> med = r ? std::optional<double>(r->pga_estimate_g.median) : std::nullopt;
    out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{}", csv_name(p.name), p.distance_km,
                       cell(p.instrument_pga_g), cell(med), cell(r ? r->pga_estimate_g.ci95_low : std::nullopt),
                       cell(r ? r->pga_estimate_g.ci95_high : std::nullopt), p.pga_g.median, p.pga_g.ci68_low,
                       p.pga_g.ci68_high, p.pga_g.ci95_low, p.pga_g.ci95_high, p.relation_pga_g.median);
    // Empty cells for a site without an intensity; the agreement (true/false) only where the site also has objects.
    if (const auto& i = p.intensity) {
      out << fmt::format(",{},{},{},{},{},{},{}\n", i->intensity.value, intensity_scale_name(i->intensity.scale),
                         i->intensity.reports ? fmt::format("{}", *i->intensity.reports) : std::string(), i->pga_g,
                         i->ci95_low_g(), i->ci95_high_g(),
                         r != nullptr ? (objects_agree_with_intensity(r->pga_estimate_g, *i) ? "true" : "false") : "");
    } else {
      out << ",,,,,,,\n";
    }
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
      // Longitudes in [-180, 180), lines cut at the antimeridian (RFC 7946 3.1.9; field.hpp, split_at_antimeridian).
      for (const auto& piece : split_at_antimeridian(line)) {
        nlohmann::ordered_json l = nlohmann::ordered_json::array();
        for (const auto& p : piece) l.push_back({p[0], p[1]});
        lines.push_back(l);
      }
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

nlohmann::ordered_json survey_inversion_json(const Survey& survey, const SurveyInversion& inversion,
                                             const std::optional<Provenance>& provenance, const RegionalSettings& settings) {
  const std::vector<Site> sites = inversion.sites_with_objects(survey);
  // A site's JSON, with the whole provenance (a one-site survey) or without it (the caller adds the reference).
  const auto site_json = [&](std::size_t k, bool with_provenance) {
    nlohmann::ordered_json sj = provenance && with_provenance
                                    ? inversion_json(inversion.results[k], sites[k], *provenance)
                                    : inversion_json(inversion.results[k], sites[k]);
    // A site's macroseismic intensity (issue 30), beside its objects' estimate: its PGA through the conversion and
    // whether the two agree. Only for a site with an intensity: other sites' JSON is unchanged.
    if (sites[k].intensity) {
      const IntensityPga i = intensity_pga(*sites[k].intensity);
      nlohmann::ordered_json ij = intensity_json(i);
      ij["conversion"] = std::string(kIntensityConversion);
      ij["objects_agree"] = objects_agree_with_intensity(inversion.results[k].pga_estimate_g, i);
      ij["test"] = std::string(kIntensityAgreementTest);
      sj["intensity"] = ij;
    }
    return sj;
  };
  nlohmann::ordered_json j;
  if (survey.sites.size() <= 1) {
    j = site_json(0, true);
  } else {
    // Provenance once per output (issue 31): the survey text verbatim at the top level; each site keeps the small
    // fields and a reference (RFC 6901 JSON pointer) to the text instead of a copy of it, so that the JSON grows
    // linearly in the sites with a small constant (the copy made 1000 one-object sites 273 MB).
    j["sites"] = nlohmann::ordered_json::array();
    for (std::size_t k = 0; k < inversion.results.size(); ++k) {
      nlohmann::ordered_json sj = site_json(k, false);
      if (!provenance) {
        j["sites"].push_back(std::move(sj));
        continue;
      }
      nlohmann::ordered_json p = nlohmann::ordered_json::object();
      for (const ProvenanceField& field : kProvenanceFields) {
        if (field.member != &Provenance::survey_text) p[field.key] = (*provenance).*field.member;
      }
      p["survey_text_at"] = "#/provenance/survey_text";
      p["site"] = sites[k].name;
      sj["provenance"] = std::move(p);
      j["sites"].push_back(std::move(sj));
    }
    if (inversion.region) {
      j["region"] = region_json(*inversion.region, survey, inversion.per_site(survey.sites.size()), settings);
    }
    if (!inversion.region_notes.empty()) j["region_notes"] = inversion.region_notes;
    if (provenance) {
      nlohmann::ordered_json p = nlohmann::ordered_json::object();
      for (const ProvenanceField& field : kProvenanceFields) p[field.key] = (*provenance).*field.member;
      j["provenance"] = std::move(p);
    }
  }
  if (!survey.warnings.empty()) j["warnings"] = survey.warnings;  // added only when there are any: old bytes kept
  return j;
}

void write_survey_grids(const std::filesystem::path& path, const Survey& survey, const SurveyInversion& inversion) {
  for (std::size_t k = 0; k < inversion.results.size(); ++k) {
    write_inversion_grid_csv(site_output_path(path, survey, inversion.survey_index[k]), inversion.results[k]);
  }
}

void write_survey_map(const std::filesystem::path& path, const Survey& survey, const SurveyInversion& inversion) {
  const std::vector<Site> sites = inversion.sites_with_objects(survey);
  write_sites_geojson(path, sites, inversion.results);
  if (inversion.region) {
    std::filesystem::path csv(path);
    csv.replace_extension(".region.csv");
    write_region_csv(csv, *inversion.region, inversion.per_site(survey.sites.size()));
    const PooledField field = pooled_field(*inversion.region, survey);
    std::filesystem::path contours(path);
    contours.replace_extension(".contours.geojson");
    write_contours_geojson(contours, contour_field(field, contour_levels_g()), field);
  }
  if (survey.epicentre_lat_deg) {
    std::filesystem::path csv(path);
    csv.replace_extension(".distance.csv");
    write_distance_csv(csv, sites, inversion.results, *survey.epicentre_lat_deg, *survey.epicentre_lon_deg);
  }
}

}  // namespace topple::io
