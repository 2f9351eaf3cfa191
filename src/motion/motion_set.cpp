// One station's ground motion in up to three components on one grid. See motion_set.hpp for the model and rules.
#include "topple/motion/motion_set.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

/// cos of an angle in degrees, exact (0, +-1) at multiples of 90 deg, so that a projection on a component's own
/// azimuth returns that component bit for bit (eq. M1).
double cos_deg(double deg) {
  const double r = std::remainder(deg, 360.0);  // [-180, 180]
  if (r == 0.0) return 1.0;
  if (std::abs(r) == 90.0) return 0.0;
  if (std::abs(r) == 180.0) return -1.0;
  return std::cos(deg_to_rad(r));
}

std::string file_of(const GroundMotion& m, const char* role) {
  return m.metadata().source_file.empty() ? std::string(role) : m.metadata().source_file;
}

InputError component_error(const GroundMotion& m, const std::string& field, const std::string& problem) {
  return InputError(InputLocation{.file = m.metadata().source_file, .line = std::nullopt, .field = field}, problem);
}

/// The merged component c of `grid` as a GroundMotion, metadata of `source` kept: uniform when the grid's points
/// are the uniform lattice t0 + i dt (no jump), else irregular.
GroundMotion component_on(const InputGrid& grid, std::size_t c, const GroundMotion& source) {
  const auto a = grid.accel_m_s2(c);
  std::vector<double> values(a.begin(), a.end());
  if (grid.is_uniform()) {
    return GroundMotion::uniform(std::move(values), grid.dt_s(), grid.start_time_s(), source.metadata());
  }
  const auto t = grid.times_s();
  return GroundMotion::irregular(std::vector<double>(t.begin(), t.end()), std::move(values), source.metadata());
}

/// The grid's points when they are exactly t0 + i dt of a uniform first component (a second component on the same
/// lattice that is shorter or longer, ending without a jump): the merged set is then uniform.
bool on_lattice(const InputGrid& grid, const GroundMotion& first) {
  if (grid.is_uniform()) return true;
  if (!first.is_uniform()) return false;
  const auto t = grid.times_s();
  const double t0 = first.start_time_s();
  const double dt = first.dt_s();
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] != t0 + static_cast<double>(i) * dt) return false;
  }
  return true;
}

}  // namespace

int ComponentAzimuths::handedness() const noexcept {
  return std::remainder(second_deg - first_deg, 360.0) > 0.0 ? 1 : -1;
}

void ComponentAzimuths::validate(const std::string& field) const {
  if (!std::isfinite(first_deg) || !std::isfinite(second_deg)) {
    throw parameter_error(field, fmt::format("the azimuths must be finite, got {} and {} deg", first_deg, second_deg));
  }
  const double diff = std::remainder(second_deg - first_deg, 180.0);  // in [-90, 90]
  if (std::abs(std::abs(diff) - 90.0) > 1e-6) {
    throw parameter_error(field, fmt::format("the horizontal components must be perpendicular: azimuths {} and {} deg "
                                             "differ by {} deg (mod 180), not 90",
                                             first_deg, second_deg, std::abs(diff)));
  }
}

ComponentAzimuths resolve_azimuths(const GroundMotion& first, const GroundMotion& second,
                                   const std::optional<ComponentAzimuths>& user, std::vector<std::string>& warnings,
                                   const std::string& field) {
  const auto& h1 = first.metadata().azimuth_deg;
  const auto& h2 = second.metadata().azimuth_deg;
  if (!user) {
    if (!h1 || !h2) {
      const GroundMotion& silent = !h1 ? first : second;
      throw parameter_error(field, fmt::format("the header of {} does not state the component's azimuth: give both "
                                               "azimuths (degrees clockwise from north, e.g. 90,0)",
                                               file_of(silent, "the record")));
    }
    const ComponentAzimuths a{*h1, *h2};
    a.validate(field);
    return a;
  }
  user->validate(field);
  const auto differs = [](double a, double b) { return std::abs(std::remainder(a - b, 360.0)) > 1e-6; };
  if (h1 && differs(*h1, user->first_deg)) {
    warnings.push_back(fmt::format("{}: the header states azimuth {} deg, {} uses {} deg", file_of(first, "first"), *h1,
                                   field, user->first_deg));
  }
  if (h2 && differs(*h2, user->second_deg)) {
    warnings.push_back(fmt::format("{}: the header states azimuth {} deg, {} uses {} deg", file_of(second, "second"),
                                   *h2, field, user->second_deg));
  }
  return *user;
}

MotionSet MotionSet::make(const GroundMotion& first, const GroundMotion* second,
                          const std::optional<ComponentAzimuths>& azimuths, const GroundMotion* vertical) {
  if (azimuths) azimuths->validate("azimuths");
  for (const GroundMotion* h : {&first, second}) {
    if (h != nullptr && h->metadata().vertical) {
      throw component_error(*h, "component", fmt::format("the header says this is the vertical channel ('{}'), given "
                                                         "as a horizontal component",
                                                         h->metadata().component));
    }
  }
  if (vertical != nullptr && vertical->metadata().azimuth_deg) {
    throw component_error(*vertical, "component",
                          fmt::format("the header says this is a horizontal channel (azimuth {} deg, '{}'), given as "
                                      "the vertical component",
                                      *vertical->metadata().azimuth_deg, vertical->metadata().component));
  }
  // Time spans: the overlap must cover at least half of the longest one (header).
  const std::array<const GroundMotion*, 3> all{&first, second, vertical};
  double start = first.start_time_s(), end = first.end_time_s(), longest = first.duration_s();
  for (const GroundMotion* m : all) {
    if (m == nullptr) continue;
    start = std::max(start, m->start_time_s());
    end = std::min(end, m->end_time_s());
    longest = std::max(longest, m->duration_s());
  }
  if (end - start < 0.5 * longest) {
    const GroundMotion& other = second != nullptr ? *second : *vertical;
    throw component_error(other, "time span",
                          fmt::format("the components do not come from one recording: {} spans {} to {} s, {} spans "
                                      "{} to {} s{}; their common part ({} s) is less than half the longest record",
                                      file_of(first, "the first component"), first.start_time_s(),
                                      first.end_time_s(), file_of(other, "the other component"),
                                      other.start_time_s(), other.end_time_s(),
                                      second != nullptr && vertical != nullptr
                                          ? fmt::format(" (vertical {} to {} s)", vertical->start_time_s(),
                                                        vertical->end_time_s())
                                          : "",
                                      std::max(0.0, end - start)));
  }
  const InputGrid grid(all);
  if (on_lattice(grid, first) && !grid.is_uniform()) {
    // Same lattice, different lengths: uniform on the first component's step.
    const auto make_uniform = [&](std::size_t c, const GroundMotion& src) {
      const auto a = grid.accel_m_s2(c);
      return GroundMotion::uniform(std::vector<double>(a.begin(), a.end()), first.dt_s(), first.start_time_s(),
                                   src.metadata());
    };
    return MotionSet(make_uniform(0, first),
                     second != nullptr ? std::optional(make_uniform(1, *second)) : std::nullopt,
                     vertical != nullptr ? std::optional(make_uniform(2, *vertical)) : std::nullopt, azimuths);
  }
  return MotionSet(component_on(grid, 0, first),
                   second != nullptr ? std::optional(component_on(grid, 1, *second)) : std::nullopt,
                   vertical != nullptr ? std::optional(component_on(grid, 2, *vertical)) : std::nullopt, azimuths);
}

const GroundMotion& MotionSet::second() const {
  if (!second_) throw parameter_error("second", "the motion set has no second horizontal component");
  return *second_;
}

const GroundMotion& MotionSet::vertical() const {
  if (!vertical_) throw parameter_error("vertical", "the motion set has no vertical component");
  return *vertical_;
}

GroundMotion MotionSet::projected(double azimuth_deg) const {
  if (!std::isfinite(azimuth_deg)) {
    throw parameter_error("azimuth", fmt::format("the azimuth must be finite, got {}", azimuth_deg));
  }
  if (!azimuths_) {
    throw parameter_error("azimuth", "the components' azimuths are unknown: a projection on an azimuth needs them");
  }
  const double c1 = cos_deg(azimuth_deg - azimuths_->first_deg);
  const double c2 = second_ ? cos_deg(azimuth_deg - azimuths_->second_deg) : 0.0;
  if (!second_ && std::abs(c1) != 1.0) {
    throw parameter_error("azimuth", fmt::format("with one horizontal component (azimuth {} deg) only its own direction "
                                                 "or the opposite one can be projected on, not {} deg",
                                                 azimuths_->first_deg, azimuth_deg));
  }
  const auto a1 = first_.accel_m_s2();
  std::vector<double> a(a1.size());
  if (second_) {
    const auto a2 = second_->accel_m_s2();
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = c1 * a1[i] + c2 * a2[i];  // eq. M1
  } else {
    for (std::size_t i = 0; i < a.size(); ++i) a[i] = c1 * a1[i];
  }
  RecordMetadata meta = first_.metadata();
  const double az = std::fmod(std::fmod(azimuth_deg, 360.0) + 360.0, 360.0);
  meta.component = fmt::format("{:g} deg (projection)", az);
  meta.azimuth_deg = az;
  meta.vertical = false;
  if (first_.is_uniform()) return GroundMotion::uniform(std::move(a), first_.dt_s(), first_.start_time_s(), meta);
  return GroundMotion::irregular(first_.times_s(), std::move(a), meta);
}

std::pair<GroundMotion, GroundMotion> MotionSet::rotated(double azimuth_deg) const {
  return {projected(azimuth_deg), projected(azimuth_deg + 90.0)};
}

}  // namespace topple
