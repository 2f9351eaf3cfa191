// The regional map drawn by GMT (region_map.hpp).
#include "topple/output/region_map.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/plot.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

// Kilometres per degree of latitude on a sphere of the mean Earth radius 6371.0088 km (IUGG): a margin and a scale
// bar's length need no ellipsoid (GMT draws the bar itself, true at the map's middle latitude).
constexpr double kKmPerDegree = 111.195;
constexpr double kMarginFraction = 0.15;
constexpr double kMarginKm = 10.0;
// Beyond this many sites their numbers would cover the map (a survey of hundreds of sites): the symbols stay, the
// numbers go (the colours and the report's table carry the values).
constexpr std::size_t kMaxNumberedSites = 60;

/// The 1-2-5 x 10^k value at or below x (x > 0).
double floor_125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x * (1.0 + 1e-12)) return m * decade;
  }
  return decade;
}

/// The 1-2-5 x 10^k value at or above x (x > 0).
double ceil_125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * decade >= x * (1.0 - 1e-12)) return m * decade;
  }
  return 10.0 * decade;
}

/// A name as a one-line script comment (no control characters).
std::string comment_text(const std::string& s) {
  std::string out;
  for (char c : s) out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  return out;
}

/// The rows of one kind of site: instrument stations, intensity sites (issue 30), or the others (sites with objects).
void site_rows(std::ostringstream& os, const RegionMap& map, bool instrument, bool intensity = false) {
  for (const MapSite& s : map.sites) {
    if (s.instrument != instrument || s.intensity != intensity) continue;
    os << fmt::format("# {} {}\n{:.6f} {:.6f} {:.6g}\n", s.number, comment_text(s.name), s.lon_deg, s.lat_deg, s.pga_g);
  }
}

}  // namespace

RegionMap region_map(const RegionalResult& fit, const Survey& survey, const std::vector<Contour>& contours,
                     const std::vector<const InversionResult*>& per_site) {
  RegionMap m;
  m.epicentre_lat_deg = survey.epicentre_lat_deg.value();
  m.epicentre_lon_deg = survey.epicentre_lon_deg.value();
  for (const PooledSite& p : fit.sites) {
    const Site& site = survey.sites.at(p.site_index);
    // Longitudes within 180 degrees of the epicentre's (issue 31): a survey across the antimeridian is one small
    // region (GMT takes a region such as 175/185), not the globe between its sites.
    const double lon = m.epicentre_lon_deg + std::remainder(site.lon_deg.value() - m.epicentre_lon_deg, 360.0);
    m.sites.push_back(MapSite{static_cast<int>(p.site_index) + 1, p.name, site.lat_deg.value(), lon,
                              p.pga_g.median, p.instrument_pga_g.has_value(), std::nullopt,
                              p.intensity.has_value() && site.objects.empty() && !p.instrument_pga_g});
    const InversionResult* r = p.site_index < per_site.size() ? per_site[p.site_index] : nullptr;
    if (r != nullptr && r->three_component && r->three_component->direction.constrained) {
      m.sites.back().direction = r->three_component->direction;
    }
  }
  m.contours = contours;
  return m;
}

MapBounds map_bounds(const RegionMap& map) {
  MapBounds b{map.epicentre_lon_deg, map.epicentre_lon_deg, map.epicentre_lat_deg, map.epicentre_lat_deg};
  for (const MapSite& s : map.sites) {
    b.lon_min_deg = std::min(b.lon_min_deg, s.lon_deg);
    b.lon_max_deg = std::max(b.lon_max_deg, s.lon_deg);
    b.lat_min_deg = std::min(b.lat_min_deg, s.lat_deg);
    b.lat_max_deg = std::max(b.lat_max_deg, s.lat_deg);
  }
  const double mid_lat_rad = deg_to_rad(0.5 * (b.lat_min_deg + b.lat_max_deg));
  const double dlat = std::max(kMarginFraction * (b.lat_max_deg - b.lat_min_deg), kMarginKm / kKmPerDegree);
  const double dlon = std::max(kMarginFraction * (b.lon_max_deg - b.lon_min_deg),
                               kMarginKm / (kKmPerDegree * std::max(std::cos(mid_lat_rad), 0.05)));
  b.lon_min_deg -= dlon;
  b.lon_max_deg += dlon;
  b.lat_min_deg = std::max(b.lat_min_deg - dlat, -89.0);  // Mercator cannot reach the poles
  b.lat_max_deg = std::min(b.lat_max_deg + dlat, 89.0);
  return b;
}

std::pair<double, double> map_palette_range_g(const RegionMap& map) {
  double lo = 0.0, hi = 0.0;
  for (const MapSite& s : map.sites) {
    if (!(s.pga_g > 0.0) || !std::isfinite(s.pga_g)) continue;
    lo = lo == 0.0 ? s.pga_g : std::min(lo, s.pga_g);
    hi = std::max(hi, s.pga_g);
  }
  if (lo == 0.0) return {0.01, 1.0};  // no site with a PGA: a default decade pair, never a degenerate palette
  lo = floor_125(lo);
  hi = ceil_125(hi);
  if (hi <= lo) hi = ceil_125(lo * 1.5);  // all sites equal: one 1-2-5 step
  return {lo, hi};
}

std::string gmt_map_script(const RegionMap& map) {
  const MapBounds b = map_bounds(map);
  const auto [lo_g, hi_g] = map_palette_range_g(map);
  const double mid_lat = 0.5 * (b.lat_min_deg + b.lat_max_deg);
  const double width_km = (b.lon_max_deg - b.lon_min_deg) * kKmPerDegree * std::cos(deg_to_rad(mid_lat));
  const double bar_km = floor_125(width_km / 5.0);  // a scale bar about a fifth of the map's width
  std::ostringstream os;
  os << "#!/usr/bin/env bash\n"
        "# The regional map of topple's regional report (docs/method.md, \"The regional map\"), a GMT 6 modern-mode\n"
        "# script with its data inline. Redraw:  bash region_map.gmt.sh [OUTPUT.png [GMT]]\n"
        "# (default region_map.png, and GMT's command from TOPPLE_GMT or `gmt`). Needs GMT (Debian: gmt gmt-gshhg\n"
        "# gmt-dcw) and ghostscript.\n"
        "# Coastlines and lakes: GSHHG (Wessel & Smith 1996); borders: WDBII, shipped with GSHHG.\n"
        "set -euo pipefail\n"
        "out=\"${1:-region_map.png}\"\n"
        "gmt_command=\"${2:-${TOPPLE_GMT:-gmt}}\"\n"
        "gmt() { command \"$gmt_command\" \"$@\"; }\n"
        "# A session of its own: maps drawn side by side do not share GMT's state.\n"
        "export GMT_SESSION_NAME=\"topple$$\"\n"
        "gmt begin \"${out%.png}\" png E150\n"
        "gmt set MAP_FRAME_TYPE plain FONT_ANNOT_PRIMARY 9p FONT_LABEL 10p FORMAT_GEO_MAP ddd:mmF\n";
  os << fmt::format("# region (lon min/max, lat min/max, degrees): the sites and the epicentre with a margin\n"
                    "gmt coast -R{:.4f}/{:.4f}/{:.4f}/{:.4f} -JM16c -Baf -BWSne -Da -A5 -Gwhitesmoke -Slightsteelblue1 "
                    "-W0.5p,gray30 -N1/0.8p,gray20,-\n",
                    b.lon_min_deg, b.lon_max_deg, b.lat_min_deg, b.lat_max_deg);
  os << fmt::format("# palette: pooled PGA (g) from {:g} to {:g}, logarithmic (-Q: the -T ends are log10 g)\n"
                    "gmt makecpt -Cturbo -T{:.6g}/{:.6g} -Q -D\n",
                    lo_g, hi_g, std::log10(lo_g), std::log10(hi_g));
  for (const Contour& c : map.contours) {
    os << fmt::format("# iso-acceleration line {:g} g ({} polylines of lon lat)\n", c.level_g, c.lines.size());
    if (c.lines.empty()) continue;
    os << fmt::format("gmt plot -W1.1p,gray10 -Sqn1:+l\"{:g} g\"+f7p,Helvetica,gray10+gwhite+c1p << 'EOD'\n", c.level_g);
    for (const auto& line : c.lines) {
      os << ">\n";
      for (const auto& p : line) os << fmt::format("{:.5f} {:.5f}\n", p[0], p[1]);
    }
    os << "EOD\n";
  }
  // Three components: each constrained direction of strongest shaking, under the site's symbol. Mercator is
  // conformal, so an azimuth az is the paper angle 90 - az (counter-clockwise from east) at every point.
  bool any_direction = false;
  for (const MapSite& s : map.sites) any_direction = any_direction || s.direction.has_value();
  if (any_direction) {
    os << "# directions of strongest shaking (three components, where constrained): the 95 % arc as a wedge pair\n"
          "# (lon lat diameter start end, paper angles), then the mode as a bar through the site (lon lat angle length)\n"
          "gmt plot -Sw -Ggray60@40 -W0.4p,gray30 << 'EOD'\n";
    for (const MapSite& s : map.sites) {
      if (!s.direction) continue;
      const DirectionArc& a = s.direction->ci95;
      for (double turn : {0.0, 180.0}) {
        os << fmt::format("{:.6f} {:.6f} 1.6c {:.4g} {:.4g}\n", s.lon_deg, s.lat_deg, 90.0 - a.high_deg() - turn,
                          90.0 - a.low_deg - turn);
      }
    }
    os << "EOD\ngmt plot -Sv0c+jc -W2p,black << 'EOD'\n";
    for (const MapSite& s : map.sites) {
      if (s.direction) os << fmt::format("{:.6f} {:.6f} {:.4g} 1.6c\n", s.lon_deg, s.lat_deg, 90.0 - s.direction->mode_deg);
    }
    os << "EOD\n";
  }
  os << "# sites with objects (circles): lon lat pooled PGA (g), coloured by the palette; the comment is # number name\n"
        "gmt plot -Sc0.32c -C -W0.6p,black << 'EOD'\n";
  site_rows(os, map, false);
  os << "EOD\n"
        "# instrument stations (inverted triangles): lon lat pooled PGA (g)\n"
        "gmt plot -Si0.48c -C -W1p,black << 'EOD'\n";
  site_rows(os, map, true);
  os << "EOD\n";
  // Intensity sites (issue 30), only when the survey has some: other surveys' scripts are unchanged.
  const bool any_intensity = std::any_of(map.sites.begin(), map.sites.end(), [](const MapSite& s) { return s.intensity; });
  if (any_intensity) {
    os << "# intensity sites (diamonds): lon lat pooled PGA (g), a macroseismic intensity and no objects\n"
          "gmt plot -Sd0.38c -C -W0.8p,gray30 << 'EOD'\n";
    site_rows(os, map, false, true);
    os << "EOD\n";
  }
  if (map.sites.size() <= kMaxNumberedSites) {
    os << "# site numbers (their position in the survey, as the report's siteN pages)\n"
          "gmt text -F+f7p,Helvetica-Bold,black+jBL -D0.18c/0.12c << 'EOD'\n";
    for (const MapSite& s : map.sites) os << fmt::format("{:.6f} {:.6f} {}\n", s.lon_deg, s.lat_deg, s.number);
    os << "EOD\n";
  } else {
    os << fmt::format("# site numbers left out: {} sites (more than {})\n", map.sites.size(), kMaxNumberedSites);
  }
  os << fmt::format("# epicentre (star)\ngmt plot -Sa0.6c -Gred -W0.6p,black << 'EOD'\n{:.6f} {:.6f}\nEOD\n",
                    map.epicentre_lon_deg, map.epicentre_lat_deg);
  os << fmt::format("# scale bar, true at the map's middle latitude\n"
                    "gmt basemap -LjBL+c{:.4f}+w{:g}k+f+lkm+o0.4c/0.4c -F+gwhite@20+p0.3p,gray40\n",
                    mid_lat, bar_km);
  os << "gmt legend -DjTR+o0.2c -F+gwhite@10+p0.5p,gray40 << 'EOD'\n"
        "S 0.25c c 0.3c gray70 0.6p,black 0.6c site with objects (colour: pooled PGA)\n"
        "S 0.25c i 0.4c gray70 1p,black 0.6c instrument station\n";
  if (any_intensity) os << "S 0.25c d 0.38c gray70 0.8p,gray30 0.6c intensity site (macroseismic intensity)\n";
  os << "S 0.25c a 0.45c red 0.6p,black 0.6c epicentre\n"
        "S 0.25c - 0.5c - 1.1p,gray10 0.6c iso-acceleration line (g)\n";
  if (any_direction) {
    os << "S 0.25c - 0.5c - 2p,black 0.6c direction of strongest shaking (grey: its 95 % arc)\n";
  }
  os << "EOD\n"
        "gmt colorbar -DJBC+w10c+o0/1c+h -Bxa2f3+l\"pooled PGA, posterior median (g)\" -Q\n"
        "gmt end\n";
  return os.str();
}

std::optional<std::filesystem::path> find_program(const std::string& name) {
  if (name.empty()) return std::nullopt;
  const auto runnable = [](const std::filesystem::path& p) {
    std::error_code ec;
    return std::filesystem::is_regular_file(p, ec) && ::access(p.c_str(), X_OK) == 0;
  };
  if (name.find('/') != std::string::npos) {
    return runnable(name) ? std::optional<std::filesystem::path>(name) : std::nullopt;
  }
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (runnable(candidate)) return candidate;
  }
  return std::nullopt;
}

std::string gmt_program_from_environment() {
  const char* v = std::getenv("TOPPLE_GMT");
  return v != nullptr && *v != '\0' ? std::string(v) : std::string("gmt");
}

MapOutcome write_region_map(const std::filesystem::path& dir, const RegionMap& map, const std::string& gmt_program) {
  const std::string script = gmt_map_script(map);
  io::write_file_atomically(dir / kRegionMapScript, script);
  std::vector<std::string> missing;
  if (!find_program(gmt_program)) missing.push_back(fmt::format("`{}` (GMT; Debian: gmt gmt-gshhg gmt-dcw)", gmt_program));
  // GMT's PNG goes through PostScript and ghostscript (psconvert).
  if (!find_program("gs")) missing.push_back("`gs` (ghostscript; Debian: ghostscript)");
  if (!missing.empty()) {
    std::string names;
    for (std::size_t i = 0; i < missing.size(); ++i) names += (i == 0 ? "" : " and ") + missing[i];
    return {false, fmt::format("the map with coastlines and borders was not drawn: {} not found; {} is written, "
                               "run `bash {}` where GMT is installed",
                               names, kRegionMapScript, kRegionMapScript)};
  }
  io::OutputFile image(dir / kRegionMapPng);
  // The script takes its output file (the temporary name, renamed once GMT succeeded) and GMT's command as its
  // arguments.
  try {
    plot::run_figure_program("bash", script, ".gmt.sh", {image.temporary_path().string(), gmt_program}, image,
                             "are gmt, gmt-gshhg and ghostscript installed?");
  } catch (const OutputError&) {
    throw;
  } catch (const std::runtime_error& e) {
    std::string message = e.what();
    if (message.size() > 2000) message = message.substr(0, 2000) + " [...]";
    return {false, "the map with coastlines and borders was not drawn: " + message};
  }
  return {true, {}};
}

}  // namespace topple
