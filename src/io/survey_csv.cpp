// CSV surveys (docs/survey.md, "CSV surveys"): a spreadsheet's export rewritten as the equivalent TOML survey.
//
// The CSV is read as RFC 4180 (quoted cells may hold the separator, doubled quotes and line breaks) over the lines of
// detail::split_lines (which drops a UTF-8 byte-order mark and CR before LF, as spreadsheets write them). Debian's one
// C CSV library (libcsv, last released 2013) would save the 60 lines of the cell splitter below but not the line and
// column bookkeeping the error messages need, so the splitter is written here.
#include "io/survey_csv.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <set>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

struct Cell {
  std::string text;      // unquoted; trimmed when it was not quoted
  std::size_t line = 0;  // where the cell starts
};

struct Row {
  std::size_t line = 0;  // where the row starts
  std::vector<Cell> cells;
  [[nodiscard]] bool blank() const {
    return std::all_of(cells.begin(), cells.end(), [](const Cell& c) { return is_blank(c.text); });
  }
};

/// Spreadsheet column letters: 0 -> A, 25 -> Z, 26 -> AA.
std::string column_letters(std::size_t column) {
  std::string out;
  for (std::size_t n = column + 1; n > 0; n = (n - 1) / 26) out.insert(out.begin(), static_cast<char>('A' + (n - 1) % 26));
  return out;
}

std::string column_field(std::size_t column, std::string_view header) {
  return header.empty() ? fmt::format("column {}", column_letters(column))
                        : fmt::format("column {} ('{}')", column_letters(column), header);
}

bool is_comment_or_blank(std::string_view line) {
  const std::string_view t = trim(line);
  return t.empty() || t.front() == '#';
}

/// The separator: ',' unless the first line that holds data has ';' and no ',' (spreadsheets in locales whose
/// decimal mark is a comma export with ';'; the numbers must still be written with a point).
char separator_of(const std::vector<Line>& lines) {
  for (const Line& l : lines) {
    if (is_comment_or_blank(l.text)) continue;
    return l.text.find(',') == std::string_view::npos && l.text.find(';') != std::string_view::npos ? ';' : ',';
  }
  return ',';
}

std::vector<Row> split_rows(const Text& text) {
  const std::vector<Line>& lines = text.lines();
  const char sep = separator_of(lines);
  std::vector<Row> rows;
  std::size_t i = 0;
  while (i < lines.size()) {
    if (is_comment_or_blank(lines[i].text)) {  // a comment, or an empty row, between rows (never inside a cell)
      ++i;
      continue;
    }
    Row row{lines[i].number, {}};
    std::string cell;
    std::size_t cell_line = lines[i].number;
    bool quoted = false, in_quotes = false, closed = false;
    std::size_t li = i, p = 0;
    const auto push = [&] {
      row.cells.push_back(Cell{quoted ? cell : std::string(trim(cell)), cell_line});
      cell.clear();
      quoted = closed = false;
    };
    while (true) {
      const std::string_view t = lines[li].text;
      if (p == t.size()) {
        if (!in_quotes) {
          push();
          break;
        }
        if (li + 1 >= lines.size()) text.fail(cell_line, column_field(row.cells.size(), ""), "a quoted cell is never closed (a '\"' is missing)");
        cell += '\n';
        ++li;
        p = 0;
        continue;
      }
      const char c = t[p++];
      if (c == '\0') {  // quoted as \0 here: a raw NUL would end the message where it is printed as a C string
        text.fail(lines[li].number, column_field(row.cells.size(), ""),
                  "a NUL byte (\\0) in the cell: a CSV survey is text (was the file saved as UTF-16 or binary?)");
      }
      if (in_quotes) {
        if (c != '"') cell += c;
        else if (p < t.size() && t[p] == '"') cell += '"', ++p;
        else in_quotes = false, closed = true;
      } else if (c == sep) {
        push();
        cell_line = lines[li].number;
      } else if (c == '"' && !quoted && is_blank(cell)) {
        in_quotes = quoted = true;
        cell.clear();
        cell_line = lines[li].number;
      } else if (closed) {
        if (c != ' ' && c != '\t') {
          text.fail(lines[li].number, column_field(row.cells.size(), ""),
                    fmt::format("text after the closing quote of a cell (write a '\"' inside a quoted cell as '\"\"')"));
        }
      } else {
        cell += c;
      }
    }
    if (!row.blank()) rows.push_back(std::move(row));
    i = li + 1;
  }
  return rows;
}

bool is_bare_key(std::string_view key) {
  return !key.empty() && std::all_of(key.begin(), key.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-';
  });
}

std::string toml_string(std::string_view s) {
  std::string out = "\"";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') out += '\\', out += c;
    else if (c == '\n') out += "\\n";
    else if (c == '\t') out += "\\t";
    else if (u < 0x20 || u == 0x7F) out += fmt::format("\\u{:04X}", u);
    else out += c;
  }
  return out + '"';
}

/// The cell as a TOML value when it is one (a number, a range "[0.4, 0.6]", an axis "[0.02, 2.0, 30]"), else as a
/// string: the TOML reader then says what it expected, as it would for the TOML file.
std::string toml_value(std::string_view cell) {
  if (cell.find_first_of("\r\n") == std::string_view::npos) {
    try {
      const toml::table t = toml::parse(fmt::format("v = {}\n", cell));
      if (t.size() == 1 && t.contains("v")) return std::string(cell);
    } catch (const toml::parse_error&) {
      // not a TOML value: a string (below)
    }
  }
  return toml_string(cell);
}

// The keys whose values are text, lengths and areas (survey_file.cpp reads them; docs/survey.md lists them).
// `support` is not among them: besides a text it may be a flexible support's inline table {freq_hz = ..., ...}.
const std::set<std::string, std::less<>> kStringKeys{"id",   "description", "shape",  "outcome",  "evidence",
                                                     "name", "notes",       "family", "mesh", "mesh_unit", "model",
                                                     "intensity_scale", "population", "friction_3d"};
const std::set<std::string, std::less<>> kLengthKeys{"width", "height", "diameter",         "a",            "h",
                                                     "b1",    "b2",     "slid", "slid_uncertainty", "slid_at_least",
                                                     "depth"};
/// The keys whose values are areas (D = I_O / m, inertia = I_cm / m): "D_cm2", "inertia_cm2".
const std::set<std::string, std::less<>> kAreaKeys{"D", "inertia"};
constexpr std::array<std::string_view, 5> kLengthUnits{"mm", "cm", "m", "in", "ft"};
constexpr std::array<std::string_view, 3> kAreaUnits{"mm2", "cm2", "m2"};

struct Column {
  std::string key;     // survey key ("width")
  std::string unit;    // from the header ("cm"), or empty
  std::string header;  // as written ("width_cm")
};

/// "width_cm" -> {width, cm}; "D_cm2" -> {D, cm2}; anything else is its own key.
Column column_of(const std::string& header) {
  const std::size_t us = header.rfind('_');
  if (us != std::string::npos) {
    const std::string base = header.substr(0, us);
    const std::string unit = header.substr(us + 1);
    if (kLengthKeys.contains(base) && std::find(kLengthUnits.begin(), kLengthUnits.end(), unit) != kLengthUnits.end()) {
      return {base, unit, header};
    }
    if (kAreaKeys.contains(base) && std::find(kAreaUnits.begin(), kAreaUnits.end(), unit) != kAreaUnits.end()) {
      return {base, unit, header};
    }
  }
  return {header, "", header};
}

/// A header that column_of read as a key of its own but that looks like KEY_UNIT with a unit that does not fit
/// (`height_furlong`, `height_cm2`, `height_CM`, `height_g`, `mu_cm`) is refused, naming the column as typed:
/// unrefused, the misspelt column would be an unknown key found only after "a block needs its height".
void check_header_unit(const Text& text, std::size_t line, std::size_t c, const Column& col) {
  if (!col.unit.empty() || kLengthKeys.contains(col.key) || kAreaKeys.contains(col.key) ||
      kStringKeys.contains(col.key)) {
    return;  // a key with a known unit, or a key of its own (slid_uncertainty)
  }
  const std::size_t us = col.header.rfind('_');
  if (us == std::string::npos || us == 0) return;
  const std::string base = col.header.substr(0, us);
  const std::string unit = col.header.substr(us + 1);
  const auto listed = [](const auto& units, const std::string& u) {
    return std::find(units.begin(), units.end(), to_lower(u)) != units.end();
  };
  const auto field = column_field(c, col.header);
  if (kLengthKeys.contains(base)) {
    text.fail(line, field, fmt::format("{} is not a length unit for {} (a length column's unit is one of mm, cm, m, "
                                       "in, ft, in lower case: {}_cm)", detail::quoted(unit), base, base));
  }
  if (kAreaKeys.contains(base)) {
    text.fail(line, field, fmt::format("{} is not an area unit for {} (an area column's unit is one of mm2, cm2, m2, "
                                       "in lower case: {}_cm2)", detail::quoted(unit), base, base));
  }
  if (listed(kLengthUnits, unit) || listed(kAreaUnits, unit)) {
    text.fail(line, field, fmt::format("{} takes no unit: only lengths (width, height, diameter, a, h, b1, b2, slid, "
                                       "slid_uncertainty, slid_at_least, depth) and areas (D, inertia) name one in "
                                       "the header", base));
  }
}

class Writer {
 public:
  void line(std::string text, CsvOrigin origin) {
    out_.toml += text;
    out_.toml += '\n';
    out_.origins.push_back(std::move(origin));
  }
  CsvSurveyText take() { return std::move(out_); }

 private:
  CsvSurveyText out_;
};

/// A cell that opens a TOML inline table ('{') but is not one (its closing brace missing, a typo inside) is refused:
/// taken as text, a flexible support would become a free-text label and the object would stand on a rigid support.
void refuse_broken_table(const Text& text, const Cell& cell, const std::string& field, const std::string& value) {
  if (cell.text.starts_with('{') && value.starts_with('"')) {
    text.fail(cell.line, field,
              fmt::format("{} opens a table with '{{' but is not one (a closing '}}' missing?): write e.g. "
                          "\"{{freq_hz = 3, damping = 0.05}}\"", detail::quoted(cell.text)));
  }
}

/// A setting's value as TOML: text keys quoted; inversion.records, a list of record files separated by ';' (a TOML
/// array is accepted too); anything else as written.
std::string setting_value(const std::string& section, const std::string& key, const std::string& cell) {
  if (kStringKeys.contains(key)) return toml_string(cell);
  if (section == "inversion" && key == "records" && !cell.starts_with('[')) {
    // A list of record files separated by ';' (a TOML array is accepted too).
    std::string value = "[";
    std::string_view rest = cell;
    while (true) {
      const std::size_t semi = rest.find(';');
      value += toml_string(trim(rest.substr(0, semi)));
      if (semi == std::string_view::npos) break;
      value += ", ";
      rest.remove_prefix(semi + 1);
    }
    value += "]";
    return value;
  }
  return toml_value(cell);
}

/// The setting rows ("site.name", "inversion.pga_g", "event.epicentre" and a value), written as TOML tables. Returns
/// the index of the first row that is not a setting (the header row).
std::size_t write_settings(const Text& text, const std::vector<Row>& rows, Writer& w) {
  // Setting rows ("site.name", "inversion.pga_g", "event.epicentre" and a value) come before the header row.
  std::map<std::string, std::vector<std::pair<std::string, CsvOrigin>>> sections;
  std::vector<std::string> order;
  std::size_t r = 0;
  for (; r < rows.size(); ++r) {
    const Row& row = rows[r];
    const std::string& first = row.cells.front().text;
    const std::size_t dot = first.find('.');
    if (dot == std::string::npos) break;  // the header row
    const std::string section = first.substr(0, dot);
    const std::string key = first.substr(dot + 1);
    if (section != "site" && section != "inversion" && section != "event") {
      text.fail(row.line, column_field(0, ""),
                fmt::format("unknown setting {} (a setting row is site.KEY, inversion.KEY or event.KEY, then its "
                            "value; the header row with an id column comes after them)", detail::quoted(first)));
    }
    if (!is_bare_key(key)) text.fail(row.line, column_field(0, ""), fmt::format("{} is not a key", detail::quoted(first)));
    if (row.cells.size() < 2 || row.cells[1].text.empty()) {
      text.fail(row.line, column_field(1, ""), fmt::format("the setting {} has no value (in the next column)", first));
    }
    for (std::size_t c = 2; c < row.cells.size(); ++c) {
      if (!row.cells[c].text.empty()) {
        text.fail(row.cells[c].line, column_field(c, ""), fmt::format("a setting row holds a key and one value; "
                                                                      "what follows {}'s value is not empty", first));
      }
    }
    const std::string value = setting_value(section, key, row.cells[1].text);
    refuse_broken_table(text, row.cells[1], column_field(1, ""), value);
    if (!sections.contains(section)) order.push_back(section);
    sections[section].emplace_back(key + " = " + value, CsvOrigin{row.cells[1].line, 1, first});
  }
  for (const std::string& section : order) {
    w.line("[" + section + "]", CsvOrigin{sections[section].front().second.line, {}, {}});
    for (auto& [toml_line, origin] : sections[section]) w.line(toml_line, origin);
  }
  return r;
}

/// The header row's columns: a survey key each, with an optional unit; none for a column without a header.
std::vector<std::optional<Column>> read_header(const Text& text, const Row& head) {
  std::vector<std::optional<Column>> columns;
  std::map<std::string, std::size_t, std::less<>> seen;
  for (std::size_t c = 0; c < head.cells.size(); ++c) {
    const std::string& h = head.cells[c].text;
    if (h.empty()) {
      columns.emplace_back();  // a column without a header must stay empty (checked per row)
      continue;
    }
    if (!is_bare_key(h)) {
      text.fail(head.line, column_field(c, ""),
                fmt::format("{} is not a column name: a column is named by a survey key (id, width, mu, ...), with "
                            "an optional unit (width_cm)", detail::quoted(h)));
    }
    Column col = column_of(h);
    check_header_unit(text, head.line, c, col);
    if (const auto it = seen.find(col.key); it != seen.end()) {
      text.fail(head.line, column_field(c, h),
                fmt::format("{} is given twice: here and in {}", col.key, column_field(it->second, columns[it->second]->header)));
    }
    seen.emplace(col.key, c);
    columns.emplace_back(std::move(col));
  }
  if (!seen.contains("id")) {
    text.fail(head.line, "id", "the header row has no id column (every object needs an id; docs/survey.md)");
  }
  return columns;
}

/// A row that reads as a setting (`site.KEY`, `inversion.KEY` or `event.KEY` and one value): below the header row it
/// would be read as an object whose id is the setting's name.
bool is_setting_row(const Row& row) {
  const std::string& first = row.cells.front().text;
  const std::size_t dot = first.find('.');
  if (dot == std::string::npos) return false;
  const std::string section = first.substr(0, dot);
  if (section != "site" && section != "inversion" && section != "event") return false;
  if (!is_bare_key(std::string_view(first).substr(dot + 1))) return false;
  return std::all_of(row.cells.begin() + std::min<std::size_t>(2, row.cells.size()), row.cells.end(),
                     [](const Cell& c) { return c.text.empty(); });
}

// ---- Populations in a CSV survey (docs/survey.md, "[[population]]"): a row with a `count` cell is a population (its
// keys as in TOML; a size range in a column with a unit is written "[25, 45]"), a row with a `population` cell is a
// measured member of the population of that id (its width/height/diameter). Kept apart from write_objects. ----

/// The column of `key`, if the header has it.
std::optional<std::size_t> column_index(const std::vector<std::optional<Column>>& columns, std::string_view key) {
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (columns[c] && columns[c]->key == key) return c;
  }
  return std::nullopt;
}

bool cell_given(const Row& row, std::optional<std::size_t> c) {
  return c && *c < row.cells.size() && !row.cells[*c].text.empty();
}

/// A population's row or a sample member's row: not an object.
bool is_population_row(const Row& row, const std::vector<std::optional<Column>>& columns) {
  return cell_given(row, column_index(columns, "count")) || cell_given(row, column_index(columns, "population"));
}

/// A cell's TOML value in a population's row or a member's: a length column with a header unit takes a number or a
/// range "[low, high]" of numbers (each given the unit); the rest as an object's cell.
std::string population_cell_value(const Text& text, const Cell& cell, std::size_t c, const Column& col) {
  if (col.unit.empty()) {
    // The counts (a population's `slid` is a count, an object's a distance).
    if (col.key == "slid" || col.key == "count" || col.key == "overturned" || col.key == "rocked") {
      return toml_value(cell.text);
    }
    if (kStringKeys.contains(col.key) || kLengthKeys.contains(col.key) || kAreaKeys.contains(col.key)) {
      return toml_string(cell.text);
    }
    return toml_value(cell.text);
  }
  const std::string_view t = trim(cell.text);
  if (t.size() >= 2 && t.front() == '[' && t.back() == ']') {
    const std::string_view inner = t.substr(1, t.size() - 2);
    const std::size_t comma = inner.find(',');
    const std::string lo(trim(inner.substr(0, comma)));
    const std::string hi(comma == std::string_view::npos ? "" : std::string(trim(inner.substr(comma + 1))));
    if (comma == std::string_view::npos || !try_number(lo) || !try_number(hi)) {
      text.fail(cell.line, column_field(c, col.header),
                fmt::format("a range of sizes is [low, high] in the header's unit ({}), not {}", col.unit,
                            detail::quoted(cell.text)));
    }
    return fmt::format("[{}, {}]", toml_string(lo + col.unit), toml_string(hi + col.unit));
  }
  if (!try_number(cell.text)) {
    text.fail(cell.line, column_field(c, col.header),
              fmt::format("the header gives the unit ({}): write a bare number or a range [low, high], not {}",
                          col.unit, detail::quoted(cell.text)));
  }
  return toml_string(cell.text + col.unit);
}

/// The populations: a [[population]] table per row with a `count`, its measured members (rows whose `population` is
/// its id) as its `sample`, one inline table per row. A member of an unknown population is refused at its cell.
void write_populations(const Text& text, const std::vector<Row>& rows, std::size_t first,
                       const std::vector<std::optional<Column>>& columns, Writer& w) {
  const auto count_col = column_index(columns, "count");
  const auto pop_col = column_index(columns, "population");
  const auto id_col = column_index(columns, "id");
  std::set<std::string, std::less<>> ids;
  for (std::size_t r = first; r < rows.size(); ++r) {
    if (cell_given(rows[r], count_col) && cell_given(rows[r], id_col)) ids.insert(rows[r].cells[*id_col].text);
  }
  for (std::size_t r = first; r < rows.size(); ++r) {
    const Row& row = rows[r];
    if (cell_given(row, pop_col) && !ids.contains(row.cells[*pop_col].text)) {
      text.fail(row.cells[*pop_col].line, column_field(*pop_col, columns[*pop_col]->header),
                fmt::format("no population with id {} (a row with that id and a count)",
                            detail::quoted(row.cells[*pop_col].text)));
    }
    if (cell_given(row, pop_col) && cell_given(row, count_col)) {
      text.fail(row.cells[*count_col].line, column_field(*count_col, columns[*count_col]->header),
                "a row is a population (a count) or a measured member of one (population), not both");
    }
  }
  for (std::size_t r = first; r < rows.size(); ++r) {
    const Row& row = rows[r];
    if (!cell_given(row, count_col)) continue;
    w.line("[[population]]", CsvOrigin{row.line, {}, {}});
    for (std::size_t c = 0; c < row.cells.size(); ++c) {
      const Cell& cell = row.cells[c];
      if (cell.text.empty()) continue;
      if (c >= columns.size() || !columns[c]) {
        text.fail(cell.line, column_field(c, ""), fmt::format("{} is in a column without a header", detail::quoted(cell.text)));
      }
      w.line(columns[c]->key + " = " + population_cell_value(text, cell, c, *columns[c]), CsvOrigin{cell.line, c, columns[c]->header});
    }
    const std::string& id = id_col && *id_col < row.cells.size() ? row.cells[*id_col].text : std::string();
    bool any = false;
    for (std::size_t m = first; m < rows.size(); ++m) {
      const Row& member = rows[m];
      if (!cell_given(member, pop_col) || member.cells[*pop_col].text != id) continue;
      if (!any) w.line("sample = [", CsvOrigin{member.line, {}, {}});
      any = true;
      std::string entry;
      for (std::size_t c = 0; c < member.cells.size(); ++c) {
        const Cell& cell = member.cells[c];
        if (cell.text.empty() || c >= columns.size() || !columns[c]) continue;
        const std::string& key = columns[c]->key;
        if (key == "population" || key == "id" || key == "description") continue;
        if (key != "width" && key != "height" && key != "diameter") {
          text.fail(cell.line, column_field(c, columns[c]->header),
                    fmt::format("a measured member of a population gives its sizes (width, height, diameter), not {}",
                                key));
        }
        entry += (entry.empty() ? "" : ", ") + key + " = " + population_cell_value(text, cell, c, *columns[c]);
      }
      w.line("  {" + entry + "},", CsvOrigin{member.line, {}, {}});
    }
    if (any) w.line("]", CsvOrigin{row.line, {}, {}});
  }
}

/// One object per row from `first` on: a [[object]] table each, a key per non-empty cell.
void write_objects(const Text& text, const std::vector<Row>& rows, std::size_t first, const Row& head,
                   const std::vector<std::optional<Column>>& columns, Writer& w) {
  for (std::size_t r = first; r < rows.size(); ++r) {
    const Row& row = rows[r];
    if (is_population_row(row, columns)) continue;  // write_populations
    if (is_setting_row(row)) {
      text.fail(row.line, column_field(0, ""),
                fmt::format("{} is a setting row after the header row (line {}): setting rows (site.KEY, "
                            "inversion.KEY, event.KEY) go before the header row (docs/survey.md, \"CSV surveys\")",
                            detail::quoted(row.cells.front().text), head.line));
    }
    w.line("[[object]]", CsvOrigin{row.line, {}, {}});
    for (std::size_t c = 0; c < row.cells.size(); ++c) {
      const Cell& cell = row.cells[c];
      if (cell.text.empty()) continue;  // an empty cell: the key is not given (its default applies)
      if (c >= columns.size() || !columns[c]) {
        text.fail(cell.line, column_field(c, ""),
                  fmt::format("{} is in a column without a header (the header row has {} columns)", detail::quoted(cell.text),
                              head.cells.size()));
      }
      const Column& col = *columns[c];
      std::string value;
      if (!col.unit.empty()) {
        if (!try_number(cell.text)) {
          text.fail(cell.line, column_field(c, col.header),
                    fmt::format("the header gives the unit ({}): write a bare number, not {}", col.unit,
                                detail::quoted(cell.text)));
        }
        value = toml_string(cell.text + col.unit);
      } else if (kStringKeys.contains(col.key) || kLengthKeys.contains(col.key) || kAreaKeys.contains(col.key)) {
        value = toml_string(cell.text);  // a length without a header unit carries its own ("8cm"), as in TOML
      } else {
        value = toml_value(cell.text);
        refuse_broken_table(text, cell, column_field(c, col.header), value);
      }
      w.line(col.key + " = " + value, CsvOrigin{cell.line, c, col.header});
    }
  }
}

}  // namespace

bool is_csv_survey(std::string_view text, std::string_view name) {
  if (name.size() >= 4 && to_lower(name.substr(name.size() - 4)) == ".csv") return true;
  if (name.size() >= 5 && to_lower(name.substr(name.size() - 5)) == ".toml") return false;
  for (const Line& l : split_lines(text, 1000)) {
    if (is_comment_or_blank(l.text)) continue;
    const std::string_view t = trim(l.text);
    if (t.front() == '[') return false;  // a TOML table
    const std::size_t sep = t.find_first_of(",;");
    return sep != std::string_view::npos && t.substr(0, sep).find('=') == std::string_view::npos;
  }
  return false;
}

CsvSurveyText csv_survey_to_toml(std::string_view content, const std::string& name) {
  // Line ends: LF and CRLF (split_lines), and a CR alone, as old Mac programs write it (one line end each, so that
  // line numbers stay those an editor shows).
  std::string lone_cr;
  for (std::size_t i = 0; i < content.size(); ++i) {
    if (content[i] != '\r' || (i + 1 < content.size() && (content[i + 1] == '\n' || content[i + 1] == '\r'))) continue;
    if (lone_cr.empty()) lone_cr.assign(content);
    lone_cr[i] = '\n';
  }
  if (!lone_cr.empty()) content = lone_cr;
  const Text text(content, name);
  const std::vector<Row> rows = split_rows(text);
  Writer w;
  std::size_t r = write_settings(text, rows, w);
  if (r == rows.size()) {
    text.fail(text.last_line_number(), "id",
              "no header row: a CSV survey has one row of column names (id, shape, width_cm, ...) and then one "
              "object per row (docs/survey.md, \"CSV surveys\")");
  }
  // The header row.
  const Row& head = rows[r++];
  const std::vector<std::optional<Column>> columns = read_header(text, head);
  write_objects(text, rows, r, head, columns, w);
  write_populations(text, rows, r, columns, w);
  return w.take();
}

InputError relocate_csv_error(const InputError& e, const CsvSurveyText& csv, const std::string& name) {
  InputLocation where = e.where();
  where.file = name;
  if (where.line && *where.line >= 1 && *where.line <= csv.origins.size()) {
    const CsvOrigin& o = csv.origins[*where.line - 1];
    where.line = o.line;
    if (o.column) {
      const std::string column = column_field(*o.column, o.header);
      where.field = where.field.empty() ? column : where.field + " in " + column;
    }
  }
  return InputError(where, e.problem());
}

std::string relocate_csv_note(const std::string& note, const CsvSurveyText& csv, const std::string& name) {
  const std::string prefix = name + ":";
  if (!note.starts_with(prefix)) return note;
  std::size_t end = prefix.size();
  std::size_t line = 0;
  while (end < note.size() && note[end] >= '0' && note[end] <= '9' && line < csv.origins.size() + 1) {
    line = line * 10 + static_cast<std::size_t>(note[end++] - '0');
  }
  if (line < 1 || line > csv.origins.size() || end >= note.size() || note[end] != ':') return note;
  return fmt::format("{}{}{}", prefix, csv.origins[line - 1].line, note.substr(end));
}

}  // namespace topple::io::detail
