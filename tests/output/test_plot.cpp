// Figures: files are produced, valid and non-trivial (gnuplot must be installed; scripts/install-deps.sh does it).
#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/output/plot.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"

namespace topple {
namespace {

using test::count;
using test::slurp;

plot::Figure sliding_example() {
  const auto motion = make_pulse({PulseKind::double_triangular, 2.0 * kStandardGravity, 0.2, 0.5, 0.0});
  const auto block = SlidingBlock::make(0.3);
  return plot::sliding_figure(motion, slide(motion, block), block, "double triangular pulse");
}

TEST(Plot, SlidingFigureAsSvgHasThreePanelsWithData) {
  test::TempDir tmp;
  const auto path = tmp.path() / "slide.svg";
  plot::render(sliding_example(), path);
  const std::string svg = slurp(path);
  ASSERT_GT(svg.size(), 5000u);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.rfind("</svg>"), std::string::npos);
  // labels with units are in the text of the figure
  EXPECT_NE(svg.find("relative displacement (m)"), std::string::npos);
  EXPECT_NE(svg.find("acceleration (g)"), std::string::npos);
  EXPECT_NE(svg.find("time (s)"), std::string::npos);
  // ground, velocity and displacement curves plus the two yield levels: at least 5 drawn paths
  EXPECT_GE(count(svg, "<path"), 5u);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".gp"));  // the script is cleaned up
}

TEST(Plot, PngIsAPngImage) {
  test::TempDir tmp;
  const auto path = tmp.path() / "slide.png";
  plot::render(sliding_example(), path);
  const std::string png = slurp(path);
  ASSERT_GT(png.size(), 10000u);
  EXPECT_EQ(png.substr(1, 3), "PNG");
}

TEST(Plot, PathsWithQuotesAndSpaces) {
  // The script is handed to gnuplot through /bin/sh: quotes and spaces in the folder name must survive.
  test::TempDir tmp;
  const auto dir = tmp.path() / "O'Brien's \"figures\" $HOME";
  std::filesystem::create_directories(dir);
  const auto path = dir / "slide.svg";
  plot::render(sliding_example(), path);
  EXPECT_GT(slurp(path).size(), 10000u);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".gp"));
}

TEST(Plot, MapFigure) {
  plot::MapFigure map;
  map.title = "likelihood";
  map.xlabel = "PGA (g)";
  map.ylabel = "predominant frequency (Hz)";
  map.zlabel = "likelihood";
  map.log_x = map.log_y = true;
  for (int i = 0; i < 10; ++i) map.x.push_back(0.05 * std::pow(1.4, i));
  for (int j = 0; j < 8; ++j) map.y.push_back(0.5 * std::pow(1.6, j));
  for (int j = 0; j < 8; ++j) {
    for (int i = 0; i < 10; ++i) map.z.push_back(std::exp(-0.1 * ((i - 5) * (i - 5) + (j - 3) * (j - 3))));
  }
  map.overlay.push_back({"lower bound", {0.2, 0.2}, {0.5, 10.0}, "lines", "#c0392b", 2.0});
  test::TempDir tmp;
  const auto path = tmp.path() / "map.svg";
  plot::render(map, path);
  const std::string svg = slurp(path);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_GE(count(svg, "<polygon"), 80u);  // the gridded field: one filled cell per grid point (10 x 8)
  EXPECT_NE(svg.find("lower bound"), std::string::npos);
}

TEST(Plot, RockingFigureThresholdsAndFall) {
  const auto motion = make_pulse({PulseKind::sine, 0.25 * kStandardGravity, 0.5, 2.5, 0.0});
  const auto body = RockingBody::block(0.04, 0.20);
  RockingOptions options;
  options.restitution = RestitutionMode::given;
  options.e = 0.9;
  const auto result = rock(motion, body, options);
  ASSERT_TRUE(result.summary.overturned);
  const auto f = plot::rocking_figure(motion, result, body, "falling block");
  ASSERT_EQ(f.panels.size(), 3u);
  ASSERT_EQ(f.panels[0].levels.size(), 2u);  // uplift at +-a/h (in g)
  EXPECT_DOUBLE_EQ(f.panels[0].levels[0].y, 0.2);
  EXPECT_DOUBLE_EQ(f.panels[0].levels[1].y, -0.2);
  ASSERT_EQ(f.panels[1].levels.size(), 2u);  // theta/alpha = +-1
  EXPECT_DOUBLE_EQ(f.panels[1].levels[0].y, 1.0);
  EXPECT_DOUBLE_EQ(f.panels[1].levels[1].y, -1.0);
  // the fall is a vertical line at the overturning instant in every panel
  for (const auto& panel : f.panels) {
    const auto& mark = panel.series.back();
    EXPECT_EQ(mark.x, (std::vector<double>{*result.summary.overturn_time_s, *result.summary.overturn_time_s}));
  }
}

TEST(Plot, PanelsWithTheirOwnAxisBelowTimeHistories) {
  const auto motion = make_pulse({PulseKind::ricker, 0.3 * kStandardGravity, 0.4, 2.0, 0.005});
  const auto periods = log_spaced(0.02, 5.0, 50);
  const auto f = plot::record_figure(motion, integrate_ground(motion), response_spectrum(motion, periods),
                                     {{0.4, "Tp", "#e67e22"}}, kStandardGravity, "ricker");
  ASSERT_EQ(f.panels.size(), 4u);
  const std::string script = plot::gnuplot_script(f, "x.svg");
  // time (s) once, under the last time history; the spectrum has its own log axis over its own periods
  EXPECT_EQ(count(script, "set xlabel \"time (s)\""), 1u);
  EXPECT_EQ(count(script, "set xlabel \"period (s)\""), 1u);
  EXPECT_LT(script.find("set xlabel \"time (s)\""), script.find("set xlabel \"period (s)\""));
  EXPECT_NE(script.find("set xrange [0.02:5]\nset logscale x"), std::string::npos);
  EXPECT_EQ(count(script, "set logscale x"), 1u);
}

TEST(Plot, UnknownExtensionIsAnInputError) {
  test::TempDir tmp;
  EXPECT_THROW(plot::render(sliding_example(), tmp.path() / "figure.jpeg"), InputError);
}

TEST(Plot, CliSlideWritesTheFigure) {
  test::TempDir tmp;
  const auto path = tmp.path() / "cli.svg";
  const auto r = test::run_cli("slide --pulse sine --amp-g 0.6 --duration 0.5 --mu 0.2 --plot '" + path.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GT(std::filesystem::file_size(path), 5000u);
  const auto bad = test::run_cli("slide --pulse sine --amp-g 0.6 --duration 0.5 --mu 0.2 --plot '" +
                                 (tmp.path() / "x.gif").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find(".svg or .png"), std::string::npos);
}

// ---- Pairs: every component drawn, not only the first ----

SynthesizedSet small_station() {
  SynthesisSetSpec spec;
  spec.horizontal.pga_m_s2 = 0.4 * kStandardGravity;
  spec.horizontal.predominant_frequency_hz = 3.0;
  spec.horizontal.duration_s = 8.0;
  spec.horizontal.seed = 5;
  return synthesize_set(spec);  // H1 at 90 deg, H2 at 0 deg, a vertical
}

TEST(PlotPairs, RecordSetFigureDrawsEveryComponentAndTheRotDSpectrum) {
  const SynthesizedSet s = small_station();
  const MotionSet set = MotionSet::make(s.first, &s.second, ComponentAzimuths{90.0, 0.0}, &*s.vertical);
  const std::vector<double> periods{0.1, 0.3, 1.0, 3.0};
  const RotDMeasures rotd = rotd_measures(set, periods);
  std::vector<plot::ComponentRecord> c;
  for (const auto& [label, m] : {std::pair{"H1 (90 deg)", &set.first()}, std::pair{"H2 (0 deg)", &set.second()},
                                 std::pair{"V (up)", &set.vertical()}}) {
    c.push_back({label, m, integrate_ground(*m), response_spectrum(*m, periods)});
  }
  const plot::Figure f = plot::record_set_figure(c, &rotd, kStandardGravity, "pair");
  ASSERT_EQ(f.panels.size(), 4u);
  for (std::size_t p = 0; p < 3; ++p) ASSERT_EQ(f.panels[p].series.size(), 3u) << "panel " << p;
  // The second component's acceleration is drawn, in g, sample for sample (a division: exact to 1 ulp).
  const auto& h2 = f.panels[0].series[1];
  ASSERT_EQ(h2.y.size(), set.size());
  EXPECT_EQ(h2.label, "H2 (0 deg)");
  for (std::size_t i = 0; i < set.size(); i += 97) EXPECT_EQ(h2.y[i], set.second().accel_m_s2()[i] / kStandardGravity);
  // Spectrum panel: three components' PSA, then the pair's RotD50 and RotD100 at their periods, in g.
  ASSERT_EQ(f.panels[3].series.size(), 5u);
  const auto& d50 = f.panels[3].series[3];
  EXPECT_EQ(d50.label, "RotD50 (pair)");
  EXPECT_EQ(d50.x, periods);
  for (std::size_t k = 0; k < periods.size(); ++k) EXPECT_EQ(d50.y[k], rotd.psa_m_s2[k].rotd50 / kStandardGravity);
  EXPECT_EQ(f.panels[3].series[4].label, "RotD100 (pair)");
  // The script names every component in every panel's legend and the RotD curves once.
  const std::string script = plot::gnuplot_script(f, "pair.svg");
  EXPECT_EQ(count(script, "title \"H1 (90 deg)\""), 3u);
  EXPECT_EQ(count(script, "title \"H2 (0 deg)\""), 3u);
  EXPECT_EQ(count(script, "title \"V (up)\""), 3u);
  EXPECT_EQ(count(script, "title \"RotD50 (pair)\""), 1u);
  EXPECT_EQ(count(script, "title \"RotD100 (pair)\""), 1u);
  EXPECT_EQ(count(script, "set xlabel \"period (s)\""), 1u);
}

TEST(PlotPairs, Sliding2dFigureDrawsBothComponentsAndBothDirections) {
  const SynthesizedSet s = small_station();
  const ComponentAzimuths az{90.0, 0.0};
  const SlidingBlock block = SlidingBlock::make(0.2);
  const Sliding2dResult r = slide_2d(s.first, s.second, az, block, &*s.vertical);
  ASSERT_GT(r.summary.slip_episodes, 0);  // the figure shows a response, not a block at rest
  const plot::Figure f = plot::sliding_2d_figure(s.first, s.second, az, &*s.vertical, r, block, "2d");
  ASSERT_EQ(f.panels.size(), 3u);
  ASSERT_EQ(f.panels[0].series.size(), 3u);
  EXPECT_EQ(f.panels[0].series[0].label, "H1 (90 deg)");
  EXPECT_EQ(f.panels[0].series[1].label, "H2 (0 deg)");
  EXPECT_EQ(f.panels[0].series[2].label, "V (up)");
  ASSERT_EQ(f.panels[0].levels.size(), 2u);
  EXPECT_EQ(f.panels[0].levels[0].y, 0.2);  // mu_s g in g
  EXPECT_EQ(f.panels[0].levels[1].y, -0.2);
  // Slip starts marked: one per transition from stuck to slipping, at most one per episode.
  EXPECT_GT(f.panels[0].marks_x.size(), 0u);
  EXPECT_LE(f.panels[0].marks_x.size(), static_cast<std::size_t>(r.summary.slip_episodes));
  for (std::size_t p = 1; p < 3; ++p) {
    ASSERT_EQ(f.panels[p].series.size(), 2u);
    EXPECT_EQ(f.panels[p].series[0].label, "east");
    EXPECT_EQ(f.panels[p].series[1].label, "north");
  }
  EXPECT_EQ(f.panels[2].series[0].y, r.history.east_m);
  EXPECT_EQ(f.panels[2].series[1].y, r.history.north_m);
  const std::string script = plot::gnuplot_script(f, "2d.svg");
  EXPECT_EQ(count(script, "title \"H2 (0 deg)\""), 1u);
  EXPECT_EQ(count(script, "title \"north\""), 2u);
}

TEST(PlotPairs, CliInfoAndSlideDrawPairs) {
  test::TempDir tmp;
  const std::string base = (tmp.path() / "s.csv").string();
  const auto made = test::run_cli("synth --pga 0.4g --freq 3Hz --duration 8s --seed 5 --components 3 --out '" + base + "'");
  ASSERT_EQ(made.exit_code, 0) << made.err;
  const std::string h1 = (tmp.path() / "s.h1.csv").string(), h2 = (tmp.path() / "s.h2.csv").string(),
                    v = (tmp.path() / "s.v.csv").string();
  const auto info_svg = tmp.path() / "info.svg";
  const auto info = test::run_cli("info '" + h1 + "' '" + h2 + "' '" + v + "' --azimuths 90,0 --plot '" +
                                  info_svg.string() + "'");
  ASSERT_EQ(info.exit_code, 0) << info.err;
  const std::string svg = slurp(info_svg);
  for (const char* text : {"H1 (90 deg)", "H2 (0 deg)", "V (up)", "RotD50 (pair)"}) {
    EXPECT_NE(svg.find(text), std::string::npos) << text;
  }
  const auto slide_svg = tmp.path() / "slide.svg";
  const auto slide = test::run_cli("slide '" + h1 + "' --h2 '" + h2 + "' --vertical '" + v +
                                   "' --azimuths 90,0 --mu 0.2 --plot '" + slide_svg.string() + "'");
  ASSERT_EQ(slide.exit_code, 0) << slide.err;
  const std::string svg2 = slurp(slide_svg);
  for (const char* text : {"H2 (0 deg)", "north", "relative displacement (m)"}) {
    EXPECT_NE(svg2.find(text), std::string::npos) << text;
  }
}

// Titles name files by their file name: a title travels with the figure (reports, other machines).
TEST(PlotTitles, FileLabelDropsTheDirectories) {
  EXPECT_EQ(plot::file_label("/work/shared/records/RSN6_IMPVALL.I_I-ELC180.AT2"), "RSN6_IMPVALL.I_I-ELC180.AT2");
  EXPECT_EQ(plot::file_label("../records/CPM000.AT2"), "CPM000.AT2");
  EXPECT_EQ(plot::file_label("CPM000.AT2"), "CPM000.AT2");
}

// Nothing clipped: a long title wraps at its ", " separators into lines that fit the figure, and each panel's legend
// gets the right margin its longest label needs (the fragility legend was cut at "β =").
TEST(PlotTitles, LongTitleWrapsAndLegendHasRoom) {
  plot::Figure f = sliding_example();
  f.title = "Fragility over 200 synthetic motions (f_p 2Hz, seeds from 1), slide > d = 5cm at μ = 0.3, slope 10°, "
            "one-way, overturn of a block 10cm x 40cm, e = housner";
  const std::string label = "overturn: θ = 0.316 g, β = 0.41, a longer label";
  f.panels[0].series[0].label = label;
  const std::string script = plot::gnuplot_script(f, "x.png");
  // The title: one gnuplot string with line breaks, broken between the analysis' parts, never inside "5cm".
  const std::size_t at = script.find("set multiplot layout");
  ASSERT_NE(at, std::string::npos);
  const std::string title_line = script.substr(at, script.find('\n', at) - at);
  EXPECT_NE(title_line.find("\\n"), std::string::npos) << title_line;
  EXPECT_NE(title_line.find("5cm"), std::string::npos) << title_line;
  EXPECT_EQ(title_line.find('/'), std::string::npos) << title_line;
  // Each line at most (width - 40 px) / 9 px characters: Helvetica 13 averages about 7 px a character, 9 px is the
  // widest mean (digits and capitals) the layout must allow for.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(script, m, std::regex("set terminal pngcairo size (\\d+),(\\d+)")));
  const int width = std::stoi(m[1]);
  std::size_t start = title_line.find('"') + 1;
  const std::size_t stop = title_line.rfind('"');
  while (start < stop) {
    const std::size_t end = std::min(stop, title_line.find("\\n", start));
    const std::string line = title_line.substr(start, end - start);
    const auto chars = std::count_if(line.begin(), line.end(), [](char c) { return (c & 0xC0) != 0x80; });
    EXPECT_LE(chars * 9, width - 40) << line;
    start = end + 2;
  }
  // The legend: the right margin leaves at least 7 px a character of the longest label (Helvetica 10 averages about
  // 5.5 px) plus the sample line, and the plots keep at least half of the figure.
  ASSERT_TRUE(std::regex_search(script, m, std::regex("set rmargin at screen ([0-9.]+)")));
  const double rmargin = std::stod(m[1]);
  const auto label_chars = std::count_if(label.begin(), label.end(), [](char c) { return (c & 0xC0) != 0x80; });
  EXPECT_GE((1.0 - rmargin) * width, 7.0 * static_cast<double>(label_chars) + 40.0) << "rmargin " << rmargin;
  EXPECT_GE(rmargin - 0.09, 0.5);
  // A short title stays one line, and the default margin is kept when the legend is short.
  const std::string short_script = plot::gnuplot_script(sliding_example(), "x.svg");
  EXPECT_NE(short_script.find("title \"double triangular pulse\" font"), std::string::npos);
  EXPECT_NE(short_script.find("set rmargin at screen 0.78"), std::string::npos);
}

}  // namespace
}  // namespace topple
