// ESM / ITACA ASCII records, "DYNA 1.2" header (layout in SOURCES.md; ESM, "ASCII format description").
//
// 64 "KEY: value" lines (EVENT_NAME, NETWORK, STATION_CODE, SAMPLING_INTERVAL_S, NDATA, STREAM, UNITS: cm/s^2,
// DATA_TYPE: ACCELERATION, ...), then the values, one per line. The header is read by key, not by position, and ends
// at the first line that is not "KEY: value".
#include <cmath>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

/// "KEY: value" with KEY in upper case letters, digits and the punctuation ESM uses ("_/^-."): the key, else "".
std::string_view key_of(std::string_view s) {
  const std::size_t colon = s.find(':');
  if (colon == std::string_view::npos || colon == 0) return {};
  const std::string_view key = s.substr(0, colon);
  for (char c : key) {
    const bool ok = (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '/' || c == '^' ||
                    c == '-' || c == '.';
    if (!ok) return {};
  }
  // A key has at least one letter (so that "12:30" is not a key).
  for (char c : key) {
    if (c >= 'A' && c <= 'Z') return key;
  }
  return {};
}

struct Entry {
  std::string_view value;
  std::size_t line = 0;
};

}  // namespace

bool looks_like_esm(const std::vector<Line>& head) {
  if (head.empty() || key_of(head[0].text).empty()) return false;
  for (const Line& line : head) {
    if (key_of(line.text) == "SAMPLING_INTERVAL_S") return true;
  }
  return false;
}

GroundMotion read_esm(const Text& text, const ReadOptions& options) {
  std::map<std::string_view, Entry> header;
  std::size_t i = 0;
  for (; i < text.size(); ++i) {
    const std::string_view key = key_of(text[i].text);
    if (key.empty()) break;
    header.emplace(key, Entry{trim(text[i].text.substr(key.size() + 1)), text[i].number});
  }
  const std::size_t header_end = i == 0 ? 1 : text[i - 1].number;
  auto get = [&](std::string_view key) -> std::optional<Entry> {
    const auto it = header.find(key);
    if (it == header.end() || it->second.value.empty()) return std::nullopt;
    return it->second;
  };
  auto required = [&](std::string_view key) -> Entry {
    const auto e = get(key);
    if (!e) text.fail(header_end, key, "missing from the header (or empty)");
    return *e;
  };

  if (const auto type = get("DATA_TYPE"); type && !contains_ci(type->value, "ACCELERATION")) {
    text.fail(type->line, "DATA_TYPE", fmt::format("this file holds {}, not acceleration", detail::quoted(type->value)));
  }
  const Entry dt_entry = required("SAMPLING_INTERVAL_S");
  const double dt = parse_number(text, dt_entry.value, dt_entry.line, "SAMPLING_INTERVAL_S");
  if (!(dt > 0.0)) {
    text.fail(dt_entry.line, "SAMPLING_INTERVAL_S", fmt::format("the sampling interval must be positive, got {}", dt));
  }
  const Entry n_entry = required("NDATA");
  const auto npts = static_cast<std::size_t>(parse_integer(text, n_entry.value, n_entry.line, "NDATA", 1,
                                                           1'000'000'000));
  const Entry units = required("UNITS");
  const double factor = file_unit_factor(text, units.value, units.line, "UNITS", options);

  Samples samples;
  const std::size_t next =
      read_count(text, i, npts, Layout{}, "acceleration", "NDATA", [](std::string_view) { return false; }, samples);
  require_no_more_values(text, next, "NDATA", npts);
  // DURATION_S is NDATA x SAMPLING_INTERVAL_S (HI.ARS1: 19128 x 0.005 = 95.640), printed to 1 ms: a difference
  // beyond one sample interval means the header and the data disagree.
  if (const auto declared = get("DURATION_S")) {
    check_declared_duration(text, parse_number(text, declared->value, declared->line, "DURATION_S"),
                            static_cast<double>(npts) * dt, dt + 1e-3, declared->line, "DURATION_S",
                            fmt::format("NDATA x SAMPLING_INTERVAL_S = {} x {}", npts, dt));
  }

  RecordMetadata meta;
  std::string event;
  for (std::string_view key : {"EVENT_NAME", "EVENT_DATE_YYYYMMDD", "EVENT_TIME_HHMMSS"}) {
    if (const auto e = get(key)) {
      if (!event.empty()) event.push_back(' ');
      event.append(e->value);
    }
  }
  if (event.empty()) {
    if (const auto e = get("EVENT_ID")) event = std::string(e->value);
  }
  meta.event = event;
  const auto network = get("NETWORK");
  const auto code = get("STATION_CODE");
  const auto name = get("STATION_NAME");
  if (code) meta.station = network ? fmt::format("{}.{}", network->value, code->value) : std::string(code->value);
  if (name) meta.station += meta.station.empty() ? std::string(name->value) : fmt::format(" ({})", name->value);
  if (const auto stream = get("STREAM")) meta.component = std::string(stream->value);
  meta.units_as_read = std::string(units.value);
  return uniform_record(text, to_m_s2(text, samples, factor, "acceleration"), dt, dt_entry.line,
                        "SAMPLING_INTERVAL_S", std::move(meta), options);
}

}  // namespace topple::io::detail
