// PEER NGA / PE&A ".AT2" accelerograms.
//
// Layout (SOURCES.md, "AT2, all variants"; PEER NGA-West2 flatfile documentation): four header lines, then the
// accelerations in g, five per line (E15.7), the last line short when NPTS is not a multiple of 5.
//   1  PEER NGA STRONG MOTION DATABASE RECORD
//   2  Imperial Valley-02, 5/19/1940, El Centro Array #9, 180      (event, date, station, component)
//   3  ACCELERATION TIME SERIES IN UNITS OF G
//   4  NPTS=   5372, DT=   .0100 SEC,      or  NPTS=  1500, DT= .02000 SEC   or  NPTS=   1451, dt=  .02000
//      or NPTS=   1991, DT=   .0100 SEC,   0 POLE @ ...    or (older files)  "  4164    0.0100    NPTS, DT"
// Values are separated by blanks in every variant, so the data are split on whitespace.
#include <optional>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

struct NptsDt {
  std::string_view npts;
  std::string_view dt;
};

/// The token after "KEY=" (blanks allowed around '='), ended by a blank or a comma.
std::optional<std::string_view> value_after_key(std::string_view line, std::string_view key) {
  for (std::size_t at = find_ci(line, key); at != std::string_view::npos; at = find_ci(line, key, at + 1)) {
    // "DT" must be a word of its own (not the tail of another word).
    if (at > 0) {
      const char before = line[at - 1];
      if ((before >= 'A' && before <= 'Z') || (before >= 'a' && before <= 'z')) continue;
    }
    std::size_t i = at + key.size();
    while (i < line.size() && line[i] == ' ') ++i;
    if (i >= line.size() || line[i] != '=') continue;
    ++i;
    while (i < line.size() && line[i] == ' ') ++i;
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != ',' && line[i] != '\t') ++i;
    if (i == begin) return std::nullopt;
    return line.substr(begin, i - begin);
  }
  return std::nullopt;
}

/// The NPTS and DT tokens of header line 4 in any of its forms, or nothing when the line is not such a line.
std::optional<NptsDt> find_npts_dt(std::string_view line) {
  const auto npts = value_after_key(line, "NPTS");
  const auto dt = value_after_key(line, "DT");
  if (npts && dt) return NptsDt{*npts, *dt};
  // Older form: the numbers first, then a label naming them in order ("4164  0.0100  NPTS, DT").
  const std::size_t label = line.find_first_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz");
  if (label == std::string_view::npos) return std::nullopt;
  const std::string names = to_upper(collapse_spaces(line.substr(label)));
  auto numbers = split_whitespace(line.substr(0, label));
  for (auto& n : numbers) {
    while (!n.empty() && n.back() == ',') n.remove_suffix(1);
  }
  if (numbers.size() != 2) return std::nullopt;
  if (names.starts_with("NPTS, DT") || names.starts_with("NPTS DT")) return NptsDt{numbers[0], numbers[1]};
  if (names.starts_with("DT, NPTS") || names.starts_with("DT NPTS")) return NptsDt{numbers[1], numbers[0]};
  return std::nullopt;
}

/// "Imperial Valley-02, 5/19/1940, El Centro Array #9, 180" (NGA-West2: event, date, station, component) or
/// "CAPE MENDOCINO 04/25/92 1806, CAPE MENDOCINO, 000 (CDMG STATION 89005)" (older: event and date, station,
/// component).
void metadata_from_line2(std::string_view line, RecordMetadata& meta) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (begin <= line.size()) {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(collapse_spaces(line.substr(begin, comma == std::string_view::npos ? line.size() - begin
                                                                                         : comma - begin)));
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
  if (fields.size() < 3) {
    meta.event = collapse_spaces(line);
    return;
  }
  const std::size_t n = fields.size();
  const std::size_t station_first = n >= 4 ? 2 : 1;
  meta.event = n >= 4 ? fields[0] + ", " + fields[1] : fields[0];
  for (std::size_t i = station_first; i + 1 < n; ++i) {
    if (!meta.station.empty()) meta.station += ", ";
    meta.station += fields[i];
  }
  // The component is the first word of the last field; anything after it ("(CDMG STATION 89005)") describes the
  // station.
  const auto words = split_whitespace(fields[n - 1]);
  if (!words.empty()) meta.component = std::string(words[0]);
  const std::size_t space = fields[n - 1].find(' ');
  if (space != std::string::npos) {
    meta.station.append(" ").append(std::string_view(fields[n - 1]).substr(space + 1));
  }
}

}  // namespace

bool looks_like_peer_at2(const std::vector<Line>& head) {
  return head.size() >= 4 && find_npts_dt(head[3].text).has_value();
}

GroundMotion read_peer_at2(const Text& text, const ReadOptions& options) {
  if (text.size() < 4) {
    text.fail(text.last_line_number(), "NPTS",
              "the file ends before line 4, the line of an AT2 file that gives NPTS and DT");
  }
  const Line& units_line = text[2];
  const Line& npts_line = text[3];

  // Line 3 states what the values are. AT2 values are accelerations in g; the sister files .VT2 and .DT2 hold
  // velocity and displacement with the same layout, and are refused rather than read as accelerations.
  const std::string what = to_upper(trim(units_line.text));
  if (what.starts_with("VELOCITY") || what.starts_with("DISPLACEMENT")) {
    text.fail(units_line.number, "units",
              fmt::format("this is a {} time series, not an acceleration record", to_lower(what.substr(0, what.find(' ')))));
  }
  std::string unit = "g";
  if (const std::size_t at = what.find("UNITS OF "); at != std::string::npos) {
    const auto words = split_whitespace(std::string_view(what).substr(at + 9));
    if (!words.empty()) {
      std::string_view word = words[0];
      while (!word.empty() && (word.back() == '.' || word.back() == ',')) word.remove_suffix(1);
      unit = to_lower(word);
    }
  }
  const double factor = file_unit_factor(text, unit, units_line.number, "units", options);

  const auto tokens = find_npts_dt(npts_line.text);
  if (!tokens) {
    text.fail(npts_line.number, "NPTS",
              fmt::format("expected NPTS and DT on line 4 (e.g. 'NPTS=   5372, DT=   .0100 SEC'), found {}",
                          detail::quoted(trim(npts_line.text))));
  }
  const auto npts = static_cast<std::size_t>(parse_integer(text, tokens->npts, npts_line.number, "NPTS", 0,
                                                           1'000'000'000));
  if (npts == 0) text.fail(npts_line.number, "NPTS", "NPTS is 0: the record has no samples");
  const double dt = parse_number(text, tokens->dt, npts_line.number, "DT");
  if (!(dt > 0.0)) text.fail(npts_line.number, "DT", fmt::format("DT must be positive, got {}", dt));

  Samples samples;
  const std::size_t next =
      read_count(text, 4, npts, Layout{}, "acceleration", "NPTS", [](std::string_view) { return false; }, samples);
  require_no_more_values(text, next, "NPTS", npts);

  RecordMetadata meta;
  metadata_from_line2(text[1].text, meta);
  meta.units_as_read = unit;
  return uniform_record(text, to_m_s2(text, samples, factor, "acceleration"), dt, npts_line.number, "DT",
                        std::move(meta), options);
}

}  // namespace topple::io::detail
