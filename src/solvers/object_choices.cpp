// Names of the choices a user makes about an object (sliding mode, rocking method, restitution, shape) and the body
// built from the dimensions a user gives: the one text <-> value mapping that the CLI, the Python module and the
// file readers share.
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {

constexpr std::array<EnumName<SlidingMode>, 2> kSlidingModeNames{{
    {SlidingMode::two_way, "two-way"},
    {SlidingMode::one_way, "one-way"},
}};

std::string_view sliding_mode_name(SlidingMode mode) { return enum_name(kSlidingModeNames, mode); }

SlidingMode parse_sliding_mode(std::string_view name, const std::string& field) {
  if (name == "two-way") return SlidingMode::two_way;
  if (name == "one-way") return SlidingMode::one_way;
  throw parameter_error(field, fmt::format("unknown mode '{}' (known: two-way, one-way)", name));
}

constexpr std::array<EnumName<RestitutionMode>, 2> kRestitutionModeNames{{
    {RestitutionMode::housner, "housner"},
    {RestitutionMode::given, "given"},
}};

std::string_view restitution_mode_name(RestitutionMode mode) { return enum_name(kRestitutionModeNames, mode); }

constexpr std::array<EnumName<RockingMethod>, 2> kRockingMethodNames{{
    {RockingMethod::adaptive, "adaptive"},
    {RockingMethod::rk4, "rk4"},
}};

std::string_view rocking_method_name(RockingMethod method) { return enum_name(kRockingMethodNames, method); }

RockingMethod parse_rocking_method(std::string_view name, const std::string& field) {
  if (name == "adaptive") return RockingMethod::adaptive;
  if (name == "rk4") return RockingMethod::rk4;
  throw parameter_error(field, fmt::format("unknown method '{}' (known: adaptive, rk4)", name));
}

RestitutionChoice parse_restitution(std::string_view text, const std::string& field) {
  if (text == "housner") return {};
  double e = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), e);
  if (text.empty() || ec != std::errc{} || ptr != text.data() + text.size() || !std::isfinite(e)) {
    throw parameter_error(field, fmt::format("'{}' is neither a number in [0, 1] nor 'housner'", text));
  }
  return {RestitutionMode::given, e};
}

}  // namespace topple
