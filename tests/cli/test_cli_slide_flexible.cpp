// topple slide on a flexible support: the CLI prints what the library computes, and rejects bad input with exit 2.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/io/read.hpp"
#include "topple/fragility/object_spectra.hpp"

namespace topple {
namespace {

using test::run_cli;
using test::run_json;

const char* kRecord = "RSN6_IMPVALL.I_I-ELC180.AT2";

TEST(CliSlideFlexible, ShelfJsonMatchesTheLibrary) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto path = test::shared_record(kRecord);
  const GroundMotion g = io::read_motion(path);
  for (const bool coupled : {false, true}) {
    // --mass-ratio goes with --coupled only (issue 31: the decoupled analysis ignored it without a word).
    const auto j = run_json(fmt::format("slide '{}' --mu 0.1 --support-freq 4Hz --support-damping 5% {} --json",
                                        path.string(), coupled ? "--mass-ratio 0.2 --coupled" : ""));
    const auto r = slide_flexible(g, SupportOscillator::make(4.0, 0.05, 0.2), SlidingBlock::make(0.1),
                                  coupled ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled);
    // Same library call on the same record: only the JSON's 17 significant digits separate them.
    EXPECT_NEAR(j.at("residual_displacement_m").get<double>(), r.sliding.residual_displacement_m, 1e-15);
    EXPECT_EQ(j.at("support").at("analysis"), coupled ? "coupled" : "decoupled");
    EXPECT_DOUBLE_EQ(j.at("support").at("freq_hz").get<double>(), 4.0);
    EXPECT_DOUBLE_EQ(j.at("support").at("damping_ratio").get<double>(), 0.05);
    EXPECT_NEAR(j.at("support").at("kmax").get<double>(), r.kmax, 1e-15);
  }
}

TEST(CliSlideFlexible, SlidingMassJsonMatchesTheLibrary) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto path = test::shared_record(kRecord);
  const GroundMotion g = io::read_motion(path);
  const auto j = run_json(fmt::format("slide '{}' --mu 0.1 --one-way --height 50m --vs-slope 600 --vs-base 600 "
                                      "--damping 5% --ref-strain 0.05% --coupled --json", path.string()));
  const auto r = slide_flexible(g, SlidingMassColumn::make(50.0, 600.0, 600.0, 0.05, 0.0005), 0.1,
                                FlexibleAnalysis::coupled, SlidingMode::one_way);
  EXPECT_NEAR(j.at("residual_displacement_m").get<double>(), r.sliding.residual_displacement_m, 1e-15);
  EXPECT_NEAR(j.at("support").at("vs_final_m_s").get<double>(), r.mode.vs_m_s, 1e-9);
  EXPECT_DOUBLE_EQ(j.at("support").at("reference_strain").get<double>(), 0.0005);
  EXPECT_GT(r.mode.iterations, 0);
}

TEST(CliSlideFlexible, BadInputExitsTwo) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const std::string rec = "slide '" + test::shared_record(kRecord).string() + "' --mu 0.1 ";
  const auto expect_2 = [](const test::CommandResult& r, const std::string& text) {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find(text), std::string::npos) << r.err;
  };
  expect_2(run_cli(rec + "--support-freq 0Hz"), "got 0 Hz");
  expect_2(run_cli(rec + "--support-freq 4Hz --support-damping 5x"), "5x");
  expect_2(run_cli(rec + "--support-freq 4Hz --height 10m"), "either --support-freq");
  expect_2(run_cli(rec + "--height 10m --vs-slope 300"), "needs --vs-slope, --vs-base and --damping");
  // --out and --plot are available on a flexible support (OutAndPlotWriteTheHistoryAndTheFigure); their paths are
  // checked as the rigid run's, before any work.
  expect_2(run_cli(rec + "--support-freq 4Hz --plot /tmp/never.txt"), "figures are written as .svg or .png");
  // The coupled analysis takes a vertical record (FlexibleVertical tests): it runs.
  const auto with_vertical =
      run_cli(rec + "--support-freq 4Hz --coupled --vertical '" + test::shared_record(kRecord).string() + "'");
  EXPECT_EQ(with_vertical.exit_code, 0) << with_vertical.err;
  expect_2(run_cli(rec + "--support-freq 4Hz --mu-kinetic 0.05 --coupled"), "--mu-kinetic: ");
}

TEST(CliSlideFlexible, OutAndPlotWriteTheHistoryAndTheFigure) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto path = test::shared_record(kRecord);
  const GroundMotion g = io::read_motion(path);
  test::TempDir tmp;
  for (const bool coupled : {false, true}) {
    SCOPED_TRACE(coupled ? "coupled" : "decoupled");
    const auto csv = tmp.path() / (coupled ? "c.csv" : "d.csv");
    const auto svg = tmp.path() / (coupled ? "c.svg" : "d.svg");
    const auto r = run_cli(fmt::format("slide '{}' --mu 0.1 --support-freq 4Hz --support-damping 5% {} "
                                       "--out '{}' --plot '{}'",
                                       path.string(), coupled ? "--mass-ratio 0.2 --coupled" : "", csv.string(),
                                       svg.string()));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("history written to"), std::string::npos) << r.out;
    std::ifstream in(csv);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(header, "time_s,ground_accel_m_s2,support_accel_m_s2,displacement_m,velocity_m_s,state");
    std::string line;
    std::string last;
    std::size_t rows = 0;
    while (std::getline(in, line)) {
      last = line;
      ++rows;
    }
    EXPECT_GE(rows, g.size());  // every record sample at least (sub-steps and events add rows)
    const auto lib = slide_flexible(g, SupportOscillator::make(4.0, 0.05, 0.2), SlidingBlock::make(0.1),
                                    coupled ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled);
    // The last row's displacement (4th column, 12 significant digits) is the residual.
    std::size_t at = 0;
    for (int c = 0; c < 3; ++c) at = last.find(',', at) + 1;
    const double d = std::stod(last.substr(at));
    EXPECT_NEAR(d, lib.sliding.residual_displacement_m, 1e-11 * std::max(1.0, std::abs(d)));
    std::ifstream fig(svg);
    std::string text((std::istreambuf_iterator<char>(fig)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("<svg"), std::string::npos);
    EXPECT_NE(text.find("support"), std::string::npos);  // the support's acceleration is drawn and named
  }
}

TEST(CliSlideFlexible, SpectraOnAFlexibleSupport) {
  // `topple spectrum slide|rock --support-freq`: the spectrum of the support's motion (support_motion), against the
  // library's functions directly; JSON's 17 significant digits are the only difference.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto path = test::shared_record(kRecord);
  const GroundMotion g = io::read_motion(path);
  const GroundMotion on_support = support_motion(g, SupportOscillator::make(2.0, 0.05));
  const auto j = run_json(fmt::format("spectrum slide '{}' --mu 0.1,0.3 --support-freq 2Hz --support-damping 5% --json",
                                      path.string()));
  const std::vector<double> mu{0.1, 0.3};
  const SlidingSpectrum lib = sliding_spectrum(on_support, mu);
  ASSERT_EQ(j.at("points").size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_NEAR(j.at("points")[i].at("max_abs_displacement_m").get<double>(), lib.points[i].max_abs_displacement_m,
                1e-15);
  }
  EXPECT_DOUBLE_EQ(j.at("support").at("ground_pga_g").get<double>(), g.pga_m_s2() / kStandardGravity);
  // The 2 Hz support is near the record's predominant period: it amplifies the peak (measured 0.74 g against 0.28 g).
  EXPECT_GT(j.at("support").at("support_pga_g").get<double>(), 2.0 * j.at("support").at("ground_pga_g").get<double>());
  const auto r = run_cli(fmt::format("spectrum slide '{}' --mu 0.1 --support-damping 5%", path.string()));
  EXPECT_EQ(r.exit_code, 2) << r.err;  // a damping without a support
  EXPECT_NE(r.err.find("--support-damping"), std::string::npos) << r.err;
  const auto rock = run_json(fmt::format("spectrum rock '{}' --alpha 0.2rad --heights 20cm,1m --pga 0.2g,0.4g "
                                         "--support-freq 2Hz --json", path.string()));
  EXPECT_DOUBLE_EQ(rock.at("support").at("freq_hz").get<double>(), 2.0);
}

TEST(CliSlideFlexible, UpperFloorExampleRuns) {
  // examples/upper_floor.sh (README) must keep working: four runs, the coupled one included, exit status 0.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto run = test::run_example("upper_floor.sh", "'" + test::shared_record(kRecord).string() + "'");
  const std::string& out = run.out;
  EXPECT_EQ(run.exit_code, 0) << out;
  EXPECT_NE(out.find("coupled analysis on a shelf/floor oscillator"), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '='), 8) << out;  // four "== ..." headers
}

}  // namespace
}  // namespace topple
