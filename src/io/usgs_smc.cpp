// USGS SMC ("strong-motion card") files (layout in SOURCES.md; USGS Open-File Report 2000-0350 / the SMC format
// description of the National Strong-Motion Project).
//
//   lines 1-11   text; line 1 "2 CORRECTED ACCELEROGRAM" (the leading code is the data type), line 4 date and
//                event, line 6 "station = ..., component= 360"
//   lines 12-17  48 integers (8I10); #16 = number of comment lines, #17 = number of samples (1-based)
//   lines 18-27  50 reals (5E15.7); #2 = sampling rate, samples/s
//   comments     lines starting with '|'
//   data         8E10.4, fixed width with no blank between values ("1.5057E+0-2.2223E+0"), cm/s^2
// Missing values are -32768 (integers) and 1.7E38 (reals).
#include <cmath>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

constexpr double kMissingInt = -32768.0;
constexpr double kMissingReal = 1.7e38;
constexpr std::size_t kTextLines = 11;
constexpr std::size_t kIntLines = 6;
constexpr std::size_t kRealLines = 10;

/// Integer header value #k (1-based), refusing the missing-value marker.
std::size_t header_integer(const Text& text, const Samples& ints, std::size_t k, std::string_view what,
                           long long lo) {
  const std::string field = fmt::format("integer header #{}", k);
  const double v = ints.values[k - 1];
  const std::size_t line = ints.lines[k - 1];
  if (v == kMissingInt) text.fail(line, field, fmt::format("the {} is missing (-32768)", what));
  if (!(v >= static_cast<double>(lo) && v <= 1e9) || v != std::floor(v)) {
    text.fail(line, field, fmt::format("the {} must be an integer of at least {}, got {}", what, lo, v));
  }
  return static_cast<std::size_t>(v);
}

}  // namespace

bool looks_like_usgs_smc(const std::vector<Line>& head) {
  // Line 1 is a one-digit data-type code and its name, e.g. "2 CORRECTED ACCELEROGRAM", "3 VELOCITY".
  if (head.size() < kTextLines + kIntLines) return false;
  const std::string_view l1 = head[0].text;
  if (l1.size() < 3 || l1[0] < '0' || l1[0] > '9' || l1[1] != ' ') return false;
  const std::string_view name = trim(l1.substr(2));
  return contains_ci(name, "ACCELEROGRAM") || starts_with_ci(name, "VELOCITY") ||
         starts_with_ci(name, "DISPLACEMENT") || contains_ci(name, "SPECTR");
}

GroundMotion read_usgs_smc(const Text& text, const ReadOptions& options) {  // values are always cm/s^2
  constexpr std::size_t kFirstData = kTextLines + kIntLines + kRealLines;  // index of the first comment line
  if (text.size() < kFirstData) {
    text.fail(text.last_line_number(), "header",
              fmt::format("the file ends inside the {}-line SMC header", kFirstData));
  }
  // Data type: 1 = uncorrected, 2 = corrected accelerogram; 3, 4 are velocity and displacement, others spectra.
  const Line& l1 = text[0];
  const std::string_view type = trim(l1.text);
  if (type.empty() || (type[0] != '1' && type[0] != '2') || !contains_ci(type, "ACCELEROGRAM")) {
    text.fail(l1.number, "data type",
              fmt::format("this SMC file holds {}, not an accelerogram (type 1 or 2)", detail::quoted(type)));
  }

  Samples ints;
  for (std::size_t k = 0; k < kIntLines; ++k) {
    parse_values(text, text[kTextLines + k], Layout{10, "8I10"}, "integer header", ints);
  }
  if (ints.size() < 17) {
    text.fail(text[kTextLines + kIntLines - 1].number, "integer header",
              fmt::format("{} integers in lines 12-17 where 48 are expected", ints.size()));
  }
  Samples reals;
  for (std::size_t k = 0; k < kRealLines; ++k) {
    parse_values(text, text[kTextLines + kIntLines + k], Layout{15, "5E15.7"}, "real header", reals);
  }
  if (reals.size() < 2) {
    text.fail(text[kFirstData - 1].number, "real header",
              fmt::format("{} reals in lines 18-27 where 50 are expected", reals.size()));
  }
  const std::size_t n_comments = header_integer(text, ints, 16, "number of comment lines", 0);
  const std::size_t npts = header_integer(text, ints, 17, "number of samples", 1);
  const double rate = reals.values[1];
  if (rate >= kMissingReal) text.fail(reals.lines[1], "real header #2", "the sampling rate is missing (1.7E38)");
  if (!(rate > 0.0) || !std::isfinite(1.0 / rate)) {
    text.fail(reals.lines[1], "real header #2", fmt::format("the sampling rate must be positive, got {}", rate));
  }

  for (std::size_t k = 0; k < n_comments; ++k) {
    const std::size_t i = kFirstData + k;
    if (i >= text.size()) {
      text.fail(text.last_line_number(), "comments",
                fmt::format("the file ends inside the {} comment lines of integer header #16", n_comments));
    }
    if (!text[i].text.starts_with('|')) {
      text.fail(text[i].number, "comments",
                fmt::format("comment line {} of the {} that integer header #16 announces does not start with '|'",
                            k + 1, n_comments));
    }
  }
  Samples samples;
  const std::size_t next = read_count(text, kFirstData + n_comments, npts, Layout{10, "8E10.4"}, "acceleration",
                                      "integer header #17", [](std::string_view) { return false; }, samples);
  require_no_more_values(text, next, "integer header #17", npts);

  RecordMetadata meta;
  meta.event = collapse_spaces(text[3].text);
  // "station = San Francisco, 1295 Shafter, F component=    360"
  const std::string_view station_line = text[5].text;
  const std::size_t comp = find_ci(station_line, "component=");
  const std::size_t eq = station_line.find('=');
  if (eq != std::string_view::npos && starts_with_ci(trim(station_line), "station")) {
    const std::size_t stop = comp == std::string_view::npos || comp < eq ? std::string_view::npos : comp - eq - 1;
    meta.station = collapse_spaces(station_line.substr(eq + 1, stop));
  }
  if (comp != std::string_view::npos) meta.component = collapse_spaces(station_line.substr(comp + 10));
  meta.units_as_read = "cm/s2";
  const double factor = file_unit_factor(text, "cm/s2", std::nullopt, "units", options);
  return uniform_record(text, to_m_s2(text, samples, factor, "acceleration"), 1.0 / rate, reals.lines[1],
                        "real header #2", std::move(meta), options);
}

}  // namespace topple::io::detail
