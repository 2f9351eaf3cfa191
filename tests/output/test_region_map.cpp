// The regional map (region_map.hpp, issue 17 "Maps"): the GMT script generator as a pure function (its region, one
// symbol per site with its PGA as colour value, the contour levels), the map in the report when GMT is installed, and
// the report without GMT (a note in the page, a warning naming the program, never a failure).
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/output_file.hpp"
#include "topple/region/region.hpp"
#include "topple/output/region_map.hpp"
#include "topple/output/region_report.hpp"
#include "topple/output/report.hpp"

namespace topple {
namespace {

// ---- Fixtures ----

/// Four sites around an epicentre at (38, 23): two with objects, two stations, spanning lon 22.5-23.7, lat 37.3-38.44.
RegionMap four_sites() {
  RegionMap m;
  m.epicentre_lat_deg = 38.0;
  m.epicentre_lon_deg = 23.0;
  m.sites = {MapSite{1, "station \"north\"", 38.44, 22.8, 0.571234, true, std::nullopt},
             MapSite{2, "south", 37.3, 22.84, 0.0312, false, std::nullopt},
             MapSite{3, "east\nvillage", 38.1, 23.7, 0.0801, false, std::nullopt},
             MapSite{4, "west station", 37.87, 22.5, 0.123, true, std::nullopt}};
  Contour c01;
  c01.level_g = 0.1;
  c01.lines = {{{22.9, 37.8}, {23.1, 37.8}, {23.1, 38.2}, {22.9, 37.8}}, {{23.5, 38.3}, {23.6, 38.35}}};
  Contour c02;
  c02.level_g = 0.2;
  c02.lines = {{{22.95, 37.9}, {23.05, 37.9}, {23.0, 38.05}}};
  Contour c04;  // no line: the field never reaches 0.4 g
  c04.level_g = 0.4;
  m.contours = {c01, c02, c04};
  return m;
}

struct Region {
  double lon_min, lon_max, lat_min, lat_max;
};

/// The -R argument of the script's coast command.
Region script_region(const std::string& script) {
  const auto at = script.find("gmt coast -R");
  EXPECT_NE(at, std::string::npos);
  Region r{};
  char slash = 0;
  std::istringstream in(script.substr(at + 12));
  in >> r.lon_min >> slash >> r.lon_max >> slash >> r.lat_min >> slash >> r.lat_max;
  return r;
}

/// The data rows (lines not starting with '#') of the here-document after the first line that starts with `command`.
std::vector<std::vector<double>> block_rows(const std::string& script, const std::string& command) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(script);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (!inside) {
      inside = line.rfind(command, 0) == 0;
      continue;
    }
    if (line == "EOD") break;
    if (line.empty() || line[0] == '#' || line[0] == '>') continue;
    std::istringstream fields(line);
    std::vector<double> row;
    for (double v = 0; fields >> v;) row.push_back(v);
    rows.push_back(row);
  }
  return rows;
}

/// A regional fit of three instrument stations around (38, 23) and its survey: write_region_report's inputs without
/// an inversion (the stations carry no objects).
struct StationRegion {
  Survey survey;
  RegionalResult fit;
  std::vector<const InversionResult*> per_site;
  std::vector<std::string> pages;
};

StationRegion station_region() {
  StationRegion s;
  s.survey.epicentre_lat_deg = 38.0;
  s.survey.epicentre_lon_deg = 23.0;
  const double where[][3] = {{38.1, 23.05, 0.4}, {37.8, 22.8, 0.12}, {38.3, 23.4, 0.05}, {37.7, 23.3, 0.07}};
  std::vector<SiteEvidence> evidence;
  for (const auto& w : where) {
    Site site;
    site.name = fmt::format("station at {} {}", w[0], w[1]);
    site.lat_deg = w[0];
    site.lon_deg = w[1];
    site.instrument_pga_g = w[2];
    s.survey.sites.push_back(site);
  }
  s.per_site.assign(s.survey.sites.size(), nullptr);
  s.pages.assign(s.survey.sites.size(), "");
  std::vector<std::string> notes;
  s.fit = fit_survey_region(s.survey, s.per_site, notes).value();
  return s;
}

/// Sets an environment variable for one scope and restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const std::string& value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    ::setenv(name, value.c_str(), 1);
  }
  ~ScopedEnv() {
    if (old_) {
      ::setenv(name_, old_->c_str(), 1);
    } else {
      ::unsetenv(name_);
    }
  }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// ---- The script generator ----

// The box: the sites span lon 22.5-23.7 (1.2 deg) and lat 37.3-38.44 (1.14 deg); 15 % of each (0.18, 0.171 deg)
// exceeds 10 km (0.114 deg of longitude, 0.090 deg of latitude at 38 N), so the frame lies 15 % out on each side.
// Tolerance 1e-4 deg: the script prints four decimals.
TEST(RegionMapScript, RegionHoldsEverySiteWithAMargin) {
  const RegionMap m = four_sites();
  const Region r = script_region(gmt_map_script(m));
  EXPECT_NEAR(r.lon_min, 22.5 - 0.18, 1e-4);
  EXPECT_NEAR(r.lon_max, 23.7 + 0.18, 1e-4);
  EXPECT_NEAR(r.lat_min, 37.3 - 0.171, 1e-4);
  EXPECT_NEAR(r.lat_max, 38.44 + 0.171, 1e-4);
  for (const MapSite& s : m.sites) {
    EXPECT_GE(s.lon_deg - r.lon_min, 0.18 - 1e-4) << s.name;
    EXPECT_GE(r.lon_max - s.lon_deg, 0.18 - 1e-4) << s.name;
    EXPECT_GE(s.lat_deg - r.lat_min, 0.171 - 1e-4) << s.name;
    EXPECT_GE(r.lat_max - s.lat_deg, 0.171 - 1e-4) << s.name;
  }
}

// Sites either side of the antimeridian (issue 31): the map's region is the small box around them (its longitudes
// may pass 180, as GMT allows), not the 359 degrees between -179.8 and 179.7.
TEST(RegionMapScript, SitesAcrossTheAntimeridianMakeOneSmallRegion) {
  Survey survey;
  survey.epicentre_lat_deg = -17.0;
  survey.epicentre_lon_deg = 179.9;
  const double where[][3] = {{-17.1, -179.8, 0.3}, {-16.8, 179.7, 0.12}, {-17.3, -179.6, 0.08}, {-16.9, 179.5, 0.06}};
  for (const auto& w : where) {
    Site site;
    site.name = fmt::format("station at {} {}", w[0], w[1]);
    site.lat_deg = w[0];
    site.lon_deg = w[1];
    site.instrument_pga_g = w[2];
    survey.sites.push_back(site);
  }
  const std::vector<const InversionResult*> per_site(survey.sites.size(), nullptr);
  std::vector<std::string> notes;
  const RegionalResult fit = fit_survey_region(survey, per_site, notes).value();
  const RegionMap m = region_map(fit, survey, {}, per_site);
  const MapBounds b = map_bounds(m);
  EXPECT_LT(b.lon_max_deg - b.lon_min_deg, 2.0);  // the sites span 0.9 degrees; a margin of 10 km or 20 % each side
  for (const MapSite& site : m.sites) {
    EXPECT_GT(site.lon_deg, b.lon_min_deg) << site.name;
    EXPECT_LT(site.lon_deg, b.lon_max_deg) << site.name;
    EXPECT_NEAR(std::remainder(site.lon_deg - survey.epicentre_lon_deg.value(), 360.0),
                site.lon_deg - survey.epicentre_lon_deg.value(), 1e-9) << site.name;
  }
  EXPECT_NEAR(m.sites[0].lon_deg, 180.2, 1e-9);  // -179.8 drawn east of 180
}

// A lone site on the epicentre still gets a map: 10 km each side, measured here by the WGS84 geodesic (the margin is
// computed on a sphere of the mean radius; the two differ by under 0.5 % at 38 N, hence 9.95 km).
TEST(RegionMapScript, ALoneSiteGetsTenKilometresEachSide) {
  RegionMap m;
  m.epicentre_lat_deg = 38.0;
  m.epicentre_lon_deg = 23.0;
  m.sites = {MapSite{1, "only", 38.0, 23.0, 0.2, false, std::nullopt}};
  const MapBounds b = map_bounds(m);
  EXPECT_GT(geodesic_distance_km(38.0, 23.0, 38.0, b.lon_min_deg), 9.95);
  EXPECT_GT(geodesic_distance_km(38.0, 23.0, 38.0, b.lon_max_deg), 9.95);
  EXPECT_GT(geodesic_distance_km(38.0, 23.0, b.lat_min_deg, 23.0), 9.95);
  EXPECT_GT(geodesic_distance_km(38.0, 23.0, b.lat_max_deg, 23.0), 9.95);
  EXPECT_LT(geodesic_distance_km(38.0, 23.0, b.lat_max_deg, 23.0), 10.5);
}

// One circle per site with objects and one triangle per station, each row "lon lat pga" with the site's pooled PGA as
// its colour value (printed to 6 significant digits: relative error under 5e-6), each site numbered once.
TEST(RegionMapScript, OneSymbolPerSiteWithItsPgaAsColourValue) {
  const RegionMap m = four_sites();
  const std::string script = gmt_map_script(m);
  const auto circles = block_rows(script, "gmt plot -Sc");
  const auto triangles = block_rows(script, "gmt plot -Si");
  ASSERT_EQ(circles.size(), 2u);
  ASSERT_EQ(triangles.size(), 2u);
  std::size_t c = 0, t = 0;
  for (const MapSite& s : m.sites) {
    const std::vector<double>& row = s.instrument ? triangles[t++] : circles[c++];
    ASSERT_EQ(row.size(), 3u) << s.name;
    EXPECT_NEAR(row[0], s.lon_deg, 1e-6) << s.name;
    EXPECT_NEAR(row[1], s.lat_deg, 1e-6) << s.name;
    EXPECT_NEAR(row[2], s.pga_g, 5e-6 * s.pga_g) << s.name;
  }
  const auto numbers = block_rows(script, "gmt text");
  ASSERT_EQ(numbers.size(), m.sites.size());
  for (std::size_t i = 0; i < m.sites.size(); ++i) EXPECT_EQ(numbers[i][2], m.sites[i].number);
  // Both symbol kinds take their colour from the palette (-C); the epicentre is a star.
  EXPECT_NE(script.find("gmt plot -Sc0.32c -C"), std::string::npos);
  EXPECT_NE(script.find("gmt plot -Si0.48c -C"), std::string::npos);
  const auto star = block_rows(script, "gmt plot -Sa");
  ASSERT_EQ(star.size(), 1u);
  EXPECT_EQ(star[0], (std::vector<double>{23.0, 38.0}));
  // A name with a newline stays one comment line: the data after it is still read as data (checked above).
  EXPECT_NE(script.find("# 3 east village\n"), std::string::npos);
}

// Up to 60 sites are numbered on the map; beyond, the numbers would cover it: the symbols stay, the numbers go.
TEST(RegionMapScript, ManySitesKeepTheirSymbolsWithoutNumbers) {
  RegionMap m = four_sites();
  const MapSite first = m.sites[1];
  while (m.sites.size() < 60) m.sites.push_back(first);
  EXPECT_EQ(block_rows(gmt_map_script(m), "gmt text").size(), 60u);
  m.sites.push_back(first);
  const std::string script = gmt_map_script(m);
  EXPECT_EQ(script.find("gmt text"), std::string::npos);
  EXPECT_NE(script.find("# site numbers left out: 61 sites"), std::string::npos);
  EXPECT_EQ(block_rows(script, "gmt plot -Sc").size() + block_rows(script, "gmt plot -Si").size(), 61u);
}

// Each level with lines is drawn and labelled with its value in g, one segment header per polyline; a level without
// lines is named in a comment only.
TEST(RegionMapScript, ContourLevelsDrawnAndLabelled) {
  const std::string script = gmt_map_script(four_sites());
  EXPECT_EQ(test::count(script, "+l\"0.1 g\""), 1u);
  EXPECT_EQ(test::count(script, "+l\"0.2 g\""), 1u);
  EXPECT_EQ(test::count(script, "+l\"0.4 g\""), 0u);
  EXPECT_NE(script.find("# iso-acceleration line 0.4 g (0 polylines"), std::string::npos);
  EXPECT_EQ(test::count(script, "\n>\n"), 3u);
  const auto first = block_rows(script, "gmt plot -W1.1p,gray10 -Sqn1:+l\"0.1 g\"");
  ASSERT_EQ(first.size(), 6u);  // 4 + 2 vertices
  EXPECT_EQ(first[2], (std::vector<double>{23.1, 38.2}));
}

// The palette: sites from 0.0312 to 0.571 g give 1-2-5 ends 0.02 and 1 g, written as log10 ends for makecpt -Q
// (log10 0.02 = -1.69897 to 6 digits); equal values still give a palette one step wide; a scale labelled in g.
TEST(RegionMapScript, PaletteEndsAreOneTwoFiveValuesAroundTheSites) {
  const RegionMap m = four_sites();
  const auto [lo, hi] = map_palette_range_g(m);
  EXPECT_DOUBLE_EQ(lo, 0.02);
  EXPECT_DOUBLE_EQ(hi, 1.0);
  const std::string script = gmt_map_script(m);
  EXPECT_NE(script.find("gmt makecpt -Cturbo -T-1.69897/0 -Q"), std::string::npos);
  EXPECT_NE(script.find("gmt colorbar"), std::string::npos);
  EXPECT_NE(script.find("+l\"pooled PGA, posterior median (g)\""), std::string::npos);
  RegionMap same = m;
  for (MapSite& s : same.sites) s.pga_g = 0.2;
  const auto [lo2, hi2] = map_palette_range_g(same);
  EXPECT_DOUBLE_EQ(lo2, 0.2);
  EXPECT_DOUBLE_EQ(hi2, 0.5);
}

// The scale bar: the map is 1.56 deg wide at 37.87 N, i.e. 1.56 x 111.195 x cos(37.87 deg) = 136.9 km; a fifth is
// 27.4 km, whose 1-2-5 floor is 20 km.
TEST(RegionMapScript, ScaleBarIsAOneTwoFiveLengthNearAFifthOfTheWidth) {
  const std::string script = gmt_map_script(four_sites());
  EXPECT_NE(script.find("gmt basemap -LjBL+c37.8700+w20k"), std::string::npos) << script.substr(script.find("-LjBL"), 40);
}

// Three components: a site's constrained direction of strongest shaking is drawn as a bar along its mode (paper
// angle 90 - azimuth on the conformal Mercator) over a wedge pair of its 95 % arc; a site without one draws nothing,
// and a map without any has neither the layers nor the legend line. With GMT installed the script draws.
TEST(RegionMapScript, DirectionsOfStrongestShakingAreBarsOverTheirArcs) {
  RegionMap m = four_sites();
  EXPECT_EQ(gmt_map_script(m).find("direction of strongest shaking"), std::string::npos);
  DirectionEstimate d;
  d.mode_deg = 30.0;
  d.ci95 = DirectionArc{15.0, 45.0};  // 15-60 deg
  d.constrained = true;
  m.sites[1].direction = d;
  const std::string script = gmt_map_script(m);
  EXPECT_NE(script.find("gmt plot -Sw -Ggray60@40"), std::string::npos) << script;
  // The arc 15-60 deg clockwise from north is the paper angles 30 to 75, and 180 deg on, -150 to -105.
  EXPECT_NE(script.find("22.840000 37.300000 1.6c 30 75\n"), std::string::npos) << script;
  EXPECT_NE(script.find("22.840000 37.300000 1.6c -150 -105\n"), std::string::npos) << script;
  EXPECT_NE(script.find("gmt plot -Sv0c+jc -W2p,black << 'EOD'\n22.840000 37.300000 60 1.6c\nEOD"), std::string::npos)
      << script;
  EXPECT_NE(script.find("direction of strongest shaking (grey: its 95 % arc)"), std::string::npos);
  if (!find_program(gmt_program_from_environment()) || !find_program("gs")) {
    GTEST_SKIP() << "gmt or gs not installed (scripts/install-deps.sh --run installs them)";
  }
  test::TempDir tmp;
  io::write_file_atomically(tmp.path() / "map.gmt.sh", script);
  const std::string draw = "cd '" + tmp.path().string() + "' && bash map.gmt.sh map.png >gmt.log 2>&1";
  ASSERT_EQ(std::system(draw.c_str()), 0) << test::slurp(tmp.path() / "gmt.log");
  EXPECT_GT(test::slurp(tmp.path() / "map.png").size(), 10000u);  // as the report's map: tens of kB
}

TEST(RegionMapProgram, FindsTheShellAndRefusesAMissingPath) {
  const auto sh = find_program("sh");
  ASSERT_TRUE(sh.has_value());
  EXPECT_EQ(sh->filename(), "sh");
  EXPECT_FALSE(find_program("/nonexistent/topple-no-gmt").has_value());
  EXPECT_FALSE(find_program("topple-no-such-program-anywhere").has_value());
  EXPECT_FALSE(find_program("").has_value());
}

// ---- The map in the report ----

/// Width and height from a PNG's IHDR chunk (bytes 16-23, big-endian); zeros when the file is no PNG.
std::pair<std::uint32_t, std::uint32_t> png_size(const std::string& bytes) {
  if (bytes.size() < 24 || bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") != 0 || bytes.compare(12, 4, "IHDR") != 0) return {0, 0};
  const auto be32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (std::size_t k = 0; k < 4; ++k) v = (v << 8) | static_cast<unsigned char>(bytes[at + k]);
    return v;
  };
  return {be32(16), be32(20)};
}

// The page embeds the PNG as base64: RFC 4648's own test vectors (section 10), padding included.
TEST(RegionMapReport, InlinePngIsRfc4648Base64) {
  test::TempDir tmp;
  const std::pair<const char*, const char*> vectors[] = {{"", ""},         {"f", "Zg=="},         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},  {"foob", "Zm9vYg=="},  {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : vectors) {
    test::write_file(tmp.path() / "x.png", in);
    EXPECT_EQ(inline_png(tmp.path() / "x.png"), std::string("data:image/png;base64,") + out) << in;
  }
  test::write_file(tmp.path() / "x.png", std::string("\xff\xfe\x00", 3));  // high bytes and a NUL
  EXPECT_EQ(inline_png(tmp.path() / "x.png"), "data:image/png;base64,//4A");
}

// With GMT (and ghostscript) installed, the report holds region_map.png: a real PNG whose size follows from the
// script (16 cm map plus annotations and colour bar at 150 dpi: about 1030 px wide; the region here is about as tall
// as wide, plus the colour bar), embedded in the page, with its script beside it and no warning.
TEST(RegionMapReport, WritesTheMapPngWhenGmtIsInstalled) {
  if (!find_program(gmt_program_from_environment()) || !find_program("gs")) {
    GTEST_SKIP() << "gmt or gs not installed (scripts/install-deps.sh --run installs them)";
  }
  const StationRegion s = station_region();
  test::TempDir tmp;
  const std::vector<std::string> warnings = write_region_report(tmp.path(), s.survey, s.fit, s.per_site, s.pages);
  EXPECT_TRUE(warnings.empty()) << warnings.front();
  const std::string png = test::slurp(tmp.path() / kRegionMapPng);
  ASSERT_GT(png.size(), 10000u);  // coastlines, symbols and a colour bar: tens of kB (a blank page is a few kB)
  const auto [w, h] = png_size(png);
  EXPECT_GT(w, 900u);
  EXPECT_LT(w, 1300u);
  EXPECT_GT(h, 900u);
  EXPECT_LT(h, 2000u);
  // The script beside it redraws the same figure (same size) on its own, from the report folder.
  const std::string redraw = "cd '" + tmp.path().string() + "' && bash " + kRegionMapScript + " redrawn.png";
  ASSERT_EQ(std::system(redraw.c_str()), 0) << redraw;
  EXPECT_EQ(png_size(test::slurp(tmp.path() / "redrawn.png")), png_size(png));
  std::filesystem::remove(tmp.path() / "redrawn.png");
  const std::string page = test::slurp(tmp.path() / "index.html");
  EXPECT_NE(page.find("<figure id=\"geomap\"><img"), std::string::npos);
  EXPECT_NE(page.find("src=\"data:image/png;base64,iVBORw0KGgo"), std::string::npos);  // the PNG signature in base64
  EXPECT_EQ(page.find("geomap-missing"), std::string::npos);
  // Nothing left behind: no temporary file, no GMT session files in the report folder.
  for (const auto& e : std::filesystem::directory_iterator(tmp.path())) {
    EXPECT_NE(e.path().filename().string().rfind(".tmp-", 0), 0u) << e.path();
    EXPECT_NE(e.path().filename().string(), "gmt.history") << e.path();
  }
}

// Without GMT (TOPPLE_GMT names a program that does not exist) the report is still written: the page says why there
// is no map and names the program, the call returns that warning, the script is there to run elsewhere, and the
// gnuplot figures are unaffected.
TEST(RegionMapReport, WithoutGmtTheReportIsWrittenWithANote) {
  const ScopedEnv env("TOPPLE_GMT", "/nonexistent/topple-no-gmt");
  const StationRegion s = station_region();
  test::TempDir tmp;
  std::vector<std::string> warnings;
  ASSERT_NO_THROW(warnings = write_region_report(tmp.path(), s.survey, s.fit, s.per_site, s.pages));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("`/nonexistent/topple-no-gmt`"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("not found"), std::string::npos) << warnings[0];
  const std::string page = test::slurp(tmp.path() / "index.html");
  const auto note = page.find("<p class=\"note\" id=\"geomap-missing\">No map: ");
  ASSERT_NE(note, std::string::npos);
  EXPECT_NE(page.find("/nonexistent/topple-no-gmt", note), std::string::npos);
  EXPECT_EQ(page.find("<figure id=\"geomap\">"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / kRegionMapPng));
  EXPECT_NE(test::slurp(tmp.path() / kRegionMapScript).find("gmt begin"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "attenuation.svg"));
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "pga_map.svg"));
}

// A GMT that runs but fails (here `false`, which exits 1) is no failure either: the note carries the failure.
TEST(RegionMapReport, AFailingGmtLeavesANoteNotAnError) {
  const auto f = find_program("false");
  ASSERT_TRUE(f.has_value());
  const StationRegion s = station_region();
  test::TempDir tmp;
  if (!find_program("gs")) GTEST_SKIP() << "gs not installed: the missing program is reported before GMT runs";
  const MapOutcome out = write_region_map(tmp.path(), region_map(s.fit, s.survey, {}), f->string());
  EXPECT_FALSE(out.drawn);
  EXPECT_NE(out.note.find("bash failed"), std::string::npos) << out.note;
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / kRegionMapPng));
  for (const auto& e : std::filesystem::directory_iterator(tmp.path())) {
    EXPECT_NE(e.path().filename().string().rfind(".tmp-", 0), 0u) << e.path();
  }
}

// The command: the warning reaches stderr (even with --quiet) and the exit status stays 0.
TEST(RegionMapCli, MissingGmtWarnsOnStderr) {
  const ScopedEnv env("TOPPLE_GMT", "/nonexistent/topple-no-gmt");
  test::TempDir tmp;
  const auto r = test::run_cli("invert '" + (std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples/regional_survey.toml").string() +
                               "' --quiet --report '" + (tmp.path() / "rep").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("topple: warning: the map with coastlines and borders was not drawn: `/nonexistent/topple-no-gmt`"),
            std::string::npos)
      << r.err;
  EXPECT_NE(test::slurp(tmp.path() / "rep" / "index.html").find("geomap-missing"), std::string::npos);
}

}  // namespace
}  // namespace topple
