#pragma once
// Internal to the survey reader (not installed): a CSV survey (docs/survey.md, "CSV surveys") rewritten as the
// equivalent TOML survey, so that one reader (survey_file.cpp) applies every rule, default and check to both forms,
// and the errors of that reader placed back at the CSV's line and column.
//
// The rewrite puts one value per TOML line and remembers, for each TOML line, the CSV line (and column) it came
// from; a TOML error at line L is then reported at origins[L-1].
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/core/error.hpp"

namespace topple::io::detail {

/// Where a line of the generated TOML came from.
struct CsvOrigin {
  std::size_t line = 0;            ///< 1-based CSV line (of the row, or of the cell's start)
  std::optional<std::size_t> column;  ///< 0-based column of the cell, when the TOML line holds one cell
  std::string header;              ///< the column's header as written (e.g. "width_cm")
};

struct CsvSurveyText {
  std::string toml;                  ///< the equivalent TOML survey
  std::vector<CsvOrigin> origins;    ///< origins[L-1] for TOML line L
};

/// True when a survey named `name` with content `text` is a CSV survey: by the extension (".csv" yes, ".toml" no,
/// case-insensitive), else by content (the first line that is not blank or a '#' comment does not open a TOML table
/// and has a ',' before any '=').
[[nodiscard]] bool is_csv_survey(std::string_view text, std::string_view name);

/// Rewrites a CSV survey as TOML. Throws InputError{name, line, field} for a malformed CSV: an unterminated quote,
/// no header row (one with an `id` column), a header that is not a plain key, a column given twice (also `width`
/// with `width_cm`), a unit in both the header and a cell, a row with more cells than the header, a bad setting row.
[[nodiscard]] CsvSurveyText csv_survey_to_toml(std::string_view text, const std::string& name);

/// The TOML reader's error `e` placed at the CSV's line and column (the field then names the column, e.g.
/// "object[2](speaker).width (column D, 'width_cm')").
[[nodiscard]] InputError relocate_csv_error(const InputError& e, const CsvSurveyText& csv, const std::string& name);

/// A reader note "name:L: field: text" with the TOML line L replaced by the CSV line.
[[nodiscard]] std::string relocate_csv_note(const std::string& note, const CsvSurveyText& csv,
                                            const std::string& name);

}  // namespace topple::io::detail
