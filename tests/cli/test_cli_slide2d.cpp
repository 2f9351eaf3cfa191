// `topple slide FILE --h2 FILE2 --azimuths A1,A2`: bidirectional sliding through the CLI, and its bad input.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/csv_table.hpp"
#include "support/shared_data.hpp"

namespace topple {
namespace {

/// A friction coefficient as the command line takes it back: shortest round-trip digits.
std::string fmt_mu(double mu) { return nlohmann::json(mu).dump(); }

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

TEST(CliSlide2d, HistoryOfTheRecordOnBothAxesIsThe1dHistoryAlong225Degrees) {
  // The same record at 0 and 90 deg is the 1-D motion sqrt(2) x record along 45 deg; the block moves against it
  // where the 1-D d is positive, so each history row's east and north displacement and velocity are -d / sqrt(2),
  // -v / sqrt(2), the ground's east and north components a / sqrt(2) of the scaled 1-D record, and the rows (grid
  // points and events) are the same. Tolerances: the 2-D solver matches the exact 1-D one to 1e-9 relative
  // (test_sliding2d); the CSVs print 9 (ground, time) and 12 (response) digits.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const std::string rec = "'" + test::shared_record("slammer/Kocaeli_1999_ATS-090.csv").string() + "'";
  test::TempDir tmp;
  const auto two_path = tmp.path() / "two.csv";
  const auto one_path = tmp.path() / "one.csv";
  auto r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 0,90 --mu 0.05 --out '" + two_path.string() +
                         "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("history written to"), std::string::npos) << r.out;
  r = test::run_cli("slide " + rec + " --scale 1.4142135623730951 --mu 0.05 --out '" + one_path.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::Table two = test::read_table(two_path);
  const test::Table one = test::read_table(one_path);
  EXPECT_EQ(two.header, (std::vector<std::string>{"time_s", "ground_east_m_s2", "ground_north_m_s2", "ground_up_m_s2",
                                                  "displacement_east_m", "displacement_north_m", "velocity_east_m_s",
                                                  "velocity_north_m_s", "slipping"}));
  ASSERT_EQ(two.rows.size(), one.rows.size());
  ASSERT_GT(two.rows.size(), 26000U);  // 26780 samples and the events
  const double root2 = std::sqrt(2.0);
  const double u_scale = 0.238159;  // the run's max |u| (m), printed by `slide`
  const double v_scale = 0.420487;  // its peak relative speed (m/s)
  int slipping_rows = 0;
  for (std::size_t i = 0; i < two.rows.size(); ++i) {
    const auto cell = [](const test::Table& t, std::size_t row, const char* col) { return std::stod(t.at(row, col)); };
    ASSERT_NEAR(cell(two, i, "time_s"), cell(one, i, "time_s"), 1e-8) << i;
    const double a = cell(one, i, "ground_accel_m_s2") / root2;
    EXPECT_NEAR(cell(two, i, "ground_east_m_s2"), a, 1e-8 * (std::abs(a) + 1e-3)) << i;
    EXPECT_NEAR(cell(two, i, "ground_north_m_s2"), a, 1e-8 * (std::abs(a) + 1e-3)) << i;
    EXPECT_EQ(cell(two, i, "ground_up_m_s2"), 0.0) << i;
    const double d = -cell(one, i, "displacement_m") / root2;
    const double v = -cell(one, i, "velocity_m_s") / root2;
    EXPECT_NEAR(cell(two, i, "displacement_east_m"), d, 1e-9 * u_scale) << i;
    EXPECT_NEAR(cell(two, i, "displacement_north_m"), d, 1e-9 * u_scale) << i;
    EXPECT_NEAR(cell(two, i, "velocity_east_m_s"), v, 1e-9 * v_scale) << i;
    EXPECT_NEAR(cell(two, i, "velocity_north_m_s"), v, 1e-9 * v_scale) << i;
    const bool slipping = one.at(i, "state") != "0";
    EXPECT_EQ(two.at(i, "slipping"), slipping ? "1" : "0") << i;
    slipping_rows += slipping ? 1 : 0;
  }
  EXPECT_GT(slipping_rows, 1000);  // 15.6 s of slip at 0.005 s
}

TEST(CliSlide2d, HistoryCarriesTheVerticalAndIsRefusedWithFlexibleSupports) {
  // The vertical column is the vertical record as given (scaled with the horizontal; --scale 1 here), to its
  // 9 printed digits.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const std::string rec = "'" + test::shared_record("slammer/Kocaeli_1999_ATS-090.csv").string() + "'";
  test::TempDir tmp;
  const auto path = tmp.path() / "h.csv";
  auto r = test::run_cli("slide " + rec + " --h2 " + rec + " --vertical " + rec + " --azimuths 90,0 --mu 0.2 --out '" +
                         path.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::Table t = test::read_table(path);
  ASSERT_GT(t.rows.size(), 1000U);
  // east = the first component, north = the second, up = the vertical: the same record in all three columns
  for (std::size_t i = 0; i < t.rows.size(); i += 97) {
    const double east = std::stod(t.at(i, "ground_east_m_s2"));
    EXPECT_NEAR(std::stod(t.at(i, "ground_north_m_s2")), east, 1e-8 * (std::abs(east) + 1e-3)) << i;
    EXPECT_NEAR(std::stod(t.at(i, "ground_up_m_s2")), east, 1e-8 * (std::abs(east) + 1e-3)) << i;
  }
  r = test::run_cli("slide " + rec + " --h2 " + rec + " --azimuths 90,0 --mu 0.2 --support-freq 5 --out '" +
                    path.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--h2"), std::string::npos) << r.err;
}

TEST(CliSlide2d, SpectrumPointsAreTheSingleRunsAndItsAxisIsTheRotD50Pga) {
  // A synthetic station (`synth --components 3`: H1 east, H2 north, V; portable samples): each spectrum point is
  // `slide --h2 --json` at its mu, the same call on the same set, so every field is equal exactly (JSON prints 17
  // digits); each component alone is `slide FILE --vertical V --json`.
  test::TempDir dir;
  const std::string base = "'" + (dir.path() / "m.csv").string() + "'";
  (void)test::run_json("synth --components 3 --pga 0.4g --freq 2Hz --duration 15 --seed 7 --azimuths 90,0 --json "
                       "--out " + base);
  const std::string h1 = "'" + (dir.path() / "m.h1.csv").string() + "'";
  const std::string h2 = "'" + (dir.path() / "m.h2.csv").string() + "'";
  const std::string v = "'" + (dir.path() / "m.v.csv").string() + "'";
  const std::string pair = h1 + " --h2 " + h2 + " --vertical " + v + " --azimuths 90,0";
  const auto sp = test::run_json("spectrum slide " + pair + " --mu 0.05,0.15,0.3 --json");
  ASSERT_EQ(sp.at("points").size(), 3U);
  EXPECT_EQ(sp.at("vertical"), true);
  EXPECT_EQ(sp.at("pga_axis"), "RotD50 of the pair (Boore 2010)");
  // The PGA axis is `info H1 H2`'s RotD50 PGA (the same function on the same merged pair; info prints 6 digits),
  // which is the --pga synth scaled the pair to (synthesis.hpp: the request to round-off).
  const auto info = test::run_json("info " + h1 + " " + h2 + " --azimuths 90,0 --json");
  const double rotd50 = info.at("rotd").at("pga").at("rotd50_g").get<double>();
  EXPECT_NEAR(sp.at("rotd50_pga_g").get<double>(), rotd50, 5e-7 * rotd50);
  EXPECT_NEAR(sp.at("rotd50_pga_g").get<double>(), 0.4, 1e-9);
  int moved = 0;
  for (const auto& p : sp.at("points")) {
    const double mu = p.at("mu").get<double>();
    SCOPED_TRACE(mu);
    // k_y / PGA on the RotD50 axis: mu g / RotD50 (1e-12: rounding of the division and of the printed digits).
    EXPECT_NEAR(p.at("ky_over_rotd50_pga").get<double>(), mu / sp.at("rotd50_pga_g").get<double>(), 1e-12);
    const auto one = test::run_json("slide " + pair + " --mu " + fmt_mu(mu) + " --json");
    for (const auto& [key, value] : one.items()) {
      if (key == "input") continue;
      EXPECT_EQ(p.at(key), value) << key;
    }
    for (const auto& [alone, file] : {std::pair{"h1_alone", h1}, std::pair{"h2_alone", h2}}) {
      const auto single = test::run_json("slide " + file + " --vertical " + v + " --mu " + fmt_mu(mu) + " --json");
      for (const char* key : {"max_abs_displacement_m", "residual_displacement_m", "slip_episodes"}) {
        EXPECT_EQ(p.at(alone).at(key), single.at(key)) << alone << " " << key;
      }
    }
    moved += p.at("residual_displacement_m").get<double>() > 1e-3 ? 1 : 0;
  }
  EXPECT_GE(moved, 2);
  // --ky-ratio-range on the RotD50 axis: mu = ratio x RotD50 / g, so the axis gives back the ratio (1e-12 relative).
  const auto ky = test::run_json("spectrum slide " + pair + " --ky-ratio-range 0.2:0.6:3 --json");
  const double ratios[] = {0.2, 0.4, 0.6};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(ky.at("points")[i].at("ky_over_rotd50_pga").get<double>(), ratios[i], 1e-12);
  }
  // The CSV has the same numbers (shortest round-trip digits).
  test::TempDir tmp;
  const auto csv = tmp.path() / "sp.csv";
  const auto r = test::run_cli("spectrum slide " + pair + " --mu 0.05,0.15,0.3 --out '" + csv.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::Table t = test::read_table(csv);
  ASSERT_EQ(t.rows.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& p = sp.at("points")[i];
    for (const char* key : {"max_abs_displacement_m", "residual_displacement_m", "residual_azimuth_deg",
                            "path_length_m", "max_abs_velocity_m_s", "slip_episodes", "total_slip_duration_s"}) {
      test::expect_same(t.at(i, key), p.at(key), key);
    }
    test::expect_same(t.at(i, "h2_max_abs_displacement_m"), p.at("h2_alone").at("max_abs_displacement_m"), "h2");
  }
}

TEST(CliSlide2d, SpectrumOfACollinearPairIsThe1dSpectrum) {
  // The record at 90 deg with a zero second component is collinear input: the 2-D spectrum is the 1-D one of the
  // record, max |u| and |residual| to 1e-9 relative (the 2-D solver's agreement with the exact 1-D one,
  // test_sliding2d), the block moving west (270 deg) where the 1-D d is positive.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  test::TempDir tmp;
  const auto [h1, zero] = test::kocaeli_with_zero_partner(tmp.path());
  const auto two = test::run_json("spectrum slide " + h1 + " --h2 " + zero + " --azimuths 90,0 "
                                  "--mu 0.05,0.1,0.2 --json");
  const auto one = test::run_json("spectrum slide " + h1 + " --mu 0.05,0.1,0.2 --json");
  for (std::size_t i = 0; i < 3; ++i) {
    const auto& p2 = two.at("points")[i];
    const auto& p1 = one.at("points")[i];
    const double scale = p1.at("max_abs_displacement_m").get<double>();
    const double d = p1.at("residual_displacement_m").get<double>();
    EXPECT_NEAR(p2.at("max_abs_displacement_m").get<double>(), scale, 1e-9 * scale);
    EXPECT_NEAR(p2.at("residual_displacement_m").get<double>(), std::abs(d), 1e-9 * scale);
    EXPECT_NEAR(p2.at("residual_east_m").get<double>(), -d, 1e-9 * scale);
    if (std::abs(d) > 1e-6) {
      EXPECT_NEAR(p2.at("residual_azimuth_deg").get<double>(), d > 0 ? 270.0 : 90.0, 1e-6);
    }
    EXPECT_EQ(p2.at("slip_episodes"), p1.at("slip_episodes"));
    EXPECT_EQ(p2.at("h1_alone").at("residual_displacement_m"), p1.at("residual_displacement_m"));
    EXPECT_EQ(p2.at("h2_alone").at("max_abs_displacement_m").get<double>(), 0.0);
  }
}

TEST(CliSlide2d, SpectrumBadInputExitsTwoNamingTheOption) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const std::string rec = "'" + test::shared_record("slammer/Kocaeli_1999_ATS-090.csv").string() + "'";
  const std::string pair = "spectrum slide " + rec + " --h2 " + rec + " --azimuths 90,0";
  for (const auto& [args, option] :
       {std::pair{pair + " --mu 0.1 --slope-deg 5", "--slope-deg"}, std::pair{pair + " --mu 0.1 --one-way", "--one-way"},
        std::pair{pair + " --mu 0.1 --bearing-deg 30", "--bearing-deg"},
        std::pair{pair + " --mu 0.1 --plot x.svg", "--plot"},
        std::pair{pair + " --mu 0.1 --support-freq 4Hz", "--support-freq"},
        std::pair{pair + " --mu 0.1,-0.2", "--mu"}, std::pair{pair + " --mu-range 0.1:0.2:0", "--mu-range"},
        std::pair{"spectrum slide " + rec + " --h2 " + rec + " --mu 0.1", "--azimuths"},
        std::pair{"spectrum slide " + rec + " --vertical " + rec + " --mu 0.1", "--vertical"},
        std::pair{"spectrum slide " + rec + " --bearing-deg 10 --mu 0.1", "--bearing-deg"}}) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
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
