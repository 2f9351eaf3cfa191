// The survey's key table (survey/schema.hpp), from which `topple survey-form` builds its page, held against the
// reader (io/survey_file.cpp, io/survey_csv.cpp) so that the two cannot drift: every key of the table parses; every
// value its range refuses the reader refuses with the table's words, and the boundary values it accepts the reader
// accepts; every condition, required key and choice is the reader's; every key the reader reads is in the table; and
// the friction table is docs/survey.md's.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>

#include <gtest/gtest.h>
#include <fmt/format.h>

#include "support/meshes.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/survey/schema.hpp"

namespace topple {
namespace {

const std::filesystem::path kSource = std::filesystem::path(TOPPLE_SOURCE_DIR);

/// A survey written from key = value lines per table ("object" for the one object, "support" for its flexible
/// support's inline table), with what every table needs filled in: an object's dimensions for its shape, a mesh's
/// azimuth, an outcome and mu.
struct SurveyText {
  std::map<std::string, std::map<std::string, std::string>> tables;

  void set(const std::string& table, const std::string& key, const std::string& value) { tables[table][key] = value; }
  void unset(const std::string& table, const std::string& key) { tables[table].erase(key); }
  [[nodiscard]] std::string text() const {
    std::string out;
    for (const char* t : {"inversion", "event", "site"}) {
      if (!tables.contains(t)) continue;
      out += fmt::format("[{}]\n", t);
      for (const auto& [k, v] : tables.at(t)) out += fmt::format("{} = {}\n", k, v);
    }
    out += "[[object]]\n";
    if (tables.contains("object")) {
      for (const auto& [k, v] : tables.at("object")) out += fmt::format("{} = {}\n", k, v);
    }
    if (tables.contains("support")) {
      std::string inline_table;
      for (const auto& [k, v] : tables.at("support")) inline_table += (inline_table.empty() ? "" : ", ") + k + " = " + v;
      out += "support = {" + inline_table + "}\n";
    }
    if (tables.contains("population")) {
      out += "[[population]]\n";
      for (const auto& [k, v] : tables.at("population")) out += fmt::format("{} = {}\n", k, v);
    }
    return out;
  }
};

/// A TOML value of a choice as written: a number bare, a word quoted.
std::string toml_choice(const std::string& v) {
  return !v.empty() && std::all_of(v.begin(), v.end(), [](char c) { return c >= '0' && c <= '9'; }) ? v : "\"" + v + "\"";
}

/// Sets the key that a condition names (as "table.key" or a key of `table`) to `value` (as TOML).
void set_condition_key(SurveyText& s, const std::string& table, const std::string& key, const std::string& value) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) s.set(table == "support" ? "object" : table, key, value);
  else s.set(key.substr(0, dot), key.substr(dot + 1), value);
}
void unset_condition_key(SurveyText& s, const std::string& table, const std::string& key) {
  const auto dot = key.find('.');
  if (dot == std::string::npos) s.unset(table == "support" ? "object" : table, key);
  else s.unset(key.substr(0, dot), key.substr(dot + 1));
}
/// The schema entry a condition names.
const SurveyKey& condition_key(const std::string& table, const std::string& key) {
  const auto dot = key.find('.');
  const SurveyKey* k = dot == std::string::npos ? find_survey_key(table, key)
                                                : find_survey_key(key.substr(0, dot), key.substr(dot + 1));
  if (k == nullptr) throw std::runtime_error("a condition names an unknown key: " + key);
  return *k;
}

/// The object's dimensions for its shape (and what a mesh or a support needs), unless the key itself is one.
void complete(SurveyText& s) {
  auto& o = s.tables["object"];
  const auto put = [&](const char* k, const char* v) {
    if (!o.contains(k)) o[k] = v;
  };
  put("id", "\"o1\"");
  put("mu", "0.5");
  put("outcome", "\"not_overturned\"");
  if (o.contains("mesh")) {
    put("mesh_azimuth_deg", "0");
  } else {
    std::string shape = o.contains("shape") ? o["shape"] : "\"block\"";
    if (shape == "\"general\"" && (o.contains("b1") || o.contains("b2") || o.contains("inertia"))) {
      put("b1", "\"10cm\"");
      put("b2", "\"12cm\"");
      put("h", "\"30cm\"");
      put("inertia", "\"0.02m2\"");
    } else if (shape == "\"general\"") {
      put("a", "\"5cm\"");
      put("h", "\"20cm\"");
      put("D", "\"0.06m2\"");  // >= a^2 + h^2 = 0.0425 m2 (a real body)
    } else if (shape == "\"cylinder\"") {
      put("diameter", "\"10cm\"");
      put("height", "\"40cm\"");
    } else {
      put("width", "\"10cm\"");
      put("height", "\"40cm\"");
    }
  }
  if (s.tables.contains("population")) {
    auto& p = s.tables["population"];
    const auto pput = [&](const char* k, const char* v) {
      if (!p.contains(k)) p[k] = v;
    };
    pput("id", "\"p1\"");
    pput("count", "10");
    pput("overturned", "1");  // one: as many as count's lowest value, 1, and a fall direction (the examples)
    pput("mu", "0.5");
    // Fall directions need a cylinder or a box: a cylinder unless a depth makes the block a box.
    if (p.contains("fallen_azimuths_deg") && !p.contains("depth")) pput("shape", "\"cylinder\"");
    if (!p.contains("sample")) {
      if (p.contains("shape") && p["shape"] == "\"cylinder\"") pput("diameter", "\"10cm\"");
      else pput("width", "\"10cm\"");
      pput("height", "\"40cm\"");
    }
  }
  if (s.tables.contains("support")) {
    auto& t = s.tables["support"];
    if (!t.contains("freq_hz")) t["freq_hz"] = "[3, 6]";
    if (!t.contains("damping")) t["damping"] = "0.05";
  }
}

/// A survey with `k` set to `value` and every condition of `k` held (its first value; a key that must be present set
/// to its example), except the condition `broken` (if given), which is made to fail.
SurveyText survey_with(const SurveyKey& k, const std::string& value, const SurveyKeyCondition* broken = nullptr) {
  SurveyText s;
  // An object's dimension of another shape than a block: that shape.
  if (!k.required_for_shapes.empty()) {
    const std::string& shape = k.required_for_shapes.front();
    s.set("object", "shape", shape == "general asymmetric" ? "\"general\"" : toml_choice(shape));
    if (shape == "general asymmetric") s.set("object", "b1", "\"10cm\"");
  }
  if (k.table == "support") s.set("support", "freq_hz", "[3, 6]");
  for (const SurveyKeyCondition& c : k.conditions) {
    const bool absent = std::find(c.values.begin(), c.values.end(), "<absent>") != c.values.end();
    if (&c == broken) {
      if (c.values.empty()) unset_condition_key(s, k.table, c.key);
      else if (absent) set_condition_key(s, k.table, c.key, condition_key(k.table, c.key).example);
      else {
        const SurveyKey& other = condition_key(k.table, c.key);
        const auto it = std::find_if(other.choices.begin(), other.choices.end(), [&](const std::string& v) {
          return std::find(c.values.begin(), c.values.end(), v) == c.values.end();
        });
        if (it == other.choices.end()) throw std::runtime_error("no value breaks the condition on " + c.key);
        set_condition_key(s, k.table, c.key, toml_choice(*it));
      }
      continue;
    }
    if (c.values.empty()) set_condition_key(s, k.table, c.key, condition_key(k.table, c.key).example);
    else if (!absent) set_condition_key(s, k.table, c.key, toml_choice(c.values.front()));
  }
  // A key that goes with model = "3d" (friction_3d): a valid three-dimensional object, three components and a box.
  const auto object = s.tables.find("object");
  if (object != s.tables.end() && object->second.contains("model") && object->second.at("model") == "\"3d\"") {
    s.set("inversion", "components", "3");
    s.set("object", "depth", "\"30cm\"");
  }
  s.set(k.table, k.key, value);
  complete(s);
  return s;
}

class SchemaAgainstReader : public ::testing::Test {
 protected:
  void SetUp() override {
    // The files that keys name: a mesh (a 20 x 30 x 50 box: a body in m, cm or mm), a record, a station's record.
    test::write_file(tmp_.path() / "scan.obj", test::obj_text(test::box_mesh(20.0, 30.0, 50.0)));
    test::write_file(tmp_.path() / "r.csv", "0,0\n0.01,0.1\n");
    test::write_file(tmp_.path() / "station.csv", "0,0\n0.01,0.1\n");
  }
  [[nodiscard]] Survey parse(const SurveyText& s) const { return io::parse_survey(s.text(), "s.toml", tmp_.path()); }
  /// The reader's refusal of `s`, or a failure when it accepts it.
  [[nodiscard]] std::optional<InputError> refusal(const SurveyText& s) const {
    try {
      (void)parse(s);
    } catch (const InputError& e) {
      return e;
    }
    return std::nullopt;
  }
  test::TempDir tmp_;
};

/// The reader names the field as table.key, object[1](o1).key or object[1](o1).support.key.
bool names_key(const InputError& e, const SurveyKey& k) {
  const std::string& f = e.where().field;
  return f == k.table + "." + k.key || f.ends_with("." + k.key) || f == k.key;
}

TEST_F(SchemaAgainstReader, EveryKeyParsesWithItsExample) {
  ASSERT_GT(survey_schema().size(), 60u);
  for (const SurveyKey& k : survey_schema()) {
    SCOPED_TRACE(k.table + "." + k.key);
    const SurveyText s = survey_with(k, k.example);
    try {
      (void)parse(s);
    } catch (const InputError& e) {
      ADD_FAILURE() << e.what() << "\n" << s.text();
    }
  }
}

/// A value of `k` as TOML: a number bare, a length or an area with its unit (the range of a length is in m).
std::string toml_number(const SurveyKey& k, double v) {
  if (k.kind == SurveyKeyKind::length) return fmt::format("\"{}m\"", v);
  if (k.kind == SurveyKeyKind::axis) return fmt::format("[{}, {}, 5]", v, v + 1.0);
  return fmt::format("{}", v);
}

TEST_F(SchemaAgainstReader, RangesRefuseWhatTheReaderRefusesInItsWords) {
  int checked = 0;
  for (const SurveyKey& k : survey_schema()) {
    if (!k.low && !k.high) continue;
    SCOPED_TRACE(k.table + "." + k.key);
    ASSERT_FALSE(k.range_problem.empty());
    const double step = k.kind == SurveyKeyKind::integer ? 1.0 : 0.01;
    for (const auto& [bound, sign] : {std::pair{k.low, -1.0}, std::pair{k.high, 1.0}}) {
      if (!bound) continue;
      // The bound itself: accepted when inclusive, refused when not; one step beyond it: refused.
      for (const double v : {bound->value, bound->value + sign * step}) {
        const bool refused = v != bound->value || !bound->inclusive;
        const auto e = refusal(survey_with(k, toml_number(k, v)));
        ++checked;
        if (!refused) {
          EXPECT_FALSE(e) << v << ": " << (e ? e->what() : "");
          continue;
        }
        ASSERT_TRUE(e) << v << " is accepted by the reader";
        EXPECT_TRUE(names_key(*e, k)) << e->what();
        std::string want = k.kind == SurveyKeyKind::axis ? fmt::format("need 0 < min < max, got [{}, {}]", v, v + 1.0)
                                                         : survey_range_problem(k, v).value_or("(inside)");
        EXPECT_TRUE(e->problem().starts_with(want)) << "reader: " << e->problem() << "\nschema: " << want;
      }
    }
  }
  EXPECT_GT(checked, 60);
}

TEST_F(SchemaAgainstReader, ARangesEndsAreBothChecked) {
  // mu = [0.2, x]: the high end of a range is held to the same range as a value (e's [0, 1], checked at both ends).
  const SurveyKey& e = *find_survey_key("object", "e");
  const auto refused = refusal(survey_with(e, "[0.5, 1.01]"));
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->problem(), survey_range_problem(e, 1.01).value());
  EXPECT_FALSE(refusal(survey_with(e, "[0, 1]")));
  // The epicentre takes the site's latitude and longitude ranges (the form checks it with them).
  const SurveyKey& epi = *find_survey_key("event", "epicentre");
  const auto lat = refusal(survey_with(epi, "[90.5, 0]"));
  ASSERT_TRUE(lat);
  EXPECT_EQ(lat->problem(), find_survey_key("site", "lat")->range_problem);
  const auto lon = refusal(survey_with(epi, "[0, -180.5]"));
  ASSERT_TRUE(lon);
  EXPECT_EQ(lon->problem(), find_survey_key("site", "lon")->range_problem);
}

TEST_F(SchemaAgainstReader, ConditionsAreTheReaders) {
  int checked = 0;
  for (const SurveyKey& k : survey_schema()) {
    for (const SurveyKeyCondition& c : k.conditions) {
      SCOPED_TRACE(k.table + "." + k.key + " with " + c.key);
      const SurveyText s = survey_with(k, k.example, &c);
      const auto e = refusal(s);
      ++checked;
      ASSERT_TRUE(e) << "accepted:\n" << s.text();
      EXPECT_TRUE(names_key(*e, k)) << e->what();
      EXPECT_TRUE(e->problem().starts_with(c.problem)) << "reader: " << e->problem() << "\nschema: " << c.problem;
    }
  }
  EXPECT_GT(checked, 20);
}

TEST_F(SchemaAgainstReader, RequiredKeysAreMissedInTheReadersWords) {
  int checked = 0;
  for (const SurveyKey& k : survey_schema()) {
    if (!k.required && k.required_for_shapes.empty()) continue;
    std::vector<std::string> shapes = k.required_for_shapes;
    if (shapes.empty()) shapes.push_back("");
    for (const std::string& shape : shapes) {
      SCOPED_TRACE(k.table + "." + k.key + " " + shape);
      SurveyText s;
      if (!shape.empty()) {
        s.set("object", "shape", shape == "general asymmetric" ? "\"general\"" : toml_choice(shape));
        // An asymmetric body is one with b1, b2 or inertia: keep one of the others given.
        if (shape == "general asymmetric") s.set("object", k.key == "b1" ? "b2" : "b1", "\"10cm\"");
      }
      if (k.table == "support") s.set("support", k.key == "freq_hz" ? "damping" : "freq_hz", k.key == "freq_hz" ? "0.05" : "3");
      if (k.table == "population") s.set("population", "id", "\"p1\"");  // complete() fills the rest of it
      complete(s);
      s.unset(k.table, k.key);
      const auto e = refusal(s);
      ++checked;
      ASSERT_TRUE(e) << "accepted without it:\n" << s.text();
      std::string want = k.missing_problem;
      if (const auto at = want.find("{shape}"); at != std::string::npos) want.replace(at, 7, shape.substr(0, shape.find(' ')));
      EXPECT_EQ(e->problem(), want) << e->what();
      EXPECT_TRUE(names_key(*e, k)) << e->what();
    }
  }
  EXPECT_GE(checked, 14);
}

TEST_F(SchemaAgainstReader, EveryChoiceParsesAndNoOtherWord) {
  for (const SurveyKey& k : survey_schema()) {
    if (k.choices.empty()) continue;
    SCOPED_TRACE(k.table + "." + k.key);
    for (const std::string& c : k.choices) {
      SurveyText s = survey_with(k, toml_choice(c));
      // Choices whose meaning needs more than the example's context: a records family needs its files; an outcome
      // other than a fall is kept by the base object; a model is chosen for a body that can do what it saw.
      if (k.key == "family" && c == "records") s.set("inversion", "records", "[\"r.csv\"]");
      if (k.key == "outcome" || k.key == "model") s.set("object", "mu", "0.1");
      if (k.key == "model" && c == "slide") s.set("object", "outcome", "\"not_slid\"");
      if (k.key == "model" && c == "3d") {  // three components and a box (docs/survey.md)
        s.set("inversion", "components", "3");
        s.set("object", "depth", "\"30cm\"");
      }
      if (k.key == "outcome" && (c == "slid_toppled" || c == "walked")) s.set("object", "mu", "0.8");
      const auto e = refusal(s);
      EXPECT_FALSE(e) << c << ": " << (e ? e->what() : "");
    }
    if (k.kind == SurveyKeyKind::choice) {
      const auto e = refusal(survey_with(k, "\"zzz\""));
      ASSERT_TRUE(e) << "\"zzz\" accepted";
      EXPECT_TRUE(names_key(*e, k)) << e->what();
    }
  }
}

/// The keys the reader asks a table for, read from its source: the calls of its Reader (string, number, interval,
/// length, axis, get, has), of the mesh pose's `fixed`, the record options' `checked` and a population's counts and
/// sizes (`population_count`, `population_length_range`), and the key lists of the
/// shape checks. A key the reader reads and the table lacks fails here, naming it.
std::set<std::string> reader_keys() {
  const std::string source = test::slurp(kSource / "src" / "io" / "survey_file.cpp");
  std::set<std::string> keys;
  const std::regex call(
      R"re(\b(?:(?:string|number|interval|length|axis|get|has|fixed|checked|require)\(|(?:population_count|population_length_range)\(named, )"([A-Za-z_][A-Za-z0-9_]*)")re");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), call); it != std::sregex_iterator(); ++it) {
    keys.insert((*it)[1]);
  }
  const std::regex list(R"re(for \(const char\* key : \{([^}]*)\}\))re");
  const std::regex word(R"re("([A-Za-z_][A-Za-z0-9_]*)")re");
  for (auto it = std::sregex_iterator(source.begin(), source.end(), list); it != std::sregex_iterator(); ++it) {
    const std::string inner = (*it)[1];
    for (auto w = std::sregex_iterator(inner.begin(), inner.end(), word); w != std::sregex_iterator(); ++w) {
      keys.insert((*w)[1]);
    }
  }
  return keys;
}

TEST(SurveySchema, EveryKeyTheReaderReadsIsInTheTable) {
  const std::set<std::string> keys = reader_keys();
  ASSERT_GT(keys.size(), 50u);  // the scan found the reader's calls
  // The tables themselves, not keys of one.
  const std::set<std::string> tables{"site", "sites", "object", "population", "inversion", "event"};
  for (const std::string& key : keys) {
    if (tables.contains(key)) continue;
    const bool found = std::any_of(survey_schema().begin(), survey_schema().end(),
                                   [&](const SurveyKey& k) { return k.key == key; });
    EXPECT_TRUE(found) << "the reader reads '" << key << "', which include/topple/survey/schema.hpp's table lacks";
  }
  // And the other way: every key of the table is one the reader reads.
  for (const SurveyKey& k : survey_schema()) {
    if (k.key == "epicentre" || k.key == "records" || k.key == "record_columns" || k.key == "support") continue;
    EXPECT_TRUE(keys.contains(k.key)) << k.table << "." << k.key << " is in the table but not read by the scan";
  }
}

/// The keys of one of survey_csv.cpp's sets (`name{"a", "b", ...}`).
std::set<std::string> csv_set(const std::string& source, const std::string& name) {
  const auto at = source.find(name + "{");
  if (at == std::string::npos) return {};
  const auto end = source.find('}', at);
  const std::string inner = source.substr(at, end - at);
  std::set<std::string> out;
  const std::regex word(R"re("([A-Za-z_][A-Za-z0-9_]*)")re");
  for (auto w = std::sregex_iterator(inner.begin(), inner.end(), word); w != std::sregex_iterator(); ++w) out.insert((*w)[1]);
  return out;
}

TEST(SurveySchema, TheCsvReadersKindsAreTheTables) {
  const std::string source = test::slurp(kSource / "src" / "io" / "survey_csv.cpp");
  const auto lengths = csv_set(source, "kLengthKeys");
  const auto areas = csv_set(source, "kAreaKeys");
  const auto strings = csv_set(source, "kStringKeys");
  ASSERT_GT(lengths.size(), 8u);
  ASSERT_EQ(areas.size(), 2u);
  ASSERT_GT(strings.size(), 8u);
  const auto kinds_of = [](const std::string& key) {
    std::set<SurveyKeyKind> kinds;
    for (const SurveyKey& k : survey_schema()) {
      if (k.key == key) kinds.insert(k.kind);
    }
    return kinds;
  };
  for (const auto& key : lengths) EXPECT_TRUE(kinds_of(key).contains(SurveyKeyKind::length)) << key;
  for (const auto& key : areas) EXPECT_TRUE(kinds_of(key).contains(SurveyKeyKind::area)) << key;
  for (const auto& key : strings) {
    if (key == "population") continue;  // a CSV sample row's link to its population's id, not a TOML key
    const auto kinds = kinds_of(key);
    EXPECT_TRUE(kinds.contains(SurveyKeyKind::text) || kinds.contains(SurveyKeyKind::choice) ||
                kinds.contains(SurveyKeyKind::path))
        << key;
  }
  // The form writes an object's lengths and areas in CSV cells with their units ("8cm" under `width`): the CSV
  // reader must know each of them as one.
  for (const SurveyKey& k : survey_schema()) {
    if (k.table != "object" || !k.in_form) continue;
    if (k.kind == SurveyKeyKind::length) {
      EXPECT_TRUE(lengths.contains(k.key)) << k.key;
    }
    if (k.kind == SurveyKeyKind::area) {
      EXPECT_TRUE(areas.contains(k.key)) << k.key;
    }
  }
}

/// "0.25–0.5" -> {0.25, 0.5}.
std::pair<double, double> mu_range(const std::string& text) {
  const auto dash = text.find("–");
  return {std::stod(text.substr(0, dash)), std::stod(text.substr(dash + std::string("–").size()))};
}

TEST(SurveySchema, FrictionTableIsTheDocs) {
  std::ifstream docs(kSource / "docs" / "survey.md");
  std::string line;
  while (std::getline(docs, line) && !line.starts_with("| base on support |")) {
  }
  ASSERT_TRUE(docs) << "docs/survey.md has no friction table";
  std::getline(docs, line);  // |---|
  std::vector<FrictionRow> rows;
  while (std::getline(docs, line) && line.starts_with("| ")) {
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(2));
    for (std::string c; std::getline(ss, c, '|');) {
      const auto a = c.find_first_not_of(' ');
      const auto b = c.find_last_not_of(' ');
      cells.push_back(a == std::string::npos ? "" : c.substr(a, b - a + 1));
    }
    ASSERT_GE(cells.size(), 3u) << line;
    const auto [lo, hi] = mu_range(cells[1]);
    rows.push_back({cells[0], lo, hi, cells[2]});
  }
  const auto& table = friction_table();
  ASSERT_EQ(rows.size(), table.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].surfaces, table[i].surfaces);
    EXPECT_EQ(rows[i].mu_low, table[i].mu_low) << rows[i].surfaces;
    EXPECT_EQ(rows[i].mu_high, table[i].mu_high) << rows[i].surfaces;
    EXPECT_EQ(rows[i].source, table[i].source) << rows[i].surfaces;
    EXPECT_LT(table[i].mu_low, table[i].mu_high);
  }
}

}  // namespace
}  // namespace topple
