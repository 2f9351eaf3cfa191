// Issue 11, the command line: inputs that used to hang, eat memory, overflow into inf/NaN or be silently
// reinterpreted. Each case must end with exit status 2 and a message naming the file and the field (or the limit),
// quickly, and no inf or NaN may reach stdout. Every command runs under `timeout -s KILL`, so that a regression fails
// (exit 137) instead of stalling the suite.
#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"

namespace topple {
namespace {

using test::run_cli;
using test::TempDir;
using test::write_file;

constexpr int kTimeoutS = 20;  // a hang or unbounded read is killed long before the suite's own timeout

struct Case {
  const char* name;
  std::string args;                 ///< "{dir}" is replaced by the temporary directory
  std::vector<std::string> messages;  ///< substrings of the error message
  int exit_code = 2;
};

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

class CliHardening : public ::testing::TestWithParam<Case> {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const auto d = dir_->path();
    write_file(d / "ok.csv", "time_s,accel_g\n0,0\n0.01,0.2\n0.02,-0.1\n0.03,0\n");
    write_file(d / "huge.csv", "time_s,accel_g\n0,0\n0.01,1e300\n0.02,0\n");        // 1e300 g
    write_file(d / "long.csv", "time_s,accel_g\n0,0\n1e300,0.1\n");                 // times 0 and 1e300
    write_file(d / "rec.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 090\n"
                              "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=      4, DT=   .0100 SEC,\n"
                              "  0.1  -0.2  0.1  0\n");
    ::mkfifo((d / "fifo").c_str(), 0600);
    write_file(d / "big.csv", "time_s,accel_g\n");
    std::filesystem::resize_file(d / "big.csv", (std::uintmax_t{64} << 20) + 1);  // sparse: no disk used
    std::filesystem::create_directory(d / "a-directory");
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static TempDir* dir_;
};

TempDir* CliHardening::dir_ = nullptr;

TEST_P(CliHardening, RefusedQuicklyNamingFileAndField) {
  const Case& c = GetParam();
  std::string args = c.args;
  for (std::size_t at; (at = args.find("{dir}")) != std::string::npos;) args.replace(at, 5, dir_->path().string());
  const auto start = std::chrono::steady_clock::now();
  const auto r = run_cli(args, kTimeoutS);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, c.exit_code) << args << "\n" << r.err;
  std::string expected_err = "topple: error: ";
  EXPECT_NE(r.err.find(expected_err), std::string::npos) << r.err;
  for (std::string part : c.messages) {
    for (std::size_t at; (at = part.find("{dir}")) != std::string::npos;) part.replace(at, 5, dir_->path().string());
    EXPECT_NE(r.err.find(part), std::string::npos) << "missing '" << part << "' in: " << r.err;
  }
  // A refusal is decided from the file's type, size, a header or the first values: a fraction of a second. 5 s
  // leaves room for a loaded machine and sanitizer builds; the unbounded reads this replaces never ended.
  EXPECT_LT(seconds, 5.0) << args;
  const std::string out = lower(r.out);
  EXPECT_EQ(out.find("inf"), std::string::npos) << r.out;
  EXPECT_EQ(out.find("nan"), std::string::npos) << r.out;
}

const Case kCases[] = {
    // Resources: non-regular files, size cap. These grew memory without bound.
    {"InfoDevZero", "info /dev/zero", {"/dev/zero: ", "character device", "not a record file"}},
    {"InfoDevZeroCosmos", "info /dev/zero --format cosmos-v2", {"/dev/zero: ", "character device"}},
    {"InvertDevZero", "invert /dev/zero", {"/dev/zero: ", "character device", "not a survey file"}},
    {"SweepDevZero", "sweep /dev/zero", {"/dev/zero: ", "character device", "not a sweep file"}},
    {"InfoFifo", "info {dir}/fifo", {"{dir}/fifo: ", "FIFO"}},
    {"InfoDirectory", "info {dir}/a-directory", {"{dir}/a-directory: ", "is a directory"}},
    {"InvertDirectory", "invert {dir}/a-directory", {"{dir}/a-directory: ", "is a directory, not a survey file"}},
    {"SweepDirectory", "sweep {dir}/a-directory", {"{dir}/a-directory: ", "is a directory, not a sweep file"}},
    {"InfoFileOverTheCap", "info {dir}/big.csv", {"{dir}/big.csv: ", "64 MiB"}},
    // Overflow: 1e300 g (rock: "more than 1000000 events", info: Arias inf, Tm -nan, slide: inf m).
    {"Info1e300g", "info {dir}/huge.csv", {"{dir}/huge.csv:3: accel_g: ", "100 g"}},
    {"Slide1e300g", "slide {dir}/huge.csv --mu 0.3", {"{dir}/huge.csv:3: accel_g: ", "100 g"}},
    {"Rock1e300g", "rock {dir}/huge.csv --shape block --width 4cm --height 20cm",
     {"{dir}/huge.csv:3: accel_g: ", "100 g"}},
    {"InfoScale1e308", "info {dir}/ok.csv --scale 1e308", {"{dir}/ok.csv: --scale: ", "100 g"}},
    {"SlideScale1e308", "slide {dir}/ok.csv --scale 1e308 --mu 0.3", {"{dir}/ok.csv: --scale: ", "100 g"}},
    {"InfoScalePga", "info {dir}/ok.csv --scale-pga 1000g", {"{dir}/ok.csv: --scale-pga: ", "100 g"}},
    {"SlideTimes0And1e300", "slide {dir}/long.csv --mu 0.1", {"{dir}/long.csv:3: time: ", "6 h"}},
    {"InfoTimes0And1e300", "info {dir}/long.csv", {"{dir}/long.csv:3: time: ", "6 h"}},
    {"SynthPga1e300g", "synth --pga 1e300g --freq 3Hz --duration 20s --out {dir}/s.csv", {"--pga: ", "100 g"}},
    // Silent guesses: options that disagree with what the file states.
    {"UnitsGalOnAt2InG", "info {dir}/rec.AT2 --units gal", {"{dir}/rec.AT2:3: --units: ", "'gal' disagrees"}},
    {"DtOnAt2WithItsOwnDt", "info {dir}/rec.AT2 --dt 0.02", {"{dir}/rec.AT2:4: --dt: ", "--dt 0.02 disagrees"}},
    {"UnitsGalOnCsvInG", "info {dir}/ok.csv --units gal", {"{dir}/ok.csv:1: --units: ", "'gal' disagrees"}},
};

INSTANTIATE_TEST_SUITE_P(Issue11, CliHardening, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<Case>& p) { return std::string(p.param.name); });

TEST(CliHardeningAgreement, OptionsThatAgreeWithTheFileAreAccepted) {
  // The option may still be given when it says what the file says.
  TempDir dir;
  write_file(dir.path() / "rec.AT2", "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 090\n"
                                     "ACCELERATION TIME SERIES IN UNITS OF G\nNPTS=      4, DT=   .0100 SEC,\n"
                                     "  0.1  -0.2  0.1  0\n");
  const auto r = run_cli("info '" + (dir.path() / "rec.AT2").string() + "' --units g --dt 0.01 --json", kTimeoutS);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("\"pga_g\": 0.2"), std::string::npos) << r.out;
}

TEST(CliHardeningKnet, TruncatedRealRecordIsRefused) {
  // A real K-NET file cut inside its last value: was accepted, with the cut "2516" read as 25.
  if (!test::have_shared()) GTEST_SKIP() << "shared/records not found";
  TempDir dir;
  std::string content = test::slurp(test::shared_record("AOM0081801241951.NS"));
  content.resize(60000);
  while (content.back() == ' ' || content.back() == '\n') content.pop_back();
  content.pop_back();
  const auto path = dir.path() / "cut.NS";
  write_file(path, content);
  const auto r = run_cli("info '" + path.string() + "'", kTimeoutS);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(path.string() + ":12: Duration Time(s): 138 s at 100 Hz announces 13800 counts"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace topple
