// `topple rock --model coupled`: the JSON summary is the library's (slide_rock.hpp) exactly, its keys are stable, the
// history CSV has its columns, and bad input exits 2 naming the option.
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <fmt/format.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple {
namespace {

void expect_error(const std::string& args, const std::string& option) {
  const auto r = test::run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
  EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
}

/// The CLI's `--pulse sine --amp-g 1.2 --duration 0.3` (its default tail: 5 durations).
GroundMotion sine_1_2g() {
  PulseSpec spec;
  spec.kind = PulseKind::sine;
  spec.amplitude_m_s2 = 1.2 * kStandardGravity;
  spec.duration_s = 0.3;
  spec.tail_s = 1.5;
  return make_pulse(spec);
}

TEST(CliRockCoupled, JsonIsTheLibrarySummary) {
  // A one-cycle sine of 1.2 g, 0.3 s on a 20 x 60 cm block with mu_s = 0.45, mu_k = 0.4: it rocks, slips and falls.
  // The CLI only translates, so the numbers are slide_rock's on the same pulse (JSON round-trip: 1e-15 relative).
  const auto j = test::run_json("rock --pulse sine --amp-g 1.2 --duration 0.3 --shape block --width 20cm "
                                "--height 60cm --model coupled --mu 0.45 --mu-k 0.4 --json");
  const auto s = slide_rock(sine_1_2g(), SlideRockBody::block(0.2, 0.6, 0.45, 0.4)).summary;
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
  expect_error(base + "--model coupled --mu 0.4 --bearing-deg 30", "--bearing-deg");  // no --h2
  expect_error(base + "--model coupled --mu 0.4 --plot fig.pdf", "--plot");
  expect_error(base + "--model coupled --mu 0.4 --slope-deg 25", "--slope-deg");  // atan(0.4) = 21.8 deg
  expect_error(base + "--model coupled --mu 2 --slope-deg 20", "--slope-deg");    // alpha = 18.4 deg
  expect_error(base + "--model coupled --mu 0.4 --slope-deg -5", "--slope-deg");
  expect_error(base + "--slope-deg 5", "--slope-deg");  // the rocking model has a level base
}

TEST(CliRockCoupled, SlopeIsTheLibrarysInclinedBase) {
  // The JSON case above on an 8 deg slope: the CLI only translates, so the numbers are slide_rock's with slope_rad
  // (JSON round-trip: 1e-15 relative), and the slope is reported.
  const auto j = test::run_json("rock --pulse sine --amp-g 1.2 --duration 0.3 --shape block --width 20cm "
                                "--height 60cm --model coupled --mu 0.45 --mu-k 0.4 --slope-deg 8 --json");
  SlideRockOptions o;
  o.slope_rad = 8.0 * kPi / 180.0;
  const auto s = slide_rock(sine_1_2g(), SlideRockBody::block(0.2, 0.6, 0.45, 0.4), o).summary;
  const auto level = slide_rock(sine_1_2g(), SlideRockBody::block(0.2, 0.6, 0.45, 0.4)).summary;
  ASSERT_NE(s.max_rotation_over_alpha, level.max_rotation_over_alpha);  // the slope changes the response
  EXPECT_EQ(j.at("overturned").get<bool>(), s.overturned);
  EXPECT_EQ(j.at("impacts").get<std::size_t>(), s.impacts);
  EXPECT_NEAR(j.at("residual_slide_m").get<double>(), s.residual_slide_m, 1e-15);
  EXPECT_NEAR(j.at("max_rotation_over_alpha").get<double>(), s.max_rotation_over_alpha, 1e-14);
  EXPECT_NEAR(j.at("slope").at("slope_deg").get<double>(), 8.0, 1e-13);
  EXPECT_EQ(j.at("slope").at("down_slope").get<std::string>(), "-x");
}

/// The synthetic station of test::SyntheticStation: at its 0.3 g a 20 x 80 cm block (b/h = 0.25) with mu_s = 0.26
/// rocks and slips.
class CliRockCoupledPair : public ::testing::Test {
 protected:
  static std::string quote(const std::filesystem::path& p) { return fmt::format("'{}'", p.string()); }
  test::TempDir dir;
  test::SyntheticStation station{dir.path()};
  const std::string& h1 = station.h1;
  const std::string& h2 = station.h2;
  const std::string& v = station.v;
  const std::string body = " --shape block --width 20cm --height 80cm --model coupled --mu 0.26 --json";
};

/// The projection on a component's own azimuth is that component bit for bit (MotionSet::projected), so the coupled
/// run at that bearing is the single-component run: compared exactly (JSON prints 17 digits).
void expect_same_coupled(const nlohmann::json& x, const nlohmann::json& y) {
  for (const char* key : {"overturned", "max_rotation_over_alpha", "residual_slide_m", "max_abs_slide_m",
                          "slip_episodes", "impacts", "onset_mode", "end_mode", "friction_energy_j_per_kg",
                          "impact_energy_j_per_kg", "end_time_s"}) {
    EXPECT_EQ(x.at(key), y.at(key)) << key;
  }
}

TEST_F(CliRockCoupledPair, BearingAlongEitherComponentIsThatComponentAlone) {
  const auto along_h1 =
      test::run_json("rock " + h1 + " --h2 " + h2 + " --vertical " + v + " --azimuths 0,90 --bearing-deg 0" + body);
  const auto alone_h1 = test::run_json("rock " + h1 + " --vertical " + v + body);
  ASSERT_GT(alone_h1.at("impacts").get<int>(), 10);  // the comparison is of a run that rocked
  ASSERT_GT(alone_h1.at("slip_episodes").get<int>(), 0);
  expect_same_coupled(along_h1, alone_h1);
  EXPECT_EQ(along_h1.at("orientation").at("bearing_deg"), 0.0);
  EXPECT_EQ(along_h1.at("orientation").at("azimuths_deg"), nlohmann::json::array({0.0, 90.0}));
  const auto along_h2 =
      test::run_json("rock " + h1 + " --h2 " + h2 + " --vertical " + v + " --azimuths 0,90 --bearing-deg 90" + body);
  expect_same_coupled(along_h2, test::run_json("rock " + h2 + " --vertical " + v + body));
  // The opposite bearing is the same plane with +x reversed: the body is symmetric, so the response is the mirror
  // image (same rotation ratio and impacts; the slide changes sign). Tolerance: the negated input is integrated
  // with the same steps, so the results agree to round-off (1e-12 relative).
  const auto reversed =
      test::run_json("rock " + h1 + " --h2 " + h2 + " --vertical " + v + " --azimuths 0,90 --bearing-deg 180" + body);
  EXPECT_EQ(reversed.at("impacts"), along_h1.at("impacts"));
  EXPECT_NEAR(reversed.at("residual_slide_m").get<double>(), -along_h1.at("residual_slide_m").get<double>(),
              1e-12 * std::abs(along_h1.at("max_abs_slide_m").get<double>()) + 1e-15);
}

TEST_F(CliRockCoupledPair, SlopeLiesInTheBearingsPlane) {
  // --slope-deg with a pair: the base is inclined in the vertical plane of the bearing (down-slope is the body's -x),
  // so along the first component's azimuth the run is that component's alone on the same slope: compared exactly,
  // as above (the projection on a component's own azimuth is that component bit for bit).
  const std::string slope = " --slope-deg 4";
  const auto along_h1 = test::run_json("rock " + h1 + " --h2 " + h2 + " --vertical " + v +
                                       " --azimuths 0,90 --bearing-deg 0" + body + slope);
  const auto alone_h1 = test::run_json("rock " + h1 + " --vertical " + v + body + slope);
  const auto level = test::run_json("rock " + h1 + " --vertical " + v + body);
  ASSERT_NE(alone_h1.at("residual_slide_m"), level.at("residual_slide_m"));  // the slope changes the response
  expect_same_coupled(along_h1, alone_h1);
  EXPECT_NEAR(along_h1.at("slope").at("slope_deg").get<double>(), 4.0, 1e-13);
  // Along the second component: that component alone on the slope.
  expect_same_coupled(test::run_json("rock " + h1 + " --h2 " + h2 + " --vertical " + v +
                                     " --azimuths 0,90 --bearing-deg 90" + body + slope),
                      test::run_json("rock " + h2 + " --vertical " + v + body + slope));
}

TEST_F(CliRockCoupledPair, PairOptionsAreCheckedAndThePlotIsDrawn) {
  const std::string pair = "rock " + h1 + " --h2 " + h2 + " --azimuths 0,90 --shape block --width 20cm --height "
                           "80cm --model coupled --mu 0.26";
  expect_error(pair, "--bearing-deg");                               // the plane must be given
  expect_error(pair + " --bearing-deg 30 --depth 30cm", "--depth");  // one plane only
  expect_error(pair + " --bearing-deg 30 --direction-step-deg 15", "--direction-step-deg");
  const std::filesystem::path svg = dir.path() / "coupled.svg";
  const auto r = test::run_cli(pair + " --bearing-deg 30 --plot " + quote(svg));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(svg);
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  EXPECT_EQ(text.rfind("<?xml", 0), 0u);
  for (const char* label : {"ground acceleration (g)", "of its side", "slide u of the pivot", "mode (index)",
                            "along 30"}) {
    EXPECT_NE(text.find(label), std::string::npos) << label;
  }
}

}  // namespace
}  // namespace topple
