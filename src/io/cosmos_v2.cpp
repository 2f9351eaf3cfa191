// COSMOS V2 / V2c processed records (COSMOS Strong-Motion Data Format v01.20; layout in SOURCES.md).
//
// A file is one or more blocks, each:
//   line 1        "Corrected acceleration    (Format v01.20 with 13 text lines) ..."  (number of text lines)
//   text lines    event (line 2), station (line 5), channel (line 9) ...
//   " 100 Integer-header values follow on  10 lines, Format= (10I8)"  and those lines
//   " 100 Real-header values follow on  20 lines, Format= (5F15.6)"   and those lines
//   "   6 Comment line(s) follow, each starting with a "|":"           and those lines
//   "   42000 acceleration pts, approx  210 secs, units=cm/sec2(04),Format=(1E15.6)"  and the data
//   "End-of-data for ChanBNZ acceleration"
// The time step is Real header 62 (1-based) in milliseconds. Real header 34 is the sampling interval of the V0
// (raw) series, which processing may have changed, so it is never used. -999 marks an unknown value. Values are read
// in the fixed columns of the data line's Fortran format: that is what the format defines, and F-format values may
// fill their whole field.
#include <optional>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

constexpr double kUnknown = -999.0;

/// Fixed-width layout from a Fortran format such as "(10I8)", "(5F15.6)", "(1E15.6)", "(8E10.4)".
std::optional<Layout> fortran_layout(std::string_view line) {
  const std::size_t at = find_ci(line, "format=");
  if (at == std::string_view::npos) return std::nullopt;
  std::string_view s = trim(line.substr(at + 7));
  if (!s.starts_with('(')) return std::nullopt;
  const std::size_t close = s.find(')');
  if (close == std::string_view::npos) return std::nullopt;
  const std::string_view spec = trim(s.substr(1, close - 1));
  std::size_t i = 0;
  while (i < spec.size() && spec[i] >= '0' && spec[i] <= '9') ++i;
  if (i >= spec.size()) return std::nullopt;
  const char kind = static_cast<char>(spec[i] & ~0x20);  // upper case
  if (kind != 'I' && kind != 'F' && kind != 'E' && kind != 'G' && kind != 'D') return std::nullopt;
  ++i;
  std::size_t width = 0;
  const std::size_t width_begin = i;
  while (i < spec.size() && spec[i] >= '0' && spec[i] <= '9' && i - width_begin < 4) {
    width = width * 10 + static_cast<std::size_t>(spec[i] - '0');
    ++i;
  }
  if (width == 0) return std::nullopt;
  if (i < spec.size() && spec[i] == '.') {
    ++i;
    while (i < spec.size() && spec[i] >= '0' && spec[i] <= '9') ++i;
  }
  if (i != spec.size()) return std::nullopt;
  return Layout{width, std::string(spec)};
}

/// The integer that starts `s` (after blanks), as a token.
std::string_view first_token(std::string_view s) {
  const auto tokens = split_whitespace(s);
  return tokens.empty() ? std::string_view{} : tokens.front();
}

struct Block {
  std::size_t first = 0;       ///< index of line 1
  std::string kind;            ///< "acceleration", "velocity", ... from the data line
  std::size_t data_line = 0;   ///< index of the "N ... pts" line
  std::size_t npts = 0;
  Layout layout;
  std::string unit;
  std::size_t end = 0;         ///< index of the End-of-data line (or the number of lines when it is missing)
  Samples reals;
  RecordMetadata meta;
};

/// Parses "N <what> values follow on M lines, Format= (...)" at index i and reads the N values after it.
std::size_t read_header_values(const Text& text, std::size_t i, std::string_view what, Samples& out) {
  if (i >= text.size()) {
    text.fail(text.last_line_number(), what, fmt::format("the file ends before the {} values", what));
  }
  const Line& line = text[i];
  const auto layout = fortran_layout(line.text);
  if (!contains_ci(line.text, what) || !layout) {
    text.fail(line.number, what,
              fmt::format("expected 'N {} values follow on M lines, Format= (...)', found {}", what,
                          detail::quoted(trim(line.text))));
  }
  const auto n = static_cast<std::size_t>(parse_integer(text, first_token(line.text), line.number, what, 0, 100000));
  // A wrong count runs into the next header line; naming it as the end of the values makes that message clear.
  return read_count(text, i + 1, n, *layout, what, fmt::format("line {}", line.number),
                    [](std::string_view s) { return contains_ci(s, "values follow") || contains_ci(s, "comment line"); },
                    out);
}

/// Parses one block starting at index `first`; returns it with `end` set.
Block parse_block(const Text& text, std::size_t first) {
  Block b;
  b.first = first;
  const Line& l1 = text[first];
  const std::size_t label = find_ci(l1.text, "text lines");
  if (!contains_ci(l1.text, "(format v") || label == std::string_view::npos) {
    text.fail(l1.number, "text header",
              fmt::format("expected a COSMOS header line such as 'Corrected acceleration (Format v01.20 with 13 text "
                          "lines)', found {}",
                          detail::quoted(trim(l1.text))));
  }
  // The number just before "text lines".
  std::string_view before = trim_right(l1.text.substr(0, label));
  std::size_t digits = before.size();
  while (digits > 0 && before[digits - 1] >= '0' && before[digits - 1] <= '9') --digits;
  const auto n_text = static_cast<std::size_t>(
      parse_integer(text, before.substr(digits), l1.number, "text lines", 1, 10000));
  if (first + n_text >= text.size()) {
    text.fail(text.last_line_number(), "text header",
              fmt::format("the file ends inside the {} text lines announced on line {}", n_text, l1.number));
  }
  auto text_line = [&](std::size_t k) -> std::string_view {  // 1-based line of the text header, "" if absent
    return k <= n_text ? text[first + k - 1].text : std::string_view{};
  };
  std::string event = collapse_spaces(text_line(2));
  if (starts_with_ci(event, "record of ")) event = event.substr(10);
  b.meta.event = event;
  const std::string_view station = text_line(5);
  const std::size_t code = find_ci(station, "code:");
  b.meta.station = collapse_spaces(code == std::string_view::npos ? station : station.substr(code + 5));

  Samples ints;
  std::size_t i = read_header_values(text, first + n_text, "Integer-header", ints);
  i = read_header_values(text, i, "Real-header", b.reals);

  if (i >= text.size()) text.fail(text.last_line_number(), "comments", "the file ends before the comment count line");
  const Line& comments = text[i];
  if (!contains_ci(comments.text, "comment line")) {
    text.fail(comments.number, "comments",
              fmt::format("expected 'N Comment line(s) follow, each starting with a \"|\"', found {}",
                          detail::quoted(trim(comments.text))));
  }
  const auto n_comments = static_cast<std::size_t>(
      parse_integer(text, first_token(comments.text), comments.number, "comments", 0, 1000000));
  for (std::size_t k = 1; k <= n_comments; ++k) {
    if (i + k >= text.size()) {
      text.fail(text.last_line_number(), "comments",
                fmt::format("the file ends inside the {} comment lines announced on line {}", n_comments,
                            comments.number));
    }
    if (!trim(text[i + k].text).starts_with('|')) {
      text.fail(text[i + k].number, "comments",
                fmt::format("comment line {} of the {} announced on line {} does not start with '|'", k, n_comments,
                            comments.number));
    }
  }
  i += n_comments + 1;

  if (i >= text.size()) text.fail(text.last_line_number(), "data", "the file ends before the data line");
  const Line& data = text[i];
  const auto words = split_whitespace(data.text);
  const auto layout = fortran_layout(data.text);
  if (words.size() < 3 || !contains_ci(data.text, " pts") || !layout) {
    text.fail(data.number, "data",
              fmt::format("expected a data line such as '42000 acceleration pts, approx 210 secs, "
                          "units=cm/sec2(04),Format=(1E15.6)', found {}",
                          detail::quoted(trim(data.text))));
  }
  b.data_line = i;
  b.npts = static_cast<std::size_t>(parse_integer(text, words[0], data.number, "pts", 1, 1'000'000'000));
  b.kind = to_lower(words[1]);
  b.layout = *layout;
  if (const std::size_t u = find_ci(data.text, "units="); u != std::string_view::npos) {
    const std::string_view rest = data.text.substr(u + 6);
    b.unit = std::string(trim(rest.substr(0, rest.find_first_of("(,"))));
  }

  // The block ends at its End-of-data line; the data are read later, for the chosen block only.
  b.end = i + 1;
  while (b.end < text.size() && !starts_with_ci(trim(text[b.end].text), "end-of-data")) ++b.end;
  if (b.end < text.size()) {
    // "End-of-data for ChanBNZ acceleration": the channel code.
    const std::string_view eod = trim(text[b.end].text);
    if (const std::size_t chan = find_ci(eod, "chan"); chan != std::string_view::npos) {
      b.meta.component = std::string(first_token(eod.substr(chan + 4)));
    }
  }
  if (b.meta.component.empty()) {
    // Text line 9: "Sta Chan   1: 90 deg (Rcrdr Chan  1) Location: ..."
    std::string_view chan = text_line(9);
    if (starts_with_ci(chan, "sta chan")) {
      chan = chan.substr(8);
      b.meta.component = collapse_spaces(chan.substr(0, find_ci(chan, "(rcrdr")));
    }
  }
  return b;
}

}  // namespace

bool looks_like_cosmos_v2(const std::vector<Line>& head) {
  return !head.empty() && contains_ci(head[0].text, "(format v") && contains_ci(head[0].text, "text lines");
}

GroundMotion read_cosmos_v2(const Text& text, const ReadOptions& options) {
  std::vector<Block> blocks;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && is_blank(text[i].text)) ++i;
    if (i >= text.size()) break;
    blocks.push_back(parse_block(text, i));
    i = blocks.back().end + 1;
  }
  std::vector<const Block*> accel;
  std::vector<std::string> names;
  for (const Block& b : blocks) {
    if (b.kind.starts_with("accel")) {
      accel.push_back(&b);
      names.push_back(b.meta.component);
    }
  }
  if (accel.empty()) {
    text.fail(text[blocks.front().data_line].number, "data",
              fmt::format("the file holds {} data, not acceleration", blocks.front().kind));
  }
  const Block& b = *accel[choose_channel(text, names, options.channel)];
  const Line& data = text[b.data_line];

  // Time step: Real header 62, ms.
  if (b.reals.size() < 62) {
    text.fail(data.number, "Real header 62",
              fmt::format("the real header holds {} values; the sampling interval is value 62", b.reals.size()));
  }
  const double dt_ms = b.reals.values[61];
  const std::size_t dt_line = b.reals.lines[61];
  if (dt_ms == kUnknown) {
    text.fail(dt_line, "Real header 62", "the sampling interval is unknown (-999)");
  }
  if (!(dt_ms > 0.0)) {
    text.fail(dt_line, "Real header 62", fmt::format("the sampling interval must be positive, got {} ms", dt_ms));
  }
  if (b.unit.empty()) {
    text.fail(data.number, "units", "the data line names no units (expected e.g. 'units=cm/sec2(04)')");
  }
  const double factor = file_unit_factor(text, b.unit, data.number, "units", options);

  Samples samples;
  const std::size_t next = read_count(
      text, b.data_line + 1, b.npts, b.layout, "acceleration", fmt::format("line {}", data.number),
      [](std::string_view s) { return starts_with_ci(trim(s), "end-of-data"); }, samples);
  for (std::size_t k = next; k < b.end; ++k) {
    if (!is_blank(text[k].text)) {
      text.fail(text[k].number, "acceleration",
                fmt::format("more values than the {} that line {} announces", b.npts, data.number));
    }
  }
  if (b.end >= text.size()) {
    text.fail(text.last_line_number(), "End-of-data", "the file ends without its 'End-of-data' line (truncated?)");
  }
  // "42000 acceleration pts, approx  210 secs": the duration is stated to whole seconds ("approx"), as npts x dt
  // (42000 x 5 ms = 210 s). A difference of more than a second and a sample is a wrong count or time step.
  if (const std::size_t approx = find_ci(data.text, "approx"); approx != std::string_view::npos) {
    const auto after = split_whitespace(data.text.substr(approx + 6));
    if (after.size() >= 2 && starts_with_ci(after[1], "sec")) {
      const double dt_s = dt_ms / 1000.0;
      check_declared_duration(text, parse_number(text, after[0], data.number, "approx secs"),
                              static_cast<double>(b.npts) * dt_s, 1.0 + dt_s, data.number, "approx secs",
                              fmt::format("pts x Real header 62 = {} x {} ms", b.npts, dt_ms));
    }
  }
  RecordMetadata meta = b.meta;
  meta.units_as_read = b.unit;
  return uniform_record(text, to_m_s2(text, samples, factor, "acceleration"), dt_ms / 1000.0, dt_line,
                        "Real header 62", std::move(meta), options);
}

}  // namespace topple::io::detail
