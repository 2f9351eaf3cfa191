// The cylinder with a slipping rim point and free flight (issue 29; docs/method.md, "A circular base with friction";
// rigid3d_disc.hpp). rock3d_cylinder hands a run to it where the rolling contact fails (N -> 0 or |F_t| > mu_s N).
//
// Model (per unit mass, ground frame; f = (-a_x, -a_y, -(g + a_z)) at c). A free rigid body: c, its velocity v, q,
// w (ground frame). The contact is the lowest point of the base circle, p = c + rho, rho = -h a + R u (a the axis, u
// the lowest point's direction from the base's centre: u = (a_z e, -sin(theta)), e = a_h / |a_h|, as the rolling
// engine's; within a step continued past the upright on the step's side, u -> -u, as there). Its velocity v_p = v +
// w x rho; its height's rate is v_p . z (the envelope theorem: the lowest point's height changes as the material point
// there moves), and the rate of v_p is (rho' = -h a' + R u', the geometric motion of the contact point)
//   a_p = a_c + alpha x rho + w x rho' = b + W F,   b = f + alpha_0 x rho + w x rho',   alpha_0 = -J^-1 (w x J w),
//   W F = F + (J^-1 (rho x F)) x rho   (J = J_G, the inertia about c in the ground frame),
// with a_c = f + F, J alpha = rho x F - w x J w (Newton-Euler; the contact force F at p). Modes:
//   stick (rolling on the rim): a_p = 0 (3 equations): F = -W^-1 b (the rolling engine's motion exactly);
//   slip: F = N (z - mu_k s), s = v_p,h / |v_p,h| (Coulomb), a_p . z = 0: N = -b_z / (W (z - mu_k s))_z;
//   flight: F = 0; flat: the base flat on the ground, at rest or sliding in translation (rigid3d_slide.cpp's flat
//   phase: F = (-mu_k N s_h, N), N = g + a_z; no rotation).
// Transitions (events located by TOMS 748 on the Dormand-Prince dense output, 4 parts per step): stick -> slip where
// |F_t| = mu_s N, the slip's direction from rest by Coulomb at acceleration level (the slip acceleration a_p,h along s
// with F_t = -mu_k N s: a fixed point from s = -F_t / |F_t|, the stick force's opposite); slip -> stick or turn where
// v_p,h . s0 -> 0 (s0 the direction at the step's start): stick if the stick force is in the cone, else a slip from
// rest; stick/slip -> flight where N -> 0; flight -> impact where the lowest point's height -> 0; the base landing
// flat (the rolling engine's landing function); the tilt reaching 90 degrees (fallen); flat sliding -> rest where the
// speed -> 0, flight where g + a_z -> 0; rest -> rim (the rolling engine's uplift test) or sliding (|a_h| > mu_s N), flight where g + a_z <= 0;
// flat sliding -> rim (slipping) at once where mu_k h > R (the centre of pressure beyond the rim).
// Painleve: a slip with (W (z - mu_k s))_z <= 0 has no consistent N; the contact is then held sticking (slide_rock.hpp's
// rule), counted in painleve_events.
// Impacts: a rim point landing from flight: plastic normally, a Coulomb impulse tangentially (the stick impulse P =
// -W^-1 v_p- if |P_t| <= mu_s P_z, else P = P_n (z - mu_k s), s along v_p,h-; rigid3d_contact.cpp's law at one point).
// The base landing flat (from the rim or from flight with tilt below 1e-3 alpha): the rolling engine's Housner law about
// the new rim point where its impulse is in the friction cone (P = v_c+ - v_c-); else the flat outcome of
// rigid3d_contact.cpp (the vertical and tilting motion stopped, the horizontal one stopped if |v_h| <= mu_s |v_z-|,
// else sliding with |v_h| reduced by mu_k |v_z-|, spin stopped: an approximation, stated).
#include "rigid3d_disc_contact.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "rigid3d_math.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/numerics/event_root.hpp"

namespace topple::detail {
namespace {

using namespace r3d;
// c (3), v (3), q (4), w (3), slip path, friction work, slip displacement (2: the integral of the contact's slip
// velocity, east and north; max_slide_m is its largest length, rigid3d.hpp)
constexpr std::size_t kN = 17;
using SX = State<kN>;
constexpr double kDirectionFloor = 1e-12;  // sin(tilt) below which the contact direction is the remembered one
constexpr double kFlatTilt = 1e-3;         // a landing from flight with tilt below this times alpha lands flat

enum class Kind : std::uint8_t { rest, flat_slip, stick, slip, flight };

Vec3 hpart(const Vec3& v) { return {v[0], v[1], 0.0}; }
double hnorm(const Vec3& v) { return std::hypot(v[0], v[1]); }
double azimuth(const Vec3& d) {
  double az = std::atan2(d[0], d[1]) * 180.0 / M_PI;
  if (az < 0.0) az += 360.0;
  return az;
}

class DiscEngine;
struct Rhs {
  DiscEngine* e;
  void operator()(const SX& x, double t, SX& dx) const;
};

/// The contact's geometry and rates of a state (header).
struct Rim {
  Vec3 a, u, rho, rhod, vp;
  double sin_tilt = 0.0;
};

class DiscEngine {
 public:
  DiscEngine(const InputGrid& grid, std::vector<double> gravity, const CylinderBody3D& body, const Rigid3DOptions& opt,
             const DiscStart& start)
      : grid_(grid), ax_(grid.accel_m_s2(0)), ay_(grid.accel_m_s2(1)), gravity_(std::move(gravity)),
        R_(body.radius_m), h_(body.centre_height_m), Ja_(body.inertia_axial_m2), Jt_(body.inertia_transverse_m2),
        opt_(opt), dp_(Rhs{this}, opt.abs_tol, opt.rel_tol, 0.1 * (grid.dt_s() > 0.0 ? grid.dt_s() : 0.01)),
        start_(start) {
    g_ = opt.g_m_s2;
    mu_s_ = *opt.mu_s;
    mu_k_ = opt.mu_k.value_or(mu_s_);
    size_ = std::hypot(R_, h_);
    alpha_ = std::atan2(R_, h_);
    p_ref_ = std::sqrt(g_ / size_);
    const double a = alpha_, L = size_ * a, V = p_ref_ * size_ * a;
    dp_.set_scale({L, L, L, V, V, V, a, a, a, a, p_ref_ * a, p_ref_ * a, p_ref_ * a, L, g_ * L, L, L});
    u_ = hpart(start.contact_direction);
    const double n = hnorm(u_);
    u_ = n > 0.0 ? (1.0 / n) * u_ : Vec3{1.0, 0.0, 0.0};
  }

  Rigid3DResult run() {
    const std::size_t n = grid_.size();
    t_ = start_.time_s;
    mode_since_ = t_;
    std::size_t i = 0;
    while (i + 2 < n && grid_.time_s(i + 1) <= t_) ++i;
    for (std::size_t k = 0; k < 3; ++k) {
      x_[k] = start_.position_m[k];
      x_[3 + k] = start_.velocity_m_s[k];
      x_[10 + k] = start_.angular_velocity_rad_s[k];
    }
    for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = start_.orientation[k];
    base0_ = hpart(start_.position_m - h_ * axis(x_));
    if (i + 1 < n) set_forcing(i);
    if (start_.at_rest) {
      enter(Kind::rest);
    } else {
      decide_rim(false);
    }
    row();
    for (; !done_ && i + 1 < n; ++i) {
      const double tb = grid_.time_s(i + 1);
      if (!(tb > grid_.time_s(i))) continue;
      set_forcing(i);
      interval(tb);
      if (!done_) row();
    }
    if (!done_) run_out();
    auto& s = out_.summary;
    close_mode();
    s.end_time_s = t_;
    s.end_mode = mode_name();
    if (!done_ && kind_ != Kind::rest) {
      s.warnings.push_back(fmt::format("the body was still moving {} s after the record ended (max_run_out_s)",
                                       opt_.max_run_out_s));
    }
    const Vec3 base = hpart(centre() - h_ * axis(x_));
    s.residual_slide_east_m = base[0];
    s.residual_slide_north_m = base[1];
    const M3 Rm = rotation(quat(x_));
    s.residual_yaw_deg = std::atan2(Rm[1][0] - Rm[0][1], Rm[0][0] + Rm[1][1]) * 180.0 / M_PI;
    s.slide_path_length_m = x_[13];
    s.friction_energy_j_per_kg = x_[14];
    s.steps = steps_;
    s.max_tilt_over_limit = s.max_tilt_rad / alpha_;
    return std::move(out_);
  }

  // ------------------------------------------------------------------------------------------------------------
  // State algebra

  static Quaternion quat(const SX& x) { return {x[6], x[7], x[8], x[9]}; }
  static Vec3 omega(const SX& x) { return {x[10], x[11], x[12]}; }
  [[nodiscard]] Vec3 centre() const { return {x_[0], x_[1], x_[2]}; }
  static Vec3 axis(const SX& x) {
    const M3 m = rotation(quat(x));
    return {m[0][2], m[1][2], m[2][2]};
  }
  /// J^-1 v for the axisymmetric inertia about c: J = J_t 1 + (J_a - J_t) a a^T.
  [[nodiscard]] Vec3 Jinv(const Vec3& a, const Vec3& v) const {
    const double k = dot(a, v);
    return (1.0 / Jt_) * (v - k * a) + (k / Ja_) * a;
  }
  [[nodiscard]] Vec3 Jmul(const Vec3& a, const Vec3& v) const { return Jt_ * v + ((Ja_ - Jt_) * dot(a, v)) * a; }

  /// The rim's geometry at x; u0: the step's starting contact (continued past the upright on its side).
  [[nodiscard]] Rim rim(const SX& x, const Vec3& u0) const {
    Rim r;
    r.a = axis(x);
    const Vec3 w = omega(x);
    const Vec3 ad = cross(w, r.a);
    const double hz = hnorm(r.a);
    r.sin_tilt = hz;
    Vec3 ud{};
    if (hz > kDirectionFloor) {
      const double ex = r.a[0] / hz, ey = r.a[1] / hz;
      r.u = {r.a[2] * ex, r.a[2] * ey, -hz};
      // d' as the rolling engine's (rigid3d_disc.cpp, rim_rates)
      const double turn = (ex * ad[1] - ey * ad[0]) / hz;
      ud = {ad[2] * ex - r.a[2] * turn * ey, ad[2] * ey + r.a[2] * turn * ex, -(ex * ad[0] + ey * ad[1])};
      if (dot(r.u, u0) < 0.0) {
        r.u = -1.0 * r.u;
        ud = -1.0 * ud;
      }
    } else {
      r.u = u0;
      ud = cross(w, r.u);
    }
    r.rho = R_ * r.u - h_ * r.a;
    r.rhod = R_ * ud - h_ * ad;
    r.vp = Vec3{x[3], x[4], x[5]} + cross(w, r.rho);
    return r;
  }

  /// W's columns and b (header) at x under f.
  struct Ab {
    M3 W;  // rows
    Vec3 b;
  };
  [[nodiscard]] Ab contact_problem(const SX& x, const Rim& r, const Vec3& f) const {
    const Vec3 w = omega(x);
    const Vec3 al0 = -1.0 * Jinv(r.a, cross(w, Jmul(r.a, w)));
    Ab out;
    out.b = f + cross(al0, r.rho) + cross(w, r.rhod);
    for (std::size_t j = 0; j < 3; ++j) {
      Vec3 e{};
      e[j] = 1.0;
      const Vec3 col = e + cross(Jinv(r.a, cross(r.rho, e)), r.rho);
      for (std::size_t i = 0; i < 3; ++i) out.W[i][j] = col[i];
    }
    return out;
  }
  [[nodiscard]] static Vec3 solve(const M3& W, const Vec3& rhs) { return mul(inverse(W), rhs); }

  /// The contact force of the current kind at x (stick, slip; zero in flight).
  [[nodiscard]] Vec3 force(const SX& x, const Rim& r, const Vec3& f, Kind kind, const Vec3& s, bool* painleve) const {
    if (kind == Kind::flight) return {};
    const Ab ab = contact_problem(x, r, f);
    if (kind == Kind::stick) return solve(ab.W, -1.0 * ab.b);
    const Vec3 dir{-mu_k_ * s[0], -mu_k_ * s[1], 1.0};
    const double wz = dot(ab.W[2], dir);
    if (!(wz > 1e-12)) {
      if (painleve) *painleve = true;
      return solve(ab.W, -1.0 * ab.b);
    }
    return (-ab.b[2] / wz) * dir;
  }

  void rhs(const SX& x, double t, SX& dx) const {
    const Vec3 f = forcing_.f(t);
    dx = {};
    for (std::size_t k = 0; k < 3; ++k) dx[k] = x[3 + k];
    if (kind_ == Kind::flat_slip) {
      const double G = -f[2];
      const double sp = std::hypot(x[3], x[4]);
      // a flat slide from rest: its direction regularised as a rim slip's (slip_direction): s = (v + e s_0) /
      // |v + e s_0|, so that a slide starting at |a_h| = mu G (zero acceleration along s_0) does not turn stiffly at
      // 1e-11 m/s (issue 29's sweep, 12 runs; docs/method.md)
      const double eps = kSlipStart * p_ref_ * size_;
      const double e = fresh_ ? std::max(0.0, eps * (1.0 - sp / (kFreshEnd * eps))) : 0.0;
      const double vx = x[3] + e * slip_dir_[0], vy = x[4] + e * slip_dir_[1], vn = std::hypot(vx, vy);
      const Vec3 s = vn > 0.0 ? Vec3{vx / vn, vy / vn, 0.0} : slip_dir_;
      dx[3] = f[0] - mu_k_ * G * s[0];
      dx[4] = f[1] - mu_k_ * G * s[1];
      dx[5] = 0.0;
      dx[13] = sp;
      dx[14] = mu_k_ * G * sp;
      dx[15] = x[3];
      dx[16] = x[4];
      return;
    }
    const Vec3 w = omega(x);
    const Quaternion qd = qmul({0.0, w[0], w[1], w[2]}, quat(x));
    for (std::size_t k = 0; k < 4; ++k) dx[6 + k] = 0.5 * qd[k];
    const Rim r = rim(x, u_);
    Vec3 F{};
    if (kind_ == Kind::stick || kind_ == Kind::slip) {
      const Vec3 s = slip_direction(x, r, f);
      F = force(x, r, f, kind_, s, nullptr);
      if (kind_ == Kind::slip) {
        const double sp = hnorm(r.vp);
        dx[13] = sp;
        dx[14] = mu_k_ * F[2] * sp;
        dx[15] = r.vp[0];
        dx[16] = r.vp[1];
      }
    }
    const Vec3 ac = f + F;
    const Vec3 al = Jinv(r.a, cross(r.rho, F) - cross(w, Jmul(r.a, w)));
    for (std::size_t k = 0; k < 3; ++k) {
      dx[3 + k] = ac[k];
      dx[10 + k] = al[k];
    }
  }

  /// A slipping contact's direction: along its slip velocity; a slip from rest (fresh, until it is faster than
  /// kFreshEnd eps) regularised by Coulomb's direction from rest s_0 (slip_from_rest), s = (v + e s_0) / |v + e s_0|,
  /// v = v_p,h, e = eps (1 - |v| / (kFreshEnd eps)) >= 0, eps = kSlipStart p size: continuous in the state (so that
  /// the error control sees it), s_0 at the start, the slip's own direction from kFreshEnd eps on (a stated
  /// regularisation, docs/method.md).
  [[nodiscard]] Vec3 slip_direction(const SX& x, const Rim& r, const Vec3& f) const {
    (void)x;
    (void)f;
    const double eps = kSlipStart * p_ref_ * size_;
    const double e = fresh_ ? std::max(0.0, eps * (1.0 - hnorm(r.vp) / (kFreshEnd * eps))) : 0.0;
    const Vec3 v = hpart(r.vp) + e * slip_dir_;
    const double n = hnorm(v);
    return n > 0.0 ? (1.0 / n) * v : slip_dir_;
  }

  /// The direction of a slip from rest (header): Coulomb at acceleration level, the slip acceleration a_p,h along s
  /// with F = N (z - mu_k s); the fixed point from s (a step is kept only where a_p,h is resolved, above 1e-9 g: at
  /// a stick limit with mu_k = mu_s the slip's acceleration starts from 0 and s stays the stick force's opposite).
  [[nodiscard]] Vec3 slip_from_rest(const Ab& ab, Vec3 s) const {
    for (int it = 0; it < 20; ++it) {
      const Vec3 dir{-mu_k_ * s[0], -mu_k_ * s[1], 1.0};
      const double wz = dot(ab.W[2], dir);
      if (!(wz > 1e-12)) break;
      const Vec3 Fs = (-ab.b[2] / wz) * dir;
      const Vec3 ap = hpart(ab.b + mul(ab.W, Fs));
      const double an = hnorm(ap);
      if (!(an > 1e-9 * g_)) break;
      const Vec3 sn = (1.0 / an) * ap;
      if (hnorm(sn - s) < 1e-12) break;
      s = sn;
    }
    return s;
  }

  // ------------------------------------------------------------------------------------------------------------
  // Mode choice at an instant

  /// The body on its rim at x_ (after an event or an impact): flight, stick or slip (header), from the contact's
  /// velocity and the forces. allow_stick false: where the rolling contact just failed (the caller's hand-over).
  void decide_rim(bool allow_stick = true) {
    const Vec3 f = forcing_.f(t_);
    const Rim r = rim(x_, u_);
    if (r.sin_tilt > kDirectionFloor) u_ = (1.0 / hnorm(r.u)) * hpart(r.u);
    if (r.vp[2] < -kSlipZero * p_ref_ * size_) {
      // the contact point on the ground moving down (a touch-down that no event saw): the landing's impulse first
      // (rim_impulse: plastic normally, Coulomb tangentially), so that the rim never goes below the ground
      ++out_.summary.impacts;
      rim_impulse(r);
      return decide_rim(allow_stick);
    }
    const double sp = hnorm(r.vp);
    const Ab ab = contact_problem(x_, r, f);
    if (sp <= kSlipZero * p_ref_ * size_) {
      const Vec3 F = solve(ab.W, -1.0 * ab.b);
      if (!(F[2] > 0.0)) return enter(Kind::flight);
      if (allow_stick && hnorm(F) <= mu_s_ * F[2] * (1.0 + 1e-9)) return enter(Kind::stick);
      // a slip from rest: Coulomb at acceleration level, the fixed point from the stick force's opposite
      const double fn = hnorm(F);
      slip_dir_ = slip_from_rest(ab, fn > 0.0 ? (-1.0 / fn) * hpart(F) : Vec3{1.0, 0.0, 0.0});
      fresh_ = true;
      slip_start_ = t_;
    } else {
      slip_dir_ = (1.0 / sp) * hpart(r.vp);
      fresh_ = false;
      slip_start_ = t_;
    }
    const Vec3 dir{-mu_k_ * slip_dir_[0], -mu_k_ * slip_dir_[1], 1.0};
    const double wz = dot(ab.W[2], dir);
    if (!(wz > 1e-12)) {  // Painleve: no consistent slip; held sticking (or stopped by the stick impulse)
      ++out_.summary.painleve_events;
      if (sp > 0.0) stick_impulse(r);
      return enter(Kind::stick);
    }
    const double N = -ab.b[2] / wz;
    if (!(N > 0.0)) return enter(Kind::flight);
    enter(Kind::slip);
  }

  /// The contact's velocity stopped by an impulse at p (P = -W^-1 v_p: the sticking impulse).
  void stick_impulse(const Rim& r) {
    const Ab ab = contact_problem(x_, r, {});
    const Vec3 P = solve(ab.W, -1.0 * r.vp);
    const double before = kinetic(x_);
    apply_impulse(r, P);
    out_.summary.energy_lost_j_per_kg += before - kinetic(x_);  // >= 0: a plastic impulse
  }
  void apply_impulse(const Rim& r, const Vec3& P) {
    const Vec3 dw = Jinv(r.a, cross(r.rho, P));
    for (std::size_t k = 0; k < 3; ++k) {
      x_[3 + k] += P[k];
      x_[10 + k] += dw[k];
    }
  }

  void enter(Kind k) {
    const Rigid3DMode old = mode_name();
    close_mode();
    kind_ = k;
    const Rigid3DMode m = mode_name();
    auto& s = out_.summary;
    if (k == Kind::slip || k == Kind::flat_slip) {
      if (!s.first_slip_time_s) s.first_slip_time_s = t_;
      if (old == Rigid3DMode::rest || old == Rigid3DMode::rocking) ++s.slip_episodes;
    }
    if (k == Kind::slip && !s.slide_rock_time_s) s.slide_rock_time_s = t_;
    if (k == Kind::flight) {
      // the landing: the lowest point back below its height at the take-off (0, or the contact's drift below it)
      // less 1e-12 of the body's size, so that a take-off at N = 0 is not at once a landing
      const Rim r = rim(x_, u_);
      gap_ref_ = std::min(0.0, x_[2] + r.rho[2]) - 1e-12 * size_;
      ++s.flights;
      if (!s.flight_time_s) s.flight_time_s = t_;
    }
    if (s.modes.empty() || s.modes.back().mode != m) s.modes.push_back({t_, m, -1, -1});
    restart_ = true;
  }
  [[nodiscard]] Rigid3DMode mode_name() const {
    if (fallen_) return Rigid3DMode::fallen;
    switch (kind_) {
      case Kind::rest: return Rigid3DMode::rest;
      case Kind::flat_slip: return Rigid3DMode::sliding;
      case Kind::stick: return Rigid3DMode::rocking;
      case Kind::slip: return Rigid3DMode::slide_rock;
      case Kind::flight: return Rigid3DMode::flight;
    }
    return Rigid3DMode::rest;
  }
  void close_mode() {
    const Rigid3DMode m = mode_name();
    if (m == Rigid3DMode::slide_rock) out_.summary.slide_rock_duration_s += t_ - mode_since_;
    if (m == Rigid3DMode::flight) out_.summary.flight_duration_s += t_ - mode_since_;
    mode_since_ = t_;
  }

  // ------------------------------------------------------------------------------------------------------------
  // Time stepping and events

  void set_forcing(std::size_t i) {
    forcing_ = Forcing::interval(i, grid_.time_s(i), grid_.time_s(i + 1), ax_, ay_, gravity_, g_);
    restart_ = true;
  }

  void interval(double tb) {
    int count = 0;
    while (!done_ && t_ < tb) {
      if (++count > kMaxEvents) {
        throw EventLimitError(fmt::format("rock3d_cylinder: more than {} events in one sample interval ending at {} s",
                                          kMaxEvents, tb));
      }
      if (tb - t_ <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(tb), 1.0)) {
        t_ = tb;
        break;
      }
      if (count % kSlowSteps == 0 && kind_ == Kind::slip && slow_slip()) continue;
      if (count % kSlowSteps == 0 && kind_ == Kind::flat_slip && slow_flat_slide()) continue;
      if (kind_ == Kind::rest) {
        rest_phase(tb);
      } else {
        phase(tb);
      }
    }
  }

  void run_out() {
    if (kind_ == Kind::rest || opt_.max_run_out_s == 0.0) return;
    const double t_end = t_;
    forcing_ = Forcing::still(t_end, g_);
    restart_ = true;
    const double t_stop = t_end + opt_.max_run_out_s;
    const double dt = std::max(grid_.dt_s(), opt_.max_run_out_s * 1e-5);
    double next = t_end + dt;
    while (!done_ && kind_ != Kind::rest && t_ < t_stop) {
      interval(std::min(next, t_stop));
      if (!done_) row();
      next += dt;
    }
  }

  /// At rest (base flat, stuck): the uplift (the rolling engine's threshold |a_h| > (g + a_z) R / h), a slip
  /// (|a_h| > mu_s (g + a_z)) or flight (g + a_z <= 0), whichever first, on the linear input.
  void rest_phase(double tb) {
    const auto acc = [&](double t) { return -1.0 * forcing_.f(t); };  // (a_x, a_y, G)
    const auto lift = [&](double t) {
      const Vec3 a = acc(t);
      return a[0] * a[0] + a[1] * a[1] - std::pow(a[2] * R_ / h_, 2);
    };
    const auto slide = [&](double t) {
      const Vec3 a = acc(t);
      return a[0] * a[0] + a[1] * a[1] - std::pow(mu_s_ * a[2], 2);
    };
    const auto fly = [&](double t) { return -acc(t)[2]; };
    double t_ev = tb;
    int which = 0;
    for (int k = 0; k < 3; ++k) {
      const auto fn = [&](double t) { return k == 0 ? lift(t) : k == 1 ? slide(t) : fly(t); };
      const double fa = fn(t_), fb = fn(tb);
      double te = std::numeric_limits<double>::infinity();
      if (fa > 0.0) {
        te = t_;
      } else if (fb > 0.0) {
        // |a_h|^2 - (k G)^2 on a linear piece is a quadratic: one root where it starts below and ends above
        te = locate(fn, t_, tb, fa, fb);
        for (int n = 0; n < 16 && !(fn(te) > 0.0) && te < tb; ++n) te = std::nextafter(te, tb);
      }
      if (te < t_ev || (te == t_ev && which == 0 && te < tb)) {
        t_ev = te;
        which = k + 1;
      }
    }
    t_ = t_ev;
    if (which == 0) return;
    const Vec3 a = acc(t_);
    if (which == 3) return enter(Kind::flight);
    const double ah = std::hypot(a[0], a[1]);
    if (which == 1) {  // uplift: the rim point toward -a_h, at rest
      u_ = {-a[0] / ah, -a[1] / ah, 0.0};
      ++out_.summary.uplifts;
      if (!out_.summary.uplift_time_s) out_.summary.uplift_time_s = t_;
      decide_rim();
      row();
      return;
    }
    slip_dir_ = {-a[0] / ah, -a[1] / ah, 0.0};  // the flat block slides along -a_h from rest
    fresh_ = true;
    enter(Kind::flat_slip);
  }

  template <class Fn>
  double locate(Fn f, double ta, double tb, double fa, double fb) const {
    const double r = find_root(f, ta, tb, fa, fb);
    if (std::isnan(r)) {
      throw RootFindingError(fmt::format("rock3d_cylinder: event location did not converge on [{}, {}] s", ta, tb));
    }
    return r;
  }

  /// One integrator step toward tb and the first event in it.
  void phase(double tb) {
    if (kind_ == Kind::flat_slip && mu_k_ * h_ > R_) {
      // the centre of pressure c_plan + h mu_k s beyond the rim: the leading rim point carries the body, slipping
      const double sp = std::hypot(x_[3], x_[4]);
      u_ = sp > 0.0 ? Vec3{x_[3] / sp, x_[4] / sp, 0.0} : slip_dir_;
      ++out_.summary.uplifts;
      if (!out_.summary.uplift_time_s) out_.summary.uplift_time_s = t_;
      decide_rim();
      if (kind_ == Kind::flat_slip) return;
    }
    if (restart_) {
      dp_.restart(t_, x_);
      restart_ = false;
    }
    if (!dp_.step(tb, steps_, opt_.max_steps)) {
      throw StepLimitError(fmt::format("rock3d_cylinder: more than {} integrator steps", opt_.max_steps));
    }
    const double t0 = dp_.t0(), t1 = dp_.t1();
    const SX x0 = dp_.x0();
    const Vec3 u0 = u_;
    const Rim r0 = rim(x0, u0);
    const Vec3 s0 = kind_ == Kind::flat_slip
                        ? (std::hypot(x0[3], x0[4]) > 0.0 ? (1.0 / std::hypot(x0[3], x0[4])) * Vec3{x0[3], x0[4], 0.0}
                                                          : slip_dir_)
                        : slip_direction(x0, r0, forcing_.f(t0));
    // The event functions (> 0 while the mode holds), by index: 0 N (flight), 1 stick cone, 2 slip speed along s0,
    // 3 landing flat, 4 the tilt below 90 degrees, 5 flight: the lowest point's height, 6 flat: the slide speed, 7 the
    // tilt's rate (a minimum: the whirl rule), 8 flat: g + a_z (flight).
    const auto ev = [&](int k, double t) -> double {
      const SX x = dp_.dense(t);
      if (k == 6) return x[3] * s0[0] + x[4] * s0[1];
      const Rim r = rim(x, u0);
      switch (k) {
        case 0:
        case 1: {
          const Vec3 f = forcing_.f(t);
          const Vec3 F = force(x, r, f, kind_, slip_direction(x, r, f), nullptr);
          // the tolerance of decide_rim's stick test (1e-9 relative), so that a contact chosen there is not at once
          // an event
          return k == 0 ? F[2] / g_ : (mu_s_ * F[2] * (1.0 + 1e-9) - hnorm(F)) / g_;
        }
        case 2: return dot(hpart(r.vp), s0) / (p_ref_ * size_);
        // the lean toward the step's contact: 0 where the axis passes the vertical (rigid3d_disc.cpp's landing
        // -z_perp . u0 without its factor a_z, which would also vanish at the fall)
        case 3: return dot(hpart(r.a), u0) / alpha_;
        // fallen at 90 degrees less 1e-6 rad: the side on the ground (a body lying on its rim point can hover there)
        case 4: return r.a[2] - 1e-6;
        case 5: return (x[2] + r.rho[2] - gap_ref_) / size_;
        case 7: return cross(omega(x), r.a)[2] / p_ref_;  // a_z' > 0 while the tilt falls: 0 at a tilt minimum
        // flat sliding: the normal force g + a_z (issue 29: below 0 the flat phase's friction would push, mu_k N < 0)
        case 8: return -forcing_.f(t)[2] / g_;
        default: return 1.0;
      }
    };
    std::vector<int> active;
    switch (kind_) {
      case Kind::stick: active = {0, 1, 3, 4, 7}; break;
      case Kind::slip: active = {0, 2, 3, 4, 7}; break;
      case Kind::flight: active = {5, 4}; break;
      case Kind::flat_slip: active = {6, 8}; break;
      case Kind::rest: break;
    }
    // the landing function starts at 0 on a flat start: armed once it has been positive (rigid3d_disc.cpp's rule)
    if (!(r0.sin_tilt > kDirectionFloor)) landing_armed_ = false;
    double t_ev = t1;
    int which = -1;
    for (const int k : active) {
      double ta = t0, fa = ev(k, t0);
      if (k == 3 && !landing_armed_) {
        if (fa > 0.0) landing_armed_ = true;
      }
      for (int j = 1; j <= kParts; ++j) {
        const double tj = t0 + (t1 - t0) * j / kParts;
        if (tj > t_ev) break;
        const double fj = ev(k, tj);
        if (k == 3 && !landing_armed_) {
          if (fj > 0.0) landing_armed_ = true;
          ta = tj;
          fa = fj;
          continue;
        }
        if (fa > 0.0 && !(fj > 0.0)) {
          const double te = locate([&](double t) { return ev(k, t); }, ta, tj, fa, fj);
          if (te < t_ev || which < 0) {
            t_ev = te;
            which = k;
          }
          break;
        }
        ta = tj;
        fa = fj;
      }
    }
    // max tilt at the step's parts (and the event)
    for (int j = 1; j <= kParts; ++j) {
      const double tj = t0 + (t1 - t0) * j / kParts;
      if (tj >= t_ev) break;
      track(tj, dp_.dense(tj));
    }
    const bool event = which >= 0;
    x_ = event ? dp_.dense(t_ev) : dp_.x1();
    t_ = event ? t_ev : t1;
    track(t_, x_);
    if (kind_ == Kind::slip || kind_ == Kind::flat_slip) {
      const double sp = kind_ == Kind::slip ? hnorm(rim(x_, u0).vp) : std::hypot(x_[3], x_[4]);
      out_.summary.max_slide_speed_m_s = std::max(out_.summary.max_slide_speed_m_s, sp);
      if (fresh_ && sp > kFreshEnd * kSlipStart * p_ref_ * size_) fresh_ = false;  // e = 0 there: no jump
    }
    if (kind_ == Kind::stick || kind_ == Kind::slip || kind_ == Kind::flight) {
      const Rim r = rim(x_, u0);
      if (r.sin_tilt > kDirectionFloor) u_ = (1.0 / hnorm(r.u)) * hpart(r.u);
    }
    if (kind_ == Kind::stick || kind_ == Kind::slip) project_onto_ground();
    if (!event) {
      if (kind_ == Kind::stick && !landing_armed_ && ev(3, t1) < 0.0) no_lift();  // never rose: back flat at rest
      if (kind_ == Kind::slip && !landing_armed_ && ev(3, t1) < 0.0) {
        // a slip from flat that never rose on its contact's side tilted the other way: the step's contact held on
        // the ground while the opposite rim point went below it (issue 29's invariant: 1.5e-5 m in the one-component
        // comparison). The base lands flat at the step's end (the flat landing's law: Housner about the new rim point,
        // or the flat outcome; no_lift's rule for a stick, which stops the body, would also stop the slip)
        flat_landing();
        row();
      }
      return;
    }
    restart_ = true;
    switch (which) {
      case 0:
        enter(Kind::flight);
        break;
      case 1:
        decide_rim(false);
        break;
      case 2: {
        // the slip stops (or turns): zero the residual slip velocity with the stick impulse (of the order of the
        // located root's tolerance), then stick or slip from rest; a slip that stops within kChatter_s of its start
        // is held sticking (rigid3d_contact.cpp's rule; counted in painleve_events)
        stick_impulse(rim(x_, u_));
        if (t_ - slip_start_ < kChatter_s) {
          ++out_.summary.painleve_events;
          enter(Kind::stick);
        } else {
          decide_rim();
        }
        break;
      }
      case 3:
        flat_landing();
        break;
      case 7:
        // a tilt minimum: with a sideways rate the lowest point runs round the rim instead of the base landing
        // (rigid3d_disc.cpp's whirl rule): below kFlatTilt alpha the base lands flat here; else the motion goes on
        // (with a sideways rate w . u != 0, as there: in one vertical plane the minimum is the landing itself)
        if (rim(x_, u_).sin_tilt < std::sin(kFlatTilt * alpha_) && std::abs(dot(omega(x_), u_)) > 1e-8) {
          flat_landing();
        }
        break;
      case 4:
        fall();
        break;
      case 5:
        rim_landing();
        break;
      case 6:
        x_[3] = x_[4] = 0.0;
        slide_stops();
        break;
      case 8:
        enter(Kind::flight);  // the base leaves the ground flat, sliding (the landing: rim_landing, flat below 1e-3 alpha)
        break;
      default:
        break;
    }
    row();
  }

  /// On the rim (stick, slip) the contact holds only at the acceleration level (a_p . z = 0), so the lowest point's
  /// height and its rate drift with the integration error (issue 29's invariant found 1.2e-6 m after 5 s of rolling
  /// at rel_tol 1e-8). Where the height leaves 0 by more than kProject of the size, the state is projected back onto
  /// the constraint (Hairer, Lubich & Wanner 2006, Geometric Numerical Integration, sec. IV.4, projection methods):
  /// c lowered or raised by the height, v_z less the contact's normal velocity; the integrator restarts there.
  void project_onto_ground() {
    const Rim r = rim(x_, u_);
    const double low = x_[2] + r.rho[2];  // the contact's point (continued past the upright on the step's side)
    if (std::abs(low) <= kProject * size_) return;
    x_[2] -= low;
    x_[5] -= r.vp[2];
    restart_ = true;
  }

  /// The backstops of a slip that takes kSlowSteps steps in one sample interval (rigid3d_contact.cpp's
  /// hold_slow_slips): slower than kSlipStart p size (a slip spiralling in to rest, whose stop the event along the
  /// step's direction does not see), it is stopped by the sticking impulse and held sticking; within kNearFlat alpha of
  /// the upright (the contact running round the rim faster than the slip resolves, u' ~ w / theta) the base lands flat.
  /// Both counted in painleve_events (docs/method.md: stated approximations).
  bool slow_slip() {
    const Rim r = rim(x_, u_);
    // kSlowHold eps, not eps: the regularised direction (slip_direction) is singular where v_p,h = -e s_0, |v_p,h| =
    // e <= eps; a fresh slip that runs against s_0 is caught there, its direction flipping on each step (the sweep's
    // one EventLimitError: 0.3 x 0.9 m, mu 0.8, hovering at 1.001 eps), so the hold covers speeds up to 2 eps
    if (hnorm(r.vp) < kSlowHold * kSlipStart * p_ref_ * size_) {
      ++out_.summary.painleve_events;
      stick_impulse(r);
      enter(Kind::stick);
      return true;
    }
    if (r.sin_tilt < std::sin(kNearFlat * alpha_)) {
      ++out_.summary.painleve_events;
      flat_landing();
      row();
      return true;
    }
    return false;
  }

  /// The flat phase's backstop (rigid3d_contact.cpp's flat floor, issue 29): a flat slide that takes kSlowSteps steps
  /// in one sample interval slower than kSlipStart p size has stopped (its direction, v / |v| in the friction force,
  /// turns on the time scale |v| / |a| and its stop event, the speed along the step's direction -> 0, is never
  /// crossed: the sweep's 12 runs of mu h < R with g + a_z reaching 0 at 1 g, stepping 1e-11 s at 1e-11 m/s); then
  /// rest or a slide from rest (slide_stops). Counted in painleve_events.
  bool slow_flat_slide() {
    if (!(std::hypot(x_[3], x_[4]) < kSlowHold * kSlipStart * p_ref_ * size_)) return false;
    ++out_.summary.painleve_events;
    x_[3] = x_[4] = 0.0;
    slide_stops();
    row();
    return true;
  }

  void slide_stops() {
    const Vec3 a = -1.0 * forcing_.f(t_);
    const double ah = std::hypot(a[0], a[1]);
    if (ah <= mu_s_ * a[2]) return enter(Kind::rest);
    slip_dir_ = {-a[0] / ah, -a[1] / ah, 0.0};
    fresh_ = true;
    enter(Kind::flat_slip);
  }

  /// A step from flat in which the body never rose: flat and at rest at the step's end (rigid3d_disc.cpp's rule).
  void no_lift() {
    out_.summary.energy_lost_j_per_kg += std::max(0.0, energy(x_));
    set_flat(0.0);
    // all of the motion stopped, the rotation too (issue 29's invariant: a rate left here made the next uplift start
    // its rim point moving down, w x rho, 2.5 mm/s into the ground in the one-component comparison)
    for (const std::size_t k : {3U, 4U, 5U, 10U, 11U, 12U}) x_[k] = 0.0;
    enter(Kind::rest);
  }

  void fall() {
    fallen_ = true;
    done_ = true;
    auto& s = out_.summary;
    const Vec3 a = axis(x_);
    s.overturned = true;
    s.overturn_time_s = t_;
    s.overturn_azimuth_deg = azimuth(a);
    s.max_tilt_rad = 0.5 * M_PI;  // the fall: 90 degrees (the event is 1e-6 rad short of it)
    s.max_tilt_time_s = t_;
    s.max_tilt_azimuth_deg = azimuth(a);
    close_mode();
    s.modes.push_back({t_, Rigid3DMode::fallen, -1, -1});
  }

  /// The body turned flat about the horizontal axis a x z, its base's centre kept (a landing); c's height h.
  void set_flat(double) {
    const Vec3 a = axis(x_);
    const Vec3 o = centre() - h_ * a;
    const Vec3 nrm = cross(a, kUp);
    const double sn = norm(nrm);
    if (sn > 0.0) {
      const Quaternion rot = axis_angle((1.0 / sn) * nrm, std::atan2(sn, a[2]));
      const Quaternion q = normalized(qmul(rot, quat(x_)));
      for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = q[k];
    } else {
      const Quaternion q = normalized(quat(x_));
      for (std::size_t k = 0; k < 4; ++k) x_[6 + k] = q[k];
    }
    x_[0] = o[0];
    x_[1] = o[1];
    x_[2] = h_;
  }

  [[nodiscard]] double kinetic(const SX& x) const {
    const Vec3 v{x[3], x[4], x[5]}, w = omega(x);
    return 0.5 * dot(v, v) + 0.5 * dot(w, Jmul(axis(x), w));
  }
  [[nodiscard]] double energy(const SX& x) const { return kinetic(x) + g_ * (x[2] - h_); }

  /// The base lands flat (from the rim or from flight): Housner's law about the new rim point (rigid3d_disc.cpp's
  /// impact) where its impulse is in the friction cone, else the flat outcome (header).
  void flat_landing() {
    auto& s = out_.summary;
    ++s.impacts;
    const double e_before = energy(x_);
    const double ke_before = kinetic(x_);
    const Vec3 w = omega(x_);
    const Vec3 v{x_[3], x_[4], x_[5]};
    set_flat(0.0);
    // the new contact: the rim point with the largest downward velocity, -(z x w_h) (rigid3d_disc.cpp)
    Vec3 zw = cross(kUp, hpart(w));
    const double nzw = norm(zw);
    const Vec3 un = nzw > 0.0 ? (-1.0 / nzw) * zw : -1.0 * u_;
    const Vec3 tn = cross(kUp, un);
    const Vec3 r_new = h_ * kUp - R_ * un;  // c - p'
    const Vec3 vc_rel = v;                  // c's velocity before
    // angular momentum about p' (moving with the ground): J w + r' x v
    const Vec3 L = Jmul(kUp, w) + cross(r_new, vc_rel);
    const auto Mp = [&](const Vec3& u) { return Jmul(kUp, u) + dot(r_new, r_new) * u - dot(r_new, u) * r_new; };
    const double m11 = dot(tn, Mp(tn)), m12 = dot(tn, Mp(kUp)), m22 = dot(kUp, Mp(kUp));
    const double l1 = dot(tn, L), l2 = dot(kUp, L);
    const auto [wt, wz, ke_after] = r3d::flat_landing(m11, m12, m22, l1, l2, ke_before, opt_);
    const Vec3 w_after = wt * tn + wz * kUp;
    const Vec3 v_after = cross(w_after, r_new);
    const Vec3 P = v_after - v;
    const double lift_energy = g_ * (size_ - h_);
    const bool rocks = wt > 0.0 && ke_after >= opt_.rest_energy_fraction * lift_energy;
    if (rocks && P[2] >= 0.0 && hnorm(P) <= mu_s_ * P[2]) {
      for (std::size_t k = 0; k < 3; ++k) {
        x_[3 + k] = v_after[k];
        x_[10 + k] = w_after[k];
      }
      u_ = un;
      s.energy_lost_j_per_kg += e_before - energy(x_);
      landing_armed_ = false;
      decide_rim();
      return;
    }
    // the flat outcome: vertical and tilting motion stopped; the horizontal one by a Coulomb impulse
    const double vz = std::abs(v[2]);
    Vec3 vh = hpart(v);
    const double sp = hnorm(vh);
    if (sp <= mu_s_ * vz || !rocks) {
      vh = {};
    } else {
      vh = ((sp - mu_k_ * vz) / sp) * vh;
    }
    for (std::size_t k = 0; k < 3; ++k) {
      x_[3 + k] = vh[k];
      x_[10 + k] = 0.0;
    }
    s.energy_lost_j_per_kg += e_before - energy(x_);
    if (hnorm(vh) > 0.0) {
      slip_dir_ = (1.0 / hnorm(vh)) * vh;
      fresh_ = false;
      enter(Kind::flat_slip);
    } else {
      enter(Kind::rest);
    }
  }

  /// A rim point lands from flight (header): plastic, a Coulomb impulse.
  void rim_landing() {
    auto& s = out_.summary;
    const Rim r = rim(x_, u_);
    if (r.sin_tilt < std::sin(kFlatTilt * alpha_)) return flat_landing();
    ++s.impacts;
    rim_impulse(r);
    decide_rim();
  }

  /// The landing impulse at the rim point of r (rim_landing's law, header): P_z from v_p,z+ = 0.
  void rim_impulse(const Rim& r) {
    auto& s = out_.summary;
    const double e_before = energy(x_);
    const Ab ab = contact_problem(x_, r, {});
    Vec3 P = solve(ab.W, -1.0 * r.vp);
    if (!(P[2] >= 0.0 && hnorm(P) <= mu_s_ * P[2])) {
      const double sp = hnorm(r.vp);
      const Vec3 sd = sp > 0.0 ? (1.0 / sp) * hpart(r.vp) : (-1.0 / std::max(hnorm(P), 1e-300)) * hpart(P);
      const Vec3 dir{-mu_k_ * sd[0], -mu_k_ * sd[1], 1.0};
      const double wz = dot(ab.W[2], dir);
      if (wz > 1e-12) P = (-r.vp[2] / wz) * dir;  // else (Painleve at impact level): the stick impulse
    }
    apply_impulse(r, P);
    s.energy_lost_j_per_kg += std::max(0.0, e_before - energy(x_));
  }

  // ------------------------------------------------------------------------------------------------------------
  // Summary and history

  void track(double t, const SX& x) {
    // (not in a step from flat before the body has risen: there the step's side may run past the upright, which
    // no_lift resolves by setting the base flat at the step's end; row() checks that state)
    if (landing_armed_) check_above_ground(t, x);
    const Vec3 a = axis(x);
    const double tilt = std::atan2(hnorm(a), a[2]);
    auto& s = out_.summary;
    if (tilt > s.max_tilt_rad) {
      s.max_tilt_rad = tilt;
      s.max_tilt_time_s = t;
      s.max_tilt_azimuth_deg = azimuth(a);
    }
    if (tilt >= alpha_ && !s.exceeded_limit_time_s) s.exceeded_limit_time_s = t;
    // max_slide_m: how far the contact has slipped from where it started (rolling without slip moves no base point
    // on the ground: the polygon engine's "a vertex on the ground, its own displacement" for the rim)
    s.max_slide_m = std::max(s.max_slide_m, std::hypot(x[15], x[16]));
  }

  /// The invariant of issue 29: the rim's lowest point never more than kBelowGround of the size below the ground (on
  /// the rim it is held at 0 to the constraint's drift, in flight the landing event stops it at 0). A violation is a
  /// defect of the engine: an internal error, never a silent answer. Flat (rest, sliding) the base is set on the
  /// ground exactly.
  void check_above_ground(double t, const SX& x) const {
    if (kind_ == Kind::rest || kind_ == Kind::flat_slip) return;
    const Rim r = rim(x, u_);
    const double low = x[2] + std::min(r.rho[2], -h_ * r.a[2] - R_ * r.sin_tilt);
    if (!(low >= -kBelowGround * size_)) {
      throw SolverError(fmt::format(
          "rock3d_cylinder: internal error: the rim's lowest point {:.3g} m below the ground at {} s (more than {} of "
          "the body's size; mode {}, sin tilt {:.3g}, contact side {:.3g}): please report it",
          -low, t, kBelowGround, static_cast<int>(kind_), r.sin_tilt, x[2] + r.rho[2]));
    }
  }

  void row() {
    check_above_ground(t_, x_);
    if (!opt_.record_history) return;
    auto& h = out_.history;
    const Rigid3DMode m = mode_name();
    const Quaternion q = normalized(quat(x_));
    const Vec3 origin = centre() - h_ * axis(x_);
    if (!h.time_s.empty() && h.time_s.back() == t_) {
      h.position_m.back() = origin;
      h.orientation.back() = q;
      h.angular_velocity_rad_s.back() = omega(x_);
      h.energy_j_per_kg.back() = energy(x_);
      h.mode.back() = m;
      return;
    }
    h.time_s.push_back(t_);
    h.position_m.push_back(origin);
    h.orientation.push_back(q);
    h.angular_velocity_rad_s.push_back(omega(x_));
    h.energy_j_per_kg.push_back(energy(x_));
    h.mode.push_back(m);
  }

  static constexpr int kParts = 4;
  static constexpr int kMaxEvents = 10'000;
  static constexpr double kSlipStart = 1e-6;
  static constexpr double kSlipZero = 1e-9;
  static constexpr double kFreshEnd = 1e3;
  static constexpr double kChatter_s = 1e-6;
  static constexpr int kSlowSteps = 1'000;
  static constexpr double kProject = 1e-9;       // the rim's drift from the ground projected away (project_onto_ground)
  static constexpr double kSlowHold = 2.0;      // the slow-slip backstop's speed, in eps (slow_slip)
  static constexpr double kBelowGround = 1e-6;  // the invariant: the rim never lower than this times the size
  static constexpr double kNearFlat = 0.02;

  const InputGrid& grid_;
  std::span<const double> ax_, ay_;
  std::vector<double> gravity_;
  double R_, h_, Ja_, Jt_;
  const Rigid3DOptions& opt_;
  Dp5<kN, Rhs> dp_;
  DiscStart start_;
  double g_ = 0.0, mu_s_ = 0.0, mu_k_ = 0.0, size_ = 0.0, alpha_ = 0.0, p_ref_ = 0.0;
  Forcing forcing_{};
  Rigid3DResult out_;
  SX x_{};
  Vec3 u_{1.0, 0.0, 0.0}, slip_dir_{1.0, 0.0, 0.0}, base0_{};
  double t_ = 0.0, mode_since_ = 0.0, slip_start_ = -1.0, gap_ref_ = 0.0;
  Kind kind_ = Kind::stick;
  bool restart_ = true, done_ = false, fallen_ = false, fresh_ = false, landing_armed_ = true;
  std::size_t steps_ = 0;
};

void Rhs::operator()(const SX& x, double t, SX& dx) const { e->rhs(x, t, dx); }

}  // namespace

Rigid3DResult rock3d_disc_contact(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                  const CylinderBody3D& body, const Rigid3DOptions& options, const DiscStart& start) {
  const std::array<const GroundMotion*, 3> components{&x, y, z};
  const InputGrid grid(components);
  std::vector<double> gravity = effective_gravity(grid, 2, options.g_m_s2);
  DiscEngine engine(grid, std::move(gravity), body, options, start);
  return engine.run();
}

}  // namespace topple::detail
