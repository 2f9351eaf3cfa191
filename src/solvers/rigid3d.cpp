// Three-dimensional rocking and pivoting engine. The model, the contact modes, the transitions, the impact law and
// the method: include/topple/solvers/rigid3d.hpp and docs/method.md, "Rocking in three dimensions".
#include "topple/solvers/rigid3d.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <string>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "topple/core/enum_names.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/numerics/dp5.hpp"
#include "topple/numerics/event_root.hpp"
#include "topple/numerics/step_law.hpp"
#include "rigid3d_math.hpp"
#include "rigid3d_slide.hpp"

namespace topple {
namespace {

using namespace detail::r3d;  // rigid3d_math.hpp: the algebra and the Dormand-Prince stepper

// ---------------------------------------------------------------------------------------------------------------
// Geometry of the body, precomputed per edge and per vertex.

struct EdgeGeom {
  int a = 0, b = 0;    // vertex indices: the edge runs from a to b = a + 1 (counter-clockwise)
  Vec3 e_b{}, n_b{};   // unit axis (a -> b) and outward normal e x z, body frame
  double dist = 0.0;   // b: distance of c's plan from the edge line, > 0
  double length = 0.0; // L
  double s = 0.0;      // (c - v_a) . e
  double J = 0.0;      // J_e = e . J e + b^2 + h^2
  double jn = 0.0, jz = 0.0;  // n_b . J e_b, z . J e_b (products of inertia about c)
  double alpha = 0.0;  // atan(b / h), the static tilt limit about this edge
  double lift_energy = 0.0;  // g (sqrt(b^2 + h^2) - h): per unit mass, to bring c over the edge
};

struct VertexGeom {
  Vec3 p{}, r{};       // the vertex and r = c - p, body frame
  M3 Jp{}, Jp_inv{};   // J + |r|^2 1 - r r^T and its inverse
  double lift_energy = 0.0;
};

struct Geometry {
  std::size_t n = 0;
  std::vector<Vec3> v;  // vertices, body frame (z = 0)
  Vec3 c{};
  double h = 0.0;
  M3 J{};
  std::vector<EdgeGeom> edges;
  std::vector<VertexGeom> vertices;
  double size = 0.0;    // largest distance from c to a vertex: the length scale of the tolerances
  double alpha_ref = 0.0, p_ref = 0.0;  // the smallest static tilt limit and its frequency parameter (scaling)

  [[nodiscard]] double limit_toward(const Vec3& u_b) const {  // static tilt limit toward the plan direction u_b
    double b = -std::numeric_limits<double>::infinity();
    for (const Vec3& p : v) b = std::max(b, (p[0] - c[0]) * u_b[0] + (p[1] - c[1]) * u_b[1]);
    return std::atan2(b, h);
  }
};

Geometry make_geometry(const RigidBody3D& body, double g) {
  Geometry geo;
  geo.n = body.base_xy_m.size();
  for (const auto& p : body.base_xy_m) geo.v.push_back({p[0], p[1], 0.0});
  geo.c = body.centre_of_mass_m;
  geo.h = geo.c[2];
  geo.J = body.inertia_cm_m2;
  geo.alpha_ref = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < geo.n; ++i) {
    EdgeGeom e;
    e.a = static_cast<int>(i);
    e.b = static_cast<int>((i + 1) % geo.n);
    const Vec3 d = geo.v[static_cast<std::size_t>(e.b)] - geo.v[i];
    e.length = norm(d);
    e.e_b = (1.0 / e.length) * d;
    e.n_b = cross(e.e_b, kUp);
    const Vec3 rc = geo.c - geo.v[i];
    e.dist = -(rc[0] * e.n_b[0] + rc[1] * e.n_b[1]);
    e.s = dot(rc, e.e_b);
    e.J = dot(e.e_b, mul(geo.J, e.e_b)) + e.dist * e.dist + geo.h * geo.h;
    e.jn = dot(e.n_b, mul(geo.J, e.e_b));
    e.jz = dot(kUp, mul(geo.J, e.e_b));
    e.alpha = std::atan2(e.dist, geo.h);
    e.lift_energy = g * (std::hypot(e.dist, geo.h) - geo.h);
    if (e.alpha < geo.alpha_ref) {
      geo.alpha_ref = e.alpha;
      geo.p_ref = std::sqrt(g * std::hypot(e.dist, geo.h) / e.J);
    }
    geo.edges.push_back(e);
    VertexGeom vg;
    vg.p = geo.v[i];
    vg.r = geo.c - vg.p;
    vg.Jp = shifted_inertia(geo.J, vg.r);
    vg.Jp_inv = inverse(vg.Jp);
    vg.lift_energy = g * (norm(vg.r) - geo.h);
    geo.vertices.push_back(vg);
    geo.size = std::max(geo.size, norm(vg.r));
  }
  return geo;
}

// ---------------------------------------------------------------------------------------------------------------
// The engine.

using S2 = State<2>;
using S7 = State<7>;

class Engine {
 public:
  /// start_time_s: the body at rest at that time (before the grid's start: from its start).
  Engine(const InputGrid& grid, std::vector<double> gravity, const Geometry& geo, const Rigid3DOptions& opt,
         double start_time_s = -std::numeric_limits<double>::infinity())
      : grid_(grid), ax_(grid.accel_m_s2(0)), ay_(grid.accel_m_s2(1)), gravity_(std::move(gravity)), geo_(geo),
        opt_(opt),
        edge_(EdgeRhs{this}, opt.abs_tol, opt.rel_tol, 0.1 * grid.dt_s()),
        pivot_(PivotRhs{this}, opt.abs_tol, opt.rel_tol, 0.1 * grid.dt_s()) {
    start_time_s_ = start_time_s;
    eps_z_ = 1e-12 * geo_.size;
    // Simultaneous contact (touch_down): vertices within simultaneous_contact (1e-5) of the size of the ground when
    // another touches down join the impact (a base within about 1e-5 rad of flat lands flat, one impact over all its
    // contacts). Which of them lands first, microseconds apart, hangs on micrometres (roughness, the contact's
    // compliance, the input's last digits) that a rigid model does not have; one impact does not (docs/method.md,
    // "Impact law"). The floor 1e-12 (eps_z_) keeps a vertex on the ground to round-off in the set at 0.
    tie_z_ = std::max(opt.simultaneous_contact, 1e-12) * geo_.size;
    pivot_.set_scale({geo_.alpha_ref, geo_.alpha_ref, geo_.alpha_ref, geo_.alpha_ref, geo_.p_ref * geo_.alpha_ref,
                      geo_.p_ref * geo_.alpha_ref, geo_.p_ref * geo_.alpha_ref});
    P_w_ = geo_.v[0];
    rest_contact_ = geo_.v[0];
  }

  Rigid3DResult run() {
    const std::size_t n = grid_.size();
    t_ = grid_.time_s(0);
    std::size_t i_start = 0;  // a later start (rigid3d_slide.cpp: at rest after sliding): its sample interval
    if (start_time_s_ > t_) {
      while (i_start + 2 < n && grid_.time_s(i_start + 1) <= start_time_s_) ++i_start;
      t_ = start_time_s_;
    }
    enter(Rigid3DMode::rest, -1, -1);
    row();
    refresh_rest();
    for (std::size_t i = i_start; !done_ && i + 1 < n; ++i) {
      if (mode_ == Rigid3DMode::rest && (i > 0 || rest_below(0))) {
        // Full contact: each sample costs one test per edge (the uplift functions are linear in t over an interval,
        // so both ends below zero keep the whole interval below).
        if (ay_.empty() && gravity_.empty()) {  // x alone: the test is x_lo <= a_x <= x_hi
          const double* a = ax_.data();
          while (i + 1 < n && a[i + 1] >= x_lo_ && a[i + 1] <= x_hi_) {
            ++i;
            if (opt_.record_history) {
              t_ = grid_.time_s(i);
              row();
            }
          }
        } else {
          while (i + 1 < n && rest_below(i + 1)) {
            ++i;
            if (opt_.record_history) {
              t_ = grid_.time_s(i);
              row();
            }
          }
        }
        t_ = std::max(t_, grid_.time_s(i));  // a start inside interval i stays where it is
        if (i + 1 >= n) break;
      }
      const double ta = grid_.time_s(i);
      const double tb = grid_.time_s(i + 1);
      if (!(tb > ta)) {
        restart_ = true;
        continue;
      }
      set_forcing(i, ta, tb);
      interval(tb);
      if (!done_) row();
    }
    if (!done_) run_out();
    auto& s = out_.summary;
    s.end_time_s = t_;
    s.end_mode = mode_;
    if (!done_ && mode_ != Rigid3DMode::rest) {
      s.warnings.push_back(fmt::format("the body was still moving {} s after the record ended (max_run_out_s)",
                                       opt_.max_run_out_s));
    }
    if (opt_.record_history && (out_.history.time_s.empty() || out_.history.time_s.back() < t_)) row();
    return std::move(out_);
  }

 private:
  // ---- right-hand sides ----
  struct EdgeRhs {
    Engine* self;
    void operator()(const S2& x, double t, S2& dx) const {
      dx[0] = x[1];
      dx[1] = self->edge_accel(x[0], t);
    }
  };
  struct PivotRhs {
    Engine* self;
    void operator()(const S7& x, double t, S7& dx) const { self->pivot_rhs(x, t, dx); }
  };

  /// theta'' about the current edge (header): the planar equation with this edge's b, h, J_e.
  [[nodiscard]] double edge_accel(double theta, double t) const {
    const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(edge_index_)];
    const Vec3 f = forcing_.f(t);
    const double fn = f[0] * n_w_[0] + f[1] * n_w_[1];
    const double sn = std::sin(theta);
    const double cs = std::cos(theta);
    return ((e.dist * sn + geo_.h * cs) * fn + f[2] * (e.dist * cs - geo_.h * sn)) / e.J;
  }

  void pivot_rhs(const S7& x, double t, S7& dx) const {
    const VertexGeom& vg = geo_.vertices[static_cast<std::size_t>(vertex_)];
    const Quaternion q{x[0], x[1], x[2], x[3]};
    const Vec3 w{x[4], x[5], x[6]};
    const M3 R = rotation(q);
    const Vec3 fb = mul_t(R, forcing_.f(t));
    const Vec3 wdot = mul(vg.Jp_inv, cross(vg.r, fb) - cross(w, mul(vg.Jp, w)));
    const Quaternion qd = qmul(q, Quaternion{0.0, w[0], w[1], w[2]});
    for (std::size_t i = 0; i < 4; ++i) dx[i] = 0.5 * qd[i];
    for (std::size_t i = 0; i < 3; ++i) dx[4 + i] = wdot[i];
  }

  // ---- kinematics of the current mode ----
  [[nodiscard]] Quaternion edge_orientation(double theta) const { return qmul(axis_angle(e_w_, theta), q_flat_); }

  /// Vertical contact forces at the two ends of the edge (per unit mass; docs/method.md): F_b from the moment balance
  /// about v_a along n, F_a the rest of the vertical force.
  [[nodiscard]] std::pair<double, double> edge_forces(double theta, double w, double t) const {
    const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(edge_index_)];
    const double wd = edge_accel(theta, t);
    const double sn = std::sin(theta);
    const double cs = std::cos(theta);
    const double rn = geo_.h * sn - e.dist * cs;
    const double rz = e.dist * sn + geo_.h * cs;
    const Vec3 f = forcing_.f(t);
    const double fe = f[0] * e_w_[0] + f[1] * e_w_[1];
    const double Jne = cs * e.jn + sn * e.jz - rn * e.s;  // (J_p)_{ne} in the ground frame about v_a
    const double Jze = -sn * e.jn + cs * e.jz - rz * e.s;
    const double Fb = (wd * Jne + w * w * Jze - (e.s * f[2] - rz * fe)) / e.length;
    const double Fz = -rn * wd - rz * w * w - f[2];
    return {Fz - Fb, Fb};
  }

  [[nodiscard]] double pivot_force(const S7& x, double t) const {
    const VertexGeom& vg = geo_.vertices[static_cast<std::size_t>(vertex_)];
    S7 dx{};
    pivot_rhs(x, t, dx);
    const Vec3 w{x[4], x[5], x[6]};
    const Vec3 wd{dx[4], dx[5], dx[6]};
    const Vec3 acc_b = cross(wd, vg.r) + cross(w, cross(w, vg.r));
    const M3 R = rotation({x[0], x[1], x[2], x[3]});
    return dot(R[2], acc_b) - forcing_.f(t)[2];
  }

  /// Height of vertex j above the ground in the pivot mode.
  [[nodiscard]] double vertex_height(const S7& x, std::size_t j) const {
    const M3 R = rotation({x[0], x[1], x[2], x[3]});
    return dot(R[2], geo_.v[j] - geo_.vertices[static_cast<std::size_t>(vertex_)].p);
  }

  /// The vertical velocity of vertex j in the pivot mode: (w x (R (v_j - p)))_z, w = R w_B.
  [[nodiscard]] double vertex_rate(const S7& x, std::size_t j) const {
    const M3 R = rotation({x[0], x[1], x[2], x[3]});
    const Vec3 w = mul(R, Vec3{x[4], x[5], x[6]});
    const Vec3 r = mul(R, geo_.v[j] - geo_.vertices[static_cast<std::size_t>(vertex_)].p);
    return w[0] * r[1] - w[1] * r[0];
  }

  /// d/dt (q_x^2 + q_y^2) / |q|^2 ... its sign: the tilt grows when q_x q_x' + q_y q_y' > 0 (cos tilt =
  /// 1 - 2 (q_x^2 + q_y^2) for a unit q).
  [[nodiscard]] static double tilt_rate(const S7& x) {
    const Quaternion q{x[0], x[1], x[2], x[3]};
    const Quaternion qd = qmul(q, Quaternion{0.0, x[4], x[5], x[6]});
    return q[1] * qd[1] + q[2] * qd[2];
  }

  // ---- tracking ----
  void track(double t, const Quaternion& q_raw) {
    const M3 R = rotation(q_raw);
    const Vec3 zb{R[0][2], R[1][2], R[2][2]};  // the body's z axis in the ground frame
    const double horizontal = std::hypot(zb[0], zb[1]);
    const double tilt = std::atan2(horizontal, zb[2]);
    auto& s = out_.summary;
    if (tilt <= 0.0) return;
    const Vec3 d{zb[0] / horizontal, zb[1] / horizontal, 0.0};
    // The body's plan direction that tips toward d: with the tilt tau a rotation about the horizontal axis z x d,
    // the plan direction u_B with R u_B = d cos(tau) - z sin(tau) (the base's line of steepest descent; at 90 degrees
    // still defined, where the plan part of R^T d vanishes).
    Vec3 u = mul_t(R, Vec3{d[0] * zb[2], d[1] * zb[2], -horizontal});
    const double un = std::hypot(u[0], u[1]);
    u = {u[0] / un, u[1] / un, 0.0};
    const double ratio = tilt / geo_.limit_toward(u);
    if (tilt > s.max_tilt_rad) {
      s.max_tilt_rad = tilt;
      s.max_tilt_time_s = t;
      s.max_tilt_azimuth_deg = azimuth(d);
    }
    if (ratio > s.max_tilt_over_limit) s.max_tilt_over_limit = ratio;
    if (ratio >= 1.0 && !s.exceeded_limit_time_s) s.exceeded_limit_time_s = t;
  }
  static double azimuth(const Vec3& d) {
    double a = rad_to_deg(std::atan2(d[0], d[1]));
    if (a < 0.0) a += 360.0;
    return a;
  }

  [[nodiscard]] Quaternion orientation() const {
    if (mode_ == Rigid3DMode::rocking) return normalized(edge_orientation(xe_[0]));
    if (mode_ == Rigid3DMode::pivot) return normalized({xv_[0], xv_[1], xv_[2], xv_[3]});
    return q_flat_;
  }
  [[nodiscard]] Vec3 omega_world() const {
    if (mode_ == Rigid3DMode::rocking) return xe_[1] * e_w_;
    if (mode_ == Rigid3DMode::pivot) return mul(rotation({xv_[0], xv_[1], xv_[2], xv_[3]}), {xv_[4], xv_[5], xv_[6]});
    return {0.0, 0.0, 0.0};
  }
  /// The contact point's body coordinates (rocking: v_a; pivot: the vertex; rest: v_0).
  [[nodiscard]] Vec3 contact_b() const {
    if (mode_ == Rigid3DMode::rocking) return geo_.v[static_cast<std::size_t>(edge_index_)];
    if (mode_ == Rigid3DMode::pivot) return geo_.v[static_cast<std::size_t>(vertex_)];
    return rest_contact_;
  }
  /// Kinetic energy per unit mass about the fixed contact, and potential g (z_c - h).
  [[nodiscard]] double energy() const {
    const Quaternion q = orientation();
    const M3 R = rotation(q);
    const Vec3 pb = contact_b();
    const double zc = dot(R[2], geo_.c - pb);
    double ke = 0.0;
    if (mode_ == Rigid3DMode::rocking) {
      ke = 0.5 * geo_.edges[static_cast<std::size_t>(edge_index_)].J * xe_[1] * xe_[1];
    } else if (mode_ == Rigid3DMode::pivot) {
      const Vec3 w{xv_[4], xv_[5], xv_[6]};
      ke = 0.5 * dot(w, mul(geo_.vertices[static_cast<std::size_t>(vertex_)].Jp, w));
    }
    if (frame_.level) return ke + g_ * (zc - geo_.h);
    // An inclined base: the potential of still ground's load in the base frame (rigid3d_math.hpp, BaseFrame), c
    // relative to its place at the start (the body frame's origin at the ground's).
    return ke + frame_.potential(P_w_ + mul(R, geo_.c - pb), geo_.c);
  }

  void row() {
    if (!opt_.record_history) return;
    auto& h = out_.history;
    const Quaternion q = orientation();
    const M3 R = rotation(q);
    const Vec3 origin = P_w_ - mul(R, contact_b());
    if (!h.time_s.empty() && h.time_s.back() == t_ && h.mode.back() == mode_) {
      h.position_m.back() = origin;
      h.orientation.back() = q;
      h.angular_velocity_rad_s.back() = omega_world();
      h.energy_j_per_kg.back() = energy();
      return;
    }
    h.time_s.push_back(t_);
    h.position_m.push_back(origin);
    h.orientation.push_back(q);
    h.angular_velocity_rad_s.push_back(omega_world());
    h.energy_j_per_kg.push_back(energy());
    h.mode.push_back(mode_);
  }

  void enter(Rigid3DMode mode, int a, int b) {
    mode_ = mode;
    out_.summary.modes.push_back({t_, mode, a, b});
    restart_ = true;
  }

  // ---- the input ----
  void set_forcing(std::size_t i, double ta, double tb) {
    forcing_ = Forcing::interval(i, ta, tb, ax_, ay_, gravity_, g_);
    // No restart: the forcing is continuous at a sample, so the last stage's derivative (FSAL) holds there.
  }

  void interval(double tb) {
    int events = 0;
    while (!done_ && t_ < tb) {
      if (++events > kMaxEventsPerInterval) {
        throw EventLimitError(fmt::format("rock3d: more than {} events in one sample interval ending at {} s",
                                          kMaxEventsPerInterval, tb));
      }
      if (tb - t_ <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(tb), 1.0)) {
        t_ = tb;
        break;
      }
      switch (mode_) {
        case Rigid3DMode::rest: rest_phase(tb); break;
        case Rigid3DMode::rocking: rocking_phase(tb); break;
        case Rigid3DMode::pivot: pivot_phase(tb); break;
        default: done_ = true; break;
      }
    }
  }

  // ---- rest: the centre of pressure leaving the polygon (linear in t over the interval) ----
  /// The ground-frame outward normals of the edges and their distances b_e, for the pose at rest.
  void refresh_rest() {
    const M3 R = rotation(q_flat_);
    rest_edges_.clear();
    for (const EdgeGeom& e : geo_.edges) {
      const Vec3 n = mul(R, e.n_b);
      rest_edges_.push_back({geo_.h * n[0], geo_.h * n[1], e.dist});
    }
    // Under x alone, -a_x h n_x - g b <= 0 for every edge is x_lo <= a_x <= x_hi.
    x_lo_ = -std::numeric_limits<double>::infinity();
    x_hi_ = std::numeric_limits<double>::infinity();
    for (const auto& r : rest_edges_) {
      if (r[0] > 0.0) x_lo_ = std::max(x_lo_, -g_ * r[2] / r[0]);
      if (r[0] < 0.0) x_hi_ = std::min(x_hi_, -g_ * r[2] / r[0]);
    }
  }
  /// Every edge's uplift function u_e = -h a_h . n_e - (g + a_z) b_e at sample i is <= 0.
  [[nodiscard]] bool rest_below(std::size_t i) const {
    const double ax = ax_[i];
    const double ay = ay_.empty() ? 0.0 : ay_[i];
    const double G = gravity_.empty() ? g_ : gravity_[i];
    for (const auto& r : rest_edges_) {
      if (-(ax * r[0] + ay * r[1]) - G * r[2] > 0.0) return false;
    }
    return true;
  }

  void rest_phase(double tb) {
    // edge e: uplift when u_e(t) = -h a_h . n_e - G b_e > 0, linear in t (a_h and G linear).
    const double ta = t_;
    double t_first = std::numeric_limits<double>::infinity();
    std::vector<std::pair<double, int>> hits;
    for (std::size_t k = 0; k < geo_.edges.size(); ++k) {
      const EdgeGeom& e = geo_.edges[k];
      const auto& r = rest_edges_[k];
      const auto u = [&](double t) {
        const Vec3 f = forcing_.f(t);
        return f[0] * r[0] + f[1] * r[1] + f[2] * r[2];
      };
      const double u0 = u(ta);
      const double u1 = u(tb);
      double tu = std::numeric_limits<double>::infinity();
      if (u0 > 0.0) {
        tu = ta;
      } else if (u1 > 0.0) {
        tu = std::min(tb, ta + (tb - ta) * (-u0) / (u1 - u0));
      }
      if (tu < std::numeric_limits<double>::infinity()) hits.emplace_back(tu, e.a);
      t_first = std::min(t_first, tu);
    }
    if (hits.empty()) {
      t_ = tb;
      return;
    }
    // Edges whose threshold is crossed at the same instant (to 1e-9 of the interval): two adjacent ones mean the
    // centre of pressure leaves through their common vertex.
    const double tie = 1e-9 * (tb - ta) + detail::time_tolerance(tb);
    std::vector<int> at_once;
    for (const auto& [tu, a] : hits) {
      if (tu <= t_first + tie) at_once.push_back(a);
    }
    t_ = t_first;
    ++out_.summary.uplifts;
    if (!out_.summary.uplift_time_s) out_.summary.uplift_time_s = t_;
    int vertex = -1;
    const int n = static_cast<int>(geo_.n);
    for (const int a : at_once) {
      for (const int b : at_once) {
        if (b == (a + 1) % n) vertex = b;  // edges a and a + 1 share the vertex a + 1
      }
    }
    from_rest_ = true;
    if (vertex >= 0) {
      start_pivot(vertex, q_flat_, {0.0, 0.0, 0.0});
    } else {
      start_rocking(at_once.front(), 0.0, 0.0);
    }
    row();
  }

  void start_rocking(int edge, double theta, double theta_dot) {
    const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(edge)];
    // the contact point: v_a's position in the ground frame (from the current pose)
    const Quaternion q = orientation();
    const M3 R = rotation(q);
    const Vec3 Pa = P_w_ + mul(R, geo_.v[static_cast<std::size_t>(e.a)] - contact_b());
    Vec3 ew = mul(R, e.e_b);
    ew[2] = 0.0;
    ew = (1.0 / norm(ew)) * ew;
    edge_index_ = edge;
    e_w_ = ew;
    n_w_ = cross(ew, kUp);
    q_flat_ = normalized(qmul(axis_angle(ew, -theta), q));
    P_w_ = {Pa[0], Pa[1], 0.0};
    xe_ = {theta, theta_dot};
    edge_.set_scale({e.alpha, e.alpha * std::sqrt(g_ * std::hypot(e.dist, geo_.h) / e.J)});
    enter(Rigid3DMode::rocking, e.a, e.b);
  }

  void start_pivot(int vertex, const Quaternion& q, const Vec3& w_body) {
    const Quaternion q0 = orientation();
    const M3 R0 = rotation(q0);
    const Vec3 P = P_w_ + mul(R0, geo_.v[static_cast<std::size_t>(vertex)] - contact_b());
    vertex_ = vertex;
    P_w_ = {P[0], P[1], 0.0};
    const Quaternion qn = normalized(q);
    xv_ = {qn[0], qn[1], qn[2], qn[3], w_body[0], w_body[1], w_body[2]};
    enter(Rigid3DMode::pivot, vertex, -1);
  }

  void go_rest(double lost) {
    // flat: remove the tilt by the minimal rotation
    const Quaternion q = orientation();
    const M3 R = rotation(q);
    const Vec3 zb{R[0][2], R[1][2], R[2][2]};
    const Vec3 axis = cross(zb, kUp);
    const double s = norm(axis);
    const Quaternion flat = s > 0.0 ? normalized(qmul(axis_angle((1.0 / s) * axis, std::atan2(s, zb[2])), q)) : q;
    // the contact keeps its ground position
    rest_contact_ = contact_b();
    q_flat_ = flat;
    P_w_ = {P_w_[0], P_w_[1], 0.0};
    out_.summary.energy_lost_j_per_kg += lost;
    edge_index_ = -1;
    vertex_ = -1;
    refresh_rest();
    enter(Rigid3DMode::rest, -1, -1);
  }

  // ---- rocking about an edge ----
  void rocking_phase(double tb) {
    if (restart_) {
      edge_.restart(t_, xe_);
      restart_ = false;
    }
    if (!edge_.step(tb, out_.summary.steps, opt_.max_steps)) step_limit();
    const double t0 = edge_.t0();
    const double t1 = edge_.t1();
    const S2 x0 = edge_.x0();
    const S2 x1 = edge_.x1();
    // Split at a turning point of theta (theta' changes sign), so that theta is monotone on each piece.
    double tp = t1;
    if ((x0[1] > 0.0 && x1[1] <= 0.0) || (x0[1] < 0.0 && x1[1] >= 0.0)) {
      tp = locate([&](double t) { return edge_.dense(t)[1]; }, t0, t1, x0[1], x1[1]);
    }
    for (int piece = 0; piece < 2; ++piece) {
      const double ta = piece == 0 ? t0 : tp;
      const double tb2 = piece == 0 ? tp : t1;
      if (!(tb2 > ta) && piece == 1) break;
      const S2 xa = edge_.dense(ta);
      const S2 xb = edge_.dense(tb2);
      // Events on the piece, earliest first: fall (theta = pi/2), impact (theta = 0), an end unloading.
      const double half_pi = kPi / 2.0;
      // theta passing alpha_e (the static limit toward this edge's normal): located, as the planar engine's
      // exceeded_alpha_time_s
      const double alpha_e = geo_.edges[static_cast<std::size_t>(edge_index_)].alpha;
      if (!out_.summary.exceeded_limit_time_s && xa[0] < alpha_e && xb[0] >= alpha_e) {
        out_.summary.exceeded_limit_time_s =
            locate([&](double t) { return edge_.dense(t)[0] - alpha_e; }, ta, tb2, xa[0] - alpha_e, xb[0] - alpha_e);
      }
      if (xb[0] >= half_pi && xa[0] < half_pi) {
        const double tf = locate([&](double t) { return edge_.dense(t)[0] - half_pi; }, ta, tb2, xa[0] - half_pi,
                                 xb[0] - half_pi);
        fall(tf, edge_.dense(tf));
        return;
      }
      const auto [Fa0, Fb0] = edge_forces(xa[0], xa[1], ta);
      const auto [Fa1, Fb1] = edge_forces(xb[0], xb[1], tb2);
      // The total vertical force vanishing is reported (the first time) and the contact kept, as the planar engine
      // does (Housner's model); an end unloading while the other still carries the body starts a pivot.
      if (Fa0 + Fb0 > 0.0 && !(Fa1 + Fb1 > 0.0)) {
        note_flight(locate([&](double t) {
          const S2 x = edge_.dense(t);
          const auto [Fa, Fb] = edge_forces(x[0], x[1], t);
          return Fa + Fb;
        }, ta, tb2, Fa0 + Fb0, Fa1 + Fb1));
      }
      double t_force = std::numeric_limits<double>::infinity();
      int unloaded = 0;  // +1: the end b unloads (pivot on a); -1: the end a unloads (pivot on b)
      const bool loaded = Fa0 + Fb0 > 0.0 && Fa1 + Fb1 > 0.0;
      if (loaded && Fb1 < 0.0 && Fb0 >= 0.0) {
        t_force = locate([&](double t) {
          const S2 x = edge_.dense(t);
          return edge_forces(x[0], x[1], t).second;
        }, ta, tb2, Fb0, Fb1);
        unloaded = 1;
      }
      if (loaded && Fa1 < 0.0 && Fa0 >= 0.0) {
        const double tfa = locate([&](double t) {
          const S2 x = edge_.dense(t);
          return edge_forces(x[0], x[1], t).first;
        }, ta, tb2, Fa0, Fa1);
        if (tfa < t_force) {
          t_force = tfa;
          unloaded = -1;
        }
      }
      double t_impact = std::numeric_limits<double>::infinity();
      if (xb[0] <= 0.0 && xa[0] > 0.0) {
        t_impact = locate([&](double t) { return edge_.dense(t)[0]; }, ta, tb2, xa[0], xb[0]);
      } else if (xb[0] <= 0.0 && from_rest_) {
        // a lift-off that did not happen: theta stayed at 0 and round-off sent it below; back to full contact
        t_ = tb2;
        xe_ = {0.0, 0.0};
        go_rest(0.0);
        row();
        return;
      }
      if (t_impact < std::numeric_limits<double>::infinity() && t_impact <= t_force) {
        const S2 x = edge_.dense(t_impact);
        t_ = t_impact;
        xe_ = {0.0, x[1]};
        from_rest_ = false;
        land_flat();
        return;
      }
      if (unloaded != 0) {
        const S2 x = edge_.dense(t_force);
        t_ = t_force;
        xe_ = x;
        track(t_, orientation());
        const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(edge_index_)];
        const Quaternion q = orientation();
        from_rest_ = false;
        start_pivot(unloaded > 0 ? e.a : e.b, q, x[1] * e.e_b);
        row();
        return;
      }
      if (piece == 0 && tp < t1) {  // a turning point: track the peak
        xe_ = edge_.dense(tp);
        const double t_save = t_;
        t_ = tp;
        track(tp, orientation());
        t_ = t_save;
      }
      if (tp >= t1) break;
    }
    t_ = t1;
    xe_ = x1;
    if (xe_[0] > 0.0) from_rest_ = false;
    track(t_, orientation());
  }

  // ---- pivoting on a vertex ----
  /// One step, and its events on kPivotSubdivisions equal parts of it (the dense output sampled so that a vertex that
  /// lifts and comes down again within one step, as after a flat landing, where every event function starts at 0,
  /// is found): the fall (cos tilt = 0), a vertex touching down, a tilt maximum (tracked), the vertical force
  /// vanishing (reported).
  void pivot_phase(double tb) {
    if (restart_) {
      const Quaternion qn = normalized({xv_[0], xv_[1], xv_[2], xv_[3]});
      for (std::size_t i = 0; i < 4; ++i) xv_[i] = qn[i];
      pivot_.restart(t_, xv_);
      restart_ = false;
    }
    if (!pivot_.step(tb, out_.summary.steps, opt_.max_steps)) step_limit();
    const double t0 = pivot_.t0();
    const double t1 = pivot_.t1();
    const auto cos_tilt = [](const S7& x) { return rotation({x[0], x[1], x[2], x[3]})[2][2]; };
    double ta = t0;
    S7 xa = pivot_.x0();
    bool lifted = !from_rest_;
    for (int k = 1; k <= kPivotSubdivisions; ++k) {
      const double tb2 = k == kPivotSubdivisions ? t1 : t0 + (t1 - t0) * k / kPivotSubdivisions;
      const S7 xb = pivot_.dense(tb2);
      if (cos_tilt(xb) <= 0.0 && cos_tilt(xa) > 0.0) {
        const double tf = locate([&](double t) { return cos_tilt(pivot_.dense(t)); }, ta, tb2, cos_tilt(xa),
                                 cos_tilt(xb));
        fall(tf, pivot_.dense(tf));
        return;
      }
      double t_touch = std::numeric_limits<double>::infinity();
      int touched = -1;
      bool any_up = false;
      for (std::size_t j = 0; j < geo_.n; ++j) {
        if (static_cast<int>(j) == vertex_) continue;
        const double za = vertex_height(xa, j);
        const double zb = vertex_height(xb, j);
        any_up = any_up || zb > eps_z_;
        double tt = std::numeric_limits<double>::infinity();
        const auto height = [&](double t) { return vertex_height(pivot_.dense(t), j); };
        if (zb <= 0.0 && za > eps_z_) {
          tt = locate(height, ta, tb2, za, zb);
        } else if (zb < 0.0 && vertex_rate(xa, j) > 0.0 && vertex_rate(xb, j) < 0.0) {
          // it left the ground at the start (a flat landing or a lift-off) and came down within the part: locate its
          // highest point, then the touch-down after it
          const double tp = locate([&](double t) { return vertex_rate(pivot_.dense(t), j); }, ta, tb2,
                                   vertex_rate(xa, j), vertex_rate(xb, j));
          // above eps_z_, as the first case: a vertex that starts at rest on the ground and only grazes it (a rate
          // of round-off size at a lift-off) has not left it
          const double zp = height(tp);
          if (zp > eps_z_) tt = locate(height, tp, tb2, zp, zb);
        }
        if (tt < t_touch) {
          t_touch = tt;
          touched = static_cast<int>(j);
        }
      }
      if (!lifted && !any_up && touched < 0) {
        // a lift-off that did not happen: from rest, the base has not left the ground (round-off sent it below)
        bool below = false;
        for (std::size_t j = 0; j < geo_.n; ++j) {
          if (static_cast<int>(j) != vertex_ && vertex_height(xb, j) < 0.0) below = true;
        }
        if (below) {
          t_ = tb2;
          xv_ = xb;
          go_rest(0.0);
          row();
          return;
        }
      }
      lifted = lifted || any_up;
      const double Fa = pivot_force(xa, ta);
      const double Fb = pivot_force(xb, tb2);
      if (Fa > 0.0 && !(Fb > 0.0)) {
        const double tfl = locate([&](double t) { return pivot_force(pivot_.dense(t), t); }, ta, tb2, Fa, Fb);
        if (tfl < t_touch) note_flight(tfl);
      }
      if (touched >= 0) {
        t_ = t_touch;
        xv_ = pivot_.dense(t_touch);
        from_rest_ = false;
        touch_down(touched);
        return;
      }
      const double ra = tilt_rate(xa);
      const double rb = tilt_rate(xb);
      if (ra > 0.0 && rb <= 0.0) {
        const double tp = locate([&](double t) { return tilt_rate(pivot_.dense(t)); }, ta, tb2, ra, rb);
        const S7 save = xv_;
        xv_ = pivot_.dense(tp);
        track(tp, orientation());
        xv_ = save;
      }
      ta = tb2;
      xa = xb;
    }
    t_ = t1;
    xv_ = pivot_.x1();
    if (lifted) from_rest_ = false;
    track(t_, orientation());
  }

  void note_flight(double t) {
    if (out_.summary.flight_time_s) return;
    out_.summary.flight_time_s = t;
    out_.summary.warnings.push_back(fmt::format("t = {} s: the vertical contact force vanished (the body would leave "
                                                "the ground); free flight is not modelled: the contact was kept, as "
                                                "the planar engine keeps it", t));
  }

  // ---- impacts (header; docs/method.md, "Impact law": a perfectly plastic, sticking impact solved as a small linear
  // complementarity problem over the contacts active at the instant) ----
  /// Angular momentum per unit mass about the ground point Q of the rotation omega (ground frame) about the fixed
  /// point F (positions relative to the old contact, the origin here): J_w omega + (c - Q) x (omega x (c - F)).
  [[nodiscard]] Vec3 momentum_about(const M3& R, const Vec3& omega, const Vec3& c_w, const Vec3& F,
                                    const Vec3& Q) const {
    const Vec3 wb = mul_t(R, omega);
    const Vec3 Jw = mul(R, mul(geo_.J, wb));
    return Jw + cross(c_w - Q, cross(omega, c_w - F));
  }

  /// Kinetic energy per unit mass of the rotation omega (ground frame) about the fixed body point pb.
  [[nodiscard]] double kinetic(const M3& R, const Vec3& omega, const Vec3& pb) const {
    const Vec3 wb = mul_t(R, omega);
    return 0.5 * dot(wb, mul(shifted_inertia(geo_.J, geo_.c - pb), wb));
  }

  struct Outcome {
    bool ok = false;
    int edge = -1;    // rocking about this edge, or
    int vertex = -1;  // pivoting on this vertex (both -1 with ok: the flat base at rest)
    Vec3 omega{};     // after (ground frame)
    double violation = std::numeric_limits<double>::infinity();  // of the complementarity conditions, relative:
    double pull = 0.0;         // of the impulses' sign (a contact that would have to pull), and
    double penetration = 0.0;  // of the other contacts' velocities (one that would move into the ground)
  };

  /// The impact law. Just before the impact the body turns with omega (ground frame) about its old contact, the body
  /// point pb_old (an end of the rocking edge, or the pivot), which is the origin of this computation; R is the
  /// orientation at the impact; `active` the vertices on the ground at that instant (the old contact among them);
  /// `flat`: the whole base is down. The impact is perfectly plastic and sticking (Newton's e = 0, friction large
  /// enough that no contact slides: the model's assumption): the contacts that carry an impulse end at rest, the
  /// others carry none. Which ones carry it is a linear complementarity problem (Moreau 1988; Glocker & Pfeiffer
  /// 1995; Pfeiffer & Glocker 1996, ch. 7), solved here by enumerating its complementary sets, the body's modes:
  ///   vertex p alone  the impulse at p only, so the angular momentum about p is conserved (Housner 1963 in 3-D):
  ///                   J_p w+ = H_p-; its vertical impulse v_cz+ - v_cz- >= 0;
  ///   edge (a, b)     impulses at both ends, the momentum about the edge's axis conserved: J_e theta'+ = e . H_a-;
  ///                   each end's vertical impulse >= 0 (the end b's from the moment balance about a:
  ///                   Lambda_bz = n . (H_a+ - H_a-) / L, n = e x z; the end a's the rest of Lambda_z);
  ///   flat            (the whole base down) w+ = 0: the impulse -v_c- and the moment -H_O- need a vertical
  ///                   resultant >= 0 acting at a point of the base (the centre of the impulses' pressure);
  /// and in every case each active vertex that carries no impulse has a normal velocity >= 0 after it (it lifts or
  /// stays). The set that meets every condition is the solution; this is the old contact lifting at once when the
  /// new one alone can carry the impulse (a corner landing next to a pivot pivots on the new corner), and Housner's
  /// law (a block onto its opposite edge) where that is the solution. Tolerances: each condition relative to
  /// |w-| size (velocities and vertical impulses per unit mass) or to size (the centre of pressure); when no set
  /// meets them all (round-off at a tie) the least violating one is taken. Ties within the tolerance prefer the set
  /// with more contacts (flat, then an edge, then a vertex): its motion is the one a smaller violation would pick.
  [[nodiscard]] Outcome impact(const M3& R, const Vec3& omega, const Vec3& pb_old, const std::vector<int>& active,
                               bool flat) const {
    const Vec3 cw = mul(R, geo_.c - pb_old);
    const Vec3 zero{0.0, 0.0, 0.0};
    const double w_norm = norm(omega);
    const double v_scale = std::max(w_norm * geo_.size, std::numeric_limits<double>::min());
    const double vcz_before = cross(omega, cw)[2];
    std::vector<Vec3> P(geo_.n);  // the vertices relative to the old contact
    for (std::size_t k = 0; k < geo_.n; ++k) P[k] = mul(R, geo_.v[k] - pb_old);
    const auto is_active = [&](int k) { return std::find(active.begin(), active.end(), k) != active.end(); };
    // the largest violation of "every active vertex not in S moves up or stays" (relative), for w+ about F
    const auto lift_violation = [&](const Vec3& w, const Vec3& F, int s1, int s2) {
      double worst = -std::numeric_limits<double>::infinity();
      for (const int k : active) {
        if (k == s1 || k == s2) continue;
        worst = std::max(worst, -cross(w, P[static_cast<std::size_t>(k)] - F)[2] / v_scale);
      }
      return worst;
    };
    constexpr double kTol = 1e-9;
    Outcome best;            // the first set that meets every condition (flat, edges, vertices), else the least violating
    Outcome best_no_entry;   // the least pulling among the sets that move no contact into the ground
    best_no_entry.pull = std::numeric_limits<double>::infinity();
    const auto consider = [&](Outcome o) {
      o.violation = std::max(o.pull, o.penetration);
      if (!(best.violation <= kTol && o.violation <= kTol) && o.violation < best.violation) best = o;
      if (o.penetration <= kTol && o.pull < best_no_entry.pull) best_no_entry = o;
    };
    if (flat) {
      Outcome o;
      o.ok = true;
      const Vec3 H = momentum_about(R, omega, cw, zero, zero);
      const double Lz = -vcz_before;  // the vertical impulse that stops c
      double viol = -Lz / v_scale;
      if (Lz > 0.0) {
        const Vec3 X{H[1] / Lz, -H[0] / Lz, 0.0};  // where the resultant of the vertical impulses acts
        for (std::size_t k = 0; k < geo_.n; ++k) {
          const Vec3& A = P[k];
          const Vec3& B = P[(k + 1) % geo_.n];
          const Vec3 d = B - A;
          const double inside = (d[0] * (X[1] - A[1]) - d[1] * (X[0] - A[0])) / norm(d);  // > 0 inside (CCW)
          viol = std::max(viol, -inside / geo_.size);
        }
      }
      o.pull = viol;
      consider(o);
    }
    for (const EdgeGeom& e : geo_.edges) {
      if (!is_active(e.a) || !is_active(e.b)) continue;
      const Vec3 F = P[static_cast<std::size_t>(e.a)];
      Vec3 ew = mul(R, e.e_b);
      ew[2] = 0.0;
      ew = (1.0 / norm(ew)) * ew;
      const Vec3 H = momentum_about(R, omega, cw, zero, F);
      Outcome o;
      o.ok = true;
      o.edge = e.a;
      o.omega = (dot(ew, H) / e.J) * ew;
      const Vec3 dH = momentum_about(R, o.omega, cw, F, F) - H;
      const double Lz = cross(o.omega, cw - F)[2] - vcz_before;
      const double Lbz = dot(cross(ew, kUp), dH) / e.length;
      const double Laz = Lz - Lbz;
      o.pull = std::max(-Laz / v_scale, -Lbz / v_scale);
      o.penetration = lift_violation(o.omega, F, e.a, e.b);
      consider(o);
    }
    for (const int p : active) {
      const VertexGeom& vg = geo_.vertices[static_cast<std::size_t>(p)];
      const Vec3 F = P[static_cast<std::size_t>(p)];
      const Vec3 H = momentum_about(R, omega, cw, zero, F);
      Outcome o;
      o.ok = true;
      o.vertex = p;
      o.omega = mul(R, mul(vg.Jp_inv, mul_t(R, H)));
      const double Lz = cross(o.omega, cw - F)[2] - vcz_before;
      o.pull = -Lz / v_scale;
      o.penetration = lift_violation(o.omega, F, p, -1);
      consider(o);
    }
    // No set meets them all: the conditions have no solution with contacts that stick (the impact would make a
    // contact slide, which the model excludes). The set that moves no contact into the ground and pulls least is
    // taken (at a corner landing next to the pivot: the edge, an end pulling a little), else the least violating.
    if (best.violation > kTol && best_no_entry.ok) best = best_no_entry;
    if (best.ok && opt_.restitution == RestitutionMode::given && (best.edge >= 0 || best.vertex >= 0)) {
      // the direction of the motion after the impact as above, the ratio of kinetic energies e^2
      const double before = kinetic(R, omega, pb_old);
      const Vec3 pb_new = best.edge >= 0 ? geo_.v[static_cast<std::size_t>(best.edge)]
                                         : geo_.v[static_cast<std::size_t>(best.vertex)];
      const double after = kinetic(R, best.omega, pb_new);
      if (after > 0.0) best.omega = (opt_.e * std::sqrt(before / after)) * best.omega;
    }
    return best;
  }

  /// Starts the motion the impact law chose (the orientation R, the old contact still current) and counts the
  /// energy lost; false (nothing counted): the body comes to rest, the flat set or the rest rule.
  bool after_impact(const Outcome& o, const M3& R, double theta, double ke_before) {
    if (o.edge < 0 && o.vertex < 0) return false;
    const Vec3 pb_new = geo_.v[static_cast<std::size_t>(o.edge >= 0 ? o.edge : o.vertex)];
    const double ke_after = kinetic(R, o.omega, pb_new);
    if (theta == 0.0) {  // a flat landing: the rest rule (as the planar engine's)
      const double lift = o.edge >= 0 ? geo_.edges[static_cast<std::size_t>(o.edge)].lift_energy
                                      : geo_.vertices[static_cast<std::size_t>(o.vertex)].lift_energy;
      if (ke_after < opt_.rest_energy_fraction * lift) return false;
    }
    out_.summary.energy_lost_j_per_kg += ke_before - ke_after;
    if (o.edge >= 0) {
      const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(o.edge)];
      Vec3 ew = mul(R, e.e_b);
      ew[2] = 0.0;
      start_rocking(o.edge, theta, dot(o.omega, (1.0 / norm(ew)) * ew));
    } else {
      start_pivot(o.vertex, orientation(), mul_t(R, o.omega));
    }
    row();
    return true;
  }

  /// The base lands flat (theta = 0 while rocking, or every vertex down while pivoting).
  void land_flat() {
    ++out_.summary.impacts;
    const Vec3 pb_old = contact_b();
    const Vec3 omega = omega_world();
    // Put the pose exactly flat (the tilt left is of the order of the event tolerance).
    const Quaternion q = orientation();
    const M3 Rt = rotation(q);
    const Vec3 zb{Rt[0][2], Rt[1][2], Rt[2][2]};
    const Vec3 axis = cross(zb, kUp);
    const double sa = norm(axis);
    const Quaternion flat = sa > 0.0 ? normalized(qmul(axis_angle((1.0 / sa) * axis, std::atan2(sa, zb[2])), q)) : q;
    const M3 R = rotation(flat);
    const double ke_before = kinetic(R, omega, pb_old);
    // pose: flat, contact unchanged (orientation() and contact_b() below read q_flat_ and rest_contact_)
    rest_contact_ = pb_old;
    mode_ = Rigid3DMode::rest;
    q_flat_ = flat;
    double vmin = 0.0;
    for (std::size_t j = 0; j < geo_.n; ++j) vmin = std::min(vmin, cross(omega, mul(R, geo_.v[j] - pb_old))[2]);
    if (!(vmin < 0.0)) {  // nothing comes down: no impulse, the body stays
      go_rest(ke_before);
      row();
      return;
    }
    std::vector<int> all(geo_.n);
    for (std::size_t j = 0; j < geo_.n; ++j) all[j] = static_cast<int>(j);
    const Outcome o = impact(R, omega, pb_old, all, true);
    note_violation(o);
    if (!after_impact(o, R, 0.0, ke_before)) {
      go_rest(ke_before);
      row();
    }
  }

  /// An impact whose conditions no set of sticking contacts meets (impact()): counted, and named once in the warnings.
  void note_violation(const Outcome& o) {
    if (!(o.violation > 1e-6)) return;
    if (++unmet_impacts_ == 1) {
      out_.summary.warnings.push_back(fmt::format("t = {} s: an impact that would make a contact slide (no set of "
                                                  "sticking contacts meets the impact law, by {:.2e} of |w| size); "
                                                  "the set that moves no contact into the ground and pulls least was "
                                                  "taken, here and at any later such impact", t_, o.violation));
    }
  }

  /// While pivoting, vertex j touched the ground.
  void touch_down(int j) {
    const Quaternion q = orientation();
    const M3 R = rotation(q);
    const Vec3 pb_old = contact_b();
    const int n = static_cast<int>(geo_.n);
    // The vertices on the ground at this instant: the pivot, j, and any other within tie_z_ (a base almost flat).
    // Three of a convex base down is the whole base: a flat landing.
    std::vector<int> active{vertex_, j};
    for (int k = 0; k < n; ++k) {
      if (k == vertex_ || k == j) continue;
      if (dot(R[2], geo_.v[static_cast<std::size_t>(k)] - pb_old) <= tie_z_) active.push_back(k);
    }
    if (active.size() > 2 || (j != (vertex_ + 1) % n && (j + 1) % n != vertex_)) {
      land_flat();
      return;
    }
    const Vec3 omega = omega_world();
    const double ke_before = kinetic(R, omega, pb_old);
    const double theta = std::atan2(std::hypot(R[0][2], R[1][2]), R[2][2]);
    ++out_.summary.impacts;
    Outcome o = impact(R, omega, pb_old, active, false);
    note_violation(o);
    if (o.vertex == j) {
      // The old pivot lifts. While it is the edge's other end, what separates the pivot on j from rocking about the
      // edge is the kinetic energy of the motion's part off the edge's axis (the edge's part, e . J_j w / J_e, is
      // that of the edge impact: the momentum along the axis is the same about both ends). Each swap of the pivot
      // between the two ends removes part of it (a Zeno sequence of ever shorter pivots, whose limit is the rocking
      // about the edge); below kZenoEnergyFraction of the kinetic energy the engine takes that limit.
      const int edge = j == (vertex_ + 1) % n ? vertex_ : j;
      const EdgeGeom& e = geo_.edges[static_cast<std::size_t>(edge)];
      Vec3 ew = mul(R, e.e_b);
      ew[2] = 0.0;
      ew = (1.0 / norm(ew)) * ew;
      const Vec3 F = mul(R, geo_.v[static_cast<std::size_t>(j)] - pb_old);
      const double theta_dot = dot(ew, momentum_about(R, o.omega, mul(R, geo_.c - pb_old), F, F)) / e.J;
      const double ke_vertex = kinetic(R, o.omega, geo_.v[static_cast<std::size_t>(j)]);
      if (ke_vertex - 0.5 * e.J * theta_dot * theta_dot <= kZenoEnergyFraction * ke_vertex) {
        o.vertex = -1;
        o.edge = edge;
        o.omega = theta_dot * ew;
      }
    }
    if (!after_impact(o, R, theta, ke_before)) {
      // no motion chosen (cannot happen with a tilted base: the flat set is not a candidate); keep the edge
      out_.summary.energy_lost_j_per_kg += ke_before;
      start_rocking(j == (vertex_ + 1) % n ? vertex_ : j, theta, 0.0);
      row();
    }
  }

  void fall(double t, const auto& x) {
    t_ = t;
    if constexpr (std::tuple_size_v<std::decay_t<decltype(x)>> == 2) {
      xe_ = x;
    } else {
      xv_ = x;
    }
    const Quaternion q = orientation();
    track(t, q);
    const M3 R = rotation(q);
    auto& s = out_.summary;
    s.overturned = true;
    s.overturn_time_s = t;
    s.overturn_azimuth_deg = azimuth({R[0][2], R[1][2], 0.0});
    row();
    mode_ = Rigid3DMode::fallen;
    s.modes.push_back({t, Rigid3DMode::fallen, -1, -1});
    if (opt_.record_history) {
      // The fallen row repeats the state at the fall: row() would take the resting orientation (orientation() has
      // no fallen state) and report the body upright, at rest, after its fall.
      auto& h = out_.history;
      h.time_s.push_back(t);
      h.position_m.push_back(Vec3(h.position_m.back()));
      h.orientation.push_back(Quaternion(h.orientation.back()));
      h.angular_velocity_rad_s.push_back(Vec3(h.angular_velocity_rad_s.back()));
      h.energy_j_per_kg.push_back(double(h.energy_j_per_kg.back()));
      h.mode.push_back(Rigid3DMode::fallen);
    }
    done_ = true;
  }

  [[noreturn]] void step_limit() const {
    throw StepLimitError(fmt::format("rock3d: more than max_steps = {} integrator steps by t = {} s", opt_.max_steps,
                                     t_));
  }

  template <class Fn>
  double locate(Fn f, double ta, double tb, double fa, double fb) const {
    const double r = detail::find_root(f, ta, tb, fa, fb);
    if (std::isnan(r)) {
      throw RootFindingError(fmt::format("rock3d: event location did not converge on [{}, {}] s", ta, tb));
    }
    return r;
  }

  void run_out() {
    if (mode_ == Rigid3DMode::rest || opt_.max_run_out_s == 0.0) return;
    const double t_end = t_;
    forcing_ = Forcing::still(t_end, frame_.still);  // level: (0, 0, g)
    restart_ = true;
    run_out_on_still_ground(
        t_end, grid_.dt_s(), opt_.max_run_out_s, t_, [this] { return !done_ && mode_ != Rigid3DMode::rest; },
        [this](double tb) { interval(tb); },
        [this] {
          if (!done_) row();
        });
  }

  static constexpr int kMaxEventsPerInterval = 100'000;
  static constexpr int kPivotSubdivisions = 4;
  static constexpr double kZenoEnergyFraction = 1e-8;  // touch_down: a pivot swap's wobble taken as the edge's limit
  double start_time_s_ = 0.0;
  const InputGrid& grid_;
  std::span<const double> ax_, ay_;
  std::vector<double> gravity_;
  const Geometry& geo_;
  const Rigid3DOptions& opt_;
  double g_ = opt_.g_m_s2;
  BaseFrame frame_ = BaseFrame::make(opt_.base_incline_deg, opt_.base_incline_azimuth_deg, opt_.g_m_s2);
  Dp5<2, EdgeRhs> edge_;
  Dp5<7, PivotRhs> pivot_;
  Forcing forcing_{};
  Rigid3DResult out_;
  double t_ = 0.0;
  Rigid3DMode mode_ = Rigid3DMode::rest;
  bool restart_ = true;
  bool done_ = false;
  bool from_rest_ = false;
  double eps_z_ = 0.0, tie_z_ = 0.0;
  std::size_t unmet_impacts_ = 0;  // impacts whose law no set of sticking contacts meets (note_violation)
  // rocking
  int edge_index_ = -1;
  Vec3 e_w_{}, n_w_{};
  S2 xe_{};
  // pivot
  int vertex_ = -1;
  S7 xv_{};
  // pose
  Quaternion q_flat_ = kIdentityQuaternion;  // rest: the pose; rocking: the pose at theta = 0
  Vec3 P_w_{};                               // the contact point in the ground frame
  Vec3 rest_contact_{};
  std::vector<std::array<double, 3>> rest_edges_;
  double x_lo_ = 0.0, x_hi_ = 0.0;  // rest: h n_x, h n_y (ground frame) and b_e per edge
};

void check_options(const Rigid3DOptions& o) {
  require_positive(o.g_m_s2, "g", "g");
  if (o.restitution == RestitutionMode::given && (!std::isfinite(o.e) || o.e < 0.0 || o.e > 1.0)) {
    throw parameter_error("e", fmt::format("coefficient of restitution must be in [0, 1], got {}", o.e));
  }
  if (!std::isfinite(o.rel_tol) || !(o.rel_tol > 0.0) || o.rel_tol >= 1.0) {
    throw parameter_error("rel_tol", fmt::format("relative tolerance must be in (0, 1), got {}", o.rel_tol));
  }
  if (!std::isfinite(o.abs_tol) || !(o.abs_tol > 0.0)) {
    throw parameter_error("abs_tol", fmt::format("absolute tolerance must be positive and finite, got {}", o.abs_tol));
  }
  if (!std::isfinite(o.rest_energy_fraction) || !(o.rest_energy_fraction > 0.0) || o.rest_energy_fraction >= 1.0) {
    throw parameter_error("rest_energy_fraction", fmt::format("must be in (0, 1), got {}", o.rest_energy_fraction));
  }
  if (!std::isfinite(o.simultaneous_contact) || o.simultaneous_contact < 0.0 || o.simultaneous_contact > 0.01) {
    throw parameter_error("simultaneous_contact", fmt::format("must be in [0, 0.01], got {}", o.simultaneous_contact));
  }
  if (!std::isfinite(o.max_run_out_s) || o.max_run_out_s < 0.0) {
    throw parameter_error("max_run_out_s", fmt::format("must be >= 0 and finite, got {}", o.max_run_out_s));
  }
  if (o.max_steps < 1) throw parameter_error("max_steps", "the integrator needs at least 1 step, got 0");
  if (!std::isfinite(o.base_incline_deg) || o.base_incline_deg < 0.0 || o.base_incline_deg >= 90.0) {
    throw parameter_error("base_incline_deg", fmt::format("the base's inclination must be in [0, 90) degrees, got {}",
                                                          o.base_incline_deg));
  }
  if (!std::isfinite(o.base_incline_azimuth_deg)) {
    throw parameter_error("base_incline_azimuth_deg",
                          fmt::format("the downhill azimuth must be finite, got {}", o.base_incline_azimuth_deg));
  }
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------
// The body.

RigidBody3D RigidBody3D::box(double width_m, double depth_m, double height_m) {
  const auto check = [](double v, const char* field) {
    require_positive(v, field, field);
    if (v > kMaxBodyDimension_m) {
      throw parameter_error(field, fmt::format("{} = {} m exceeds {} m", field, v, kMaxBodyDimension_m));
    }
  };
  check(width_m, "width");
  check(depth_m, "depth");
  check(height_m, "height");
  const double a = 0.5 * width_m;
  const double b = 0.5 * depth_m;
  RigidBody3D body;
  body.base_xy_m = {{-a, -b}, {a, -b}, {a, b}, {-a, b}};
  body.centre_of_mass_m = {0.0, 0.0, 0.5 * height_m};
  // uniform box: I_xx / m = (d^2 + H^2) / 12, ...
  const double w2 = width_m * width_m, d2 = depth_m * depth_m, h2 = height_m * height_m;
  body.inertia_cm_m2 = {{{(d2 + h2) / 12.0, 0.0, 0.0}, {0.0, (w2 + h2) / 12.0, 0.0}, {0.0, 0.0, (w2 + d2) / 12.0}}};
  return body;
}

RigidBody3D RigidBody3D::polygon(std::vector<std::array<double, 2>> base_xy_m, Vec3 centre_of_mass_m,
                                 std::array<Vec3, 3> inertia_cm_m2) {
  const std::size_t n = base_xy_m.size();
  if (n < 3) throw parameter_error("base", fmt::format("a base polygon needs at least 3 vertices, got {}", n));
  double extent = 0.0;
  for (const auto& p : base_xy_m) {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || std::abs(p[0]) > kMaxBodyDimension_m ||
        std::abs(p[1]) > kMaxBodyDimension_m) {
      throw parameter_error("base", "every vertex must be finite and within the largest body dimension");
    }
    extent = std::max({extent, std::abs(p[0]), std::abs(p[1])});
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = base_xy_m[i];
    const auto& b = base_xy_m[(i + 1) % n];
    const auto& c = base_xy_m[(i + 2) % n];
    const double turn = (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
    if (!(turn > 1e-12 * extent * extent)) {
      throw parameter_error("base", fmt::format("the base polygon must be strictly convex and counter-clockwise; "
                                                "vertex {} is not (turn {})", i + 2, turn));
    }
  }
  const Vec3& c = centre_of_mass_m;
  if (!std::isfinite(c[0]) || !std::isfinite(c[1]) || !std::isfinite(c[2]) || !(c[2] > 0.0) ||
      c[2] > kMaxBodyDimension_m) {
    throw parameter_error("centre_of_mass", "the centre of mass must be finite with a height h > 0 above the base");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = base_xy_m[i];
    const auto& b = base_xy_m[(i + 1) % n];
    const double side = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if (!(side > 0.0)) {
      throw parameter_error("centre_of_mass", "the centre of mass must lie strictly inside the base polygon in plan "
                                              "(else the body does not stand)");
    }
  }
  const auto& J = inertia_cm_m2;
  // Symmetric to 1e-9 of the tensor's largest diagonal component: relative to the pair alone, two off-diagonal
  // components that are round-off of zero (a square base turned about the vertical, rotated_about_vertical: J_xy =
  // (J_xx - J_yy) sin cos, -3.5e-18 and +3.5e-18 at 0.5 rad) were refused, and the friction engine, which checks a
  // body again, failed on such a turned box.
  const double scale = std::max({std::abs(J[0][0]), std::abs(J[1][1]), std::abs(J[2][2])});
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      if (!std::isfinite(J[i][j])) throw parameter_error("inertia", "every component must be finite");
      if (std::abs(J[i][j] - J[j][i]) > 1e-9 * std::max(scale, std::abs(J[i][j]) + std::abs(J[j][i]))) {
        throw parameter_error("inertia", "the inertia tensor must be symmetric");
      }
    }
  }
  // positive definite (Sylvester) and the triangle inequality of the diagonal (J_xx <= J_yy + J_zz ...)
  const double m1 = J[0][0];
  const double m2 = J[0][0] * J[1][1] - J[0][1] * J[1][0];
  const double m3 = dot(J[0], cross(J[1], J[2]));
  if (!(m1 > 0.0 && m2 > 0.0 && m3 > 0.0) || J[0][0] > J[1][1] + J[2][2] || J[1][1] > J[0][0] + J[2][2] ||
      J[2][2] > J[0][0] + J[1][1]) {
    throw parameter_error("inertia", "the inertia tensor per unit mass must be positive definite and a real body's "
                                     "(each principal moment at most the sum of the other two)");
  }
  RigidBody3D body;
  body.base_xy_m = std::move(base_xy_m);
  body.centre_of_mass_m = c;
  body.inertia_cm_m2 = J;
  return body;
}

RigidBody3D RigidBody3D::from_mesh(const MeshBody& mesh) {
  std::array<Vec3, 3> J{};
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) J[i][j] = mesh.mass.inertia_cm_kg_m2[i][j] / mesh.mass.mass_kg;
  }
  const Vec3& c = mesh.mass.centre_of_mass_m;
  return polygon(mesh.support.hull_xy_m, {c[0], c[1], c[2] - mesh.support.z_m}, J);
}

RigidBody3D RigidBody3D::rotated_about_vertical(double angle_rad) const {
  const double cs = std::cos(angle_rad);
  const double sn = std::sin(angle_rad);
  const M3 Rz{{{cs, -sn, 0.0}, {sn, cs, 0.0}, {0.0, 0.0, 1.0}}};
  RigidBody3D out = *this;
  for (auto& p : out.base_xy_m) p = {cs * p[0] - sn * p[1], sn * p[0] + cs * p[1]};
  out.centre_of_mass_m = mul(Rz, centre_of_mass_m);
  for (std::size_t i = 0; i < 3; ++i) {  // R J R^T
    for (std::size_t j = 0; j < 3; ++j) {
      double s = 0.0;
      for (std::size_t k = 0; k < 3; ++k) {
        for (std::size_t l = 0; l < 3; ++l) s += Rz[i][k] * inertia_cm_m2[k][l] * Rz[j][l];
      }
      out.inertia_cm_m2[i][j] = s;
    }
  }
  return out;
}

double RigidBody3D::static_tilt_limit_rad(double azimuth_deg) const {
  const double a = deg_to_rad(azimuth_deg);
  double b = -std::numeric_limits<double>::infinity();
  for (const auto& p : base_xy_m) {
    b = std::max(b, (p[0] - centre_of_mass_m[0]) * std::sin(a) + (p[1] - centre_of_mass_m[1]) * std::cos(a));
  }
  return std::atan2(b, centre_of_mass_m[2]);
}

constexpr std::array<EnumName<Rigid3DMode>, 7> kModeNames{{
    {Rigid3DMode::rest, "rest"},
    {Rigid3DMode::rocking, "rocking"},
    {Rigid3DMode::pivot, "pivot"},
    {Rigid3DMode::fallen, "fallen"},
    {Rigid3DMode::sliding, "sliding"},
    {Rigid3DMode::slide_rock, "slide_rock"},
    {Rigid3DMode::flight, "flight"},
}};

std::string_view rigid3d_mode_name(Rigid3DMode mode) { return enum_name(kModeNames, mode); }

Rigid3DResult rock3d(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z, const RigidBody3D& body,
                     const Rigid3DOptions& options) {
  check_options(options);
  if (options.mu_s || options.mu_k) return detail::rock3d_friction(x, y, z, body, options);  // rigid3d_slide.cpp
  if (options.base_incline_deg != 0.0) {  // the engine in the base's frame (header, "Inclined base")
    const detail::BaseRecords base = detail::base_records(x, y, z, options);
    return detail::rock3d_rigid(*base.x, &*base.y, &*base.z, body, options, -std::numeric_limits<double>::infinity());
  }
  return detail::rock3d_rigid(x, y, z, body, options, -std::numeric_limits<double>::infinity());
}

Rigid3DResult detail::rock3d_rigid(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                   const RigidBody3D& body, const Rigid3DOptions& options, double start_time_s) {
  const RigidBody3D checked = RigidBody3D::polygon(body.base_xy_m, body.centre_of_mass_m, body.inertia_cm_m2);
  const std::array<const GroundMotion*, 3> components{&x, y, z};
  const InputGrid grid(components);
  std::vector<double> gravity = effective_gravity(grid, 2, options.g_m_s2);
  if (!gravity.empty()) {
    const double lowest = *std::min_element(gravity.begin(), gravity.end());
    if (!(lowest > 0.0)) {
      if (options.base_incline_deg != 0.0) {  // z: the load normal to the inclined base, less g
        throw parameter_error("vertical", fmt::format("the load normal to the inclined base (gravity's and the "
                                                      "ground's) falls to {} m/s2 <= 0: the body would leave the "
                                                      "base, which this model excludes", lowest));
      }
      throw parameter_error("vertical", fmt::format("the vertical acceleration reaches {} m/s2, so g + a_z = {} m/s2 "
                                                    "<= 0: the body would leave the ground, which this model excludes",
                                                    lowest - options.g_m_s2, lowest));
    }
  }
  const Geometry geo = make_geometry(checked, options.g_m_s2);
  Engine engine(grid, std::move(gravity), geo, options, start_time_s);
  return engine.run();
}

Rigid3DOptions rigid3d_options(const RockingOptions& rocking) {
  Rigid3DOptions o;
  o.g_m_s2 = rocking.g_m_s2;
  o.restitution = rocking.restitution;
  o.e = rocking.e;
  o.rel_tol = rocking.rel_tol;
  o.max_run_out_s = rocking.max_run_out_s;
  o.max_steps = rocking.max_steps;
  return o;
}

}  // namespace topple
