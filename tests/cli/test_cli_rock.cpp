// `topple rock`: the JSON summary (stable keys), the history CSV, records and pulses, vertical input, and bad input
// (exit 2 naming the option). The CLI only parses and prints, so its numbers must be the library's exactly.
#include <cmath>
#include <fstream>
#include <set>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {
namespace {

using test::run_json;

void expect_error(const std::string& args, const std::string& option) {
  const auto r = test::run_cli(args);
  EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out;
  EXPECT_NE(r.err.find(option), std::string::npos) << args << "\n" << r.err;
}

TEST(CliRock, PulseJsonIsTheLibrarySummary) {
  // One-cycle cosine of 0.5 g, 0.5 s on the thesis' object A (4 x 20 cm), g = 9.81: the JSON numbers are those of
  // rock_summary on the same pulse (printed with full precision by nlohmann: equal to round-trip, 1e-15).
  const auto j = run_json("rock --shape block --width 4cm --height 20cm --pulse cosine --amp-g 0.25 --duration 0.5s "
                          "--g 9.81 --e 0.6 --json");
  PulseSpec spec;
  spec.kind = PulseKind::cosine;
  spec.amplitude_m_s2 = 0.25 * 9.81;
  spec.duration_s = 0.5;
  spec.tail_s = 2.5;  // the CLI's default tail: 5 durations
  RockingOptions o;
  o.g_m_s2 = 9.81;
  o.restitution = RestitutionMode::given;
  o.e = 0.6;
  const auto s = rock_summary(make_pulse(spec), RockingBody::block(0.04, 0.20), o);
  ASSERT_GT(s.impacts, 0u);
  EXPECT_NEAR(j.at("max_abs_rotation_rad").get<double>(), s.max_abs_rotation_rad, 1e-15);
  EXPECT_NEAR(j.at("max_rotation_over_alpha").get<double>(), s.max_rotation_over_alpha, 1e-14);
  EXPECT_EQ(j.at("impacts").get<std::size_t>(), s.impacts);
  EXPECT_EQ(j.at("overturned").get<bool>(), s.overturned);
  EXPECT_NEAR(j.at("uplift_time_s").get<double>(), *s.uplift_time_s, 1e-15);
  EXPECT_NEAR(j.at("alpha_rad").get<double>(), std::atan(0.2), 1e-15);
  EXPECT_NEAR(j.at("p_rad_s").get<double>(), std::sqrt(3.0 * 9.81 / (4.0 * std::hypot(0.02, 0.1))), 1e-12);
  EXPECT_DOUBLE_EQ(j.at("e").get<double>(), 0.6);
  EXPECT_DOUBLE_EQ(j.at("g_m_s2").get<double>(), 9.81);
  EXPECT_EQ(j.at("onset_mode").get<std::string>(), "unchecked");
  // Stable interface: these keys are always present (null where there is no value).
  for (const char* key : {"max_abs_rotation_rad", "max_rotation_over_alpha", "impacts", "uplift_time_s",
                          "exceeded_alpha_time_s", "overturned", "overturn_time_s", "alpha_rad", "p_rad_s", "e",
                          "onset_mode", "g_m_s2", "energy_lost_j_per_kg", "body", "solver", "input", "warnings"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j.at("body").at("shape").get<std::string>(), "block");
  EXPECT_DOUBLE_EQ(j.at("body").at("width_m").get<double>(), 0.04);
  EXPECT_DOUBLE_EQ(j.at("body").at("height_m").get<double>(), 0.20);
}

TEST(CliRock, NoUpliftGivesNullTimes) {
  // 0.15 g < a/h = 0.2: the block never leaves full contact.
  const auto j = run_json("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.15 --duration 0.5 --json");
  EXPECT_TRUE(j.at("uplift_time_s").is_null());
  EXPECT_TRUE(j.at("exceeded_alpha_time_s").is_null());
  EXPECT_TRUE(j.at("overturn_time_s").is_null());
  EXPECT_FALSE(j.at("overturned").get<bool>());
  EXPECT_EQ(j.at("max_abs_rotation_rad").get<double>(), 0.0);
  EXPECT_EQ(j.at("e_mode").get<std::string>(), "housner");
  EXPECT_NEAR(j.at("e").get<double>(), 1.0 - 1.5 * std::pow(std::sin(std::atan(0.2)), 2), 1e-15);
}

TEST(CliRock, OverturningPulseAndShapes) {
  // A long rectangular pulse well above the threshold topples every shape.
  const auto block = run_json("rock --shape block --width 4cm --height 20cm --pulse rect --amp-g 0.5 --duration 1s --json");
  EXPECT_TRUE(block.at("overturned").get<bool>());
  EXPECT_FALSE(block.at("overturn_time_s").is_null());
  EXPECT_FALSE(block.at("exceeded_alpha_time_s").is_null());
  EXPECT_EQ(block.at("end_state").get<std::string>(), "fallen");
  const auto cyl = run_json("rock --shape cylinder --diameter 40mm --height 0.2m --pulse rect --amp-g 0.5 --duration 1s --json");
  EXPECT_TRUE(cyl.at("overturned").get<bool>());
  EXPECT_NEAR(cyl.at("body").at("D_m2").get<double>(), (15.0 * 0.02 * 0.02 + 16.0 * 0.1 * 0.1) / 12.0, 1e-15);
  const auto gen = run_json("rock --shape general --a 2cm --h 10cm --D 140cm2 --pulse rect --amp-g 0.5 --duration 1s --json");
  EXPECT_TRUE(gen.at("overturned").get<bool>());
  EXPECT_NEAR(gen.at("body").at("D_m2").get<double>(), 0.014, 1e-15);
}

TEST(CliRock, HistoryCsvHasUnitsInItsHeaderAndValidStates) {
  test::TempDir tmp;
  const auto out = tmp.path() / "h.csv";
  const auto r = test::run_cli("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.3 --duration 0.4 "
                               "--e 0.7 --out '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time_s,theta_rad,theta_dot_rad_s,state");
  const std::set<std::string> states{"rest", "rocking+", "rocking-", "fallen"};
  std::set<std::string> seen;
  int rows = 0;
  std::string line;
  double last_t = -1.0;
  while (std::getline(in, line)) {
    ++rows;
    const auto c3 = line.rfind(',');
    const std::string state = line.substr(c3 + 1);
    EXPECT_TRUE(states.count(state)) << line;
    seen.insert(state);
    const double t = std::stod(line.substr(0, line.find(',')));
    EXPECT_GE(t, last_t) << line;
    last_t = t;
  }
  EXPECT_GT(rows, 2000);  // 2000 pulse samples and the tail, plus events
  EXPECT_TRUE(seen.count("rest"));
  EXPECT_TRUE(seen.count("rocking+") || seen.count("rocking-"));
}

TEST(CliRock, ShentonWarningOnStderr) {
  // mu = 0.1 < a/h = 0.2: the block slides before it can rock; the run still succeeds, with a warning.
  const auto r = test::run_cli("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.3 --duration 0.4 "
                               "--mu 0.1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning"), std::string::npos) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j.at("onset_mode").get<std::string>(), "slide");
  EXPECT_FALSE(j.at("warnings").empty());
  const auto ok = run_json("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.3 --duration 0.4 "
                           "--mu 0.8 --json");
  EXPECT_EQ(ok.at("onset_mode").get<std::string>(), "rock");
}

TEST(CliRock, RecordScaledAndInvertedMatchesTheLibrary) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto path = test::shared_record("RSN6_IMPVALL.I_I-ELC180.AT2");
  const auto j = run_json("rock '" + path.string() + "' --shape block --width 4cm --height 20cm --e 0.75 "
                          "--scale-pga 0.3g --invert --json");
  const GroundMotion m = io::read_motion(path).scaled_to_pga(0.3 * kStandardGravity).inverted();
  RockingOptions o;
  o.restitution = RestitutionMode::given;
  o.e = 0.75;
  const auto s = rock_summary(m, RockingBody::block(0.04, 0.20), o);
  EXPECT_NEAR(j.at("max_abs_rotation_rad").get<double>(), s.max_abs_rotation_rad, 1e-15);
  EXPECT_EQ(j.at("impacts").get<std::size_t>(), s.impacts);
  EXPECT_NEAR(j.at("input").at("pga_g").get<double>(), 0.3, 1e-12);
  EXPECT_TRUE(j.at("input").at("invert").get<bool>());
}

TEST(CliRock, VerticalInputIsReadAndScaled) {
  // A plain vertical record of constant -g/2 halves the effective gravity: a 0.15 g pulse (below a/h = 0.2 alone)
  // rocks the block with it.
  test::TempDir tmp;
  const auto v = tmp.path() / "v.csv";
  test::write_file(v, "time_s,accel_g\n0,-0.5\n5,-0.5\n");
  const std::string base = "rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.15 --duration 0.5 --json";
  EXPECT_TRUE(run_json(base).at("uplift_time_s").is_null());
  const auto j = run_json(base + " --vertical '" + v.string() + "'");
  EXPECT_FALSE(j.at("uplift_time_s").is_null());
  EXPECT_EQ(j.at("input").at("vertical").get<std::string>(), v.string());
}

TEST(CliRock, StepLimitIsExitStatus3NamingTheLimit) {
  // --max-steps sets RockingOptions::max_steps; a rocking sine pulse needs hundreds of steps, so 10 is exceeded.
  const auto r = test::run_cli("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.5 --duration 0.5 "
                               "--max-steps 10");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("max_steps = 10"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("solver limit"), std::string::npos) << r.err;
  EXPECT_EQ(test::run_cli("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.5 --duration 0.5 "
                          "--max-steps 0").exit_code, 2);
}

TEST(CliRock, MethodsAgree) {
  // Fixed-step RK4 (dt/100 on the pulse's 0.25 ms samples) and the adaptive method: max |theta| to 1e-6 relative.
  const std::string base = "rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.3 --duration 0.5 --e 0.7 --json";
  const auto a = run_json(base + " --rtol 1e-10");
  const auto r = run_json(base + " --method rk4 --rk4-substeps 100");
  EXPECT_NEAR(r.at("max_abs_rotation_rad").get<double>() / a.at("max_abs_rotation_rad").get<double>(), 1.0, 1e-6);
  EXPECT_EQ(r.at("solver").at("method").get<std::string>(), "rk4");
}

TEST(CliRock, AsymmetricGeneralBodyReportsEachSide) {
  // --b1 7cm --b2 13cm --h 45cm --inertia 0.025m2 under a sine pulse that throws the body toward -x first (a_h > 0
  // at the start): it falls about O- (the low side, b1). The JSON numbers are the library's (nlohmann prints them
  // to round trip: 1e-15).
  const auto j = run_json("rock --shape general --b1 7cm --b2 13cm --h 45cm --inertia 0.025m2 --pulse sine "
                          "--amp-g 0.3 --duration 0.6s --g 9.81 --json");
  // The CLI's default tail: 5 durations.
  const GroundMotion pulse =
      make_pulse({.kind = PulseKind::sine, .amplitude_m_s2 = 0.3 * 9.81, .duration_s = 0.6, .tail_s = 3.0});
  const RockingBody body = RockingBody::general_asymmetric(0.07, 0.13, 0.45, 0.025);
  RockingOptions o;
  o.g_m_s2 = 9.81;
  const auto s = rock_summary(pulse, body, o);
  ASSERT_TRUE(s.overturned);
  EXPECT_EQ(s.overturned_side, -1);
  EXPECT_EQ(j.at("overturned").get<bool>(), true);
  EXPECT_EQ(j.at("sides").at("overturned_side").get<std::string>(), "negative");
  EXPECT_NEAR(j.at("sides").at("positive").at("max_rotation_rad").get<double>(), s.max_rotation_positive_rad, 1e-15);
  EXPECT_NEAR(j.at("sides").at("negative").at("alpha_rad").get<double>(), std::atan(0.07 / 0.45), 1e-15);
  EXPECT_NEAR(j.at("sides").at("negative").at("e_onto").get<double>(), housner_restitution(body, -1), 1e-15);
  EXPECT_DOUBLE_EQ(j.at("body").at("b1_m").get<double>(), 0.07);
  EXPECT_DOUBLE_EQ(j.at("body").at("b2_m").get<double>(), 0.13);
  // Symmetric bodies keep their keys: no "sides".
  const auto sym = run_json("rock --shape block --width 4cm --height 20cm --pulse sine --amp-g 0.3 --duration 0.6s "
                            "--json");
  EXPECT_FALSE(sym.contains("sides"));
  // Half an asymmetric body, or a mixture with a/D, is refused naming the option.
  expect_error("rock --shape general --b1 7cm --b2 13cm --h 45cm --pulse sine --amp-g 0.3 --duration 0.6s",
               "--inertia");
  expect_error("rock --shape general --b1 7cm --b2 13cm --h 45cm --inertia 0.02m2 --D 0.3m2 --pulse sine --amp-g "
               "0.3 --duration 0.6s",
               "--D");
  expect_error("rock --shape general --b1 -7cm --b2 13cm --h 45cm --inertia 0.02m2 --pulse sine --amp-g 0.3 "
               "--duration 0.6s",
               "--b1");
}

TEST(CliRock, BadInputExitsWithStatus2NamingTheOption) {
  const std::string pulse = "rock --pulse sine --amp-g 0.3 --duration 0.5 ";
  expect_error(pulse + "--shape block --width 0.04 --height 20cm", "--width");          // bare number
  expect_error(pulse + "--shape block --width -4cm --height 20cm", "--width");          // non-positive
  expect_error(pulse + "--shape block --width 4cm", "--height");                        // missing
  expect_error(pulse + "--shape cylinder --diameter 0cm --height 20cm", "--diameter");
  expect_error(pulse + "--shape general --a 2cm --h 10cm --D 0.001m2", "--D");          // D < a^2 + h^2
  expect_error(pulse + "--shape general --a 2cm --h 10cm --D 0.02", "--D");             // no unit
  expect_error(pulse + "--shape block --width 4cm --height 20cm --e 1.5", "--e");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --e -0.1", "--e");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --e soft", "--e");
  expect_error(pulse + "--shape block --width 1m --height 50cm", "--e");                // Housner e < 0
  expect_error(pulse + "--shape block --width 4cm --height 20cm --mu -0.2", "--mu");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --g -9.8", "--g");
  expect_error(pulse + "--width 4cm --height 20cm", "--shape");
  expect_error(pulse + "--shape prism --width 4cm --height 20cm", "--shape");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --diameter 4cm", "--diameter");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --method euler", "--method");
  expect_error(pulse + "--shape block --width 4cm --height 20cm --rtol 2", "--rtol");
  expect_error("rock --shape block --width 4cm --height 20cm", "FILE");  // neither a file nor a pulse
}

// `rock --body FILE` reads what `topple body --json` writes: the same run as the `rock --shape general --b1 --b2 --h
// --inertia` command `topple body` prints for that mesh and azimuth. The printed command carries 9 significant digits
// (5e-9 relative rounding each), the JSON 17: the bodies agree to 1e-8 relative, and the response on a pulse that
// rocks the body without overturning it (a smooth function of the body there) to 1e-6 relative.
TEST(CliRock, BodyFileIsTheBodyTopplePrints) {
  test::TempDir dir;
  const std::string mesh = "'" + std::string(TOPPLE_SOURCE_DIR) + "/examples/mesh/balanced_rock.obj'";
  const auto body_json = test::run_cli("body " + mesh + " --azimuth 30 --json");
  ASSERT_EQ(body_json.exit_code, 0) << body_json.err;
  const auto body_path = dir.path() / "rock body.json";
  test::write_file(body_path, body_json.out);
  const auto text = test::run_cli("body " + mesh + " --azimuth 30");
  ASSERT_EQ(text.exit_code, 0) << text.err;
  const auto from = text.out.find("topple rock --shape general --b1");
  ASSERT_NE(from, std::string::npos) << text.out;
  const auto to = text.out.find('`', from);
  const std::string printed = text.out.substr(from + std::string("topple ").size(), to - from - 7);
  const std::string pulse = " --pulse sine --amp-g 0.2 --duration 0.8s --json";
  const auto a = run_json("rock --body '" + body_path.string() + "'" + pulse);
  const auto b = run_json(printed + pulse);
  ASSERT_GT(a.at("max_rotation_over_alpha").get<double>(), 0.05);  // it rocks...
  ASSERT_FALSE(a.at("overturned").get<bool>());                    // ...and stands
  EXPECT_EQ(b.at("overturned").get<bool>(), false);
  for (const char* key : {"alpha_rad", "R_m", "p_rad_s", "e"}) {
    EXPECT_NEAR(a.at(key).get<double>(), b.at(key).get<double>(), 1e-8 * std::abs(b.at(key).get<double>())) << key;
  }
  for (const char* key : {"max_abs_rotation_rad", "max_rotation_over_alpha", "energy_lost_j_per_kg"}) {
    EXPECT_NEAR(a.at(key).get<double>(), b.at(key).get<double>(), 1e-6 * std::abs(b.at(key).get<double>())) << key;
  }
  EXPECT_EQ(a.at("uplifts"), b.at("uplifts"));
  // The body's b1, b2 and h are the file's exactly (doubles read back from 17 digits).
  const auto j = nlohmann::json::parse(body_json.out);
  EXPECT_EQ(a.at("body").at("b1_m").get<double>(), j.at("b1_m").get<double>());
  EXPECT_EQ(a.at("body").at("b2_m").get<double>(), j.at("b2_m").get<double>());
  EXPECT_EQ(a.at("body").at("h_m").get<double>(), j.at("h_m").get<double>());
}

// A file that is not such a JSON object is refused with exit status 2, naming the file and the field; --body
// excludes the shape options; unknown fields (the pose fields other commands add) are ignored.
TEST(CliRock, BadBodyFileNamesTheFileAndTheField) {
  test::TempDir dir;
  const std::string pulse = " --pulse sine --amp-g 0.2 --duration 0.8s";
  const auto check = [&](const std::string& name, const std::string& content, const std::string& field) {
    const auto path = dir.path() / name;
    test::write_file(path, content);
    const auto r = test::run_cli("rock --body '" + path.string() + "'" + pulse);
    EXPECT_EQ(r.exit_code, 2) << content << "\n" << r.out;
    EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(field), std::string::npos) << r.err;
  };
  const std::string good_rest = R"("h_m": 0.6, "mass_kg": 100, "inertia_cm_plane_kg_m2": 10)";
  check("missing.json", R"({"b1_m": 0.1, )" + good_rest + "}", "b2_m");
  check("text.json", R"({"b1_m": 0.1, "b2_m": "0.2", )" + good_rest + "}", "b2_m");
  check("negative.json", R"({"b1_m": -0.1, "b2_m": 0.2, )" + good_rest + "}", "b1_m");
  check("nan.json", R"({"b1_m": 0.1, "b2_m": 0.2, "h_m": 0.6, "mass_kg": 0, "inertia_cm_plane_kg_m2": 10})", "mass_kg");
  check("array.json", "[1, 2]", "JSON object");
  check("broken.json", "{\"b1_m\": 0.1,\n \"b2_m\": }", "not JSON");
  check("mesh.obj", "v 0 0 0\n", "not JSON");
  // A number beyond double's range: the JSON parser's out_of_range, refused as the others (found by fuzz_body_file).
  check("huge.json", R"({"b1_m": 1e400, "b2_m": 0.2, )" + good_rest + "}", "not a body file");
  const auto none = test::run_cli("rock --body '" + (dir.path() / "absent.json").string() + "'" + pulse);
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("absent.json"), std::string::npos) << none.err;
  // Unknown keys ignored: the body is k2 = 10 / 100 = 0.1 m2, as `--shape general` with the same numbers.
  const auto extra = dir.path() / "extra.json";
  test::write_file(extra, R"({"pose": {"up": [0, 0, 1]}, "b1_m": 0.1, "b2_m": 0.2, )" + good_rest + "}");
  const auto a = run_json("rock --body '" + extra.string() + "'" + pulse + " --json");
  const auto b = run_json("rock --shape general --b1 0.1m --b2 0.2m --h 0.6m --inertia 0.1m2" + pulse + " --json");
  EXPECT_EQ(a.at("max_abs_rotation_rad").get<double>(), b.at("max_abs_rotation_rad").get<double>());
  EXPECT_EQ(a.at("p_rad_s").get<double>(), b.at("p_rad_s").get<double>());
  const auto both = test::run_cli("rock --body '" + extra.string() + "' --shape block" + pulse);
  EXPECT_NE(both.exit_code, 0);
  EXPECT_NE(both.err.find("--body"), std::string::npos) << both.err;
}

}  // namespace
}  // namespace topple
