// Slide-rock and flight of the three-dimensional body with Coulomb friction (rigid3d.hpp; rigid3d_contact.cpp;
// docs/method.md, "Slide-rock and flight in three dimensions").
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple {
namespace {

constexpr double kG = 9.80665;

GroundMotion sine(double amplitude, double period, double cycles, double dt, double tail, double t0 = 0.0) {
  const auto n = static_cast<std::size_t>(std::llround((t0 + cycles * period + tail) / dt)) + 1;
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt - t0;
    if (t >= 0.0 && t <= cycles * period) a[i] = amplitude * std::sin(2.0 * M_PI * t / period);
  }
  return GroundMotion::uniform(a, dt);
}

Rigid3DOptions friction(double mu_s, double mu_k) {
  Rigid3DOptions o;
  o.mu_s = mu_s;
  o.mu_k = mu_k;
  return o;
}

struct Case {
  double amp_g, period_s, mu, vert_g, vert_period_s;
};

TEST(Rigid3DContact, Explore) {
  const RigidBody3D box = RigidBody3D::box(0.4, 0.3, 0.8);
  const std::vector<Case> cases{{0.7, 0.6, 0.55, 0, 1}, {0.9, 0.6, 0.55, 0, 1}, {0.7, 0.6, 0.6, 0, 1},
                                {0.9, 0.6, 0.6, 0, 1},  {0.8, 0.5, 0.52, 0, 1}, {0.6, 0.6, 0.35, 0, 1},
                                {0.5, 0.4, 0.5, 1.3, 0.3}, {0.6, 0.6, 0.6, 1.2, 0.2}, {0.4, 0.5, 0.4, 1.5, 0.25}};
  for (const Case& c : cases) {
    const GroundMotion x = sine(c.amp_g * kG, c.period_s, 3.0, 0.005, 2.0);
    const GroundMotion z = sine(c.vert_g * kG, c.vert_period_s, 3.0 * c.period_s / c.vert_period_s, 0.005, 2.0);
    const bool vert = c.vert_g > 0.0;
    const SlideRockResult p = slide_rock(x, SlideRockBody::block(0.4, 0.8, c.mu), {}, vert ? &z : nullptr);
    const auto& s = p.summary;
    Rigid3DOptions o = friction(c.mu, c.mu);
    const Rigid3DResult r = rock3d(x, nullptr, vert ? &z : nullptr, box, o);
    const double theta = std::max(s.max_rotation_positive_rad, s.max_rotation_negative_rad);
    std::printf("case %.2f %.2f mu %.2f v %.2f: planar ov %d th %.9f slide %.9f imp %zu sr %zu fl %zu | 3d ov %d th "
                "%.9f slide %.9f imp %zu sr %s fl %zu pain %zu warn %zu\n",
                c.amp_g, c.period_s, c.mu, c.vert_g, s.overturned, theta, s.residual_slide_m, s.impacts,
                s.mode_entries[static_cast<std::size_t>(SlideRockMode::slide_rock)],
                s.mode_entries[static_cast<std::size_t>(SlideRockMode::flight)], r.summary.overturned,
                r.summary.max_tilt_rad, r.summary.residual_slide_east_m, r.summary.impacts,
                r.summary.slide_rock_time_s ? "y" : "n", r.summary.flights, r.summary.painleve_events,
                r.summary.warnings.size());
    for (const auto& w : r.summary.warnings) std::printf("   %s\n", w.c_str());
    if (std::getenv("R3D_PLANAR")) {
      for (const auto& t : p.transitions) std::printf("  planar %.9f %s\n", t.time_s, std::string(slide_rock_mode_name(t.mode)).c_str());
    }
  }
}

}  // namespace
}  // namespace topple
