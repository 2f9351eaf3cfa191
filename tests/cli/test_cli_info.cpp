// `topple info FILE --json` on every public record in ../shared/records, and its exit status on bad input.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"

namespace topple {
namespace {

using test::have_shared;
using test::run_cli;
using test::shared_dir;

std::string quote(const std::string& s) { return "'" + s + "'"; }

/// Every record file under shared/records (and records/slammer), with the options it needs: the CSMIP file holds
/// three channels and is run once per channel.
std::vector<std::pair<std::filesystem::path, std::string>> all_records() {
  std::vector<std::pair<std::filesystem::path, std::string>> out;
  for (const auto& sub : {std::filesystem::path("records"), std::filesystem::path("records") / "slammer"}) {
    for (const auto& entry : std::filesystem::directory_iterator(shared_dir() / sub)) {
      if (!entry.is_regular_file()) continue;
      const auto name = entry.path().filename().string();
      if (name == "SOURCES.md" || name == "README.md" || name == "gm_summary.csv") continue;
      if (name == "ce36456p_CE36456.V2") {
        for (int ch = 1; ch <= 3; ++ch) out.emplace_back(entry.path(), " --channel " + std::to_string(ch));
      } else {
        out.emplace_back(entry.path(), "");
      }
    }
  }
  return out;
}

TEST(CliInfo, JsonForEveryRecord) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  const auto records = all_records();
  ASSERT_GE(records.size(), 14u + 18u);  // 12 top-level files (3 CSMIP channels) and 18 pySLAMMER CSVs
  for (const auto& [path, extra] : records) {
    SCOPED_TRACE(path.string() + extra);
    const auto r = run_cli("info " + quote(path.string()) + extra + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);
    for (const char* key : {"npts", "dt_s", "duration_s", "pga_g", "pga_time_s", "pgv_m_s", "pgd_m", "arias_m_s"}) {
      ASSERT_TRUE(j.contains(key)) << key;
      ASSERT_TRUE(j[key].is_number()) << key << " = " << j[key].dump();
      EXPECT_TRUE(std::isfinite(j[key].get<double>())) << key;
    }
    EXPECT_GT(j["npts"].get<double>(), 100.0);
    EXPECT_GT(j["dt_s"].get<double>(), 0.0);
    EXPECT_GT(j["pga_g"].get<double>(), 0.0);
    EXPECT_GT(j["arias_m_s"].get<double>(), 0.0);
    EXPECT_NE(j["format"].get<std::string>(), "");
  }
}

TEST(CliInfo, TextOutput) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  const auto r = run_cli("info " + quote(test::shared_record("RSN6_IMPVALL.I_I-ELC180.AT2").string()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("peer-at2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("5372"), std::string::npos) << r.out;
}

TEST(CliInfo, BadFileExitsWithStatus2AndNamesIt) {
  test::TempDir dir;
  const auto bad = dir.path() / "truncated_record.AT2";
  test::write_file(bad, "PEER\nX\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   10, DT= .01 SEC\n 0.1 0.2\n");
  const auto r = run_cli("info " + quote(bad.string()) + " --json");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad.string() + ":5"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("truncated"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;

  const auto missing = run_cli("info " + quote((dir.path() / "no_such_file.AT2").string()));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_NE(missing.err.find("no_such_file.AT2"), std::string::npos) << missing.err;

  const auto plain = dir.path() / "one_column.txt";
  test::write_file(plain, "0.1\n0.2\n");
  const auto no_units = run_cli("info " + quote(plain.string()));
  EXPECT_EQ(no_units.exit_code, 2);
  EXPECT_NE(no_units.err.find("--units"), std::string::npos) << no_units.err;
  const auto no_dt = run_cli("info " + quote(plain.string()) + " --units g");
  EXPECT_EQ(no_dt.exit_code, 2);
  EXPECT_NE(no_dt.err.find("--dt"), std::string::npos) << no_dt.err;
  const auto ok = run_cli("info " + quote(plain.string()) + " --units g --dt 0.01 --json");
  EXPECT_EQ(ok.exit_code, 0) << ok.err;
}

TEST(CliInfo, CsmipWithoutChannelExitsWithStatus2) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  const auto r = run_cli("info " + quote(test::shared_record("ce36456p_CE36456.V2").string()));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ce36456p_CE36456.V2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--channel"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace topple
