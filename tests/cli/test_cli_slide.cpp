// `topple slide`: JSON interface, pulses, every shared record, and bad input (exit 2 naming the option).
#include <cmath>
#include <filesystem>
#include <fstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/closed_forms/sliding_pulses.hpp"
#include "topple/motion/pulses.hpp"

namespace topple {
namespace {

using test::run_json;

TEST(CliSlide, PulseJsonMatchesTheClosedForm) {
  // Thesis Table 3.1 row 1 with g = 9.81: U_m = 0.5 v^2 / (g N) (1 - N/A), v = A g t0.
  const auto j = run_json("slide --pulse rect --amp-g 2 --duration 0.1 --mu 0.3 --g 9.81 --json");
  const auto cf = rectangular_pulse_sliding(2.0, 0.1, 0.3, 9.81);
  EXPECT_NEAR(j.at("max_abs_displacement_m").get<double>(), cf.max_displacement_m, 1e-9 * cf.max_displacement_m);
  EXPECT_NEAR(j.at("residual_displacement_m").get<double>(), cf.max_displacement_m, 1e-9 * cf.max_displacement_m);
  EXPECT_EQ(j.at("slip_episodes").get<int>(), 1);
  EXPECT_DOUBLE_EQ(j.at("first_slip_time_s").get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j.at("g_m_s2").get<double>(), 9.81);
  EXPECT_DOUBLE_EQ(j.at("mu_static").get<double>(), 0.3);
  EXPECT_EQ(j.at("mode").get<std::string>(), "two-way");
  for (const char* key : {"total_slip_duration_s", "max_displacement_time_s", "input"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
}

TEST(CliSlide, AZeroVerticalRecordKeepsThePulseJump) {
  // Issue 12's bug through the CLI: with an all-zero vertical record every 0.1 s the residual was 0.2419 m instead of
  // the closed form 0.3530 m (the merged grid lost the pulse's jump).
  test::TempDir tmp;
  const auto v = tmp.path() / "zeros.csv";
  std::string text = "time_s,accel_g\n";
  for (int i = 0; i <= 10; ++i) text += std::to_string(0.1 * i) + ",0\n";
  test::write_file(v, text);
  const auto j = run_json("slide --pulse rect --amp-g 0.8 --duration 0.3 --mu 0.4 --json --vertical '" + v.string() + "'");
  const auto cf = rectangular_pulse_sliding(0.8, 0.3, 0.4);
  // Exact solver against the closed form; the JSON prints 17 significant digits, so round-off only.
  EXPECT_NEAR(j.at("residual_displacement_m").get<double>(), cf.max_displacement_m, 1e-12 * cf.max_displacement_m);
  EXPECT_NEAR(j.at("residual_displacement_m").get<double>(), 0.3530, 5e-5);  // the 4 digits
}

TEST(CliSlide, NoSlipGivesNullFirstSlip) {
  const auto j = run_json("slide --pulse tri --amp-g 0.2 --duration 0.1 --mu 0.3 --json");
  EXPECT_TRUE(j.at("first_slip_time_s").is_null());
  EXPECT_EQ(j.at("max_abs_displacement_m").get<double>(), 0.0);
}

TEST(CliSlide, HistoryCsvHasUnitsInItsHeader) {
  test::TempDir tmp;
  const auto out = tmp.path() / "h.csv";
  const auto r = test::run_cli("slide --pulse double-tri --amp-g 2 --duration 0.2 --mu 0.3 --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time_s,ground_accel_m_s2,displacement_m,velocity_m_s,state");
  int rows = 0;
  std::string line;
  while (std::getline(in, line)) ++rows;
  EXPECT_GT(rows, 5);
}

TEST(CliSlide, EveryRecordInSharedSlides) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(test::shared_dir() / "records")) {
    if (!entry.is_regular_file() || entry.path().extension() == ".md") continue;
    std::string extra;
    if (entry.path().filename() == "ce36456p_CE36456.V2") extra = " --channel 1";
    const auto j = run_json("slide '" + entry.path().string() + "'" + extra + " --mu 0.1 --scale-pga 0.3g --json");
    EXPECT_NEAR(j.at("input").at("pga_g").get<double>(), 0.3, 1e-12) << entry.path();
    EXPECT_GT(j.at("max_abs_displacement_m").get<double>(), 0.0) << entry.path();
    EXPECT_TRUE(std::isfinite(j.at("residual_displacement_m").get<double>())) << entry.path();
    ++files;
  }
  EXPECT_GE(files, 12);
}

TEST(CliSlide, ShakeTableFileAsRecordedWithColumnsAndBaseline) {
  // A table record as a lab writes it (issue 28): a tab-separated header whose names hold spaces, eight columns, a
  // +0.02 g DC offset on the table acceleration; the shaking is a 2 g, 0.1 s pulse after 1 s of quiet. With
  // --columns and --baseline pre-event:0.5 the slide is the one of the clean pulse written as a two-column file,
  // to rounding; without --baseline the offset changes it.
  test::TempDir tmp;
  const auto table = tmp.path() / "table.txt";
  const auto clean = tmp.path() / "clean.csv";
  std::string t = "Time (s)\tTable Acc (g)\tTable Disp (mm)\tTable Vel (m/s)\tAcc 2 (g)\tStatus\tLVDT 1 (mm)\tCmd (mm)\n";
  std::string c = "time_s,accel_g\n";
  for (int k = 0; k <= 3000; ++k) {
    const double time = 0.001 * k;
    const double a = (k >= 1000 && k <= 1100) ? 2.0 : 0.0;
    t += fmt::format("{:.3f}\t{:.17g}\t{}\t0\t0.1\t{}\t0\t0\n", time, a + 0.02, k, k % 7 ? "run" : "-");
    c += fmt::format("{:.3f},{:.17g}\n", time, a);
  }
  test::write_file(table, t);
  test::write_file(clean, c);
  const auto ref = run_json("slide '" + clean.string() + "' --mu 0.3 --json");
  const double d_ref = ref.at("max_abs_displacement_m").get<double>();
  // The sampled pulse is a trapezoid (ramps of 1 ms) of the area of a 0.101 s rectangle: it slides as that
  // rectangle (closed form) to within the ramps' effect.
  const auto cf = rectangular_pulse_sliding(2.0, 0.101, 0.3);
  EXPECT_NEAR(d_ref, cf.max_displacement_m, 0.005 * cf.max_displacement_m);
  for (const std::string cols : {"--columns 1,2", "--columns 'Time (s),Table Acc (g)'",
                                 "--columns '\"Time (s)\",\"Table Acc (g)\"'"}) {
    const auto j = run_json("slide '" + table.string() + "' " + cols + " --baseline pre-event:0.5 --mu 0.3 --json");
    EXPECT_NEAR(j.at("max_abs_displacement_m").get<double>(), d_ref, 1e-9 * d_ref) << cols;
    EXPECT_NEAR(j.at("input").at("pga_g").get<double>(), 2.0, 1e-12) << cols;
  }
  const auto raw = run_json("slide '" + table.string() + "' --columns 1,2 --mu 0.3 --json");
  EXPECT_GT(std::abs(raw.at("max_abs_displacement_m").get<double>() - d_ref), 1e-3 * d_ref);
  // Bad choices: exit 2 naming the option and, for a missing name, the header's names.
  auto r = test::run_cli("slide '" + table.string() + "' --columns 'Time (s),Acc (g)' --mu 0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--columns"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("'Table Acc (g)'"), std::string::npos) << r.err;
  r = test::run_cli("slide '" + table.string() + "' --columns 1,2 --baseline poly:4 --mu 0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--baseline"), std::string::npos) << r.err;
  r = test::run_cli("slide '" + table.string() + "' --mu 0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("8 columns"), std::string::npos) << r.err;
}

TEST(CliSlide, BadInputExitsTwoNamingTheOption) {
  auto r = test::run_cli("slide --pulse rect --amp-g 2 --duration 0.1 --mu -1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("mu"), std::string::npos) << r.err;
  r = test::run_cli("slide --pulse rect --amp-g 2 --duration 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--mu"), std::string::npos) << r.err;
  r = test::run_cli("slide --pulse square --amp-g 2 --duration 0.1 --mu 0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--pulse"), std::string::npos) << r.err;
  r = test::run_cli("slide /nonexistent/file.AT2 --mu 0.3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/file.AT2"), std::string::npos) << r.err;
  r = test::run_cli("slide --pulse rect --amp-g 2 --duration 0.1 --mu 0.3 --scale-pga 0.5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--scale-pga"), std::string::npos) << r.err;
  r = test::run_cli("slide --pulse rect --amp-g 2 --duration 0.1 --mu 0.3 --slope-deg 95");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_cli("slide --pulse rect --amp-g 2 --duration 0.1 --mu nope");
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace topple
