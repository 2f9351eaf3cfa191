#pragma once
// Grid options of `topple spectrum` and `topple fragility`: lists "a,b,c" and ranges "LO:HI:N", each value parsed
// by the caller's unit parser (so that "0.1g:1g:10" and "10cm:2m:20" carry their units). No physics here.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple::cli {

/// The most points of one grid axis (a range's COUNT or a list's length): far beyond any figure or table a user
/// reads, and small enough that no grid asks for more memory than a laptop has (1e4 points of a spectrum: < 1 MB).
inline constexpr std::size_t kMaxGridPoints = 10'000;

using ValueParser = std::function<double(const std::string& text, const std::string& option)>;

/// A plain number (no unit), for options such as --mu.
inline double parse_number(const std::string& text, const std::string& option) {
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(v)) {
    throw parameter_error(option, fmt::format("'{}' is not a finite number", text));
  }
  return v;
}

inline std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : text) {
    if (c == sep) {
      parts.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

/// "a,b,c" -> values (at least one, at most kMaxGridPoints).
inline std::vector<double> parse_list(const std::string& text, const std::string& option, const ValueParser& parse) {
  std::vector<double> out;
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() > kMaxGridPoints) {
    throw parameter_error(option, fmt::format("{} values exceed the limit of {} points", parts.size(), kMaxGridPoints));
  }
  for (const std::string& part : parts) {
    if (part.empty()) throw parameter_error(option, fmt::format("empty value in the list '{}'", text));
    out.push_back(parse(part, option));
  }
  return out;
}

struct Range {
  double lo = 0.0;
  double hi = 0.0;
  std::size_t n = 0;
};

/// "LO:HI:N" -> its parts (1 <= N <= max_points an integer, LO <= HI).
inline Range parse_range(const std::string& text, const std::string& option, const ValueParser& parse,
                         std::size_t max_points = kMaxGridPoints) {
  const auto parts = split(text, ':');
  if (parts.size() != 3) {
    throw parameter_error(option, fmt::format("'{}' is not a range LOW:HIGH:COUNT (e.g. 0.1g:1g:20)", text));
  }
  Range r;
  r.lo = parse(parts[0], option);
  r.hi = parse(parts[1], option);
  std::size_t n = 0;
  const auto [ptr, ec] = std::from_chars(parts[2].data(), parts[2].data() + parts[2].size(), n);
  if (ec == std::errc::result_out_of_range || (ec == std::errc{} && ptr == parts[2].data() + parts[2].size() &&
                                               n > max_points)) {
    throw parameter_error(option, fmt::format("the count in '{}' exceeds the limit of {} points", text, max_points));
  }
  if (ec != std::errc{} || ptr != parts[2].data() + parts[2].size() || n < 1) {
    throw parameter_error(option, fmt::format("the count in '{}' must be a whole number >= 1", text));
  }
  r.n = n;
  if (!(r.lo <= r.hi)) throw parameter_error(option, fmt::format("'{}': LOW must not exceed HIGH", text));
  return r;
}

/// A 64-bit seed as typed: digits only (no sign, no wrap-around), at most 2^64 - 1. InputError naming `option`.
inline std::uint64_t parse_seed(const std::string& text, const std::string& option) {
  std::uint64_t v = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (text.empty() || ec != std::errc{} || ptr != text.data() + text.size()) {
    throw parameter_error(option, fmt::format("'{}' is not a seed: a whole number from 0 to 18446744073709551615",
                                              text));
  }
  return v;
}

/// Worker threads: 0 (every core) up to kMaxThreads. InputError naming `option`.
inline constexpr int kMaxThreads = 4096;
inline void check_threads(int threads, const std::string& option = "--threads") {
  if (threads < 0 || threads > kMaxThreads) {
    throw parameter_error(option, fmt::format("must be 0 (every core) to {}, got {}", kMaxThreads, threads));
  }
}

}  // namespace topple::cli
