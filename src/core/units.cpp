#include "topple/core/units.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple {
namespace {

struct UnitFactor {
  std::string_view unit;
  double factor;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return out;
}

/// Splits "4.5 cm" into (4.5, "cm"). Throws when there is no number or it is not finite.
std::pair<double, std::string> split_quantity(std::string_view text, const std::string& field, std::string_view kind) {
  const std::string_view s = trim(text);
  double value = 0.0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  if (!s.empty() && *first == '+') ++first;  // from_chars refuses a leading '+'
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc{} || ptr == first) {
    throw parameter_error(field, fmt::format("'{}' is not a {} (expected a number followed by a unit)", text, kind));
  }
  if (!std::isfinite(value)) throw parameter_error(field, fmt::format("'{}' is not finite", text));
  return {value, lower(trim(std::string_view(ptr, static_cast<std::size_t>(last - ptr))))};
}

template <std::size_t N>
double convert(std::string_view text, const std::string& field, std::string_view kind,
               const std::array<UnitFactor, N>& table) {
  const auto [value, unit] = split_quantity(text, field, kind);
  if (unit.empty()) {
    throw parameter_error(field, fmt::format("'{}' has no unit; write it with one, e.g. '{}{}'", text, value,
                                             table.front().unit));
  }
  for (const auto& [name, factor] : table) {
    if (unit == name) return value * factor;
  }
  std::string known;
  for (const auto& entry : table) known += (known.empty() ? "" : ", ") + std::string(entry.unit);
  throw parameter_error(field, fmt::format("unknown {} unit '{}' in '{}' (known: {})", kind, unit, text, known));
}

}  // namespace

double parse_length_m(std::string_view text, const std::string& field) {
  static constexpr std::array<UnitFactor, 6> table{{
      {"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"in", 0.0254}, {"ft", 0.3048}, {"km", 1000.0}}};
  return convert(text, field, "length", table);
}

double parse_area_m2(std::string_view text, const std::string& field) {
  static constexpr std::array<UnitFactor, 6> table{{
      {"m2", 1.0}, {"m^2", 1.0}, {"cm2", 1e-4}, {"cm^2", 1e-4}, {"mm2", 1e-6}, {"mm^2", 1e-6}}};
  return convert(text, field, "area", table);
}

double parse_acceleration_m_s2(std::string_view text, const std::string& field, double g_m_s2) {
  const std::array<UnitFactor, 8> table{{{"g", g_m_s2},
                                         {"m/s2", 1.0},
                                         {"m/s^2", 1.0},
                                         {"cm/s2", 0.01},
                                         {"cm/s^2", 0.01},
                                         {"gal", 0.01},
                                         {"mm/s2", 0.001},
                                         {"mm/s^2", 0.001}}};
  return convert(text, field, "acceleration", table);
}

double parse_duration_s(std::string_view text, const std::string& field) {
  static constexpr std::array<UnitFactor, 4> table{{{"s", 1.0}, {"ms", 1e-3}, {"sec", 1.0}, {"min", 60.0}}};
  return convert(text, field, "duration", table);
}

double parse_frequency_hz(std::string_view text, const std::string& field) {
  static constexpr std::array<UnitFactor, 3> table{{{"hz", 1.0}, {"khz", 1e3}, {"rad/s", 1.0 / (2.0 * kPi)}}};
  return convert(text, field, "frequency", table);
}

double parse_angle_rad(std::string_view text, const std::string& field) {
  static constexpr std::array<UnitFactor, 4> table{{{"deg", kPi / 180.0}, {"rad", 1.0}, {"°", kPi / 180.0},
                                                    {"degrees", kPi / 180.0}}};
  return convert(text, field, "angle", table);
}

double acceleration_unit_factor(std::string_view unit, const std::string& field, double g_m_s2) {
  const std::string u = lower(trim(unit));
  if (u == "g") return g_m_s2;
  if (u == "m/s2" || u == "m/s^2" || u == "m/s/s" || u == "m/sec2" || u == "m/sec/sec") return 1.0;
  if (u == "cm/s2" || u == "cm/s^2" || u == "cm/s/s" || u == "cm/sec2" || u == "cm/sec/sec" || u == "gal") return 0.01;
  if (u == "mm/s2" || u == "mm/s^2" || u == "mm/s/s") return 0.001;
  throw parameter_error(field, fmt::format("unknown acceleration unit '{}' (known: g, m/s2, cm/s2, gal, mm/s2)", unit));
}

}  // namespace topple
