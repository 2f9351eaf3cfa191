#pragma once
// Internal to the readers (not installed): a file as numbered lines, and number parsing whose every failure is an
// InputError naming the file, the 1-based line and the field. All readers go through these helpers so that messages
// read alike and no reader can index past the end of a line or of the file.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/core/error.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/io/read.hpp"

namespace topple::io::detail {

struct Line {
  std::string_view text;   ///< without its terminator ('\n' and every '\r' before it)
  std::size_t number = 0;  ///< 1-based, as an editor shows it
};

/// Splits `content` into lines at '\n', dropping any run of '\r' before it (CRLF, and the CR CR LF of PE&A's
/// ARL360.at2). A UTF-8 byte-order mark at the start is skipped; trailing 0x1A bytes (the CP/M end-of-file padding
/// of CSMIP V2 files) end the text. At most `max_lines` lines are returned.
[[nodiscard]] std::vector<Line> split_lines(std::string_view content, std::size_t max_lines = SIZE_MAX);

/// A file being read: its name (for messages) and its lines.
class Text {
 public:
  Text(std::string_view content, std::string file);

  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] std::size_t size() const noexcept { return lines_.size(); }
  [[nodiscard]] bool empty() const noexcept { return lines_.empty(); }
  [[nodiscard]] const Line& operator[](std::size_t i) const noexcept { return lines_[i]; }
  [[nodiscard]] const std::vector<Line>& lines() const noexcept { return lines_; }
  /// The line to cite when the file ends too early: its last line (1 for an empty file).
  [[nodiscard]] std::size_t last_line_number() const noexcept { return lines_.empty() ? 1 : lines_.back().number; }

  /// Throws InputError{file, line, field}.
  [[noreturn]] void fail(std::size_t line, std::string_view field, const std::string& problem) const;
  /// Throws InputError{file, -, field}: a problem of the whole file or of an option.
  [[noreturn]] void fail_file(std::string_view field, const std::string& problem) const;

 private:
  std::string file_;
  std::vector<Line> lines_;
};

// ---- strings ----
[[nodiscard]] std::string_view trim(std::string_view s) noexcept;
[[nodiscard]] std::string_view trim_right(std::string_view s) noexcept;
[[nodiscard]] bool is_blank(std::string_view s) noexcept;
[[nodiscard]] std::string to_lower(std::string_view s);
[[nodiscard]] std::string to_upper(std::string_view s);
/// Case-insensitive (ASCII) search; npos when absent.
[[nodiscard]] std::size_t find_ci(std::string_view haystack, std::string_view needle, std::size_t from = 0) noexcept;
[[nodiscard]] bool contains_ci(std::string_view haystack, std::string_view needle) noexcept;
[[nodiscard]] bool starts_with_ci(std::string_view s, std::string_view prefix) noexcept;
/// Runs of spaces and tabs become one space; the ends are trimmed.
[[nodiscard]] std::string collapse_spaces(std::string_view s);
[[nodiscard]] std::vector<std::string_view> split_whitespace(std::string_view s);
/// A token as it appears in a message: quoted, at most 40 characters, control and non-ASCII bytes as \xNN.
[[nodiscard]] std::string quoted(std::string_view token);

// ---- numbers ----
/// A finite decimal number: optional sign (including '+', which std::from_chars refuses), digits with an optional
/// point, optional exponent (E, or Fortran's D). The whole token must be used. Throws, quoting the token, for
/// anything else, for NaN/Inf and for values beyond the range of double.
[[nodiscard]] double parse_number(const Text& text, std::string_view token, std::size_t line, std::string_view field);
/// As parse_number, without throwing.
[[nodiscard]] std::optional<double> try_number(std::string_view token) noexcept;
/// An integer written with digits only (optional sign), within [lo, hi].
[[nodiscard]] long long parse_integer(const Text& text, std::string_view token, std::size_t line,
                                      std::string_view field, long long lo, long long hi);

/// Values read so far, each with the line it came from (so that a later check can still name the line).
struct Samples {
  std::vector<double> values;
  std::vector<std::size_t> lines;
  void push(double value, std::size_t line) {
    values.push_back(value);
    lines.push_back(line);
  }
  [[nodiscard]] std::size_t size() const noexcept { return values.size(); }
};

/// How the numbers of a data line are laid out.
struct Layout {
  std::size_t width = 0;  ///< fixed field width (Fortran Fw.d / Ew.d); 0 = separated by whitespace
  std::string description;  ///< for messages, e.g. "8E10.4"
};

/// Appends the numbers of `line` to `out`. With a fixed width, the line (right-trimmed) must be a whole number of
/// fields: values in these formats are right-justified and may touch ("1.5057E+0-2.2223E+0"), so splitting on
/// blanks would be wrong, and a line that does not fit the columns is refused rather than guessed at.
void parse_values(const Text& text, const Line& line, const Layout& layout, std::string_view field, Samples& out);

/// Reads exactly `count` values from the lines starting at index `first`, stopping at the line where the count is
/// reached. A line for which `ends_data` is true, or the end of the file, before that is a truncation error; a line
/// holding values beyond `count` is an error. `count_field` names the header field that announced the count.
/// Returns the index of the line after the last one read.
template <class EndsData>
std::size_t read_count(const Text& text, std::size_t first, std::size_t count, const Layout& layout,
                       std::string_view field, std::string_view count_field, EndsData ends_data, Samples& out);

/// The factor from `unit` to m/s^2 (see acceleration_unit_factor), with errors placed at `line` of the file.
[[nodiscard]] double unit_factor(const Text& text, std::string_view unit, std::size_t line, std::string_view field,
                                 double g_m_s2);

/// The factor to m/s^2 of the unit `unit` that the file states (at `line`, or the whole file when nullopt, in
/// `field`), refusing a ReadOptions::units that disagrees with it: a unit given by the user is a check, never an
/// override of what the file says.
[[nodiscard]] double file_unit_factor(const Text& text, std::string_view unit, std::optional<std::size_t> line,
                                      std::string_view field, const ReadOptions& options);

/// values * factor, checking each product is finite (a huge value times a unit factor can overflow) and within
/// GroundMotionLimits::max_abs_accel_m_s2, naming the line of the value.
[[nodiscard]] std::vector<double> to_m_s2(const Text& text, const Samples& samples, double factor,
                                          std::string_view field);

/// GroundMotion::uniform, refusing here (at `line` of the file, or the whole file when nullopt, in `field`) a time
/// step outside GroundMotionLimits, a record longer than their duration or sample count, and a ReadOptions::dt_s
/// that disagrees with the file's time step by more than 1e-6 relative.
[[nodiscard]] GroundMotion uniform_record(const Text& text, std::vector<double> accel_m_s2, double dt_s,
                                          std::optional<std::size_t> line, std::string_view field,
                                          RecordMetadata meta, const ReadOptions& options);

/// Cross-check of a duration a header declares (`declared_s`, at `line` in `field`) against the data: refuses a
/// difference beyond `tolerance_s` (a truncated or padded file, or a wrong time step).
void check_declared_duration(const Text& text, double declared_s, double data_s, double tolerance_s,
                             std::size_t line, std::string_view field, std::string_view data_description);

/// Throws unless no non-blank line remains from index `from` on: values beyond the announced count.
void require_no_more_values(const Text& text, std::size_t from, std::string_view count_field, std::size_t count);

// ---- the readers, one file each ----
[[nodiscard]] GroundMotion read_peer_at2(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_cosmos_v2(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_csmip_v2(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_knet(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_usgs_smc(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_esm(const Text& text, const ReadOptions& options);
[[nodiscard]] GroundMotion read_plain(const Text& text, const ReadOptions& options);

// Content tests used by detect_format (each looks only at the first lines).
[[nodiscard]] bool looks_like_peer_at2(const std::vector<Line>& head);
[[nodiscard]] bool looks_like_cosmos_v2(const std::vector<Line>& head);
[[nodiscard]] bool looks_like_csmip_v2(const std::vector<Line>& head);
[[nodiscard]] bool looks_like_knet(const std::vector<Line>& head);
[[nodiscard]] bool looks_like_usgs_smc(const std::vector<Line>& head);
[[nodiscard]] bool looks_like_esm(const std::vector<Line>& head);

/// Channel choice in a multi-channel file. `names` are the components of channels 1..n, for the message that lists
/// them when the file holds several and none was chosen. Returns the 0-based index.
[[nodiscard]] std::size_t choose_channel(const Text& text, const std::vector<std::string>& names,
                                         const std::optional<int>& channel);

// ---- template definition ----
template <class EndsData>
std::size_t read_count(const Text& text, std::size_t first, std::size_t count, const Layout& layout,
                       std::string_view field, std::string_view count_field, EndsData ends_data, Samples& out) {
  const std::size_t start = out.size();
  std::size_t i = first;
  while (out.size() - start < count) {
    if (i >= text.size() || ends_data(text[i].text)) {
      const std::size_t at = i < text.size() ? text[i].number : text.last_line_number();
      text.fail(at, field,
                "truncated data: " + std::to_string(out.size() - start) + " values where " + std::string(count_field) +
                    " announces " + std::to_string(count) +
                    (i < text.size() ? " (the data ends here)" : " (the file ends here)"));
    }
    parse_values(text, text[i], layout, field, out);
    if (out.size() - start > count) {
      text.fail(text[i].number, field,
                "more values than the " + std::to_string(count) + " that " + std::string(count_field) + " announces");
    }
    ++i;
  }
  return i;
}

}  // namespace topple::io::detail
