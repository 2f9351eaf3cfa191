#pragma once
// The rocking engine's input, right-hand side and steppers (src/solvers/rocking.cpp; the model, the sign convention
// and the method: include/topple/solvers/rocking.hpp): the adaptive Dormand-Prince 5(4) stepper written out for the
// two components with the library's tableau (numerics/dp5.hpp), and the thesis' fixed-step RK4. Private to
// rocking.cpp, which alone includes it: its definitions stay in an unnamed namespace, so that the engine's calls into
// them inline as they did when they were one file.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <boost/numeric/odeint/stepper/runge_kutta4.hpp>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/numerics/angle_series.hpp"
#include "topple/numerics/dp5.hpp"
#include "topple/numerics/event_root.hpp"
#include "topple/numerics/step_law.hpp"

namespace topple {
namespace {

namespace odeint = boost::numeric::odeint;

/// Scaled state (theta / alpha, theta' / (p alpha)).
using State = std::array<double, 2>;

// ---------------------------------------------------------------------------------------------------------------
// Input on one time grid (input_grid.hpp: the union of the components' grids, jumps of either kept): horizontal a_h
// and, with a vertical record, the effective gravity g + a_v per point.

struct Input {
  Input(const GroundMotion& horizontal, const GroundMotion* vertical, double g)
      : grid(horizontal, vertical), accel(grid.accel_m_s2(0)), gravity(effective_gravity(grid, 1, g)) {
    if (gravity.empty()) return;
    const double lowest = *std::min_element(gravity.begin(), gravity.end());
    if (!(lowest > 0.0)) {
      throw parameter_error("vertical", fmt::format("the vertical acceleration reaches {} m/s2, so g + a_v = {} m/s2 "
                                                    "<= 0: the body would leave the ground, which this model excludes",
                                                    lowest - g, lowest));
    }
  }
  InputGrid grid;
  std::span<const double> accel;
  std::vector<double> gravity;  // g + a_v per point; empty without vertical input
  [[nodiscard]] std::size_t size() const { return grid.size(); }
  [[nodiscard]] double time(std::size_t i) const { return grid.time_s(i); }
  /// Sample interval (mean interval when irregular): the run-out grid and the RK4 step.
  [[nodiscard]] double dt() const { return grid.dt_s(); }
};

// ---------------------------------------------------------------------------------------------------------------
// Right-hand side: the equation of motion of rocking.hpp in the scaled state, with the forcing linear in time over
// the current sample interval.

struct Rhs {
  double p = 0.0;
  double alpha = 0.0;
  double k = 0.0;        // (R_s / D_s) / (p alpha), s the pivot (alpha, p: the scale, Params)
  double s_alpha = 0.0;  // s * alpha_s, s the pivot
  // forcing: a_h = ah0 + ahs (t - t_ref), g + a_v = ge0 + ges (t - t_ref)
  double t_ref = 0.0, ah0 = 0.0, ahs = 0.0, ge0 = 0.0, ges = 0.0;
  // sin and cos of phi = s alpha - theta at the start of the current step. The stages of a step lie close to it,
  // so sin and cos there follow from the angle-addition formulas with a short series in the difference: one libm
  // sincos per step instead of six (it was a third of the run time while rocking).
  double phi_ref = 0.0;
  double sin_ref = 0.0;
  double cos_ref = 1.0;

  // Reference moves since the last exact sin/cos (angle_series.hpp, move_reference).
  int moves = 0;

  // sin and cos of +alpha and -alpha (set once per run): the reference at theta = 0, where every restart after an
  // uplift or an impact is, without a libm call (the same values the calls would return).
  std::array<double, 2> sin_pm_alpha{};  // {sin(-alpha), sin(alpha)}
  std::array<double, 2> cos_pm_alpha{1.0, 1.0};

  // The pivot angles of O- and O+, {-alpha-, alpha+} (symmetric body: {-alpha, alpha}).
  std::array<double, 2> pm_alpha{};

  /// scale: the alpha of the scaled state; the pivot angles of O- and O+ (all three alpha for a symmetric body).
  void set_alpha(double scale, double alpha_negative, double alpha_positive) {
    alpha = scale;
    pm_alpha = {-alpha_negative, alpha_positive};
    sin_pm_alpha = {std::sin(-alpha_negative), std::sin(alpha_positive)};
    cos_pm_alpha = {std::cos(-alpha_negative), std::cos(alpha_positive)};
  }

  void set_reference(double u0) {
    phi_ref = s_alpha - alpha * u0;
    if (u0 == 0.0 && (s_alpha == pm_alpha[1] || s_alpha == pm_alpha[0])) {
      const std::size_t i = s_alpha > 0.0 ? 1 : 0;
      sin_ref = sin_pm_alpha[i];
      cos_ref = cos_pm_alpha[i];
    } else {
      sin_ref = std::sin(phi_ref);
      cos_ref = std::cos(phi_ref);
    }
    moves = 0;
  }

  /// The reference moved to the start of the next step: sin and cos there follow from the current reference by the
  /// same short series as the stages (the move is a step's change of phi, small), instead of a libm sincos per step
  /// (it was 13 % of the inversion's instructions).
  void move_reference(double u0) {
    if (!detail::move_reference(s_alpha - alpha * u0, phi_ref, sin_ref, cos_ref, moves)) set_reference(u0);
  }

  static constexpr double kSeriesRange = detail::kSeriesRange;

  /// sin d and cos d - 1 by their series (angle_series.hpp; false when |d| > kSeriesRange: the caller uses libm).
  [[gnu::always_inline]] static bool series(double d, double& sd, double& cd_minus_1) {
    return detail::angle_series(d, sd, cd_minus_1);
  }

  /// sin and cos of phi = phi_ref + d: the angle-addition formulas with the series of d, or libm when d is large.
  [[gnu::always_inline]] void sin_cos(double phi, double& sn, double& cs) const {
    detail::sin_cos_near(phi, phi_ref, sin_ref, cos_ref, sn, cs);
  }

  /// The second component of the right-hand side, d(theta' / (p alpha))/dt = -k (G sin(phi) + A cos(phi)), at
  /// phi = phi_ref + d and time t, G = g + a_v and A = a_h at t. By the angle-addition formulas that is
  /// P (1 + (cos d - 1)) + Q sin d with P = -k (G sin_ref + A cos_ref) and Q = -k (G cos_ref - A sin_ref), which
  /// depend on the time only: they are formed while the
  /// stage's state is still being computed, which leaves the series and two multiply-adds on the chain from one stage
  /// to the next (the stages are sequential: that chain is the step's latency).
  [[gnu::always_inline]] double accel(double d, double t) const {
    const double tau = t - t_ref;
    const double G = ge0 + ges * tau;
    const double A = ah0 + ahs * tau;
    double sd = 0.0;
    double cd_minus_1 = 0.0;
    if (!series(d, sd, cd_minus_1)) {
      const double phi = phi_ref + d;
      return -k * (G * std::sin(phi) + A * std::cos(phi));
    }
    const double P = -k * (G * sin_ref + A * cos_ref);
    const double Q = -k * (G * cos_ref - A * sin_ref);
    return P + (P * cd_minus_1 + Q * sd);
  }

  [[gnu::always_inline]] void operator()(const State& u, State& du, double t) const {
    du[0] = p * u[1];
    du[1] = accel((s_alpha - alpha * u[0]) - phi_ref, t);
  }
};

using detail::StepLaw;  // step_law.hpp, shared with slide_rock.cpp

// ---------------------------------------------------------------------------------------------------------------
// Dormand-Prince 5(4) (Dormand & Prince 1980, J. Comput. Appl. Math. 6(1), 19-26; the tableau, the embedded error
// estimate and the 4th-order dense output of Hairer, Norsett & Wanner 1993, II.5 and II.6, as Boost.Odeint's
// runge_kutta_dopri5 has them), written out for the rocking equation's two components: no generic algebra, the
// right-hand side inlined, and the dense output expanded once per step into a polynomial in the step fraction
// (evaluated by Horner in the event root finder instead of recomputing its weights at every call).
namespace dp5 = detail::dp5;  // numerics/dp5.hpp: the tableau and the dense-output weights

// Event location (event_root.hpp, shared with slide_rock.cpp).
using detail::find_root;
using detail::kMaxRootIterations;
using detail::time_tolerance;

// ---------------------------------------------------------------------------------------------------------------
// Steppers. Both take one step from the last state toward t_limit (never past it) and give the state anywhere in
// that step (dense output) for the event root finder.

class AdaptiveStepper {
 public:
  AdaptiveStepper(Rhs& rhs, double abs_tol, double rel_tol, double dt0)
      : rhs_(&rhs), abs_tol_(abs_tol), rel_tol_(rel_tol), dt_(dt0) {}

  void restart(double t, const State& x) {
    t1_ = t;
    x1_ = x;
    rhs_->set_reference(x1_[0]);
    (*rhs_)(x1_, k7_, t1_);
  }

  /// False (and no step taken) when the step count would pass max_steps: the engine reports the limit.
  [[nodiscard]] bool step(double t_limit, std::size_t& steps, std::size_t max_steps) {
    t0_ = t1_;
    x0_ = x1_;
    k1_ = k7_;
    dense_ready_ = false;
    const double remaining = t_limit - t0_;
    rhs_->move_reference(x0_[0]);
    for (;;) {
      if (++steps > max_steps) {
        x1_ = x0_;
        t1_ = t0_;
        return false;
      }
      const bool clamped = dt_ >= remaining;
      const double dt = clamped ? remaining : dt_;
      const double error = try_step(dt);
      if (error <= 1.0) {
        h_ = dt;
        t1_ = clamped ? t_limit : t0_ + dt;
        // A step shortened to reach the sample instant says little about the step the solution allows.
        const double next = StepLaw::increase(dt, error);
        dt_ = clamped ? std::max(dt_, next) : next;
        return true;
      }
      dt_ = StepLaw::decrease(dt, error);
    }
  }

  /// The 4th-order dense output at t in [t0, t1].
  [[nodiscard]] State dense(double t) const {
    if (!dense_ready_) expand_dense();
    const double s = (t - t0_) / h_;
    State x{};
    for (std::size_t i = 0; i < 2; ++i) {
      const auto& c = poly_[i];
      x[i] = x0_[i] + s * (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4]))));
    }
    return x;
  }

  /// Bounds on x_i over the step from the dense polynomial x0 + c1 s + ... + c5 s^5, s in [0, 1]: the linear part
  /// is extreme at an end, the rest is at most sum |c_m| (m >= 2) in magnitude. Loose, but rigorous (to round-off).
  [[nodiscard]] std::pair<double, double> range(std::size_t i) const {
    if (!dense_ready_) expand_dense();
    const auto& c = poly_[i];
    const double rest = std::abs(c[1]) + std::abs(c[2]) + std::abs(c[3]) + std::abs(c[4]);
    return {x0_[i] + std::min(c[0], 0.0) - rest, x0_[i] + std::max(c[0], 0.0) + rest};
  }

  /// The time in [ta, tb] where sign * x_i = level on the dense output, given the values fa, fb of
  /// sign * x_i - level at the ends (opposite signs, or one zero). Newton on the dense polynomial, whose derivative is
  /// at hand, kept inside the bracket (a step that leaves it is replaced by bisection), from the regula falsi point;
  /// it stops when the Newton correction is below time_tolerance. NaN after kMaxRootIterations.
  [[nodiscard]] double locate(std::size_t i, double sign, double level, double ta, double tb, double fa,
                              double fb) const {
    if (fa == 0.0) return ta;
    if (fb == 0.0) return tb;
    if (!dense_ready_) expand_dense();
    const auto& c = poly_[i];
    const double base = x0_[i] - sign * level;  // sign * (x_i - sign * level) = sign * x_i - level
    double lo = (ta - t0_) / h_;
    double hi = (tb - t0_) / h_;
    const bool rising = fa < 0.0;  // the function goes from fa to fb
    double s = lo + (hi - lo) * fa / (fa - fb);
    for (std::uintmax_t k = 0; k < kMaxRootIterations; ++k) {
      const double g = sign * (base + s * (c[0] + s * (c[1] + s * (c[2] + s * (c[3] + s * c[4])))));
      const double dg = sign * (c[0] + s * (2.0 * c[1] + s * (3.0 * c[2] + s * (4.0 * c[3] + s * 5.0 * c[4]))));
      if (g == 0.0) return t0_ + s * h_;
      if ((g < 0.0) == rising) {
        lo = s;
      } else {
        hi = s;
      }
      double next = s - g / dg;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);  // also catches dg = 0
      const double t = t0_ + next * h_;
      if (std::abs(next - s) * h_ <= time_tolerance(t) || (hi - lo) * h_ <= time_tolerance(t)) return t;
      s = next;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

  [[nodiscard]] double t0() const { return t0_; }
  [[nodiscard]] double t1() const { return t1_; }
  [[nodiscard]] const State& x0() const { return x0_; }
  [[nodiscard]] const State& x1() const { return x1_; }

 private:
  /// One Dormand-Prince step of length h from (t0_, x0_, k1_) into x1_, k7_ (and the stages k3.._k6 kept for the dense
  /// output). Returns the error norm: max over the components of |err_i| / (abs_tol + rel_tol |x0_i|) (odeint's
  /// default_error_checker with a_x = 1, a_dxdt = 0); the step is accepted when it is <= 1.
  [[gnu::always_inline]] double try_step(double h) {
    using namespace dp5;
    const Rhs& f = *rhs_;
    // Each stage: theta' (component 1, y_j below) from the stage's combination, and the rotation from the increment
    // of component 0 (phi - phi_ref = -alpha (u0 - x0_0): the reference is at the step's start), which saves forming
    // u0 and phi on the chain between stages. Component 0's derivative is p y_j, so its increments are formed from the
    // y_j with p in the coefficient (hp = h p): the products k_j[0] = p y_j, needed by the solution and the dense
    // output, stay off that chain.
    const double nal = -f.alpha;
    const double hp = h * f.p;
    State k2{};
    const double y2 = x0_[1] + h * b21 * k1_[1];
    k2[1] = f.accel(nal * (h * b21 * k1_[0]), t0_ + h * a2);
    const double y3 = x0_[1] + h * b31 * k1_[1] + h * b32 * k2[1];
    k3_[1] = f.accel(nal * (h * b31 * k1_[0] + hp * b32 * y2), t0_ + h * a3);
    const double y4 = x0_[1] + h * b41 * k1_[1] + h * b42 * k2[1] + h * b43 * k3_[1];
    k4_[1] = f.accel(nal * (h * b41 * k1_[0] + hp * b42 * y2 + hp * b43 * y3), t0_ + h * a4);
    const double y5 = x0_[1] + h * b51 * k1_[1] + h * b52 * k2[1] + h * b53 * k3_[1] + h * b54 * k4_[1];
    k5_[1] = f.accel(nal * (h * b51 * k1_[0] + hp * b52 * y2 + hp * b53 * y3 + hp * b54 * y4), t0_ + h * a5);
    const double y6 =
        x0_[1] + h * b61 * k1_[1] + h * b62 * k2[1] + h * b63 * k3_[1] + h * b64 * k4_[1] + h * b65 * k5_[1];
    k6_[1] = f.accel(nal * (h * b61 * k1_[0] + hp * b62 * y2 + hp * b63 * y3 + hp * b64 * y4 + hp * b65 * y5), t0_ + h);
    const double inc0 = h * c1 * k1_[0] + hp * c3 * y3 + hp * c4 * y4 + hp * c5 * y5 + hp * c6 * y6;
    x1_[0] = x0_[0] + inc0;
    x1_[1] = x0_[1] + h * c1 * k1_[1] + h * c3 * k3_[1] + h * c4 * k4_[1] + h * c5 * k5_[1] + h * c6 * k6_[1];
    k7_[1] = f.accel(nal * inc0, t0_ + h);
    k3_[0] = f.p * y3;
    k4_[0] = f.p * y4;
    k5_[0] = f.p * y5;
    k6_[0] = f.p * y6;
    k7_[0] = f.p * x1_[1];
    double error = 0.0;
    for (std::size_t i = 0; i < 2; ++i) {
      const double e = h * dc1 * k1_[i] + h * dc3 * k3_[i] + h * dc4 * k4_[i] + h * dc5 * k5_[i] +
                       h * dc6 * k6_[i] + h * dc7 * k7_[i];
      error = std::max(error, std::abs(e) / (abs_tol_ + rel_tol_ * std::abs(x0_[i])));
    }
    return error;
  }

  /// poly_[i][m - 1] = h sum_j (coefficient of s^m in b_j(s)) k_j[i], m = 1 .. 5.
  void expand_dense() const {
    const std::array<const State*, 6> k{&k1_, &k3_, &k4_, &k5_, &k6_, &k7_};
    for (std::size_t i = 0; i < 2; ++i) {
      for (std::size_t m = 1; m < 6; ++m) {
        double sum = 0.0;
        for (std::size_t j = 0; j < 6; ++j) sum += dp5::kDense[j].c[m] * (*k[j])[i];
        poly_[i][m - 1] = h_ * sum;
      }
    }
    dense_ready_ = true;
  }

  Rhs* rhs_;
  double abs_tol_;
  double rel_tol_;
  double dt_;
  double h_ = 0.0;
  double t0_ = 0.0;
  double t1_ = 0.0;
  State x0_{};
  State x1_{};
  State k1_{};
  State k3_{};
  State k4_{};
  State k5_{};
  State k6_{};
  State k7_{};
  mutable std::array<std::array<double, 5>, 2> poly_{};
  mutable bool dense_ready_ = false;
};

class Rk4Stepper {
 public:
  Rk4Stepper(Rhs& rhs, double h) : rhs_(&rhs), h_(h) {}

  void restart(double t, const State& x) {
    t1_ = t;
    x1_ = x;
  }

  /// False (and no step taken) when the step count would pass max_steps: the engine reports the limit.
  [[nodiscard]] bool step(double t_limit, std::size_t& steps, std::size_t max_steps) {
    if (++steps > max_steps) return false;
    t0_ = t1_;
    x0_ = x1_;
    const double remaining = t_limit - t0_;
    // Equal steps of at most h over what is left of the sample interval: dt/n over a whole interval (thesis).
    const double n = std::max(1.0, std::ceil(remaining / h_ - 1e-9));
    const double dt = remaining / n;
    rhs_->set_reference(x0_[0]);
    rk4_.do_step(std::cref(*rhs_), x0_, t0_, x1_, dt);
    t1_ = n == 1.0 ? t_limit : t0_ + dt;
    return true;
  }

  /// A classical RK4 step of length t - t0 from the step's start: a continuous extension of order 4.
  [[nodiscard]] State dense(double t) const {
    if (t == t1_) return x1_;
    State x{};
    rk4_.do_step(std::cref(*rhs_), x0_, t0_, x, t - t0_);
    return x;
  }

  /// No bounds on x_i over the step (the engine then locates every turning point).
  [[nodiscard]] std::pair<double, double> range(std::size_t /*i*/) const {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }

  /// The time in [ta, tb] where sign * x_i = level on the continuous extension (TOMS 748; NaN when it ran out).
  [[nodiscard]] double locate(std::size_t i, double sign, double level, double ta, double tb, double fa,
                              double fb) const {
    return find_root([&](double t) { return sign * dense(t)[i] - level; }, ta, tb, fa, fb);
  }

  [[nodiscard]] double t0() const { return t0_; }
  [[nodiscard]] double t1() const { return t1_; }
  [[nodiscard]] const State& x0() const { return x0_; }
  [[nodiscard]] const State& x1() const { return x1_; }

 private:
  Rhs* rhs_;
  double h_;
  mutable odeint::runge_kutta4<State> rk4_;
  double t0_ = 0.0;
  double t1_ = 0.0;
  State x0_{};
  State x1_{};
};

}  // namespace
}  // namespace topple
