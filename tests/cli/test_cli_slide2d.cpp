// `topple slide FILE --h2 FILE2 --azimuths A1,A2`: bidirectional sliding through the CLI, and its bad input.
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"

namespace topple {
namespace {

/// The same record at 0 and 90 deg is a motion along 45 deg of sqrt(2) times the record: the 1-D solver's result
/// on the scaled record, with the block moving against the axis (toward 225 deg) where the 1-D d is positive. The
/// 2-D solver reproduces the exact 1-D one to 1e-9 (test_sliding2d); JSON prints 17 digits. Returns the 2-D JSON.
nlohmann::json expect_both_axes_equal_scaled_1d(const std::string& options_2d, const std::string& options_1d) {
  const std::string rec = "'" + test::shared_record("slammer/Kocaeli_1999_ATS-090.csv").string() + "'";
  const auto two = test::run_json("slide " + rec + " --h2 " + rec + " --azimuths 0,90 " + options_2d + " --json");
  const auto one = test::run_json("slide " + rec + " --scale 1.4142135623730951 " + options_1d + " --json");
  const double d = one.at("residual_displacement_m").get<double>();
  const double scale = one.at("max_abs_displacement_m").get<double>();
  EXPECT_GT(std::abs(d), 1e-3);
  EXPECT_NEAR(two.at("residual_displacement_m").get<double>(), std::abs(d), 1e-9 * scale);
  EXPECT_NEAR(two.at("max_abs_displacement_m").get<double>(), scale, 1e-9 * scale);
  EXPECT_NEAR(two.at("residual_azimuth_deg").get<double>(), d > 0.0 ? 225.0 : 45.0, 1e-6);
  EXPECT_EQ(two.at("slip_episodes").get<int>(), one.at("slip_episodes").get<int>());
  EXPECT_NEAR(two.at("residual_east_m").get<double>(), two.at("residual_north_m").get<double>(), 1e-9 * scale);
  return two;
}

TEST(CliSlide2d, OneRecordOnBothAxesIsTheScaled1dRecordAt45Degrees) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto two = expect_both_axes_equal_scaled_1d("--mu 0.05", "--mu 0.05");
  for (const char* key : {"path_length_m", "input_work_J_kg", "friction_work_J_kg", "integrator_steps", "input"}) {
    EXPECT_TRUE(two.contains(key)) << key;
  }
}

TEST(CliSlide2d, OneRecordOnBothAxesOnTheFallLineIsThe1dIncline) {
  // As above on a 6 deg slope falling toward 225 deg (the block's 1-D downslope direction): the 1-D incline on the
  // scaled record (method.md S11; 1e-9, as test_sliding2d's CollinearInputOnTheFallLineEqualsThe1dIncline).
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto two = expect_both_axes_equal_scaled_1d("--mu 0.15 --slope-deg 6 --slope-azimuth-deg 225",
                                                    "--mu 0.15 --slope-deg 6");
  EXPECT_NEAR(two.at("input").at("slope_deg").get<double>(), 6.0, 1e-12);
  EXPECT_EQ(two.at("input").at("slope_azimuth_deg").get<double>(), 225.0);
}

TEST(CliSlide2d, BadInputExitsTwoNamingTheOption) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const std::string rec = "'" + test::shared_record("slammer/Kocaeli_1999_ATS-090.csv").string() + "'";
  auto r = test::run_cli("slide " + rec + " --h2 " + rec + " --mu 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--azimuths"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90,10 --mu 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("perpendicular"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90 --mu 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--azimuths"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90,0 --mu 0.1 --slope-deg 5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--slope-deg"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90,0 --mu 0.1 --slope-deg 5");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--slope-azimuth-deg"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --mu 0.1 --slope-deg 5 --slope-azimuth-deg 30");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--slope-azimuth-deg"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90,0 --mu 0.1 --slope-deg 5 --slope-azimuth-deg 30 "
                    "--one-way");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--one-way"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --azimuths 90,0 --mu 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--h2"), std::string::npos) << r.err;
  r = test::run_cli("slide " + rec + " --h2 /nonexistent/h2.csv --azimuths 90,0 --mu 0.1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("/nonexistent/h2.csv"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace topple
