// CSMIP / CDMG "DMG" V2 corrected records (layout in SOURCES.md; CDMG OSMS report 84-xx on the V2 volume format).
//
// One file holds several channels (three for a free-field station), each a block of:
//   25 text lines            line 1 "CORRECTED ACCELEROGRAM  36456-S4384-83123.01  CHAN  1:  90 DEG  FROM",
//                            line 3 event, line 6 "STATION NO. 36456 ...", line 7 station name, line 8 "CHAN  1:  90 DEG"
//   100 integers (16I5), 100 reals (8F10.3)
//   " 3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)"  then 8F10.3 values
//   the same for VELOC (cm/s) and DISPL (cm)
//   "/&  ----------  END OF DATA FOR CHANNEL  1  ----------"
// Lines end in CRLF and the file is padded with 0x1A (both handled by split_lines). Only the ACCEL section is read;
// channel blocks are found by their END OF DATA lines, so the fixed header sizes are not relied on.
#include <optional>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

constexpr std::string_view kAccelSection = "POINTS OF ACCEL DATA";
constexpr std::string_view kEndOfChannel = "END OF DATA FOR CHANNEL";

struct Channel {
  std::size_t first = 0;  ///< index of the block's first line
  std::size_t end = 0;    ///< index of its END OF DATA line
  std::string name;       ///< component as the file names it ("90 DEG", "UP")
};

bool ends_section(std::string_view s) { return contains_ci(s, "POINTS OF") || contains_ci(s, kEndOfChannel); }

/// "CHAN  1:  90 DEG     FROM" -> {1, "90 DEG"}.
std::optional<std::pair<std::string, std::string>> parse_chan(std::string_view s) {
  const std::size_t at = find_ci(s, "CHAN");
  if (at == std::string_view::npos) return std::nullopt;
  const std::string_view rest = s.substr(at + 4);
  const std::size_t colon = rest.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  std::string_view name = rest.substr(colon + 1);
  name = name.substr(0, find_ci(name, " FROM"));
  return std::pair{collapse_spaces(rest.substr(0, colon)), collapse_spaces(name)};
}

std::vector<Channel> find_channels(const Text& text) {
  std::vector<Channel> channels;
  std::size_t i = 0;
  while (true) {
    while (i < text.size() && is_blank(text[i].text)) ++i;
    if (i >= text.size()) break;
    Channel c;
    c.first = i;
    while (i < text.size() && !contains_ci(text[i].text, kEndOfChannel)) ++i;
    if (i >= text.size()) {
      text.fail(text.last_line_number(), "channel",
                fmt::format("the channel block starting at line {} has no 'END OF DATA FOR CHANNEL' line: the file "
                            "is truncated",
                            text[c.first].number));
    }
    c.end = i;
    // The channel line: line 8 of the block ("CHAN  1:  90 DEG"), else the end of line 1.
    std::optional<std::pair<std::string, std::string>> chan;
    for (std::size_t k = c.first; k < c.end && k < c.first + 25 && !chan; ++k) {
      if (starts_with_ci(trim(text[k].text), "CHAN")) chan = parse_chan(text[k].text);
    }
    if (!chan) chan = parse_chan(text[c.first].text);
    if (chan) {
      const std::string position = std::to_string(channels.size() + 1);
      c.name = chan->first == position ? chan->second : fmt::format("CHAN {}: {}", chan->first, chan->second);
    }
    channels.push_back(std::move(c));
    ++i;
  }
  return channels;
}

}  // namespace

bool looks_like_csmip_v2(const std::vector<Line>& head) {
  for (const Line& line : head) {
    if (contains_ci(line.text, "POINTS OF ACCEL DATA EQUALLY SPACED")) return true;
  }
  return false;
}

GroundMotion read_csmip_v2(const Text& text, const ReadOptions& options) {
  const std::vector<Channel> channels = find_channels(text);
  std::vector<std::string> names;
  for (const Channel& c : channels) names.push_back(c.name);
  const std::size_t chosen = choose_channel(text, names, options.channel);
  const Channel& c = channels[chosen];

  std::size_t s = c.first;
  while (s < c.end && !contains_ci(text[s].text, kAccelSection)) ++s;
  if (s >= c.end) {
    text.fail(text[c.first].number, "ACCEL",
              fmt::format("channel {} has no '{}' line", chosen + 1, kAccelSection));
  }
  // " 3251 POINTS OF ACCEL DATA EQUALLY SPACED AT  .020 SEC.  (UNITS: CM/SEC/SEC)"
  const Line& section = text[s];
  const auto words = split_whitespace(section.text);
  const auto npts = static_cast<std::size_t>(
      parse_integer(text, words.empty() ? std::string_view{} : words[0], section.number, "POINTS", 1, 1'000'000'000));
  const std::size_t at = find_ci(section.text, "SPACED AT");
  if (at == std::string_view::npos) {
    text.fail(section.number, "DT", "expected 'EQUALLY SPACED AT <dt> SEC' on the ACCEL data line");
  }
  const auto dt_words = split_whitespace(section.text.substr(at + 9));
  const double dt = parse_number(text, dt_words.empty() ? std::string_view{} : dt_words[0], section.number, "DT");
  if (!(dt > 0.0)) text.fail(section.number, "DT", fmt::format("the time step must be positive, got {}", dt));
  const std::size_t units_at = find_ci(section.text, "UNITS:");
  if (units_at == std::string_view::npos) {
    text.fail(section.number, "UNITS", "the ACCEL data line names no units (expected '(UNITS: CM/SEC/SEC)')");
  }
  const std::string_view unit_text = section.text.substr(units_at + 6);
  const std::string unit = to_lower(trim(unit_text.substr(0, unit_text.find(')'))));
  const double factor = file_unit_factor(text, unit, section.number, "UNITS", options);

  Samples samples;
  const std::size_t next =
      read_count(text, s + 1, npts, Layout{10, "8F10.3"}, "ACCEL", "POINTS", ends_section, samples);
  for (std::size_t k = next; k < c.end && !ends_section(text[k].text); ++k) {
    if (!is_blank(text[k].text)) {
      text.fail(text[k].number, "ACCEL", fmt::format("more values than the {} POINTS of line {}", npts,
                                                     section.number));
    }
  }

  RecordMetadata meta;
  auto block_line = [&](std::size_t k) -> std::string_view {  // 1-based line of the block's text header
    return c.first + k - 1 < c.end ? text[c.first + k - 1].text : std::string_view{};
  };
  const std::string_view date = block_line(4);
  meta.event = collapse_spaces(block_line(3));
  if (const std::string d = collapse_spaces(date.substr(0, date.find('('))); !d.empty()) meta.event += ", " + d;
  const std::string_view station_no = block_line(6);
  std::string station;
  if (const std::size_t no = find_ci(station_no, "STATION NO."); no != std::string_view::npos) {
    const auto tokens = split_whitespace(station_no.substr(no + 11));
    if (!tokens.empty()) station = std::string(tokens[0]) + " ";
  }
  meta.station = station + collapse_spaces(block_line(7));
  meta.component = c.name;
  meta.units_as_read = unit;
  return uniform_record(text, to_m_s2(text, samples, factor, "ACCEL"), dt, section.number, "DT", std::move(meta),
                        options);
}

}  // namespace topple::io::detail
