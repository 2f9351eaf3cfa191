// Names of the choices a user makes about an object (sliding mode, rocking method, restitution, shape) and the body
// built from the dimensions a user gives: the one text <-> value mapping that the CLI, the Python module and the
// file readers share.
#include <charconv>
#include <cmath>

#include <fmt/format.h>

#include "topple/error.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"

namespace topple {

std::string_view sliding_mode_name(SlidingMode mode) {
  return mode == SlidingMode::one_way ? "one-way" : "two-way";
}

SlidingMode parse_sliding_mode(std::string_view name, const std::string& field) {
  if (name == "two-way") return SlidingMode::two_way;
  if (name == "one-way") return SlidingMode::one_way;
  throw parameter_error(field, fmt::format("unknown mode '{}' (known: two-way, one-way)", name));
}

std::string_view restitution_mode_name(RestitutionMode mode) {
  return mode == RestitutionMode::housner ? "housner" : "given";
}

std::string_view rocking_method_name(RockingMethod method) {
  return method == RockingMethod::rk4 ? "rk4" : "adaptive";
}

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

RockingBody::Shape parse_shape(std::string_view name, const std::string& field) {
  if (name == "block") return RockingBody::Shape::block;
  if (name == "cylinder") return RockingBody::Shape::cylinder;
  if (name == "general") return RockingBody::Shape::general;
  if (name.empty()) throw parameter_error(field, "the body's shape is required: block, cylinder or general");
  throw parameter_error(field, fmt::format("unknown shape '{}' (known: block, cylinder, general)", name));
}

RockingBody make_rocking_body(RockingBody::Shape shape, const BodyDimensions& d) {
  struct Dimension {
    const std::optional<double>& value;
    const char* field;
    bool area;
  };
  const Dimension all[] = {{d.width_m, "width", false}, {d.height_m, "height", false},
                           {d.diameter_m, "diameter", false}, {d.a_m, "a", false},
                           {d.h_m, "h", false},           {d.D_m2, "D", true},
                           {d.b1_m, "b1", false},         {d.b2_m, "b2", false},
                           {d.inertia_m2, "inertia", true}};
  const std::string_view name = shape_name(shape);
  // A general body is symmetric (a, h, D) unless one of the asymmetric fields is given (b1, b2, h, inertia).
  const bool asymmetric = shape == RockingBody::Shape::general && (d.b1_m || d.b2_m || d.inertia_m2);
  const auto needs = [&](std::string_view field) {
    switch (shape) {
      case RockingBody::Shape::block: return field == "width" || field == "height";
      case RockingBody::Shape::cylinder: return field == "diameter" || field == "height";
      case RockingBody::Shape::general:
        if (asymmetric) return field == "b1" || field == "b2" || field == "h" || field == "inertia";
        return field == "a" || field == "h" || field == "D";
    }
    return false;
  };
  for (const auto& [value, field, area] : all) {
    if (needs(field) && !value) throw parameter_error(field, fmt::format("shape {} needs {}", name, field));
  }
  for (const auto& [value, field, area] : all) {
    if (!needs(field) && value) {
      throw parameter_error(field, fmt::format("{} does not apply to shape {}{}", field, name,
                                               shape == RockingBody::Shape::general
                                                   ? " (it takes a, h, D, or b1, b2, h, inertia when asymmetric)"
                                                   : ""));
    }
  }
  for (const auto& [value, field, area] : all) {
    const double limit = area ? kMaxBodyDimension_m * kMaxBodyDimension_m : kMaxBodyDimension_m;
    if (value && !(std::abs(*value) <= limit)) {
      throw parameter_error(field, fmt::format("{} {} is beyond the largest body topple accepts ({} {})", *value,
                                               area ? "m2" : "m", limit, area ? "m2" : "m"));
    }
  }
  switch (shape) {
    case RockingBody::Shape::block: return RockingBody::block(*d.width_m, *d.height_m);
    case RockingBody::Shape::cylinder: return RockingBody::cylinder(*d.diameter_m, *d.height_m);
    case RockingBody::Shape::general:
      if (asymmetric) return RockingBody::general_asymmetric(*d.b1_m, *d.b2_m, *d.h_m, *d.inertia_m2);
      return RockingBody::general(*d.a_m, *d.h_m, *d.D_m2);
  }
  throw parameter_error("shape", "unknown shape");
}

}  // namespace topple
