// A cylinder rocking and rolling on its rim in three dimensions (rigid3d_disc.hpp; docs/method.md, "A circular base:
// rolling on the rim").
#include "topple/solvers/rigid3d_disc.hpp"

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

#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/numerics/dp5.hpp"
#include "topple/numerics/event_root.hpp"
#include "rigid3d_disc_contact.hpp"
#include "rigid3d_math.hpp"
#include "rigid3d_slide.hpp"

namespace topple {
namespace {

using V = Vec3;
constexpr std::size_t kN = 10;  // q (4), w (3, ground frame), x_c (3)
using State = std::array<double, kN>;
// Below this sin(tilt) the contact's direction is taken from the last step's end (or the uplift, or the impact): the
// direction of z_perp there is rounding noise (|q| = 1 to 1e-16).
constexpr double kDirectionFloor = 1e-12;
// A tilt minimum below kFlatTilt times alpha with a sideways rate above kWhirlRate_rad_s is a flat landing (header).
constexpr double kFlatTilt = 1e-3;
constexpr double kWhirlRate_rad_s = 1e-8;
// A step from flat shorter than this (times 1/p) in which the body never rises above the ground ends at rest: a lift
// shorter than it is not resolved (finish_step).
constexpr double kMinLiftStep = 1e-7;

V add(V a, V b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
V sub(V a, V b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
V mul(V a, double k) { return {a[0] * k, a[1] * k, a[2] * k}; }
double dot(V a, V b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
V cross(V a, V b) { return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}; }
double norm(V a) { return std::sqrt(dot(a, a)); }
constexpr V kZ{0.0, 0.0, 1.0};

Quaternion quat(const State& y) { return {y[0], y[1], y[2], y[3]}; }
V omega(const State& y) { return {y[4], y[5], y[6]}; }
V position(const State& y) { return {y[7], y[8], y[9]}; }

/// The body's axis R(q) e_z for any q != 0 (the third column of the rotation of q / |q|: one division, no root).
V axis(const Quaternion& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double inv = 1.0 / (w * w + x * x + y * y + z * z);
  return {2.0 * (x * z + w * y) * inv, 2.0 * (y * z - w * x) * inv, (w * w - x * x - y * y + z * z) * inv};
}
Quaternion qmul(Quaternion a, Quaternion b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
Quaternion normalised(Quaternion q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& c : q) c /= n;
  return q;
}
/// Solves the symmetric 3x3 system M x = b (Cramer; M is an inertia tensor, positive definite).
V solve3(const std::array<V, 3>& M, V b) {
  const V c0{M[0][0], M[1][0], M[2][0]}, c1{M[0][1], M[1][1], M[2][1]}, c2{M[0][2], M[1][2], M[2][2]};
  const V c12 = cross(c1, c2);
  const double inv = 1.0 / dot(c0, c12);
  return {dot(b, c12) * inv, dot(c0, cross(b, c2)) * inv, dot(c0, cross(c1, b)) * inv};
}
double azimuth_deg(V d) {  // clockwise from north of a plan direction
  double az = std::atan2(d[0], d[1]) * 180.0 / M_PI;
  if (az < 0.0) az += 360.0;
  return az;
}

struct Geo {
  double R, h, Ja, Jt, alpha, lift_energy;
  [[nodiscard]] V JG(V a, V w) const { return add(mul(w, Jt), mul(a, (Ja - Jt) * dot(a, w))); }
  /// M_p = J_G + |r|^2 1 - r r^T
  [[nodiscard]] std::array<V, 3> Mp(V a, V r) const {
    std::array<V, 3> M{};
    const double rr = dot(r, r);
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        M[i][j] = (Ja - Jt) * a[i] * a[j] - r[i] * r[j] + (i == j ? Jt + rr : 0.0);
      }
    }
    return M;
  }
  [[nodiscard]] V Mp_times(V a, V r, V w) const {
    return add(JG(a, w), sub(mul(w, dot(r, r)), mul(r, dot(r, w))));
  }
};

/// z - (a . z) a = a x (z x a), written so that each component keeps its relative precision at small tilts (the
/// z component a_x^2 + a_y^2 rather than 1 - a_z^2).
V z_perp(V a) { return {-a[2] * a[0], -a[2] * a[1], a[0] * a[0] + a[1] * a[1]}; }
/// Its time derivative for a' = ad.
V z_perp_rate(V a, V ad) {
  return {-ad[2] * a[0] - a[2] * ad[0], -ad[2] * a[1] - a[2] * ad[1], 2.0 * (a[0] * ad[0] + a[1] * ad[1])};
}

/// The contact geometry of a state: axis a, contact direction u (from the base's centre), sin(theta), r = c - p.
/// d = -z_perp / sin(theta) is the lowest point's direction. Within a step the rim equations are continued past the
/// upright on the step's side (as the planar engine continues its pivot's equation past theta = 0): where d points
/// away from the step's starting contact u0 (d . u0 < 0: the lowest point is now on the other side), u = -d, the
/// point of the rim opposite the lowest one. In one vertical plane that is the rim point fixed in the body that was
/// the contact, (cos theta, 0, -sin theta) on both sides of the upright: the planar engine's continued pivot, smooth
/// through theta = 0, so a step may run past the landing, which is then found on its dense output. Out of the plane
/// (a sideways rate near the upright) u jumps where d . u0 changes sign; the landing is found there (finish_step)
/// and the step's error control sees the jump beyond it.
struct Contact {
  V a, u, r, d;
  double sin_tilt;
  double ex = 0.0, ey = 0.0;  // e = a_h / sin(theta) (tilted only)
  double inv_sin_tilt = 0.0;  // 1 / sin(theta) (tilted only)
  bool reflected = false;
};
Contact contact_of(const Geo& g, const Quaternion& q, V fallback_u, const V* u0 = nullptr) {
  Contact c;
  // the axis as axis(q), its horizontal length and direction from the unnormalised column (two independent chains)
  const double qw = q[0], qx = q[1], qy = q[2], qz = q[3];
  const double Ax = 2.0 * (qx * qz + qw * qy), Ay = 2.0 * (qy * qz - qw * qx);
  const double n2 = qw * qw + qx * qx + qy * qy + qz * qz;
  const double inv_n2 = 1.0 / n2;
  const double horizontal = std::sqrt(Ax * Ax + Ay * Ay);
  c.a = {Ax * inv_n2, Ay * inv_n2, (qw * qw - qx * qx - qy * qy + qz * qz) * inv_n2};
  // |z_perp| = |a_h| |a| = sin(theta) and d = -z_perp / sin(theta) = a_z e - sin(theta) z, e = a_h / |a_h|
  c.sin_tilt = horizontal * inv_n2;
  if (c.sin_tilt > kDirectionFloor) {
    const double inv = 1.0 / horizontal;
    const double ex = Ax * inv, ey = Ay * inv;
    c.inv_sin_tilt = inv * n2;
    c.ex = ex;
    c.ey = ey;
    c.d = {c.a[2] * ex, c.a[2] * ey, -c.sin_tilt};
    c.u = c.d;
    if (u0 != nullptr && dot(c.d, *u0) < 0.0) {
      c.u = mul(c.d, -1.0);
      c.reflected = true;
    }
  } else {
    // flat: the contact chosen at the uplift or the impact, or (a landing inside a step) the step's starting contact
    // brought to the ground plane: at the upright the rim point that was the contact is horizontal (its tilted
    // direction would put r off by R sin(theta0), a relative error theta0 in the impact's velocity)
    const double hn = std::hypot(fallback_u[0], fallback_u[1]);
    c.u = hn > 0.0 ? V{fallback_u[0] / hn, fallback_u[1] / hn, 0.0} : fallback_u;
    c.d = c.u;
  }
  c.r = sub(mul(c.a, g.h), mul(c.u, g.R));
  return c;
}

/// Kinetic energy (relative to the ground) plus potential, per unit mass, on the rim.
double energy(const Geo& g, const State& y, V fallback_u, double grav) {
  const Contact c = contact_of(g, quat(y), fallback_u);
  const V w = omega(y);
  return 0.5 * dot(w, g.Mp_times(c.a, c.r, w)) + grav * (c.r[2] - g.h);
}

class Engine {
 public:
  Engine(const InputGrid& grid, std::vector<double> gravity, const Geo& geo, const Rigid3DOptions& opt)
      : grid_(grid),
        gravity_(std::move(gravity)),
        g_(geo),
        opt_(opt),
        p_(std::sqrt(opt.g_m_s2 / std::hypot(geo.R, geo.h))) {
    if (opt.mu_s) mu_s_ = *opt.mu_s;
  }

  Rigid3DResult run(const std::optional<CylinderInitialState>& initial) {
    Rigid3DSummary& s = res_.summary;
    y_ = State{1, 0, 0, 0, 0, 0, 0, 0, 0, g_.h};
    mode_ = Rigid3DMode::rest;
    const double t0 = grid_.time_s(0);
    if (initial) {
      const Quaternion q = normalised(initial->orientation);
      const V a = axis(q);
      if (!(a[2] > 0.0 && a[2] < 1.0)) {
        throw parameter_error("initial", "the initial tilt must be strictly between 0 and 90 degrees");
      }
      const V w = initial->angular_velocity_rad_s;
      const Contact c = contact_of(g_, q, kZ);
      y_ = State{q[0], q[1], q[2], q[3], w[0], w[1], w[2], 0.0, 0.0, c.r[2]};
      y_[7] = c.r[0];  // the contact point at the ground frame's origin
      y_[8] = c.r[1];
      u_ = c.u;
      mode_ = Rigid3DMode::rocking;
    }
    s.modes.push_back({t0, mode_, -1, -1});
    record(t0);
    const std::size_t n = grid_.size();
    double t_end = t0;
    // The rest scan (the planar engine's, rocking.cpp): with no vertical component the uplift test at rest is one
    // comparison per sample, |a_h|^2 <= (g R / h)^2: |a_h|^2 is convex on each linear piece, so both ends below the
    // level keep the whole interval below it. The first sample is left to the general path (a jump from still ground).
    const bool fast_rest = gravity_.empty();
    const double level2 = std::pow(opt_.g_m_s2 * g_.R / g_.h, 2);
    const std::span<const double> ax = grid_.accel_m_s2(0);
    const std::span<const double> ay = grid_.has(1) ? grid_.accel_m_s2(1) : std::span<const double>{};
    for (std::size_t i = 0; i + 1 < n && !done(); ++i) {
      if (fast_rest && mode_ == Rigid3DMode::rest && i > 0) {
        if (ay.empty()) {
          while (i + 1 < n && ax[i + 1] * ax[i + 1] <= level2) {
            ++i;
            if (opt_.record_history) record(grid_.time_s(i));
          }
        } else {
          while (i + 1 < n && ax[i + 1] * ax[i + 1] + ay[i + 1] * ay[i + 1] <= level2) {
            ++i;
            if (opt_.record_history) record(grid_.time_s(i));
          }
        }
        t_end = grid_.time_s(i);
        if (i + 1 >= n) break;
      }
      const double ta = grid_.time_s(i), tb = grid_.time_s(i + 1);
      if (tb > ta) advance(ta, tb, accel(i), accel(i + 1));
      t_end = tb;
      if (!done() && opt_.record_history) record(tb);
    }
    // Run-out on still ground: the forcing is constant, so steps need not end on a grid (one interval up to the cap,
    // the error control sets the steps; the planar engine's run-out). History rows continue the record's spacing from
    // each step's dense output (finish_step), so a run with a history takes the same steps as one without.
    const double dt = grid_.dt_s() > 0.0 ? grid_.dt_s() : 0.01;
    const std::array<double, 3> still{0.0, 0.0, opt_.g_m_s2};
    const double t_stop = t_end + opt_.max_run_out_s;
    double t = t_end;
    if (!done() && mode_ != Rigid3DMode::rest && t_stop > t_end) {
      rows_dt_ = dt;
      rows_t0_ = t_end;
      rows_next_ = 1;
      fsal_valid_ = false;  // the ground jumps to still
      advance(t_end, t_stop, still, still);
      rows_dt_ = 0.0;
      t = done() || mode_ != Rigid3DMode::rest ? t_stop : s.modes.back().time_s;
      if (!done() && mode_ != Rigid3DMode::rest && opt_.record_history &&
          (res_.history.time_s.empty() || res_.history.time_s.back() < t)) {
        record(t);
      }
    }
    if (!done() && mode_ != Rigid3DMode::rest) {
      // as the contact engine (rigid3d_disc_contact.cpp): a run-out that ends with the body still on its rim says so
      // (issue 29's sweep: a cylinder wobbling on its rim without a landing, which the no-slip rim conserves, ended
      // "rocking" at the cap without a word)
      s.warnings.push_back(fmt::format("the body was still moving {} s after the record ended (max_run_out_s)",
                                       opt_.max_run_out_s));
    }
    s.end_time_s = stop_time_ ? *stop_time_ : done() ? *s.overturn_time_s : t;
    s.end_mode = mode_;
    s.steps = steps_;
    s.max_tilt_over_limit = s.max_tilt_rad / g_.alpha;
    return std::move(res_);
  }

 private:
  /// (a_x, a_y, g + a_z) at grid point i.
  [[nodiscard]] std::array<double, 3> accel(std::size_t i) const {
    const auto comp = [&](std::size_t c) { return grid_.has(c) ? grid_.accel_m_s2(c)[i] : 0.0; };
    return {comp(0), comp(1), gravity_.empty() ? opt_.g_m_s2 : gravity_[i]};
  }
  [[nodiscard]] bool done() const { return mode_ == Rigid3DMode::fallen || stop_time_.has_value(); }

  void record(double t) { record_state(t, y_); }
  void record_state(double t, const State& y) {
    if (!opt_.record_history) return;
    Rigid3DHistory& h = res_.history;
    const Quaternion q = normalised(quat(y));
    const V a = axis(q);
    h.time_s.push_back(t);
    h.position_m.push_back(sub(position(y), mul(a, g_.h)));
    h.orientation.push_back(q);
    h.angular_velocity_rad_s.push_back(omega(y));
    h.energy_j_per_kg.push_back(mode_ == Rigid3DMode::rest ? 0.0 : energy(g_, y, u_, opt_.g_m_s2));
    h.mode.push_back(mode_);
  }

  /// The rim's rates of a state: the contact, w' and r' (header).
  struct RimRates {
    Contact c;
    V wd, rd;
  };
  [[nodiscard]] RimRates rim_rates(const State& y, const std::array<double, 3>& acc) const {
    const Quaternion q = quat(y);
    const V w = omega(y);
    const Contact c = contact_of(g_, q, u_, &u_);  // u_: the step's starting contact (continued past the upright)
    const V ad = cross(w, c.a);
    // flat (first stage after an uplift or an impact): the contact is the rim point fixed in the body, u' = w x u
    // (the rocking limit; a sideways rate there would make u' infinite)
    V ud = cross(w, c.u);
    if (c.sin_tilt > kDirectionFloor) {
      // d = a_z e - sin(theta) z with e = a_h / sin(theta): d' = a_z' e + a_z e' - (e . a_h') z, e' the part of a_h'
      // normal to e over sin(theta), ((e x a_h') . z / sin(theta)) (z x e) (exactly 0 in one vertical plane)
      const double ex = c.ex, ey = c.ey;
      const double turn = (ex * ad[1] - ey * ad[0]) * c.inv_sin_tilt;
      ud = {ad[2] * ex - c.a[2] * turn * ey, ad[2] * ey + c.a[2] * turn * ex, -(ex * ad[0] + ey * ad[1])};
      if (c.reflected) ud = mul(ud, -1.0);  // u = -d past the upright
    }
    const V rd = sub(mul(ad, g_.h), mul(ud, g_.R));
    const V f{-acc[0], -acc[1], -acc[2]};
    const V rhs_m = sub(sub(cross(c.r, f), cross(w, g_.JG(c.a, w))), cross(c.r, cross(w, rd)));
    return {c, solve3(g_.Mp(c.a, c.r), rhs_m), rd};
  }

  // The equations of motion on the rim (header), f = (-a_x, -a_y, -(g + a_z)): rim_rates' w', with q' and the
  // centre of mass's velocity w x r.
  [[nodiscard]] State rhs(const State& y, const std::array<double, 3>& acc) const {
    const Quaternion q = quat(y);
    const V w = omega(y);
    const RimRates k = rim_rates(y, acc);
    const Quaternion qd = qmul({0.0, w[0], w[1], w[2]}, q);
    const V vc = cross(w, k.c.r);
    return {0.5 * qd[0], 0.5 * qd[1], 0.5 * qd[2], 0.5 * qd[3], k.wd[0], k.wd[1], k.wd[2], vc[0], vc[1], vc[2]};
  }

  /// The contact force per unit mass on the rim (friction given): Newton, F = a_c - f with a_c = d(w x r)/dt =
  /// w' x r + w x r' (header); its margin min(N, mu_s N - |F_t|) / (g + a_z): > 0 while the rolling contact holds.
  [[nodiscard]] V contact_force(const State& y, const std::array<double, 3>& acc) const {
    const RimRates k = rim_rates(y, acc);
    const V w = omega(y);
    const V ac = add(cross(k.wd, k.c.r), cross(w, k.rd));
    return {ac[0] + acc[0], ac[1] + acc[1], ac[2] + acc[2]};
  }
  [[nodiscard]] double contact_margin(const State& y, const std::array<double, 3>& acc) const {
    const V F = contact_force(y, acc);
    return std::min(F[2], mu_s_ * F[2] - std::hypot(F[0], F[1])) / acc[2];
  }

  /// The sample interval [ta, tb] with the input linear between acc_a and acc_b.
  void advance(double ta, double tb, std::array<double, 3> acc_a, std::array<double, 3> acc_b) {
    const auto acc_at = [&](double t) {
      const double s = (t - ta) / (tb - ta);
      return std::array<double, 3>{acc_a[0] + s * (acc_b[0] - acc_a[0]), acc_a[1] + s * (acc_b[1] - acc_a[1]),
                                   acc_a[2] + s * (acc_b[2] - acc_a[2])};
    };
    double t = ta;
    while (t < tb && !done()) {
      if (mode_ == Rigid3DMode::rest) {
        // onset: |a_h|^2 - ((g + a_z) R / h)^2 crosses zero upward (header)
        const double k = g_.R / g_.h;
        const auto f = [&](double tt) {
          const auto a = acc_at(tt);
          return a[0] * a[0] + a[1] * a[1] - (a[2] * k) * (a[2] * k);
        };
        // friction given: g + a_z reaching 0 at rest is flight, the contact engine's (rigid3d_disc_contact.cpp); the
        // uplift is looked for before it
        double t_lim = tb;
        bool flies = false;
        if (mu_s_ >= 0.0) {
          const auto G = [&](double tt) { return acc_at(tt)[2]; };
          const double ga = G(t), gb = G(tb);
          if (!(ga > 0.0)) return contact_fails(t, acc_at(t));
          if (!(gb > 0.0)) {
            t_lim = detail::find_root(G, t, tb, ga, gb);
            flies = true;
          }
        }
        const double fa = f(t), fb = f(t_lim);
        if (fa > 0.0) {
          uplift(t, acc_at(t));
          continue;
        }
        if (!(fb > 0.0)) {
          if (flies) contact_fails(t_lim, acc_at(t_lim));
          return;
        }
        const double tu = detail::find_root(f, t, t_lim, fa, fb);
        // the uplift instant: the root (the planar engine's too), nudged up by a few ulps to where the threshold is
        // met when rounding left it just below
        double tr = tu;
        for (int n = 0; n < 16 && !(f(tr) > 0.0) && tr < tb; ++n) tr = std::nextafter(tr, tb);
        if (!std::isfinite(tr)) tr = tb;
        t = tr;
        uplift(t, acc_at(t));
        continue;
      }
      t = step(t, tb, acc_at);
    }
  }

  void uplift(double t, std::array<double, 3> acc) {
    Rigid3DSummary& s = res_.summary;
    const double ah = std::hypot(acc[0], acc[1]);
    const V u_g{-acc[0] / ah, -acc[1] / ah, 0.0};  // toward -a_h (the base is flat: body plane = ground plane)
    u_ = u_g;
    mode_ = Rigid3DMode::rocking;
    ++s.uplifts;
    if (!s.uplift_time_s) s.uplift_time_s = t;
    s.modes.push_back({t, mode_, -1, -1});
    h_try_ = 0.0;
    fsal_valid_ = false;
    record(t);
  }

  /// One Dormand-Prince step from t toward at most tb (events inside); returns the new time.
  template <class Acc>
  double step(double t, double tb, const Acc& acc_at) {
    using namespace detail::dp5;
    if (h_try_ <= 0.0) h_try_ = std::min(tb - t, 1e-3);
    double h = std::min(h_try_, tb - t);
    if (tb - t - h < 1e-12 * std::max(1.0, std::abs(tb))) h = tb - t;
    const double p = p_;
    const std::array<double, kN> scale{g_.alpha, g_.alpha, g_.alpha, g_.alpha, p * g_.alpha, p * g_.alpha,
                                       p * g_.alpha, g_.alpha * g_.h, g_.alpha * g_.h, g_.alpha * g_.h};
    while (true) {
      if (++steps_ > opt_.max_steps) {
        throw StepLimitError(fmt::format("rock3d_cylinder: more than {} integrator steps", opt_.max_steps));
      }
      const State& y0 = y_;
      const auto stage = [&](const std::array<std::pair<double, const State*>, 6>& terms, std::size_t m) {
        State y = y0;
        for (std::size_t j = 0; j < m; ++j) {
          for (std::size_t i = 0; i < kN; ++i) y[i] += h * terms[j].first * (*terms[j].second)[i];
        }
        return y;
      };
      // first same as last: the previous accepted step's k7 is this step's k1 (same state, same time, same input)
      // (and with the same input there: a jump between pieces, or the run-out's still ground, changes it)
      const std::array<double, 3> acc0 = acc_at(t);
      if (!fsal_valid_ || acc0 != fsal_acc_) {
        k1_ = rhs(y0, acc0);
        fsal_valid_ = true;
      }
      const State& k1 = k1_;
      const State k2 = rhs(stage({{{b21, &k1}}}, 1), acc_at(t + a2 * h));
      const State k3 = rhs(stage({{{b31, &k1}, {b32, &k2}}}, 2), acc_at(t + a3 * h));
      const State k4 = rhs(stage({{{b41, &k1}, {b42, &k2}, {b43, &k3}}}, 3), acc_at(t + a4 * h));
      const State k5 = rhs(stage({{{b51, &k1}, {b52, &k2}, {b53, &k3}, {b54, &k4}}}, 4), acc_at(t + a5 * h));
      const State k6 =
          rhs(stage({{{b61, &k1}, {b62, &k2}, {b63, &k3}, {b64, &k4}, {b65, &k5}}}, 5), acc_at(t + h));
      const State y1 = stage({{{c1, &k1}, {c3, &k3}, {c4, &k4}, {c5, &k5}, {c6, &k6}}}, 5);
      const State k7 = rhs(y1, acc_at(t + h));
      double err = 0.0;
      // q and w: x_c is a quadrature (w x r) that does not feed back, so it does not set the step
      for (std::size_t i = 0; i < 7; ++i) {
        const double e = h * (dc1 * k1[i] + dc3 * k3[i] + dc4 * k4[i] + dc5 * k5[i] + dc6 * k6[i] + dc7 * k7[i]);
        const double sc = opt_.abs_tol * scale[i] + opt_.rel_tol * std::max(std::abs(y0[i]), std::abs(y1[i]));
        err = std::max(err, std::abs(e) / sc);
      }
      if (!(err <= 1.0)) {
        if (!std::isfinite(err)) err = 1e10;
        h *= std::max(0.2, 0.9 * std::pow(err, -0.2));
        if (h < 1e-15 * std::max(1.0, std::abs(t))) {
          throw StepLimitError("rock3d_cylinder: the step size fell below the time's resolution");
        }
        continue;
      }
      h_try_ = h * std::min(5.0, std::max(0.2, 0.9 * std::pow(std::max(err, 1e-10), -0.2)));
      const std::array<const State*, 6> ks{&k1, &k3, &k4, &k5, &k6, &k7};
      const auto dense = [&](double s) {
        if (s == 0.0) return y0;  // the step's ends: exact (the events look there first)
        if (s == 1.0) return y1;
        State y = y0;
        for (std::size_t j = 0; j < 6; ++j) {
          double b = 0.0;
          for (std::size_t d = 6; d-- > 0;) b = b * s + kDense[j].c[d];
          for (std::size_t i = 0; i < kN; ++i) y[i] += h * b * (*ks[j])[i];
        }
        return y;
      };
      const std::optional<double> t_next = finish_step(t, h, y1, dense, acc_at);
      if (!t_next) {
        // a lift from flat shorter than the step's sixteenth: the step again, 16 times shorter (bounded: finish_step
        // accepts "no lift" once h is below kMinLiftStep / p)
        h /= 16.0;
        continue;
      }
      const double t_new = *t_next;
      // k7 is f(y1, t + h) of this step's input piece: valid as the next k1 only when the step ran to its end with no
      // event and the state was not changed
      if (t_new == t + h && mode_ == Rigid3DMode::rocking && y_ == y1) {
        k1_ = k7;
        fsal_acc_ = acc_at(t + h);
      } else {
        fsal_valid_ = false;
      }
      return t_new;
    }
  }

  template <class Dense, class Acc>
  std::optional<double> finish_step(double t, double h, const State& y1, const Dense& dense, const Acc& acc_at) {
    Rigid3DSummary& s = res_.summary;
    const V u0 = contact_of(g_, quat(y_), u_).u;
    // event functions of the step fraction, on the axis and the rate (the step's ends computed once)
    struct AxisRate {
      V a, w;
    };
    const AxisRate end0{axis(quat(y_)), omega(y_)}, end1{axis(quat(y1)), omega(y1)};
    const auto at = [&](double sf) {
      if (sf == 0.0) return end0;
      if (sf == 1.0) return end1;
      const State y = dense(sf);
      return AxisRate{axis(quat(y)), omega(y)};
    };
    const auto axis_z = [&](double sf) { return at(sf).a[2]; };
    const auto tilt_rate = [&](double sf) {  // d(a_z)/dt = (w x a)_z: > 0 while the tilt decreases
      const AxisRate x = at(sf);
      return cross(x.w, x.a)[2];
    };
    const auto landing = [&](double sf) { return -dot(z_perp(at(sf).a), u0); };
    const auto landing_rate = [&](double sf) {  // d/dt of landing: -z_perp' . u0, a' = w x a
      const AxisRate x = at(sf);
      return -dot(z_perp_rate(x.a, cross(x.w, x.a)), u0);
    };
    // the earliest terminal event
    double s_end = 1.0;
    int kind = 0;  // 0 none, 1 landing, 2 fall
    double s_lo = 0.0;  // a step fraction where the body is on its rim (landing > 0), from which to look for events
    double l_lo = landing(0.0);
    const double l1_end = landing(1.0);
    double l1 = l1_end;
    if (!(l_lo > 0.0)) {
      // The step starts flat (the first step after an uplift or an impact): the continued equations may rise and come
      // back within the step (a lift and return, in chatter). The first of 16 equally spaced points where the body is
      // up starts the search; none: the step is taken again 16 times shorter (the lift may be shorter than h / 16),
      // and once h p is below kMinLiftStep the lift did not happen (the ground's pull was too short or round-off sent
      // the body below): the body stays at rest at the step's end (the planar engine's rule), time advancing by h > 0.
      for (int j = 1; j <= 16 && !(l_lo > 0.0); ++j) {
        s_lo = j / 16.0;
        l_lo = j == 16 ? l1_end : landing(s_lo);
      }
      if (!(l_lo > 0.0)) {
        (void)y1;
        if (h * p_ > kMinLiftStep) return std::nullopt;  // look again with a shorter step
        return no_lift(t + h);
      }
    }
    double s_land = 1.0;
    if (l_lo > 0.0 && l1 > 0.0) {
      // The step ends on the rim. On the continued equations it may still have passed the upright and come back (a
      // landing and a rise on the far rim point inside one step): then the landing function has a minimum inside at
      // or below zero, where its rate goes from < 0 to > 0 (the planar engine's turning points of theta); the landing
      // is the root before it.
      const double sr0 = landing_rate(s_lo), sr1 = landing_rate(1.0);
      if (sr0 < 0.0 && sr1 > 0.0) {
        const double s_min = detail::find_root(landing_rate, s_lo, 1.0, sr0, sr1);
        if (std::isfinite(s_min)) {
          const double lm = landing(s_min);
          if (!(lm > 0.0)) {
            l1 = lm;
            s_land = s_min;
          }
        }
      }
    }
    if (l_lo > 0.0 && l1 > 0.0) {
      // a tilt minimum inside the step (a_z' from > 0 to < 0) with a sideways rate: a whirl, the contact runs round
      // the rim as the tilt passes a small minimum (w . u != 0; exactly 0 in planar rocking) instead of landing: the
      // base is within 2 R sin(theta) of the ground all round; below kFlatTilt alpha it counts as landed flat at the
      // minimum (docs/method.md)
      const double q0 = tilt_rate(s_lo), q1 = tilt_rate(1.0);
      if (q0 > 0.0 && q1 < 0.0) {
        const double s_min = detail::find_root(tilt_rate, s_lo, 1.0, q0, q1);
        if (std::isfinite(s_min)) {
          const State ym = dense(s_min);
          const Contact cm = contact_of(g_, quat(ym), u0);
          if (std::asin(std::min(cm.sin_tilt, 1.0)) < kFlatTilt * g_.alpha &&
              std::abs(dot(omega(ym), cm.u)) > kWhirlRate_rad_s) {
            s_end = s_min;
            kind = 1;
          }
        }
      }
    }
    if (kind == 0 && l_lo > 0.0 && l1 <= 0.0) {
      // the landing: s_lo < root <= s_land (l_lo > 0), so time advances
      s_end = detail::find_root(landing, s_lo, s_land, l_lo, l1);
      kind = 1;
    }
    const double z0 = axis_z(0.0), z1 = axis_z(s_end);
    if (z0 > 0.0 && z1 <= 0.0) {
      s_end = detail::find_root(axis_z, 0.0, s_end, z0, z1);
      kind = 2;
    }
    if (mu_s_ >= 0.0) {
      // friction given: the rolling contact holds while N > 0 and |F_t| <= mu_s N (header); the first root of the
      // margin on the dense output, looked for on 4 equal parts of the step up to its terminal event (a violation
      // that begins and ends inside one part is missed, as the polygon engine's pivot events: stated)
      const auto margin = [&](double sf) { return contact_margin(sf == 0.0 ? y_ : dense(sf), acc_at(t + sf * h)); };
      double s_prev = 0.0, m_prev = margin(0.0);
      if (!(m_prev > 0.0)) {
        s_end = 0.0;
        kind = 3;
      }
      for (int j = 1; j <= 4 && kind != 3; ++j) {
        const double sj = s_end * j / 4.0;
        const double mj = margin(sj);
        if (!(mj > 0.0)) {
          s_end = std::isfinite(mj) ? detail::find_root(margin, s_prev, sj, m_prev, mj) : sj;
          kind = 3;
        }
        s_prev = sj;
        m_prev = mj;
      }
    }
    // tilt maxima (a_z' from < 0 to > 0) and the static limit, before the terminal event
    const double r0 = tilt_rate(0.0), r1 = tilt_rate(s_end);
    const auto note_tilt = [&](double sf) {
      const V a = at(sf).a;
      // the tilt stays below 90 degrees (the fall ends the run there), where sin^2 orders it: most steps stop here
      const double sin2 = a[0] * a[0] + a[1] * a[1];
      if (sin2 < max_tilt_sin2_) return;
      const double tilt = std::atan2(std::sqrt(sin2), a[2]);
      if (tilt > s.max_tilt_rad) {
        s.max_tilt_rad = tilt;
        s.max_tilt_azimuth_deg = azimuth_deg(a);
        s.max_tilt_time_s = t + sf * h;
        max_tilt_sin2_ = std::pow(std::sin(tilt), 2) * (1.0 - 1e-12);
      }
    };
    if (r0 < 0.0 && r1 > 0.0) note_tilt(detail::find_root(tilt_rate, 0.0, s_end, r0, r1));
    note_tilt(s_end);
    if (!s.exceeded_limit_time_s) {
      const double cos_alpha = std::cos(g_.alpha);
      const auto lim = [&](double sf) { return axis_z(sf) - cos_alpha; };
      const double e0 = lim(0.0), e1 = lim(s_end);
      if (e0 > 0.0 && e1 <= 0.0) s.exceeded_limit_time_s = t + h * detail::find_root(lim, 0.0, s_end, e0, e1);
    }
    const double t_new = kind == 0 ? t + h : t + h * s_end;
    if (rows_dt_ > 0.0 && opt_.record_history) {
      // run-out history rows on the record's spacing inside this step (an event's own row is at t_new)
      for (;;) {
        const double tg = rows_t0_ + static_cast<double>(rows_next_) * rows_dt_;
        if (tg > t_new || (kind != 0 && tg == t_new)) break;
        ++rows_next_;
        if (tg > t) record_state(tg, tg == t + h ? y1 : dense((tg - t) / h));
      }
    }
    y_ = kind == 0 ? y1 : dense(s_end);
    u_ = contact_of(g_, quat(y_), u_).u;
    if (!std::isfinite(t_new)) throw StepLimitError("rock3d_cylinder: an event could not be located");
    if (kind == 2) {
      mode_ = Rigid3DMode::fallen;
      s.overturned = true;
      s.overturn_time_s = t_new;
      s.overturn_azimuth_deg = azimuth_deg(axis(quat(y_)));
      s.modes.push_back({t_new, mode_, -1, -1});
      record(t_new);
    } else if (kind == 1) {
      impact(t_new, u0);
    } else if (kind == 3) {
      contact_fails(t_new, acc_at(t_new));
    }
    (void)acc_at;
    return t_new;
  }

  /// The rolling contact needs more than Coulomb's friction or a pull (friction given): slip on the rim or flight
  /// begins at t. The run stops here and rock3d_cylinder hands it to the contact engine (rigid3d_disc_contact.cpp)
  /// from this state: c's velocity w x r (rolling), the contact direction u.
  void contact_fails(double t, const std::array<double, 3>& acc) {
    (void)acc;
    stop_time_ = t;
    const Contact c = contact_of(g_, quat(y_), u_);
    const V w = omega(y_);
    handover_ = detail::DiscStart{{t, position(y_), cross(w, c.r), normalised(quat(y_)), w}, c.u};
  }

 public:
  [[nodiscard]] const std::optional<detail::DiscStart>& handover() const { return handover_; }

 private:
  /// A step from flat whose continued motion never rose above the ground (finish_step): the body stays flat and at
  /// rest; time moves on to t_new (> the step's start), so this cannot loop.
  double no_lift(double t_new) {
    Rigid3DSummary& s = res_.summary;
    // the kinetic energy the body had at the step's flat start (after an impact) is lost with it (flat: no potential)
    s.energy_lost_j_per_kg += std::max(0.0, energy(g_, y_, u_, opt_.g_m_s2));
    y_[4] = y_[5] = y_[6] = 0.0;  // y_ is still the step's flat start
    mode_ = Rigid3DMode::rest;
    s.modes.push_back({t_new, mode_, -1, -1});
    h_try_ = 0.0;
    fsal_valid_ = false;
    record(t_new);
    return t_new;
  }

  /// The base lands flat (header: the impact law).
  void impact(double t, V u_old) {
    Rigid3DSummary& s = res_.summary;
    ++s.impacts;
    const Quaternion q = normalised(quat(y_));
    const Contact c = contact_of(g_, q, u_old);
    const V w = omega(y_);
    const double ke_before = 0.5 * dot(w, g_.Mp_times(c.a, c.r, w));
    const double e_before = ke_before + opt_.g_m_s2 * (c.r[2] - g_.h);
    // put the body flat: turn it back by its tilt about the horizontal axis z x a
    const V n = cross(c.a, kZ);  // a -> z
    const double sn = norm(n);
    Quaternion qf = q;
    if (sn > 0.0) {
      const double ang = std::atan2(sn, c.a[2]);
      const double hs = std::sin(0.5 * ang) / sn;
      qf = normalised(qmul({std::cos(0.5 * ang), n[0] * hs, n[1] * hs, n[2] * hs}, q));
    }
    // the new contact: the rim point with the largest downward velocity, -(z x w_h) (header)
    const V wh{w[0], w[1], 0.0};
    V zw = cross(kZ, wh);
    const double nzw = norm(zw);
    V u_new = nzw > 0.0 ? mul(zw, -1.0 / nzw) : mul(u_old, -1.0);
    u_new[2] = 0.0;
    const V tn = cross(kZ, u_new);
    // angular momentum about the new contact (flat): L = J w- + r' x v_c-, v_c- = w- x r
    const V a_f = kZ;
    const V r_new = sub(mul(a_f, g_.h), mul(u_new, g_.R));
    const V vc = cross(w, c.r);
    const V L = add(g_.JG(c.a, w), cross(r_new, vc));
    const std::array<V, 3> M = g_.Mp(a_f, r_new);
    const auto Mv = [&](V v) { return V{dot(M[0], v), dot(M[1], v), dot(M[2], v)}; };
    const double m11 = dot(tn, Mv(tn)), m12 = dot(tn, Mv(kZ)), m22 = dot(kZ, Mv(kZ));
    const double l1 = dot(tn, L), l2 = dot(kZ, L);
    const auto [wt, wz, ke_after] = detail::r3d::flat_landing(m11, m12, m22, l1, l2, ke_before, opt_);
    // the position of the centre of mass: flat, above the landing spot
    const V o_flat = sub(position(y_), mul(c.a, g_.h));  // the base's centre (the tilt is 0 to rounding)
    y_[0] = qf[0], y_[1] = qf[1], y_[2] = qf[2], y_[3] = qf[3];
    y_[7] = o_flat[0], y_[8] = o_flat[1], y_[9] = g_.h;
    if (!(wt > 0.0) || ke_after < opt_.rest_energy_fraction * g_.lift_energy) {
      s.energy_lost_j_per_kg += e_before;
      y_[4] = y_[5] = y_[6] = 0.0;
      mode_ = Rigid3DMode::rest;
      s.modes.push_back({t, mode_, -1, -1});
    } else {
      s.energy_lost_j_per_kg += e_before - ke_after;
      const V wn = add(mul(tn, wt), mul(kZ, wz));
      y_[4] = wn[0], y_[5] = wn[1], y_[6] = wn[2];
      u_ = u_new;
      s.modes.push_back({t, mode_, -1, -1});
    }
    h_try_ = 0.0;
    fsal_valid_ = false;
    record(t);
  }

  const InputGrid& grid_;
  std::vector<double> gravity_;
  Geo g_;
  Rigid3DOptions opt_;
  double max_tilt_sin2_ = 0.0;  // below sin^2 of the summary's max tilt (less a margin for rounding)
  double rows_dt_ = 0.0;  // > 0 in the run-out: history rows at rows_t0_ + k rows_dt_ (k >= rows_next_)
  double rows_t0_ = 0.0;
  std::size_t rows_next_ = 0;
  double p_;  // the frequency parameter sqrt(g / |r|) of the upright body (the error norm's rate scale), rad/s
  Rigid3DResult res_;
  State y_{};
  V u_{1.0, 0.0, 0.0};
  Rigid3DMode mode_ = Rigid3DMode::rest;
  double mu_s_ = -1.0;                 // friction given: mu_s (>= 0); absent: -1 (the contact force is not checked)
  std::optional<double> stop_time_;    // the run stopped where the rolling contact failed (contact_fails)
  std::optional<detail::DiscStart> handover_;  // the state there, for the contact engine
  double h_try_ = 0.0;
  std::size_t steps_ = 0;
  State k1_{};
  bool fsal_valid_ = false;
  std::array<double, 3> fsal_acc_{};
};

/// The rolling engine's run up to the hand-over followed by the contact engine's (rigid3d_disc_contact.cpp): modes
/// and history joined, counters added, the extremes of both, the contact engine's end.
Rigid3DResult merge_disc_contact(Rigid3DResult a, Rigid3DResult b, const Rigid3DOptions& options, double alpha) {
  Rigid3DSummary& s = a.summary;
  Rigid3DSummary& e = b.summary;
  for (std::size_t k = 0; k < e.modes.size(); ++k) {
    if (k == 0 && !s.modes.empty() && e.modes[k].mode == s.modes.back().mode) continue;
    s.modes.push_back(e.modes[k]);
  }
  s.overturned = e.overturned;
  s.overturn_time_s = e.overturn_time_s;
  s.overturn_azimuth_deg = e.overturn_azimuth_deg;
  if (e.max_tilt_rad > s.max_tilt_rad) {
    s.max_tilt_rad = e.max_tilt_rad;
    s.max_tilt_azimuth_deg = e.max_tilt_azimuth_deg;
    s.max_tilt_time_s = e.max_tilt_time_s;
  }
  s.max_tilt_over_limit = s.max_tilt_rad / alpha;
  if (!s.exceeded_limit_time_s) s.exceeded_limit_time_s = e.exceeded_limit_time_s;
  s.impacts += e.impacts;
  s.uplifts += e.uplifts;
  if (!s.uplift_time_s) s.uplift_time_s = e.uplift_time_s;
  s.energy_lost_j_per_kg += e.energy_lost_j_per_kg;
  s.flight_time_s = e.flight_time_s;
  detail::r3d::copy_slide_totals(s, e);  // the rolling engine does not slide
  s.slide_rock_time_s = e.slide_rock_time_s;
  s.slide_rock_duration_s = e.slide_rock_duration_s;
  s.flights = e.flights;
  s.flight_duration_s = e.flight_duration_s;
  s.residual_yaw_deg = e.residual_yaw_deg;
  s.painleve_events = e.painleve_events;
  s.end_time_s = e.end_time_s;
  s.end_mode = e.end_mode;
  s.steps += e.steps;
  for (auto& w : e.warnings) s.warnings.push_back(std::move(w));
  if (options.record_history) {
    detail::r3d::append_history(a.history, b.history, false);  // the hand-over row: the contact engine's state
  }
  return a;
}

}  // namespace

CylinderBody3D CylinderBody3D::solid(double diameter_m, double height_m) {
  require_positive(diameter_m, "diameter", "the diameter");
  require_positive(height_m, "height", "the height");
  if (diameter_m > kMaxBodyDimension_m) throw parameter_error("diameter", "the diameter exceeds 1000 m");
  if (height_m > kMaxBodyDimension_m) throw parameter_error("height", "the height exceeds 1000 m");
  const double R = 0.5 * diameter_m;
  return {R, 0.5 * height_m, 0.5 * R * R, (3.0 * R * R + height_m * height_m) / 12.0};
}

CylinderBody3D CylinderBody3D::general(double radius_m, double centre_height_m, double inertia_axial_m2,
                                       double inertia_transverse_m2) {
  require_positive(radius_m, "radius", "the radius");
  require_positive(centre_height_m, "height", "the height of the centre of mass");
  require_positive(inertia_axial_m2, "inertia", "the axial inertia");
  require_positive(inertia_transverse_m2, "inertia", "the transverse inertia");
  if (inertia_axial_m2 > 2.0 * inertia_transverse_m2) {
    throw parameter_error("inertia", "J_axial > 2 J_transverse violates the triangle inequality of principal moments");
  }
  return {radius_m, centre_height_m, inertia_axial_m2, inertia_transverse_m2};
}

double CylinderBody3D::static_tilt_limit_rad() const { return std::atan2(radius_m, centre_height_m); }

Rigid3DResult rock3d_cylinder(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                              const CylinderBody3D& body, const Rigid3DOptions& options,
                              const std::optional<CylinderInitialState>& initial) {
  const CylinderBody3D b =
      CylinderBody3D::general(body.radius_m, body.centre_height_m, body.inertia_axial_m2, body.inertia_transverse_m2);
  if (!(options.g_m_s2 > 0.0) || !std::isfinite(options.g_m_s2)) throw parameter_error("g", "g must be positive");
  if (!(options.rel_tol > 0.0 && options.rel_tol < 1.0)) throw parameter_error("rel_tol", "rel_tol must be in (0, 1)");
  if (!(options.abs_tol > 0.0 && options.abs_tol < 1.0)) throw parameter_error("abs_tol", "abs_tol must be in (0, 1)");
  if (!(options.e >= 0.0 && options.e <= 1.0)) throw parameter_error("e", "e must be in [0, 1]");
  if (!(options.rest_energy_fraction > 0.0 && options.rest_energy_fraction < 1.0)) {
    throw parameter_error("rest_energy_fraction", "rest_energy_fraction must be in (0, 1)");
  }
  if (!(options.max_run_out_s >= 0.0) || !std::isfinite(options.max_run_out_s)) {
    throw parameter_error("max_run_out_s", "max_run_out_s must be >= 0 and finite");
  }
  if (options.base_incline_deg != 0.0) throw parameter_error("base_incline_deg", "the rim engine has a level base");
  if (options.mu_s || options.mu_k) {
    detail::check_friction(options);
  }
  const std::array<const GroundMotion*, 3> components{&x, y, z};
  const InputGrid grid(components);
  std::vector<double> gravity = effective_gravity(grid, 2, options.g_m_s2);
  const bool shenton = options.mu_s && !initial && *options.mu_s * b.centre_height_m < b.radius_m;
  if (!gravity.empty() && (!options.mu_s || shenton)) {  // friction given: flight is modelled (contact engine)
    const double lowest = *std::min_element(gravity.begin(), gravity.end());
    if (!(lowest > 0.0) && shenton) {
      // the flat slide model excludes flight; the contact engine's flat phases (rest, sliding, flight, landing) hold
      // Shenton's flat base as well (its flat sliding lifts onto the rim only where mu_k h > R)
      detail::DiscStart flat;
      flat.time_s = grid.time_s(0);
      flat.position_m = {0.0, 0.0, b.centre_height_m};
      flat.at_rest = true;
      return detail::rock3d_disc_contact(x, y, z, b, options, flat);
    }
    if (!(lowest > 0.0)) {
      throw parameter_error("vertical", fmt::format("g + a_z reaches {} m/s2 <= 0: the body would leave the ground, "
                                                    "which this model excludes",
                                                    lowest));
    }
  }
  if (shenton) {
    // Shenton (1996): with mu_s h < R the centre of pressure c_plan + h F_t / N (|F_t| <= mu_s N) never reaches the
    // rim, so the base never lifts and the body is the sliding block of sliding2d.hpp exactly (docs/method.md)
    return detail::rock3d_flat_slide(x, y, z, options);
  }
  Geo geo{b.radius_m, b.centre_height_m, b.inertia_axial_m2, b.inertia_transverse_m2,
          std::atan2(b.radius_m, b.centre_height_m), 0.0};
  geo.lift_energy = options.g_m_s2 * (std::hypot(geo.R, geo.h) - geo.h);
  Engine engine(grid, std::move(gravity), geo, options);
  Rigid3DResult rolled = engine.run(initial);
  if (!engine.handover()) return rolled;
  return merge_disc_contact(std::move(rolled), detail::rock3d_disc_contact(x, y, z, b, options, *engine.handover()),
                            options, geo.alpha);
}

}  // namespace topple
