#pragma once
// A survey's inversion, the one entry point of `topple invert` and of Python's topple.invert / topple.invert_region
// (issue 27: the front ends only translate). A survey of one or many sites, one or three components, with a regional
// fit or not: every site with objects is inverted (inversion.hpp), the sites split across MPI ranks
// (inversion_distributed.hpp), then the regional fit (fit.hpp) over the located sites at their hypocentral distances
// (geodesy.hpp). The rules a front end would otherwise repeat live here: which sites are inverted (a station without
// objects is not: it enters the regional fit only), when a regional fit is tried (two sites or more), and where each
// site's outputs go (site_report_folder, site_output_path).
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/region/fit.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

namespace ensemble {
class Cluster;
}  // namespace ensemble

/// A survey's regional fit (the CLI's and Python's entry): each located site's evidence (its inversion, where it has
/// objects, and its instrument) at its hypocentral distance from [event] (geodesic_distance_km, hypocentral_distance_km
/// with depth_km, 0 when not given). `results[i]` is survey.sites[i]'s inversion, or nullptr for a station without
/// objects. None, with the reason in `notes`, when the survey has no epicentre or fewer than 3 located sites; sites
/// without coordinates are left out with a note. A one-site survey: none, and no note.
[[nodiscard]] std::optional<RegionalResult> fit_survey_region(const Survey& survey,
                                                              const std::vector<const InversionResult*>& results,
                                                              std::vector<std::string>& notes,
                                                              const RegionalSettings& settings = {});

/// A survey's inversion as `topple invert` and Python's topple.invert_region run it: every site with objects
/// inverted (invert_sites_distributed: one motion family; under MPI the sites split across the cluster's ranks), then,
/// on rank 0, the regional fit (fit_survey_region).
struct SurveyInversion {
  std::vector<InversionResult> results;   ///< the sites with objects, in survey order
  std::vector<std::size_t> survey_index;  ///< results[k] is survey.sites[survey_index[k]]
  std::optional<RegionalResult> region;   ///< none: see region_notes (and always none on ranks other than 0)
  std::vector<std::string> region_notes;  ///< fit_survey_region's notes
  /// Per survey site: its result, or nullptr for a station without objects (pointers into `results`).
  [[nodiscard]] std::vector<const InversionResult*> per_site(std::size_t site_count) const;
  /// The sites of `results`, in their order: survey.sites[survey_index[k]].
  [[nodiscard]] std::vector<Site> sites_with_objects(const Survey& survey) const;
};

[[nodiscard]] SurveyInversion invert_survey(const Survey& survey, const InversionOptions& options,
                                            ensemble::Cluster& cluster, const RegionalSettings& settings = {});

/// Where survey site `survey_index` (an index into survey.sites) writes its report, relative to the report
/// directory: the directory itself ("") for a one-site survey, else "site<survey_index + 1>" (so a site keeps its
/// folder whatever the other sites hold; a station without objects has a number but no folder). The regional page
/// at the directory's top links "site<N>/index.html".
[[nodiscard]] std::filesystem::path site_report_folder(const Survey& survey, std::size_t survey_index);

/// Where survey site `survey_index` writes a per-site file named after `path` (`topple invert --grid`): `path` itself
/// for a one-site survey, else "<stem>.site<survey_index + 1><extension>" beside it.
[[nodiscard]] std::filesystem::path site_output_path(const std::filesystem::path& path, const Survey& survey,
                                                     std::size_t survey_index);

}  // namespace topple
