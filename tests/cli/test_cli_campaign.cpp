// `topple campaign`: the one command that scores a shake-table campaign (docs/campaign.md). The summary and rows of a
// campaign whose outcomes are known in closed form (blocks below their static threshold, and far above a
// rectangular pulse's overturning threshold), one outcome deliberately wrong; the outputs written whole; bad files
// refused with exit 2 naming the file, line and key; the example script.
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/csv_table.hpp"
#include "support/shared_data.hpp"

namespace topple {
namespace {

namespace fs = std::filesystem;
using test::run_cli;
using test::TempDir;
using test::write_file;

/// A plain record (time_s, accel_g): `amp_g` for 2 s, then 3 s of still ground, dt 0.005 s.
std::string campaign_pulse_csv(double amp_g) {
  std::string s = "time_s,accel_g\n";
  for (int i = 0; i <= 1000; ++i) s += fmt::format("{:.3f},{}\n", i * 0.005, i * 0.005 < 2.0 ? amp_g : 0.0);
  return s;
}

/// Blocks 0.2 x 0.3 x 0.8 m (b / h = 0.25 along x): 0.1 g does not lift them (below g b / h); 1 g for 2 s is four
/// times the linearised rectangular-pulse threshold g alpha / (1 - exp(-p t1)) = 0.245 g (closed_forms/rocking.hpp):
/// they fall, toward -x (azimuth 180). Test "wrong" is observed overturned though it cannot have moved.
const char* kCampaign = R"([campaign]
name = "closed-form blocks"
models = ["planar", "3d"]

[[test]]
id = "still"
block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }
x = "low.csv"
observed = "standing"

[[test]]
id = "falls"
block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }
x = "high.csv"
observed = "overturned"
observed_azimuth_deg = 190

[[test]]
id = "wrong"
block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }
x = "low.csv"
observed = "overturned"

[[test]]
id = "falls-too"
block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }
x = "high.csv"
y = "low.csv"
observed = "overturned"
)";

TEST(CliCampaign, ClosedFormBlocksScoreThreeOfFour) {
  TempDir dir;
  write_file(dir.path() / "low.csv", campaign_pulse_csv(0.1));
  write_file(dir.path() / "high.csv", campaign_pulse_csv(1.0));
  write_file(dir.path() / "c.toml", kCampaign);
  const fs::path rows = dir.path() / "rows.csv";
  const auto run = run_cli(fmt::format("campaign '{}' --csv '{}' --threads 2", (dir.path() / "c.toml").string(),
                                       rows.string()),
                           120);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const nlohmann::json j = nlohmann::json::parse(run.out);
  EXPECT_EQ(j["campaign"], "closed-form blocks");
  EXPECT_EQ(j["blind"], true);
  EXPECT_EQ(j["tests"], 4);
  ASSERT_EQ(j["models"].size(), 2u);
  EXPECT_EQ(j["models"][0]["model"], "planar");
  EXPECT_EQ(j["models"][1]["model"], "3d");
  for (const auto& m : j["models"]) {
    EXPECT_EQ(m["tp"], 2);
    EXPECT_EQ(m["fp"], 0);
    EXPECT_EQ(m["tn"], 1);
    EXPECT_EQ(m["fn"], 1);
    EXPECT_DOUBLE_EQ(m["accuracy"].get<double>(), 0.75);
    EXPECT_DOUBLE_EQ(m["recall"].get<double>(), 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(m["precision"].get<double>(), 1.0);
    EXPECT_DOUBLE_EQ(m["f1"].get<double>(), 0.8);
    EXPECT_EQ(m["azimuths_compared"], 1);
    EXPECT_NEAR(m["median_azimuth_error_deg"].get<double>(), 10.0, 1e-6);
    EXPECT_DOUBLE_EQ(m["simulated_s"].get<double>(), 20.0);
    EXPECT_GT(m["times_real_time"].get<double>(), 0.0);
    EXPECT_EQ(m["meets_target"]["accuracy"], false);
    EXPECT_EQ(m["meets_target"]["all"], false);
  }
  // The rows: one per test and model, in file order whatever the threads.
  const test::Table t = test::read_table(rows);
  ASSERT_EQ(t.rows.size(), 8u);
  const std::vector<std::string> ids{"still", "still", "falls", "falls", "wrong", "wrong", "falls-too", "falls-too"};
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    EXPECT_EQ(t.at(i, "id"), ids[i]);
    EXPECT_EQ(t.at(i, "model"), i % 2 == 0 ? "planar" : "3d");
    EXPECT_EQ(t.at(i, "predicted"), ids[i].starts_with("falls") ? "overturned" : "standing");
    EXPECT_DOUBLE_EQ(std::stod(t.at(i, "duration_s")), 5.0);
  }
  EXPECT_EQ(t.at(4, "observed"), "overturned");
  EXPECT_NEAR(std::stod(t.at(2, "overturn_azimuth_deg")), 180.0, 1e-6);
  EXPECT_NEAR(std::stod(t.at(2, "overturn_time_s")), std::stod(t.at(3, "overturn_time_s")), 1e-6);  // planar = 3-D in-plane
  EXPECT_EQ(t.at(0, "overturn_time_s"), "");

  // --json: the summary to a file (the same one), a short table on stdout.
  const fs::path summary = dir.path() / "summary.json";
  const auto table = run_cli(fmt::format("campaign '{}' --json '{}' --threads 1 --quiet", (dir.path() / "c.toml").string(),
                                         summary.string()),
                             120);
  ASSERT_EQ(table.exit_code, 0) << table.err;
  EXPECT_NE(table.out.find("accuracy 0.7500"), std::string::npos) << table.out;
  const nlohmann::json again = nlohmann::json::parse(test::slurp(summary));
  EXPECT_EQ(again["models"][1]["tp"], 2);
  EXPECT_EQ(again["models"][1]["fn"], 1);
}

TEST(CliCampaign, BadCampaignsExitTwoNamingFileLineAndKey) {
  TempDir dir;
  write_file(dir.path() / "low.csv", campaign_pulse_csv(0.1));
  const fs::path c = dir.path() / "c.toml";
  write_file(c, "[[test]]\nid = \"t4\"\nblock = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\n"
                "x = \"gone.csv\"\nobserved = \"standing\"\n");
  const auto missing = run_cli(fmt::format("campaign '{}'", c.string()), 60);
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find(c.string() + ":4: test[1].x: test 't4': file"), std::string::npos) << missing.err;
  EXPECT_TRUE(missing.out.empty());

  write_file(dir.path() / "junk.csv", "time_s,accel_g\n0,0.1\n0.005,zz\n");
  write_file(c, "[[test]]\nid = \"t5\"\nblock = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\n"
                "x = \"low.csv\"\nz = \"junk.csv\"\nobserved = \"standing\"\n");
  const fs::path rows = dir.path() / "rows.csv";
  const auto junk = run_cli(fmt::format("campaign '{}' --csv '{}'", c.string(), rows.string()), 60);
  EXPECT_EQ(junk.exit_code, 2);
  EXPECT_NE(junk.err.find(c.string() + ":5: test[1].z: test 't5': "), std::string::npos) << junk.err;
  EXPECT_NE(junk.err.find("junk.csv:3"), std::string::npos) << junk.err;
  EXPECT_FALSE(fs::exists(rows));  // nothing written: the outputs are written whole or not at all

  write_file(c, "[campaign]\nmodels = [\"coupled\"]\n[[test]]\nid = \"a\"\n"
                "block = { width_m = 0.2, depth_m = 0.3, height_m = 0.8 }\nx = \"low.csv\"\nobserved = \"standing\"\n");
  const auto coupled = run_cli(fmt::format("campaign '{}'", c.string()), 60);
  EXPECT_EQ(coupled.exit_code, 2);
  EXPECT_NE(coupled.err.find(":2: campaign.models: the model 'coupled' needs mu"), std::string::npos) << coupled.err;

  const auto threads = run_cli(fmt::format("campaign '{}' --threads -1", c.string()), 60);
  EXPECT_EQ(threads.exit_code, 2);
  EXPECT_NE(threads.err.find("--threads"), std::string::npos) << threads.err;
}

TEST(CliCampaign, ExampleScriptRunsAndScores) {
  TempDir dir;
  const auto run = test::run_example("campaign.sh", "'" + dir.path().string() + "'");
  ASSERT_EQ(run.exit_code, 0) << run.out;
  EXPECT_NE(run.out.find("campaign example: 6 tests, blind"), std::string::npos) << run.out;
  const nlohmann::json j = nlohmann::json::parse(test::slurp(dir.path() / "summary.json"));
  ASSERT_EQ(j["models"].size(), 2u);
  for (const auto& m : j["models"]) {
    EXPECT_EQ(m["tp"].get<int>() + m["fp"].get<int>() + m["tn"].get<int>() + m["fn"].get<int>(), 6);
    EXPECT_DOUBLE_EQ(m["simulated_s"].get<double>(), 60.0);
  }
  // The weak motion (RotD50 PGA 0.1 g; its x component's peak stays below 0.2 g) is below the slender block's static
  // threshold g b / h = 0.2 g: the block cannot move.
  const test::Table t = test::read_table(dir.path() / "rows.csv");
  ASSERT_EQ(t.rows.size(), 12u);
  EXPECT_EQ(t.at(0, "id"), "slender-weak");
  EXPECT_EQ(t.at(0, "predicted"), "standing");
  EXPECT_EQ(std::stod(t.at(0, "max_tilt_over_limit")), 0.0);
}

}  // namespace
}  // namespace topple
