#pragma once
// The regional fit as JSON (the `region` key of `topple invert --json` on a multi-site survey; docs/survey.md lists
// every key) and as CSV beside the --map GeoJSON.
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "topple/inversion/inversion.hpp"
#include "topple/region/region.hpp"
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
/// median and 68/95 % ends, relation median (g). Empty cells where a value does not exist.
void write_region_csv(const std::filesystem::path& path, const RegionalResult& fit,
                      const std::vector<const InversionResult*>& results);

/// The iso-acceleration contours as GeoJSON: one Feature per level, a MultiLineString of [lon, lat] polylines, with
/// properties pga_g (the level) and the field's correlation (model and range_km).
void write_contours_geojson(const std::filesystem::path& path, const std::vector<Contour>& contours,
                            const PooledField& field);

}  // namespace topple::io
