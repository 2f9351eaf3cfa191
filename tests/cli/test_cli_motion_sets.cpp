// Motion sets through the CLI: `topple info H1 H2 [V]` (RotD), `topple synth --components 2|3`, and
// `topple slide H1 --h2 H2` reading the azimuths from the headers; their bad input.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

std::string quote(const std::filesystem::path& p) { return fmt::format("'{}'", p.string()); }

TEST(CliInfoPair, CsmipChannelsWithHeaderAzimuthsAndRotD) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  const std::string v2 = quote(test::shared_record("ce36456p_CE36456.V2"));
  const auto j = test::run_json("info " + v2 + " " + v2 + " " + v2 + " --channels 1,3,2 --json");
  ASSERT_EQ(j.at("components").size(), 3u);
  EXPECT_EQ(j.at("azimuths_deg"), nlohmann::json({90.0, 0.0}));  // CHAN 1: 90 DEG, CHAN 3: 0 DEG
  EXPECT_TRUE(j.at("components")[2].at("vertical").get<bool>());  // CHAN 2: UP
  // Each component's block is what `info FILE --channel c` prints (same reader, same measures): equal numbers.
  const auto single = test::run_json("info " + v2 + " --channel 3 --json");
  EXPECT_EQ(j.at("components")[1].at("pga_g"), single.at("pga_g"));
  EXPECT_EQ(j.at("components")[1].at("tp_s"), single.at("tp_s"));
  // The RotD numbers are the library's (rotd_measures on the same set, checked against pyrotd in test_motion_set);
  // JSON prints 17 digits: equal to 1e-15 relative.
  io::ReadOptions r1, r3;
  r1.channel = 1;
  r3.channel = 3;
  const GroundMotion h1 = io::read_motion(test::shared_record("ce36456p_CE36456.V2"), r1);
  const GroundMotion h2 = io::read_motion(test::shared_record("ce36456p_CE36456.V2"), r3);
  const RotDMeasures lib = rotd_measures(MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0}), rotd_periods_s());
  const auto& rotd = j.at("rotd");
  const double g = kStandardGravity;
  EXPECT_NEAR(rotd.at("pga").at("rotd50_g").get<double>(), lib.pga_m_s2.rotd50 / g, 1e-15);
  EXPECT_NEAR(rotd.at("pga").at("rotd100_g").get<double>(), lib.pga_m_s2.rotd100 / g, 1e-15);
  ASSERT_EQ(rotd.at("psa").size(), rotd_periods_s().size());
  for (std::size_t p = 0; p < lib.psa_m_s2.size(); ++p) {
    const auto& row = rotd.at("psa")[p];
    EXPECT_NEAR(row.at("rotd50_g").get<double>(), lib.psa_m_s2[p].rotd50 / g, 1e-15 * lib.psa_m_s2[p].rotd50);
    EXPECT_NEAR(row.at("rotd100_g").get<double>(), lib.psa_m_s2[p].rotd100 / g, 1e-15 * lib.psa_m_s2[p].rotd100);
    EXPECT_LE(row.at("rotd50_g").get<double>(), row.at("rotd100_g").get<double>());
    // The direction: first + theta for this clockwise-from-east... 90 then 0 is counter-clockwise: 90 - theta.
    const double theta = row.at("rotd100_angle_deg").get<double>();
    EXPECT_NEAR(row.at("rotd100_azimuth_deg").get<double>(), std::fmod(90.0 - theta + 180.0, 180.0), 1e-12);
  }
  // RotD50 lies between the smaller and larger component PGA's cos-45 bounds: sanity of the pair (0.2732 and 0.2613 g,
  // SOURCES.md), RotD100 at least the larger of them.
  EXPECT_GE(rotd.at("pga").at("rotd100_g").get<double>(), 0.2732 - 5e-5);
}

TEST(CliInfoPair, UserAzimuthsWinWithAWarningAndBadSetsExitTwo) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  const std::string v2 = quote(test::shared_record("ce36456p_CE36456.V2"));
  auto r = test::run_cli("info " + v2 + " " + v2 + " --channels 1,3 --azimuths 100,10 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the header states azimuth 90 deg, --azimuths uses 100 deg"), std::string::npos) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out).at("azimuths_deg"), nlohmann::json({100.0, 10.0}));
  // The UP channel as a horizontal component: refused, naming the file.
  r = test::run_cli("info " + v2 + " " + v2 + " --channels 2,3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("ce36456p_CE36456.V2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("vertical channel"), std::string::npos) << r.err;
  // Records of different events: Imperial Valley (53.7 s) with Northridge Rinaldi (19.9 s): less than half shared.
  r = test::run_cli("info " + quote(test::shared_record("RSN6_IMPVALL.I_I-ELC180.AT2")) + " " +
                    quote(test::shared_record("Rinaldi228.AT2")));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("time span"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("Rinaldi228.AT2"), std::string::npos) << r.err;
  r = test::run_cli("info " + v2 + " " + v2 + " --channels 1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--channels"), std::string::npos) << r.err;
  r = test::run_cli("info " + v2 + " " + v2 + " --channels 1,3 --azimuths 90,45");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("perpendicular"), std::string::npos) << r.err;
  r = test::run_cli("info " + v2 + " --channel 1 --azimuths 90,0");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--azimuths"), std::string::npos) << r.err;
}

TEST(CliSynthSet, PairAndVerticalFilesWithRotD50Pga) {
  const test::TempDir dir;
  const auto out = dir.path() / "m.csv";
  const auto j = test::run_json("synth --components 3 --pga 0.25g --freq 2.5Hz --duration 30 --seed 9 --coherence 0.3 "
                                "--azimuths 0,90 --json --out " + quote(out));
  for (const char* name : {"m.h1.csv", "m.h2.csv", "m.v.csv"}) EXPECT_TRUE(std::filesystem::exists(dir.path() / name));
  EXPECT_FALSE(std::filesystem::exists(out));
  // --pga is the pair's RotD50 PGA; the files store a / g with 17 significant digits: 1e-12.
  EXPECT_NEAR(j.at("rotd50_pga_g").get<double>(), 0.25, 1e-12);
  EXPECT_NEAR(j.at("vertical_pga_g").get<double>(), 0.25 * 2.0 / 3.0, 1e-12);
  // Read back through `info H1 H2 V` (plain CSV, no azimuths in the header the reader trusts): the same RotD50.
  const auto info = test::run_json("info " + quote(dir.path() / "m.h1.csv") + " " + quote(dir.path() / "m.h2.csv") +
                                   " " + quote(dir.path() / "m.v.csv") + " --json");
  EXPECT_NEAR(info.at("rotd").at("pga").at("rotd50_g").get<double>(), 0.25, 1e-12);
  EXPECT_TRUE(info.at("azimuths_deg").is_null());
  // The component and azimuth are written in the file's comment lines.
  const std::string h2 = test::slurp(dir.path() / "m.h2.csv");
  EXPECT_NE(h2.find("# component=H2 azimuth_deg=90"), std::string::npos) << h2.substr(0, 300);
  // Same seed, same bits.
  const test::TempDir again;
  (void)test::run_json("synth --components 3 --pga 0.25g --freq 2.5Hz --duration 30 --seed 9 --coherence 0.3 "
                       "--azimuths 0,90 --json --out " + quote(again.path() / "m.csv"));
  EXPECT_EQ(test::slurp(again.path() / "m.v.csv"), test::slurp(dir.path() / "m.v.csv"));
}

TEST(CliSynthSet, BadOptionsExitTwoNamingThem) {
  const test::TempDir dir;
  const std::string base = "synth --pga 0.3g --freq 3Hz --duration 20 --out " + quote(dir.path() / "m.csv");
  for (const auto& [args, option] : {std::pair{" --components 2 --coherence 2", "--coherence"},
                                     std::pair{" --components 4", "--components"},
                                     std::pair{" --components 3 --vh-ratio 0", "--vh-ratio"},
                                     std::pair{" --components 3 --vh-freq-ratio 9", "--vh-freq-ratio"},
                                     std::pair{" --components 2 --azimuths 0,45", "--azimuths"},
                                     std::pair{" --components 2 --plot x.svg", "--plot"}}) {
    const auto r = test::run_cli(base + args);
    EXPECT_EQ(r.exit_code, 2) << args << ": " << r.err;
    EXPECT_NE(r.err.find(option), std::string::npos) << args << ": " << r.err;
  }
}

/// A K-NET file (SOURCES.md layout) with direction `dir` holding `counts`.
void write_knet(const std::filesystem::path& path, const char* dir, const std::vector<int>& counts) {
  std::ofstream out(path);
  out << "Origin Time       2018/01/24 19:51:00\nLat.              41.0\nLong.             142.0\n"
         "Depth. (km)       30\nMag.              6.2\nStation Code      TST001\nStation Lat.      40.0\n"
         "Station Long.     141.0\nStation Height(m) 10\nRecord Time       2018/01/24 19:51:10\n"
         "Sampling Freq(Hz) 100Hz\n"
      << fmt::format("Duration Time(s)  {}\n", static_cast<double>(counts.size()) / 100.0) << "Dir.              " << dir
      << "\nScale Factor      3920(gal)/6182761\nMax. Acc. (gal)   1\nLast Correction   2018/01/24 19:51:00\nMemo.\n";
  for (std::size_t i = 0; i < counts.size(); ++i) out << counts[i] << ((i % 8 == 7) ? "\n" : " ");
  out << "\n";
}

TEST(CliSlideHeaders, AzimuthsFromKnetHeaders) {
  const test::TempDir dir;
  std::vector<int> ns, ew;
  for (int i = 0; i < 1000; ++i) {  // 10 s of a 2 Hz burst, +-400000 counts = +-254 gal
    const double t = i / 100.0;
    const double env = std::sin(3.141592653589793 * t / 10.0);
    ns.push_back(static_cast<int>(400000 * env * std::sin(2 * 3.141592653589793 * 2 * t)));
    ew.push_back(static_cast<int>(300000 * env * std::cos(2 * 3.141592653589793 * 2 * t)));
  }
  write_knet(dir.path() / "a.NS", "N-S", ns);
  write_knet(dir.path() / "a.EW", "E-W", ew);
  const std::string files = quote(dir.path() / "a.NS") + " --h2 " + quote(dir.path() / "a.EW");
  const auto from_headers = test::run_json("slide " + files + " --mu 0.1 --json");
  EXPECT_EQ(from_headers.at("input").at("azimuths_deg"), nlohmann::json({0.0, 90.0}));
  const auto given = test::run_json("slide " + files + " --azimuths 0,90 --mu 0.1 --json");
  EXPECT_EQ(given.at("residual_displacement_m"), from_headers.at("residual_displacement_m"));
  const auto r = test::run_cli("slide " + files + " --azimuths 90,0 --mu 0.1");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("a.NS: the header states azimuth 0 deg, --azimuths uses 90 deg"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace topple
