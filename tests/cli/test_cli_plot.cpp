// `--plot FILE.svg|FILE.png` on rock, synth and info: the figure is a valid SVG with the expected panels, axis labels
// with units, threshold lines and marks; PNG files are PNG images; a bad extension exits 2 before any work. Also: every
// pulse of the library is accepted by slide and rock, with its parameters, and misused pulse options exit 2.
// (gnuplot must be installed; scripts/install-deps.sh does it.)
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"

namespace topple {
namespace {

using test::count;
using test::slurp;

std::string q(const std::filesystem::path& p) { return fmt::format("'{}'", p.string()); }

/// A gnuplot SVG: its text elements, its panels (gnuplot groups each plot's curves as gnuplot_plot_<curve><panel>, the
/// panel a letter per plot of the multiplot), its drawn paths.
struct Svg {
  std::string text;
  std::set<std::string> labels;
  std::set<char> panels;

  explicit Svg(const std::filesystem::path& path) : text(slurp(path)) {
    const std::regex label("<text>([^<]*)</text>");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), label); it != std::sregex_iterator(); ++it) {
      labels.insert((*it)[1].str());
    }
    const std::regex plot("id=\"gnuplot_plot_[0-9]+([a-z])\"");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), plot); it != std::sregex_iterator(); ++it) {
      panels.insert((*it)[1].str()[0]);
    }
  }
  [[nodiscard]] bool has(const std::string& label) const { return labels.count(label) > 0; }
  [[nodiscard]] bool has_prefix(const std::string& prefix) const {
    for (const auto& l : labels) {
      if (l.rfind(prefix, 0) == 0) return true;
    }
    return false;
  }
  [[nodiscard]] std::size_t paths() const { return count(text, "<path"); }
};

void expect_valid_svg(const Svg& svg) {
  EXPECT_GT(svg.text.size(), 10000u);
  EXPECT_EQ(svg.text.rfind("<?xml", 0), 0u);
  EXPECT_NE(svg.text.find("<svg"), std::string::npos);
  EXPECT_NE(svg.text.rfind("</svg>"), std::string::npos);
}

void expect_png(const std::filesystem::path& path) {
  ASSERT_TRUE(std::filesystem::exists(path));
  const std::string png = slurp(path);
  EXPECT_GT(png.size(), 20000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // IHDR: width and height, big-endian, at bytes 16-23 (the figures are 1000 px wide)
  ASSERT_GT(png.size(), 24u);
  const auto be32 = [&](std::size_t at) {
    return (static_cast<unsigned>(static_cast<unsigned char>(png[at])) << 24) |
           (static_cast<unsigned>(static_cast<unsigned char>(png[at + 1])) << 16) |
           (static_cast<unsigned>(static_cast<unsigned char>(png[at + 2])) << 8) |
           static_cast<unsigned>(static_cast<unsigned char>(png[at + 3]));
  };
  EXPECT_EQ(be32(16), 1000u);
  EXPECT_GT(be32(20), 500u);
}

void expect_bad_extension(const std::string& args, const std::filesystem::path& dir) {
  const auto bad = dir / "figure.gif";
  const auto r = test::run_cli(args + " --plot " + q(bad));
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
  EXPECT_NE(r.err.find("--plot"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(".svg or .png"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(bad));
}

constexpr const char* kFallingBlock =
    "rock --pulse sine --amp-g 0.25 --duration 0.5 --shape block --width 4cm --height 20cm --e 0.9";

TEST(CliPlot, RockSvgHasThreePanelsThresholdsImpactsAndTheFall) {
  test::TempDir tmp;
  const auto path = tmp.path() / "rock.svg";
  const auto r = test::run_cli(std::string(kFallingBlock) + " --json --plot " + q(path));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.at("overturned").get<bool>());
  const Svg svg(path);
  expect_valid_svg(svg);
  EXPECT_EQ(svg.panels, (std::set<char>{'a', 'b', 'c'}));
  for (const char* label : {"ground acceleration (g)", "rotation θ/α (-)", "angular velocity (rad/s)", "time (s)",
                            "horizontal", "θ/α", "dθ/dt"}) {
    EXPECT_TRUE(svg.has(label)) << label;
  }
  // uplift threshold a/h = 0.02/0.10 in g, the overturning limits theta/alpha = +-1
  EXPECT_TRUE(svg.has("uplift ±a/h = ±0.2 g"));
  EXPECT_TRUE(svg.has("overturning limit ±1"));
  EXPECT_TRUE(svg.has(fmt::format("impacts ({})", j.at("impacts").get<int>())));
  EXPECT_TRUE(svg.has(fmt::format("overturned, t = {:.3f} s", j.at("overturn_time_s").get<double>())));
  // 3 curves, impacts, 4 threshold lines, the fall marked in 3 panels, plus axes and grids
  EXPECT_GE(svg.paths(), 11u);
  EXPECT_FALSE(std::filesystem::exists(path.string() + ".gp"));
}

// The title says the analysis and names the record by its file name only, with its scaling (issue 13).
TEST(CliPlot, TitlesCarryTheAnalysisAndNoDirectory) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared/records is absent";
  test::TempDir tmp;
  const std::filesystem::path record = std::filesystem::absolute(test::shared_record("CPM000.AT2"));
  const auto rock = tmp.path() / "rock.svg";
  auto r = test::run_cli("rock " + q(record) + " --shape block --width 10cm --height 60cm --scale-pga 0.4g --plot " +
                         q(rock));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string rock_svg = test::slurp(rock);
  EXPECT_NE(rock_svg.find("CPM000.AT2 scaled to PGA 0.4g"), std::string::npos);
  EXPECT_NE(rock_svg.find("(Housner)"), std::string::npos);
  EXPECT_EQ(rock_svg.find(record.parent_path().string()), std::string::npos) << "a directory in the title";
  const auto slide = tmp.path() / "slide.svg";
  r = test::run_cli("slide " + q(record) + " --mu 0.2 --slope-deg 5 --one-way --scale 2 --plot " + q(slide));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string slide_svg = test::slurp(slide);
  EXPECT_NE(slide_svg.find("Sliding block, μ = 0.2, slope 5°, one-way: CPM000.AT2 x 2"), std::string::npos);
  EXPECT_EQ(slide_svg.find(record.parent_path().string()), std::string::npos);
  const auto frag = tmp.path() / "frag.svg";
  r = test::run_cli("fragility " + q(record) + " --im-range 0.1:1:4 --mu 0.3 --threshold 5cm --quiet --plot " +
                    q(frag));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string frag_svg = test::slurp(frag);
  EXPECT_NE(frag_svg.find("Fragility over 1 records (CPM000.AT2), slide > d = 5cm at μ = 0.3, two-way"),
            std::string::npos);
  EXPECT_EQ(frag_svg.find(record.parent_path().string()), std::string::npos);
}

TEST(CliPlot, RockWithVerticalRecordDrawsIt) {
  test::TempDir tmp;
  const auto vertical = tmp.path() / "v.csv";
  ASSERT_EQ(test::run_cli("synth --pga 0.1g --freq 8Hz --duration 4s --seed 3 --out " + q(vertical)).exit_code, 0);
  const auto path = tmp.path() / "rock.svg";
  const auto r = test::run_cli("rock --pulse cosine --amp-g 0.3 --duration 0.5 --shape cylinder --diameter 10cm "
                               "--height 40cm --vertical " + q(vertical) + " --plot " + q(path));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("figure written to"), std::string::npos);
  const Svg svg(path);
  expect_valid_svg(svg);
  EXPECT_EQ(svg.panels.size(), 3u);
  EXPECT_TRUE(svg.has("vertical"));
  EXPECT_TRUE(svg.has("uplift ±a/h = ±0.25 g"));
  EXPECT_FALSE(svg.has_prefix("overturned"));
}

TEST(CliPlot, RockPngAndBadExtension) {
  test::TempDir tmp;
  const auto path = tmp.path() / "rock.png";
  const auto r = test::run_cli(std::string(kFallingBlock) + " --plot " + q(path));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  expect_png(path);
  expect_bad_extension(kFallingBlock, tmp.path());
}

TEST(CliPlot, SynthSvgHasTheMotionAndItsSpectrumWithBothFrequencies) {
  test::TempDir tmp;
  const auto path = tmp.path() / "synth.svg";
  // --plot alone: no CSV is needed
  const auto r = test::run_cli("synth --pga 0.3g --freq 3Hz --duration 20s --seed 7 --json --plot " + q(path));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j.at("out").is_null());
  EXPECT_EQ(j.at("plot").get<std::string>(), path.string());
  const Svg svg(path);
  expect_valid_svg(svg);
  EXPECT_EQ(svg.panels, (std::set<char>{'a', 'b'}));
  for (const char* label : {"acceleration (g)", "time (s)", "Fourier amplitude (m/s)", "frequency (Hz)", "FAS",
                            "smoothed (K-O, b = 40)", "requested 3 Hz"}) {
    EXPECT_TRUE(svg.has(label)) << label;
  }
  EXPECT_TRUE(svg.has(fmt::format("measured f_p {:.3g} Hz", j.at("predominant_frequency_hz").get<double>())));
  // log axes: decade tick labels of the amplitude axis
  EXPECT_TRUE(svg.has(" 0.001") && svg.has(" 0.01") && svg.has(" 10"));
}

TEST(CliPlot, SynthPngBadExtensionAndNothingToWrite) {
  test::TempDir tmp;
  const std::string args = "synth --pga 0.2g --freq 5Hz --duration 10s --seed 1";
  const auto csv = tmp.path() / "m.csv";
  const auto png = tmp.path() / "m.png";
  const auto r = test::run_cli(args + " --out " + q(csv) + " --plot " + q(png));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(csv));
  expect_png(png);
  expect_bad_extension(args + " --out " + q(tmp.path() / "n.csv"), tmp.path());
  EXPECT_FALSE(std::filesystem::exists(tmp.path() / "n.csv"));  // refused before any work
  const auto none = test::run_cli(args);
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--out"), std::string::npos) << none.err;
}

TEST(CliPlot, InfoSvgHasGroundMotionAndResponseSpectrumWithTp) {
  test::TempDir tmp;
  const auto csv = tmp.path() / "m.csv";
  ASSERT_EQ(test::run_cli("synth --pga 0.3g --freq 2Hz --duration 15s --seed 5 --out " + q(csv)).exit_code, 0);
  const auto path = tmp.path() / "info.svg";
  const auto r = test::run_cli("info " + q(csv) + " --json --plot " + q(path));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const Svg svg(path);
  expect_valid_svg(svg);
  EXPECT_EQ(svg.panels, (std::set<char>{'a', 'b', 'c', 'd'}));
  for (const char* label : {"acceleration (g)", "velocity (m/s)", "displacement (m)", "time (s)",
                            "pseudo-acceleration (g)", "period (s)", "PSA, 5 % damping"}) {
    EXPECT_TRUE(svg.has(label)) << label;
  }
  EXPECT_TRUE(svg.has(fmt::format("Tp = {:.3f} s", j.at("tp_s").get<double>())));
  EXPECT_GE(svg.paths(), 5u);

  const auto png = tmp.path() / "info.png";
  ASSERT_EQ(test::run_cli("info " + q(csv) + " --plot " + q(png)).exit_code, 0);
  expect_png(png);
  expect_bad_extension("info " + q(csv), tmp.path());
}

// ---- Pulses: every pulse the library has, on both commands ----

TEST(CliPulses, SlideAndRockAcceptEveryPulse) {
  const char* pulses[] = {
      "--pulse rect --amp-g 0.5 --duration 0.2",
      "--pulse tri --amp-g 0.5 --duration 0.2",
      "--pulse double-tri --amp-g 0.5 --duration 0.2",
      "--pulse sine --amp-g 0.5 --duration 0.4",
      "--pulse cosine --amp-g 0.5 --duration 0.4",
      "--pulse ricker --amp-g 0.5 --duration 0.4",
      "--pulse tri-train --amp-g 0.5 --duration 0.4 --cycles 3",
      "--pulse trap-train --amp-g 0.5 --duration 0.4 --cycles 2 --ramp-fraction 0.25",
      "--pulse mp --vel-amp 0.4 --duration 0.8 --gamma 2.5 --nu-deg 90",
  };
  for (const char* pulse : pulses) {
    const auto s = test::run_cli(std::string("slide ") + pulse + " --mu 0.2 --json");
    ASSERT_EQ(s.exit_code, 0) << pulse << "\n" << s.err;
    EXPECT_GT(nlohmann::json::parse(s.out).at("max_abs_displacement_m").get<double>(), 0.0) << pulse;
    const auto k = test::run_cli(std::string("rock ") + pulse + " --shape block --width 10cm --height 40cm --json");
    ASSERT_EQ(k.exit_code, 0) << pulse << "\n" << k.err;
    EXPECT_TRUE(nlohmann::json::parse(k.out).contains("max_rotation_over_alpha")) << pulse;
  }
}

TEST(CliPulses, TrainCyclesAndMpParametersShapeTheMotion) {
  // More cycles: a longer motion (3 cycles of 0.4 s, then a tail of 5 periods).
  const auto one = nlohmann::json::parse(
      test::run_cli("slide --pulse tri-train --amp-g 0.5 --duration 0.4 --mu 0.2 --json").out);
  const auto three = nlohmann::json::parse(
      test::run_cli("slide --pulse tri-train --amp-g 0.5 --duration 0.4 --cycles 3 --mu 0.2 --json").out);
  EXPECT_GT(three.at("input").at("npts").get<int>(), one.at("input").at("npts").get<int>());
  // MP: the velocity amplitude scales the motion linearly; the phase changes it.
  const auto mp = [](const std::string& extra) {
    const auto r = test::run_cli("slide --pulse mp --vel-amp 0.4 --duration 0.8 --mu 0.2 --json " + extra);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return nlohmann::json::parse(r.out).at("input").at("pga_g").get<double>();
  };
  const double base = mp("");
  EXPECT_GT(base, 0.0);
  const double doubled = nlohmann::json::parse(
      test::run_cli("slide --pulse mp --vel-amp 0.8 --duration 0.8 --mu 0.2 --json").out)
                             .at("input").at("pga_g").get<double>();
  EXPECT_NEAR(doubled, 2.0 * base, 1e-9 * base);
  EXPECT_NE(mp("--nu-deg 90"), base);
  EXPECT_NE(mp("--gamma 3"), base);
}

TEST(CliPulses, MisusedPulseOptionsExit2NamingTheOption) {
  const std::pair<const char*, const char*> cases[] = {
      {"--pulse sine --amp-g 0.5 --duration 0.4 --cycles 2", "--cycles"},
      {"--pulse tri-train --amp-g 0.5 --duration 0.4 --cycles 0", "--cycles"},
      {"--pulse tri-train --amp-g 0.5 --duration 0.4 --ramp-fraction 0.2", "--ramp-fraction"},
      {"--pulse trap-train --amp-g 0.5 --duration 0.4 --ramp-fraction 0.7", "--ramp-fraction"},
      {"--pulse mp --amp-g 0.5 --duration 0.8", "--amp-g"},
      {"--pulse mp --duration 0.8", "--vel-amp"},
      {"--pulse mp --vel-amp 0.4 --duration 0.8 --gamma 1", "--gamma"},
      {"--pulse sine --amp-g 0.5 --duration 0.4 --gamma 2", "--gamma"},
      {"--pulse rect --amp-g 0.5 --duration 0.4 --vel-amp 2", "--vel-amp"},
      {"--pulse ricker --amp-g 0.5 --duration 0.4 --nu-deg 10", "--nu-deg"},
      {"--pulse mp --vel-amp 0.4 --duration 0", "--duration"},
      {"--pulse wave --amp-g 0.5 --duration 0.4", "mp"},  // the list of known pulses names mp
  };
  for (const auto& [args, option] : cases) {
    for (const std::string cmd : {"slide --mu 0.2 ", "rock --shape block --width 10cm --height 40cm "}) {
      const auto r = test::run_cli(cmd + args);
      EXPECT_EQ(r.exit_code, 2) << cmd << args << "\n" << r.out;
      EXPECT_NE(r.err.find(option), std::string::npos) << cmd << args << "\n" << r.err;
    }
  }
}

TEST(CliPulses, HelpListsEveryPulseAndItsParameters) {
  for (const char* cmd : {"slide --help", "rock --help"}) {
    const auto r = test::run_cli(cmd);
    ASSERT_EQ(r.exit_code, 0);
    for (const char* word : {"tri-train", "trap-train", "ricker", "mp", "--cycles", "--ramp-fraction", "--vel-amp",
                             "--gamma", "--nu-deg", "--plot"}) {
      EXPECT_NE(r.out.find(word), std::string::npos) << cmd << ": " << word;
    }
  }
}

}  // namespace
}  // namespace topple
