// `topple spectrum slide|rock` and `topple fragility`: JSON equals single runs, CSV headers carry units, figures
// are produced and non-trivial, bad input exits 2 naming the option.
#include <cmath>
#include <algorithm>
#include <vector>
#include <string>
#include <array>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/closed_forms/sliding_pulses.hpp"
#include "topple/motion/pulses.hpp"

namespace topple {
namespace {

using test::slurp;
using test::run_json;

std::string first_line(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  std::getline(in, line);
  return line;
}

TEST(CliSpectrum, SlideEntriesEqualSingleSlideRunsAndTheClosedForm) {
  const std::string pulse = "--pulse rect --amp-g 2 --duration 0.1 --g 9.81";
  const auto j = run_json("spectrum slide " + pulse + " --mu 0.1,0.3,0.5 --json");
  ASSERT_EQ(j.at("points").size(), 3u);
  for (const auto& p : j.at("points")) {
    const double mu = p.at("mu").get<double>();
    const auto one = run_json(fmt::format("slide {} --mu {} --json", pulse, mu));
    EXPECT_DOUBLE_EQ(p.at("max_abs_displacement_m").get<double>(), one.at("max_abs_displacement_m").get<double>());
    EXPECT_DOUBLE_EQ(p.at("residual_displacement_m").get<double>(), one.at("residual_displacement_m").get<double>());
    // thesis Table 3.1 closed form, 1e-9 relative (exact solver on an exactly piecewise-linear pulse)
    const double um = rectangular_pulse_sliding(2.0, 0.1, mu, 9.81).max_displacement_m;
    EXPECT_NEAR(p.at("max_abs_displacement_m").get<double>(), um, 1e-9 * um);
  }
}

TEST(CliSpectrum, SlideCsvAndFigure) {
  test::TempDir tmp;
  const auto csv = tmp.path() / "s.csv";
  const auto svg = tmp.path() / "s.svg";
  const auto r = test::run_cli("spectrum slide --pulse double-tri --amp-g 1 --duration 0.2 --ky-ratio-range 0.05:0.9:12 "
                               "--one-way --slope-deg 5 --out '" + csv.string() + "' --plot '" + svg.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(first_line(csv), "mu,yield_accel_g,ky_over_pga,max_abs_displacement_m,residual_displacement_m,"
                             "slip_episodes,total_slip_duration_s");
  const std::string s = slurp(svg);
  ASSERT_GT(s.size(), 5000u);
  EXPECT_NE(s.find("</svg>"), std::string::npos);
  EXPECT_NE(s.find("sliding displacement (m)"), std::string::npos);
  EXPECT_NE(s.find("PGA"), std::string::npos);
}

TEST(CliSpectrum, RockMapEqualsSingleRockRuns) {
  const std::string pulse = "--pulse sine --amp-g 1 --duration 0.5 --pulse-dt 0.0005";
  const auto j = run_json("spectrum rock " + pulse + " --slenderness 0.25 --heights 20cm,1m --pga 0.3g,0.6g,1g --json");
  ASSERT_EQ(j.at("sizes").size(), 2u);
  const std::vector<std::string> heights{"20cm", "1m"};
  const std::vector<std::string> pgas{"0.3g", "0.6g", "1g"};
  for (std::size_t s = 0; s < 2; ++s) {
    std::optional<double> first;
    const double h = j.at("sizes")[s].at("height_m").get<double>();
    for (std::size_t k = 0; k < 3; ++k) {
      const auto one = run_json(fmt::format("rock {} --scale-pga {} --shape block --width {}m --height {} --json", pulse,
                                            pgas[k], 0.25 * h, heights[s]));
      if (one.at("overturned").get<bool>() && !first) first = j.at("pga_g")[k].get<double>();
    }
    const auto& f = j.at("sizes")[s].at("first_overturn_pga_g");
    if (first) {
      EXPECT_DOUBLE_EQ(f.get<double>(), *first) << s;
    } else {
      EXPECT_TRUE(f.is_null()) << s;
    }
  }
}

TEST(CliSpectrum, RockCsvAndFigure) {
  test::TempDir tmp;
  const auto csv = tmp.path() / "m.csv";
  const auto svg = tmp.path() / "m.svg";
  const auto r = test::run_cli("spectrum rock --pulse sine --amp-g 1 --duration 0.5 --alpha 0.2rad --height-range "
                               "10cm:2m:6 --pga-range 0.1g:1.2g:6 --out '" + csv.string() + "' --plot '" + svg.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(first_line(csv), "height_m,width_m,R_m,p_rad_s,pga_g,overturned,max_rotation_over_alpha");
  const std::string s = slurp(svg);
  ASSERT_GT(s.size(), 5000u);
  EXPECT_NE(s.find("PGA (g)"), std::string::npos);
  EXPECT_NE(s.find("block height 2h (m)"), std::string::npos);
  EXPECT_NE(s.find("first-overturn PGA"), std::string::npos);
}

TEST(CliFragility, SyntheticEnsembleJsonCsvAndFigure) {
  test::TempDir tmp;
  const auto csv = tmp.path() / "f.csv";
  const auto svg = tmp.path() / "f.svg";
  const auto j = run_json("fragility --synth 6 --freq 2Hz --duration 8s --im-range 0.05:1.5:8 --mu 0.2 --threshold 2cm "
                          "--shape block --width 10cm --height 40cm --json --out '" + csv.string() + "' --plot '" +
                          svg.string() + "'");
  ASSERT_EQ(j.at("curves").size(), 2u);
  EXPECT_EQ(j.at("runs").get<int>(), 6 * 8 * 2);
  for (const auto& c : j.at("curves")) {
    ASSERT_FALSE(c.at("fit").is_null()) << c;
    const double theta = c.at("fit").at("theta").get<double>();
    EXPECT_GT(theta, 0.05);
    EXPECT_LT(theta, 1.5);
    EXPECT_EQ(c.at("levels").size(), 8u);
  }
  EXPECT_EQ(first_line(csv), "curve,im_pga_g,trials,failures,fraction,fitted_probability,band_lower,band_upper");
  const std::string s = slurp(svg);
  ASSERT_GT(s.size(), 5000u);
  EXPECT_NE(s.find("PGA (g)"), std::string::npos);
  EXPECT_NE(s.find("probability of failure (-)"), std::string::npos);
}

TEST(CliFragility, SyntheticPairsOnTheRotD50AxisWithRandomBearings) {
  // --synth N --components 2: pairs of independent components at 90,0 (synthesis.hpp), the IM each pair's RotD50 PGA,
  // a bearing drawn per motion (none given).
  test::TempDir tmp;
  const auto csv = tmp.path() / "f.csv";
  const auto j = run_json("fragility --synth 6 --components 2 --freq 2Hz --duration 8s --im-range 0.05:1.5:8 --mu 0.2 "
                          "--threshold 2cm --shape block --width 10cm --height 40cm --json --quiet --out '" +
                          csv.string() + "'");
  EXPECT_NE(j.at("im_definition").get<std::string>().find("RotD50"), std::string::npos);
  EXPECT_NE(j.at("bearing").get<std::string>().find("uniformly random"), std::string::npos);
  ASSERT_EQ(j.at("bearings_deg").size(), 6u);
  for (const auto& b : j.at("bearings_deg")) {
    EXPECT_GE(b.get<double>(), 0.0);
    EXPECT_LT(b.get<double>(), 360.0);
  }
  EXPECT_EQ(j.at("runs").get<int>(), 6 * 8 * 2);
  for (const auto& c : j.at("curves")) {
    EXPECT_EQ(c.at("levels")[0].at("failures").get<int>(), 0) << c;  // 0.05 g: below mu and g tan(alpha)
    EXPECT_EQ(c.at("levels")[7].at("failures").get<int>(), 6) << c;  // 1.5 g: every block slides and falls
  }
  EXPECT_EQ(first_line(csv), "curve,im_rotd50_pga_g,trials,failures,fraction,fitted_probability,band_lower,band_upper");
  // A given bearing: the same for every motion.
  const auto at = run_json("fragility --synth 3 --components 3 --duration 8s --im-range 0.05:0.6:4 --shape block "
                           "--width 10cm --height 40cm --bearing-deg 30 --json --quiet");
  EXPECT_EQ(at.at("bearings_deg"), nlohmann::json::array({30.0, 30.0, 30.0}));
  // With the vertical, levels where a pair's scaled vertical reaches -1 g are outside the rocking model: refused
  // before any run, naming --im-range, the pair and the highest level every pair allows (fragility.cpp).
  const auto high = test::run_cli("fragility --synth 3 --components 3 --duration 8s --im-range 0.05:3:4 --shape block "
                                  "--width 10cm --height 40cm --bearing-deg 30 --quiet");
  EXPECT_EQ(high.exit_code, 2) << high.err;
  EXPECT_NE(high.err.find("--im-range"), std::string::npos) << high.err;
  EXPECT_NE(high.err.find("every pair keeps contact below"), std::string::npos) << high.err;
  EXPECT_TRUE(high.out.empty()) << high.out;
}

TEST(CliFragility, RecordPairWithAZeroSecondComponentIsThe1dFragility) {
  // The record at 90 deg with a zero second component (collinear input) and the block at bearing 90: the record's
  // own 1-D runs (fragility.hpp, "Pairs"; test_fragility). The pair's RotD50 PGA is the record's PGA x cos 45 deg,
  // so its levels are the 1-D levels x cos 45 deg (log grids agree to rounding) and theta comes out x cos 45 deg
  // (1e-8 relative: the fit's stopping rule, far above the grids' rounding).
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  test::TempDir tmp;
  const auto [rec, zero] = test::kocaeli_with_zero_partner(tmp.path());
  const double c = std::cos(std::acos(-1.0) / 4.0);
  const std::string objects = " --mu 0.2 --threshold 5cm --shape block --width 20cm --height 80cm --json --quiet";
  const auto one = run_json("fragility " + rec + " --im-range 0.1:1.5:10" + objects);
  const auto two = run_json("fragility " + rec + " --h2 " + zero + " --azimuths 90,0 --bearing-deg 90 " +
                            fmt::format("--im-range {:.17g}:{:.17g}:10", 0.1 * c, 1.5 * c) + objects);
  ASSERT_EQ(two.at("curves").size(), 2u);
  int failures = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const auto& c1 = one.at("curves")[k];
    const auto& c2 = two.at("curves")[k];
    for (std::size_t i = 0; i < 10; ++i) {
      EXPECT_EQ(c2.at("levels")[i].at("failures"), c1.at("levels")[i].at("failures")) << k << " " << i;
      EXPECT_NEAR(c2.at("levels")[i].at("im_rotd50_pga_g").get<double>(),
                  c1.at("levels")[i].at("im_pga_g").get<double>() * c, 1e-12);
      failures += c1.at("levels")[i].at("failures").get<int>();
    }
    ASSERT_FALSE(c1.at("fit").is_null());
    const double theta = c1.at("fit").at("theta").get<double>();
    EXPECT_NEAR(c2.at("fit").at("theta").get<double>(), theta * c, 1e-8 * theta);
  }
  EXPECT_GT(failures, 4);
}

TEST(CliFragility, PairBadInputExitsTwoNamingTheOption) {
  const std::string objects = " --im-range 0.1:1:3 --mu 0.2 --threshold 5cm --quiet";
  for (const auto& [args, option] :
       {std::pair{"fragility --synth 3 --components 4" + objects, "--components"},
        std::pair{"fragility a.csv --components 2" + objects, "--components"},
        std::pair{"fragility --synth 3 --h2 b.csv" + objects, "--h2"},
        std::pair{"fragility a.csv c.csv --h2 b.csv" + objects, "--h2"},
        std::pair{"fragility a.csv --h2 b.csv --vertical v.csv w.csv" + objects, "--vertical"},
        std::pair{"fragility a.csv --vertical v.csv" + objects, "--vertical"},
        std::pair{"fragility --synth 3" + objects + " --bearing-deg 10", "--bearing-deg"},
        std::pair{"fragility --synth 3" + objects + " --azimuths 90,0", "--azimuths"},
        std::pair{"fragility --synth 3 --components 2" + objects + " --azimuths 90,0", "--azimuths"},
        std::pair{"fragility --synth 3 --components 2 --im pgv" + objects, "--im"},
        std::pair{"fragility --synth 3 --components 2 --one-way --slope-deg 5" + objects, "--one-way"},
        std::pair{"fragility --synth 3 --components 2 --slope-deg 5" + objects, "--slope-deg"},
        std::pair{std::string("fragility --synth 3 --components 2 --im-range 0.1:1:3 --shape cylinder --diameter 10cm "
                              "--height 40cm --bearing-deg 10 --quiet"), "--bearing-deg"},
        std::pair{"fragility --synth 3 --components 2 --bearing-seed x" + objects, "--bearing-seed"}}) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
}

TEST(CliSpectrum, BadInputExitsTwoNamingTheOption) {
  const std::string pulse = " --pulse rect --amp-g 2 --duration 0.1";
  const auto expect2 = [](const std::string& args, const std::string& option) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
  };
  expect2("spectrum slide" + pulse, "--mu");
  expect2("spectrum slide" + pulse + " --mu 0.1,-2", "--mu");
  expect2("spectrum slide" + pulse + " --mu-range 0.1:0.5", "--mu-range");
  expect2("spectrum slide" + pulse + " --mu 0.2 --plot x.pdf", "--plot");
  expect2("spectrum slide /nonexistent/record.AT2 --mu 0.2", "/nonexistent/record.AT2");
  expect2("spectrum rock" + pulse + " --alpha 0.2rad --heights 1m", "--pga");
  expect2("spectrum rock" + pulse + " --alpha 2rad --heights 1m --pga 1g", "--alpha");
  expect2("spectrum rock" + pulse + " --alpha 0.2rad --heights 1m,-2m --pga 1g", "--heights");
  expect2("spectrum rock" + pulse + " --alpha 0.2rad --heights 1m --pga-range 1g:0.1g:3", "--pga-range");
  expect2("spectrum rock" + pulse + " --shape sphere --alpha 0.2rad --heights 1m --pga 1g", "--shape");
  expect2("fragility --synth 3 --im-range 0.1:1:3", "--mu");
  expect2("fragility --synth 3 --im-range 0.1:1:3 --mu 0.2", "--threshold");
  expect2("fragility --synth 3 --im pgz --im-range 0.1:1:3 --mu 0.2 --threshold 1cm", "--im");
  expect2("fragility --synth 3 --mu 0.2 --threshold 1cm", "--im-range");
  expect2("fragility /nonexistent/a.AT2 --im-range 0.1:1:3 --mu 0.2 --threshold 1cm", "/nonexistent/a.AT2");
  expect2("fragility --synth 3 --im-range 0.1:1:3 --shape block --width 0cm --height 1m", "--width");
}

// ---- fragility --as-recorded, general bodies, --body, --mesh, the coupled model ----

/// 40 synthetic records written by `topple synth` (PGA 0.086 to 1.2 g, f_p 1 to 6 Hz, 8 s), their paths quoted.
std::vector<std::string> write_records(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  for (int s = 1; s <= 40; ++s) {
    const double pga = 0.08 * std::pow(1.07, s);
    const double freq = std::array{1.0, 1.5, 2.0, 3.0, 4.0, 6.0}[static_cast<std::size_t>(s % 6)];
    const auto path = dir / fmt::format("r{}.csv", s);
    const auto r = test::run_cli(fmt::format("synth --pga {:.4f}g --freq {}Hz --duration 8s --seed {} --out '{}'", pga,
                                             freq, s, path.string()));
    EXPECT_EQ(r.exit_code, 0) << r.err;
    files.push_back("'" + path.string() + "'");
  }
  return files;
}

std::string joined(const std::vector<std::string>& v, std::size_t n = 1000) {
  std::string out;
  for (std::size_t i = 0; i < std::min(n, v.size()); ++i) out += " " + v[i];
  return out;
}

// Each record runs once as recorded: its PGA is the record's (the synth's, to the 4 decimals asked), its outcome is
// `rock`'s on the same file, and the surface is fitted with finite standard errors (21 of 40 fall here). The CSV has
// its stated columns and the figure its axes.
TEST(CliFragility, AsRecordedRunsEachRecordOnceAndFitsTheSurface) {
  test::TempDir tmp;
  const auto files = write_records(tmp.path());
  const std::string body = " --shape general --b1 5cm --b2 8cm --h 30cm --inertia 0.02m2";
  const auto csv = tmp.path() / "records.csv";
  const auto svg = tmp.path() / "surface.svg";
  const auto j = run_json("fragility --as-recorded --quiet --json" + body + joined(files) + " --out '" + csv.string() +
                          "' --plot '" + svg.string() + "'");
  EXPECT_EQ(j.at("mode"), "as-recorded");
  ASSERT_EQ(j.at("records").size(), 40u);
  EXPECT_EQ(j.at("runs").get<int>(), 40);
  int fell = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const auto& r = j.at("records")[i];
    EXPECT_NEAR(r.at("pga_g").get<double>(), 0.08 * std::pow(1.07, static_cast<double>(i + 1)), 6e-5) << i;
    EXPECT_NEAR(r.at("pgv_over_pga_s").get<double>(),
                r.at("pgv_m_s").get<double>() / (r.at("pga_g").get<double>() * 9.80665), 1e-12);
    const auto one = run_json("rock " + files[i] + body + " --json");
    EXPECT_EQ(r.at("overturn_failed").get<bool>(), one.at("overturned").get<bool>()) << files[i];
    fell += one.at("overturned").get<bool>() ? 1 : 0;
  }
  const auto& c = j.at("curves")[0];
  EXPECT_EQ(c.at("curve"), "overturn");
  EXPECT_EQ(c.at("failures").get<int>(), fell);
  ASSERT_FALSE(c.at("surface").is_null()) << c;
  const auto& f = c.at("surface");
  EXPECT_GT(f.at("beta").get<double>(), 0.0);
  EXPECT_GT(f.at("se_beta").get<double>(), 0.0);
  EXPECT_GT(f.at("se_gamma").get<double>(), 0.0);
  // The median lies above min(b1, b2)/h = 0.167 g, below which no record can even lift the body, and inside the
  // records' PGA range.
  EXPECT_GT(f.at("theta_ref_g").get<double>(), 0.05 / 0.30);
  EXPECT_LT(f.at("theta_ref_g").get<double>(), 1.2);
  EXPECT_EQ(first_line(csv), "motion,pga_g,pgv_m_s,pgv_over_pga_s,overturn_failed,overturn_probability");
  const std::string figure = slurp(svg);
  EXPECT_NE(figure.find("PGV/PGA (s)"), std::string::npos);
  EXPECT_NE(figure.find("P = 0.5"), std::string::npos);
  // The text names the form and the source.
  const auto text = test::run_cli("fragility --as-recorded --quiet" + body + joined(files));
  ASSERT_EQ(text.exit_code, 0) << text.err;
  EXPECT_NE(text.out.find("Purvance"), std::string::npos);
  EXPECT_NE(text.out.find("gamma = "), std::string::npos);
}

// The coupled model: each record's outcome is `rock --model coupled`'s; the mesh (--mesh at an azimuth) and the body
// file `topple body --json` wrote for it give the same outcomes; a general body runs in the scaled fragility too.
TEST(CliFragility, CoupledModelMeshAndBodyFile) {
  test::TempDir tmp;
  const auto files = write_records(tmp.path());
  const std::string some = joined(files, 8);
  const auto j = run_json("fragility --as-recorded --quiet --json --shape block --width 20cm --height 60cm --model "
                          "coupled --rock-mu 0.4 --rock-mu-k 0.35" + some);
  for (std::size_t i = 0; i < 8; ++i) {
    const auto one = run_json("rock " + files[i] + " --shape block --width 20cm --height 60cm --model coupled --mu 0.4 "
                              "--mu-k 0.35 --json");
    EXPECT_EQ(j.at("records")[i].at("overturn_failed").get<bool>(), one.at("overturned").get<bool>()) << files[i];
  }
  const std::string mesh = "'" + std::string(TOPPLE_SOURCE_DIR) + "/examples/mesh/balanced_rock.obj'";
  const auto body_json = test::run_cli("body " + mesh + " --azimuth 30 --json");
  ASSERT_EQ(body_json.exit_code, 0) << body_json.err;
  const auto body_path = tmp.path() / "rock.json";
  test::write_file(body_path, body_json.out);
  const auto by_mesh = run_json("fragility --as-recorded --quiet --json --mesh " + mesh + " --azimuth 30" +
                                joined(files));
  const auto by_body = run_json("fragility --as-recorded --quiet --json --body '" + body_path.string() + "'" +
                                joined(files));
  int fell = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    EXPECT_EQ(by_mesh.at("records")[i].at("overturn_failed"), by_body.at("records")[i].at("overturn_failed")) << i;
    fell += by_mesh.at("records")[i].at("overturn_failed").get<bool>() ? 1 : 0;
  }
  EXPECT_GT(fell, 0);  // the example rock (alpha- 9 deg) falls under the strongest records...
  EXPECT_LT(fell, 40);  // ...and stands under the weakest
  const auto scaled = run_json("fragility --quiet --json --im-range 0.1:1.5:5 --shape general --b1 5cm --b2 8cm --h "
                               "30cm --inertia 0.02m2 --model coupled --rock-mu 0.5" + some);
  EXPECT_EQ(scaled.at("runs").get<int>(), 8 * 5);
  EXPECT_EQ(scaled.at("curves")[0].at("levels").size(), 5u);
}

TEST(CliFragility, AsRecordedAndBodyBadInputExitsTwoNamingTheOption) {
  const std::string block = " --shape block --width 10cm --height 40cm --quiet";
  for (const auto& [args, option] :
       {std::pair{"fragility a.csv --as-recorded --im-range 0.1:1:3" + block, "--im-range"},
        std::pair{"fragility --synth 3 --as-recorded" + block, "--synth"},
        std::pair{"fragility a.csv --h2 b.csv --as-recorded" + block, "--as-recorded"},
        std::pair{"fragility a.csv --as-recorded --im pgv" + block, "--im"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --rock-mu 0.5" + block, "--rock-mu"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --model coupled" + block, "--rock-mu"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --model sliding" + block, "--model"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --model coupled --rock-mu -1" + block, "--rock-mu"},
        std::pair{std::string("fragility --synth 3 --im-range 0.1:1:3 --shape general --b1 5cm --b2 8cm --h 30cm "
                              "--quiet"), "--inertia"},
        std::pair{std::string("fragility --synth 3 --im-range 0.1:1:3 --shape general --b1 5cm --b2 8cm --h 30cm "
                              "--inertia 0.02m2 --height 1m --quiet"), "--height"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --b1 5cm" + block, "--b1"},
        std::pair{"fragility --synth 3 --im-range 0.1:1:3 --body b.json" + block, "--body"},
        std::pair{std::string("fragility --synth 3 --im-range 0.1:1:3 --body absent.json --quiet"), "absent.json"},
        std::pair{std::string("fragility --synth 3 --im-range 0.1:1:3 --mesh absent.obj --quiet"), "absent.obj"}}) {
    const auto r = test::run_cli(args);
    EXPECT_NE(r.exit_code, 0) << args;
    if (std::string(option) != "--body") {
      EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    }
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
}

}  // namespace
}  // namespace topple
