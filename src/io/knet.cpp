// NIED K-NET / KiK-net ASCII records (layout in SOURCES.md; NIED, "K-NET/KiK-net ASCII data format").
//
// 17 header lines, a label in columns 1-18 and its value after:
//   Origin Time       2018/01/24 19:51:00      (JST)
//   Station Code      AOM008
//   Sampling Freq(Hz) 100Hz                    dt = 1 / freq
//   Dir.              N-S                      KiK-net: 1-3 borehole, 4-6 surface (N-S, E-W, U-D)
//   Scale Factor      7845(gal)/8223790        acc[gal] = count * 7845 / 8223790
//   Memo.
// then integer counts, 8 per line; npts is not stated. NIED's own processing (and its "Max. Acc." header) removes
// the mean of the whole record, which also removes the digitiser's offset, so the reader does the same.
#include <cmath>
#include <optional>

#include <fmt/format.h>

#include "io/text_lines.hpp"

namespace topple::io::detail {
namespace {

constexpr std::size_t kHeaderLines = 17;
constexpr std::size_t kLabelWidth = 18;

/// The value of the header line whose label (columns 1-18) is `label`, with its line; nothing when absent.
std::optional<Line> header_value(const Text& text, std::string_view label) {
  for (std::size_t i = 0; i < kHeaderLines && i < text.size(); ++i) {
    const std::string_view s = text[i].text;
    if (trim(s.substr(0, std::min(s.size(), kLabelWidth))) == label) {
      return Line{trim(s.size() > kLabelWidth ? s.substr(kLabelWidth) : std::string_view{}), text[i].number};
    }
  }
  return std::nullopt;
}

Line required(const Text& text, std::string_view label) {
  auto v = header_value(text, label);
  if (!v) text.fail(std::min(text.last_line_number(), kHeaderLines), label, "missing header line");
  if (v->text.empty()) text.fail(v->number, label, "the header line has no value");
  return *v;
}

std::string kiknet_direction(std::string_view dir) {
  static constexpr std::string_view kNames[] = {"N-S", "E-W", "U-D"};
  if (dir.size() == 1 && dir[0] >= '1' && dir[0] <= '6') {
    const int d = dir[0] - '1';
    return fmt::format("{} ({}, Dir. {})", kNames[d % 3], d < 3 ? "borehole" : "surface", dir);
  }
  return std::string(dir);
}

}  // namespace

bool looks_like_knet(const std::vector<Line>& head) {
  if (head.empty() || !starts_with_ci(head[0].text, "Origin Time")) return false;
  for (std::size_t i = 0; i < head.size() && i < kHeaderLines; ++i) {
    if (starts_with_ci(head[i].text, "Scale Factor")) return true;
  }
  return false;
}

GroundMotion read_knet(const Text& text, const ReadOptions& options) {
  if (text.size() <= kHeaderLines) {
    text.fail(text.last_line_number(), "data", "the file ends inside or right after the 17 header lines: no data");
  }
  const Line freq = required(text, "Sampling Freq(Hz)");
  std::string_view f = freq.text;
  if (f.size() >= 2 && starts_with_ci(f.substr(f.size() - 2), "hz")) f.remove_suffix(2);
  const double hz = parse_number(text, trim(f), freq.number, "Sampling Freq(Hz)");
  if (!(hz > 0.0) || !std::isfinite(1.0 / hz)) {
    text.fail(freq.number, "Sampling Freq(Hz)", fmt::format("the sampling frequency must be positive, got {}", hz));
  }

  // "3920(gal)/6182761"
  const Line scale = required(text, "Scale Factor");
  const std::size_t unit = find_ci(scale.text, "(gal)/");
  if (unit == std::string_view::npos) {
    text.fail(scale.number, "Scale Factor",
              fmt::format("expected 'NUMERATOR(gal)/DENOMINATOR', found {}", detail::quoted(scale.text)));
  }
  const double numerator = parse_number(text, trim(scale.text.substr(0, unit)), scale.number, "Scale Factor");
  const double denominator = parse_number(text, trim(scale.text.substr(unit + 6)), scale.number, "Scale Factor");
  if (denominator == 0.0) text.fail(scale.number, "Scale Factor", "the denominator is zero");
  const double gal_per_count = numerator / denominator;
  if (!std::isfinite(gal_per_count)) text.fail(scale.number, "Scale Factor", "the scale factor is not finite");

  Samples counts;
  for (std::size_t i = kHeaderLines; i < text.size(); ++i) parse_values(text, text[i], Layout{}, "counts", counts);
  if (counts.size() == 0) text.fail(text.last_line_number(), "data", "no data after the 17 header lines");
  // "Duration Time(s)  143" with 200 Hz: 28600 counts. NIED records whole seconds, and the count is exactly
  // duration x frequency (AICH04: 143 s x 200 Hz = 28600; AOM008: 138 s x 100 Hz = 13800). A file cut anywhere,
  // even inside a number (the tail of "2516" read as 25), has fewer.
  const Line duration = required(text, "Duration Time(s)");
  const double seconds = parse_number(text, duration.text, duration.number, "Duration Time(s)");
  const double expected = seconds * hz;
  if (!(std::abs(expected - static_cast<double>(counts.size())) < 0.5)) {
    text.fail(duration.number, "Duration Time(s)",
              fmt::format("{} s at {} Hz announces {:.0f} counts but the data hold {} (truncated or padded file)",
                          seconds, hz, expected, counts.size()));
  }

  // Mean as the sum of count/n: no intermediate sum can overflow.
  double mean = 0.0;
  const auto n = static_cast<double>(counts.size());
  for (double c : counts.values) mean += c / n;
  Samples centred = counts;
  for (double& c : centred.values) c -= mean;

  RecordMetadata meta;
  const auto origin = header_value(text, "Origin Time");
  const auto magnitude = header_value(text, "Mag.");
  if (origin && !origin->text.empty()) {
    meta.event = std::string(origin->text) + " JST";
    if (magnitude && !magnitude->text.empty()) meta.event += fmt::format(", Mj {}", magnitude->text);
  }
  if (const auto station = header_value(text, "Station Code")) meta.station = std::string(station->text);
  if (const auto dir = header_value(text, "Dir.")) meta.component = kiknet_direction(dir->text);
  meta.units_as_read = fmt::format("counts*{}/{} gal, record mean removed", numerator, denominator);
  const double m_s2_per_gal = file_unit_factor(text, "gal", scale.number, "Scale Factor", options);
  return uniform_record(text, to_m_s2(text, centred, gal_per_count * m_s2_per_gal, "counts"), 1.0 / hz, freq.number,
                        "Sampling Freq(Hz)", std::move(meta), options);
}

}  // namespace topple::io::detail
