// `topple rock --model coupled`: the JSON summary is the library's (slide_rock.hpp) exactly, its keys are stable, the
// history CSV has its columns, and bad input exits 2 naming the option.
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/pulses.hpp"
#include "topple/slide_rock.hpp"

namespace topple {
namespace {

void expect_error(const std::string& args, const std::string& option) {
  const auto r = test::run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
  EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
}

TEST(CliRockCoupled, JsonIsTheLibrarySummary) {
  // A one-cycle sine of 1.2 g, 0.3 s on a 20 x 60 cm block with mu_s = 0.45, mu_k = 0.4: it rocks, slips and falls.
  // The CLI only translates, so the numbers are slide_rock's on the same pulse (JSON round-trip: 1e-15 relative).
  const auto j = test::run_json("rock --pulse sine --amp-g 1.2 --duration 0.3 --shape block --width 20cm "
                                "--height 60cm --model coupled --mu 0.45 --mu-k 0.4 --json");
  PulseSpec spec;
  spec.kind = PulseKind::sine;
  spec.amplitude_m_s2 = 1.2 * kStandardGravity;
  spec.duration_s = 0.3;
  spec.tail_s = 1.5;  // the CLI's default tail: 5 durations
  const auto s = slide_rock(make_pulse(spec), SlideRockBody::block(0.2, 0.6, 0.45, 0.4)).summary;
  ASSERT_GT(s.slip_episodes, 0);
  EXPECT_EQ(j.at("overturned").get<bool>(), s.overturned);
  EXPECT_EQ(j.at("impacts").get<std::size_t>(), s.impacts);
  EXPECT_EQ(j.at("slip_episodes").get<int>(), s.slip_episodes);
  EXPECT_NEAR(j.at("residual_slide_m").get<double>(), s.residual_slide_m, 1e-15);
  EXPECT_NEAR(j.at("max_rotation_over_alpha").get<double>(), s.max_rotation_over_alpha, 1e-14);
  EXPECT_NEAR(j.at("friction_energy_j_per_kg").get<double>(), s.friction_energy_j_per_kg, 1e-14);
  EXPECT_EQ(j.at("onset_mode").get<std::string>(), std::string(slide_rock_mode_name(s.onset_mode)));
  EXPECT_DOUBLE_EQ(j.at("mu_kinetic").get<double>(), 0.4);
  for (const char* key : {"overturned", "overturned_side", "overturn_time_s", "max_rotation_over_alpha",
                          "residual_slide_m", "max_abs_slide_m", "slip_episodes", "impacts", "onset_mode",
                          "end_mode", "friction_energy_j_per_kg", "impact_energy_j_per_kg", "modes", "warnings",
                          "body", "input"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  for (const char* mode : {"rest", "slide", "rock", "slide-rock", "flight", "fallen"}) {
    EXPECT_TRUE(j.at("modes").contains(mode)) << mode;
  }
  EXPECT_DOUBLE_EQ(j.at("body").at("b1_m").get<double>(), 0.1);
}

TEST(CliRockCoupled, PainleveCaseCompletes) {
  // An asymmetric body (b1 = 20 cm, b2 = 5 cm, h = 30 cm, I/m = 0.00925 m2) with mu = 5 under a one-cycle sine of 3 g,
  // 0.5 s: its pivot passes the stick limit where the slip has no solution (Painleve). This exited 3 (SolverError);
  // now exit 0, the hold counted as the library counts it, and a warning.
  const auto r = test::run_cli("rock --pulse sine --amp-g 3 --duration 0.5 --shape general --b1 20cm --b2 5cm "
                               "--h 30cm --inertia 0.00925m2 --model coupled --mu 5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  PulseSpec spec;
  spec.kind = PulseKind::sine;
  spec.amplitude_m_s2 = 3.0 * kStandardGravity;
  spec.duration_s = 0.5;
  spec.tail_s = 2.5;  // the CLI's default tail: 5 durations
  const auto s = slide_rock(make_pulse(spec), SlideRockBody::make(0.2, 0.05, 0.3, 0.00925, 5.0)).summary;
  ASSERT_GE(s.painleve_holds, 1u);
  EXPECT_EQ(j.at("painleve_holds").get<std::size_t>(), s.painleve_holds);
  EXPECT_EQ(j.at("tangential_impacts").get<std::size_t>(), s.tangential_impacts);
  EXPECT_EQ(j.at("overturned").get<bool>(), s.overturned);
  EXPECT_NE(j.at("warnings").dump().find("Painleve"), std::string::npos) << j.at("warnings").dump();
}

TEST(CliRockCoupled, HistoryCsvHasItsColumns) {
  const std::string out = ::testing::TempDir() + "coupled_history.csv";
  const auto r = test::run_cli("rock --pulse sine --amp-g 0.6 --duration 0.3 --shape block --width 20cm "
                               "--height 60cm --model coupled --mu 0.5 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time_s,slide_m,slide_velocity_m_s,theta_rad,theta_dot_rad_s,cm_height_m,mode");
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) ++rows;
  EXPECT_GT(rows, 100);
}

TEST(CliRockCoupled, BadInputNamesTheOption) {
  const std::string base = "rock --pulse sine --amp-g 1 --duration 0.3 --shape block --width 20cm --height 60cm ";
  expect_error(base + "--model coupled", "--mu");
  expect_error(base + "--model coupled --mu 0.4 --mu-k 0.5", "--mu-k");
  expect_error(base + "--model sideways --mu 0.4", "--model");
  expect_error(base + "--mu 0.4 --mu-k 0.3", "--mu-k");
}

}  // namespace
}  // namespace topple
