// A survey's inversion and regional fit, the front ends' one entry point (survey_inversion.hpp).
#include "topple/region/survey_inversion.hpp"

#include <fmt/format.h>

#include "topple/region/geodesy.hpp"
#include "topple/region/inversion_distributed.hpp"

namespace topple {

std::optional<RegionalResult> fit_survey_region(const Survey& survey,
                                                const std::vector<const InversionResult*>& results,
                                                std::vector<std::string>& notes, const RegionalSettings& settings) {
  if (survey.sites.size() < 2) return std::nullopt;  // a one-site survey: no regional picture, nothing to say
  if (!survey.epicentre_lat_deg || !survey.epicentre_lon_deg) {
    notes.push_back("no regional fit: the survey gives no [event] epicentre = [lat, lon]");
    return std::nullopt;
  }
  const double depth = survey.epicentre_depth_km.value_or(0.0);
  std::vector<SiteEvidence> evidence;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < survey.sites.size(); ++i) {
    const Site& site = survey.sites[i];
    if (!site.lat_deg || !site.lon_deg) {
      notes.push_back(fmt::format("regional fit: site '{}' has no lat/lon and is left out", site.name));
      continue;
    }
    const double r = hypocentral_distance_km(
        geodesic_distance_km(*survey.epicentre_lat_deg, *survey.epicentre_lon_deg, *site.lat_deg, *site.lon_deg), depth);
    evidence.push_back(site_evidence(site.name, r, results.at(i), site.instrument_pga_g, site.intensity));
    index.push_back(i);
  }
  if (evidence.size() < 3) {
    notes.push_back(fmt::format("no regional fit: it needs at least 3 located sites, the survey has {}", evidence.size()));
    return std::nullopt;
  }
  RegionalResult fit = fit_region(evidence, settings);
  for (std::size_t k = 0; k < fit.sites.size(); ++k) fit.sites[k].site_index = index[k];
  return fit;
}

std::vector<const InversionResult*> SurveyInversion::per_site(std::size_t site_count) const {
  std::vector<const InversionResult*> out(site_count, nullptr);
  for (std::size_t k = 0; k < results.size(); ++k) out.at(survey_index[k]) = &results[k];
  return out;
}

std::vector<Site> SurveyInversion::sites_with_objects(const Survey& survey) const {
  std::vector<Site> out;
  out.reserve(survey_index.size());
  for (const std::size_t i : survey_index) out.push_back(survey.sites.at(i));
  return out;
}

SurveyInversion invert_survey(const Survey& survey, const InversionOptions& options, ensemble::Cluster& cluster,
                              const RegionalSettings& settings) {
  SurveyInversion out;
  // An instrument station (or an intensity site) without objects has nothing to invert: it enters the regional fit
  // only.
  std::vector<Site> with_objects;
  for (std::size_t i = 0; i < survey.sites.size(); ++i) {
    if (!survey.sites[i].has_observations()) continue;
    with_objects.push_back(survey.sites[i]);
    out.survey_index.push_back(i);
  }
  out.results = invert_sites_distributed(with_objects, survey.inversion, options, cluster);
  if (cluster.rank() != 0) return out;  // the joint fit is rank 0's (milliseconds to seconds, on its threads)
  out.region = fit_survey_region(survey, out.per_site(survey.sites.size()), out.region_notes, settings);
  return out;
}

std::filesystem::path site_report_folder(const Survey& survey, std::size_t survey_index) {
  if (survey.sites.size() <= 1) return {};
  return fmt::format("site{}", survey_index + 1);
}

std::filesystem::path site_output_path(const std::filesystem::path& path, const Survey& survey,
                                       std::size_t survey_index) {
  if (survey.sites.size() <= 1) return path;
  return path.parent_path() / fmt::format("{}.site{}{}", path.stem().string(), survey_index + 1, path.extension().string());
}

}  // namespace topple
