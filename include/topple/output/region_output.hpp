#pragma once
// The regional fit as JSON (the `region` key of `topple invert --json` on a multi-site survey; docs/survey.md lists
// every key) and as CSV beside the --map GeoJSON; a survey's inversion (survey_inversion.hpp) as the JSON, the grids
// and the map files `topple invert` writes, so that every front end writes the same.
#include <filesystem>
#include <optional>
#include <vector>

#include <nlohmann/json.hpp>

#include "topple/inversion/inversion.hpp"
#include "topple/output/provenance.hpp"
#include "topple/region/field.hpp"
#include "topple/region/fit.hpp"
#include "topple/region/survey_inversion.hpp"
#include "topple/survey/survey.hpp"

namespace topple::io {

/// The iso-acceleration levels the report and JSON name, g (docs/survey.md): 0.05, 0.1, 0.2, 0.4.
[[nodiscard]] const std::vector<double>& contour_levels_g();

/// Keys: model, relation {c0_ln_g, c1, c2_km (fixed), tau_ln, reference_distance_km, pga_at_reference_g: each
/// {median, ci68, ci95}}, priors, sites [{site, survey_index, hypocentral_distance_km, instrument_pga_g, pooled_pga_g,
/// relation_pga_g, independent_pga_g (the site's own inversion, null for a station without objects), calibration
/// (stations with objects: objects_agree), independent_freq_hz, pooled_freq_hz, relation_freq_hz (null unless the
/// frequency relation is supported)}], frequency_relation (null or {d0_ln_hz, d1, tau_f_ln, constant_model,
/// ln_bayes_factor, supported, ...}), contour_levels_g, notes. `results[i]` as in fit_survey_region.
[[nodiscard]] nlohmann::ordered_json region_json(const RegionalResult& fit, const Survey& survey,
                                                 const std::vector<const InversionResult*>& results,
                                                 const RegionalSettings& settings);

/// One row per fitted site: site,hypocentral_distance_km,instrument_pga_g,independent median and 95 % ends, pooled
/// median and 68/95 % ends, relation median (g); then (issue 30, appended) the site's intensity, its scale, reports,
/// the PGA it implies through WGRW12 (median and 95 % ends, g) and whether the objects agree with it (true/false,
/// empty without objects). Empty cells where a value does not exist.
void write_region_csv(const std::filesystem::path& path, const RegionalResult& fit,
                      const std::vector<const InversionResult*>& results);

/// The iso-acceleration contours as GeoJSON: one Feature per level, a MultiLineString of [lon, lat] polylines, with
/// properties pga_g (the level) and the field's correlation (model and range_km).
void write_contours_geojson(const std::filesystem::path& path, const std::vector<Contour>& contours,
                            const PooledField& field);

/// A survey's inversion as `topple invert --json` prints it. One site: its inversion_json (with `provenance` at the
/// end when given), plus "warnings" (the survey's) only when there are any. Several sites: {"sites": [each inverted
/// site's inversion_json, in survey order], "region": region_json (with a regional fit), "region_notes" (when any),
/// "warnings" (when any)}.
[[nodiscard]] nlohmann::ordered_json survey_inversion_json(const Survey& survey, const SurveyInversion& inversion,
                                                           const std::optional<Provenance>& provenance = std::nullopt,
                                                           const RegionalSettings& settings = {});

/// Each inverted site's likelihood grid (write_inversion_grid_csv) at site_output_path(path, survey, its index):
/// `topple invert --grid`.
void write_survey_grids(const std::filesystem::path& path, const Survey& survey, const SurveyInversion& inversion);

/// `topple invert --map PATH`: PATH, one GeoJSON point per inverted site (write_sites_geojson); with a regional fit,
/// PATH with the extension .region.csv (write_region_csv) and .contours.geojson (the pooled field's contours at
/// contour_levels_g); with an epicentre, .distance.csv (write_distance_csv).
void write_survey_map(const std::filesystem::path& path, const Survey& survey, const SurveyInversion& inversion);

}  // namespace topple::io
