// The readers against the public records in ../shared/records, and plain-text variants written on the fly.
//
// Expected npts, dt, PGA and time of peak for the top-level records are the table of shared/records/SOURCES.md,
// computed there by an independent parser. That table prints PGA with 4 decimals of g, so PGA is checked to
// 0.5e-4 g (half a unit of its last digit); times of peak are printed to the millisecond and fall on samples, so
// they are checked to 1e-6 s; dt to 1e-9 relative; npts exactly.
// For the pySLAMMER CSVs (shared/records/slammer), dt and PGA are the columns of their own gm_summary.csv (PGA to 3
// decimals, so checked to 0.5e-3 g), and npts and t_pk were counted with a few lines of Python (csv module,
// first |a| maximum), independent of topple.
#include <cctype>
#include <cmath>
#include <functional>
#include <vector>

#include <fmt/format.h>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/baseline.hpp"
#include "topple/core/units.hpp"

namespace topple::io {
namespace {

using test::have_shared;
using test::shared_record;

struct RecordCase {
  std::string file;  ///< relative to shared/records
  Format format;
  std::size_t npts;
  double dt_s;
  double pga_g;
  double pga_tolerance_g;
  double t_peak_s;
  std::optional<int> channel = std::nullopt;
  std::string station = "";    ///< substring expected in metadata().station ("" = not checked)
  std::string component = "";  ///< expected metadata().component ("" = not checked)
};

void PrintTo(const RecordCase& c, std::ostream* os) { *os << c.file << (c.channel ? " channel " : "") << c.channel.value_or(0); }

constexpr double kTable = 0.5e-4;   // SOURCES.md: 4 decimals of g
constexpr double kSummary = 0.5e-3; // gm_summary.csv: 3 decimals of g

const RecordCase kRecords[] = {
    // SOURCES.md table.
    {"RSN6_IMPVALL.I_I-ELC180.AT2", Format::peer_at2, 5372, 0.01, 0.2808, kTable, 2.180, {}, "El Centro Array #9", "180"},
    {"Rinaldi228.AT2", Format::peer_at2, 1991, 0.01, 0.8741, kTable, 2.560, {}, "Rinaldi", "228"},
    {"ARL360.at2", Format::peer_at2, 2000, 0.02, 0.3081, kTable, 5.100, {}, "ARLETA", "360"},
    {"CPM000.AT2", Format::peer_at2, 1500, 0.02, 1.4973, kTable, 3.000, {}, "CAPE MENDOCINO", "000"},
    {"RSN763_LOMAP_GIL067.AT2", Format::peer_at2, 7999, 0.005, 0.3585, kTable, 3.365, {}, "Gilroy", "67"},
    {"Kobe_1995_TAK-090.csv", Format::plain, 4015, 0.01, 0.6155, kTable, 2.710, {}, "TAK", "090"},
    {"us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c", Format::cosmos_v2, 42000, 0.005, 0.0070, kTable, 76.215, {},
     "Bremner River", "BNZ"},
    {"ce36456p_CE36456.V2", Format::csmip_v2, 3251, 0.02, 0.2732, kTable, 10.94, 1, "PARKFIELD", "90 DEG"},
    {"ce36456p_CE36456.V2", Format::csmip_v2, 3250, 0.02, 0.0967, kTable, 11.68, 2, "PARKFIELD", "UP"},
    {"ce36456p_CE36456.V2", Format::csmip_v2, 3250, 0.02, 0.2613, kTable, 7.74, 3, "PARKFIELD", "0 DEG"},
    {"0111a.smc", Format::usgs_smc, 6001, 0.005, 0.1065, kTable, 10.170, {}, "1295 Shafter", "360"},
    {"AOM0081801241951.NS", Format::knet, 13800, 0.01, 0.0369, kTable, 31.260, {}, "AOM008", "N-S"},
    {"AICH040010061330.NS2", Format::knet, 28600, 0.005, 0.0057, kTable, 60.805, {}, "AICH04", ""},
    {"HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC", Format::esm, 19128, 0.005, 0.0003, kTable, 20.670, {}, "ARS1", "HNE"},
    // pySLAMMER CSVs: dt and PGA from gm_summary.csv; npts and t_pk counted independently.
    {"slammer/Cape_Mendocino_1992_PET-090.csv", Format::plain, 1800, 0.02, 0.662, kSummary, 3.280},
    {"slammer/Chi-Chi_1999_TCU068-090.csv", Format::plain, 13102, 0.005, 0.566, kSummary, 13.840},
    {"slammer/Coalinga_1983_PVB-045.csv", Format::plain, 7690, 0.005, 0.380, kSummary, 3.825},
    {"slammer/Coyote_Lake_1979_G02-050.csv", Format::plain, 5070, 0.005, 0.211, kSummary, 2.925},  // CRLF, no final EOL
    {"slammer/Duzce_1999_375-090.csv", Format::plain, 3077, 0.01, 0.514, kSummary, 6.910},
    {"slammer/Imperial_Valley_1979_BCR-230.csv", Format::plain, 7348, 0.005, 0.775, kSummary, 6.795},
    {"slammer/Kocaeli_1999_ATS-090.csv", Format::plain, 26780, 0.005, 0.185, kSummary, 17.955},
    {"slammer/Landers_1992_LCN-345.csv", Format::plain, 9495, 0.005, 0.789, kSummary, 14.480},
    {"slammer/Loma_Prieta_1989_HSP-000.csv", Format::plain, 11177, 0.005, 0.371, kSummary, 7.880},
    {"slammer/Mammoth_Lakes-1_1980_CVK-090.csv", Format::plain, 5861, 0.005, 0.416, kSummary, 5.525},
    {"slammer/Mammoth_Lakes-2_1980_CVK-090.csv", Format::plain, 5049, 0.005, 0.266, kSummary, 4.460},
    {"slammer/Morgan_Hill_1984_CYC-285.csv", Format::plain, 5723, 0.005, 1.298, kSummary, 3.725},
    {"slammer/N_Palm_Springs_1986_WWT-180.csv", Format::plain, 3948, 0.005, 0.492, kSummary, 3.150},
    {"slammer/Nahanni_1985_NS1-280.csv", Format::plain, 4113, 0.005, 1.096, kSummary, 9.160},
    {"slammer/Nisqually_2001_UNR-058.csv", Format::plain, 10744, 0.01, 0.274, kSummary, 14.520},
    {"slammer/Northridge_1994_PAC-175.csv", Format::plain, 1000, 0.02, 0.415, kSummary, 3.540},
    {"slammer/Northridge_1994_VSP-360.csv", Format::plain, 9327, 0.005, 0.934, kSummary, 7.775},  // UTF-8 BOM, CRLF
};

class ReaderRecords : public ::testing::TestWithParam<RecordCase> {};

TEST_P(ReaderRecords, MatchesIndependentTable) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  const RecordCase& c = GetParam();
  const auto path = shared_record(c.file);
  ASSERT_TRUE(std::filesystem::exists(path)) << path;

  ReadOptions options;
  options.channel = c.channel;
  const GroundMotion m = read_motion(path, options);
  std::ifstream in(path, std::ios::binary);
  const std::string content((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(detect_format(content), c.format);
  EXPECT_EQ(m.metadata().format, format_name(c.format));
  EXPECT_EQ(m.metadata().source_file, path.string());
  EXPECT_EQ(m.size(), c.npts);
  EXPECT_TRUE(m.is_uniform());
  EXPECT_NEAR(m.dt_s(), c.dt_s, 1e-9 * c.dt_s);
  EXPECT_DOUBLE_EQ(m.start_time_s(), 0.0);
  EXPECT_NEAR(m.pga_m_s2() / kStandardGravity, c.pga_g, c.pga_tolerance_g);
  EXPECT_NEAR(m.pga_time_s(), c.t_peak_s, 1e-6);
  for (double a : m.accel_m_s2()) ASSERT_TRUE(std::isfinite(a));
  if (!c.station.empty()) {
    EXPECT_NE(m.metadata().station.find(c.station), std::string::npos) << m.metadata().station;
  }
  if (!c.component.empty()) {
    EXPECT_EQ(m.metadata().component, c.component);
  }
  EXPECT_FALSE(m.metadata().units_as_read.empty());

  // Forcing the detected format reads the same record.
  options.format = c.format;
  const GroundMotion forced = parse_motion(content, c.file, options);
  EXPECT_EQ(forced.size(), m.size());
  EXPECT_DOUBLE_EQ(forced.pga_m_s2(), m.pga_m_s2());
}

std::string case_name(const ::testing::TestParamInfo<RecordCase>& info) {
  std::string name;
  for (char ch : info.param.file.substr(info.param.file.rfind('/') + 1)) {
    name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  }
  if (info.param.channel) name += "_ch" + std::to_string(*info.param.channel);
  return name;
}

INSTANTIATE_TEST_SUITE_P(Shared, ReaderRecords, ::testing::ValuesIn(kRecords), case_name);

// ---- Values in the headers, to their printed precision ----

TEST(ReaderHeaderPeaks, AgreeWithTheReadValues) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  {  // COSMOS line 11: "Max = -6.852 cm/sec2 at 76.215 sec"
    const auto m = read_motion(shared_record("us1000hyfh_akbmrp_AKBMR--n.1000hyfh.BNZ.--.acc.V2c"));
    EXPECT_NEAR(m.pga_m_s2(), 0.06852, 0.5e-5);
    EXPECT_NEAR(m.pga_time_s(), 76.215, 1e-9);
  }
  {  // CSMIP channel 1: "PEAK ACCELERATION =  -267.957 CM/SEC/SEC AT 10.940 SEC."
    ReadOptions o;
    o.channel = 1;
    const auto m = read_motion(shared_record("ce36456p_CE36456.V2"), o);
    EXPECT_NEAR(m.pga_m_s2(), 2.67957, 0.5e-5);
  }
  {  // K-NET: "Max. Acc. (gal)   36.185", after removing the record mean.
    const auto m = read_motion(shared_record("AOM0081801241951.NS"));
    EXPECT_NEAR(m.pga_m_s2() * 100.0, 36.185, 0.5e-3);
    const auto k = read_motion(shared_record("AICH040010061330.NS2"));
    EXPECT_NEAR(k.pga_m_s2() * 100.0, 5.605, 0.5e-3);
    EXPECT_NE(k.metadata().component.find("surface"), std::string::npos);
  }
  {  // ESM: "PGA_CM/S^2: 0.300022", "TIME_PGA_S: 20.670000"
    const auto m = read_motion(shared_record("HI.ARS1..HNE.D.20190728.160908.C.ACC.ASC"));
    EXPECT_NEAR(m.pga_m_s2() * 100.0, 0.300022, 0.5e-6);
    EXPECT_NEAR(m.pga_time_s(), 20.67, 1e-9);
  }
}

TEST(ReaderChannels, CsmipWithoutChannelListsThem) {
  if (!have_shared()) GTEST_SKIP() << "shared/records not found";
  try {
    (void)read_motion(shared_record("ce36456p_CE36456.V2"));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ce36456p_CE36456.V2"), std::string::npos) << what;
    EXPECT_EQ(e.where().field, "--channel");
    EXPECT_NE(what.find("1 (90 DEG), 2 (UP), 3 (0 DEG)"), std::string::npos) << what;
  }
}

// ---- Plain text written on the fly ----

GroundMotion parse(const std::string& text, ReadOptions options = {}) { return parse_motion(text, "mem.txt", options); }

TEST(ReaderPlain, OneColumnNeedsDtAndUnits) {
  ReadOptions o;
  o.dt_s = 0.5;
  o.units = "m/s2";
  const auto m = parse("0\n1\n-2\n0.5\n", o);
  EXPECT_TRUE(m.is_uniform());
  EXPECT_EQ(m.size(), 4u);
  EXPECT_DOUBLE_EQ(m.dt_s(), 0.5);
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 2.0);
  EXPECT_DOUBLE_EQ(m.pga_time_s(), 1.0);
  EXPECT_EQ(m.metadata().format, "plain");
}

TEST(ReaderPlain, HeaderUnitsConvert) {
  EXPECT_DOUBLE_EQ(parse("time_s,accel_g\n0,0\n0.01,0.5\n0.02,0\n").pga_m_s2(), 0.5 * kStandardGravity);
  EXPECT_DOUBLE_EQ(parse("time_s,accel_m_s2\n0,0\n0.01,0.5\n0.02,0\n").pga_m_s2(), 0.5);
  EXPECT_DOUBLE_EQ(parse("time_s,accel_cm_s2\n0,0\n0.01,50\n0.02,0\n").pga_m_s2(), 0.5);
  ReadOptions o;
  o.dt_s = 0.01;
  EXPECT_DOUBLE_EQ(parse("accel_cm_s2\n0\n50\n0\n", o).pga_m_s2(), 0.5);
  EXPECT_DOUBLE_EQ(parse("time [s], accel [gal]\n0, 0\n0.01, 50\n0.02, 0\n").pga_m_s2(), 0.5);
  // ReadOptions::units no longer overrides the header (issue 11: that was a silent guess): it may confirm it, and a
  // conflict is refused naming --units (tests/io/test_reader_errors.cpp, UnitsOptionMustAgreeWithTheFile).
  ReadOptions g;
  g.units = "g";
  EXPECT_THROW((void)parse("time_s,accel_m_s2\n0,0\n0.01,0.5\n0.02,0\n", g), InputError);
  EXPECT_DOUBLE_EQ(parse("time_s,accel_g\n0,0\n0.01,0.5\n0.02,0\n", g).pga_m_s2(), 0.5 * kStandardGravity);
  // g itself is an option.
  ReadOptions g981;
  g981.g_m_s2 = 9.81;
  EXPECT_DOUBLE_EQ(parse("time_s,accel_g\n0,0\n0.01,1\n", g981).pga_m_s2(), 9.81);
}

TEST(ReaderPlain, CommentedHeaderOfPySlammer) {
  const auto m = parse("# Time Series: Kobe, Japan 1995 - TAK-090\n# Time (s),Acceleration (g's)\n0.0,0.1\n0.01,-0.2\n");
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 0.2 * kStandardGravity);
  EXPECT_EQ(m.metadata().event, "Kobe, Japan 1995");
  EXPECT_EQ(m.metadata().station, "TAK");
  EXPECT_EQ(m.metadata().component, "090");
  EXPECT_EQ(m.metadata().units_as_read, "g");
}

TEST(ReaderPlain, BomCrlfWhitespaceAndComments) {
  const auto m = parse("\xEF\xBB\xBF# made by hand\r\ntime_s  accel_g\r\n\r\n0.0\t0.1\r\n# a comment\r\n0.01  -0.3\r\n0.02 0");
  EXPECT_EQ(m.size(), 3u);
  EXPECT_TRUE(m.is_uniform());
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 0.3 * kStandardGravity);
}

TEST(ReaderPlain, UniformTimesBecomeUniformOthersIrregular) {
  const auto u = parse("time_s,accel_g\n1.00,0\n1.01,1\n1.02,0\n1.03,0\n");
  EXPECT_TRUE(u.is_uniform());
  EXPECT_NEAR(u.dt_s(), 0.01, 1e-12);
  EXPECT_DOUBLE_EQ(u.start_time_s(), 1.0);
  EXPECT_NEAR(u.pga_time_s(), 1.01, 1e-12);
  const auto irr = parse("time_s,accel_g\n0,0\n0.01,1\n0.03,0\n0.04,0\n");
  EXPECT_FALSE(irr.is_uniform());
  EXPECT_DOUBLE_EQ(irr.time_s(2), 0.03);
  // A milliseconds column.
  const auto ms = parse("time_ms,accel_g\n0,0\n10,1\n20,0\n");
  EXPECT_NEAR(ms.dt_s(), 0.01, 1e-15);
}

TEST(ReaderDetect, FromContentNeverFromName) {
  EXPECT_EQ(detect_format("time_s,accel_g\n0,0\n"), Format::plain);
  EXPECT_EQ(detect_format(""), Format::plain);
  EXPECT_EQ(detect_format("A\nB\nACCELERATION TIME SERIES IN UNITS OF G\nNPTS=   3, DT=   .0100 SEC,\n1 2 3\n"),
            Format::peer_at2);
  EXPECT_EQ(detect_format("A\nB\nC\n  4164    0.0100    NPTS, DT\n"), Format::peer_at2);
  EXPECT_EQ(detect_format("Corrected acceleration    (Format v01.20 with 13 text lines)\n"), Format::cosmos_v2);
  EXPECT_EQ(detect_format("EVENT_NAME: X\nSAMPLING_INTERVAL_S: 0.01\n"), Format::esm);
  EXPECT_EQ(detect_format("Origin Time       2018/01/24 19:51:00\nScale Factor      3920(gal)/6182761\n"),
            Format::knet);
}

TEST(ReaderFormatNames, RoundTrip) {
  for (Format f : {Format::automatic, Format::peer_at2, Format::cosmos_v2, Format::csmip_v2, Format::knet,
                   Format::usgs_smc, Format::esm, Format::plain}) {
    EXPECT_EQ(parse_format_name(format_name(f)), f);
  }
  EXPECT_THROW((void)parse_format_name("at2"), InputError);
}

// ---- plain files as recorded: column choice, separators, baseline (issue 28) ----

/// A shake-table-like file: a tab-separated header whose names hold spaces, eight columns, a text column (Status)
/// and a displacement column in mm; the table acceleration is a_k = 0.02 + 0.5 sin(2 pi k / 10) g at t_k = k dt.
std::string shake_table(char sep, int rows = 41, double dt = 0.005) {
  const std::vector<std::string> names = {"Time (s)",  "Table Acc (g)", "Table Disp (mm)", "Table Vel (m/s)",
                                          "Acc 2 (g)", "Status",        "LVDT 1 (mm)",     "Cmd Disp (mm)"};
  std::string s = "# Shake table test 17, rock B2\n";
  for (std::size_t k = 0; k < names.size(); ++k) s += (k ? std::string(1, sep) : "") + names[k];
  s += "\n";
  for (int k = 0; k < rows; ++k) {
    const double a = 0.02 + 0.5 * std::sin(2.0 * M_PI * k / 10.0);
    s += fmt::format("{:.6f}{s}{:.17g}{s}{}{s}0.1{s}-0.3{s}{}{s}12.5{s}0\n", k * dt, a, 1.5 * k,
                     k % 2 ? "OK" : "n/a", fmt::arg("s", std::string(1, sep)));
  }
  return s;
}

double expected_shake_accel_m_s2(int k) { return (0.02 + 0.5 * std::sin(2.0 * M_PI * k / 10.0)) * kStandardGravity; }

TEST(ReaderColumns, ShakeTableFileByNameAndByNumber) {
  ReadOptions by_name;
  by_name.columns = parse_columns("Time (s),Table Acc (g)");
  ReadOptions by_number;
  by_number.columns = parse_columns("1,2");
  ReadOptions quoted;
  quoted.columns = parse_columns("\"time (S)\" , \"TABLE ACC (G)\"");  // case-insensitive, trimmed
  for (const ReadOptions& o : {by_name, by_number, quoted}) {
    const GroundMotion m = parse(shake_table('\t'), o);
    ASSERT_EQ(m.size(), 41u);
    EXPECT_TRUE(m.is_uniform());
    EXPECT_NEAR(m.dt_s(), 0.005, 1e-15);
    EXPECT_EQ(m.metadata().units_as_read, "g");  // from "(g)" in the chosen column's name
    for (int k = 0; k < 41; ++k) EXPECT_NEAR(m.accel_m_s2()[k], expected_shake_accel_m_s2(k), 1e-14) << k;
  }
  // Another acceleration channel, chosen by its number: the same rows, column 5 (-0.3 g everywhere).
  ReadOptions five;
  five.columns = parse_columns("1,5");
  EXPECT_DOUBLE_EQ(parse(shake_table('\t'), five).pga_m_s2(), 0.3 * kStandardGravity);
  // No time column: the acceleration alone, with dt.
  for (const char* text : {",Table Acc (g)", "accel=2"}) {
    ReadOptions o;
    o.columns = parse_columns(text);
    o.dt_s = 0.005;
    const GroundMotion m = parse(shake_table('\t'), o);
    ASSERT_EQ(m.size(), 41u) << text;
    EXPECT_DOUBLE_EQ(m.accel_m_s2()[3], expected_shake_accel_m_s2(3)) << text;
  }
}

TEST(ReaderColumns, CommaSemicolonAndBlankSeparators) {
  ReadOptions o;
  o.columns = parse_columns("Time (s),Table Acc (g)");
  for (char sep : {',', ';'}) {
    const GroundMotion m = parse(shake_table(sep), o);
    ASSERT_EQ(m.size(), 41u) << sep;
    EXPECT_NEAR(m.accel_m_s2()[7], expected_shake_accel_m_s2(7), 1e-14) << sep;
  }
  // Forced: a file with semicolons read as comma-separated has no column 2.
  ReadOptions forced = o;
  forced.separator = Separator::comma;
  EXPECT_THROW((void)parse(shake_table(';'), forced), InputError);
  // Blank-separated with names without spaces; units given by the name's suffix or by --units.
  ReadOptions b;
  b.columns = parse_columns("t_s,table_acc");
  b.units = "m/s2";
  const GroundMotion blank = parse("t_s  table_acc  disp_mm\n0 0.5 1\n0.01 -1.5 2\n0.02 0 3\n", b);
  EXPECT_DOUBLE_EQ(blank.pga_m_s2(), 1.5);
  EXPECT_EQ(blank.metadata().units_as_read, "m/s2");
  ReadOptions c;
  c.columns = parse_columns("3,accel_cm_s2");
  EXPECT_DOUBLE_EQ(parse("accel_cm_s2;x;time_ms\n50;a;0\n-100;b;10\n", c).pga_m_s2(), 1.0);
  // A commented header counts when it names every column.
  ReadOptions h;
  h.columns = parse_columns("Time (s),Acc (gal)");
  EXPECT_DOUBLE_EQ(parse("# Time (s)\tAcc (gal)\tDisp (mm)\n0\t10\t1\n0.01\t-20\t2\n", h).pga_m_s2(), 0.2);
  // A blank-separated comment is a sentence, not a header, even when it has as many words as the data has columns.
  ReadOptions n;
  n.columns = parse_columns("1,2");
  n.units = "cm/s2";
  const GroundMotion title = parse("# amplitude (g)\n0\t10\n0.01\t-20\n", n);  // not column 2 in g
  EXPECT_DOUBLE_EQ(title.pga_m_s2(), 0.2);
  EXPECT_EQ(title.metadata().units_as_read, "cm/s2");
}

TEST(ReaderColumns, OldFilesMeanWhatTheyMeant) {
  // Without --columns the one- and two-column files read as before (the whole existing ReaderPlain suite too), and a
  // tab-separated two-column file with names holding spaces now reads.
  const GroundMotion m = parse("Time (s)\tAcceleration (g)\n0\t0.1\n0.01\t-0.2\n");
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 0.2 * kStandardGravity);
  EXPECT_DOUBLE_EQ(parse("time_s;accel_g\n0;0.1\n0.01;-0.3\n").pga_m_s2(), 0.3 * kStandardGravity);
  // The header and the data split by their own separators, as every line was before: a "name, name" header over
  // blank-separated data, a tab-separated header (commented too) over data aligned with blanks.
  EXPECT_DOUBLE_EQ(parse("time_s, accel_g\n0 0.1\n0.01 -0.4\n").pga_m_s2(), 0.4 * kStandardGravity);
  EXPECT_DOUBLE_EQ(parse("Time (s)\tAcc (g)\n0  0.1\n0.01  -0.5\n").pga_m_s2(), 0.5 * kStandardGravity);
  EXPECT_DOUBLE_EQ(parse("# Time (s)\tAcceleration (g)\n0  0.1\n0.01  -0.6\n").pga_m_s2(), 0.6 * kStandardGravity);
}

TEST(ReaderColumns, ParseColumnsGrammar) {
  const ColumnChoice a = parse_columns("1,2");
  ASSERT_TRUE(a.time);
  EXPECT_EQ(a.time->number, 1u);
  EXPECT_EQ(a.accel.number, 2u);
  const ColumnChoice b = parse_columns("time=Time (s), accel=Table Acc (g)");
  EXPECT_EQ(b.time->name, "Time (s)");
  EXPECT_EQ(b.accel.name, "Table Acc (g)");
  EXPECT_FALSE(parse_columns(",3").time);
  EXPECT_FALSE(parse_columns("accel=3").time);
  EXPECT_EQ(parse_columns("accel=3").accel.number, 3u);
  EXPECT_EQ(parse_columns("\"a,b\",2").time->name, "a,b");
  for (const char* bad : {"", "3", "1,2,3", "0,2", "1,", "2,2", "x,X", "time=1,time=2", "speed=2", "\"a,2"}) {
    EXPECT_THROW((void)parse_columns(bad), InputError) << bad;
  }
  EXPECT_EQ(parse_separator("tab"), Separator::tab);
  EXPECT_EQ(parse_separator("semicolon"), Separator::semicolon);
  EXPECT_THROW((void)parse_separator("pipe"), InputError);
}

// Baselines against closed forms. The record: n = 2001 samples at dt = 0.005 s over T = 10 s, a sine of 20 whole
// periods (f = 2 Hz) whose uniform samples sum to zero (to rounding), on top of an offset.
GroundMotion offset_record(const std::function<double(double)>& offset, double amp = 1.0) {
  std::vector<double> a(2001);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = 0.005 * static_cast<double>(i);
    a[i] = offset(t) + amp * std::sin(2.0 * M_PI * 2.0 * t);
  }
  return GroundMotion::uniform(std::move(a), 0.005);
}

double max_abs_diff(const GroundMotion& m, const std::function<double(double)>& expected) {
  double worst = 0.0;
  for (std::size_t i = 0; i < m.size(); ++i) worst = std::max(worst, std::abs(m.accel_m_s2()[i] - expected(m.time_s(i))));
  return worst;
}

TEST(Baseline, MeanAndPolyZeroRemoveAConstantExactly) {
  const auto sine = [](double t) { return std::sin(2.0 * M_PI * 2.0 * t); };
  const GroundMotion m = offset_record([](double) { return 0.15; });
  EXPECT_LT(max_abs_diff(remove_baseline(m, parse_baseline("mean")), sine), 1e-13);
  EXPECT_LT(max_abs_diff(remove_baseline(m, parse_baseline("poly:0")), sine), 1e-13);
  // none: the record itself, bit for bit.
  const GroundMotion same = remove_baseline(m, parse_baseline("none"));
  for (std::size_t i = 0; i < m.size(); ++i) ASSERT_EQ(same.accel_m_s2()[i], m.accel_m_s2()[i]);
}

TEST(Baseline, PolynomialsRemoveDriftsOfTheirDegreeExactly) {
  // A linear drift alone is removed to rounding by poly:1; with the sine on top the result is the sine's own poly:1
  // residual (the fit is linear in the data), whatever the drift.
  const auto drift = [](double t) { return 0.3 - 0.04 * t; };
  const GroundMotion pure = offset_record(drift, 0.0);
  EXPECT_LT(max_abs_diff(remove_baseline(pure, parse_baseline("poly:1")), [](double) { return 0.0; }), 1e-13);
  const GroundMotion with = remove_baseline(offset_record(drift), parse_baseline("poly:1"));
  const GroundMotion alone = remove_baseline(offset_record([](double) { return 0.0; }), parse_baseline("poly:1"));
  for (std::size_t i = 0; i < with.size(); ++i) ASSERT_NEAR(with.accel_m_s2()[i], alone.accel_m_s2()[i], 1e-13);
  // A cubic in t (large coefficients, t far from 0: the Legendre basis on [-1, 1] keeps this well conditioned).
  std::vector<double> a(3001);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = 1000.0 + 0.01 * static_cast<double>(i);
    a[i] = 2.0 - 0.5 * (t - 1000.0) + 0.03 * std::pow(t - 1010.0, 2) - 0.002 * std::pow(t - 1015.0, 3);
  }
  const GroundMotion cubic = GroundMotion::uniform(a, 0.01, 1000.0);
  EXPECT_LT(max_abs_diff(remove_baseline(cubic, parse_baseline("poly:3")), [](double) { return 0.0; }), 1e-10);
  // poly:2 of x^3 on [-1, 1]: the continuous least-squares residual is x^3 - (3/5) x (x^3 minus its projection on
  // P_1, since x^3 = (2/5) P_3 + (3/5) P_1); on 10001 uniform samples within 1e-3.
  std::vector<double> x3(10001);
  for (std::size_t i = 0; i < x3.size(); ++i) x3[i] = std::pow(-1.0 + 2e-4 * static_cast<double>(i), 3);
  const GroundMotion x3m = GroundMotion::uniform(x3, 2e-4, -1.0);
  EXPECT_LT(max_abs_diff(remove_baseline(x3m, parse_baseline("poly:2")),
                         [](double x) { return x * x * x - 0.6 * x; }),
            1e-3);
}

TEST(Baseline, PreEventRemovesTheWindowsMean) {
  // Over the first 2 s the record is 0.2 + 0.05 t (no shaking yet): the window's mean is 0.2 + 0.05 * 1 = 0.25 (the
  // samples are symmetric about t = 1 s); afterwards a sine. The whole record loses 0.25.
  std::vector<double> a(2001);
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = 0.005 * static_cast<double>(i);
    a[i] = t <= 2.0 + 1e-12 ? 0.2 + 0.05 * t : 0.3 + std::sin(2.0 * M_PI * t);
  }
  const GroundMotion m = GroundMotion::uniform(a, 0.005);
  const GroundMotion r = remove_baseline(m, parse_baseline("pre-event:2"));
  for (std::size_t i = 0; i < m.size(); ++i) ASSERT_NEAR(r.accel_m_s2()[i], a[i] - 0.25, 1e-14) << i;
  // With a unit; and the names round-trip.
  const GroundMotion ms = remove_baseline(m, parse_baseline("pre-event:2000ms"));
  EXPECT_NEAR(ms.accel_m_s2()[0], a[0] - 0.25, 1e-14);
  for (const char* name : {"none", "mean", "pre-event:2", "pre-event:0.5", "poly:0", "poly:3"}) {
    EXPECT_EQ(baseline_name(parse_baseline(name)), name);
  }
}

TEST(Baseline, ReadOptionsApplyItToEveryFormat) {
  ReadOptions o;
  o.columns = parse_columns("Time (s),Table Acc (g)");
  o.baseline = parse_baseline("pre-event:0.0001");  // refused: the window holds one sample
  EXPECT_THROW((void)parse(shake_table('\t'), o), InputError);
  o.baseline = parse_baseline("mean");
  const GroundMotion m = parse(shake_table('\t', 41), o);
  // 41 samples over 4 whole periods of 10 samples plus one (sin 0 = 0): the mean is the 0.02 g offset.
  EXPECT_NEAR(m.accel_m_s2()[5], (0.5 * std::sin(M_PI)) * kStandardGravity, 1e-13);
  EXPECT_NEAR(m.accel_m_s2()[2], 0.5 * std::sin(0.4 * M_PI) * kStandardGravity, 1e-13);
  // A one-column file, and an agency format (PEER AT2) too.
  ReadOptions one;
  one.units = "g";
  one.dt_s = 0.01;
  one.baseline = parse_baseline("poly:0");
  EXPECT_DOUBLE_EQ(parse("1\n2\n3\n", one).accel_m_s2()[2], 1.0 * kStandardGravity);
  if (have_shared()) {
    ReadOptions at2;
    at2.baseline = parse_baseline("mean");
    const GroundMotion raw = read_motion(shared_record("Rinaldi228.AT2"));
    const GroundMotion cor = read_motion(shared_record("Rinaldi228.AT2"), at2);
    double mean = 0.0;
    for (double v : raw.accel_m_s2()) mean += v;
    mean /= static_cast<double>(raw.size());
    EXPECT_NEAR(cor.accel_m_s2()[100], raw.accel_m_s2()[100] - mean, 1e-12);
  }
}

}  // namespace
}  // namespace topple::io
