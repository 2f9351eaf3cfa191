// Shared line splitting and number parsing of the readers (see text_lines.hpp).
#include "io/text_lines.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <system_error>

#include <fmt/format.h>

#include "topple/core/units.hpp"

namespace topple::io::detail {

std::vector<Line> split_lines(std::string_view content, std::size_t max_lines) {
  constexpr std::string_view kBom = "\xEF\xBB\xBF";
  if (content.starts_with(kBom)) content.remove_prefix(kBom.size());
  // CSMIP V2 files end in 0x1A padding (CP/M end-of-file); it is not text.
  while (!content.empty() && content.back() == '\x1A') content.remove_suffix(1);
  std::vector<Line> lines;
  std::size_t number = 1;
  while (!content.empty() && lines.size() < max_lines) {
    const std::size_t nl = content.find('\n');
    std::string_view text = content.substr(0, nl);
    while (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    lines.push_back(Line{text, number++});
    if (nl == std::string_view::npos) break;
    content.remove_prefix(nl + 1);
  }
  return lines;
}

Text::Text(std::string_view content, std::string file) : file_(std::move(file)), lines_(split_lines(content)) {}

void Text::fail(std::size_t line, std::string_view field, const std::string& problem) const {
  throw InputError(InputLocation{.file = file_, .line = line, .field = std::string(field)}, problem);
}

void Text::fail_file(std::string_view field, const std::string& problem) const {
  throw InputError(InputLocation{.file = file_, .line = {}, .field = std::string(field)}, problem);
}

// ---- strings ----

namespace {
constexpr bool is_space(char c) noexcept { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
constexpr char lower_ascii(char c) noexcept { return (c >= 'A' && c <= 'Z') ? static_cast<char>(c - 'A' + 'a') : c; }
constexpr char upper_ascii(char c) noexcept { return (c >= 'a' && c <= 'z') ? static_cast<char>(c - 'a' + 'A') : c; }
}  // namespace

std::string_view trim(std::string_view s) noexcept {
  while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
  return trim_right(s);
}

std::string_view trim_right(std::string_view s) noexcept {
  while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
  return s;
}

bool is_blank(std::string_view s) noexcept { return trim(s).empty(); }

std::string to_lower(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = lower_ascii(c);
  return r;
}

std::string to_upper(std::string_view s) {
  std::string r(s);
  for (char& c : r) c = upper_ascii(c);
  return r;
}

std::size_t find_ci(std::string_view haystack, std::string_view needle, std::size_t from) noexcept {
  if (needle.size() > haystack.size()) return std::string_view::npos;
  for (std::size_t i = from; i + needle.size() <= haystack.size(); ++i) {
    bool match = true;
    for (std::size_t k = 0; k < needle.size(); ++k) {
      if (lower_ascii(haystack[i + k]) != lower_ascii(needle[k])) {
        match = false;
        break;
      }
    }
    if (match) return i;
  }
  return std::string_view::npos;
}

bool contains_ci(std::string_view haystack, std::string_view needle) noexcept {
  return find_ci(haystack, needle) != std::string_view::npos;
}

bool starts_with_ci(std::string_view s, std::string_view prefix) noexcept {
  return s.size() >= prefix.size() && find_ci(s.substr(0, prefix.size()), prefix) == 0;
}

std::string collapse_spaces(std::string_view s) {
  std::string r;
  bool pending_space = false;
  for (char c : trim(s)) {
    if (is_space(c)) {
      pending_space = true;
      continue;
    }
    if (pending_space) r += ' ';
    pending_space = false;
    r += c;
  }
  return r;
}

std::vector<std::string_view> split_whitespace(std::string_view s) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < s.size()) {
    while (i < s.size() && is_space(s[i])) ++i;
    const std::size_t begin = i;
    while (i < s.size() && !is_space(s[i])) ++i;
    if (i > begin) tokens.push_back(s.substr(begin, i - begin));
  }
  return tokens;
}

std::string quoted(std::string_view token) {
  constexpr std::size_t kMax = 40;
  std::string r = "'";
  for (std::size_t i = 0; i < token.size() && i < kMax; ++i) {
    const auto c = static_cast<unsigned char>(token[i]);
    if (c < 0x20 || c >= 0x7F || c == '\'') {
      r += fmt::format("\\x{:02X}", static_cast<unsigned>(c));
    } else {
      r += static_cast<char>(c);
    }
  }
  if (token.size() > kMax) r += "...";
  r += "'";
  return r;
}

// ---- numbers ----

namespace {

enum class NumberStatus { ok, not_a_number, not_finite, out_of_range };

/// The grammar accepted: [+-] digits [. digits] [(E|e|D|d) [+-] digits], with at least one digit in the mantissa.
/// Checked by hand first because std::from_chars also takes "inf", "nan" and hex-free oddities we want to name.
NumberStatus scan_number(std::string_view token, double& value) noexcept {
  if (token.empty() || token.size() > 400) return NumberStatus::not_a_number;
  std::array<char, 401> buffer{};
  std::size_t n = 0;
  std::size_t i = 0;
  if (token[i] == '+' || token[i] == '-') {
    if (token[i] == '-') buffer[n++] = '-';
    ++i;
  }
  std::size_t mantissa_digits = 0;
  while (i < token.size() && token[i] >= '0' && token[i] <= '9') {
    buffer[n++] = token[i++];
    ++mantissa_digits;
  }
  if (i < token.size() && token[i] == '.') {
    buffer[n++] = token[i++];
    while (i < token.size() && token[i] >= '0' && token[i] <= '9') {
      buffer[n++] = token[i++];
      ++mantissa_digits;
    }
  }
  if (mantissa_digits == 0) {
    const std::string_view word = token.substr(token.front() == '+' || token.front() == '-' ? 1 : 0);
    if (find_ci(word, "nan") == 0 || find_ci(word, "inf") == 0) {
      if (word.size() == 3 || (word.size() == 8 && find_ci(word, "infinity") == 0) ||
          (word.size() > 3 && find_ci(word, "nan(") == 0)) {
        return NumberStatus::not_finite;
      }
    }
    return NumberStatus::not_a_number;
  }
  if (i < token.size() && (token[i] == 'E' || token[i] == 'e' || token[i] == 'D' || token[i] == 'd')) {
    buffer[n++] = 'e';
    ++i;
    if (i < token.size() && (token[i] == '+' || token[i] == '-')) buffer[n++] = token[i++];
    std::size_t exponent_digits = 0;
    while (i < token.size() && token[i] >= '0' && token[i] <= '9') {
      buffer[n++] = token[i++];
      ++exponent_digits;
    }
    if (exponent_digits == 0) return NumberStatus::not_a_number;
  }
  if (i != token.size()) return NumberStatus::not_a_number;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(buffer.data(), buffer.data() + n, v, std::chars_format::general);
  if (ec == std::errc::result_out_of_range) return NumberStatus::out_of_range;
  if (ec != std::errc{} || ptr != buffer.data() + n) return NumberStatus::not_a_number;
  if (!std::isfinite(v)) return NumberStatus::not_finite;
  value = v;
  return NumberStatus::ok;
}

}  // namespace

std::optional<double> try_number(std::string_view token) noexcept {
  double v = 0.0;
  if (scan_number(token, v) != NumberStatus::ok) return std::nullopt;
  return v;
}

double parse_number(const Text& text, std::string_view token, std::size_t line, std::string_view field) {
  double v = 0.0;
  switch (scan_number(token, v)) {
    case NumberStatus::ok: return v;
    case NumberStatus::not_finite: text.fail(line, field, fmt::format("NaN or infinite value {}", detail::quoted(token)));
    case NumberStatus::out_of_range:
      text.fail(line, field, fmt::format("number {} is out of the range of double precision", detail::quoted(token)));
    case NumberStatus::not_a_number: break;
  }
  text.fail(line, field, fmt::format("not a number: {}", detail::quoted(token)));
}

long long parse_integer(const Text& text, std::string_view token, std::size_t line, std::string_view field,
                        long long lo, long long hi) {
  std::string_view digits = token;
  if (digits.starts_with('+')) digits.remove_prefix(1);
  long long v = 0;
  const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), v);
  if (digits.empty() || digits.starts_with('+') || ec == std::errc::invalid_argument ||
      ptr != digits.data() + digits.size()) {
    text.fail(line, field, fmt::format("not an integer: {}", detail::quoted(token)));
  }
  if (ec == std::errc::result_out_of_range || v < lo || v > hi) {
    text.fail(line, field, fmt::format("{} is out of range (expected {} to {})", detail::quoted(token), lo, hi));
  }
  return v;
}

void parse_values(const Text& text, const Line& line, const Layout& layout, std::string_view field, Samples& out) {
  if (layout.width == 0) {
    for (std::string_view token : split_whitespace(line.text)) out.push(parse_number(text, token, line.number, field), line.number);
    return;
  }
  const std::string_view s = trim_right(line.text);
  if (s.size() % layout.width != 0) {
    text.fail(line.number, field,
              fmt::format("values do not fit the {}-character columns of format {} (line is {} characters long)",
                          layout.width, layout.description, s.size()));
  }
  for (std::size_t at = 0; at < s.size(); at += layout.width) {
    const std::string_view cell = trim(s.substr(at, layout.width));
    if (cell.empty()) {
      text.fail(line.number, field,
                fmt::format("blank value in columns {}-{} (format {})", at + 1, at + layout.width, layout.description));
    }
    out.push(parse_number(text, cell, line.number, field), line.number);
  }
}

double unit_factor(const Text& text, std::string_view unit, std::size_t line, std::string_view field,
                   double g_m_s2) {
  try {
    return acceleration_unit_factor(unit, std::string(field), g_m_s2);
  } catch (const InputError& e) {
    text.fail(line, field, e.problem());
  }
}

double file_unit_factor(const Text& text, std::string_view unit, std::optional<std::size_t> line,
                        std::string_view field, const ReadOptions& options) {
  const auto fail = [&](const std::string& f, const std::string& problem) {
    if (line) text.fail(*line, f, problem);
    text.fail_file(f, problem);
  };
  double factor = 0.0;
  try {
    factor = acceleration_unit_factor(unit, std::string(field), options.g_m_s2);
  } catch (const InputError& e) {
    fail(std::string(field), e.problem());
  }
  if (!options.units.empty()) {
    double given = 0.0;
    try {
      given = acceleration_unit_factor(options.units, "--units", options.g_m_s2);
    } catch (const InputError& e) {
      text.fail_file("--units", e.problem());
    }
    // Equal factors (gal and cm/s2) agree; anything else would silently rescale the record.
    if (std::abs(given - factor) > 1e-12 * factor) {
      fail("--units", fmt::format("the file states its values in {} ({}); --units {} disagrees (leave --units out, "
                                  "or give the unit the file states)",
                                  detail::quoted(unit), field, detail::quoted(options.units)));
    }
  }
  return factor;
}

std::vector<double> to_m_s2(const Text& text, const Samples& samples, double factor, std::string_view field) {
  std::vector<double> out(samples.values.size());
  constexpr double kLimit = GroundMotionLimits::max_record_accel_m_s2;
  for (std::size_t i = 0; i < out.size(); ++i) {
    out[i] = samples.values[i] * factor;
    if (!std::isfinite(out[i]) || std::abs(out[i]) > kLimit) {
      text.fail(samples.lines[i], field,
                fmt::format("value {} is too large: x {} = {:.6g} m/s2, beyond the limit of {:.6g} m/s2 (100 g) of a "
                            "ground motion",
                            samples.values[i], factor, out[i], kLimit));
    }
  }
  return out;
}

GroundMotion uniform_record(const Text& text, std::vector<double> accel_m_s2, double dt_s,
                            std::optional<std::size_t> line, std::string_view field, RecordMetadata meta,
                            const ReadOptions& options) {
  using Limits = GroundMotionLimits;
  const auto fail = [&](std::string_view f, const std::string& problem) {
    if (line) text.fail(*line, f, problem);
    text.fail_file(f, problem);
  };
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    fail(field, fmt::format("the time step must be positive and finite, got {} s", dt_s));
  }
  if (accel_m_s2.size() > 1 && !std::isfinite(dt_s * static_cast<double>(accel_m_s2.size() - 1))) {
    fail(field, fmt::format("a time step of {} s over {} samples gives a record too long to represent", dt_s,
                            accel_m_s2.size()));
  }
  if (!(dt_s >= Limits::min_dt_s && dt_s <= Limits::max_dt_s)) {
    fail(field, fmt::format("the time step {:.6g} s is outside the limits [{:.6g}, {:.6g}] s of a ground motion",
                            dt_s, Limits::min_dt_s, Limits::max_dt_s));
  }
  if (accel_m_s2.size() > Limits::max_samples) {
    fail(field, fmt::format("{} samples, more than the limit of {} samples of a ground motion", accel_m_s2.size(),
                            Limits::max_samples));
  }
  const double duration = dt_s * static_cast<double>(accel_m_s2.size() - 1);
  if (!(duration <= Limits::max_duration_s)) {
    fail(field, fmt::format("{} samples at {:.6g} s last {:.6g} s, more than the limit of {:.6g} s (6 h) of a ground "
                            "motion",
                            accel_m_s2.size(), dt_s, duration, Limits::max_duration_s));
  }
  if (options.dt_s && !(std::abs(*options.dt_s - dt_s) <= 1e-6 * dt_s)) {
    fail("--dt", fmt::format("the file states a time step of {:.9g} s ({}); --dt {} disagrees (leave --dt out, or give "
                             "the file's time step)",
                             dt_s, field, *options.dt_s));
  }
  return GroundMotion::uniform(std::move(accel_m_s2), dt_s, 0.0, std::move(meta));
}

void check_declared_duration(const Text& text, double declared_s, double data_s, double tolerance_s,
                             std::size_t line, std::string_view field, std::string_view data_description) {
  if (!(std::abs(declared_s - data_s) <= tolerance_s)) {
    text.fail(line, field,
              fmt::format("the header declares {:.6g} s but the data hold {} = {:.6g} s (truncated or padded file, "
                          "or a wrong time step)",
                          declared_s, data_description, data_s));
  }
}

void require_no_more_values(const Text& text, std::size_t from, std::string_view count_field, std::size_t count) {
  for (std::size_t i = from; i < text.size(); ++i) {
    if (!is_blank(text[i].text)) {
      text.fail(text[i].number, count_field,
                fmt::format("more values than the {} that {} announces (unexpected {})", count, count_field,
                            detail::quoted(trim(text[i].text))));
    }
  }
}

std::size_t choose_channel(const Text& text, const std::vector<std::string>& names, const std::optional<int>& channel) {
  std::string list;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) list += ", ";
    list += names[i].empty() ? fmt::format("{}", i + 1) : fmt::format("{} ({})", i + 1, names[i]);
  }
  if (!channel) {
    if (names.size() == 1) return 0;
    text.fail_file("--channel",
                   fmt::format("the file holds {} channels: {}; choose one with --channel", names.size(), list));
  }
  if (*channel < 1 || static_cast<std::size_t>(*channel) > names.size()) {
    text.fail_file("--channel", fmt::format("there is no channel {}; the file holds {} channel{}: {}", *channel,
                                            names.size(), names.size() == 1 ? "" : "s", list));
  }
  return static_cast<std::size_t>(*channel - 1);
}

}  // namespace topple::io::detail
