#pragma once
// Inversion results as JSON (a stable interface), the grid as CSV, sites as GeoJSON, PGA vs epicentral distance.
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "topple/inversion/inversion.hpp"
#include "topple/output/provenance.hpp"
#include "topple/survey/survey.hpp"

namespace topple::io {

/// One site's result: keys summary (inversion_summary), pga_g and freq_hz ({best, median, ci68: [low, high], ci95:
/// [low, high], median_grid_edge, best_grid_edge}, null ends where unconstrained), static_bounds_pga_g ([low, high],
/// hard and soft thresholds together, null where none), static_bounds_hard_pga_g, static_thresholds (each with its
/// kind), contradictions, notes, misfit_level, constraining_objects, objects (with posterior_predictive, misfit,
/// constraint_bits), grid axes, runs, seconds. docs/survey.md lists every key. Keys are only ever added.
[[nodiscard]] nlohmann::ordered_json inversion_json(const InversionResult& result, const Site& site);

/// One field of the provenance: its key in the JSON "provenance" object (in this order), its label in the report's
/// provenance table (nullptr: not a row there; the report shows the survey text verbatim below the table), and the
/// member that holds it. The one table both writers read.
struct ProvenanceField {
  const char* key;
  const char* label;
  std::string Provenance::*member;
};
inline constexpr std::array<ProvenanceField, 7> kProvenanceFields{{
    {"topple_version", "topple version", &Provenance::topple_version},
    {"git_commit", "git commit", &Provenance::git_commit},
    {"date_utc", "date (UTC)", &Provenance::date_utc},
    {"command_line", "command line", &Provenance::command_line},
    {"survey_file", "survey file", &Provenance::survey_file},
    {"survey_xxh3_64", "survey checksum (XXH3-64)", &Provenance::survey_xxh3_64},
    {"survey_text", nullptr, &Provenance::survey_text},
}};

/// The same with a "provenance" object at the end (version, commit, date, command line, survey checksum and text).
[[nodiscard]] nlohmann::ordered_json inversion_json(const InversionResult& result, const Site& site,
                                                    const Provenance& provenance);

/// The grid row of the median PGA and the column of the median frequency (nearest in log): where the report and the
/// JSON slice a population's model fraction (docs/method.md, "Populations of objects").
struct PopulationSlices {
  std::size_t pga_row = 0;
  std::size_t freq_column = 0;
};
[[nodiscard]] PopulationSlices population_slices_at_estimate(const InversionResult& result);
/// The "populations" array of the invert JSON: each population's counts, observed fraction, the model's fraction at
/// the estimate and posterior-predictive, its members and rule, and the model's fraction over PGA (median
/// frequency's column) and over frequency (median PGA's row).
[[nodiscard]] nlohmann::ordered_json populations_json(const InversionResult& result);

/// The grid: one row per cell, pga_g,freq_hz,log_likelihood,posterior,p_<object id>...
void write_inversion_grid_csv(const std::filesystem::path& path, const InversionResult& result);

/// One GeoJSON point per site that has coordinates, with PGA median and intervals (for iso-acceleration maps).
void write_sites_geojson(const std::filesystem::path& path, const std::vector<Site>& sites,
                         const std::vector<InversionResult>& results);

/// PGA vs epicentral distance (geodesic on WGS84, region.hpp): site,distance_km,pga_median_g,ci68/ci95 ends.
void write_distance_csv(const std::filesystem::path& path, const std::vector<Site>& sites,
                        const std::vector<InversionResult>& results, double epicentre_lat_deg,
                        double epicentre_lon_deg);

/// Epicentral distance, km: geodesic_distance_km (region.hpp; WGS84, Karney 2013). Until issue 17 it was the
/// haversine on a 6371 km sphere, which differs by up to 0.5 %.
[[nodiscard]] double epicentral_distance_km(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg);

}  // namespace topple::io
