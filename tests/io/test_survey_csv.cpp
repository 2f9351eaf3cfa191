// CSV surveys (docs/survey.md, "CSV surveys"): the same survey as the TOML reader gives, the same answer from the
// inversion, and errors that name the file, the line and the column.
#include <filesystem>
#include <ostream>
#include <string>

#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/io/survey_file.hpp"

namespace topple {
namespace {

const std::filesystem::path kExamples = std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples";

// Every field the reader fills, compared exactly: both files state the same decimal numbers with the same units, so
// the conversions are the same operations on the same doubles (no tolerance is needed or wanted).
void expect_same_survey(const Survey& a, const Survey& b) {
  ASSERT_EQ(a.sites.size(), b.sites.size());
  for (std::size_t s = 0; s < a.sites.size(); ++s) {
    const Site& x = a.sites[s];
    const Site& y = b.sites[s];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.lat_deg, y.lat_deg);
    EXPECT_EQ(x.lon_deg, y.lon_deg);
    EXPECT_EQ(x.notes, y.notes);
    ASSERT_EQ(x.objects.size(), y.objects.size());
    for (std::size_t i = 0; i < x.objects.size(); ++i) {
      const ObservedObject& p = x.objects[i];
      const ObservedObject& q = y.objects[i];
      SCOPED_TRACE(p.id);
      EXPECT_EQ(p.id, q.id);
      EXPECT_EQ(p.description, q.description);
      EXPECT_EQ(p.body.shape, q.body.shape);
      EXPECT_EQ(p.body.a_m, q.body.a_m);
      EXPECT_EQ(p.body.h_m, q.body.h_m);
      EXPECT_EQ(p.body.D_m2, q.body.D_m2);
      EXPECT_EQ(p.width_m, q.width_m);
      EXPECT_EQ(p.height_m, q.height_m);
      EXPECT_EQ(p.diameter_m, q.diameter_m);
      EXPECT_EQ(p.mu.low, q.mu.low);
      EXPECT_EQ(p.mu.high, q.mu.high);
      EXPECT_EQ(p.e_housner, q.e_housner);
      EXPECT_EQ(p.support, q.support);
      EXPECT_EQ(p.amplification.low, q.amplification.low);
      EXPECT_EQ(p.amplification.high, q.amplification.high);
      EXPECT_EQ(p.outcome, q.outcome);
      EXPECT_EQ(p.slid_m, q.slid_m);
      EXPECT_EQ(p.slid_uncertainty_m, q.slid_uncertainty_m);
      EXPECT_EQ(p.slid_at_least_m, q.slid_at_least_m);
      EXPECT_EQ(p.evidence, q.evidence);
    }
  }
  EXPECT_EQ(a.inversion.pga_min_g, b.inversion.pga_min_g);
  EXPECT_EQ(a.inversion.pga_max_g, b.inversion.pga_max_g);
  EXPECT_EQ(a.inversion.pga_count, b.inversion.pga_count);
  EXPECT_EQ(a.inversion.freq_min_hz, b.inversion.freq_min_hz);
  EXPECT_EQ(a.inversion.freq_max_hz, b.inversion.freq_max_hz);
  EXPECT_EQ(a.inversion.freq_count, b.inversion.freq_count);
  EXPECT_EQ(a.inversion.motions_per_cell, b.inversion.motions_per_cell);
  EXPECT_EQ(a.inversion.seed, b.inversion.seed);
  EXPECT_EQ(a.notes.size(), b.notes.size());
}

std::string inversion_text(const Survey& survey) {
  // A coarse grid over the file's axes (5 x 3 cells, 4 motions): the comparison is of the two readers, not of the
  // inversion's accuracy.
  InversionSettings st = survey.inversion;
  st.pga_count = 5;
  st.freq_count = 3;
  st.motions_per_cell = 4;
  nlohmann::ordered_json j = io::inversion_json(invert_site(survey.sites[0], st, InversionOptions{.threads = 1}),
                                                survey.sites[0]);
  j.erase("seconds");  // wall-clock time: the one field that may differ between two runs
  return j.dump(2);
}

TEST(SurveyCsv, ExampleIsTheTomlExampleAndGivesTheSameInversion) {
  const Survey toml = io::read_survey(kExamples / "survey.toml");
  const Survey csv = io::read_survey(kExamples / "survey.csv");
  expect_same_survey(toml, csv);
  // The inversion of both: byte-identical JSON (same doubles in, same deterministic computation).
  EXPECT_EQ(inversion_text(toml), inversion_text(csv));
}

std::string toml_object(const std::string& keys) { return "[[object]]\n" + keys; }

// Units in the header (width_cm, D_cm2) or in the cells ("0.3 m"), ranges, Housner's e and the outcome aliases give
// the same objects as the TOML file.
TEST(SurveyCsv, HeaderUnitsCellUnitsAndAliasesMatchToml) {
  const Survey csv = io::parse_survey(
      "site.name,Kitchen\n"
      "id,shape,width_mm,height,a,h,D_cm2,mu,e,amplification,outcome,slid_uncertainty_cm,slid\n"
      "jar,block,80,0.3 m,,,,\"[0.4, 0.6]\",housner,,toppled,,\n"
      "pan,general,,,5cm,10cm,166.7,0.3,0.5,\"[1.0, 1.5]\",fell,,\n"
      "mug,block,60,9cm,,,,0.4,,,slid,1.5,6cm\n",
      "kitchen.csv");
  const Survey toml = io::parse_survey(
      "[site]\nname = \"Kitchen\"\n" +
          toml_object("id = \"jar\"\nshape = \"block\"\nwidth = \"80mm\"\nheight = \"0.3 m\"\nmu = [0.4, 0.6]\n"
                      "e = \"housner\"\noutcome = \"overturned\"\n") +
          toml_object("id = \"pan\"\nshape = \"general\"\na = \"5cm\"\nh = \"10cm\"\nD = \"166.7cm2\"\nmu = 0.3\n"
                      "e = 0.5\namplification = [1.0, 1.5]\noutcome = \"overturned\"\n") +
          toml_object("id = \"mug\"\nshape = \"block\"\nwidth = \"60mm\"\nheight = \"9cm\"\nmu = 0.4\n"
                      "outcome = \"slid\"\nslid_uncertainty = \"1.5cm\"\nslid = \"6cm\"\n"),
      "kitchen.toml");
  expect_same_survey(toml, csv);
  EXPECT_EQ(csv.sites[0].objects[0].outcome, Outcome::overturned);  // "toppled"
  EXPECT_EQ(csv.sites[0].objects[1].outcome, Outcome::overturned);  // "fell"
  EXPECT_DOUBLE_EQ(csv.sites[0].objects[0].width_m.value(), 0.08);
  EXPECT_DOUBLE_EQ(csv.sites[0].objects[1].body.D_m2, 166.7e-4);
  EXPECT_FALSE(csv.sites[0].objects[1].e_housner);
}

// A flexible support is its TOML inline table in the support cell (site default: a site.support setting row).
TEST(SurveyCsv, FlexibleSupportCell) {
  const Survey s = io::parse_survey("site.support,\"{freq_hz = [3, 6], damping = 0.05}\"\n"
                                    "id,width_cm,height_cm,mu,outcome,support\n"
                                    "a,10,40,0.5,toppled,\"{freq_hz = 4, damping = 0.02, name = \"\"shelf\"\"}\"\n"
                                    "b,10,40,0.5,toppled,\n"
                                    "c,10,40,0.5,toppled,upper floor\n",
                                    "flex.csv");
  const auto& o = s.sites[0].objects;
  ASSERT_EQ(o.size(), 3u);
  ASSERT_TRUE(o[0].support_filter.has_value());
  EXPECT_EQ(o[0].support_filter->freq_hz.low, 4.0);
  EXPECT_EQ(o[0].support_filter->damping.low, 0.02);
  ASSERT_TRUE(o[1].support_filter.has_value());  // the site's default
  EXPECT_EQ(o[1].support_filter->freq_hz.high, 6.0);
  EXPECT_EQ(o[2].support, "upper floor");  // free text
}

// The aliases are the TOML reader's own (the CSV only passes the word on).
TEST(SurveyCsv, TomlReaderTakesToppledAndFell) {
  for (const char* word : {"toppled", "fell", "overturned"}) {
    const Survey s = io::parse_survey(std::string("[[object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\n"
                                                  "mu = 0.5\noutcome = \"") + word + "\"\n", "s.toml");
    EXPECT_EQ(s.sites[0].objects[0].outcome, Outcome::overturned) << word;
  }
}

// Spreadsheet habits: CRLF line ends, a byte-order mark, ';' as separator, quoted cells with the separator, a doubled
// quote and a line break, rows of empty cells, missing trailing cells, comments.
TEST(SurveyCsv, SpreadsheetExportsRead) {
  const Survey s = io::parse_survey(
      "\xEF\xBB\xBF# exported\r\n"
      "site.notes;\"two lines;\r\nand a \"\"quote\"\"\"\r\n"
      ";;;;\r\n"
      "id;width_cm;height_cm;mu;outcome;description\r\n"
      "b1;10;40;0.5;not_overturned\r\n",
      "field.csv");
  ASSERT_EQ(s.sites[0].objects.size(), 1u);
  EXPECT_EQ(s.sites[0].notes, "two lines;\nand a \"quote\"");
  EXPECT_DOUBLE_EQ(s.sites[0].objects[0].body.a_m, 0.05);
  EXPECT_EQ(s.sites[0].name, "site 1");  // the TOML reader's documented default
}

// By content when the name says nothing: a CSV with no extension is read as CSV, a TOML file as TOML.
TEST(SurveyCsv, DetectedByExtensionOrContent) {
  const std::string csv = "id,width,height,mu,outcome\nb,10cm,40cm,0.5,overturned\n";
  EXPECT_EQ(io::parse_survey(csv, "survey").sites[0].objects[0].id, "b");
  EXPECT_EQ(io::parse_survey(csv, "SURVEY.CSV").sites[0].objects[0].id, "b");
  EXPECT_EQ(io::parse_survey("# c, d\n[[object]]\nid = \"t\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                             "outcome = \"overturned\"\n", "survey").sites[0].objects[0].id, "t");
  // A .toml name is never read as CSV: the TOML parser's error, not a CSV one.
  EXPECT_THROW((void)io::parse_survey(csv, "s.toml"), InputError);
}

void expect_csv_error(const std::string& text, std::size_t line, const std::string& field, const std::string& says) {
  try {
    (void)io::parse_survey(text, "field.csv");
    FAIL() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "field.csv") << e.what();
    ASSERT_TRUE(e.where().line.has_value()) << e.what();
    EXPECT_EQ(*e.where().line, line) << e.what();
    EXPECT_EQ(e.where().field, field) << e.what();
    EXPECT_NE(std::string(e.what()).find(says), std::string::npos) << e.what();
  }
}

// A bad cell is named by file, line, the object and key, and the spreadsheet column (letter and header).
TEST(SurveyCsv, BadCellsNameFileLineAndColumn) {
  const std::string head = "# a survey\nid,width_cm,height,mu,outcome,e\n";
  expect_csv_error(head + "a,10,40cm,0.5,overturned,\nb,10,40,0.5,overturned,\n", 4,
                   "object[2](b).height in column C ('height')", "has no unit");
  expect_csv_error(head + "a,10 cm,40cm,0.5,overturned,\n", 3, "column B ('width_cm')", "write a bare number");
  expect_csv_error(head + "a,10,40cm,high,overturned,\n", 3, "object[1](a).mu in column D ('mu')",
                   "expected a number");
  expect_csv_error(head + "a,10,40cm,\"[0.6, 0.4]\",overturned,\n", 3, "object[1](a).mu in column D ('mu')",
                   "low > high");
  expect_csv_error(head + "a,10,40cm,0.5,upside down,\n", 3, "object[1](a).outcome in column E ('outcome')",
                   "unknown outcome");
  expect_csv_error(head + "a,10,40cm,0.5,overturned,1.5\n", 3, "object[1](a).e in column F ('e')", "[0, 1]");
  // A squat block with Housner's e: the message says what to do.
  expect_csv_error(head + "a,60,30cm,0.5,overturned,\n", 3, "object[1](a).e", "e = 0");
  // Whole-row problems: the row's line.
  expect_csv_error(head + "a,10,40cm,0.5,,\n", 3, "object[1](a).outcome", "observed outcome");
  expect_csv_error(head + "a,10,40cm,0.5,overturned,,extra\n", 3, "column G", "column without a header");
  expect_csv_error(head + "a,10,40cm,0.5,overturned,\na,10,40cm,0.5,overturned,\n", 4, "object[2].id", "duplicate");
  // Structure: unknown key, a key given twice, no id column, an unclosed quote, a bad setting.
  expect_csv_error("id,width,height,mu,outcome,colour\na,1cm,4cm,0.5,slid,red\n", 2,
                   "object[1](a).colour in column F ('colour')", "unknown key");
  expect_csv_error("id,width,width_cm\n", 1, "column C ('width_cm')", "given twice");
  expect_csv_error("name,width\nb,1cm\n", 1, "id", "no id column");
  expect_csv_error("id,description\nb,\"open\n", 2, "column B", "never closed");
  expect_csv_error("sight.name,x\nid\n", 1, "column A", "unknown setting");
  expect_csv_error("inversion.pga_g,\"[2, 1, 30]\"\nid,width,height,mu,outcome\nb,1cm,4cm,0.5,slid\n", 1,
                   "inversion.pga_g in column B ('inversion.pga_g')", "0 < min < max");
}

// Issue 31, CSV surveys: each case refused at its line, naming the column as typed (or read as the format allows).
struct CsvRefusal {
  const char* name;
  std::string text;
  std::size_t line;
  std::string field;
  std::string says;
};

void PrintTo(const CsvRefusal& c, std::ostream* os) { *os << c.name; }

class SurveyCsvRefusals : public ::testing::TestWithParam<CsvRefusal> {};

TEST_P(SurveyCsvRefusals, NameLineAndColumnAsTyped) {
  const CsvRefusal& c = GetParam();
  expect_csv_error(c.text, c.line, c.field, c.says);
}

const std::string kRow = "b,10,40,0.5,overturned\n";

INSTANTIATE_TEST_SUITE_P(
    Issue31, SurveyCsvRefusals,
    ::testing::Values(
        // A header with a unit suffix that is no unit of its key: the column, not "a block needs its height".
        CsvRefusal{"furlong", "id,width_cm,height_furlong,mu,outcome\n" + kRow, 1, "column C ('height_furlong')",
                   "'furlong' is not a length unit"},
        CsvRefusal{"area_unit_on_a_length", "id,width_cm,height_cm2,mu,outcome\n" + kRow, 1,
                   "column C ('height_cm2')", "'cm2' is not a length unit"},
        CsvRefusal{"upper_case_unit", "id,width_cm,height_CM,mu,outcome\n" + kRow, 1, "column C ('height_CM')",
                   "in lower case"},
        CsvRefusal{"unit_on_a_number", "id,width_cm,height_cm,mu_cm,outcome\n" + kRow, 1, "column D ('mu_cm')",
                   "mu takes no unit"},
        CsvRefusal{"g_on_a_length", "id,width_cm,height_g,mu,outcome\n" + kRow, 1, "column C ('height_g')",
                   "'g' is not a length unit"},
        CsvRefusal{"area_key", "id,shape,a,h,D_furlong2,mu,outcome\nb,general,5cm,20cm,3,0.5,overturned\n", 1,
                   "column E ('D_furlong2')", "not an area unit"},
        // A setting row after the header row (it used to be read as an object: "unknown shape '17.4'").
        CsvRefusal{"setting_after_header",
                   "id,shape,width,height,mu,outcome\nb,block,10cm,40cm,0.5,overturned\nsite.lat,17.4\n", 3,
                   "column A", "go before the header row"},
        // An unclosed flexible support table is refused, never taken as a free-text support.
        CsvRefusal{"support_without_brace",
                   "id,width,height,mu,outcome,support\nb,10cm,40cm,0.5,overturned,\"{freq_hz = 3, damping = 0.05\"\n",
                   2, "column F ('support')", "closing '}' missing"},
        CsvRefusal{"site_support_without_brace",
                   "site.support,\"{freq_hz = 3, damping = 0.05\"\nid,width,height,mu,outcome\nb,10cm,40cm,0.5,overturned\n",
                   1, "column B", "closing '}' missing"},
        // Lines ended by CR alone (old Mac) are lines: the error is at the third, not "text after the closing quote".
        CsvRefusal{"cr_only_line_ends",
                   "id,description,width,height,mu,outcome\rb,\"a, b\",10cm,40cm,0.5,overturned\r"
                   "c,x,10cm,40cm,high,overturned\r",
                   3, "object[2](c).mu in column E ('mu')", "expected a number"}),
    [](const ::testing::TestParamInfo<CsvRefusal>& p) { return std::string(p.param.name); });

// CR-only line ends are read as line ends: the same survey as with LF.
TEST(SurveyCsv, CrOnlyLineEndsAreLineEnds) {
  const std::string lf = "site.name,\"x, y\"\nid,description,width,height,mu,outcome\nb,\"a, b\",10cm,40cm,0.5,overturned\n";
  std::string cr = lf;
  for (char& c : cr) c = c == '\n' ? '\r' : c;
  expect_same_survey(io::parse_survey(cr, "mac.csv"), io::parse_survey(lf, "unix.csv"));
  EXPECT_EQ(io::parse_survey(cr, "mac.csv").sites[0].objects[0].height_m, 0.4);
}

// A NUL byte is refused at its line and column, and the message is whole (a raw NUL would end it where it is printed
// as a C string): the byte is quoted as \0.
TEST(SurveyCsv, NulByteIsQuotedAndDoesNotCutTheMessage) {
  const std::string text = std::string("id,width,height,mu,outcome\nb\0x,10cm,40cm,0.5,overturned\n", 56);
  ASSERT_EQ(text.size(), 56u);
  expect_csv_error(text, 2, "column A", "(\\0)");
  try {
    (void)io::parse_survey(text, "field.csv");
  } catch (const InputError& e) {
    const std::string what = e.what();  // up to the first NUL, as a C string
    EXPECT_NE(what.find("a CSV survey is text"), std::string::npos) << what;
  }
}

// Headers that are keys of their own, with an underscore, stay keys (not a key and a unit).
TEST(SurveyCsv, UnderscoredKeysAreNotUnits) {
  const Survey s = io::parse_survey("id,width,height,mu,outcome,slid,slid_uncertainty\n"
                                    "b,10cm,40cm,0.5,slid,4cm,\nc,10cm,40cm,0.5,slid,4cm,1cm\n",
                                    "k.csv");
  EXPECT_EQ(s.sites[0].objects.size(), 2u);
}

// The sliding-uncertainty note (a documented floor that raises a given value) names the CSV line.
TEST(SurveyCsv, NotesNameTheCsvLine) {
  const Survey s = io::parse_survey("# pot\nid,shape,diameter,height,mu,outcome,slid,slid_uncertainty_mm\n"
                                    "pot,cylinder,25cm,15cm,0.25,slid,4cm,3\n",
                                    "k.csv");
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_EQ(s.notes[0].rfind("k.csv:3: object[1](pot).slid_uncertainty", 0), 0u) << s.notes[0];
}

}  // namespace
}  // namespace topple
