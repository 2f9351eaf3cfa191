#pragma once
// The regional map (issue 17, "Maps"; docs/method.md, "The regional map"): every fitted site at its place, coloured by
// its pooled PGA (posterior median, g) on a logarithmic palette with a labelled scale, the instrument stations as
// triangles, the epicentre as a star and the iso-acceleration lines (contour_field) labelled with their level, over
// coastlines, lakes and national borders, with a scale bar.
//
// Drawn offline by GMT, the Generic Mapping Tools (Wessel et al. 2019; Debian gmt, gmt-gshhg, and ghostscript for
// the PNG): coastlines and lakes from GSHHG (Wessel & Smith 1996) at the finest resolution GMT's "auto" picks for the
// map's size, national borders from the WDBII borders shipped with GSHHG (coast -N1). The library writes a GMT
// modern-mode bash script (gmt_map_script, a pure function: the data inline) and runs it through the figure runner
// that gnuplot uses (plot::run_figure_program); the script stays beside the figure, so `bash region_map.gmt.sh`
// redraws it. Without GMT the report is still written: write_region_map says why the map is missing.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "topple/inversion/direction.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/region/field.hpp"
#include "topple/region/fit.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// One site on the map.
struct MapSite {
  int number = 0;  ///< the label beside its symbol (up to 60 sites): its position in the survey, from 1 (siteN)
  std::string name;      ///< written as a comment in the script
  double lat_deg = 0.0;  ///< WGS84 latitude, degrees
  double lon_deg = 0.0;  ///< WGS84 longitude, degrees
  double pga_g = 0.0;    ///< its colour: the pooled PGA's posterior median, g
  bool instrument = false;  ///< an instrument station (drawn as a triangle)
  /// Three-component surveys: the site's direction of strongest shaking (inversion_3c.hpp) when it is constrained,
  /// drawn as a bar through the site along its mode, over a wedge pair of its 95 % arc. None: one component, or
  /// unconstrained (nothing drawn).
  std::optional<DirectionEstimate> direction;
  /// An intensity site (issue 30): a macroseismic intensity and neither objects nor an instrument (drawn as a diamond).
  bool intensity = false;
};

/// What the map shows, as plain values.
struct RegionMap {
  double epicentre_lat_deg = 0.0;
  double epicentre_lon_deg = 0.0;
  std::vector<MapSite> sites;
  std::vector<Contour> contours;  ///< iso-acceleration lines ([lon, lat] polylines) with their levels, g
};

/// The map's box, degrees.
struct MapBounds {
  double lon_min_deg = 0.0, lon_max_deg = 0.0, lat_min_deg = 0.0, lat_max_deg = 0.0;
};

/// The map of a fit: every fitted site at its survey coordinates with its pooled median, and the given contours.
/// Needs survey.epicentre and the fitted sites' coordinates (what fit_survey_region guarantees).
/// `per_site` (by survey index, may be empty or hold nulls): the sites' own results, whose constrained directions of
/// strongest shaking the map draws (three components).
[[nodiscard]] RegionMap region_map(const RegionalResult& fit, const Survey& survey,
                                   const std::vector<Contour>& contours,
                                   const std::vector<const InversionResult*>& per_site = {});

/// The box around the sites and the epicentre, widened on each side by 15 % of its extent or 10 km, whichever is
/// more (so that no symbol touches the frame and a lone site still gets a map); contours outside it are clipped.
/// Longitudes as given (a region across the antimeridian is not handled).
[[nodiscard]] MapBounds map_bounds(const RegionMap& map);

/// The palette's ends, g: the 1-2-5 values just below the smallest and just above the largest site PGA.
[[nodiscard]] std::pair<double, double> map_palette_range_g(const RegionMap& map);

/// The GMT modern-mode bash script that draws `map` (header; every value inline). Run as
/// `bash SCRIPT [OUTPUT.png [GMT]]`: OUTPUT.png defaults to region_map.png in the current directory; GMT's command is
/// the second argument, else the TOPPLE_GMT environment variable, else `gmt`.
[[nodiscard]] std::string gmt_map_script(const RegionMap& map);

/// File names in the report directory.
inline constexpr const char* kRegionMapPng = "region_map.png";
inline constexpr const char* kRegionMapScript = "region_map.gmt.sh";

/// The program on the PATH (a name holding '/' is taken as a path): its full path when it exists and is executable.
[[nodiscard]] std::optional<std::filesystem::path> find_program(const std::string& name);

/// GMT's command: the TOPPLE_GMT environment variable when set and not empty, else "gmt".
[[nodiscard]] std::string gmt_program_from_environment();

/// What write_region_map did: `drawn` when DIR/region_map.png was written; otherwise `note` says why (a missing
/// program named, or GMT's own message).
struct MapOutcome {
  bool drawn = false;
  std::string note;
};

/// Writes DIR/region_map.gmt.sh (always) and runs it with `gmt_program` to write DIR/region_map.png (both through
/// temporary names). A missing gmt or ghostscript (gs), or a failing GMT run, is no error: the outcome says why there
/// is no map. Throws OutputError when DIR cannot be written.
[[nodiscard]] MapOutcome write_region_map(const std::filesystem::path& dir, const RegionMap& map,
                                          const std::string& gmt_program);

}  // namespace topple
