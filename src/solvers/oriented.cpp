// Oriented rocking objects under a motion set: planar runs along the object's directions (oriented.hpp).
#include "topple/solvers/oriented.hpp"

#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {
namespace {

/// An azimuth in [0, 360).
double wrap_azimuth(double deg) {
  const double r = std::fmod(deg, 360.0);
  return r < 0.0 ? r + 360.0 : r;
}

}  // namespace

constexpr std::array<EnumName<OrientedAxis>, 3> kOrientedAxisNames{{
    {OrientedAxis::bearing, "bearing"},
    {OrientedAxis::across, "across"},
    {OrientedAxis::grid, "grid"},
}};

std::string_view oriented_axis_name(OrientedAxis axis) { return enum_name(kOrientedAxisNames, axis); }

OrientedBody OrientedBody::planar(const RockingBody& body) { return OrientedBody{body, std::nullopt}; }

OrientedBody OrientedBody::box(double width_m, double depth_m, double height_m) {
  const RockingBody along = RockingBody::block(width_m, height_m);
  const RockingBody across = [&] {
    try {
      return RockingBody::block(depth_m, height_m);
    } catch (const InputError& e) {
      // The other axis is a block of width `depth`: say so in the user's terms.
      if (e.where().field == "width") throw parameter_error("depth", e.problem());
      throw;
    }
  }();
  return OrientedBody{along, across};
}

OrientedBody OrientedBody::make(const RockingBody& body, std::optional<double> depth_m) {
  if (!depth_m) return planar(body);
  if (body.shape != RockingBody::Shape::block) {
    throw parameter_error("depth", fmt::format("a depth applies to a block (a box) only, not to a {}: {}",
                                               shape_name(body.shape),
                                               body.shape == RockingBody::Shape::cylinder
                                                   ? "a cylinder is taken in its worst direction"
                                                   : "a general body rocks in one plane"));
  }
  // block(width, height) stored a = width / 2, h = height / 2.
  return box(2.0 * body.a_m, *depth_m, 2.0 * body.h_m);
}

void check_orientation(const OrientedBody& body, std::optional<double> bearing_deg, bool step_given) {
  if (body.axisymmetric() && bearing_deg) {
    throw parameter_error("bearing", "a cylinder has no bearing: it is taken in its worst direction (every "
                                     "direction step, default 15 deg)");
  }
  if (!body.axisymmetric() && !bearing_deg) {
    throw parameter_error("bearing", "required under two components: the direction across the object's narrow side, "
                                     "degrees clockwise from north (the +x side of its planar body)");
  }
  if (!body.axisymmetric() && step_given) {
    throw parameter_error("cylinder_step", "applies to a cylinder only (the others rock along their bearing)");
  }
}

const RockingBody& planar_body_of(const OrientedBody& body, OrientedAxis axis) {
  if (axis == OrientedAxis::across) {
    if (!body.across) throw parameter_error("depth", "the body has no other axis (not a box)");
    return *body.across;
  }
  return body.body;
}

std::vector<std::pair<double, OrientedAxis>> oriented_directions(const OrientedBody& body, double bearing_deg,
                                                                 const OrientationOptions& orientation) {
  std::vector<std::pair<double, OrientedAxis>> out;
  if (body.axisymmetric()) {
    const double step = orientation.cylinder_step_deg;
    const double n = std::isfinite(step) && step > 0.0 ? 180.0 / step : 0.0;
    if (!(step > 0.0 && step <= 180.0) || std::abs(n - std::round(n)) > 1e-9 * n) {
      throw parameter_error("cylinder_step", fmt::format("the direction step must be in (0, 180] deg and divide 180, "
                                                         "got {} deg", step));
    }
    const auto count = static_cast<int>(std::round(n));
    for (int k = 0; k < count; ++k) out.emplace_back(static_cast<double>(k) * (180.0 / count), OrientedAxis::grid);
    return out;
  }
  if (!std::isfinite(bearing_deg)) {
    throw parameter_error("bearing", fmt::format("the bearing must be finite, got {} deg", bearing_deg));
  }
  out.emplace_back(wrap_azimuth(bearing_deg), OrientedAxis::bearing);
  if (body.across) out.emplace_back(wrap_azimuth(bearing_deg + 90.0), OrientedAxis::across);
  return out;
}

bool more_severe(const RockingSummary& x, const RockingSummary& y) noexcept {
  if (x.overturned != y.overturned) return x.overturned;
  if (x.overturned) return x.overturn_time_s.value_or(0.0) < y.overturn_time_s.value_or(0.0);
  return x.max_rotation_over_alpha > y.max_rotation_over_alpha;
}

OrientedRockingSummary rock_oriented_summary(const MotionSet& set, const OrientedBody& body, double bearing_deg,
                                             const RockingOptions& options, const OrientationOptions& orientation) {
  const auto directions = oriented_directions(body, bearing_deg, orientation);
  if (!set.has_second()) {
    throw parameter_error("second", "an oriented object needs both horizontal components: the motion along its "
                                    "directions is their projection (the motion set has one)");
  }
  OrientedRockingSummary out;
  out.directions.reserve(directions.size());
  for (const auto& [azimuth, axis] : directions) {
    // Planar model: the projection on the direction (eq. M1) with the vertical (oriented.hpp).
    const GroundMotion along = set.projected(azimuth);
    out.directions.push_back(
        DirectionResponse{azimuth, axis, rock_summary(along, planar_body_of(body, axis), options, set.vertical_ptr())});
    if (more_severe(out.directions.back().summary, out.directions[out.governing].summary)) {
      out.governing = out.directions.size() - 1;
    }
  }
  return out;
}

OrientedRockingResult rock_oriented(const MotionSet& set, const OrientedBody& body, double bearing_deg,
                                    const RockingOptions& options, const OrientationOptions& orientation) {
  OrientedRockingResult out;
  out.orientation = rock_oriented_summary(set, body, bearing_deg, options, orientation);
  const DirectionResponse& g = out.orientation.governing_response();
  out.governing = rock(set.projected(g.azimuth_deg), planar_body_of(body, g.axis), options, set.vertical_ptr());
  return out;
}

}  // namespace topple
