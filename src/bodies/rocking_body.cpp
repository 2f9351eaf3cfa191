// The rocking body's factories and the body built from a user's dimensions (topple/bodies/rocking_body.hpp).
#include "topple/bodies/rocking_body.hpp"

#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {
RockingBody RockingBody::block(double width_m, double height_m) {
  require_positive(width_m, "width", "width");
  require_positive(height_m, "height", "height");
  const double a = 0.5 * width_m;
  const double h = 0.5 * height_m;
  return RockingBody{Shape::block, a, h, 4.0 / 3.0 * (a * a + h * h), std::nullopt};  // thesis eq 3.14
}

RockingBody RockingBody::cylinder(double diameter_m, double height_m) {
  require_positive(diameter_m, "diameter", "diameter");
  require_positive(height_m, "height", "height");
  const double a = 0.5 * diameter_m;
  const double h = 0.5 * height_m;
  return RockingBody{Shape::cylinder, a, h, (15.0 * a * a + 16.0 * h * h) / 12.0, std::nullopt};  // thesis eq 3.13
}

RockingBody RockingBody::general(double a_m, double h_m, double D_m2) {
  require_positive(a_m, "a", "a (CM to pivot edge)");
  require_positive(h_m, "h", "h (CM height)");
  require_positive(D_m2, "D", "D (pivot moment of inertia per unit mass)");
  const double r2 = a_m * a_m + h_m * h_m;
  // Parallel axes: D = a^2 + h^2 + I_cm/m. Allow round-off of the factories' own arithmetic.
  if (D_m2 < r2 * (1.0 - 8.0 * std::numeric_limits<double>::epsilon())) {
    throw parameter_error("D", fmt::format("D = {:.6g} m2 is below a^2 + h^2 = {:.6g} m2: no real body has a "
                                           "negative moment of inertia about its centre of mass",
                                           D_m2, r2));
  }
  return RockingBody{Shape::general, a_m, h_m, D_m2, std::nullopt};
}

RockingBody RockingBody::general_asymmetric(double b1_m, double b2_m, double h_m, double k2_m2) {
  require_positive(b1_m, "b1", "b1 (CM to the pivot O-, theta < 0)");
  require_positive(b2_m, "b2", "b2 (CM to the pivot O+, theta > 0)");
  require_positive(h_m, "h", "h (CM height)");
  if (!std::isfinite(k2_m2) || k2_m2 < 0.0) {
    throw parameter_error("inertia", fmt::format("I_cm / m must be >= 0 and finite (m2), got {}", k2_m2));
  }
  // Parallel axes about each pivot.
  RockingBody body{Shape::general, b2_m, h_m, k2_m2 + b2_m * b2_m + h_m * h_m, std::nullopt};
  body.negative_pivot = Pivot{b1_m, k2_m2 + b1_m * b1_m + h_m * h_m};
  return body;
}

RockingBody RockingBody::side_body(int side) const {
  return RockingBody{shape, pivot_b_m(side), h_m, pivot_D_m2(side), std::nullopt};
}

double RockingBody::alpha_rad() const noexcept { return std::atan2(a_m, h_m); }
double RockingBody::R_m() const noexcept { return std::hypot(a_m, h_m); }
double RockingBody::p_rad_s(double g_m_s2) const noexcept { return std::sqrt(g_m_s2 * R_m() / D_m2); }

constexpr std::array<EnumName<RockingBody::Shape>, 3> kShapeNames{{
    {RockingBody::Shape::block, "block"},
    {RockingBody::Shape::cylinder, "cylinder"},
    {RockingBody::Shape::general, "general"},
}};

std::string_view shape_name(RockingBody::Shape shape) { return enum_name(kShapeNames, shape); }

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
