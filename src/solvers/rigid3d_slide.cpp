// Sliding of the three-dimensional body with Coulomb friction in the base plane (docs/method.md, "Sliding in three
// dimensions"; rigid3d.hpp, Rigid3DOptions::mu_s).
//
// While the base lies flat the body translates without turning, and then its translation is exactly the
// bidirectional sliding block of sliding2d.hpp (Kramer & Lindwall 2004): the contact force per unit mass is
// (F_t, N) with N = g + a_z, F_t = a_h while stuck (|a_h| <= mu_s N) and F_t = -mu_k N w / |w| while slipping, and
// the rotation stays zero as long as the contact force's moment about c vanishes, i.e. as long as it acts at the
// centre of pressure p (moment balance about c, the base at z = 0, c at height h):
//   p = c_plan + h F_t / N:   stuck  p = c_plan - h a_h / N   (the no-slip engine's rest test, rigid3d.hpp)
//                             slip   p = c_plan + h mu_k w / |w|
// and p lies inside the base. No yaw: with every point of the base sliding at the same velocity w the friction
// traction is -mu_k q(x) w / |w| for any pressure q, whose moment about the vertical through c is
// (p - c_plan) x (-mu_k N w / |w|) = 0 since p - c_plan is parallel to w. So a body that starts without spin never
// spins while it slides flat (exact, not an approximation). Like the planar coupled model's sliding kernel
// (slide_rock.hpp, sliding_kernel) the flat phases are therefore slide_2d's solution itself, and the body lifts
// where p leaves the base:
//   - stuck: p crosses an edge (linear in t between samples): the no-slip engine takes over at the last stuck row and
//     locates the uplift itself (one test, one code); from then on no contact point slides (stated limit);
//   - slipping: p = c + h mu_k w/|w| outside the base (slide -> slide-rock). Not modelled: the run stops there with
//     a warning and slide_rock_time_s (checked on slide_2d's history rows; with mu_k <= mu_s it needs w to turn
//     toward a narrower side of the base than the load that started the slip, so it is rare).
// A body with mu_s h < b_min (b_min the least distance from c's plan to an edge) can never lift: p stays within
// h mu_s (stuck) or h mu_k (slipping) of c (Shenton 1996's criterion, in every direction).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rigid3d_math.hpp"
#include "rigid3d_slide.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"

namespace topple::detail {
namespace {

/// An edge of the base in plan: outward unit normal and the distance b of c's plan from its line (> 0).
struct PlanEdge {
  double nx = 0.0, ny = 0.0, b = 0.0;
};

std::vector<PlanEdge> plan_edges(const RigidBody3D& body) {
  const auto& v = body.base_xy_m;
  const Vec3& c = body.centre_of_mass_m;
  std::vector<PlanEdge> out;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const auto& a = v[i];
    const auto& b = v[(i + 1) % v.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const double nx = (b[1] - a[1]) / len;  // e x z for a counter-clockwise base: outward
    const double ny = -(b[0] - a[0]) / len;
    out.push_back({nx, ny, -((c[0] - a[0]) * nx + (c[1] - a[1]) * ny)});
  }
  return out;
}

/// The centre of pressure c_plan + h (dx, dy) lies in the base (on an edge counts as inside: no moment yet).
bool pressure_inside(const std::vector<PlanEdge>& edges, double h, double dx, double dy) {
  return std::all_of(edges.begin(), edges.end(), [&](const PlanEdge& e) { return h * (dx * e.nx + dy * e.ny) <= e.b; });
}

GroundMotion zero_like(const GroundMotion& m) {
  std::vector<double> zeros(m.size(), 0.0);
  if (m.is_uniform()) return GroundMotion::uniform(std::move(zeros), m.dt_s(), m.start_time_s());
  return GroundMotion::irregular(m.times_s(), std::move(zeros));
}

/// The sliding phase's totals up to history row `last` (inclusive), by the trapezoidal rule on the rows (used only
/// where the run is cut while slipping, or where a cut record cannot be formed, and on an inclined base). normal(t):
/// the normal load per unit mass (g + a_z; on an incline the base frame's).
template <class Normal>
void totals_from_rows(const Sliding2dHistory& h, std::size_t last, double mu_k, Normal normal, Rigid3DSummary& s) {
  double path = 0.0, work = 0.0, vmax = 0.0;
  for (std::size_t j = 0; j <= last; ++j) {
    const double v = std::hypot(h.east_m_s[j], h.north_m_s[j]);
    vmax = std::max(vmax, v);
    if (j == 0) continue;
    const double v0 = std::hypot(h.east_m_s[j - 1], h.north_m_s[j - 1]);
    const double dt = h.time_s[j] - h.time_s[j - 1];
    const double G0 = normal(h.time_s[j - 1]);
    const double G1 = normal(h.time_s[j]);
    path += 0.5 * dt * (v0 + v);
    work += 0.5 * dt * mu_k * (G0 * v0 + G1 * v);
  }
  s.slide_path_length_m = path;
  s.friction_energy_j_per_kg = work;
  s.max_slide_speed_m_s = vmax;
}

/// The first history row at which the contact of the no-slip engine (rocking about an edge, pivoting on a vertex)
/// would need more friction than mu_s N. Per unit mass, in the ground frame: the contact force is F = a_c - f (f the
/// gravity and inertial force, a_c the acceleration of c about the fixed contact), with the angular acceleration of
/// fixed-axis rotation about the edge (axis e, J_e theta'' = e . (r x f), J_e = e . J_P e) or of Euler's equations
/// about the fixed vertex (J_P w' = r x f - w x J_P w); J_P = R J R^T + |r|^2 1 - r r^T (parallel axes). load(t):
/// (a_x, a_y, g + a_z) at t (on an inclined base in its frame, still ground's after the record), f = -load.
template <class Load>
std::optional<double> first_contact_slip(const Rigid3DResult& r, const RigidBody3D& body, Load load, double mu_s) {
  using M3 = std::array<Vec3, 3>;
  const auto dot = [](const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
  const auto cross = [](const Vec3& a, const Vec3& b) {
    return Vec3{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
  };
  const auto mul = [&](const M3& m, const Vec3& v) { return Vec3{dot(m[0], v), dot(m[1], v), dot(m[2], v)}; };
  const auto& h = r.history;
  const auto& modes = r.summary.modes;
  std::size_t m = 0;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const double t = h.time_s[i];
    while (m + 1 < modes.size() && modes[m + 1].time_s <= t) ++m;
    const Rigid3DMode mode = h.mode[i];
    if (mode != Rigid3DMode::rocking && mode != Rigid3DMode::pivot) continue;
    if (modes[m].mode != mode || modes[m].vertex_a < 0) continue;  // an event row whose mode list entry is ahead
    const Quaternion& q = h.orientation[i];
    const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
    const double sq = 2.0 / n2;
    const double qw = q[0], qx = q[1], qy = q[2], qz = q[3];
    const M3 R{{{1.0 - sq * (qy * qy + qz * qz), sq * (qx * qy - qw * qz), sq * (qx * qz + qw * qy)},
                {sq * (qx * qy + qw * qz), 1.0 - sq * (qx * qx + qz * qz), sq * (qy * qz - qw * qx)},
                {sq * (qx * qz - qw * qy), sq * (qy * qz + qw * qx), 1.0 - sq * (qx * qx + qy * qy)}}};
    const auto& va = body.base_xy_m[static_cast<std::size_t>(modes[m].vertex_a)];
    const Vec3 rb{body.centre_of_mass_m[0] - va[0], body.centre_of_mass_m[1] - va[1], body.centre_of_mass_m[2]};
    const Vec3 rw = mul(R, rb);
    M3 Jp{};  // R J R^T + |r|^2 1 - r r^T
    for (std::size_t a = 0; a < 3; ++a) {
      for (std::size_t b = 0; b < 3; ++b) {
        double sum = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
          for (std::size_t l = 0; l < 3; ++l) sum += R[a][k] * body.inertia_cm_m2[k][l] * R[b][l];
        }
        Jp[a][b] = sum + (a == b ? dot(rw, rw) : 0.0) - rw[a] * rw[b];
      }
    }
    const Vec3 l = load(t);
    const Vec3 f{-l[0], -l[1], -l[2]};
    const Vec3& w = h.angular_velocity_rad_s[i];
    Vec3 alpha{};
    if (mode == Rigid3DMode::rocking) {
      const auto& vb = body.base_xy_m[static_cast<std::size_t>(modes[m].vertex_b)];
      Vec3 e = mul(R, Vec3{vb[0] - va[0], vb[1] - va[1], 0.0});
      const double len = std::sqrt(dot(e, e));
      e = {e[0] / len, e[1] / len, e[2] / len};
      const double theta_dd = dot(e, cross(rw, f)) / dot(e, mul(Jp, e));
      alpha = {theta_dd * e[0], theta_dd * e[1], theta_dd * e[2]};
    } else {
      const Vec3 torque = cross(rw, f);
      const Vec3 gyro = cross(w, mul(Jp, w));
      const Vec3 rhs{torque[0] - gyro[0], torque[1] - gyro[1], torque[2] - gyro[2]};
      // J_P alpha = rhs by Cramer's rule (J_P symmetric positive definite)
      const double det = dot(Jp[0], cross(Jp[1], Jp[2]));
      const Vec3 c0 = cross(Jp[1], Jp[2]), c1 = cross(Jp[2], Jp[0]), c2 = cross(Jp[0], Jp[1]);
      alpha = {dot(c0, rhs) / det, dot(c1, rhs) / det, dot(c2, rhs) / det};
    }
    const Vec3 tangential = cross(alpha, rw);
    const Vec3 centripetal = cross(w, cross(w, rw));
    const Vec3 F{tangential[0] + centripetal[0] - f[0], tangential[1] + centripetal[1] - f[1],
                 tangential[2] + centripetal[2] - f[2]};
    if (F[2] > 0.0 && std::hypot(F[0], F[1]) > mu_s * F[2] * (1.0 + 1e-9)) return t;
  }
  return std::nullopt;
}

/// The flat phase's result up to history row `cut` (inclusive): modes rest / sliding, history rows (identity
/// orientation), the base's displacement at the cut, slip episodes. `handover`: the body lifts at the cut (that row is
/// stuck: a slip starting there is the one the uplift pre-empts). `incline`: the inclined base's frame (null: level),
/// whose potential of the displacement along the plane joins the history's energy (level: none while flat).
Rigid3DResult flat_phase(const Sliding2dResult& slide, std::size_t cut, bool handover, const Rigid3DOptions& options,
                         const r3d::BaseFrame* incline) {
  const Sliding2dHistory& H = slide.history;
  Rigid3DResult out;
  auto& s = out.summary;
  s.modes.push_back({H.time_s.front(), Rigid3DMode::rest, -1, -1});
  for (std::size_t j = 1; j <= cut; ++j) {
    const bool slipping = H.slipping[j] != 0 && !(handover && j == cut);
    const Rigid3DMode m = slipping ? Rigid3DMode::sliding : Rigid3DMode::rest;
    if (m != s.modes.back().mode) s.modes.push_back({H.time_s[j], m, -1, -1});
  }
  if (options.record_history) {
    auto& r = out.history;
    for (std::size_t j = 0; j <= cut; ++j) {
      const double we = H.east_m_s[j];
      const double wn = H.north_m_s[j];
      r.time_s.push_back(H.time_s[j]);
      r.position_m.push_back({H.east_m[j], H.north_m[j], 0.0});
      r.orientation.push_back(kIdentityQuaternion);
      r.angular_velocity_rad_s.push_back({0.0, 0.0, 0.0});
      r.energy_j_per_kg.push_back(0.5 * (we * we + wn * wn) +
                                  (incline ? incline->potential({H.east_m[j], H.north_m[j], 0.0}, {}) : 0.0));
      r.mode.push_back(H.slipping[j] != 0 ? Rigid3DMode::sliding : Rigid3DMode::rest);
    }
  }
  s.residual_slide_east_m = H.east_m[cut];
  s.residual_slide_north_m = H.north_m[cut];
  s.steps = slide.summary.integrator_steps;
  for (const Rigid3DModeChange& m : s.modes) {
    if (m.mode == Rigid3DMode::sliding) {
      ++s.slip_episodes;
      if (!s.first_slip_time_s) s.first_slip_time_s = m.time_s;
    }
  }
  return out;
}

/// A body that never lifted: slide_2d's summary whole on the flat phase of all rows (`incline` as flat_phase).
Rigid3DResult whole_slide(Rigid3DResult out, const Sliding2dResult& slide, const Rigid3DOptions& options,
                          const r3d::BaseFrame* incline) {
  auto& s = out.summary;
  s.max_slide_m = slide.summary.max_abs_displacement_m;
  s.max_slide_speed_m_s = slide.summary.max_abs_velocity_m_s;
  s.slide_path_length_m = slide.summary.path_length_m;
  s.friction_energy_j_per_kg = slide.summary.friction_work_J_kg;
  s.residual_slide_east_m = slide.summary.residual_east_m;
  s.residual_slide_north_m = slide.summary.residual_north_m;
  s.end_time_s = slide.summary.end_time_s;
  s.end_mode = slide.summary.at_rest_at_end ? Rigid3DMode::rest : Rigid3DMode::sliding;
  if (!slide.summary.at_rest_at_end) {
    s.warnings.push_back(incline ? "the body was still sliding down the inclined base at the record's end "
                                   "(tan(base_incline_deg) >= mu_k: it cannot stop)"
                                 : "the body was still sliding at the record's end (mu_k = 0)");
  }
  if (options.record_history && out.history.time_s.back() < s.end_time_s) {  // the run-out's stop
    auto& r = out.history;
    r.time_s.push_back(s.end_time_s);
    r.position_m.push_back({s.residual_slide_east_m, s.residual_slide_north_m, 0.0});
    r.orientation.push_back(kIdentityQuaternion);
    r.angular_velocity_rad_s.push_back({0.0, 0.0, 0.0});
    r.energy_j_per_kg.push_back(
        incline ? incline->potential({s.residual_slide_east_m, s.residual_slide_north_m, 0.0}, {}) : 0.0);
    r.mode.push_back(s.end_mode);
  }
  return out;
}

/// The flat phase up to the cut (`out`: its modes, history rows and sliding totals) followed by the contact engine
/// from `start` (rigid3d_contact.cpp).
Rigid3DResult merge_contact(Rigid3DResult out, const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                            const RigidBody3D& body, const Rigid3DOptions& options, const ContactStart& start) {
  Rigid3DResult r = rock3d_contact(x, y, z, body, options, start);
  const Rigid3DSummary& s = out.summary;
  Rigid3DSummary& e = r.summary;
  std::vector<Rigid3DModeChange> modes = s.modes;
  for (std::size_t k = 0; k < e.modes.size(); ++k) {
    if (k == 0 && e.modes[k].mode == modes.back().mode) continue;
    modes.push_back(e.modes[k]);
  }
  e.modes = std::move(modes);
  e.max_slide_m = std::max(e.max_slide_m, s.max_slide_m);
  e.max_slide_speed_m_s = std::max(e.max_slide_speed_m_s, s.max_slide_speed_m_s);
  e.slide_path_length_m += s.slide_path_length_m;
  e.friction_energy_j_per_kg += s.friction_energy_j_per_kg;
  e.slip_episodes += s.slip_episodes;
  if (s.first_slip_time_s) e.first_slip_time_s = s.first_slip_time_s;
  e.steps += s.steps;
  if (options.record_history) {
    r3d::append_history(out.history, r.history, true);  // the cut row: the engine's state
  } else {
    out.history = {};
  }
  out.summary = std::move(e);
  return out;
}

}  // namespace

void check_friction(const Rigid3DOptions& o) {
  if (!o.mu_s) throw parameter_error("mu_s", "a kinetic friction coefficient needs the static one (mu_s)");
  if (!std::isfinite(*o.mu_s) || *o.mu_s < 0.0) {
    throw parameter_error("mu_s", fmt::format("static friction must be >= 0 and finite, got {}", *o.mu_s));
  }
  if (o.mu_k && (!std::isfinite(*o.mu_k) || *o.mu_k < 0.0 || *o.mu_k > *o.mu_s)) {
    throw parameter_error("mu_k", fmt::format("kinetic friction must be in [0, mu_s = {}], got {}", *o.mu_s, *o.mu_k));
  }
  o.sliding.validate();
}

Rigid3DResult rock3d_flat_slide(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                const Rigid3DOptions& options) {
  const double mu_s = *options.mu_s;
  const SlidingBlock block =
      SlidingBlock::make(mu_s, options.mu_k.value_or(mu_s), 0.0, SlidingMode::two_way, options.g_m_s2);
  const GroundMotion north = y ? *y : zero_like(x);
  Sliding2dResult slide = slide_2d(x, north, ComponentAzimuths{90.0, 0.0}, block, z, options.sliding);
  Rigid3DResult out = flat_phase(slide, slide.history.time_s.size() - 1, false, options, nullptr);
  return whole_slide(std::move(out), slide, options, nullptr);
}

Rigid3DResult rock3d_friction(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                              const RigidBody3D& body, const Rigid3DOptions& options) {
  check_friction(options);
  const RigidBody3D checked = RigidBody3D::polygon(body.base_xy_m, body.centre_of_mass_m, body.inertia_cm_m2);
  const double mu_s = *options.mu_s;
  const double mu_k = options.mu_k.value_or(mu_s);
  const double g = options.g_m_s2;
  const GroundMotion north = y ? *y : zero_like(x);
  // An inclined base (rigid3d.hpp, "Inclined base"): the flat phases are sliding2d.hpp's incline (eq S11), whose
  // in-plane load and normal force are the base frame's load below and whose residual is in the base frame's axes
  // (the downhill in-plane axis carried on e_d); its still tail carries a run-out down the plane.
  const bool inclined = options.base_incline_deg != 0.0;
  const SlidingBlock block =
      SlidingBlock::make(mu_s, mu_k, deg_to_rad(options.base_incline_deg), SlidingMode::two_way, g);
  const ComponentAzimuths az{90.0, 0.0, options.base_incline_azimuth_deg};
  Sliding2dResult slide = slide_2d(x, north, az, block, z, options.sliding);
  // The records the engines and the tests below read: on an incline, in the base's frame.
  BaseRecords base;
  if (inclined) base = base_records(x, y, z, options);
  const GroundMotion& xb = inclined ? *base.x : x;
  const GroundMotion* yb = inclined ? &*base.y : y;
  const GroundMotion* zb = inclined ? &*base.z : z;
  const r3d::BaseFrame frame =
      r3d::BaseFrame::make(options.base_incline_deg, options.base_incline_azimuth_deg, options.g_m_s2);
  // (a_x, a_y, g + a_z) at t; outside the record the ground is still (on an incline: gravity's load in the base frame,
  // at slide_2d's tail rows and the engine's run-out).
  const auto load = [&](double t) -> Vec3 {
    if (inclined && (t > xb.end_time_s() || t < xb.start_time_s())) return frame.still;
    return {xb.accel_at(t), yb ? yb->accel_at(t) : 0.0, g + (zb ? zb->accel_at(t) : 0.0)};
  };
  const Sliding2dHistory& H = slide.history;
  const double h = checked.height_m();
  const std::vector<PlanEdge> edges = plan_edges(checked);

  // The first row where the centre of pressure leaves the base.
  std::optional<std::size_t> handover;    // the no-slip engine starts at this (stuck) row
  std::optional<std::size_t> slide_rock;  // p left the base while slipping here
  std::optional<std::size_t> last_stuck;
  for (std::size_t j = 0; j < H.time_s.size(); ++j) {
    const double t = H.time_s[j];
    const double we = H.east_m_s[j];
    const double wn = H.north_m_s[j];
    const bool moving = H.slipping[j] != 0 && (we != 0.0 || wn != 0.0);
    if (!moving) {  // stuck, or a slip starting here from sticking: F_t = a_h, at most mu_s N
      const Vec3 l = load(t);
      const double G = l[2];
      const double ax = l[0];
      const double ay = l[1];
      // At rest (w = 0) the friction force cannot exceed mu_s N: a row where |a_h| > mu_s N is a slip starting (a
      // stop at a sample row, or a stop that reverses at once), whose contact force is mu_s N along a_h at the
      // onset and mu_k N after it. Taking F_t = a_h there put p up to h |a_h| / N from c, outside the base of a body
      // with h mu_s < b that can never lift (issue 29: such a tall box was handed to the contact engine above
      // ~0.5 g at mu = 0.05, and failed on its event limit at 3.2 g with mu = 0.2).
      const double ah = std::hypot(ax, ay);
      const double k = ah > mu_s * G ? mu_s * G / ah : 1.0;
      if (!pressure_inside(edges, h, -k * ax / G, -k * ay / G)) {
        handover = last_stuck.value_or(j);
        break;
      }
      last_stuck = H.slipping[j] == 0 ? std::optional<std::size_t>(j) : std::nullopt;
    } else {
      last_stuck.reset();
      const double v = std::hypot(we, wn);
      if (!pressure_inside(edges, h, mu_k * we / v, mu_k * wn / v)) {
        slide_rock = j;
        break;
      }
    }
  }
  // g + a_z <= 0 (the vertical lifts the body: flight, the contact engine) before either: the row before it
  std::optional<std::size_t> lost;
  if (slide.summary.contact_lost_time_s) {
    std::size_t j = 0;
    while (j + 1 < H.time_s.size() && H.time_s[j + 1] < *slide.summary.contact_lost_time_s) ++j;
    const std::size_t other = handover ? *handover : slide_rock ? *slide_rock : H.time_s.size();
    if (j < other) {
      lost = j;
      handover.reset();
      slide_rock.reset();
    }
  }

  // The flat phase's modes and history up to the cut (all rows when the body never lifts).
  // slide-rock: the contact engine starts at the last row before the centre of pressure left the base (slipping)
  if (slide_rock && *slide_rock > 0) --*slide_rock;
  const std::size_t cut = handover ? *handover : slide_rock ? *slide_rock : lost ? *lost : H.time_s.size() - 1;
  Rigid3DResult out = flat_phase(slide, cut, handover.has_value(), options, inclined ? &frame : nullptr);
  auto& s = out.summary;
  const double t_cut = H.time_s[cut];

  if (!handover && !slide_rock && !lost) return whole_slide(std::move(out), slide, options, inclined ? &frame : nullptr);

  // The sliding totals up to the cut.
  if (cut > 0) {
    bool exact = false;
    // On an incline the cut records would get slide_2d's still tail (a run-out past the cut): the rows' totals.
    if (!inclined) {
      try {  // slide_2d on the records cut at t_cut: its totals are those of the phase
        const GroundMotion xc = x.trimmed(x.start_time_s(), t_cut);
        const GroundMotion nc = north.trimmed(north.start_time_s(), t_cut);
        std::optional<GroundMotion> zc;
        if (z) zc = z->trimmed(z->start_time_s(), t_cut);
        const Sliding2dSummary part = slide_2d_summary(xc, nc, az, block, zc ? &*zc : nullptr, options.sliding);
        s.max_slide_m = part.max_abs_displacement_m;
        s.max_slide_speed_m_s = part.max_abs_velocity_m_s;
        s.slide_path_length_m = part.path_length_m;
        s.friction_energy_j_per_kg = part.friction_work_J_kg;
        exact = true;
      } catch (const InputError&) {  // a cut within 1 us of a sample (GroundMotion's least step)
      }
    }
    if (!exact) totals_from_rows(H, cut, mu_k, [&](double t) { return load(t)[2]; }, s);
  }
  // The base's excursion up to the cut at the rows too (the cut row's position is where the next phase starts).
  for (std::size_t j = 0; j <= cut; ++j) s.max_slide_m = std::max(s.max_slide_m, std::hypot(H.east_m[j], H.north_m[j]));
  const ContactStart start{{t_cut, {H.east_m[cut], H.north_m[cut], 0.0}, {H.east_m_s[cut], H.north_m_s[cut], 0.0},
                            kIdentityQuaternion, {0.0, 0.0, 0.0}}};
  if (slide_rock || lost) return merge_contact(std::move(out), xb, yb, zb, checked, options, start);

  if (zb) {  // g + a_z <= 0 after the uplift: flight, which the no-slip engine excludes
    for (std::size_t i = 0; i < zb->size(); ++i) {
      if (zb->time_s(i) >= t_cut && !(g + zb->accel_m_s2()[i] > 0.0)) {
        return merge_contact(std::move(out), xb, yb, zb, checked, options, start);
      }
    }
  }
  Rigid3DOptions rigid = options;
  rigid.mu_s.reset();
  rigid.mu_k.reset();
  rigid.record_history = true;  // for the friction check of the contact below
  Rigid3DResult r = rock3d_rigid(xb, yb, zb, checked, rigid, t_cut);
  const std::optional<double> contact_slip = first_contact_slip(r, checked, load, mu_s);
  // Back at rest after the uplift, the no-slip engine keeps the body stuck: would it slide (the stick test on the
  // record's samples in those rest periods)?
  std::optional<double> slide_after;
  for (std::size_t k = 1; k < r.summary.modes.size() && !slide_after; ++k) {
    const auto& modes = r.summary.modes;
    if (modes[k].mode != Rigid3DMode::rest || modes[k].time_s <= t_cut) continue;
    const double t_to = k + 1 < modes.size() ? modes[k + 1].time_s : r.summary.end_time_s;
    for (std::size_t i = 0; i < xb.size() && !slide_after; ++i) {
      const double t = xb.time_s(i);
      if (t < modes[k].time_s || t > t_to) continue;
      const double G = g + (zb ? zb->accel_at(t) : 0.0);
      if (std::hypot(xb.accel_m_s2()[i], yb ? yb->accel_at(t) : 0.0) > mu_s * G) slide_after = t;
    }
  }
  // The no-slip engine's answer holds where no contact needed to slip, the body never slid after an uplift and never
  // left the ground; else the contact engine (rigid3d_contact.cpp) runs from the uplift instead.
  if (contact_slip || slide_after || r.summary.flight_time_s) {
    return merge_contact(std::move(out), xb, yb, zb, checked, options, start);
  }
  if (!options.record_history) r.history = {};
  // Merge: the engine's summary, the flat phase's modes first (the engine's first mode is its rest at t_cut).
  Rigid3DSummary& e = r.summary;
  std::vector<Rigid3DModeChange> modes = s.modes;
  for (std::size_t k = 0; k < e.modes.size(); ++k) {
    if (k == 0 && modes.back().mode == Rigid3DMode::rest) continue;
    modes.push_back(e.modes[k]);
  }
  e.modes = std::move(modes);
  r3d::copy_slide_totals(e, s);  // the no-slip engine's contacts do not slide
  e.steps += s.steps;
  if (options.record_history) {
    for (std::size_t k = 0; k < r.history.time_s.size(); ++k) {
      Vec3 p = r.history.position_m[k];
      p[0] += s.residual_slide_east_m;
      p[1] += s.residual_slide_north_m;
      out.history.time_s.push_back(r.history.time_s[k]);
      out.history.position_m.push_back(p);
      out.history.orientation.push_back(r.history.orientation[k]);
      out.history.angular_velocity_rad_s.push_back(r.history.angular_velocity_rad_s[k]);
      // the engine's potential is relative to its start; on an incline add the slide's along the plane
      out.history.energy_j_per_kg.push_back(
          r.history.energy_j_per_kg[k] +
          (inclined ? frame.potential({s.residual_slide_east_m, s.residual_slide_north_m, 0.0}, {}) : 0.0));
      out.history.mode.push_back(r.history.mode[k]);
    }
  }
  out.summary = std::move(e);
  return out;
}

BaseRecords base_records(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                         const Rigid3DOptions& options) {
  const std::array<const GroundMotion*, 3> components{&x, y, z};
  const InputGrid grid(components);
  const double g = options.g_m_s2;
  const std::vector<double> gravity = effective_gravity(grid, 2, g);
  const std::span<const double> ax = grid.accel_m_s2(0);
  const std::span<const double> ay = grid.accel_m_s2(1);
  const r3d::BaseFrame frame = r3d::BaseFrame::make(options.base_incline_deg, options.base_incline_azimuth_deg, g);
  const std::size_t n = grid.size();
  std::vector<double> bx(n), by(n), bz(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 l = frame.load(ax[i], ay.empty() ? 0.0 : ay[i], gravity.empty() ? g : gravity[i]);
    bx[i] = l[0];
    by[i] = l[1];
    bz[i] = l[2] - g;
  }
  const auto make = [&](std::vector<double> a) {
    if (grid.is_uniform()) return GroundMotion::uniform(std::move(a), grid.dt_s(), grid.start_time_s());
    const std::span<const double> t = grid.times_s();
    return GroundMotion::irregular(std::vector<double>(t.begin(), t.end()), std::move(a));
  };
  BaseRecords out;
  out.x = make(std::move(bx));
  out.y = make(std::move(by));
  out.z = make(std::move(bz));
  return out;
}

}  // namespace topple::detail
