// Sweep files: every key read into the spec (lists, ranges, units, globs), and every kind of bad file refused before
// any run with an InputError naming the file, the line and the key.
#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <variant>
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/meshes.hpp"
#include "support/shared_data.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/io/sweep_file.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/ensemble/sweep.hpp"

namespace topple::io {
namespace {

namespace fs = std::filesystem;
using ensemble::RockObject;
using ensemble::ScaleSpec;
using ensemble::SlideObject;
using test::TempDir;
using test::write_file;

constexpr double kG = kStandardGravity;

/// A plain record (time_s,accel_g header) of n samples at 0.01 s: 2.5 Hz, so that t = 0.1 s samples the peak.
std::string plain_record(double amp_g, std::size_t n = 200) {
  std::string s = "time_s,accel_g\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double t = 0.01 * static_cast<double>(i);
    s += fmt::format("{},{}\n", t, amp_g * std::sin(2.0 * kPi * 2.5 * t));
  }
  return s;
}

SweepFile parse_in(const TempDir& dir, const std::string& text, const std::string& name = "sweep.toml") {
  const fs::path p = dir.path() / name;
  write_file(p, text);
  return read_sweep_file(p);
}

const char* kPulseMotions = R"(
[motions]
[[motions.pulse]]
kind = "sine"
amp_g = 0.3
freq_hz = 2
)";

TEST(SweepFile, TheIssueExample) {
  TempDir dir;
  fs::create_directories(dir.path() / "records");
  fs::create_directories(dir.path() / "more");
  write_file(dir.path() / "records" / "b.AT2.csv", plain_record(0.3));
  write_file(dir.path() / "records" / "a.AT2.csv", plain_record(0.2));
  write_file(dir.path() / "more" / "c.V2.csv", plain_record(0.1));
  fs::create_directories(dir.path() / "records" / "sub.AT2.csv");  // a directory the glob also matches: skipped
  const SweepFile s = parse_in(dir, R"(
description = "the example of the issue"
[motions]
files = ["records/*.AT2.csv", "more/*.V2.csv", "records/a.AT2.csv"]   # the last one is already in: once only
scale_pga_g = [0.1, 0.2, 0.4]
polarity = ["normal", "inverse"]
[[motions.pulse]]
kind = "sine"
amp_g = [0.2, 0.4, 0.6]
freq_hz = [1.0, 2.0, 4.0]

[[object]]
model = "slide"
mu = [0.05, 0.1, 0.2]
mode = "two-way"

[[object]]
model = "rock"
shape = "block"
width = ["4cm", "8cm"]
height = "20cm"
e = "housner"

[output]
path = "results.csv"
)");
  ASSERT_EQ(s.spec.records.size(), 3u);
  EXPECT_EQ(s.spec.records[0].name, "records/a.AT2.csv");
  EXPECT_EQ(s.spec.records[1].name, "records/b.AT2.csv");
  EXPECT_EQ(s.spec.records[2].name, "more/c.V2.csv");
  EXPECT_NEAR(s.spec.records[0].motion->pga_m_s2(), 0.2 * kG, 1e-9);
  ASSERT_EQ(s.spec.scales.size(), 3u);
  EXPECT_EQ(s.spec.scales[1].kind, ScaleSpec::Kind::pga);
  EXPECT_EQ(s.spec.scales[1].value, 0.2 * kG);  // as `--scale-pga 0.2g` computes it
  EXPECT_EQ(s.spec.inverse, (std::vector<bool>{false, true}));
  ASSERT_EQ(s.spec.pulses.size(), 9u);
  EXPECT_EQ(s.spec.pulses[1].name, "sine amp_g=0.2 freq_hz=2");
  EXPECT_EQ(s.spec.pulses[1].spec.duration_s, 0.5);
  EXPECT_EQ(s.spec.pulses[1].spec.tail_s, 2.5);
  EXPECT_EQ(s.spec.pulses[3].spec.amplitude_m_s2, 0.4 * kG);
  ASSERT_EQ(s.spec.objects.size(), 5u);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[2]).block.mu_static, 0.2);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[2]).block.mu_kinetic, 0.2);
  const auto& r = std::get<RockObject>(s.spec.objects[4]);
  EXPECT_DOUBLE_EQ(*r.width_m, 0.08);
  EXPECT_DOUBLE_EQ(r.body.h_m, 0.10);
  EXPECT_EQ(r.options.restitution, RestitutionMode::housner);
  EXPECT_EQ(s.output_csv, dir.path() / "results.csv");
  EXPECT_FALSE(s.jsonl);
  const ensemble::Plan plan = ensemble::make_plan(s.spec);
  EXPECT_EQ(plan.motions.size(), 3u * 3u * 2u + 9u * 2u);
  EXPECT_EQ(plan.runs(), plan.motions.size() * 5u);
}

TEST(SweepFile, ListsRangesAndUnits) {
  TempDir dir;
  const SweepFile s = parse_in(dir, std::string(kPulseMotions) + R"(
[[motions.pulse]]
kind = ["rect", "tri"]
amp = ["2m/s2", "0.5g"]
duration = ["100ms", "0.2s"]
tail = "1s"
[[object]]
model = "slide"
mu = { from = 0.1, to = 0.5, count = 5 }
mu_kinetic = 0.05
slope = "10deg"
mode = ["two-way", "one-way"]
[[object]]
model = "slide"
mu = { from = 0.05, to = 0.2, step = 0.05 }
slope_deg = [0, 5]
[[object]]
model = "slide"
mu = { from = 0.01, to = 1, count = 3, spacing = "log" }
[[object]]
model = "rock"
shape = "cylinder"
diameter_m = { from = 0.05, to = 0.1, count = 2 }
height = { from = "20cm", to = "40cm", step = "10cm" }
e = ["housner", 0.9]
mu = [0.3, 0.6]
[[object]]
model = "rock"
shape = "general"
a = "2cm"
h_m = 0.1
D_m2 = 0.02
e = { from = 0.8, to = 0.9, count = 2 }
[output]
path = "out/r.csv"
jsonl = true
chunk_runs = 17
)");
  ASSERT_EQ(s.spec.pulses.size(), 1u + 8u);
  EXPECT_EQ(s.spec.pulses[1].spec.kind, PulseKind::rectangular);
  EXPECT_EQ(s.spec.pulses[1].spec.amplitude_m_s2, 2.0);
  EXPECT_NEAR(s.spec.pulses[1].spec.duration_s, 0.1, 1e-15);
  EXPECT_EQ(s.spec.pulses[1].spec.tail_s, 1.0);
  EXPECT_EQ(s.spec.pulses[1].name, "rect amp_g=0.20394324259558566 duration_s=0.1");
  EXPECT_EQ(s.spec.pulses[3].spec.amplitude_m_s2, 0.5 * kG);
  // slide 1: 2 modes x 1 slope x 5 mu; slide 2: 2 slopes x 4 mu; slide 3: 3 mu
  std::vector<double> mus;
  for (std::size_t i = 0; i < 10; ++i) {
    const auto& b = std::get<SlideObject>(s.spec.objects[i]);
    if (i < 5) mus.push_back(b.block.mu_static);
    EXPECT_EQ(b.block.mu_kinetic, 0.05);
    EXPECT_NEAR(b.slope_deg, 10.0, 1e-12);
    EXPECT_EQ(b.block.mode, i < 5 ? SlidingMode::two_way : SlidingMode::one_way);
  }
  EXPECT_EQ(mus, (std::vector<double>{0.1, 0.2, 0.30000000000000004, 0.4, 0.5}));
  const auto& step0 = std::get<SlideObject>(s.spec.objects[10]);
  EXPECT_EQ(step0.slope_deg, 0.0);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[13]).block.mu_static, 0.05 + 3 * 0.05);  // 'to' within round-off
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[14]).slope_deg, 5.0);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[14]).block.slope_rad, 5.0 * kPi / 180.0);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[18]).block.mu_static, 0.01);
  EXPECT_NEAR(std::get<SlideObject>(s.spec.objects[19]).block.mu_static, 0.1, 1e-15);
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[20]).block.mu_static, 1.0);
  // rock cylinders: 2 diameters x 3 heights x 2 e x 2 mu = 24, then general: 2 e
  ASSERT_EQ(s.spec.objects.size(), 21u + 24u + 2u);
  const auto& c = std::get<RockObject>(s.spec.objects[21 + 1]);
  EXPECT_EQ(c.body.shape, RockingBody::Shape::cylinder);
  EXPECT_EQ(*c.diameter_m, 0.05);
  EXPECT_DOUBLE_EQ(*c.height_m, 0.2);
  EXPECT_EQ(c.options.restitution, RestitutionMode::housner);
  EXPECT_EQ(*c.options.mu, 0.6);
  const auto& c2 = std::get<RockObject>(s.spec.objects[21 + 2]);
  EXPECT_EQ(c2.options.restitution, RestitutionMode::given);
  EXPECT_EQ(c2.options.e, 0.9);
  const auto& gen = std::get<RockObject>(s.spec.objects[46]);
  EXPECT_EQ(gen.body.shape, RockingBody::Shape::general);
  EXPECT_DOUBLE_EQ(gen.body.a_m, 0.02);
  EXPECT_EQ(gen.options.e, 0.9);
  EXPECT_EQ(s.output_csv, dir.path() / "out" / "r.csv");
  EXPECT_TRUE(s.jsonl);
  EXPECT_EQ(s.spec.chunk_runs, 17u);
  EXPECT_EQ(jsonl_path_for(s.output_csv), dir.path() / "out" / "r.jsonl");
}

TEST(SweepFile, RecordOptionsTimeScalesAndGravity) {
  TempDir dir;
  std::string one_column;
  for (int i = 0; i < 100; ++i) one_column += fmt::format("{}\n", 50.0 * std::sin(0.3 * i));
  write_file(dir.path() / "r.txt", one_column);
  const SweepFile s = parse_in(dir, R"(
g = "9.81m/s2"
[motions]
files = "r.txt"
format = "plain"
units = "gal"
dt = "20ms"
scale = [0.5, 2]
time_scale = [1, 2]
[[object]]
model = "slide"
mu = 0.1
)");
  EXPECT_EQ(s.spec.g_m_s2, 9.81);
  ASSERT_EQ(s.spec.records.size(), 1u);
  EXPECT_EQ(s.spec.records[0].name, "r.txt");
  EXPECT_NEAR(s.spec.records[0].motion->dt_s(), 0.02, 1e-15);
  EXPECT_NEAR(s.spec.records[0].motion->pga_m_s2(), 0.5, 1e-3);  // 50 gal
  ASSERT_EQ(s.spec.scales.size(), 2u);
  EXPECT_EQ(s.spec.scales[0].kind, ScaleSpec::Kind::factor);
  EXPECT_EQ(s.spec.time_scales, (std::vector<double>{1.0, 2.0}));
  EXPECT_EQ(std::get<SlideObject>(s.spec.objects[0]).block.g_m_s2, 9.81);
  EXPECT_EQ(s.output_csv, dir.path() / "sweep.csv");  // default: the sweep file's name
}

// ---- bad files ----

struct BadCase {
  const char* what;
  std::string text;
  std::string field;         // the key the message must name
  std::size_t line;          // 1-based line of the problem
  std::string problem_part;  // a piece of the reason
};

std::vector<BadCase> bad_cases() {
  const std::string pulse = "[motions]\n[[motions.pulse]]\nkind = \"sine\"\namp_g = 0.3\nfreq_hz = 2\n";  // 5 lines
  const std::string slide = "[[object]]\nmodel = \"slide\"\nmu = 0.1\n";                                    // 3 lines
  return {
      {"unknown top-level key", "[motion]\n" + pulse + slide, "motion", 1, "unknown key 'motion'"},
      {"unknown key in an object", pulse + "[[object]]\nmodel = \"slide\"\nmu = 0.1\nmue = 3\n", "object[1].mue", 9,
       "unknown key"},
      {"unknown key in a pulse", "[motions]\n[[motions.pulse]]\nkind = \"sine\"\namp_g = 0.3\nfreq = \"2Hz\"\nphase = 1\n" + slide,
       "motions.pulse[1].phase", 6, "unknown key"},
      {"missing record", "[motions]\nfiles = [\"rec.AT2\", \"nope.AT2\"]\n" + slide, "motions.files[2]", 2,
       "no such record file 'nope.AT2'"},
      {"glob matching nothing", "[motions]\nfiles = \"records/*.V2\"\n" + slide, "motions.files", 2,
       "matches no file"},
      {"empty list", pulse + "[[object]]\nmodel = \"slide\"\nmu = []\n", "object[1].mu", 8, "empty list"},
      {"empty range", pulse + "[[object]]\nmodel = \"slide\"\nmu = { from = 0.5, to = 0.1, step = 0.1 }\n",
       "object[1].mu", 8, "empty range"},
      {"range of count 0", pulse + "[[object]]\nmodel = \"slide\"\nmu = { from = 0.1, to = 0.5, count = 0 }\n",
       "object[1].mu", 8, "empty range"},
      {"missing unit", pulse + slide + "[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = [\"4cm\", 0.08]\nheight = \"20cm\"\n",
       "object[2].width", 12, "has no unit"},
      {"missing unit in a string", pulse + slide + "[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = \"4cm\"\nheight = \"20\"\n",
       "object[2].height", 13, "no unit"},
      {"unknown unit", pulse + "[[object]]\nmodel = \"slide\"\nmu = 0.1\nslope = \"10 furlongs\"\n", "object[1].slope",
       9, "unknown angle unit"},
      {"wrong type", pulse + "[[object]]\nmodel = \"slide\"\nmu = \"0.1\"\n", "object[1].mu", 8, "got a string"},
      {"wrong type in a list", pulse + "[[object]]\nmodel = \"slide\"\nmu = [0.1, true]\n", "object[1].mu", 8,
       "got a boolean"},
      {"both spellings", pulse + "[[object]]\nmodel = \"slide\"\nmu = 0.1\nslope = \"5deg\"\nslope_deg = 5\n",
       "object[1].slope", 9, "not both"},
      {"unknown model", pulse + "[[object]]\nmodel = \"topple\"\n", "object[1].model", 7, "unknown model"},
      {"missing mu", pulse + "[[object]]\nmodel = \"slide\"\n", "object[1].mu", 6, "needs its friction"},
      {"kinetic above static", pulse + "[[object]]\nmodel = \"slide\"\nmu = [0.3, 0.1]\nmu_kinetic = 0.2\n",
       "object[1].mu_kinetic", 9, "kinetic friction"},
      {"slope steeper than friction allows", pulse + "[[object]]\nmodel = \"slide\"\nmu = 1.0\nslope_deg = 50\n",
       "object[1].slope_deg", 9, "reaches 90 deg"},
      {"squat block with Housner's e", pulse + "[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = \"30cm\"\nheight = \"10cm\"\n",
       "object[1].e", 6, "give e explicitly"},
      {"e out of range", pulse + "[[object]]\nmodel = \"rock\"\nshape = \"block\"\nwidth = \"3cm\"\nheight = \"10cm\"\ne = 1.2\n",
       "object[1].e", 11, "[0, 1]"},
      {"width on a cylinder", pulse + "[[object]]\nmodel = \"rock\"\nshape = \"cylinder\"\ndiameter = \"3cm\"\nheight = \"10cm\"\nwidth = \"1cm\"\n",
       "object[1].width", 11, "does not apply"},
      {"object as a single table", pulse + "[object]\nmodel = \"slide\"\nmu = 0.1\n", "object", 6, "[[object]]"},
      {"no object", pulse, "object", 0, "no [[object]]"},
      {"no motion", "[motions]\npolarity = \"normal\"\n" + slide, "motions", 1, "no motion"},
      {"bad polarity", "[motions]\npolarity = [\"normal\", \"reverse\"]\n" + pulse.substr(10) + slide,
       "motions.polarity", 2, "unknown polarity"},
      {"scaling without records", "[motions]\nscale_pga_g = [0.1]\n" + pulse.substr(10) + slide, "motions", 2,
       "apply to record files"},
      {"scale and scale_pga", "[motions]\nfiles = \"rec.AT2\"\nscale = [1]\nscale_pga = [\"0.1g\"]\n" + slide,
       "motions.scale", 3, "not both"},
      {"pulse without amplitude", "[motions]\n[[motions.pulse]]\nkind = \"sine\"\nfreq_hz = 2\n" + slide,
       "motions.pulse[1].amp_g", 2, "amplitude"},
      {"unknown pulse kind", "[motions]\n[[motions.pulse]]\nkind = \"square\"\namp_g = 1\nfreq_hz = 2\n" + slide,
       "motions.pulse[1].kind", 3, "unknown pulse"},
      {"bad output key", pulse + slide + "[output]\nfile = \"x.csv\"\n", "output.file", 10, "unknown key"},
      {"bad chunk size", pulse + slide + "[output]\nchunk_runs = 0\n", "output.chunk_runs", 10, "must be >= 1"},
      {"not TOML", "[motions\n", "", 1, "not valid TOML"},
  };
}

/// The sweep file `p` holding `text` is refused with an InputError naming `p`, `field`, `line` (when > 0) and a
/// problem that contains `problem_part`.
void expect_refused(const fs::path& p, const std::string& text, const std::string& field, std::size_t line,
                    const std::string& problem_part) {
  write_file(p, text);
  try {
    static_cast<void>(read_sweep_file(p));
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, p.string()) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    if (line > 0) {
      EXPECT_EQ(e.where().line.value_or(0), line) << e.what();
    }
    EXPECT_NE(e.problem().find(problem_part), std::string::npos) << e.what();
  }
}

TEST(SweepFile, RecordsAsRecordedColumnsSeparatorBaseline) {
  // Issue 28: [motions] columns, separator and baseline read plain records as a lab writes them. The table file has
  // four semicolon-separated columns and a +0.05 g offset over a 2.5 Hz sine of 0.2 g (200 samples, 5 periods).
  TempDir dir;
  std::string table = "Time (s);Table Acc (g);Disp (mm);Note\n";
  for (int i = 0; i < 200; ++i) {
    const double t = 0.01 * i;
    table += fmt::format("{};{:.17g};{};x\n", t, 0.05 + 0.2 * std::sin(2.0 * kPi * 2.5 * t), i);
  }
  write_file(dir.path() / "t.txt", table);
  for (const char* columns : {R"x(["Time (s)", "Table Acc (g)"])x", "[1, 2]", R"x("1,2")x"}) {
    const SweepFile s = parse_in(dir, fmt::format(R"(
[motions]
files = "t.txt"
columns = {}
separator = "semicolon"
baseline = "mean"
[[object]]
model = "slide"
mu = 0.1
)", columns));
    ASSERT_EQ(s.spec.records.size(), 1u) << columns;
    // The mean of 5 whole periods sampled uniformly is the offset: the sine remains, peak 0.2 g at t = 0.1 s.
    EXPECT_NEAR(s.spec.records[0].motion->pga_m_s2(), 0.2 * kG, 1e-12) << columns;
    EXPECT_NEAR(s.spec.records[0].motion->accel_m_s2()[0], 0.0, 1e-13) << columns;
  }
  // No time column: ["", 2] with dt.
  const SweepFile n = parse_in(dir, "[motions]\nfiles = \"t.txt\"\ncolumns = [\"\", 2]\ndt_s = 0.01\n"
                                    "[[object]]\nmodel = \"slide\"\nmu = 0.1\n");
  EXPECT_NEAR(n.spec.records[0].motion->pga_m_s2(), 0.25 * kG, 1e-3 * kG);  // offset kept: baseline none
  // Errors name the sweep's keys; a column missing from the header names the record's file and header line.
  const std::string slide = "[[object]]\nmodel = \"slide\"\nmu = 0.1\n";
  expect_refused(dir.path() / "b1.toml", "[motions]\nfiles = \"t.txt\"\nbaseline = \"poly:7\"\n" + slide,
                 "motions.baseline", 3, "0..3");
  expect_refused(dir.path() / "b2.toml", "[motions]\nfiles = \"t.txt\"\ncolumns = [1, 2, 3]\n" + slide,
                 "motions.columns", 3, "2 columns");
  expect_refused(dir.path() / "b3.toml", "[motions]\nfiles = \"t.txt\"\nseparator = \"pipe\"\n" + slide,
                 "motions.separator", 3, "unknown separator");
  // format and units: the words of the campaign reader too (io/toml_reader.hpp, test_campaign_file.cpp).
  expect_refused(dir.path() / "b4.toml", "[motions]\nfiles = \"t.txt\"\nformat = \"at3\"\n" + slide,
                 "motions.format", 3, "unknown format 'at3'");
  expect_refused(dir.path() / "b5.toml", "[motions]\nfiles = \"t.txt\"\nunits = \"furlong\"\n" + slide,
                 "motions.units", 3, "unknown acceleration unit 'furlong'");
  expect_refused(dir.path() / "b6.toml", "[motions]\nfiles = \"t.txt\"\nformat = 3\n" + slide,
                 "motions.format", 3, "expected a string, got an integer");
  try {
    static_cast<void>(parse_in(dir, "[motions]\nfiles = \"t.txt\"\ncolumns = [1, \"Acc (g)\"]\n" + slide));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("t.txt"), std::string::npos) << e.what();
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(1)) << e.what();
    EXPECT_EQ(e.where().field, "motions.columns") << e.what();
    EXPECT_NE(e.problem().find("'Table Acc (g)'"), std::string::npos) << e.what();
  }
}

TEST(SweepFile, BadFilesNameFileLineAndKey) {
  TempDir dir;
  write_file(dir.path() / "rec.AT2", plain_record(0.2));  // a plain file named like an AT2: content decides
  for (const auto& c : bad_cases()) {
    SCOPED_TRACE(c.what);
    expect_refused(dir.path() / "bad.toml", c.text, c.field, c.line, c.problem_part);
  }
}

TEST(SweepFile, AnUnreadableRecordIsNamed) {
  TempDir dir;
  write_file(dir.path() / "good.csv", plain_record(0.2));
  write_file(dir.path() / "bad.csv", "time_s,accel_g\n0,0.1\n0.01,zero\n");
  try {
    static_cast<void>(parse_in(dir, "[motions]\nfiles = \"*.csv\"\n[[object]]\nmodel = \"slide\"\nmu = 0.1\n"));
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(e.where().file.find("bad.csv"), std::string::npos) << e.what();
    EXPECT_TRUE(e.where().line.has_value()) << e.what();
  }
}

TEST(SweepFile, MissingSweepFile) {
  TempDir dir;
  EXPECT_THROW(static_cast<void>(read_sweep_file(dir.path() / "none.toml")), InputError);
}

// ---- flexible supports (docs/sweeps.md) --------------------------------------------------------------------------

/// The value of a named column in a row of a run table.
const ensemble::Value& cell(const ensemble::ResultTable& t, std::size_t row, const std::string& column) {
  const auto it = std::find(t.columns.begin(), t.columns.end(), column);
  if (it == t.columns.end()) throw std::runtime_error("no column " + column);
  return t.rows[row][static_cast<std::size_t>(it - t.columns.begin())];
}

TEST(SweepFile, FlexibleSupportsExpandAndRunOnTheSupportsMotion) {
  TempDir dir;
  write_file(dir.path() / "sine.csv", plain_record(0.3, 400));  // 2.5 Hz, 0.3 g, 4 s at 0.01 s
  const SweepFile f = parse_in(dir, R"(
[motions]
files = "sine.csv"

[[object]]
model = "slide"
mu = 0.1
support_freq = ["2.5Hz", "200Hz"]
support_damping = 0.05

[[object]]
model = "slide"
mu = 0.1

[[object]]
model = "rock"
shape = "block"
width = "10cm"
height = "40cm"
support_freq_hz = 2
support_damping = [0.02, 0.05]
)");
  ASSERT_EQ(f.spec.objects.size(), 5u);  // 2 supports + 1 rigid + 2 supports
  const auto& s0 = std::get<SlideObject>(f.spec.objects[0]);
  ASSERT_TRUE(s0.support.has_value());
  EXPECT_EQ(s0.support->freq_hz, 2.5);
  EXPECT_EQ(s0.support->damping_ratio, 0.05);
  EXPECT_FALSE(std::get<SlideObject>(f.spec.objects[2]).support.has_value());
  EXPECT_EQ(std::get<RockObject>(f.spec.objects[4]).support->damping_ratio, 0.05);

  const ensemble::Plan plan = ensemble::make_plan(f.spec);
  const auto& oc = plan.object_columns;
  EXPECT_NE(std::find(oc.begin(), oc.end(), "support_freq_hz"), oc.end());
  EXPECT_NE(std::find(oc.begin(), oc.end(), "support_damping"), oc.end());
  const ensemble::ResultTable t = ensemble::run_in_memory(plan);
  ASSERT_EQ(t.rows.size(), 5u);
  // Against the library's solvers directly: the sine through a 2.5 Hz, 5 % support (resonant with it), then the
  // rigid sliding solver. Same operations in the same order: equal to the last bit.
  const GroundMotion& pulse = *f.spec.records[0].motion;
  const auto block = SlidingBlock::make(0.1, 0.1, 0.0, SlidingMode::two_way, kG);
  const double on_support =
      slide_summary(support_motion(pulse, SupportOscillator::make(2.5, 0.05)), block).max_abs_displacement_m;
  const double on_ground = slide_summary(pulse, block).max_abs_displacement_m;
  EXPECT_EQ(std::get<double>(cell(t, 0, "max_abs_displacement_m")), on_support);
  EXPECT_EQ(std::get<double>(cell(t, 2, "max_abs_displacement_m")), on_ground);
  EXPECT_GT(on_support, 2.0 * on_ground);  // resonance: the support amplifies the sine (transmissibility ~10)
  // A 200 Hz support follows the ground: transmissibility 1 + (2.5/200)^2 at the sine's frequency, 1.6e-4 relative,
  // and the sine is read piecewise linear in both; 2e-3 leaves room for the start-up transient (decays in 0.1 s).
  EXPECT_NEAR(std::get<double>(cell(t, 1, "max_abs_displacement_m")), on_ground, 2e-3 * on_ground);
  EXPECT_EQ(std::get<double>(cell(t, 0, "support_freq_hz")), 2.5);
  // Pulses are irregularly sampled (at their jumps): refused before any run.
  const SweepFile on_pulses = parse_in(dir, std::string(kPulseMotions) + "[[object]]\nmodel = \"slide\"\nmu = 0.1\n"
                                                                         "support_freq_hz = 3\nsupport_damping = 0.05\n");
  EXPECT_THROW(static_cast<void>(ensemble::make_plan(on_pulses.spec)), InputError);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(cell(t, 2, "support_freq_hz")));  // rigid: empty cell
}

TEST(SweepFile, WithoutSupportKeysTheColumnsAreTheOldOnes) {
  TempDir dir;
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) + "[[object]]\nmodel = \"slide\"\nmu = 0.1\n");
  const auto cols = ensemble::make_plan(f.spec).columns();
  EXPECT_EQ(std::find(cols.begin(), cols.end(), "support_freq_hz"), cols.end());
  EXPECT_EQ(std::find(cols.begin(), cols.end(), "support_damping"), cols.end());
}

TEST(SweepFile, FlexibleSupportErrorsNameTheKey) {
  TempDir dir;
  const auto field_of = [&](const std::string& keys) -> std::string {
    try {
      static_cast<void>(parse_in(dir, std::string(kPulseMotions) + "[[object]]\nmodel = \"slide\"\nmu = 0.1\n" + keys));
    } catch (const InputError& e) {
      return e.where().field;
    }
    ADD_FAILURE() << "accepted: " << keys;
    return {};
  };
  EXPECT_EQ(field_of("support_freq = \"4Hz\"\n"), "object[1].support_damping");  // no damping guessed
  EXPECT_EQ(field_of("support_damping = 0.05\n"), "object[1].support_freq_hz");
  EXPECT_EQ(field_of("support_freq_hz = -1\nsupport_damping = 0.05\n"), "object[1].support_freq_hz");
  EXPECT_EQ(field_of("support_freq = \"4Hz\"\nsupport_damping = 1.5\n"), "object[1].support_damping");
  EXPECT_EQ(field_of("support_freq = 4\nsupport_damping = 0.05\n"), "object[1].support_freq");  // no unit
}

// Asymmetric general bodies (b1, b2, h, inertia) expand as b1 x h x b2 x inertia x e x mu, each the factory's body
// on the converted numbers bit for bit; their columns are b1_m, b2_m, h_m, inertia_m2 and the per-side results.
TEST(SweepFile, AsymmetricGeneralBodiesExpandToTheFactorysBodies) {
  TempDir dir;
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) + R"([[object]]
model = "rock"
shape = "general"
b1 = ["4cm", "5cm"]
b2_m = 0.03
h = "20cm"
inertia = ["40cm2", "50cm2"]
e = ["housner", 0.8]
)");
  ASSERT_EQ(f.spec.objects.size(), 2u * 2u * 2u);
  std::size_t i = 0;
  for (const double b1 : {4 * 0.01, 5 * 0.01}) {
    for (const double k2 : {40 * 1e-4, 50 * 1e-4}) {
      for (const bool housner : {true, false}) {
        SCOPED_TRACE(i);
        const auto& ro = std::get<RockObject>(f.spec.objects.at(i++));
        const RockingBody expected = RockingBody::general_asymmetric(b1, 0.03, 20 * 0.01, k2);
        EXPECT_FALSE(ro.body.symmetric());
        EXPECT_EQ(ro.body.pivot_b_m(-1), expected.pivot_b_m(-1));
        EXPECT_EQ(ro.body.pivot_b_m(1), expected.pivot_b_m(1));
        EXPECT_EQ(ro.body.pivot_D_m2(-1), expected.pivot_D_m2(-1));
        EXPECT_EQ(ro.body.pivot_D_m2(1), expected.pivot_D_m2(1));
        EXPECT_EQ(ro.body.h_m, expected.h_m);
        EXPECT_EQ(ro.inertia_m2.value_or(-1.0), k2);
        EXPECT_EQ(ro.options.restitution, housner ? RestitutionMode::housner : RestitutionMode::given);
      }
    }
  }
  const auto cols = ensemble::make_plan(f.spec).columns();
  for (const char* c : {"b1_m", "b2_m", "h_m", "inertia_m2", "overturned_side", "exceeded_alpha_side",
                        "max_rotation_over_alpha_negative", "alpha_negative_rad"}) {
    EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  }
  for (const char* c : {"a_m", "D_m2", "mesh", "mesh_azimuth_deg"}) {
    EXPECT_EQ(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  }
}

// A body from a mesh: the wedge of test_body along +x (azimuth 90) has b1 = L/3, b2 = 2L/3, h = H/3 and
// I_cm / m = (L^2 + H^2) / 18 (1e-12 relative: the mass sums' rounding on float-exact coordinates); at 270 the pivots
// swap. The path is relative to the sweep file; azimuths expand as a list.
TEST(SweepFile, MeshBodiesAreTheMeshPipelinesBodies) {
  TempDir dir;
  constexpr double kL = 0.5, kH = 0.75, kW = 0.25;
  fs::create_directories(dir.path() / "scans");
  write_file(dir.path() / "scans" / "wedge.stl",
             test::stl_binary_bytes(test::xz_prism_mesh({{0, 0}, {kL, 0}, {0, kH}}, kW)));
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) + R"([[object]]
model = "rock"
mesh = "scans/wedge.stl"
mesh_azimuth_deg = [90, 270]
mesh_density_kg_m3 = 2000
)");
  ASSERT_EQ(f.spec.objects.size(), 2u);
  const double k2 = (kL * kL + kH * kH) / 18.0;
  const auto near = [](double x, double y) { EXPECT_NEAR(x, y, 1e-12 * std::abs(y)); };
  for (std::size_t i = 0; i < 2; ++i) {
    const auto& ro = std::get<RockObject>(f.spec.objects[i]);
    const double rear = i == 0 ? kL / 3 : 2 * kL / 3;
    const double front = i == 0 ? 2 * kL / 3 : kL / 3;
    near(ro.body.pivot_b_m(-1), rear);
    near(ro.body.pivot_b_m(1), front);
    near(ro.body.h_m, kH / 3);
    near(ro.inertia_m2.value_or(0.0), k2);
    near(ro.body.pivot_D_m2(-1), k2 + rear * rear + kH * kH / 9);
    EXPECT_EQ(ro.mesh, "scans/wedge.stl");
    EXPECT_EQ(ro.mesh_azimuth_deg.value_or(-1.0), i == 0 ? 90.0 : 270.0);
  }
  const auto plan = ensemble::make_plan(f.spec);
  const auto cols = plan.columns();
  for (const char* c : {"mesh", "mesh_azimuth_deg", "b1_m", "b2_m", "inertia_m2", "overturned_side"}) {
    EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  }
}

TEST(SweepFile, GeneralAndMeshErrorsNameFileLineKeyAndMesh) {
  TempDir dir;
  write_file(dir.path() / "open.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n");
  struct Case {
    std::string keys;  // after model = "rock" (line 9 of the file on)
    std::string field;
    std::size_t line;
    std::string problem_part;
  };
  const Case cases[] = {
      {"mesh = \"missing.obj\"\nmesh_azimuth_deg = 0\n", "object[1].mesh", 9, "missing.obj"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\n", "object[1].mesh", 9, "open.obj"},
      {"mesh = \"open.obj\"\n", "object[1].mesh_azimuth_deg", 0, "azimuth"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\nshape = \"cylinder\"\n", "object[1].shape", 11, "general"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\nh_m = 0.1\n", "object[1].h_m", 11, "does not apply"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\nmesh_unit = \"parsec\"\n", "object[1].mesh_unit", 11,
       "parsec"},
      {"mesh = \"open.obj\"\nmesh_azimuth_deg = 0\nmesh_density_kg_m3 = 0\n", "object[1].mesh_density_kg_m3", 11,
       "density"},
      {"shape = \"block\"\nwidth_m = 0.1\nheight_m = 0.3\nmesh_azimuth_deg = 3\n", "object[1].mesh_azimuth_deg",
       12, "does not apply"},
      {"shape = \"general\"\nb1_m = 0.03\nh_m = 0.2\ninertia_m2 = 0.004\n", "object[1].b2", 0, "needs b2"},
      {"shape = \"general\"\nb1_m = 0.03\nb2_m = 0.03\nh_m = 0.2\n", "object[1].inertia_m2", 0, "inertia"},
      {"shape = \"general\"\nb1_m = 0.03\nb2_m = -0.03\nh_m = 0.2\ninertia_m2 = 0.004\n", "object[1].b2_m", 11,
       "b2"},
      {"shape = \"general\"\nb1 = 0.03\nb2_m = 0.03\nh_m = 0.2\ninertia_m2 = 0.004\n", "object[1].b1", 10,
       "no unit"},
      {"shape = \"general\"\nb1_m = 0.03\nb2_m = 0.03\nh_m = 0.2\ninertia = \"0.004\"\n", "object[1].inertia", 13,
       "unit"},
      {"shape = \"general\"\nb1_m = 0.03\nb2_m = 0.03\na_m = 0.03\nh_m = 0.2\ninertia_m2 = 0.004\n",
       "object[1].a_m", 12, "does not apply"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.keys);
    expect_refused(dir.path() / "bad.toml", std::string(kPulseMotions) + "[[object]]\nmodel = \"rock\"\n" + c.keys,
                   c.field, c.line, c.problem_part);
  }
}

// model = "3d": a box (a block with its depth) is RigidBody3D::box of its width, depth and height, a mesh its posed
// three-dimensional body (here the same box scanned standing, as-scanned: the same static limits in every direction
// and the same height of the centre of mass); a model = "3d" object runs under [[motions.set]] only (make_plan names
// its model under a pulse).
TEST(SweepFile, ThreeDimensionalObjectsAreBoxesAndMeshesAsPosed) {
  TempDir dir;
  write_file(dir.path() / "box.stl", test::stl_binary_bytes(test::box_mesh(0.2, 0.3, 0.8)));
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) + R"([[object]]
model = "3d"
shape = "block"
width = "20cm"
depth_m = [0.3, 0.4]
height_m = 0.8
e = 0.9
[[object]]
model = "3d"
mesh = "box.stl"
mesh_pose = "as-scanned"
)");
  ASSERT_EQ(f.spec.objects.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) {
    SCOPED_TRACE(i);
    const auto& ro = std::get<RockObject>(f.spec.objects[i]);
    ASSERT_TRUE(ro.body_3d.has_value());
    EXPECT_FALSE(ro.mu_kinetic.has_value());
    const RigidBody3D expected = RigidBody3D::box(0.2, i == 1 ? 0.4 : 0.3, 0.8);
    const double tol = i == 2 ? 1e-7 : 1e-12;  // a binary STL holds single-precision coordinates (0.8 -> 0.8 + 1.2e-8)
    EXPECT_NEAR(ro.body_3d->height_m(), 0.4, tol);
    for (const double az : {0.0, 30.0, 90.0, 135.0, 200.0}) {
      EXPECT_NEAR(ro.body_3d->static_tilt_limit_rad(az), expected.static_tilt_limit_rad(az), tol) << az;
    }
    if (i < 2) {
      EXPECT_EQ(ro.depth_m.value_or(0.0), i == 0 ? 0.3 : 0.4);
      EXPECT_EQ(ro.options.restitution, RestitutionMode::given);
      EXPECT_EQ(ro.options.e, 0.9);
    } else {
      EXPECT_EQ(ro.mesh, "box.stl");
      EXPECT_FALSE(ro.mesh_azimuth_deg.has_value());
    }
  }
  try {
    (void)ensemble::make_plan(f.spec);
    ADD_FAILURE() << "a 3-D object under a pulse was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "object[1].model");
  }
}

// model = "3d" for a cylinder: the rim engine's solid cylinder (rigid3d_disc.hpp) of the diameter and height; a box
// and a cylinder take mu and mu_kinetic (Rigid3DOptions::mu_s, mu_k), each value a case; without them no friction
// (the no-slip engines, as before).
TEST(SweepFile, ThreeDimensionalCylindersAndFriction) {
  TempDir dir;
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) + R"([[object]]
model = "3d"
shape = "cylinder"
diameter = "30cm"
height_m = 1.0
mu = 0.5
[[object]]
model = "3d"
shape = "block"
width_m = 0.2
depth_m = 0.3
height_m = 0.8
mu = [0.3, 0.6]
mu_kinetic = 0.25
[[object]]
model = "3d"
shape = "block"
width_m = 0.2
depth_m = 0.3
height_m = 0.8
)");
  ASSERT_EQ(f.spec.objects.size(), 4U);
  const auto& cyl = std::get<RockObject>(f.spec.objects[0]);
  ASSERT_TRUE(cyl.cylinder_3d.has_value());
  EXPECT_FALSE(cyl.body_3d.has_value());
  EXPECT_EQ(cyl.options.mu.value_or(-1.0), 0.5);
  EXPECT_TRUE(cyl.three_d());
  const CylinderBody3D expected = CylinderBody3D::solid(0.3, 1.0);
  EXPECT_NEAR(cyl.cylinder_3d->radius_m, 0.15, 1e-15);
  EXPECT_NEAR(cyl.cylinder_3d->centre_height_m, 0.5, 1e-15);
  EXPECT_NEAR(cyl.cylinder_3d->inertia_axial_m2, expected.inertia_axial_m2, 1e-15);
  EXPECT_NEAR(cyl.cylinder_3d->inertia_transverse_m2, expected.inertia_transverse_m2, 1e-15);
  for (std::size_t i = 1; i < 3; ++i) {
    const auto& ro = std::get<RockObject>(f.spec.objects[i]);
    ASSERT_TRUE(ro.body_3d.has_value());
    EXPECT_EQ(ro.options.mu.value_or(-1.0), i == 1 ? 0.3 : 0.6);
    EXPECT_EQ(ro.mu_kinetic.value_or(-1.0), 0.25);
  }
  const auto& dry = std::get<RockObject>(f.spec.objects[3]);
  EXPECT_FALSE(dry.options.mu.has_value());
  EXPECT_FALSE(dry.mu_kinetic.has_value());
}

TEST(SweepFile, ThreeDimensionalRefusalsNameFileLineAndKey) {
  TempDir dir;
  write_file(dir.path() / "box.stl", test::stl_binary_bytes(test::box_mesh(0.2, 0.3, 0.8)));
  struct Case {
    std::string keys;  // after model = "3d" (line 9 of the file on)
    std::string field;
    std::size_t line;
    std::string problem_part;
  };
  const std::string box = "shape = \"block\"\nwidth_m = 0.2\ndepth_m = 0.3\nheight_m = 0.8\n";  // lines 9-12
  const Case cases[] = {
      {"shape = \"cylinder\"\ndiameter_m = 0.1\nheight_m = 0.3\nmu = 0.5\nmu_kinetic = 0.6\n", "object[1].mu_kinetic", 13,
       "[0, mu = 0.5]"},
      {"shape = \"general\"\na_m = 0.03\nh_m = 0.2\nD_m2 = 0.05\n", "object[1].shape", 9, "general body"},
      {"shape = \"block\"\nwidth_m = 0.1\nheight_m = 0.3\n", "object[1].depth", 7, "depth"},
      {box + "mu_kinetic = 0.3\n", "object[1].mu_kinetic", 13, "needs the static one"},
      {box + "mu = 0.3\nmu_kinetic = [0.2, 0.4]\n", "object[1].mu_kinetic", 14, "[0, mu = 0.3]"},
      {box + "support_freq_hz = 5\n", "object[1].support_freq_hz", 13, "support"},
      {"mesh = \"box.stl\"\nmesh_azimuth_deg = 0\n", "object[1].mesh_azimuth_deg", 10, "bearing_deg"},
      {"shape = \"block\"\nwidth_m = 0.2\ndepth_m = -0.3\nheight_m = 0.8\n", "object[1].depth", 11, "-0.3"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.keys);
    expect_refused(dir.path() / "bad.toml", std::string(kPulseMotions) + "[[object]]\nmodel = \"3d\"\n" + c.keys,
                   c.field, c.line, c.problem_part);
  }
  expect_refused(dir.path() / "bad.toml", std::string(kPulseMotions) + "[[object]]\nmodel = \"4d\"\n" + box,
                 "object[1].model", 8, "3d");
}

// Without an asymmetric body a sweep has the columns it always had: no per-side results, no b1/b2/inertia/mesh.
TEST(SweepFile, SymmetricGeneralBodiesKeepTheOldColumns) {
  TempDir dir;
  const SweepFile f = parse_in(dir, std::string(kPulseMotions) +
                                        "[[object]]\nmodel = \"rock\"\nshape = \"general\"\na_m = 0.03\nh_m = 0.2\n"
                                        "D_m2 = 0.06\n");
  const auto cols = ensemble::make_plan(f.spec).columns();
  for (const char* c : {"b1_m", "b2_m", "inertia_m2", "mesh", "mesh_azimuth_deg", "overturned_side",
                        "alpha_negative_rad"}) {
    EXPECT_EQ(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  }
  for (const char* c : {"a_m", "h_m", "D_m2"}) EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
}

}  // namespace
}  // namespace topple::io
