// The three-dimensional engine with slipping contacts and free flight (issue 29; docs/method.md, "Slide-rock and
// flight in three dimensions"; rigid3d.hpp). rock3d_friction (rigid3d_slide.cpp) hands a run to it where the flat
// sliding phase or the no-slip engine would stop or be wrong: the centre of pressure leaving the base while the body
// slides (slide-rock), a rocking or pivoting contact that needs more friction than mu_s N, sliding after an uplift,
// or the ground's vertical acceleration exceeding g (flight).
//
// Model (per unit mass, in the ground frame, which translates with the ground: the inertial force -a_g and gravity
// -g z act at c). The body is a free rigid body: c's position and velocity, the orientation q (body -> ground) and
// the angular velocity w (ground frame), with an active set of base vertices on the ground, each sticking or
// slipping. For a set, the contact forces F_k (at the vertices p_k, r_k = p_k - c) and the accelerations solve the
// constrained Newton-Euler equations
//   a_c = f + sum F_k,   J_w alpha = sum r_k x F_k - w x J_w w,   J_w = R J R^T,
//   the acceleration of contact k, a_k = a_c + alpha x r_k + w x (w x r_k) = b_k + sum_m W_km F_m,
//   W_km F = F - r_k x (J_w^-1 (r_m x F)),   b_k = f + alpha_0 x r_k + w x (w x r_k),  alpha_0 = -J_w^-1 (w x J_w w),
// with, per contact: a_k . z = 0 (the contact stays on the ground); sticking: a_k . x = a_k . y = 0; slipping with
// the unit slip velocity s: F_k = N_k (-mu_k s + z) (Coulomb). The system is linear and small (<= 6 unknowns for an
// edge) and solved by Gaussian elimination with partial pivoting. Both ends of an edge sticking leave the forces
// along the edge indeterminate (equal and opposite forces along the line of the two points move nothing): the
// second end's force along the edge is set to 0 in the solve and the total along the edge is then shared in
// proportion to the contacts' spare capacities in their cones, so that the pair sticks whenever some share would
// (contact_forces; a stated choice: it decides only the stick test, not the motion).
// The flat base (three or more vertices down) is handled as rigid3d_slide.cpp's flat phase: stuck (rest) or
// translating with F_t = -mu_k N s, N = g + a_z, no rotation, lifting where the centre of pressure leaves the base.
// Flight: a_c = f, Euler's equations about c.
//
// Mode choice (the contact LCP solved by enumeration, slide_rock.hpp's order generalised): the candidate sets are the
// vertices down (z and the normal velocity at zero); the flat base first (stuck, then slipping), then the edges, then
// single vertices, then flight; per set, contacts with zero slip velocity stick first, then slip, those with a slip
// velocity slip. The direction of a slip starting from rest (issue 29): Coulomb's law at the acceleration level, the
// slip acceleration along s and F_t = -mu_k N s, a root of an angle problem per contact (slip_directions: the stable
// root nearest the sticking force's opposite; at a stick limit the limit t -> t0+ by a short look-ahead), renewed at
// each step while the new slip is slower than kSlipStart p size; the former fixed-point rule where it has no root. The first set whose forces have N_k >= 0, |F_t,k| <= mu_s N_k for the sticking contacts,
// slip accelerations along the assumed direction for a starting slip, and whose other down vertices do not
// accelerate into the ground, is taken. None (Painleve's paradox, or round-off at a boundary): a slipping contact is
// stopped by a tangential impact (the sticking velocity impulse), a sticking one is held (slide_rock.hpp's rule);
// counted in Rigid3DSummary::painleve_events. Also counted there: a slip that stops within kChatter_s of its start
// is held sticking, and (hold_slow_slips) where one sample interval needs kSlowSteps steps while a contact slips slower
// than kSlipStart p size (stiff direction relaxation, or a slip spiralling in to rest) it is stopped and held sticking.
//
// Events, located by TOMS 748 on the Dormand-Prince dense output (4 parts per step, as the pivot mode of rigid3d.cpp):
// N_k -> 0 (lift), the slip velocity along its direction at the step's start -> 0 (stop or turn), |F_t| -> mu_s N
// (slip starts), another vertex's height -> 0 (impact), the tilt -> 90 degrees (fallen), in flight a vertex's height
// -> 0 (landing); flat: the centre of pressure crossing an edge, the slip velocity -> 0, |a_h| -> mu_s N, g + a_z ->
// 0. Tilt maxima are located as roots of the tilt's rate (the summary's max tilt).
// The ground's impenetrability (issue 29; docs/method.md): at a mode's start a vertex not in the set at a gap <= 0
// moving down strikes, one accelerating down joins the set (settle_down_vertices); a dip event per such vertex fires
// 1e-9 size below where it started (an impact); a striking vertex below the ground is levelled onto it (level_strike);
// and a vertex deeper than kPenetration of the size throws (track()).
//
// Impacts (Brogliato 1999, sec. 4.2; Glocker & Pfeiffer 1995; Shenton & Jones 1991, as slide_rock.hpp in the plane):
// plastic in the normal direction (the striking contacts' normal velocity after is 0), a Coulomb impulse
// tangentially: stick (contact velocity 0 after) when the impulse needed is inside the cone |P_t| <= mu_s P_n, else
// slip with P_t = -mu_k P_n s, s the contact's slip direction before the impact (or against the sticking impulse). The
// outcome is enumerated over the vertices down at the instant: the striking vertices alone (each, then an edge of
// them), then the edges and vertices with the old contacts, then the flat base; the first whose normal impulses are
// >= 0, whose sticking impulses are in the cones and whose other down vertices do not move into the ground. With
// friction large the sticking outcome is the no-slip engine's law (rigid3d.cpp; Housner's about the new contact). The
// flat outcome (none of those consistent) stops the vertical and tilting motion and the horizontal one if
// |v_h| <= mu_s |v_z| (else it slides with v_h reduced by mu_k |v_z|), and stops any twist (an approximation).
// Zeno (issue 29; docs/method.md, "The ground's impenetrability", rule 6): after kZenoSwaps pivot swaps in a row
// between the ends of one edge with ever slower strikes, both ends go down together (the frictionless plastic edge
// projection, taken where its impulses are >= 0 or it removes less than the rest rule's energy).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
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
#include "topple/numerics/event_root.hpp"

namespace topple::detail {
namespace {

using namespace r3d;
constexpr std::size_t kN = 15;  // c (3), v_c (3), q (4), w (3), slide path, friction work
using SX = State<kN>;

struct Contact {
  int v = 0;          // vertex index
  bool slip = false;  // slipping (else sticking)
  Vec3 s{};           // unit slip direction (ground plane) of a slipping contact
  bool fresh = false;  // a slip started from rest whose speed is still below kSlipStart (its direction: s)
};

/// Gaussian elimination with partial pivoting on an n x n system (row-major A), solution in b. False: singular.
bool gauss(std::vector<double>& A, std::vector<double>& b, std::size_t n) {
  double scale = 0.0;
  for (double a : A) scale = std::max(scale, std::abs(a));
  if (!(scale > 0.0)) return n == 0;
  for (std::size_t k = 0; k < n; ++k) {
    std::size_t p = k;
    for (std::size_t i = k + 1; i < n; ++i) {
      if (std::abs(A[i * n + k]) > std::abs(A[p * n + k])) p = i;
    }
    if (!(std::abs(A[p * n + k]) > 1e-13 * scale)) return false;
    if (p != k) {
      for (std::size_t j = 0; j < n; ++j) std::swap(A[k * n + j], A[p * n + j]);
      std::swap(b[k], b[p]);
    }
    for (std::size_t i = k + 1; i < n; ++i) {
      const double m = A[i * n + k] / A[k * n + k];
      if (m == 0.0) continue;
      for (std::size_t j = k; j < n; ++j) A[i * n + j] -= m * A[k * n + j];
      b[i] -= m * b[k];
    }
  }
  for (std::size_t k = n; k-- > 0;) {
    double s = b[k];
    for (std::size_t j = k + 1; j < n; ++j) s -= A[k * n + j] * b[j];
    b[k] = s / A[k * n + k];
  }
  return true;
}

/// The contact problem at one instant (accelerations or, for impacts, velocities: the same matrix W).
/// r: contact points from c; Jinv: J_w^-1; free_k: the contact's acceleration (velocity) without contact forces;
/// mu_k for slipping contacts. Returns the forces (impulses), or nothing where the system is singular.
std::optional<std::vector<Vec3>> contact_forces(const std::vector<Contact>& set, const std::vector<Vec3>& r,
                                                const M3& Jinv, const std::vector<Vec3>& free, double mu_k,
                                                double mu_s) {
  const std::size_t m = set.size();
  // Force directions (unknowns) and equation directions per contact.
  std::vector<std::vector<Vec3>> D(m), E(m);
  const Vec3 ex{1.0, 0.0, 0.0}, ey{0.0, 1.0, 0.0};
  bool edge_stick = m == 2 && !set[0].slip && !set[1].slip;
  Vec3 edge{};
  if (edge_stick) {
    edge = r[1] - r[0];
    edge = (1.0 / norm(edge)) * edge;
  }
  for (std::size_t k = 0; k < m; ++k) {
    if (set[k].slip) {
      D[k] = {Vec3{-mu_k * set[k].s[0], -mu_k * set[k].s[1], 1.0}};
      E[k] = {kUp};
    } else if (edge_stick && k == 1) {
      const Vec3 side = cross(kUp, edge);  // the edge's end: no force along the edge (its share is set after)
      D[k] = {kUp, side};
      E[k] = {kUp, side};
    } else {
      D[k] = {ex, ey, kUp};
      E[k] = {ex, ey, kUp};
    }
  }
  std::size_t n = 0;
  for (std::size_t k = 0; k < m; ++k) n += D[k].size();
  std::vector<double> A(n * n, 0.0), b(n, 0.0);
  std::size_t row = 0;
  for (std::size_t k = 0; k < m; ++k) {
    for (const Vec3& e : E[k]) {
      std::size_t col = 0;
      for (std::size_t j = 0; j < m; ++j) {
        for (const Vec3& d : D[j]) {
          // e . W_kj d = e . (d - r_k x (Jinv (r_j x d)))
          const Vec3 w = d - cross(r[k], mul(Jinv, cross(r[j], d)));
          A[row * n + col] = dot(e, w);
          ++col;
        }
      }
      b[row] = -dot(e, free[k]);
      ++row;
    }
  }
  if (!gauss(A, b, n)) return std::nullopt;
  std::vector<Vec3> F(m, Vec3{0.0, 0.0, 0.0});
  std::size_t col = 0;
  for (std::size_t k = 0; k < m; ++k) {
    for (const Vec3& d : D[k]) F[k] = F[k] + b[col++] * d;
  }
  if (edge_stick) {
    // Share the indeterminate force along the edge, T, in proportion to the contacts' spare capacities c_k =
    // sqrt((mu_s N_k)^2 - P_k^2) (P_k: the determinate force across the edge): the pair can stick iff some share
    // puts both forces in their cones, i.e. |P_k| <= mu_s N_k and |T| <= c_0 + c_1, and this share does so whenever
    // any does (|T_k| = |T| c_k / (c_0 + c_1) <= c_k). Coulomb's condition on the set of admissible forces (Pfeiffer &
    // Glocker 1996, ch. 8); a share in proportion to N would call a stick limit where the other end still has margin
    // (issue 29: stick-slip chattering at mu_s = mu_k). Past the cones, in proportion to N (the stick test fails).
    const double T = dot(F[0], edge) + dot(F[1], edge);
    const double Ns = F[0][2] + F[1][2];
    double cap[2];
    for (std::size_t k = 0; k < 2; ++k) {
      const double P = dot(F[k], cross(kUp, edge));
      const double lim = mu_s * std::max(F[k][2], 0.0);
      cap[k] = std::abs(P) <= lim ? std::sqrt(lim * lim - P * P) : -1.0;
    }
    double t0 = std::numeric_limits<double>::quiet_NaN();
    if (cap[0] >= 0.0 && cap[1] >= 0.0 && cap[0] + cap[1] > 0.0) {
      t0 = T * cap[0] / (cap[0] + cap[1]);
    } else if (Ns > 0.0) {
      t0 = T * F[0][2] / Ns;
    }
    if (std::isfinite(t0)) {
      F[0] = F[0] + (t0 - dot(F[0], edge)) * edge;
      F[1] = F[1] + ((T - t0) - dot(F[1], edge)) * edge;
    }
  }
  return F;
}

double hnorm(const Vec3& a) { return std::hypot(a[0], a[1]); }

enum class Kind : std::uint8_t { rest, flat_slip, contact, flight };

class ContactEngine;
struct Rhs {
  ContactEngine* e;
  void operator()(const SX& x, double t, SX& dx) const;
};

/// The instantaneous dynamics of a state with a contact set.
struct Dyn {
  bool ok = false;
  Vec3 a{}, alpha{};
  std::vector<Vec3> F;      // contact forces
  std::vector<Vec3> r;      // contact points from c (ground frame)
  std::vector<Vec3> u;      // contact velocities
  M3 R{}, Jinv{};
  Vec3 w{}, v{};
};

class ContactEngine {
 public:
  ContactEngine(const InputGrid& grid, std::vector<double> gravity, const RigidBody3D& body, const Rigid3DOptions& opt,
                const ContactStart& start)
      : grid_(grid), ax_(grid.accel_m_s2(0)), ay_(grid.accel_m_s2(1)), gravity_(std::move(gravity)), body_(body),
        opt_(opt), dp_(Rhs{this}, opt.abs_tol, opt.rel_tol, 0.1 * grid.dt_s()), start_(start) {
    g_ = opt.g_m_s2;
    mu_s_ = *opt.mu_s;
    mu_k_ = opt.mu_k.value_or(mu_s_);
    for (const auto& p : body.base_xy_m) v_.push_back({p[0], p[1], 0.0});
    c_ = body.centre_of_mass_m;
    h_ = c_[2];
    J_ = body.inertia_cm_m2;
    alpha_ref_ = std::numeric_limits<double>::infinity();
    const std::size_t n = v_.size();
    for (std::size_t i = 0; i < n; ++i) {
      size_ = std::max(size_, norm(c_ - v_[i]));
      const Vec3 d = v_[(i + 1) % n] - v_[i];
      const Vec3 nb = cross((1.0 / norm(d)) * d, kUp);
      const double b = -dot(c_ - v_[i], nb);
      edges_.push_back({nb[0], nb[1], b});
      alpha_ref_ = std::min(alpha_ref_, std::atan2(b, h_));
      lift_min_ = std::min(lift_min_, g_ * (std::hypot(b, h_) - h_));  // c over this edge from flat
    }
    p_ref_ = std::sqrt(g_ / size_);
    launch_speed_ =
        std::max(std::sqrt(opt.sliding.abs_tol * kLaunchSpeedScale), kLaunchSpeedTolerances * opt.sliding.abs_tol);
    floor_speed_ = kFloorLaunchFraction * launch_speed_;
    tie_z_ = std::max(opt.simultaneous_contact, 1e-12) * size_;
    const double a = alpha_ref_;
    const double L = size_ * a, V = p_ref_ * size_ * a;
    dp_.set_scale({L, L, L, V, V, V, a, a, a, a, p_ref_ * a, p_ref_ * a, p_ref_ * a, L, g_ * L});
  }

  Rigid3DResult run() {
    const std::size_t n = grid_.size();
    t_ = start_.time_s;
    mode_since_ = t_;
    std::size_t i = 0;
    while (i + 2 < n && grid_.time_s(i + 1) <= t_) ++i;
    x_ = {};
    const M3 R0 = rotation(start_.orientation);
    const Vec3 cw = start_.position_m + mul(R0, c_);
    for (std::size_t k = 0; k < 3; ++k) {
      x_[k] = cw[k];
      x_[3 + k] = start_.velocity_m_s[k];
      x_[10 + k] = start_.angular_velocity_rad_s[k];
    }
    for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = start_.orientation[k];
    if (i + 1 < n) set_forcing(i);
    was_slipping_ = hnorm(start_.velocity_m_s) > 0.0;  // a slip going on at the start is not a new episode
    // The start: flat on the ground (rigid3d_slide.cpp hands over a flat state); the first mode by enumeration.
    choose(all_down(), {}, -1);
    for (; !done_ && i + 1 < n; ++i) {
      const double tb = grid_.time_s(i + 1);
      if (!(tb > grid_.time_s(i))) continue;
      set_forcing(i);
      interval(tb);
      if (!done_) row();
    }
    if (!done_) run_out();
    auto& s = out_.summary;
    if (!s.modes.empty()) close_mode(s.modes.back().mode);
    s.end_time_s = t_;
    s.end_mode = mode_name();
    if (!done_ && kind_ != Kind::rest) {
      s.warnings.push_back(fmt::format("the body was still moving {} s after the record ended (max_run_out_s)",
                                       opt_.max_run_out_s));
    }
    if (painleve_ > 0) {
      s.warnings.push_back(fmt::format("Painleve's paradox (no or several consistent contact modes) met {} times: "
                                       "resolved by a tangential impact or a held contact (docs/method.md)",
                                       painleve_));
    }
    const Vec3 origin = position();
    s.residual_slide_east_m = origin[0];
    s.residual_slide_north_m = origin[1];
    const M3 R = rot();
    s.residual_yaw_deg = rad_to_deg(std::atan2(R[1][0] - R[0][1], R[0][0] + R[1][1]));
    s.slide_path_length_m = x_[13];
    s.friction_energy_j_per_kg = x_[14];
    s.steps = steps_;
    return std::move(out_);
  }

  // ---- the dynamics ----
  [[nodiscard]] Dyn dynamics(const SX& x, double t, const std::vector<Contact>& set) const {
    Dyn d;
    const Quaternion q{x[6], x[7], x[8], x[9]};
    d.R = rotation(q);
    d.v = {x[3], x[4], x[5]};
    d.w = {x[10], x[11], x[12]};
    M3 Jw{};
    for (std::size_t a = 0; a < 3; ++a) {
      for (std::size_t b = 0; b < 3; ++b) {
        double sum = 0.0;
        for (std::size_t k = 0; k < 3; ++k) {
          for (std::size_t l = 0; l < 3; ++l) sum += d.R[a][k] * J_[k][l] * d.R[b][l];
        }
        Jw[a][b] = sum;
      }
    }
    d.Jinv = inverse(Jw);
    const Vec3 f = forcing_.f(t);
    const Vec3 alpha0 = -1.0 * mul(d.Jinv, cross(d.w, mul(Jw, d.w)));
    std::vector<Contact> live = set;
    std::vector<Vec3> free;
    for (Contact& c : live) {
      const Vec3 r = mul(d.R, v_[static_cast<std::size_t>(c.v)] - c_);
      const Vec3 u = d.v + cross(d.w, r);
      d.r.push_back(r);
      d.u.push_back(u);
      if (c.slip) {
        const double sp = hnorm(u);
        if (sp > (c.fresh ? kSlipStart : kSlipZero) * p_ref_ * size_) c.s = {u[0] / sp, u[1] / sp, 0.0};  // else s
      }
      free.push_back(f + cross(alpha0, r) + cross(d.w, cross(d.w, r)));
    }
    d.a = f;
    d.alpha = alpha0;
    if (!live.empty()) {
      const auto F = contact_forces(live, d.r, d.Jinv, free, mu_k_, mu_s_);
      if (!F) return d;
      d.F = *F;
      Vec3 torque{};
      for (std::size_t k = 0; k < live.size(); ++k) {
        d.a = d.a + d.F[k];
        torque = torque + cross(d.r[k], d.F[k]);
      }
      d.alpha = d.alpha + mul(d.Jinv, torque);
    }
    d.ok = true;
    return d;
  }

  void rhs(const SX& x, double t, SX& dx) const {
    dx = {};
    const Vec3 f = forcing_.f(t);
    if (kind_ == Kind::flat_slip) {  // translation with Coulomb friction, N = g + a_z
      const double N = -f[2];
      dx[0] = x[3];
      dx[1] = x[4];
      const double fm = std::hypot(f[0], f[1]);
      if (launch_ && fm > 0.0) {
        // The launch (docs/method.md, "Bidirectional sliding", S5'): the velocity slaved to the load's direction n =
        // f_h / |f_h|, v = r n with r' = |f_h| - mu_k N and n' = (f_h' - n (f_h' . n)) / |f_h| (f_h' = -(axs, ays):
        // the load is linear on a sample interval), v' = r' n + r n'; smooth through r = 0, so that the stop event
        // (v . n at the step's start) has a simple root.
        const Vec3 n{f[0] / fm, f[1] / fm, 0.0};
        const double r = x[3] * n[0] + x[4] * n[1];
        const double fd0 = -forcing_.axs, fd1 = -forcing_.ays;
        const double along = fd0 * n[0] + fd1 * n[1];
        const double rd = fm - mu_k_ * N;
        dx[3] = rd * n[0] + r * (fd0 - n[0] * along) / fm;
        dx[4] = rd * n[1] + r * (fd1 - n[1] * along) / fm;
        dx[13] = std::abs(r);
        dx[14] = mu_k_ * N * std::abs(r);
        return;
      }
      const double sp = std::hypot(x[3], x[4]);
      const Vec3 s = sp > 0.0 ? Vec3{x[3] / sp, x[4] / sp, 0.0} : slip_dir_;
      dx[3] = f[0] - mu_k_ * N * s[0];
      dx[4] = f[1] - mu_k_ * N * s[1];
      dx[13] = sp;
      dx[14] = mu_k_ * N * sp;
      return;
    }
    const Dyn d = dynamics(x, t, set_);
    for (std::size_t k = 0; k < 3; ++k) {
      dx[k] = x[3 + k];
      dx[3 + k] = d.a[k];
      dx[10 + k] = d.alpha[k];
    }
    const Quaternion q{x[6], x[7], x[8], x[9]};
    const Quaternion qd = qmul(Quaternion{0.0, d.w[0], d.w[1], d.w[2]}, q);  // q' = (0, w) q / 2, w in G
    for (std::size_t k = 0; k < 4; ++k) dx[6 + k] = 0.5 * qd[k];
    double path = 0.0, work = 0.0;
    int slipping = 0;
    for (std::size_t k = 0; k < set_.size() && d.ok; ++k) {
      if (!set_[k].slip) continue;
      const double sp = hnorm(d.u[k]);
      path += sp;
      work += mu_k_ * std::max(d.F[k][2], 0.0) * sp;
      ++slipping;
    }
    dx[13] = slipping > 0 ? path / slipping : 0.0;
    dx[14] = work;
  }

  // ---- geometry of a state ----
  [[nodiscard]] M3 rot() const { return rotation({x_[6], x_[7], x_[8], x_[9]}); }
  [[nodiscard]] static M3 rot(const SX& x) { return rotation({x[6], x[7], x[8], x[9]}); }
  [[nodiscard]] Vec3 position() const {  // the body frame's origin
    return Vec3{x_[0], x_[1], x_[2]} - mul(rot(), c_);
  }
  [[nodiscard]] double vertex_z(const SX& x, std::size_t j) const {
    return x[2] + dot(rot(x)[2], v_[j] - c_);
  }
  [[nodiscard]] Vec3 vertex_velocity(const SX& x, std::size_t j) const {
    const Vec3 r = mul(rot(x), v_[j] - c_);
    return Vec3{x[3], x[4], x[5]} + cross(Vec3{x[10], x[11], x[12]}, r);
  }
  [[nodiscard]] double kinetic(const SX& x) const {
    const M3 R = rot(x);
    const Vec3 w{x[10], x[11], x[12]};
    const Vec3 wb = mul_t(R, w);
    return 0.5 * (x[3] * x[3] + x[4] * x[4] + x[5] * x[5]) + 0.5 * dot(wb, mul(J_, wb));
  }
  [[nodiscard]] double energy(const SX& x) const {
    if (frame_.level) return kinetic(x) + g_ * (x[2] - h_);
    return kinetic(x) + frame_.potential({x[0], x[1], x[2]}, c_);  // an inclined base: still ground's load, base frame
  }

  // ---- modes ----
  [[nodiscard]] Rigid3DMode mode_name() const {
    if (fallen_) return Rigid3DMode::fallen;
    switch (kind_) {
      case Kind::rest: return Rigid3DMode::rest;
      case Kind::flat_slip: return Rigid3DMode::sliding;
      case Kind::flight: return Rigid3DMode::flight;
      case Kind::contact: break;
    }
    for (const Contact& c : set_) {
      if (c.slip) return Rigid3DMode::slide_rock;
    }
    return set_.size() == 2 ? Rigid3DMode::rocking : Rigid3DMode::pivot;
  }

  void enter(Kind kind, std::vector<Contact> set) {
    kind_ = kind;
    set_ = std::move(set);
    since_ = t_;
    if (kind_ == Kind::rest || kind_ == Kind::flat_slip) flatten();
    restart_ = true;
    const Rigid3DMode m = mode_name();
    int a = -1, b = -1;
    if (kind_ == Kind::contact) {
      a = set_[0].v;
      if (set_.size() == 2) b = set_[1].v;
    }
    auto& s = out_.summary;
    if (s.modes.empty() || s.modes.back().mode != m || s.modes.back().vertex_a != a || s.modes.back().vertex_b != b) {
      if (!s.modes.empty()) close_mode(s.modes.back().mode);
      s.modes.push_back({t_, m, a, b});
      if (m == Rigid3DMode::slide_rock && !s.slide_rock_time_s) s.slide_rock_time_s = t_;
      if (m == Rigid3DMode::flight) {
        ++s.flights;
        if (!s.flight_time_s) s.flight_time_s = t_;
      }
      const bool slipping = m == Rigid3DMode::sliding || m == Rigid3DMode::slide_rock;
      if (slipping && !was_slipping_) {
        ++s.slip_episodes;
        if (!s.first_slip_time_s) s.first_slip_time_s = t_;
      }
      was_slipping_ = slipping;
      if ((m == Rigid3DMode::rocking || m == Rigid3DMode::pivot || m == Rigid3DMode::slide_rock ||
           m == Rigid3DMode::flight) && flat_before_) {
        ++s.uplifts;
        if (!s.uplift_time_s) s.uplift_time_s = t_;
      }
      flat_before_ = kind_ == Kind::rest || kind_ == Kind::flat_slip;
    }
    row();
  }

  /// The flat pose: the tilt removed (yaw kept), c at height h, no vertical or tilting motion.
  void flatten() {
    const M3 R = rot();
    const double yaw = std::atan2(R[1][0] - R[0][1], R[0][0] + R[1][1]);
    const Quaternion q = axis_angle(kUp, yaw);
    const Vec3 origin = position();
    const Vec3 cw = Vec3{origin[0], origin[1], 0.0} + mul(rotation(q), c_);
    for (std::size_t k = 0; k < 3; ++k) x_[k] = cw[k];
    for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = q[k];
    x_[5] = 0.0;
    x_[10] = x_[11] = x_[12] = 0.0;
    if (kind_ == Kind::rest) x_[3] = x_[4] = 0.0;
  }

  [[nodiscard]] std::vector<int> all_down() const {
    std::vector<int> d;
    for (std::size_t j = 0; j < v_.size(); ++j) {
      if (vertex_z(x_, j) <= tie_z_) d.push_back(static_cast<int>(j));
    }
    return d;
  }

  /// The centre of pressure's excess over the base's edges for the tangential force per unit N (dx, dy): p = c_plan
  /// - h F_t / N (moment balance about c); > 0: outside across that edge.
  [[nodiscard]] double pressure_excess(double fx, double fy, int* worst = nullptr) const {
    const M3 R = rot();
    double best = -std::numeric_limits<double>::infinity();
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      const Vec3 n = mul(R, Vec3{edges_[e][0], edges_[e][1], 0.0});
      const double x = -h_ * (fx * n[0] + fy * n[1]) - edges_[e][2];
      if (x > best) {
        best = x;
        if (worst) *worst = static_cast<int>(e);
      }
    }
    return best / size_;
  }

  /// Is the set's dynamics consistent (the header's conditions)? zero: contacts starting to slip (direction to check).
  bool consistent(const Dyn& d, const std::vector<Contact>& set, const std::vector<bool>& starting,
                  const std::vector<int>& down) const {
    if (!d.ok) return false;
    const double tolF = 1e-9 * g_;
    for (std::size_t k = 0; k < set.size(); ++k) {
      const Vec3& F = d.F[k];
      if (!(F[2] > tolF)) return false;  // a contact with N = 0 lifts (flight at g + a_z = 0: no contact set)
      if (!set[k].slip && hnorm(F) > mu_s_ * F[2] * (1.0 + 1e-9) + tolF) return false;
      if (set[k].slip && starting[k]) {
        const Vec3 ak = d.a + cross(d.alpha, d.r[k]) + cross(d.w, cross(d.w, d.r[k]));
        if (ak[0] * set[k].s[0] + ak[1] * set[k].s[1] < -tolF) return false;
      }
    }
    for (int j : down) {
      bool in = false;
      for (const Contact& c : set) in = in || c.v == j;
      if (in) continue;
      const Vec3 r = mul(d.R, v_[static_cast<std::size_t>(j)] - c_);
      const Vec3 aj = d.a + cross(d.alpha, r) + cross(d.w, cross(d.w, r));
      if (aj[2] < -tolF) return false;
    }
    return true;
  }

  /// Coulomb's law at the acceleration level for the contacts starting to slip from rest (issue 29; Pfeiffer &
  /// Glocker 1996, ch. 8; Glocker 2001): the friction force F_t = -mu_k N s must oppose the slip acceleration, a_t =
  /// lambda s with lambda >= 0, where a_t depends on s through the contact's Delassus matrix W and N (the normal
  /// constraint). Per contact, with s = (cos th, sin th) and the other contacts' directions held, the roots of
  /// c(th) = s x a_t(th) (z component) with s . a_t >= 0 are bracketed on 72 angles around the circle and refined by
  /// TOMS 748; the root nearest the current direction (first: against the sticking force) is taken; the contacts are
  /// swept in turn (Gauss-Seidel) until the directions change by less than 1e-10 rad. A direction already
  /// consistent to 1e-12 g is kept as it is (the plane of symmetry: the planar model's sigma, exactly).
  /// False: a contact has no such root (or the sweeps do not settle): the caller falls back.
  bool slip_directions(std::vector<Contact>& set, const std::vector<bool>& starting, const Dyn& stick) const {
    const std::size_t m = set.size();
    const double tol = 1e-12 * g_;
    // The look-ahead state: at a stick limit the sticking force is on the cone's boundary and s = -F_stick/|F_stick|
    // is a root with a_t = 0 whatever the slip that follows; the direction wanted is the limit t -> t0+ of the
    // consistent one, taken at t0 + dt_la with the velocities advanced by the sticking solution's accelerations (the
    // sticking contacts' velocities stay 0 to O(dt_la^2)); dt_la = 1e-4 of the record's step.
    bool boundary = false;
    for (std::size_t k = 0; k < m; ++k) {
      if (!starting[k] || !(stick.F.size() > k)) continue;
      const double lim = mu_s_ * stick.F[k][2];
      boundary = boundary || std::abs(hnorm(stick.F[k]) - lim) <= kConeTol * lim;
    }
    const double dt_la = boundary ? 1e-4 * grid_.dt_s() : 0.0;
    SX xl = x_;
    for (std::size_t k = 0; k < 3; ++k) {
      xl[3 + k] += dt_la * stick.a[k];
      xl[10 + k] += dt_la * stick.alpha[k];
    }
    const double tl = t_ + dt_la;
    // c and s . a_t of contact k with direction th; false where the set's forces are singular or N_k <= 0
    const auto eval = [&](std::size_t k, double th, double& c, double& h) {
      std::vector<Contact> st = set;
      st[k].s = {std::cos(th), std::sin(th), 0.0};
      const Dyn d = dynamics(xl, tl, st);
      if (!d.ok || !(d.F[k][2] > 0.0)) return false;
      const Vec3 a = d.a + cross(d.alpha, d.r[k]) + cross(d.w, cross(d.w, d.r[k]));
      c = st[k].s[0] * a[1] - st[k].s[1] * a[0];
      h = st[k].s[0] * a[0] + st[k].s[1] * a[1];
      return true;
    };
    constexpr int kScan = 72;
    for (int sweep = 0; sweep < 30; ++sweep) {
      double change = 0.0;
      for (std::size_t k = 0; k < m; ++k) {
        if (!starting[k]) continue;
        const double th0 = std::atan2(set[k].s[1], set[k].s[0]);
        double c0 = 0.0, h0 = 0.0;
        // already along the acceleration's line (the plane of symmetry: exactly): kept; the caller's check at t0
        // decides (a slip that decelerates from rest is then held sticking)
        const bool ok0 = eval(k, th0, c0, h0);
        if (ok0 && std::abs(c0) <= kParallel * std::hypot(c0, h0) + tol) continue;
        // a root is stable when c falls through it (c > 0 turns s counter-clockwise towards a_t): a small deviation
        // of the slip's direction returns (the direction's rate is c / |u|); a stable root is taken first
        double best = std::numeric_limits<double>::quiet_NaN(), best_gap = std::numeric_limits<double>::infinity();
        bool best_stable = false;
        const auto consider = [&](double th, bool stable) {
          double c = 0.0, h = 0.0;
          if (!eval(k, th, c, h) || h < -1e-9 * g_) return;
          const double gap = std::abs(std::remainder(th - th0, 2.0 * M_PI));
          if ((stable && !best_stable) || (stable == best_stable && gap < best_gap)) {
            best_gap = gap;
            best = th;
            best_stable = stable;
          }
        };
        double ta = th0, ca = 0.0, ha = 0.0;
        bool oka = eval(k, ta, ca, ha);
        for (int j = 1; j <= kScan; ++j) {
          const double tb = th0 + 2.0 * M_PI * j / kScan;
          double cb = 0.0, hb = 0.0;
          const bool okb = eval(k, tb, cb, hb);
          if (oka && okb) {
            if (ca == 0.0) {
              consider(ta, cb < 0.0);
            } else if ((ca < 0.0) != (cb < 0.0) && cb != 0.0) {
              const auto fn = [&](double th) {
                double c = 0.0, h = 0.0;
                return eval(k, th, c, h) ? c : std::numeric_limits<double>::quiet_NaN();
              };
              const double r = find_root(fn, ta, tb, ca, cb);
              if (std::isfinite(r)) consider(r, ca > 0.0);
            }
          }
          ta = tb;
          ca = cb;
          oka = okb;
        }
        if (std::isnan(best)) return false;
        change = std::max(change, best_gap);
        set[k].s = {std::cos(best), std::sin(best), 0.0};
      }
      if (change < 1e-10) return true;
    }
    return false;
  }

  /// A slip started from rest whose speed is still below the slip-zero threshold (its direction not yet set by its
  /// velocity): the consistent direction of slip_directions at each step's start, as the load turns (the direction
  /// at the start is the limit t -> t0+; the slip's own velocity takes over above the threshold).
  void follow_slip_start() {
    const std::size_t m = set_.size();
    std::vector<bool> starting(m, false);
    bool any = false;
    for (std::size_t k = 0; k < m; ++k) {
      if (!set_[k].slip || !set_[k].fresh) continue;
      const double sp = hnorm(vertex_velocity(x_, static_cast<std::size_t>(set_[k].v)));
      starting[k] = !(sp > kSlipStart * p_ref_ * size_);
      any = any || starting[k];
    }
    if (!any) return;
    std::vector<Contact> stick = set_;
    for (std::size_t k = 0; k < m; ++k) {
      if (starting[k]) stick[k].slip = false;
    }
    const Dyn ds = dynamics(x_, t_, stick);
    if (!ds.ok) return;
    std::vector<Contact> next = set_;
    if (!slip_directions(next, starting, ds)) return;
    double change = 0.0;
    for (std::size_t k = 0; k < m; ++k) change = std::max(change, hnorm(next[k].s - set_[k].s));
    if (change > kParallel) {
      set_ = std::move(next);
      restart_ = true;
    }
  }

  /// Try a contact set with all stick/slip choices for its contacts at rest tangentially. True: entered.
  bool try_set(std::vector<int> verts, const std::vector<int>& down, int no_stick) {
    const std::size_t m = verts.size();
    std::vector<bool> moving(m);
    std::vector<Contact> set(m);
    for (std::size_t k = 0; k < m; ++k) {
      set[k].v = verts[k];
      const Vec3 u = vertex_velocity(x_, static_cast<std::size_t>(verts[k]));
      const double sp = hnorm(u);
      moving[k] = sp > kSlipZero * p_ref_ * size_;
      if (moving[k]) set[k].s = {u[0] / sp, u[1] / sp, 0.0};
    }
    // choices: bit k set = contact k slips; both-slip before mixed for a pair (the symmetric solution first)
    std::vector<unsigned> choices;
    const unsigned all = (1U << m) - 1U;
    choices.push_back(0);
    if (m == 2) choices.push_back(3);
    for (unsigned c = 1; c <= all; ++c) {
      if (!(m == 2 && c == 3)) choices.push_back(c);
    }
    for (unsigned c : choices) {
      bool valid = true;
      std::vector<bool> starting(m, false);
      for (std::size_t k = 0; k < m; ++k) {
        const bool slip = ((c >> k) & 1U) != 0U || moving[k];
        if (!slip && (verts[k] == no_stick)) valid = false;
        set[k].slip = slip;
        starting[k] = slip && !moving[k];
        set[k].fresh = starting[k];
      }
      if (!valid) continue;
      if (std::any_of(starting.begin(), starting.end(), [](bool b) { return b; })) {
        // the slip start's direction: the first guess is against the sticking solution's force (the planar model's
        // sigma; exact in a plane of symmetry), then Coulomb's law at the acceleration level (slip_directions)
        std::vector<Contact> stick = set;
        for (std::size_t k = 0; k < m; ++k) {
          if (starting[k]) stick[k].slip = false;
        }
        const Dyn ds = dynamics(x_, t_, stick);
        if (!ds.ok) continue;
        for (std::size_t k = 0; k < m; ++k) {
          if (!starting[k]) continue;
          const double fn = hnorm(ds.F[k]);
          set[k].s = fn > 0.0 ? Vec3{-ds.F[k][0] / fn, -ds.F[k][1] / fn, 0.0} : Vec3{1.0, 0.0, 0.0};
        }
        if (!slip_directions(set, starting, ds)) {
          // no consistent direction (the angle problem has no root with the slip accelerating): the former rule, the
          // tangential acceleration's direction by fixed-point iteration from the sticking force's opposite
          for (std::size_t k = 0; k < m; ++k) {
            if (!starting[k]) continue;
            const double fn = hnorm(ds.F[k]);
            set[k].s = fn > 0.0 ? Vec3{-ds.F[k][0] / fn, -ds.F[k][1] / fn, 0.0} : Vec3{1.0, 0.0, 0.0};
          }
          if (consistent(dynamics(x_, t_, set), set, starting, down)) {
            slip_dir_ = {};
            enter(Kind::contact, set);
            return true;
          }
          for (int it = 0; it < 20; ++it) {
            const Dyn di = dynamics(x_, t_, set);
            if (!di.ok) break;
            double change = 0.0;
            for (std::size_t k = 0; k < m; ++k) {
              if (!starting[k]) continue;
              const Vec3 ak = di.a + cross(di.alpha, di.r[k]) + cross(di.w, cross(di.w, di.r[k]));
              const double an = hnorm(ak);
              if (!(an > 1e-6 * g_)) continue;
              const Vec3 sd{ak[0] / an, ak[1] / an, 0.0};
              change = std::max(change, hnorm(sd - set[k].s));
              set[k].s = sd;
            }
            if (change < 1e-12) break;
          }
        }
      }
      const Dyn d = dynamics(x_, t_, set);
      if (consistent(d, set, starting, down)) {
        slip_dir_ = {};
        enter(Kind::contact, set);
        return true;
      }
    }
    return false;
  }

  /// The mode at an instant, by enumeration over the vertices down (header). no_stick: a vertex that may not stick
  /// (a stick limit just reached); exclude: a vertex that just lifted.
  /// skip_rest, skip_slide: at a located exit from rest (flat sliding) the flat mode is left (on the boundary to
  /// round-off it would be taken again).
  void choose(std::vector<int> down, std::vector<int> exclude, int no_stick, bool skip_rest = false,
              bool skip_slide = false) {
    std::erase_if(down, [&](int j) { return std::find(exclude.begin(), exclude.end(), j) != exclude.end(); });
    const Vec3 f = forcing_.f(t_);
    const double G = -f[2];
    if (down.size() >= 3) {  // the flat base: rest, then flat sliding (no rotation)
      const double sp = std::hypot(x_[3], x_[4]);
      if (G > 0.0) {
        if (sp <= kSlipZero * p_ref_ * size_) {
          x_[3] = x_[4] = 0.0;
          if (!skip_rest && hnorm(f) <= mu_s_ * G && pressure_excess(-f[0] / G, -f[1] / G) <= 0.0 && no_stick < 0) {
            enter(Kind::rest, {});
            return;
          }
          const double fh = hnorm(f);
          if (!skip_slide && (fh > mu_s_ * G || no_stick >= 0 || skip_rest)) {
            slip_dir_ = fh > 0.0 ? Vec3{f[0] / fh, f[1] / fh, 0.0} : Vec3{1.0, 0.0, 0.0};
            if (pressure_excess(-mu_k_ * slip_dir_[0], -mu_k_ * slip_dir_[1]) <= 0.0) {
              launch_ = fh > 0.0;  // from rest: the launch (S5'), the velocity slaved to the load's direction
              enter(Kind::flat_slip, {});
              return;
            }
          }
        } else {
          slip_dir_ = {x_[3] / sp, x_[4] / sp, 0.0};
          if (!skip_slide && pressure_excess(-mu_k_ * slip_dir_[0], -mu_k_ * slip_dir_[1]) <= 0.0) {
            launch_ = false;  // moving: its own direction (a slow one may land on the load's, update_launch)
            enter(Kind::flat_slip, {});
            return;
          }
        }
      }
      // lifting: the edges of the base, then its vertices
      const std::size_t n = v_.size();
      for (std::size_t e = 0; e < n; ++e) {
        const int a = static_cast<int>(e), b = static_cast<int>((e + 1) % n);
        if (std::find(down.begin(), down.end(), a) == down.end()) continue;
        if (std::find(down.begin(), down.end(), b) == down.end()) continue;
        if (try_set({a, b}, down, no_stick)) return;
      }
      for (int j : down) {
        if (try_set({j}, down, no_stick)) return;
      }
    } else if (!down.empty()) {
      if (down.size() == 2 && try_set(down, down, no_stick)) return;
      for (int j : down) {
        if (try_set({j}, down, no_stick)) return;
      }
    }
    // flight: consistent when no contact is pulled into the ground
    {
      const Dyn d = dynamics(x_, t_, {});
      if (consistent(d, {}, {}, down) || down.empty()) {
        enter(Kind::flight, {});
        return;
      }
    }
    // Painleve's paradox or a boundary case: a slipping contact stopped by a tangential impact, else held sticking.
    ++painleve_;
    ++out_.summary.painleve_events;
    if (down.size() >= 3) {
      x_[3] = x_[4] = 0.0;
      enter(Kind::rest, {});
      return;
    }
    std::vector<Contact> set;
    for (int j : down) set.push_back({j, false, {}});
    stick_impulse(set);
    enter(Kind::contact, set);
  }

  /// The velocity impulse that makes the contacts of the set stick (their velocity 0), no friction limit.
  void stick_impulse(const std::vector<Contact>& set) {
    const Dyn d = dynamics(x_, t_, {});
    std::vector<Vec3> r, u;
    for (const Contact& c : set) {
      r.push_back(mul(d.R, v_[static_cast<std::size_t>(c.v)] - c_));
      u.push_back(vertex_velocity(x_, static_cast<std::size_t>(c.v)));
    }
    const auto P = contact_forces(set, r, d.Jinv, u, mu_k_, mu_s_);
    if (!P) return;
    apply_impulse(d, set, r, *P);
  }

  void apply_impulse(const Dyn& d, const std::vector<Contact>& set, const std::vector<Vec3>& r,
                     const std::vector<Vec3>& P) {
    Vec3 dv{}, dL{};
    for (std::size_t k = 0; k < set.size(); ++k) {
      dv = dv + P[k];
      dL = dL + cross(r[k], P[k]);
    }
    const Vec3 dw = mul(d.Jinv, dL);
    for (std::size_t k = 0; k < 3; ++k) {
      x_[3 + k] += dv[k];
      x_[10 + k] += dw[k];
    }
  }

  // ---- impacts ----
  /// The striking vertex back on the ground (issue 29): a vertex located by its dip strikes up to kDip size below
  /// the ground, and one that started its phase below it (the constraint's drift at the acceleration level, ~1e-10 of
  /// the size per phase) lower still; left so, a pivot swapping between the ends of an edge sinks the edge by that
  /// at each swap. The body is turned about the current contacts (the line of an edge; for a pivot, the horizontal
  /// axis through it across the striking vertex) by the small angle that brings the striking vertex to z = 0, the
  /// contacts staying where they are; in flight it is lifted. The velocities are kept (a position projection,
  /// the post-stabilisation of Cline & Pai 2003).
  void level_strike(int striking) {
    const auto js = static_cast<std::size_t>(striking);
    const double zs = vertex_z(x_, js);
    if (!(zs < 0.0)) return;
    const M3 R = rot();
    const Vec3 c{x_[0], x_[1], x_[2]};
    const auto at = [&](int j) { return c + mul(R, v_[static_cast<std::size_t>(j)] - c_); };
    Vec3 axis{};
    Vec3 pivot{};
    if (set_.size() == 2) {
      pivot = at(set_[0].v);
      axis = at(set_[1].v) - pivot;
    } else if (set_.size() == 1) {
      pivot = at(set_[0].v);
      axis = cross(kUp, at(striking) - pivot);
    }
    const double an = norm(axis);
    const double lever = an > 0.0 ? cross((1.0 / an) * axis, at(striking) - pivot)[2] : 0.0;
    if (set_.empty() || set_.size() > 2 || !(std::abs(lever) > 1e-3 * size_)) {
      x_[2] -= zs;
      return;
    }
    const double phi = -zs / lever;
    const Vec3 e = (1.0 / an) * axis;
    const Quaternion qr = axis_angle(e, phi);
    const Vec3 cn = pivot + mul(rotation(qr), c - pivot);
    const Quaternion q = normalized(qmul(qr, {x_[6], x_[7], x_[8], x_[9]}));
    for (std::size_t k = 0; k < 3; ++k) x_[k] = cn[k];
    for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = q[k];
  }

  void impact(int striking, bool land_flat = false) {
    level_strike(striking);
    const double ke_before = kinetic(x_);
    std::vector<int> down = all_down();
    if (std::find(down.begin(), down.end(), striking) == down.end()) down.push_back(striking);
    ++out_.summary.impacts;
    const Dyn d = dynamics(x_, t_, {});
    std::vector<int> fresh;
    for (int j : down) {
      bool old = false;
      for (const Contact& c : set_) old = old || c.v == j;
      if (!old) fresh.push_back(j);
    }
    // candidate outcome sets (header): the striking vertices alone, their edges, then with the old contacts; a base
    // landing flat (three or more vertices striking at once, e.g. from flight without rotation) lands flat
    std::vector<std::vector<int>> cands;
    const std::size_t n = v_.size();
    const auto adjacent = [&](int a, int b) {
      return static_cast<std::size_t>(b) == (static_cast<std::size_t>(a) + 1) % n ||
             static_cast<std::size_t>(a) == (static_cast<std::size_t>(b) + 1) % n;
    };
    const auto in = [](const std::vector<int>& s, int j) { return std::find(s.begin(), s.end(), j) != s.end(); };
    // Zeno: a strike on the neighbour of the single contact within kZenoGap_s of the last impact (pivot swaps between
    // the ends of an edge, ever shorter) is taken as the edge's limit first (cf. rigid3d.cpp's rule)
    const double v_strike = -vertex_velocity(x_, static_cast<std::size_t>(striking))[2];
    const bool swap = set_.size() == 1 && fresh.size() == 1 && adjacent(set_[0].v, fresh[0]);
    // each strike slower than the same end's last (the two ends' strike speeds need not interleave monotonically)
    const double same_end = swaps_ >= 2 ? swap_speed2_ : std::numeric_limits<double>::infinity();
    if (swap && fresh[0] == swap_pivot_ && set_[0].v == swap_striker_ && v_strike < same_end) {
      ++swaps_;
    } else {
      swaps_ = swap ? 1 : 0;
    }
    swap_pivot_ = swap ? set_[0].v : -1;
    swap_striker_ = swap ? fresh[0] : -1;
    swap_speed2_ = swap_speed_;
    swap_speed_ = v_strike;
    if (swap && (t_ - last_impact_t_ < kZenoGap_s || swaps_ >= kZenoSwaps)) {
      cands.push_back({set_[0].v, fresh[0]});
    }
    last_impact_t_ = t_;
    for (int j : fresh) cands.push_back({j});
    for (std::size_t a = 0; a < down.size(); ++a) {
      for (std::size_t b = a + 1; b < down.size(); ++b) {
        if (adjacent(down[a], down[b]) && in(fresh, down[a]) && in(fresh, down[b])) cands.push_back({down[a], down[b]});
      }
    }
    for (std::size_t a = 0; a < down.size(); ++a) {
      for (std::size_t b = a + 1; b < down.size(); ++b) {
        if (adjacent(down[a], down[b]) && !(in(fresh, down[a]) && in(fresh, down[b]))) {
          cands.push_back({down[a], down[b]});
        }
      }
    }
    for (int j : down) {
      if (!in(fresh, j)) cands.push_back({j});
    }
    // (issue 29) a strike slower than kFlatStrike p size with every base vertex within simultaneous_contact of the
    // ground lands flat too: a body sliding flat to that tolerance whose contact alternates between opposite edges
    // every 1e-8 s at strike speeds of 1e-8 m/s (an accumulation the rest rule on the whole kinetic energy does not
    // end while the body slides) is on its flat base
    if (down.size() == v_.size() && -vertex_velocity(x_, static_cast<std::size_t>(striking))[2] < kFlatStrike * p_ref_ * size_) {
      land_flat = true;
    }
    if (fresh.size() >= 3 || land_flat) cands.clear();
    const double tolV = 1e-9 * p_ref_ * size_;
    // Zeno (issue 29): kZenoSwaps pivot swaps in a row between the ends of one edge, each strike slower than the
    // last, whose edge impact with friction is inconsistent (a pulling impulse at the old pivot): the accumulation's
    // limit is the edge down (Glocker 2001, the limit contact set of a converging impact sequence). Both ends'
    // normal velocities are set to 0 by normal impulses alone (frictionless plastic: a projection in the kinetic
    // metric, so the kinetic energy does not grow); taken when both impulses are >= 0, or, as the rest rule of the
    // planar engines (rocking.hpp), when the energy it removes (the swapping rocking's) is below rest_energy_fraction
    // of the energy to lift c over an end (a slender body's projection pulls at the old pivot: the sequence's limit
    // includes the load's impulse over its finite duration, which the instantaneous projection leaves out). Slips
    // at both ends slower than kSlipStart p size then stop (the sticking impulse, hold_slow_slips' rule) unless that
    // would add energy. The edge mode is then chosen by enumeration (after_impact). docs/method.md.
    if (swap && swaps_ >= kZenoSwaps && !land_flat) {
      const std::vector<int> verts{set_[0].v, fresh[0]};
      std::vector<Vec3> r, u;
      std::vector<Contact> set(2);
      for (std::size_t k = 0; k < 2; ++k) {
        r.push_back(mul(d.R, v_[static_cast<std::size_t>(verts[k])] - c_));
        u.push_back(vertex_velocity(x_, static_cast<std::size_t>(verts[k])));
        set[k] = {verts[k], true, {1.0, 0.0, 0.0}};
      }
      const auto P = contact_forces(set, r, d.Jinv, u, 0.0, 0.0);
      if (P) {
        const SX saved = x_;
        apply_impulse(d, set, r, *P);
        const double removed = ke_before - kinetic(x_);
        // the energy to lift c over either end from here (rocking.hpp's rest rule's scale)
        double lift = std::numeric_limits<double>::infinity();
        for (std::size_t k = 0; k < 2; ++k) lift = std::min(lift, g_ * (norm(r[k]) + r[k][2]));
        if (((*P)[0][2] >= -tolV && (*P)[1][2] >= -tolV) || (removed >= 0.0 && removed < opt_.rest_energy_fraction * lift)) {
          swaps_ = 0;
          double slip = 0.0;
          for (int j : verts) slip = std::max(slip, hnorm(vertex_velocity(x_, static_cast<std::size_t>(j))));
          if (slip < kSlipStart * p_ref_ * size_) {
            const double kb = kinetic(x_);
            stick_impulse({{verts[0], false, {}}, {verts[1], false, {}}});
            if (kinetic(x_) > kb) {  // a sticking impulse adds no energy; else the projection alone
              x_ = saved;
              apply_impulse(d, set, r, *P);
            }
          }
          after_impact(ke_before, false, verts);
          return;
        }
        x_ = saved;
      }
    }
    for (const auto& verts : cands) {
      const std::size_t m = verts.size();
      std::vector<Vec3> r, u;
      for (int j : verts) {
        r.push_back(mul(d.R, v_[static_cast<std::size_t>(j)] - c_));
        u.push_back(vertex_velocity(x_, static_cast<std::size_t>(j)));
      }
      std::vector<unsigned> choices{0U};  // all stick, then all slip, then mixed (the symmetric outcome first)
      if (m == 2) choices.push_back(3U);
      for (unsigned c = 1; c < (1U << m); ++c) {
        if (!(m == 2 && c == 3U)) choices.push_back(c);
      }
      for (unsigned c : choices) {
        std::vector<Contact> set(m);
        for (std::size_t k = 0; k < m; ++k) set[k] = {verts[k], ((c >> k) & 1U) != 0U, {}};
        if (c != 0) {  // slip directions: the pre-impact slip, else against the sticking impulse
          std::vector<Contact> stick = set;
          for (auto& s : stick) s.slip = false;
          const auto P0 = contact_forces(stick, r, d.Jinv, u, mu_k_, mu_s_);
          for (std::size_t k = 0; k < m; ++k) {
            if (!set[k].slip) continue;
            const double sp = hnorm(u[k]);
            if (sp > tolV) {
              set[k].s = {u[k][0] / sp, u[k][1] / sp, 0.0};
            } else if (P0 && hnorm((*P0)[k]) > 0.0) {
              const double pn = hnorm((*P0)[k]);
              set[k].s = {-(*P0)[k][0] / pn, -(*P0)[k][1] / pn, 0.0};
            } else {
              set[k].s = {1.0, 0.0, 0.0};
            }
          }
        }
        const auto P = contact_forces(set, r, d.Jinv, u, mu_k_, mu_s_);
        if (!P) continue;
        bool ok = true;
        for (std::size_t k = 0; k < m && ok; ++k) {
          const Vec3& p = (*P)[k];
          if (p[2] < -tolV) ok = false;
          if (!set[k].slip && hnorm(p) > mu_s_ * p[2] * (1.0 + 1e-9) + tolV) ok = false;
        }
        if (!ok) continue;
        // the other down vertices must not move into the ground
        const SX saved = x_;
        apply_impulse(d, set, r, *P);
        for (int j : down) {
          if (in(verts, j)) continue;
          if (vertex_velocity(x_, static_cast<std::size_t>(j))[2] < -tolV) ok = false;
        }
        if (!ok) {
          x_ = saved;
          continue;
        }
        if (opt_.restitution == RestitutionMode::given && c == 0) {  // the user's e on a sticking outcome
          const double ke = kinetic(x_);
          if (ke > 0.0) {
            const double k = opt_.e * std::sqrt(ke_before / ke);
            for (std::size_t i = 3; i < 6; ++i) x_[i] *= k;
            for (std::size_t i = 10; i < 13; ++i) x_[i] *= k;
          }
        }
        after_impact(ke_before, down.size() >= 3, verts);
        return;
      }
    }
    // the flat outcome (approximation, header)
    const double vz = x_[5];
    const double sp = std::hypot(x_[3], x_[4]);
    const double pn = std::max(-vz, 0.0);
    if (sp <= mu_s_ * pn || sp <= mu_k_ * pn) {
      x_[3] = x_[4] = 0.0;
    } else {
      const double k = (sp - mu_k_ * pn) / sp;
      x_[3] *= k;
      x_[4] *= k;
    }
    x_[5] = 0.0;
    x_[10] = x_[11] = x_[12] = 0.0;
    double ke_after = 0.5 * (x_[3] * x_[3] + x_[4] * x_[4]);
    // The rest rule after a flat landing (rocking.hpp's, as after_impact's): kinetic energy below
    // rest_energy_fraction of the least energy to lift c over an edge of the base ends the motion. Without it a body
    // settling flat under a load at its uplift limit cycles through ever smaller flat landings, slips on an edge and
    // pivots on a vertex (issue 29: tilts of 1e-9 rad at 1e-15 J/kg, thousands of events in one sample interval).
    if (ke_after < opt_.rest_energy_fraction * lift_min_) {
      x_[3] = x_[4] = 0.0;
      ke_after = 0.0;
    }
    out_.summary.energy_lost_j_per_kg += std::max(ke_before - ke_after, 0.0);
    kind_ = Kind::rest;  // flatten below keeps the horizontal velocity when choose() slides
    flatten_keep();
    choose(all_down(), {}, -1);
  }

  void flatten_keep() {
    const double vx = x_[3], vy = x_[4];
    flatten();
    x_[3] = vx;
    x_[4] = vy;
  }

  void after_impact(double ke_before, bool flat_landing, const std::vector<int>& verts) {
    const double ke_after = kinetic(x_);
    out_.summary.energy_lost_j_per_kg += std::max(ke_before - ke_after, 0.0);
    if (flat_landing) {
      // the rest rule (rocking.hpp): kinetic energy below rest_energy_fraction of the energy to lift c over the
      // new contact
      double lift = std::numeric_limits<double>::infinity();
      const M3 R = rot();
      for (int j : verts) {
        const Vec3 r = mul(R, c_ - v_[static_cast<std::size_t>(j)]);
        lift = std::min(lift, g_ * (norm(r) - h_));
      }
      if (verts.size() == 2) {  // about the edge: the distance of c from the edge's line
        const Vec3 a = v_[static_cast<std::size_t>(verts[0])], b = v_[static_cast<std::size_t>(verts[1])];
        const Vec3 e = (1.0 / norm(b - a)) * (b - a);
        const Vec3 rc = c_ - a;
        lift = g_ * (norm(rc - dot(rc, e) * e) - h_);
      }
      if (ke_after < opt_.rest_energy_fraction * lift) {
        out_.summary.energy_lost_j_per_kg += ke_after;
        x_[3] = x_[4] = x_[5] = 0.0;
        x_[10] = x_[11] = x_[12] = 0.0;
        kind_ = Kind::rest;
        flatten();
        choose(all_down(), {}, -1);
        return;
      }
    }
    // the contacts of the outcome: the mode by enumeration over them
    choose(verts, {}, -1);
  }

  // ---- events ----
  /// The event functions of the current mode at a state (an event: a function passing from < 0 to >= 0).
  void events(const SX& x, double t, std::vector<double>& out) const {
    out.clear();
    const Vec3 f = forcing_.f(t);
    const double G = -f[2];
    if (kind_ == Kind::rest) {
      const double fh = hnorm(f);
      out.push_back((fh - mu_s_ * G) / g_);  // slip starts
      out.push_back(pressure_excess_at(x, -f[0] / std::max(G, 1e-300), -f[1] / std::max(G, 1e-300)));
      out.push_back(-G / g_);               // g + a_z <= 0: flight
      return;
    }
    if (kind_ == Kind::flat_slip) {
      out.push_back(-(x[3] * slip_ref_[0] + x[4] * slip_ref_[1]) / (p_ref_ * size_));  // stop
      const double sp = std::hypot(x[3], x[4]);
      const Vec3 s = sp > 0.0 ? Vec3{x[3] / sp, x[4] / sp, 0.0} : slip_dir_;
      out.push_back(pressure_excess_at(x, -mu_k_ * s[0], -mu_k_ * s[1]));
      out.push_back(-G / g_);
      return;
    }
    const M3 R = rot(x);
    if (kind_ == Kind::contact) {
      const Dyn d = dynamics(x, t, set_);
      for (std::size_t k = 0; k < set_.size(); ++k) {
        const double N = d.ok ? d.F[k][2] : 0.0;
        out.push_back(-N / g_);  // lift
        if (set_[k].slip) {
          out.push_back(-(d.u[k][0] * set_[k].s[0] + d.u[k][1] * set_[k].s[1]) / (p_ref_ * size_));  // stop
        } else {
          out.push_back(d.ok ? (hnorm(d.F[k]) - mu_s_ * N) / g_ : 0.0);  // slip starts
        }
      }
    }
    for (std::size_t j = 0; j < v_.size(); ++j) {
      bool in = false;
      for (const Contact& c : set_) in = in || c.v == static_cast<int>(j);
      out.push_back(in ? -1.0 : -(x[2] + dot(R[2], v_[j] - c_)) / size_);  // touch-down
    }
    out.push_back(-R[2][2]);  // fallen: the body's z axis horizontal
    // Dips (issue 29): a vertex not in the set that starts the phase at or below the ground (gap z0 <= 0) has a
    // touch-down function starting at >= 0, which is armed only once the vertex rises; moving down it would pass
    // through the ground unseen. Its dip function -(z - z0 + kDip size) / size starts below 0 and fires when the
    // vertex has gone kDip size below where it started: an impact there (the backstop of settle_down_vertices()).
    for (std::size_t j = 0; j < v_.size(); ++j) {
      const double z0 = j < dip_ref_.size() ? dip_ref_[j] : kNoDip;
      out.push_back(z0 == kNoDip ? -1.0 : -(x[2] + dot(R[2], v_[j] - c_) - z0 + kDip * size_) / size_);
    }
  }

  [[nodiscard]] double pressure_excess_at(const SX& x, double fx, double fy) const {
    const M3 R = rot(x);
    double best = -std::numeric_limits<double>::infinity();
    for (const auto& e : edges_) {
      const Vec3 n = mul(R, Vec3{e[0], e[1], 0.0});
      best = std::max(best, -h_ * (fx * n[0] + fy * n[1]) - e[2]);
    }
    return best / size_;
  }

  /// The tilt's rate sign: (w x z_b)_z, the rate of cos(tilt); a tilt maximum: from < 0 to >= 0.
  [[nodiscard]] static double tilt_rate(const SX& x) {
    const M3 R = rot(x);
    const Vec3 zb{R[0][2], R[1][2], R[2][2]};
    return cross(Vec3{x[10], x[11], x[12]}, zb)[2];
  }

  void interval(double tb) {
    int& count = interval_count_;
    count = 0;
    while (!done_ && t_ < tb) {
      if (++count > kMaxEvents) {
        throw EventLimitError(fmt::format("rock3d: more than {} events in one sample interval ending at {} s",
                                          kMaxEvents, tb));
      }
      if (count % kSlowSteps == 0 && kind_ == Kind::contact && hold_slow_slips()) continue;
      if (tb - t_ <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(tb), 1.0)) {
        t_ = tb;
        break;
      }
      phase(tb);
    }
  }

  /// The backstop of issue 29: kSlowSteps steps and events within one sample interval while a contact slips slower
  /// than kSlipStart p size (the direction of a slow slip relaxing stiffly, or a slip spiralling in to rest, that the
  /// stop event does not see): those contacts are stopped by the sticking velocity impulse and held sticking (the
  /// engine's rule for a slip that stops as it starts, slide_rock.hpp's held pivot), counted in painleve_events.
  bool hold_slow_slips() {
    std::vector<Contact> st = set_;
    bool any = false;
    for (Contact& c : st) {
      if (!c.slip) continue;
      if (hnorm(vertex_velocity(x_, static_cast<std::size_t>(c.v))) < kSlipStart * p_ref_ * size_) {
        c.slip = false;
        c.fresh = false;
        any = true;
      }
    }
    if (!any) return false;
    stick_impulse(st);
    ++painleve_;
    ++out_.summary.painleve_events;
    enter(Kind::contact, st);
    return true;
  }

  void phase(double tb) {
    if (kind_ == Kind::rest) {
      rest_phase(tb);
      return;
    }
    if (kind_ == Kind::contact) follow_slip_start();
    if (kind_ == Kind::flat_slip) update_launch();
    if (restart_) {
      dp_.restart(t_, x_);
      restart_ = false;
      arm(x_, t_);
      if (settle_down_vertices()) return;
    }
    if (kind_ == Kind::flat_slip) slip_ref_ = {x_[3], x_[4], 0.0};
    if (!dp_.step(tb, steps_, opt_.max_steps)) {
      throw StepLimitError(fmt::format("rock3d: more than max_steps = {} integrator steps by t = {} s",
                                       opt_.max_steps, t_));
    }
    if (kind_ == Kind::flat_slip) {
      const double sp = std::hypot(slip_ref_[0], slip_ref_[1]);
      slip_ref_ = sp > 0.0 ? (1.0 / sp) * slip_ref_ : slip_dir_;
    } else if (kind_ == Kind::contact) {
      const Dyn d0 = dynamics(dp_.x0(), dp_.t0(), set_);
      for (std::size_t k = 0; k < set_.size(); ++k) {
        if (!set_[k].slip) continue;
        const double sp = hnorm(d0.u[k]);
        if (sp > (set_[k].fresh ? kSlipStart : kSlipZero) * p_ref_ * size_) {
          set_[k].s = {d0.u[k][0] / sp, d0.u[k][1] / sp, 0.0};
          set_[k].fresh = false;
        }
      }
    }
    const double ta = dp_.t0(), tbs = dp_.t1();
    std::vector<double> ga, gb;
    events(dp_.x0(), ta, ga);
    double tilt_a = tilt_rate(dp_.x0());
    for (int part = 1; part <= kParts; ++part) {
      const double t0p = ta + (tbs - ta) * (part - 1) / kParts;
      const double t1p = part == kParts ? tbs : ta + (tbs - ta) * part / kParts;
      const SX x1 = dp_.dense(t1p);
      events(x1, t1p, gb);
      const double tilt_b = tilt_rate(x1);
      // the first event in the part
      double t_event = std::numeric_limits<double>::infinity();
      std::size_t which = 0;
      for (std::size_t i = 0; i < gb.size() && i < ga.size(); ++i) {
        if (!armed_[i]) {
          if (gb[i] < 0.0) {
            armed_[i] = true;
          } else if (const int j = touchdown_vertex(i); j >= 0) {
            // A vertex that left the ground at the phase's start and is back down by the part's end (a lift shorter
            // than a part): located by its highest point (the root of its vertical velocity), then the root after it
            // (as the pivot mode of rigid3d.cpp).
            const auto vz = [&, j](double t) { return vertex_velocity(dp_.dense(t), static_cast<std::size_t>(j))[2]; };
            const double va = vz(t0p), vb = vz(t1p);
            if (va > 0.0 && vb < 0.0) {
              const double tm = locate(vz, t0p, t1p, va, vb);
              const auto fn = [&, i](double t) {
                std::vector<double> g;
                events(dp_.dense(t), t, g);
                return g[i];
              };
              const double gm = fn(tm);
              if (gm < 0.0) {
                armed_[i] = true;
                const double r = locate(fn, tm, t1p, gm, gb[i]);
                if (r < t_event) {
                  t_event = r;
                  which = i;
                }
              }
            }
          }
          continue;
        }
        if (ga[i] < 0.0 && gb[i] >= 0.0) {
          const auto fn = [&, i](double t) {
            std::vector<double> g;
            events(dp_.dense(t), t, g);
            return g[i];
          };
          const double r = locate(fn, t0p, t1p, ga[i], gb[i]);
          if (r < t_event) {
            t_event = r;
            which = i;
          }
        }
      }
      // tilt maxima before the event (the summary)
      if (tilt_a < 0.0 && tilt_b >= 0.0) {
        const auto fn = [&](double t) { return tilt_rate(dp_.dense(t)); };
        const double r = locate(fn, t0p, t1p, tilt_a, tilt_b);
        if (r <= t_event) track(r, dp_.dense(r));
      }
      if (std::isfinite(t_event)) {
        t_ = t_event;
        x_ = dp_.dense(t_event);
        track(t_, x_);
        handle(which);
        return;
      }
      ga = gb;
      tilt_a = tilt_b;
    }
    t_ = tbs;
    x_ = dp_.x1();
    track(t_, x_);
    slow_slip_floor();
  }

  /// The flat slip's launch and landing at a step's start (docs/method.md, "Bidirectional sliding", S5' and the
  /// slaved landing; sliding2d.cpp's update_launch, with its launch speed r_L from Rigid3DOptions::sliding): the launch
  /// ends where the speed passes r_L or the quasi-static direction's lag behind the load, r |f_h x f_h'| / |f_h|^3,
  /// would pass kLaunchMaxLag; a block slower than r_L, decelerating (|f_h| < mu_k N), moving along the load within
  /// kLaunchMaxLag and with a lag below half of it is put on the load's direction and slaved to it again (the landing).
  void update_launch() {
    const Vec3 f = forcing_.f(t_);
    const double fm = hnorm(f), N = -f[2];
    const double r = std::hypot(x_[3], x_[4]);
    const double lag_num = r * std::abs(f[0] * forcing_.ays - f[1] * forcing_.axs);  // r |f_h x f_h'|
    if (launch_) {
      if (!(fm > 0.0) || r > launch_speed_ || lag_num > kLaunchMaxLag * fm * fm * fm) {
        launch_ = false;
        restart_ = true;
      }
      return;
    }
    if (!(r < launch_speed_) || !(r > 0.0) || !(fm > 0.0) || !(fm < mu_k_ * N)) return;
    const Vec3 n{f[0] / fm, f[1] / fm, 0.0};
    const bool along = x_[3] * n[0] + x_[4] * n[1] > 0.0 && std::abs(x_[3] * n[1] - x_[4] * n[0]) < kLaunchMaxLag * r;
    if (along && lag_num < 0.5 * kLaunchMaxLag * fm * fm * fm) {
      launch_ = true;
      x_[3] = r * n[0];
      x_[4] = r * n[1];
      restart_ = true;
    }
  }

  /// After a step without an event: slips that are over. Flat: a launch that went backwards along the load (its
  /// onset decided by round-off, the load not overcoming kinetic friction: sliding2d's "never moving forward"), or a
  /// slip slower than the noise floor r_F = kFloorLaunchFraction r_L (S6: the direction is not resolved there; the
  /// rest of the run-in is r_F^2 / (2 a) long), has stopped. A contact: a slip (not one starting from rest) slower
  /// than kFloorLaunchFraction kSlipStart p size has stopped likewise (the contact's velocity v_c + w x r is resolved
  /// only to about rel_tol |v_c|: a slip spiralling in to rest there never crosses its stop event, issue 29). The stop
  /// is handled as a located one (handle()).
  void slow_slip_floor() {
    if (done_) return;
    if (kind_ == Kind::flat_slip) {
      const double r = std::hypot(x_[3], x_[4]);
      bool stopped = !launch_ && r < floor_speed_;  // a launch grows from 0 through the floor: exempt
      if (launch_) {
        const Vec3 f = forcing_.f(t_);
        stopped = f[0] * x_[3] + f[1] * x_[4] <= 0.0;
      }
      if (stopped) handle(0);
      return;
    }
    // (contacts: a backstop, only in a sample interval that has already taken kSlowSteps steps and events; elsewhere
    // the stop event locates the stop, as the planar model's, whose Painleve counts the tests compare)
    if (kind_ != Kind::contact || interval_count_ < kSlowSteps || t_ - since_ < kChatter_s) return;
    const double floor = kFloorLaunchFraction * kSlipStart * p_ref_ * size_;
    for (std::size_t k = 0; k < set_.size(); ++k) {
      if (!set_[k].slip || set_[k].fresh) continue;
      const Vec3 u = vertex_velocity(x_, static_cast<std::size_t>(set_[k].v));
      if (!(hnorm(u) < floor)) continue;
      // slowing down along its slip direction (its acceleration against the velocity): a stop, not a turn
      const Dyn d = dynamics(x_, t_, set_);
      if (!d.ok) continue;
      const Vec3 a = d.a + cross(d.alpha, d.r[k]) + cross(d.w, cross(d.w, d.r[k]));
      if (a[0] * u[0] + a[1] * u[1] < 0.0) {
        handle(2 * k + 1);
        return;
      }
    }
  }

  /// The vertex of a touch-down event function (index i of events()), or -1.
  [[nodiscard]] int touchdown_vertex(std::size_t i) const {
    if (kind_ != Kind::contact && kind_ != Kind::flight) return -1;
    const std::size_t base = kind_ == Kind::contact ? 2 * set_.size() : 0;
    if (i < base || i >= base + v_.size()) return -1;
    const int j = static_cast<int>(i - base);
    for (const Contact& c : set_) {
      if (c.v == j) return -1;
    }
    return j;
  }

  /// The mode decision's check at a phase's start (issue 29; the event-driven rule, Pfeiffer & Glocker 1996, ch. 7;
  /// Glocker 2001): a base vertex not in the set at a gap <= 0 must separate. One moving into the ground (normal
  /// velocity < -tolV) strikes now (an impact); one at rest normally (|v_z| <= tolV) whose acceleration under the
  /// set's forces points into the ground (a_z < -tolF) closes a contact: the mode is chosen again over all the
  /// vertices down, whose check (consistent()) then includes it. A vertex separating (v_z > tolV, or a_z >= -tolF)
  /// is left to its touch-down and dip events. At most kMaxSettle times at one instant (then the dips take over).
  /// True: the state or the mode changed (the phase starts again).
  bool settle_down_vertices() {
    if (kind_ != Kind::contact && kind_ != Kind::flight) return false;
    if (t_ != settle_t_) {
      settle_t_ = t_;
      settle_n_ = 0;
    }
    if (settle_n_ >= kMaxSettle) return false;
    const double tolV = 1e-9 * p_ref_ * size_, tolF = 1e-9 * g_;
    std::optional<Dyn> d;
    int strike = -1;
    bool close = false;
    double fastest = -tolV;
    for (std::size_t j = 0; j < v_.size(); ++j) {
      bool in = false;
      for (const Contact& c : set_) in = in || c.v == static_cast<int>(j);
      if (in || vertex_z(x_, j) > 0.0) continue;
      const double vz = vertex_velocity(x_, j)[2];
      if (vz < fastest) {
        fastest = vz;
        strike = static_cast<int>(j);
        continue;
      }
      if (vz > tolV) continue;
      if (!d) d = dynamics(x_, t_, set_);
      if (!d->ok) continue;
      const Vec3 r = mul(d->R, v_[j] - c_);
      const Vec3 aj = d->a + cross(d->alpha, r) + cross(d->w, cross(d->w, r));
      if (aj[2] < -tolF) close = true;
    }
    if (strike < 0 && !close) return false;
    ++settle_n_;
    if (strike >= 0) {
      impact(strike);
    } else {
      choose(all_down(), {}, -1);
    }
    return true;
  }

  void arm(const SX& x, double t) {
    dip_ref_.assign(v_.size(), kNoDip);
    if (kind_ == Kind::contact || kind_ == Kind::flight) {
      for (std::size_t j = 0; j < v_.size(); ++j) {
        bool in = false;
        for (const Contact& c : set_) in = in || c.v == static_cast<int>(j);
        const double z = vertex_z(x, j);
        if (!in && z <= 0.0) dip_ref_[j] = z;
      }
    }
    std::vector<double> g;
    events(x, t, g);
    armed_.assign(g.size(), false);
    for (std::size_t i = 0; i < g.size(); ++i) armed_[i] = g[i] < 0.0;
  }

  void rest_phase(double tb) {
    std::vector<double> ga, gb;
    const double ta = t_;
    events(x_, ta, ga);
    for (int part = 1; part <= kParts; ++part) {
      const double t0p = ta + (tb - ta) * (part - 1) / kParts;
      const double t1p = part == kParts ? tb : ta + (tb - ta) * part / kParts;
      events(x_, t1p, gb);
      double t_event = std::numeric_limits<double>::infinity();
      std::size_t which = 0;
      for (std::size_t i = 0; i < gb.size(); ++i) {
        if (ga[i] < 0.0 && gb[i] >= 0.0) {
          const auto fn = [&, i](double t) {
            std::vector<double> g;
            events(x_, t, g);
            return g[i];
          };
          const double r = locate(fn, t0p, t1p, ga[i], gb[i]);
          if (r < t_event) {
            t_event = r;
            which = i;
          }
        }
      }
      if (std::isfinite(t_event) && t_event < tb) {
        t_ = t_event;
        const std::size_t before = out_.summary.modes.size();
        choose(all_down(), {}, -1, true, which != 0);  // 0: slip starts; 1: the centre of pressure leaves; 2: flight
        if (kind_ == Kind::rest && out_.summary.modes.size() == before) {
          // on the boundary to round-off: step past it
          t_ = std::min(tb, t_event + std::max(1e-9 * grid_.dt_s(), 4.0 * std::numeric_limits<double>::epsilon() *
                                                                         std::max(std::abs(t_event), 1.0)));
        }
        return;
      }
      ga = gb;
    }
    t_ = tb;
  }

  void handle(std::size_t which) {
    if (kind_ == Kind::flat_slip) {
      if (which == 0) {  // stopped
        x_[3] = x_[4] = 0.0;
        choose(all_down(), {}, -1);
      } else {  // the centre of pressure left the base, or flight
        choose(all_down(), {}, -1, true, true);
      }
      return;
    }
    std::size_t base = 0;
    if (kind_ == Kind::contact) {
      base = 2 * set_.size();
      if (which < base) {
        const std::size_t k = which / 2;
        const int vk = set_[k].v;
        std::vector<int> down;
        for (const Contact& c : set_) down.push_back(c.v);
        if (which % 2 == 0) {  // lift
          choose(down, {vk}, -1);
        } else if (set_[k].slip) {
          // The slip stops (its velocity along the slip direction reached 0): the located root leaves a residue (and,
          // in 3-D, the part across the direction) of the order of the tolerance; a velocity impulse at that contact
          // removes it (the contact's velocity 0, the others' normal velocity kept 0), then the mode is chosen again
          // with the contact at rest.
          std::vector<Contact> st = set_;
          st[k].slip = false;
          st[k].fresh = false;
          stick_impulse(st);
          if (t_ - since_ < kChatter_s) {
            // Stick-slip chattering (the slip that started at this instant stops at once: the stick limit and the
            // slip's deceleration balance to round-off, e.g. mu_s = mu_k at a contact of a pair): the contact is held
            // sticking, as slide_rock.hpp holds a sticking pivot, counted with Painleve's cases (docs/method.md).
            ++painleve_;
            ++out_.summary.painleve_events;
            enter(Kind::contact, st);
            return;
          }
          choose(down, {}, -1);
        } else {  // the stick limit
          choose(down, {}, vk);
        }
        return;
      }
    }
    const std::size_t j = which - base;
    if (j < v_.size()) {
      impact(static_cast<int>(j));
      return;
    }
    if (j > v_.size() && j <= 2 * v_.size()) {  // a dip (events()): the vertex is coming down through the ground
      // With every base vertex within simultaneous_contact of the ground the body is flat to that tolerance: it
      // lands flat (the flat outcome), as a strike of three or more vertices does; a body rocking between opposite
      // edges at tilts of 1e-6 rad would otherwise dip an edge at each swap (issue 29). (Every vertex, not three:
      // the neighbours of a pivot of a fine polygon, a 128-gon, are within that tolerance at tilts of 0.03 rad.)
      impact(static_cast<int>(j - v_.size() - 1), all_down().size() == v_.size());
      return;
    }
    fall();
  }

  void fall() {
    fallen_ = true;
    done_ = true;
    auto& s = out_.summary;
    s.overturned = true;
    s.overturn_time_s = t_;
    const M3 R = rot();
    s.overturn_azimuth_deg = azimuth({R[0][2], R[1][2], 0.0});
    close_mode(s.modes.back().mode);
    s.modes.push_back({t_, Rigid3DMode::fallen, -1, -1});
    row();
  }

  static double azimuth(const Vec3& d) {
    double a = rad_to_deg(std::atan2(d[0], d[1]));
    if (a < 0.0) a += 360.0;
    return a;
  }

  void track(double t, const SX& x) {
    const M3 R = rot(x);
    // The invariant (issue 29): no base vertex below the ground by more than kPenetration of the body's size. The
    // touch-down, dip and settle rules keep it; a breach is the engine's fault, never silent.
    for (std::size_t j = 0; j < v_.size(); ++j) {
      const double z = x[2] + dot(R[2], v_[j] - c_);
      if (z < -kPenetration * size_) {
        bool in = false;
        for (const Contact& c : set_) in = in || c.v == static_cast<int>(j);
        throw SolverError(fmt::format(
            "rock3d: internal error: base vertex {} is {:.3g} m below the ground at t = {} s (more than {} of the "
            "body's size {:.3g} m; mode {}, {}): the contact engine lost the ground; please report it",
            j, -z, t, kPenetration, size_, static_cast<int>(kind_), in ? "a contact" : "not a contact"));
      }
    }
    const Vec3 zb{R[0][2], R[1][2], R[2][2]};
    const double horizontal = std::hypot(zb[0], zb[1]);
    const double tilt = std::atan2(horizontal, zb[2]);
    auto& s = out_.summary;
    const double sp = std::hypot(x[3], x[4]);
    if (kind_ == Kind::flat_slip) s.max_slide_speed_m_s = std::max(s.max_slide_speed_m_s, sp);
    if (kind_ == Kind::contact) {
      for (const Contact& c : set_) {
        if (c.slip) {
          s.max_slide_speed_m_s =
              std::max(s.max_slide_speed_m_s, hnorm(vertex_velocity(x, static_cast<std::size_t>(c.v))));
        }
      }
    }
    // max_slide_m (rigid3d.hpp): the base's excursion from where it started (the body frame's origin at 0 and
    // unturned then, so a vertex started at its body coordinates): flat, its reference point; on vertices, those.
    if (kind_ == Kind::rest || kind_ == Kind::flat_slip) {
      s.max_slide_m = std::max(s.max_slide_m, hnorm(Vec3{x[0], x[1], x[2]} - mul(R, c_)));
    } else if (kind_ == Kind::contact) {
      for (const Contact& c : set_) {
        const Vec3& vb = v_[static_cast<std::size_t>(c.v)];
        const Vec3 at = Vec3{x[0], x[1], x[2]} + mul(R, vb - c_);
        s.max_slide_m = std::max(s.max_slide_m, std::hypot(at[0] - vb[0], at[1] - vb[1]));
      }
    }
    if (!(tilt > 0.0)) return;
    const Vec3 d{zb[0] / horizontal, zb[1] / horizontal, 0.0};
    Vec3 u = mul_t(R, Vec3{d[0] * zb[2], d[1] * zb[2], -horizontal});
    const double un = std::hypot(u[0], u[1]);
    u = {u[0] / un, u[1] / un, 0.0};
    double b = -std::numeric_limits<double>::infinity();
    for (const Vec3& p : v_) b = std::max(b, (p[0] - c_[0]) * u[0] + (p[1] - c_[1]) * u[1]);
    const double ratio = tilt / std::atan2(b, h_);
    if (tilt > s.max_tilt_rad) {
      s.max_tilt_rad = tilt;
      s.max_tilt_time_s = t;
      s.max_tilt_azimuth_deg = azimuth(d);
    }
    if (ratio > s.max_tilt_over_limit) s.max_tilt_over_limit = ratio;
    if (ratio >= 1.0 && !s.exceeded_limit_time_s) s.exceeded_limit_time_s = t;
  }

  /// The time since the last mode change into the durations of slide-rock and flight.
  void close_mode(Rigid3DMode m) {
    if (m == Rigid3DMode::slide_rock) out_.summary.slide_rock_duration_s += t_ - mode_since_;
    if (m == Rigid3DMode::flight) out_.summary.flight_duration_s += t_ - mode_since_;
    mode_since_ = t_;
  }

  void row() {
    if (!opt_.record_history) return;
    auto& h = out_.history;
    const Rigid3DMode m = mode_name();
    if (!h.time_s.empty() && h.time_s.back() == t_ && h.mode.back() == m) {
      h.position_m.back() = position();
      h.orientation.back() = normalized({x_[6], x_[7], x_[8], x_[9]});
      h.angular_velocity_rad_s.back() = {x_[10], x_[11], x_[12]};
      h.energy_j_per_kg.back() = energy(x_);
      return;
    }
    h.time_s.push_back(t_);
    h.position_m.push_back(position());
    h.orientation.push_back(normalized({x_[6], x_[7], x_[8], x_[9]}));
    h.angular_velocity_rad_s.push_back({x_[10], x_[11], x_[12]});
    h.energy_j_per_kg.push_back(energy(x_));
    h.mode.push_back(m);
  }

  void set_forcing(std::size_t i) {
    forcing_ = Forcing::interval(i, grid_.time_s(i), grid_.time_s(i + 1), ax_, ay_, gravity_, g_);
  }

  void run_out() {
    if (kind_ == Kind::rest || opt_.max_run_out_s == 0.0) return;
    const double t_end = t_;
    forcing_ = Forcing::still(t_end, frame_.still);  // level: (0, 0, g)
    restart_ = true;
    run_out_on_still_ground(
        t_end, grid_.dt_s(), opt_.max_run_out_s, t_, [this] { return !done_ && kind_ != Kind::rest; },
        [this](double tb) { interval(tb); },
        [this] {
          if (!done_) row();
        });
  }

  template <class Fn>
  double locate(Fn f, double ta, double tb, double fa, double fb) const {
    const double r = find_root(f, ta, tb, fa, fb);
    if (std::isnan(r)) {
      throw RootFindingError(fmt::format("rock3d: event location did not converge on [{}, {}] s", ta, tb));
    }
    return r;
  }

  static constexpr int kParts = 4;
  static constexpr int kMaxEvents = 10'000;
  static constexpr int kSlowSteps = 1'000;  // steps in a sample interval after which slow slips are held
  static constexpr double kZenoGap_s = 1e-6;
  static constexpr int kZenoSwaps = 8;  // pivot swaps in a row along one edge, each strike slower: the edge's limit
  static constexpr double kFlatStrike = 1e-6;  // a strike slower than this times p size on a flat base: lands flat
  static constexpr double kDip = 1e-9;          // a dip event's depth below the vertex's start, of the body's size
  static constexpr double kPenetration = 1e-6;  // the invariant: no vertex deeper than this of the body's size
  static constexpr double kNoDip = std::numeric_limits<double>::infinity();  // dip_ref_: no dip event
  static constexpr int kMaxSettle = 4;          // settle_down_vertices() at one instant
  static constexpr double kConeTol = 1e-6;  // a sticking force within this fraction of mu_s N: on the boundary
  static constexpr double kParallel = 1e-3;  // a slip direction within this angle (rad) of a_t's line: along it
  static constexpr double kChatter_s = 1e-6;  // a slip that stops within this of its start: held sticking
  // A slip started from rest keeps its consistent direction (slip_directions, renewed at each step) until its speed
  // exceeds kSlipStart p size: below, its velocity's direction relaxes to that direction on the time scale |u| / |a|
  // (stiff: steps of 1e-10 s at 1e-9 m/s, issue 29); above, the velocity's direction is used.
  static constexpr double kSlipStart = 1e-6;
  static constexpr double kSlipZero = 1e-9;  // a slip speed below this times p size is zero (a located stop)
  // The flat slip's launch and landing (docs/method.md, S5', sliding2d.cpp's constants): the launch speed r_L =
  // max(sqrt(abs_tol x 0.1 m/s), 1000 abs_tol) of Rigid3DOptions::sliding, the largest lag of the slaved direction,
  // and the noise floor r_F = kFloorLaunchFraction r_L below which a slowing slip has stopped.
  static constexpr double kLaunchSpeedScale = 0.1;  // m/s
  static constexpr double kLaunchSpeedTolerances = 1000.0;
  static constexpr double kLaunchMaxLag = 1e-3;
  static constexpr double kFloorLaunchFraction = 0.03;
  const InputGrid& grid_;
  std::span<const double> ax_, ay_;
  std::vector<double> gravity_;
  const RigidBody3D& body_;
  const Rigid3DOptions& opt_;
  Dp5<kN, Rhs> dp_;
  ContactStart start_;
  double g_ = 0.0, mu_s_ = 0.0, mu_k_ = 0.0, h_ = 0.0, size_ = 0.0, alpha_ref_ = 0.0, p_ref_ = 0.0, tie_z_ = 0.0;
  std::vector<Vec3> v_;
  Vec3 c_{};
  M3 J_{};
  std::vector<std::array<double, 3>> edges_;  // body frame: n_x, n_y, b
  Forcing forcing_{};
  BaseFrame frame_ = BaseFrame::make(opt_.base_incline_deg, opt_.base_incline_azimuth_deg, opt_.g_m_s2);
  Rigid3DResult out_;
  SX x_{};
  double t_ = 0.0, mode_since_ = 0.0, since_ = 0.0;  // since_: the last entry into a contact set
  double last_impact_t_ = -std::numeric_limits<double>::infinity();
  int swaps_ = 0, swap_pivot_ = -1, swap_striker_ = -1;  // the pivot swaps in a row along one edge (impact())
  double swap_speed_ = 0.0, swap_speed2_ = 0.0;  // the last two strike speeds of a swap sequence
  Kind kind_ = Kind::rest;
  std::vector<Contact> set_;
  Vec3 slip_dir_{1.0, 0.0, 0.0}, slip_ref_{};
  std::vector<bool> armed_;
  std::vector<double> dip_ref_;  // per vertex: its height at the phase's start where <= 0 (a dip event), else kNoDip
  double settle_t_ = -1.0;
  int settle_n_ = 0;
  int interval_count_ = 0;  // steps and events in the current sample interval (interval())
  bool launch_ = false;  // a flat slip whose velocity is slaved to the load's direction (update_launch)
  double launch_speed_ = 0.0, floor_speed_ = 0.0;
  double lift_min_ = std::numeric_limits<double>::infinity();  // the least energy to tip over an edge, J/kg
  bool restart_ = true, done_ = false, fallen_ = false, was_slipping_ = false, flat_before_ = true;
  std::size_t steps_ = 0, painleve_ = 0;
};

void Rhs::operator()(const SX& x, double t, SX& dx) const { e->rhs(x, t, dx); }

}  // namespace

Rigid3DResult rock3d_contact(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                             const RigidBody3D& body, const Rigid3DOptions& options, const ContactStart& start) {
  const std::array<const GroundMotion*, 3> components{&x, y, z};
  const InputGrid grid(components);
  std::vector<double> gravity = effective_gravity(grid, 2, options.g_m_s2);
  ContactEngine engine(grid, std::move(gravity), body, options, start);
  return engine.run();
}

}  // namespace topple::detail
