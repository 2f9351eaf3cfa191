// `topple synth` and the measures `topple info` gained: the CSV reads back everywhere with no options, the seed
// reproduces the file byte for byte, bad input exits 2 naming the option.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/spectra.hpp"

namespace topple {
namespace {

using test::run_json;

std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(CliSynth, WritesACsvThatEveryCommandReadsBack) {
  const test::TempDir dir;
  const auto csv = (dir.path() / "motion.csv").string();
  const auto made = run_json("synth --pga 0.3g --freq 3Hz --duration 20s --seed 7 --out '" + csv + "' --json");
  EXPECT_EQ(made.at("npts").get<int>(), 2001);
  EXPECT_DOUBLE_EQ(made.at("pga_g").get<double>(), 0.3);
  const std::string text = slurp(csv);
  EXPECT_NE(text.find("\ntime_s,accel_g\n"), std::string::npos);
  EXPECT_EQ(text.rfind("# topple synth", 0), 0U);
  EXPECT_NE(text.find("seed=7"), std::string::npos);

  const auto info = run_json("info '" + csv + "' --json");
  EXPECT_TRUE(info.at("uniform").get<bool>());
  EXPECT_DOUBLE_EQ(info.at("dt_s").get<double>(), 0.01);
  // Values in g printed in shortest round-trip form: the PGA comes back to 1 ulp of the g conversion.
  EXPECT_NEAR(info.at("pga_g").get<double>(), 0.3, 1e-15);
  // The predominant frequency that synth measured on its motion is the one info measures on the file.
  EXPECT_NEAR(info.at("predominant_frequency_hz").get<double>(), made.at("predominant_frequency_hz").get<double>(),
              1e-9);
  for (const char* key : {"d5_95_s", "d5_time_s", "d95_time_s", "cav_m_s", "tp_s", "tm_s"}) {
    ASSERT_TRUE(info.contains(key)) << key;
    EXPECT_GT(info.at(key).get<double>(), 0.0) << key;
  }
  EXPECT_EQ(test::run_cli("slide '" + csv + "' --mu 0.2 --json").exit_code, 0);
  const auto rock = test::run_cli("rock '" + csv + "' --shape block --width 20cm --height 60cm");
  EXPECT_EQ(rock.exit_code, 0) << rock.err;
}

// --magnitude and --distance-km: a motion of Boore's (2003) stochastic method (motion/stochastic.hpp); its corner
// frequency and duration are the hand values of tests/motion/test_stochastic.cpp (M 6: fc 0.316103 Hz; R 20 km:
// T_gm 4.16353 s); the file reads back; --pga scales it; --freq / --duration are refused with it, and without it
// --pga stays required.
TEST(CliSynth, StochasticPointSourceFromMagnitudeAndDistance) {
  const test::TempDir dir;
  const auto csv = (dir.path() / "m6.csv").string();
  const auto made = run_json("synth --magnitude 6 --distance-km 20 --seed 3 --out '" + csv + "' --json");
  EXPECT_EQ(made.at("model").get<std::string>(), "boore2003");
  EXPECT_NEAR(made.at("corner_frequency_hz").get<double>(), 0.31610274573218144, 1e-12);
  EXPECT_NEAR(made.at("duration_gm_s").get<double>(), 4.163528357476691, 1e-12);
  const double pga = made.at("pga_g").get<double>();
  EXPECT_GT(pga, 0.005);  // M 6 at 20 km on rock: a few hundredths to a tenth of g
  EXPECT_LT(pga, 0.5);
  const auto info = run_json("info '" + csv + "' --json");
  EXPECT_NEAR(info.at("pga_g").get<double>(), pga, 1e-12);
  EXPECT_NEAR(info.at("predominant_frequency_hz").get<double>(), made.at("predominant_frequency_hz").get<double>(),
              1e-9);
  const auto scaled = run_json("synth --magnitude 6 --distance-km 20 --seed 3 --pga 0.2g --out '" + csv + "' --json");
  EXPECT_NEAR(scaled.at("pga_g").get<double>(), 0.2, 1e-12);
  const auto expect_error = [&](const std::string& args, const std::string& option) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  };
  expect_error("synth --magnitude 6 --out '" + csv + "'", "--distance-km");
  expect_error("synth --magnitude 6 --distance-km 20 --freq 3Hz --out '" + csv + "'", "--freq");
  expect_error("synth --magnitude 9.5 --distance-km 20 --out '" + csv + "'", "--magnitude");
  expect_error("synth --freq 3Hz --duration 20s --out '" + csv + "'", "--pga");
}

TEST(CliSynth, SameSeedSameFileOtherSeedOtherFile) {
  const test::TempDir dir;
  const auto a = (dir.path() / "a.csv").string();
  const auto b = (dir.path() / "b.csv").string();
  const auto c = (dir.path() / "c.csv").string();
  const std::string common = "synth --pga 2.5m/s2 --freq 1.5Hz --duration 15s --dt 0.005s --model kanai-tajimi "
                             "--envelope jennings ";
  ASSERT_EQ(test::run_cli(common + "--seed 99 --out '" + a + "'").exit_code, 0);
  ASSERT_EQ(test::run_cli(common + "--seed 99 --out '" + b + "'").exit_code, 0);
  ASSERT_EQ(test::run_cli(common + "--seed 100 --out '" + c + "'").exit_code, 0);
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_NE(slurp(a), slurp(c));
  const GroundMotion m = io::read_motion(a);
  EXPECT_EQ(m.size(), 3001U);
  EXPECT_TRUE(m.is_uniform());
  EXPECT_NEAR(m.pga_m_s2(), 2.5, 1e-14);
}

TEST(CliSynth, BadInputNamesTheOption) {
  const test::TempDir dir;
  const auto out = (dir.path() / "m.csv").string();
  const auto expect_error = [&](const std::string& args, const std::string& option) {
    const auto r = test::run_cli(args);
    EXPECT_EQ(r.exit_code, 2) << args;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  };
  expect_error("synth --pga 0.3 --freq 3Hz --duration 20s --out '" + out + "'", "--pga");
  expect_error("synth --pga 0.3g --freq 3 --duration 20s --out '" + out + "'", "--freq");
  expect_error("synth --pga 0.3g --freq 30Hz --duration 20s --out '" + out + "'", "--freq");
  expect_error("synth --pga 0.3g --freq 3Hz --duration 0.5s --out '" + out + "'", "--duration");
  expect_error("synth --pga 0.3g --freq 3Hz --duration 20s --zeta-g 0.9 --out '" + out + "'", "--zeta-g");
  expect_error("synth --pga 0.3g --freq 3Hz --duration 20s --model boore --out '" + out + "'", "--model");
  expect_error("synth --pga 0.3g --freq 3Hz --duration 20s", "--out");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(CliInfoIntensity, RecordMeasuresMatchTheLibrary) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  const auto path = test::shared_record("RSN6_IMPVALL.I_I-ELC180.AT2");
  const auto j = run_json("info '" + path.string() + "' --json");
  const GroundMotion m = io::read_motion(path);
  const IntensityMeasures im = intensity_measures(m);
  ASSERT_TRUE(im.d5_95 && im.tp_s.value && im.tm_s.value && im.predominant_frequency_hz.value);
  EXPECT_DOUBLE_EQ(j.at("d5_95_s").get<double>(), im.d5_95->duration_s);
  EXPECT_DOUBLE_EQ(j.at("cav_m_s").get<double>(), im.cav_m_s);
  EXPECT_DOUBLE_EQ(j.at("tp_s").get<double>(), *im.tp_s.value);
  EXPECT_DOUBLE_EQ(j.at("tm_s").get<double>(), *im.tm_s.value);
  EXPECT_DOUBLE_EQ(j.at("predominant_frequency_hz").get<double>(), *im.predominant_frequency_hz.value);
  // El Centro 1940 (180): D5-95 24.19 s (eqsig's sample-level value 24.17 s, tests/motion/test_spectra.cpp); Tm in the
  // 0.4-0.6 s of Rathje et al.'s records of this size.
  EXPECT_NEAR(im.d5_95->duration_s, 24.19, 0.01);
  EXPECT_GT(*im.tm_s.value, 0.3);
  EXPECT_LT(*im.tm_s.value, 0.7);
  const auto text = test::run_cli("info '" + path.string() + "'");
  for (const char* label : {"D5-95", "CAV", "Tp", "Tm", "f_p"}) EXPECT_NE(text.out.find(label), std::string::npos);
}

TEST(CliInfoIntensity, ZeroRecordPrintsNullMeasures) {
  const test::TempDir dir;
  const auto csv = dir.path() / "zero.csv";
  test::write_file(csv, "time_s,accel_g\n0,0\n0.01,0\n0.02,0\n0.03,0\n");
  const auto j = run_json("info '" + csv.string() + "' --json");
  EXPECT_TRUE(j.at("d5_95_s").is_null());
  EXPECT_TRUE(j.at("tp_s").is_null());
  EXPECT_TRUE(j.at("predominant_frequency_hz").is_null());
  EXPECT_DOUBLE_EQ(j.at("cav_m_s").get<double>(), 0.0);
}

}  // namespace
}  // namespace topple
