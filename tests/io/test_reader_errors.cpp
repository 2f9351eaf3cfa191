// Bad inputs, written to temporary files: every reader error is an InputError that names the file, the 1-based
// line and the problem. The small well-formed files built here follow the layouts of shared/records/SOURCES.md; each
// test breaks one thing.
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"

namespace topple::io {
namespace {

using test::TempDir;
using test::write_file;

// ---- well-formed files of each format ----

std::string at2(const std::string& npts_line, const std::vector<std::string>& values) {
  std::string s = "PEER NGA STRONG MOTION DATABASE RECORD\nTest, 1/1/2000, Station, 090\n"
                  "ACCELERATION TIME SERIES IN UNITS OF G\n" + npts_line + "\n";
  for (std::size_t i = 0; i < values.size(); ++i) {
    s += fmt::format("{:>15}", values[i]);
    if (i % 5 == 4 || i + 1 == values.size()) s += "\n";
  }
  return s;
}

std::string at2_ok() { return at2("NPTS=      7, DT=   .0100 SEC,", {"0.1", "-0.2", "0.3", "0", "0", "0.05", "0"}); }

std::string cosmos(std::size_t npts, const std::vector<double>& values, double dt_ms = 10.0,
                   const std::string& units = "cm/sec2(04)") {
  std::string s = "Corrected acceleration    (Format v01.20 with 13 text lines) Src: test\n"
                  "Record of Test Earthquake of Mon Jan 1, 2024 00:00 UTC\n";
  for (int k = 3; k <= 13; ++k) {
    if (k == 5) s += "Statn No: 01-00001 Code:XX-TST  Test Station\n";
    else if (k == 9) s += "Sta Chan   1: 90 deg (Rcrdr Chan  1) Location:\n";
    else s += fmt::format("text line {}\n", k);
  }
  s += " 100 Integer-header values follow on  10 lines, Format= (10I8)\n";
  for (int line = 0; line < 10; ++line) {
    for (int k = 0; k < 10; ++k) s += fmt::format("{:8d}", -999);
    s += "\n";
  }
  s += " 100 Real-header values follow on  20 lines, Format= (5F15.6)\n";
  for (int line = 0; line < 20; ++line) {
    for (int k = 0; k < 5; ++k) s += fmt::format("{:15.6f}", line * 5 + k == 61 ? dt_ms : -999.0);
    s += "\n";
  }
  s += "   1 Comment line(s) follow, each starting with a \"|\":\n| test\n";
  s += fmt::format("{:8d} acceleration pts, approx    1 secs, units={},Format=(5E15.6)\n", npts, units);
  for (std::size_t i = 0; i < values.size(); ++i) {
    s += fmt::format("{:15.6E}", values[i]);
    if (i % 5 == 4 || i + 1 == values.size()) s += "\n";
  }
  s += "End-of-data for ChanTST acceleration\n";
  return s;
}

std::string csmip_block(int channel, const std::string& name, std::size_t npts, const std::vector<double>& values,
                        bool end_marker = true) {
  std::string s = fmt::format("CORRECTED ACCELEROGRAM   00001-T0000-24001.01       CHAN  {}: {:<8}FROM\n", channel, name);
  s += "UNCORRECTED ACCELEROGRAM DATA\nTEST EARTHQUAKE\nJAN 1, 2024 00:00 PST   (ORIGIN: 01/01/24)\nX\n";
  s += "STATION NO. 00001   35.9N, 120.4W\nTEST STATION\n";
  s += fmt::format("CHAN  {}: {}\n", channel, name);
  for (int k = 9; k <= 25; ++k) s += "TEXT\n";
  for (int line = 0; line < 7; ++line) s += "    0    0    0    0\n";
  for (int line = 0; line < 13; ++line) s += "      .000      .000\n";
  auto section = [&](const char* what, const char* units) {
    s += fmt::format(" {:4d} POINTS OF {} DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: {})\n", npts, what, units);
    for (std::size_t i = 0; i < values.size(); ++i) {
      s += fmt::format("{:10.3f}", values[i]);
      if (i % 8 == 7 || i + 1 == values.size()) s += "\n";
    }
  };
  section("ACCEL", "CM/SEC/SEC");
  section("VELOC", "CM/SEC");
  if (end_marker) s += fmt::format("/&  ----------  END OF DATA FOR CHANNEL  {}  ----------\n", channel);
  return s;
}

std::string smc(long npts, const std::vector<std::string>& data_lines, double rate = 100.0) {
  std::string s = "2 CORRECTED ACCELEROGRAM\n*\nTEST\n     2024  01  01    0000 Test, CA\nMag\n"
                  "station = Test Station component=     90\n*\n*\n*\n*\n*\n";
  for (int k = 1; k <= 48; ++k) {
    const long v = k == 16 ? 1 : k == 17 ? npts : -32768;
    s += fmt::format("{:10d}", v);
    if (k % 8 == 0) s += "\n";
  }
  for (int k = 1; k <= 50; ++k) {
    s += fmt::format("{:15.7E}", k == 2 ? rate : 1.7e38);
    if (k % 5 == 0) s += "\n";
  }
  s += "| comment\n";
  for (const auto& line : data_lines) s += line + "\n";
  return s;
}

/// `duration` is the "Duration Time(s)" header: counts / frequency (3 counts at 100 Hz by default).
std::string knet(const std::string& freq, const std::string& scale, const std::string& data,
                 const std::string& duration = "0.03") {
  std::string s;
  auto label = [&](const char* l, const std::string& v) { s += fmt::format("{:<18}{}\n", l, v); };
  label("Origin Time", "2024/01/01 00:00:00");
  label("Lat.", "41.0");
  label("Long.", "142.5");
  label("Depth. (km)", "30");
  label("Mag.", "6.2");
  label("Station Code", "TST001");
  label("Station Lat.", "41.0");
  label("Station Long.", "141.0");
  label("Station Height(m)", "17");
  label("Record Time", "2024/01/01 00:00:10");
  if (!freq.empty()) label("Sampling Freq(Hz)", freq);
  else label("Padding", "x");
  label("Duration Time(s)", duration);
  label("Dir.", "N-S");
  label("Scale Factor", scale);
  label("Max. Acc. (gal)", "1.0");
  label("Last Correction", "2024/01/01 00:00:10");
  label("Memo.", "");
  return s + data;
}

std::string esm(const std::string& ndata, const std::string& units, const std::string& values,
                const std::string& dt = "0.010000") {
  std::string s = "EVENT_NAME: TEST\nNETWORK: XX\nSTATION_CODE: TST\n";
  if (!dt.empty()) s += "SAMPLING_INTERVAL_S: " + dt + "\n";
  if (!ndata.empty()) s += "NDATA: " + ndata + "\n";
  s += "STREAM: HNE\n";
  if (!units.empty()) s += "UNITS: " + units + "\n";
  s += "DATA_TYPE: ACCELERATION\nUSER5: \n";
  return s + values;
}

// ---- checking an error ----

struct Expected {
  std::optional<std::size_t> line;  ///< nullopt: the error must not name a line
  std::string field;                ///< checked when not empty
  std::vector<std::string> problem; ///< substrings of the problem text
};

class ReaderErrors : public ::testing::Test {
 protected:
  TempDir dir;

  /// Writes `content` to a file, reads it, and checks the InputError.
  void expect_error(const std::string& content, const Expected& expected, ReadOptions options = {},
                    const std::string& name = "bad.txt") {
    const auto path = dir.path() / name;
    write_file(path, content);
    try {
      (void)read_motion(path, options);
      ADD_FAILURE() << "no InputError for " << name;
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_EQ(e.where().file, path.string()) << what;
      EXPECT_NE(what.find(path.string()), std::string::npos) << what;
      EXPECT_EQ(e.where().line, expected.line) << what;
      if (expected.line) {
        EXPECT_NE(what.find(fmt::format(":{}:", *expected.line)), std::string::npos) << what;
      }
      if (!expected.field.empty()) {
        EXPECT_EQ(e.where().field, expected.field) << what;
      }
      for (const auto& p : expected.problem) EXPECT_NE(e.problem().find(p), std::string::npos) << what;
    }
  }
};

TEST_F(ReaderErrors, WellFormedSamplesRead) {
  // The generators above make valid files; each test below breaks one thing.
  const auto read = [&](const std::string& content, ReadOptions o = {}) {
    const auto path = dir.path() / "ok.txt";
    write_file(path, content);
    return read_motion(path, o);
  };
  EXPECT_EQ(read(at2_ok()).size(), 7u);
  EXPECT_EQ(read(cosmos(3, {1.0, -2.0, 3.0})).size(), 3u);
  EXPECT_DOUBLE_EQ(read(cosmos(3, {1.0, -2.0, 3.0})).dt_s(), 0.01);
  ReadOptions ch2;
  ch2.channel = 2;
  const auto two = read(csmip_block(1, "90 DEG", 3, {1, 2, 3}) + csmip_block(2, "UP", 2, {-400, 1}), ch2);
  EXPECT_EQ(two.size(), 2u);
  EXPECT_DOUBLE_EQ(two.pga_m_s2(), 4.0);
  EXPECT_EQ(two.metadata().component, "UP");
  EXPECT_EQ(read(smc(3, {" 1.000E+00-2.000E+00 3.000E+00"})).size(), 3u);
  EXPECT_DOUBLE_EQ(read(smc(3, {" 1.000E+00-2.000E+00 3.000E+00"})).pga_m_s2(), 0.03);
  EXPECT_DOUBLE_EQ(read(knet("100Hz", "1(gal)/1", "  1  2  3\n")).pga_m_s2(), 0.01);  // mean 2 removed
  EXPECT_EQ(read(esm("3", "cm/s^2", "1\n2\n3\n")).size(), 3u);
}

// ---- empty, unreadable ----

TEST_F(ReaderErrors, EmptyFile) { expect_error("", {std::nullopt, "", {"empty"}}); }
TEST_F(ReaderErrors, BlankFile) { expect_error("\n  \r\n\n", {std::nullopt, "", {"empty"}}); }

TEST_F(ReaderErrors, MissingFileAndDirectory) {
  try {
    (void)read_motion(dir.path() / "nope.AT2");
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nope.AT2"), std::string::npos);
    EXPECT_NE(e.problem().find("cannot open"), std::string::npos);
  }
  EXPECT_THROW((void)read_motion(dir.path()), InputError);
}

// ---- PEER AT2 ----

TEST_F(ReaderErrors, At2Truncated) {
  expect_error(at2("NPTS=     10, DT=   .0100 SEC,", {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6", "0.7"}),
               {6, "acceleration", {"truncated", "7 values", "NPTS announces 10"}});
}

TEST_F(ReaderErrors, At2MoreValuesThanNpts) {
  expect_error(at2("NPTS=      4, DT=   .0100 SEC,", {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6"}),
               {5, "acceleration", {"more values", "4"}});
  expect_error(at2("NPTS=      5, DT=   .0100 SEC,", {"0.1", "0.2", "0.3", "0.4", "0.5", "0.6"}),
               {6, "NPTS", {"more values", "5"}});
}

TEST_F(ReaderErrors, At2NonNumericTokenIsQuoted) {
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "0.2x", "0.3"}), {5, "acceleration", {"'0.2x'"}});
}

TEST_F(ReaderErrors, At2NanAndInf) {
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "NaN", "0.3"}), {5, "acceleration", {"NaN", "'NaN'"}});
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "0.2", "-Inf"}), {5, "acceleration", {"infinite"}});
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "1e400", "0.3"}), {5, "acceleration", {"out of the range"}});
  // Finite in g but not in m/s^2.
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "1.7e308", "0.3"}), {5, "acceleration", {"too large"}});
}

TEST_F(ReaderErrors, At2NonPositiveDt) {
  expect_error(at2("NPTS=      3, DT=   .0000 SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"positive"}});
  expect_error(at2("NPTS=      3, DT=  -.0100 SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"positive"}});
  expect_error(at2("NPTS=      3, DT=  abc SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"'abc'"}});
}

TEST_F(ReaderErrors, At2RecordTooLongToRepresent) {
  // Found by review of the fuzz contract (finite duration): a finite DT whose record length overflows.
  expect_error(at2("NPTS=      3, DT=  1e308 SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"too long to represent"}});
  ReadOptions o;
  o.units = "g";
  o.dt_s = 1e308;
  expect_error("0\n1\n2\n", {std::nullopt, "--dt", {"too long to represent"}}, o);
}

TEST_F(ReaderErrors, At2BadNptsLine) {
  ReadOptions o;
  o.format = Format::peer_at2;
  expect_error(at2("NPTS AND DT FORGOTTEN", {"0.1"}), {4, "NPTS", {"expected NPTS and DT"}}, o);
  expect_error(at2("NPTS=   3.5, DT=   .0100 SEC,", {"0.1"}), {4, "NPTS", {"not an integer", "'3.5'"}});
  expect_error("PEER\nline 2\n", {2, "NPTS", {"ends before line 4"}}, o);
}

TEST_F(ReaderErrors, At2VelocityIsNotAcceleration) {
  std::string s = at2_ok();
  s.replace(s.find("ACCELERATION"), 12, "VELOCITY");
  expect_error(s, {3, "units", {"velocity"}});
}

TEST_F(ReaderErrors, ChannelOfASingleChannelFile) {
  ReadOptions o;
  o.channel = 2;
  expect_error(at2_ok(), {std::nullopt, "--channel", {"one channel"}}, o);
  o.channel = 0;
  expect_error(at2_ok(), {std::nullopt, "--channel", {"numbered from 1"}}, o);
}

// ---- COSMOS V2 ----

TEST_F(ReaderErrors, CosmosUnknownDt) {
  // Lines: 1-13 text, 14 integer count, 15-24 integers, 25 real count, 26-45 reals (value 62 on line 38),
  // 46 comment count, 47 comment, 48 data line, 49 values, 50 End-of-data.
  expect_error(cosmos(3, {1, 2, 3}, -999.0), {38, "Real header 62", {"unknown", "-999"}});
  expect_error(cosmos(3, {1, 2, 3}, 0.0), {38, "Real header 62", {"positive"}});
}

TEST_F(ReaderErrors, CosmosUnits) {
  expect_error(cosmos(3, {1, 2, 3}, 10.0, "furlongs/fortnight2(99)"), {48, "units", {"unknown acceleration unit"}});
}

TEST_F(ReaderErrors, CosmosTruncatedAndTooLong) {
  expect_error(cosmos(8, {1, 2, 3}), {50, "acceleration", {"truncated", "3 values", "8"}});
  expect_error(cosmos(2, {1, 2, 3}), {49, "acceleration", {"more values", "2"}});
  std::string s = cosmos(3, {1, 2, 3});
  s.resize(s.find("End-of-data"));
  expect_error(s, {49, "End-of-data", {"without its 'End-of-data'"}});
}

TEST_F(ReaderErrors, CosmosFixedColumns) {
  std::string s = cosmos(3, {1, 2, 3});
  const std::size_t at = s.find("1.000000E+00");
  s.replace(at, 12, "1.0000000E+00");  // one column too wide
  expect_error(s, {49, "acceleration", {"columns of format 5E15.6"}});
}

// ---- CSMIP V2 ----

TEST_F(ReaderErrors, CsmipSeveralChannelsNeedOne) {
  const std::string s = csmip_block(1, "90 DEG", 2, {1, 2}) + csmip_block(2, "UP", 2, {1, 2}) +
                        csmip_block(3, "360 DEG", 2, {1, 2});
  expect_error(s, {std::nullopt, "--channel", {"3 channels", "1 (90 DEG), 2 (UP), 3 (360 DEG)"}});
  ReadOptions o;
  o.channel = 4;
  expect_error(s, {std::nullopt, "--channel", {"no channel 4"}}, o);
}

TEST_F(ReaderErrors, CsmipTruncated) {
  expect_error(csmip_block(1, "90 DEG", 2, {1, 2}, false), {49, "channel", {"truncated"}});
  // The END line is present but ACCEL holds fewer values than announced: the VELOC line ends the data.
  std::string s = csmip_block(1, "90 DEG", 10, {1, 2, 3});
  expect_error(s, {48, "ACCEL", {"truncated", "3 values", "10"}});
}

TEST_F(ReaderErrors, CsmipBadValue) {
  std::string s = csmip_block(1, "90 DEG", 3, {1, 2, 3});
  s.replace(s.find("     2.000"), 10, "     2.0x0");
  expect_error(s, {47, "ACCEL", {"'2.0x0'"}});
}

TEST_F(ReaderErrors, CsmipBadDtAndUnits) {
  std::string s = csmip_block(1, "90 DEG", 3, {1, 2, 3});
  s.replace(s.find(" .020 SEC.  (UNITS: CM/SEC/SEC)"), 10, " .000 SEC.");
  expect_error(s, {46, "DT", {"positive"}});
  s = csmip_block(1, "90 DEG", 3, {1, 2, 3});
  s.replace(s.find("CM/SEC/SEC"), 10, "INCH/SEC/S");
  expect_error(s, {46, "UNITS", {"unknown acceleration unit"}});
}

// ---- USGS SMC ----

TEST_F(ReaderErrors, SmcNptsMismatch) {
  expect_error(smc(4, {" 1.000E+00-2.000E+00 3.000E+00"}), {29, "acceleration", {"truncated", "3 values", "4"}});
  expect_error(smc(2, {" 1.000E+00-2.000E+00 3.000E+00"}), {29, "acceleration", {"more values", "2"}});
  expect_error(smc(2, {" 1.000E+00-2.000E+00", " 3.000E+00"}), {30, "integer header #17", {"more values"}});
}

TEST_F(ReaderErrors, SmcFixedWidthAndTokens) {
  expect_error(smc(3, {" 1.000E+00-2.000E+00 3.00E+00"}), {29, "acceleration", {"columns of format 8E10.4"}});
  expect_error(smc(3, {" 1.000E+00-2.0x0E+00 3.000E+00"}), {29, "acceleration", {"'-2.0x0E+00'"}});
}

TEST_F(ReaderErrors, SmcMissingHeaderValues) {
  expect_error(smc(-32768, {" 1.000E+00"}), {14, "integer header #17", {"missing"}});
  expect_error(smc(1, {" 1.000E+00"}, 1.7e38), {18, "real header #2", {"missing"}});
  expect_error(smc(1, {" 1.000E+00"}, -5.0), {18, "real header #2", {"positive"}});
}

// ---- K-NET ----

TEST_F(ReaderErrors, KnetHeader) {
  expect_error(knet("", "1(gal)/1", "1 2 3\n"), {17, "Sampling Freq(Hz)", {"missing"}});
  expect_error(knet("0Hz", "1(gal)/1", "1 2 3\n"), {11, "Sampling Freq(Hz)", {"positive"}});
  expect_error(knet("100Hz", "3920/6182761", "1 2 3\n"), {14, "Scale Factor", {"(gal)/"}});
  expect_error(knet("100Hz", "3920(gal)/0", "1 2 3\n"), {14, "Scale Factor", {"zero"}});
}

TEST_F(ReaderErrors, KnetData) {
  expect_error(knet("100Hz", "1(gal)/1", "1 2 3\n4 five 6\n"), {19, "counts", {"'five'"}});
  expect_error(knet("100Hz", "1(gal)/1", ""), {17, "data", {"no data"}});
}

// ---- ESM ----

TEST_F(ReaderErrors, EsmCounts) {
  expect_error(esm("4", "cm/s^2", "1\n2\n3\n"), {12, "acceleration", {"truncated", "3 values", "4"}});
  expect_error(esm("2", "cm/s^2", "1\n2\n3\n"), {12, "NDATA", {"more values"}});
}

TEST_F(ReaderErrors, EsmHeader) {
  expect_error(esm("3", "", "1\n2\n3\n"), {8, "UNITS", {"missing"}});
  expect_error(esm("3", "furlong/s^2", "1\n2\n3\n"), {7, "UNITS", {"unknown acceleration unit"}});
  expect_error(esm("3", "cm/s^2", "1\n2\n3\n", "-0.01"), {4, "SAMPLING_INTERVAL_S", {"positive"}});
  ReadOptions o;
  o.format = Format::esm;
  expect_error(esm("3", "cm/s^2", "1\n2\n3\n", ""), {8, "SAMPLING_INTERVAL_S", {"missing"}}, o);
}

// ---- plain text ----

TEST_F(ReaderErrors, PlainDecreasingAndRepeatedTimes) {
  expect_error("time_s,accel_g\n0,0\n0.01,1\n0.005,0\n", {4, "time", {"0.005", "before", "line 3"}});
  expect_error("time_s,accel_g\n0,0\n0.01,1\n0.01,0\n", {4, "time", {"repeats", "line 3"}});
}

TEST_F(ReaderErrors, PlainUnits) {
  expect_error("0,0\n0.01,1\n", {std::nullopt, "--units", {"--units"}});
  expect_error("time,accel\n0,0\n0.01,1\n", {1, "accel", {"no acceleration unit", "--units"}});
  expect_error("time_s,accel_furlong\n0,0\n0.01,1\n", {1, "accel_furlong", {"unknown acceleration unit"}});
  ReadOptions o;
  o.units = "parsec";
  expect_error("time_s,accel_g\n0,0\n0.01,1\n", {std::nullopt, "--units", {"unknown acceleration unit"}}, o);
}

TEST_F(ReaderErrors, PlainOneColumnNeedsDt) {
  ReadOptions o;
  o.units = "g";
  expect_error("0\n1\n2\n", {std::nullopt, "--dt", {"--dt"}}, o);
  o.dt_s = 0.0;
  expect_error("0\n1\n2\n", {std::nullopt, "--dt", {"positive"}}, o);
  o.dt_s = -1.0;
  expect_error("0\n1\n2\n", {std::nullopt, "--dt", {"positive"}}, o);
}

TEST_F(ReaderErrors, PlainBadTokensAndColumns) {
  expect_error("time_s,accel_g\n0,0\n0.01,1.2.3\n", {3, "acceleration", {"'1.2.3'"}});
  expect_error("time_s,accel_g\n0,0\n0.01,nan\n", {3, "acceleration", {"NaN"}});
  expect_error("time_s,accel_g\n0,0\n0.01,1,5\n", {3, "", {"3 columns", "line 2"}});
  expect_error("time_s,accel_g\n0,0\n0.01,,\n0.02,1\n", {3, "", {"1 column", "line 2"}});
  expect_error("time_s,accel_g\n0,0,0\n", {2, "", {"3 columns"}});
  expect_error("time_s,accel_g\n0,0\n", {2, "time", {"at least two rows"}});
  expect_error("# only a comment\ntime_s,accel_g\n", {2, "", {"no data"}});
  expect_error("accel_g,time_s\n0,0\n1,1\n", {1, "accel_g", {"first of two columns must be the time"}});
}


// ---- plain files as recorded (issue 28): column choice, separators, baseline ----

const std::string kTable = "# test 3\nTime (s)\tTable Acc (g)\tTable Disp (mm)\tStatus\n0\t0.01\t1\tOK\n0.01\t0.5\t2\tOK\n"
                           "0.02\t0.01\t3\tstop\n";

ReadOptions columns(const std::string& text) {
  ReadOptions o;
  o.columns = parse_columns(text);
  return o;
}

TEST_F(ReaderErrors, ColumnsReadTheTableFile) {
  const auto path = dir.path() / "table.txt";
  write_file(path, kTable);
  EXPECT_DOUBLE_EQ(read_motion(path, columns("Time (s),Table Acc (g)")).pga_m_s2(), 0.5 * 9.80665);
  EXPECT_DOUBLE_EQ(read_motion(path, columns("1,2")).pga_m_s2(), 0.5 * 9.80665);
}

TEST_F(ReaderErrors, ColumnsMissingOrRepeatedAreRefusedListingTheHeader) {
  // A name the header does not hold: the header's line, the option, and every name the header holds.
  expect_error(kTable, {2, "--columns", {"no column named 'Table Accel (g)'", "1 'Time (s)'", "2 'Table Acc (g)'",
                                         "4 'Status'"}},
               columns("Time (s),Table Accel (g)"));
  // A number beyond the data's columns: the first data line.
  expect_error(kTable, {3, "--columns", {"column 9", "4 columns", "'Table Disp (mm)'"}}, columns("1,9"));
  // The same column twice, once by number and once by name.
  expect_error(kTable, {std::nullopt, "--columns", {"same column", "'Time (s)'"}}, columns("1,Time (s)"));
  // A name without a header.
  expect_error("0 1 2\n0.01 3 4\n", {std::nullopt, "--columns", {"no header", "by number"}}, columns("t,a"));
  // A name the header holds twice.
  expect_error("t_s,a_g,a_g\n0,1,2\n0.01,3,4\n", {1, "--columns", {"columns 2 and 3"}}, columns("1,a_g"));
  // A header naming fewer columns than the data holds.
  expect_error("t_s,a_g\n0,1,2\n0.01,3,4\n", {1, "header", {"names 2 columns", "has 3"}}, columns("1,2"));
  // The parse itself (the CLI and the sweep reader call it).
  for (const char* bad : {"2,2", "x,X", "1,2,3", "0,1", "", "time=1"}) {
    EXPECT_THROW((void)parse_columns(bad), InputError) << bad;
  }
}

TEST_F(ReaderErrors, ColumnsValuesNamedByTheirColumn) {
  // A bad value in a chosen column names the column's header name and the line; an ignored column may hold text.
  expect_error(kTable + "0.03\t0.x\t4\tOK\n", {6, "Table Acc (g)", {"'0.x'"}}, columns("1,2"));
  expect_error("0 1 2\n0.01 x 4\n", {2, "column 2", {"'x'"}}, [] {
    ReadOptions o = columns("1,2");
    o.units = "g";
    return o;
  }());
  // A row with a field missing (shifted columns) is refused even though the missing field is ignored.
  expect_error(kTable + "0.03\t0.1\t4\n", {6, "", {"3 columns", "line 3 has 4"}}, columns("1,2"));
  // More than two columns without a choice: the option to use and the header's names.
  expect_error(kTable, {3, "--columns", {"4 columns", "--columns", "'Table Acc (g)'"}});
  // The chosen column's unit: displacement is not an acceleration; none stated needs --units.
  expect_error(kTable, {2, "Table Disp (mm)", {"unknown acceleration unit"}}, columns("1,3"));
  expect_error("t (s)\tacc\n0\t1\n0.01\t2\n", {1, "acc", {"--units"}}, columns("1,2"));
  // Without a time column, --dt; with one, no --dt.
  expect_error(kTable, {std::nullopt, "--dt", {"no time column is chosen"}}, columns(",2"));
  ReadOptions dt = columns("1,2");
  dt.dt_s = 0.01;
  expect_error(kTable, {std::nullopt, "--dt", {"time column"}}, dt);
  // Column options on an agency file.
  expect_error(at2_ok(), {std::nullopt, "--columns", {"plain files"}}, columns("1,2"));
}

TEST_F(ReaderErrors, BaselineChoicesRefusedNamingTheFile) {
  ReadOptions o = columns("1,2");
  o.baseline = parse_baseline("pre-event:5");
  expect_error(kTable, {std::nullopt, "--baseline", {"longer than the record"}}, o);
  o.baseline = parse_baseline("pre-event:0.005");
  expect_error(kTable, {std::nullopt, "--baseline", {"holds 1 sample"}}, o);
  o.baseline = Baseline{BaselineMethod::polynomial, 0.0, 4};
  expect_error(kTable, {std::nullopt, "--baseline", {"0..3"}}, o);
  o.baseline = Baseline{BaselineMethod::polynomial, 0.0, 3};
  expect_error(kTable, {std::nullopt, "--baseline", {"at least 4 samples"}}, o);
  for (const char* bad : {"poly:4", "poly:-1", "poly:", "poly:1.5", "pre-event:0", "pre-event:-1", "pre-event:x",
                          "median", "", "Mean"}) {
    EXPECT_THROW((void)parse_baseline(bad, "--baseline"), InputError) << bad;
  }
}


TEST_F(ReaderErrors, SurveyRecordOptionsReadTablesAsRecorded) {
  // [inversion] record_columns / record_baseline / record_separator / record_units / record_dt_s read the survey's
  // records (and a site's instrument record) as the CLI options do.
  write_file(dir.path() / "table.txt", kTable);
  const std::string object = "[[object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                             "outcome = \"overturned\"\n";
  const auto survey = [&](const std::string& keys) {
    const auto path = dir.path() / "s.toml";
    write_file(path, "[inversion]\nfamily = \"records\"\nrecords = [\"table.txt\"]\npga_g = [0.1, 1.0, 3]\n"
                     "freq_hz = [1.0, 4.0, 2]\n" + keys + object);
    return path;
  };
  for (const char* columns : {"record_columns = [\"Time (s)\", \"Table Acc (g)\"]\n", "record_columns = [1, 2]\n",
                              "record_columns = \"1,2\"\n"}) {
    const Survey s = read_survey(survey(std::string(columns) + "record_baseline = \"mean\"\n"));
    ASSERT_EQ(s.inversion.record_motions.size(), 1u) << columns;
    // The mean of 0.01, 0.5, 0.01 g is 0.52/3 g: the peak becomes 0.5 - 0.52/3 g.
    EXPECT_NEAR(s.inversion.record_motions[0]->pga_m_s2(), (0.5 - 0.52 / 3.0) * 9.80665, 1e-12) << columns;
  }
  const Survey nt = read_survey(survey("record_columns = [\"\", 2]\nrecord_dt_s = 0.02\nrecord_separator = \"tab\"\n"));
  EXPECT_NEAR(nt.inversion.record_motions[0]->dt_s(), 0.02, 1e-15);
  // Without the keys the table file is refused as before (four columns), naming its line.
  try {
    (void)read_survey(survey(""));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("table.txt"), std::string::npos) << e.what();
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(3)) << e.what();
  }
  // Bad keys at their line of the survey; a column the header lacks at the record's header line.
  const auto refused = [&](const std::string& keys, const std::string& file_part, std::size_t line,
                           const std::string& field, const std::string& problem) {
    try {
      (void)read_survey(survey(keys));
      ADD_FAILURE() << "accepted: " << keys;
    } catch (const InputError& e) {
      EXPECT_NE(e.where().file.find(file_part), std::string::npos) << e.what();
      EXPECT_EQ(e.where().line, line == 0 ? std::nullopt : std::optional<std::size_t>(line)) << e.what();
      EXPECT_EQ(e.where().field, field) << e.what();
      EXPECT_NE(e.problem().find(problem), std::string::npos) << e.what();
    }
  };
  refused("record_baseline = \"poly:9\"\n", "s.toml", 6, "inversion.record_baseline", "0..3");
  refused("record_columns = [1, 2, 3]\n", "s.toml", 6, "inversion.record_columns", "[time, acceleration]");
  refused("record_columns = \"2,2\"\n", "s.toml", 6, "inversion.record_columns", "same column");
  refused("record_separator = \"pipe\"\n", "s.toml", 6, "inversion.record_separator", "unknown separator");
  refused("record_units = \"furlong\"\n", "s.toml", 6, "inversion.record_units", "unknown acceleration unit");
  refused("record_columns = \"1,Acc (g)\"\n", "table.txt", 2, "inversion.record_columns", "'Table Acc (g)'");
  refused("record_columns = \"1,2\"\nrecord_baseline = \"pre-event:1\"\n", "table.txt", 0, "inversion.record_baseline",
          "longer than the record");
}

// ---- hardening (issue 11): non-regular files, size and line caps, limits, declared lengths, option conflicts ----

TEST_F(ReaderErrors, NonRegularFilesAreRefusedBeforeReading) {
  // A device or a FIFO would be read for ever (or block); a directory is not a record. Refused from the file's type.
  const auto expect_kind = [](const std::filesystem::path& path, const std::string& kind) {
    try {
      (void)read_motion(path);
      ADD_FAILURE() << "no InputError for " << path;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().file, path.string()) << e.what();
      EXPECT_NE(e.problem().find(kind), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find("record file"), std::string::npos) << e.what();
    }
  };
  expect_kind("/dev/zero", "character device");
  expect_kind(dir.path(), "directory");
  std::filesystem::create_symlink("/dev/zero", dir.path() / "link-to-zero.AT2");
  expect_kind(dir.path() / "link-to-zero.AT2", "character device");
}

TEST_F(ReaderErrors, FileAndLineCaps) {
  // A sparse file one byte over the cap: refused from its size, without reading 64 MiB.
  const auto big = dir.path() / "big.csv";
  write_file(big, "time_s,accel_g\n");
  std::filesystem::resize_file(big, kMaxInputFileBytes + 1);
  try {
    (void)read_motion(big);
    ADD_FAILURE() << "no InputError for a file over the cap";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, big.string());
    EXPECT_NE(e.problem().find("64 MiB"), std::string::npos) << e.what();
  }
  // A line one byte over the cap (line 2), and the same through parse_motion (what the fuzz targets call).
  const std::string long_line = "time_s,accel_g\n" + std::string(kMaxInputLineBytes + 1, '1') + "\n";
  expect_error(long_line, {2, "", {"longer than the limit of 1024 KiB"}});
  EXPECT_THROW((void)parse_motion(long_line, "in-memory"), InputError);
  // Exactly at the cap is a line like any other (here a bad number, refused for that reason).
  expect_error("time_s,accel_g\n" + std::string(kMaxInputLineBytes, '1') + "\n", {2, "acceleration", {"not a number"}});
}

TEST_F(ReaderErrors, AccelerationLimit) {
  // 100 g is accepted, anything beyond refused at its line: 1e300 g used to reach the solvers (inf Arias, NaN Tm).
  ReadOptions o;
  o.dt_s = 0.01;
  o.units = "g";
  const auto path = dir.path() / "at-limit.txt";
  write_file(path, "0\n100\n-100\n");
  EXPECT_DOUBLE_EQ(read_motion(path, o).pga_m_s2(), 100.0 * kStandardGravity);
  expect_error("0\n100.001\n", {2, "acceleration", {"too large", "limit", "100 g"}}, o);
  expect_error(at2("NPTS=      3, DT=   .0100 SEC,", {"0.1", "1e300", "0.3"}), {5, "acceleration", {"limit", "100 g"}});
  expect_error("time_s,accel_g\n0,0\n0.01,1e300\n", {3, "accel_g", {"limit"}});
  expect_error(knet("100Hz", "1(gal)/1", "  1  2  2000000\n"), {18, "counts", {"limit"}});  // 1.33e6 gal after the mean
}

TEST_F(ReaderErrors, DurationTimeStepAndStartLimits) {
  // Times 0 and 1e300: an "infinite" record (slide printed inf m, info PGD inf).
  expect_error("time_s,accel_g\n0,0\n1e300,1\n", {3, "time", {"6 h"}});
  expect_error("time_s,accel_g\n0,0\n21600.01,1\n", {3, "time", {"6 h"}});
  expect_error("time_s,accel_g\n1e9,0\n1000000010,1\n", {2, "time", {"1 day"}});
  expect_error("time_s,accel_g\n0,0\n1e-7,1\n", {3, "time", {"closer than the limit"}});
  expect_error(at2("NPTS=      3, DT=  20 SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"outside the limits"}});
  expect_error(at2("NPTS=      3, DT=  1e-9 SEC,", {"0.1", "0.2", "0.3"}), {4, "DT", {"outside the limits"}});
  std::vector<std::string> long_record(2200, "0.1");  // 2199 x 10 s = 6.1 h
  expect_error(at2("NPTS=   2200, DT=  10 SEC,", long_record), {4, "DT", {"6 h"}});
  ReadOptions o;
  o.units = "g";
  o.dt_s = 1e-7;
  expect_error("0\n1\n", {std::nullopt, "--dt", {"outside the limits"}}, o);
}

TEST_F(ReaderErrors, KnetDurationTimeAgainstCounts) {
  // "Duration Time(s)" x frequency is the number of counts (AICH04: 143 s x 200 Hz = 28600).
  expect_error(knet("100Hz", "1(gal)/1", "  1  2  3\n", "0.04"),
               {12, "Duration Time(s)", {"4 counts", "data hold 3", "truncated"}});
  expect_error(knet("100Hz", "1(gal)/1", "  1  2  3  4\n", "0.03"), {12, "Duration Time(s)", {"data hold 4"}});
}

TEST_F(ReaderErrors, KnetRealRecordCutInsideANumber) {
  // The case: a real K-NET file cut inside its last value ("2516" read as "25") was accepted.
  if (!test::have_shared()) GTEST_SKIP() << "shared/records not found";
  std::string content = test::slurp(test::shared_record("AOM0081801241951.NS"));
  ASSERT_GT(content.size(), 60000u);
  content.resize(60000);
  while (content.back() == ' ' || content.back() == '\n') content.pop_back();
  content.pop_back();  // now inside a number
  expect_error(content, {12, "Duration Time(s)", {"138 s at 100 Hz", "13800 counts", "truncated"}}, {}, "cut.NS");
}

TEST_F(ReaderErrors, EsmAndCosmosDeclaredDuration) {
  std::string e = esm("3", "cm/s^2", "1\n2\n3\n");
  e.insert(e.find("STREAM"), "DURATION_S: 1.000\n");
  expect_error(e, {6, "DURATION_S", {"declares 1 s", "0.03 s"}});
  std::string ok = esm("3", "cm/s^2", "1\n2\n3\n");
  ok.insert(ok.find("STREAM"), "DURATION_S: 0.030\n");
  const auto path = dir.path() / "ok.asc";
  write_file(path, ok);
  EXPECT_EQ(read_motion(path).size(), 3u);
  // 300 points at 10 ms are 3 s; the data line says "approx 1 secs".
  expect_error(cosmos(300, std::vector<double>(300, 1.0)), {48, "approx secs", {"declares 1 s", "3 s"}});
}

TEST_F(ReaderErrors, UnitsOptionMustAgreeWithTheFile) {
  ReadOptions gal;
  gal.units = "gal";
  ReadOptions g;
  g.units = "g";
  expect_error(at2_ok(), {3, "--units", {"'g'", "'gal' disagrees"}}, gal);
  expect_error("time_s,accel_g\n0,0\n0.01,1\n", {1, "--units", {"'g'", "'gal' disagrees"}}, gal);
  expect_error(knet("100Hz", "1(gal)/1", "  1  2  3\n"), {14, "--units", {"disagrees"}}, g);
  expect_error(smc(3, {" 1.000E+00-2.000E+00 3.000E+00"}), {std::nullopt, "--units", {"disagrees"}}, g);
  expect_error(esm("3", "cm/s^2", "1\n2\n3\n"), {7, "--units", {"disagrees"}}, g);
  expect_error(cosmos(3, {1.0, -2.0, 3.0}), {48, "--units", {"disagrees"}}, g);
  // Agreeing units are accepted (gal = cm/s2), and read the same values.
  const auto read = [&](const std::string& content, const ReadOptions& o) {
    const auto path = dir.path() / "agree.txt";
    write_file(path, content);
    return read_motion(path, o);
  };
  EXPECT_DOUBLE_EQ(read(at2_ok(), g).pga_m_s2(), 0.3 * kStandardGravity);
  EXPECT_DOUBLE_EQ(read(knet("100Hz", "1(gal)/1", "  1  2  3\n"), gal).pga_m_s2(), 0.01);
  EXPECT_DOUBLE_EQ(read(esm("3", "cm/s^2", "1\n2\n3\n"), gal).pga_m_s2(), 0.03);
  EXPECT_DOUBLE_EQ(read("time_s,accel_g\n0,0\n0.01,1\n", g).pga_m_s2(), kStandardGravity);
}

TEST_F(ReaderErrors, DtOptionMustAgreeWithTheFile) {
  ReadOptions o;
  o.dt_s = 0.02;
  expect_error(at2_ok(), {4, "--dt", {"0.01 s", "--dt 0.02 disagrees"}}, o);
  expect_error(knet("100Hz", "1(gal)/1", "  1  2  3\n"), {11, "--dt", {"disagrees"}}, o);
  expect_error(esm("3", "cm/s^2", "1\n2\n3\n"), {4, "--dt", {"disagrees"}}, o);
  o.dt_s = 0.01;  // agrees: accepted
  const auto path = dir.path() / "agree.AT2";
  write_file(path, at2_ok());
  EXPECT_EQ(read_motion(path, o).size(), 7u);
}
}  // namespace
}  // namespace topple::io
