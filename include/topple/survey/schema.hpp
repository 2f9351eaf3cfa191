#pragma once
// The survey file's keys as one table (docs/survey.md): for each key of [site], [[object]], [inversion] and [event],
// its kind, unit, range, choices, whether it is required, the reader's words when it is missing or out of range, and
// its help text. The offline survey form (`topple survey-form`, output/survey_form.hpp) is generated from this table,
// and tests/io/test_survey_schema.cpp holds it against the reader (io/survey_file.cpp, io/survey_csv.cpp): every key
// here parses, every value its range refuses the reader refuses with the same words (and the boundary values it
// accepts the reader accepts), and every key the reader reads is here. So the form and the reader cannot drift.
#include <optional>
#include <string>
#include <vector>

namespace topple {

enum class SurveyKeyKind {
  text,            ///< free text
  choice,          ///< one of `choices`
  number,          ///< a number in `unit`
  integer,         ///< a whole number
  value_or_range,  ///< a number or [low, high] (low <= high), sampled uniformly
  length,          ///< a string with its length unit: "8cm" (mm, cm, m, in, ft)
  area,            ///< a string with its area unit: "0.01m2" (mm2, cm2, m2)
  axis,            ///< [min, max, count] of a log-spaced axis, 0 < min < max, count a whole number from 2 to 1000
  lat_lon,         ///< [lat, lon] in degrees
  support,         ///< free text, or a flexible support {freq_hz = ..., damping = ..., name = "..."}
  path,            ///< a file's path, relative to the survey file
  paths,           ///< a list of file paths
  numbers,         ///< a fixed list of numbers (mesh pose vectors)
  columns,         ///< a record's columns: [time, acceleration] or "TIME,ACCEL"
  tables,          ///< a list of inline tables (a population's measured sample)
};
[[nodiscard]] std::string_view survey_key_kind_name(SurveyKeyKind kind);  ///< "text", "choice", "number", ...

/// One end of a key's range.
struct SurveyKeyBound {
  double value = 0.0;
  bool inclusive = true;
};

/// A condition another key sets on this one: `key` (as "table.key", or a key of the same table) must hold one of
/// `values` (its text as written in TOML, without quotes; empty: `key` must be present), else the reader refuses this
/// key with `problem` (its words, or their beginning).
struct SurveyKeyCondition {
  std::string key;
  std::vector<std::string> values;
  std::string problem;
};

struct SurveyKey {
  std::string table;  ///< "site", "object", "population", "inversion", "event" (a [[sites]] table takes the site's keys)
  std::string key;
  SurveyKeyKind kind = SurveyKeyKind::text;
  std::string unit;  ///< of a number, axis or range ("g", "Hz", "deg", "m/s", "km", "s"); empty: dimensionless/in text
  std::optional<SurveyKeyBound> low, high;  ///< the range of a number (of both ends of a range; of a length, in m)
  /// The reader's words for a value outside [low, high]; "{}" stands for the value as the reader prints it (fmt's
  /// shortest round-trip form, which is JavaScript's too), in metres for a length.
  std::string range_problem;
  std::vector<std::string> choices;  ///< of a choice
  bool required = false;             ///< in every table of its kind
  std::vector<std::string> required_for_shapes;  ///< an object's dimension: required for these shapes
  std::string missing_problem;       ///< the reader's words when a required key is missing ("{shape}": the shape)
  std::vector<SurveyKeyCondition> conditions;  ///< what other keys must say for this one to be given
  std::string default_text;          ///< what an absent key means
  std::string help;                  ///< one line for the form (docs/survey.md has the whole story)
  std::string example;               ///< a TOML value the reader accepts (with the conditions' first values)
  bool in_form = true;               ///< offered by the offline form (not: keys that name files, nested tables)
};

/// Every key of the survey file, table by table, an object's in the order a field team fills them in (the form's order).
[[nodiscard]] const std::vector<SurveyKey>& survey_schema();
/// The key `key` of `table`, or nullptr.
[[nodiscard]] const SurveyKey* find_survey_key(std::string_view table, std::string_view key);
/// The range's words with the value in place of "{}": what the reader says of `value` (nullopt: inside the range).
[[nodiscard]] std::optional<std::string> survey_range_problem(const SurveyKey& key, double value);

/// A row of docs/survey.md's "Friction coefficients" table: a base on a support, its static dry mu range, the source.
struct FrictionRow {
  std::string surfaces;
  double mu_low = 0.0;
  double mu_high = 0.0;
  std::string source;
};
[[nodiscard]] const std::vector<FrictionRow>& friction_table();

/// The reader's words for a fall direction on a body whose planar model has none (survey.cpp,
/// check_object_fall_direction), which the form repeats for a population's fall directions, not one key's range.
inline constexpr const char* kFallDirectionProblem =
    "only a cylinder or a box (a block with depth), or a model = \"3d\" body, tells the direction of the shaking by "
    "the way it fell: the planar model of a block without depth falls along its bearing (give that as azimuth_deg, "
    "or give the block's depth)";

}  // namespace topple
