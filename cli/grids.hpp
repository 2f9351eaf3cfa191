#pragma once
// Grid options of `topple spectrum` and `topple fragility`: lists "a,b,c" and ranges "LO:HI:N", each value parsed
// by the caller's unit parser (so that "0.1g:1g:10" and "10cm:2m:20" carry their units). No physics here.
#include <charconv>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "topple/error.hpp"

namespace topple::cli {

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

/// "a,b,c" -> values (at least one).
inline std::vector<double> parse_list(const std::string& text, const std::string& option, const ValueParser& parse) {
  std::vector<double> out;
  for (const std::string& part : split(text, ',')) {
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

/// "LO:HI:N" -> its parts (N >= 1 an integer, LO <= HI).
inline Range parse_range(const std::string& text, const std::string& option, const ValueParser& parse) {
  const auto parts = split(text, ':');
  if (parts.size() != 3) {
    throw parameter_error(option, fmt::format("'{}' is not a range LOW:HIGH:COUNT (e.g. 0.1g:1g:20)", text));
  }
  Range r;
  r.lo = parse(parts[0], option);
  r.hi = parse(parts[1], option);
  int n = 0;
  const auto [ptr, ec] = std::from_chars(parts[2].data(), parts[2].data() + parts[2].size(), n);
  if (ec != std::errc{} || ptr != parts[2].data() + parts[2].size() || n < 1) {
    throw parameter_error(option, fmt::format("the count in '{}' must be a whole number >= 1", text));
  }
  r.n = static_cast<std::size_t>(n);
  if (!(r.lo <= r.hi)) throw parameter_error(option, fmt::format("'{}': LOW must not exceed HIGH", text));
  return r;
}

}  // namespace topple::cli
