#pragma once
// Internal: the small fixed-size algebra (3-vectors, 3x3 matrices as rows, quaternions w, x, y, z) and the
// Dormand-Prince 5(4) stepper with dense output shared by the three-dimensional engines (rigid3d.cpp, the no-slip
// engine; rigid3d_contact.cpp, the engine with slipping contacts and flight), and the pieces the engines that hand a
// run over to another share (rigid3d_slide.cpp, rigid3d_disc.cpp, rigid3d_disc_contact.cpp).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>

#include "topple/bodies/body.hpp"
#include "topple/core/units.hpp"
#include "topple/numerics/dp5.hpp"
#include "topple/numerics/step_law.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple::detail::r3d {

// ---------------------------------------------------------------------------------------------------------------
// Small fixed-size algebra (3-vectors, 3x3 matrices as rows, quaternions w, x, y, z).

using M3 = std::array<Vec3, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(double k, const Vec3& a) { return {k * a[0], k * a[1], k * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 mul(const M3& m, const Vec3& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }
inline Vec3 mul_t(const M3& m, const Vec3& v) {  // m^T v
  return {m[0][0] * v[0] + m[1][0] * v[1] + m[2][0] * v[2], m[0][1] * v[0] + m[1][1] * v[1] + m[2][1] * v[2],
          m[0][2] * v[0] + m[1][2] * v[1] + m[2][2] * v[2]};
}
inline M3 inverse(const M3& m) {
  const Vec3 c0 = cross(m[1], m[2]);
  const Vec3 c1 = cross(m[2], m[0]);
  const Vec3 c2 = cross(m[0], m[1]);
  const double det = dot(m[0], c0);
  // rows of the inverse are the columns of (c0 c1 c2) / det
  return {{{c0[0] / det, c1[0] / det, c2[0] / det},
           {c0[1] / det, c1[1] / det, c2[1] / det},
           {c0[2] / det, c1[2] / det, c2[2] / det}}};
}
/// J_p = J + |r|^2 1 - r r^T (parallel axes, per unit mass).
inline M3 shifted_inertia(const M3& J, const Vec3& r) {
  M3 out = J;
  const double r2 = dot(r, r);
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) out[i][j] += (i == j ? r2 : 0.0) - r[i] * r[j];
  }
  return out;
}

inline Quaternion qmul(const Quaternion& a, const Quaternion& b) {
  return {a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3], a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
          a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1], a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0]};
}
inline Quaternion normalized(const Quaternion& q) {
  const double n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  return {q[0] / n, q[1] / n, q[2] / n, q[3] / n};
}
/// Rotation by angle about the unit axis.
inline Quaternion axis_angle(const Vec3& axis, double angle) {
  const double s = std::sin(0.5 * angle);
  return {std::cos(0.5 * angle), s * axis[0], s * axis[1], s * axis[2]};
}
/// The rotation matrix of q / |q| (rows).
inline M3 rotation(const Quaternion& q) {
  const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  const double s = 2.0 / n2;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {{{1.0 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)},
           {s * (x * y + w * z), 1.0 - s * (x * x + z * z), s * (y * z - w * x)},
           {s * (x * z - w * y), s * (y * z + w * x), 1.0 - s * (x * x + y * y)}}};
}

constexpr Vec3 kUp{0.0, 0.0, 1.0};

// ---------------------------------------------------------------------------------------------------------------
// Dormand-Prince 5(4) with dense output for N components (the tableau and dense weights of numerics/dp5.hpp, the
// error norm and step law of rocking_steppers.hpp's AdaptiveStepper: error_i / (abs_tol scale_i + rel_tol |x0_i|)).

template <std::size_t N>
using State = std::array<double, N>;

template <std::size_t N, class F>
class Dp5 {
 public:
  Dp5(F f, double abs_tol, double rel_tol, double dt0) : f_(std::move(f)), abs_tol_(abs_tol), rel_tol_(rel_tol),
                                                         dt_(dt0) {}
  void set_scale(const State<N>& scale) { scale_ = scale; }
  void restart(double t, const State<N>& x) {
    t1_ = t;
    x1_ = x;
    f_(x1_, t1_, k_[5]);
  }
  [[nodiscard]] bool step(double t_limit, std::size_t& steps, std::size_t max_steps) {
    t0_ = t1_;
    x0_ = x1_;
    k_[0] = k_[5];
    dense_ready_ = false;
    const double remaining = t_limit - t0_;
    for (;;) {
      if (++steps > max_steps) return false;
      const bool clamped = dt_ >= remaining;
      const double dt = clamped ? remaining : dt_;
      const double error = try_step(dt);
      if (error <= 1.0) {
        h_ = dt;
        t1_ = clamped ? t_limit : t0_ + dt;
        const double next = detail::StepLaw::increase(dt, error);
        dt_ = clamped ? std::max(dt_, next) : next;
        return true;
      }
      dt_ = detail::StepLaw::decrease(dt, error);
    }
  }
  [[nodiscard]] State<N> dense(double t) const {
    if (t == t1_) return x1_;
    if (t == t0_) return x0_;
    if (!dense_ready_) expand();
    const double s = (t - t0_) / h_;
    State<N> x{};
    for (std::size_t i = 0; i < N; ++i) {
      const auto& c = poly_[i];
      x[i] = x0_[i] + s * (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4]))));
    }
    return x;
  }
  [[nodiscard]] double t0() const { return t0_; }
  [[nodiscard]] double t1() const { return t1_; }
  [[nodiscard]] const State<N>& x0() const { return x0_; }
  [[nodiscard]] const State<N>& x1() const { return x1_; }

 private:
  double try_step(double h) {
    using namespace detail::dp5;
    State<N> y{};
    State<N> k2{};
    const auto stage = [&](State<N>& out, double t, auto&&... terms) {
      for (std::size_t i = 0; i < N; ++i) y[i] = x0_[i] + h * (0.0 + ... + (terms.first * terms.second[i]));
      f_(y, t, out);
    };
    using P = std::pair<double, const State<N>&>;
    stage(k2, t0_ + a2 * h, P{b21, k_[0]});
    stage(k_[1], t0_ + a3 * h, P{b31, k_[0]}, P{b32, k2});
    stage(k_[2], t0_ + a4 * h, P{b41, k_[0]}, P{b42, k2}, P{b43, k_[1]});
    stage(k_[3], t0_ + a5 * h, P{b51, k_[0]}, P{b52, k2}, P{b53, k_[1]}, P{b54, k_[2]});
    stage(k_[4], t0_ + h, P{b61, k_[0]}, P{b62, k2}, P{b63, k_[1]}, P{b64, k_[2]}, P{b65, k_[3]});
    for (std::size_t i = 0; i < N; ++i) {
      x1_[i] = x0_[i] + h * (c1 * k_[0][i] + c3 * k_[1][i] + c4 * k_[2][i] + c5 * k_[3][i] + c6 * k_[4][i]);
    }
    f_(x1_, t0_ + h, k_[5]);
    double error = 0.0;
    for (std::size_t i = 0; i < N; ++i) {
      const double e = h * (dc1 * k_[0][i] + dc3 * k_[1][i] + dc4 * k_[2][i] + dc5 * k_[3][i] + dc6 * k_[4][i] +
                            dc7 * k_[5][i]);
      error = std::max(error, std::abs(e) / (abs_tol_ * scale_[i] + rel_tol_ * std::abs(x0_[i])));
    }
    return error;
  }
  void expand() const {
    for (std::size_t i = 0; i < N; ++i) {
      for (std::size_t m = 1; m < 6; ++m) {
        double sum = 0.0;
        for (std::size_t j = 0; j < 6; ++j) sum += detail::dp5::kDense[j].c[m] * k_[j][i];
        poly_[i][m - 1] = h_ * sum;
      }
    }
    dense_ready_ = true;
  }

  F f_;
  double abs_tol_, rel_tol_, dt_;
  State<N> scale_{};
  double h_ = 0.0, t0_ = 0.0, t1_ = 0.0;
  State<N> x0_{}, x1_{};
  std::array<State<N>, 6> k_{};  // k1, k3, k4, k5, k6, k7 (the weights' order in kDense)
  mutable std::array<std::array<double, 5>, N> poly_{};
  mutable bool dense_ready_ = false;
};

/// The input over one sample interval, linear as the record is between samples: a(t) = a0 + as (t - t_ref) along x
/// and y, G = g + a_z likewise; f(t) is the force per unit mass in the ground frame, -a_g - g z. Both engines' (the
/// no-slip one, rigid3d.cpp; the contact one, rigid3d_contact.cpp).
struct Forcing {
  double t_ref = 0.0;
  double ax0 = 0.0, axs = 0.0, ay0 = 0.0, ays = 0.0, G0 = 0.0, Gs = 0.0;
  [[nodiscard]] Vec3 f(double t) const {
    const double tau = t - t_ref;
    return {-(ax0 + axs * tau), -(ay0 + ays * tau), -(G0 + Gs * tau)};
  }
  /// Over [ta, tb], samples i and i + 1 of x (required), y and the vertical's g + a_z (empty: absent, G = g).
  [[nodiscard]] static Forcing interval(std::size_t i, double ta, double tb, std::span<const double> ax,
                                        std::span<const double> ay, std::span<const double> gravity, double g) {
    const double dt = tb - ta;
    return {ta,
            ax[i],
            (ax[i + 1] - ax[i]) / dt,
            ay.empty() ? 0.0 : ay[i],
            ay.empty() ? 0.0 : (ay[i + 1] - ay[i]) / dt,
            gravity.empty() ? g : gravity[i],
            gravity.empty() ? 0.0 : (gravity[i + 1] - gravity[i]) / dt};
  }
  /// Still ground from t on (the run-out after the record).
  [[nodiscard]] static Forcing still(double t, double g) { return {t, 0.0, 0.0, 0.0, 0.0, g, 0.0}; }
  /// Still ground from t on, the load (a_x, a_y, G) per unit mass constant (an inclined base: BaseFrame::still).
  [[nodiscard]] static Forcing still(double t, const Vec3& load) {
    return {t, load[0], 0.0, load[1], 0.0, load[2], 0.0};
  }
};

/// The run-out after the record, one loop for the no-slip (rigid3d.cpp) and the contact (rigid3d_contact.cpp)
/// engines: from t_end on still ground (the caller has set Forcing::still and its restart), intervals of
/// max(dt, max_run_out_s x 1e-5) s, each integrated by interval(t_b) and followed by row() (a history row), while
/// moving() (not at rest, not fallen) and t < t_end + max_run_out_s. t: the engine's clock, advanced by interval().
template <class Moving, class Interval, class Row>
void run_out_on_still_ground(double t_end, double dt_s, double max_run_out_s, const double& t, Moving moving,
                             Interval interval, Row row) {
  const double t_stop = t_end + max_run_out_s;
  const double dt = std::max(dt_s, max_run_out_s * 1e-5);
  double next = t_end + dt;
  while (moving() && t < t_stop) {
    interval(std::min(next, t_stop));
    row();
    next += dt;
  }
}

/// The inclined base's frame (rigid3d.hpp, "Inclined base"; docs/method.md, "An inclined base"): Q rotates by beta
/// about the horizontal axis k = z x e_d (e_d the downhill direction), so Q z = cos(beta) z + sin(beta) e_d = n, the
/// base normal, and Q e_d = cos(beta) e_d - sin(beta) z, the plane's line of steepest descent. A load (a_x, a_y, G)
/// given in the record's frame (the ground's acceleration and g + a_z) is Q^T (a_x, a_y, G) in the base frame.
struct BaseFrame {
  bool level = true;
  M3 to_base{{{1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {0.0, 0.0, 1.0}}};  // Q^T (rows)
  Vec3 still{};  // Q^T (0, 0, g): still ground's load in the base frame
  double g = 0.0;

  [[nodiscard]] static BaseFrame make(double incline_deg, double azimuth_deg, double g_m_s2) {
    BaseFrame f;
    f.g = g_m_s2;
    f.still = {0.0, 0.0, g_m_s2};
    if (incline_deg == 0.0) return f;
    f.level = false;
    const double b = deg_to_rad(incline_deg);
    const double a = deg_to_rad(azimuth_deg);
    const Vec3 k{-std::cos(a), std::sin(a), 0.0};  // z x e_d, e_d = (sin A, cos A, 0)
    const double cb = std::cos(b), sb = std::sin(b);
    // Rodrigues: Q v = v cos(b) + (k x v) sin(b) + k (k . v)(1 - cos(b)); Q^T the same with -b. Row i of Q^T is
    // Q e_i (Q^T_ij = Q_ji = e_j . Q e_i).
    for (std::size_t i = 0; i < 3; ++i) {
      Vec3 e{};
      e[i] = 1.0;
      f.to_base[i] = cb * e + sb * cross(k, e) + ((1.0 - cb) * k[i]) * k;
    }
    f.still = g_m_s2 * mul(f.to_base, kUp);
    return f;
  }
  /// The base-frame load of a record-frame one.
  [[nodiscard]] Vec3 load(double ax, double ay, double G) const {
    return level ? Vec3{ax, ay, G} : mul(to_base, Vec3{ax, ay, G});
  }
  /// The potential energy per unit mass of the centre of mass at c (base frame) relative to c0: the load of still
  /// ground times the displacement (on level ground g (z - z0)).
  [[nodiscard]] double potential(const Vec3& c, const Vec3& c0) const {
    if (level) return g * (c[2] - c0[2]);
    return dot(still, c - c0);
  }
};

// ---------------------------------------------------------------------------------------------------------------
// Handing a run over from one engine to the next.

/// Appends `next`, the history of the engine that took a run over, to `h`. A row of `next` at or before h's last time
/// is the hand-over row: it keeps h's time and takes the state of `next` (the engine that goes on); with
/// `first_row_only`, only next's first row is taken for one.
inline void append_history(Rigid3DHistory& h, const Rigid3DHistory& next, bool first_row_only) {
  for (std::size_t k = 0; k < next.time_s.size(); ++k) {
    if (!h.time_s.empty() && next.time_s[k] <= h.time_s.back() && (k == 0 || !first_row_only)) {
      h.position_m.back() = next.position_m[k];
      h.orientation.back() = next.orientation[k];
      h.angular_velocity_rad_s.back() = next.angular_velocity_rad_s[k];
      h.energy_j_per_kg.back() = next.energy_j_per_kg[k];
      h.mode.back() = next.mode[k];
      continue;
    }
    h.time_s.push_back(next.time_s[k]);
    h.position_m.push_back(next.position_m[k]);
    h.orientation.push_back(next.orientation[k]);
    h.angular_velocity_rad_s.push_back(next.angular_velocity_rad_s[k]);
    h.energy_j_per_kg.push_back(next.energy_j_per_kg[k]);
    h.mode.push_back(next.mode[k]);
  }
}

/// A landing flat on the base (the cylinder's engines, rigid3d_disc.cpp and rigid3d_disc_contact.cpp): the rates
/// about the rim's tangent and the vertical, (w_t, w_z), from the angular momentum about the new contact,
/// [m11 m12; m12 m22] (w_t, w_z) = (l1, l2) (Cramer's rule), and their kinetic energy; with a given restitution e,
/// both rates scaled so that it is e^2 of the energy before, `ke_before` (docs/method.md).
struct FlatLanding {
  double wt, wz, ke_after;
};
inline FlatLanding flat_landing(double m11, double m12, double m22, double l1, double l2, double ke_before,
                                const Rigid3DOptions& options) {
  const double det = m11 * m22 - m12 * m12;
  double wt = (l1 * m22 - l2 * m12) / det;
  double wz = (m11 * l2 - m12 * l1) / det;
  double ke_after = 0.5 * (m11 * wt * wt + 2.0 * m12 * wt * wz + m22 * wz * wz);
  if (options.restitution == RestitutionMode::given && ke_after > 0.0) {
    const double k = options.e * std::sqrt(ke_before / ke_after);
    wt *= k;
    wz *= k;
    ke_after = options.e * options.e * ke_before;
  }
  return {wt, wz, ke_after};
}

/// The state an engine takes a run over in (rigid3d_slide.hpp's ContactStart, rigid3d_disc_contact.hpp's DiscStart):
/// the time, a point of the body (ContactStart: the body frame's origin; DiscStart: the centre of mass) and the centre
/// of mass's velocity in the ground frame, the orientation (body -> ground) and the angular velocity (ground frame).
struct EngineStart {
  double time_s = 0.0;
  Vec3 position_m{};
  Vec3 velocity_m_s{};
  Quaternion orientation = kIdentityQuaternion;
  Vec3 angular_velocity_rad_s{};
};

/// Copies the sliding totals (residual slide, the largest slide and slide speed, path, friction work, slip episodes
/// and the first slip) of the phase that holds them, `from`, into `to` (the other engine's summary: its own contacts
/// did not slide, or `from` already holds them whole).
inline void copy_slide_totals(Rigid3DSummary& to, const Rigid3DSummary& from) {
  to.residual_slide_east_m = from.residual_slide_east_m;
  to.residual_slide_north_m = from.residual_slide_north_m;
  to.max_slide_m = from.max_slide_m;
  to.max_slide_speed_m_s = from.max_slide_speed_m_s;
  to.slide_path_length_m = from.slide_path_length_m;
  to.friction_energy_j_per_kg = from.friction_energy_j_per_kg;
  to.slip_episodes = from.slip_episodes;
  to.first_slip_time_s = from.first_slip_time_s;
}

}  // namespace topple::detail::r3d
