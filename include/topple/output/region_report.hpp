#pragma once
// The survey's report (`topple invert --report DIR`; Python's report_dir): each site's page (report.hpp) in its folder
// (survey_inversion.hpp: site_report_folder) and, with a regional fit, the regional page at the top linking them.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/output/provenance.hpp"
#include "topple/region/fit.hpp"
#include "topple/region/survey_inversion.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// The regional report page: DIR/index.html (the relation, every site pooled beside its own estimate, linked to its
/// page `site_pages[i]` (relative to DIR; empty: no link), the calibration sites, the attenuation figure and the map
/// of the pooled field with its contours), and beside it attenuation.svg, pga_map.svg, contours.geojson, region.csv,
/// region.json, and the GMT map region_map.png with its script region_map.gmt.sh (region_map.hpp). `per_site` as in
/// fit_survey_region. Figures need gnuplot (plot.hpp). Returns warnings for the caller to show: a map that could not
/// be drawn (GMT missing; the page says so too).
std::vector<std::string> write_region_report(const std::filesystem::path& dir, const Survey& survey,
                                             const RegionalResult& fit,
                                             const std::vector<const InversionResult*>& per_site,
                                             const std::vector<std::string>& site_pages,
                                             const RegionalSettings& settings = {});

/// What write_survey_report wrote, for the caller to say.
struct SurveyReport {
  std::vector<std::filesystem::path> site_pages;     ///< each site's index.html, in the order of the results
  std::optional<std::filesystem::path> region_page;  ///< DIR/index.html, when the survey has a regional fit
  std::vector<std::string> warnings;                 ///< write_region_report's (a map that could not be drawn)
};

/// The survey's report in DIR: every inverted site's page (write_report) in DIR/site_report_folder(...) (DIR itself
/// for a one-site survey), then, with a regional fit, the regional page (write_region_report) in DIR linking each
/// site's page (a station without objects has none).
SurveyReport write_survey_report(const std::filesystem::path& dir, const Survey& survey, const SurveyInversion& inversion,
                                 const std::optional<io::Provenance>& provenance = std::nullopt,
                                 const RegionalSettings& settings = {});

}  // namespace topple
