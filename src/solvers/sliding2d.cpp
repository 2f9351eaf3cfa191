// Bidirectional sliding on level ground. See sliding2d.hpp for the model, the frame and the method; the equations
// and the steady rotating oracle are derived in docs/method.md ("Bidirectional sliding").
#include "topple/solvers/sliding2d.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <tuple>
#include <utility>

#include <boost/math/tools/minima.hpp>
#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

namespace odeint = boost::numeric::odeint;

/// The slip state, in the frame of the two components (axis 1 along the first component's azimuth, axis 2 along the
/// second's; the problem on level ground is invariant under rotations and reflections, so the solve needs no
/// rotation and the results are mapped to east/north at the end): displacement u, velocity w, and three quadratures
/// integrated with them (path length int |w|, input work int -a.w, friction work int mu_k g_e+ |w|).
using State = std::array<double, 7>;
enum : std::size_t { kU1 = 0, kU2, kW1, kW2, kPath, kInputWork, kFrictionWork };

/// Cap on slip starts and stops inside one sample interval (after sliding.cpp's: a stop and a restart make two).
constexpr int kMaxEventsPerStep = 64;
/// Cap on TOMS 748 iterations for an onset or a stop (a smooth function on a certain bracket: a few dozen at most).
constexpr boost::uintmax_t kMaxRootIterations = 200;
/// Cap on step halvings when a step turned the velocity by 90 degrees or more without a stop (see step()).
constexpr int kMaxTurnHalvings = 60;
/// A located zero of w . w_ref is a stop only where |w| there is below this fraction of the step's speed scale; else
/// the velocity turned past 90 degrees within the step (no stop) and the step is halved. At a true stop |w| is the
/// integration error (<= tolerance x scale); a turn leaves |w| of the order of the scale.
constexpr double kStopSpeedFraction = 1e-3;
/// A block that has just started slipping follows the direction of the inertial load -a until its speed exceeds
/// sqrt(abs_tol x kLaunchSpeedScale) (3.2e-5 m/s at the default abs_tol 1e-8; at least kLaunchSpeedTolerances x abs_tol):
/// see Rhs and docs/method.md (S5'), where the error of the slaved phase is estimated. The launch used to end at
/// 1000 abs_tol (1e-7 m/s); the steps after it are stability-limited (h <= 3.3 r/|a|) and their number falls as
/// 1/sqrt(launch speed), so this takes 1.6-1.8x fewer DP5 steps on the benchmark (docs/performance.md).
constexpr double kLaunchSpeedScale = 0.1;  // m/s
constexpr double kLaunchSpeedTolerances = 1000.0;
/// The launch also ends where the quasi-static direction's lag behind -a, r psi' / |a|, would exceed this (rad).
constexpr double kLaunchMaxLag = 1e-3;
/// Landing: a block decelerating (|a| < mu_k g_e) below the launch speed, its velocity within kLaunchMaxLag of -a and
/// the quasi-static lag below half of it, is slaved to -a / |a| again, as in the launch, to its stop (S5', the same
/// error estimate). It saves the stiff steps of the way down (8-13 % of all steps, docs/performance.md).
constexpr double kLandingEntryLagFraction = 0.5;
/// A slipping block back down to this fraction of the launch speed (9.5e-7 m/s at the default abs_tol) has stopped:
/// the velocity noise floor (see integrate()). Below the launch speed, so that a launch does not end in a stop at
/// once.
constexpr double kFloorLaunchFraction = 0.03;
/// Brent's minimiser to half the mantissa in time: at a smooth extreme the value is then exact to round-off.
constexpr int kBrentBits = std::numeric_limits<double>::digits / 2;

/// Unit vector (east, north) of an azimuth in degrees clockwise from north.
std::pair<double, double> axis(double azimuth_deg) {
  const double r = deg_to_rad(azimuth_deg);
  return {std::sin(r), std::cos(r)};
}

/// The components and the effective gravity on one grid (input_grid.hpp: jumps of any component kept). On a slope
/// (method.md eq S11) a1, a2 and gravity hold the in-plane load and the normal force of the inclined plane per point
/// instead (slope_loads()), and a still tail follows the record for the run-out.
struct Input {
  Input(const GroundMotion& first, const GroundMotion& second, const GroundMotion* vertical, const SlidingBlock& b,
        const ComponentAzimuths& az)
      : grid(std::array<const GroundMotion*, 3>{&first, &second, vertical}),
        a1(grid.accel_m_s2(0)),
        a2(grid.accel_m_s2(1)),
        gravity(effective_gravity(grid, 2, b.g_m_s2)),
        record_points(grid.size()) {
    if (b.slope_rad != 0.0) slope_loads(b, az);
  }
  InputGrid grid;
  std::span<const double> a1, a2;
  std::vector<double> gravity;  // g_e per point (on a slope: the normal force); empty without a vertical record
  std::vector<double> times;    // on a slope: the grid's times and the tail's
  std::vector<double> load1, load2;  // on a slope: the in-plane load's components (a1, a2 point to them)
  std::size_t record_points;         // the record's points (before the tail)
  [[nodiscard]] std::size_t size() const { return times.empty() ? grid.size() : times.size(); }
  [[nodiscard]] double time(std::size_t i) const { return times.empty() ? grid.time_s(i) : times[i]; }

 private:
  /// The inclined plane (eq S11): beta the slope, e_d the horizontal unit vector of the fall line (azimuth
  /// slope_azimuth_deg), the ground acceleration a = a_d e_d + a_c (a_c across the slope, horizontal and in the plane).
  /// Per unit mass, in the plane (the downslope in-plane axis carried on e_d) and normal to it:
  ///   w' = -a_c + (g_e sin(beta) - a_d cos(beta)) e_d - mu_k N+ w/|w|,   N = g_e cos(beta) + a_d sin(beta)
  /// (with a_d = -a_h this is sliding.hpp's f_t and n on the fall line): the level solver's equations with
  /// a -> a_c + (a_d cos(beta) - g_e sin(beta)) e_d and g_e -> N, both linear in time on a step as a and g_e are.
  /// After the record the ground is still (a = 0, g_e = g): a tail interval of constant load, long enough for any
  /// run-out, lets the same integration carry the (curved) run-out to its stop.
  void slope_loads(const SlidingBlock& b, const ComponentAzimuths& az) {
    const std::size_t n = grid.size();
    const double c = std::cos(b.slope_rad);
    const double s = std::sin(b.slope_rad);
    const auto [e1x, e1y] = axis(az.first_deg);
    const auto [e2x, e2y] = axis(az.second_deg);
    const auto [dx, dy] = axis(az.slope_azimuth_deg);
    const double d1 = dx * e1x + dy * e1y;  // e_d in the components' frame
    const double d2 = dx * e2x + dy * e2y;
    times.resize(n + 2);
    load1.resize(n + 2);
    load2.resize(n + 2);
    std::vector<double> normal(n + 2);
    double speed_bound = 0.0;  // integral of |load|: bounds |w| at the record's end (|w|' <= |load| while slipping)
    for (std::size_t i = 0; i < n; ++i) {
      const double ge = gravity.empty() ? b.g_m_s2 : gravity[i];
      const double ad = a1[i] * d1 + a2[i] * d2;
      const double along = ad * c - ge * s;
      load1[i] = a1[i] - ad * d1 + along * d1;
      load2[i] = a2[i] - ad * d2 + along * d2;
      normal[i] = ge * c + ad * s;
      times[i] = grid.time_s(i);
      if (i > 0) {
        speed_bound += 0.5 * (times[i] - times[i - 1]) *
                       (std::hypot(load1[i - 1], load2[i - 1]) + std::hypot(load1[i], load2[i]));
      }
    }
    // The tail: a jump to still ground at the record's end, held for the longest run-out: |w| falls at least at
    // g (mu_k cos(beta) - sin(beta)) on still ground. Where that is not positive the block can never stop: no tail.
    const double decel = b.g_m_s2 * (b.mu_kinetic * c - s);
    const double t_end = times[n - 1];
    const double tail = decel > 0.0 ? 1.01 * speed_bound / decel + 1.0 : 0.0;
    for (std::size_t i = n; i < n + 2; ++i) {
      times[i] = i == n ? t_end : t_end + tail;
      load1[i] = -b.g_m_s2 * s * d1;
      load2[i] = -b.g_m_s2 * s * d2;
      normal[i] = b.g_m_s2 * c;
    }
    if (!(tail > 0.0)) {
      times.resize(n);
      load1.resize(n);
      load2.resize(n);
      normal.resize(n);
    }
    gravity = std::move(normal);
    a1 = load1;
    a2 = load2;
  }
};

/// Right-hand side on one sample interval, in local time sigma = t - t_i: a = a0 + as sigma, g_e = g0 + gs sigma.
/// The friction direction is w / |w| continued through w = 0 by the sign of w . ref (see the header): smooth up to
/// and just past a stop, so that the event function w . ref has a simple root there. At w = 0 (slip onset) the
/// direction is ref itself, the onset direction -a / |a|.
///
/// Launch. Slip starts from rest in the direction -a (eq S5); while the speed is below the velocity tolerance the
/// direction of w is not resolved by the integration (the direction equation is stiff there, relaxing toward -a at
/// the rate |a| / |w|, docs/method.md), so until the speed first exceeds the launch speed (above) the
/// velocity is slaved to the quasi-static direction -a / |a|: w = r n, n = -a / |a|, r' = |a| - mu_k g_e+ (for
/// collinear input this is (S2) itself; in two dimensions the true lag of w behind -a there is |w| psi' / |a|, psi'
/// the turning rate of a: below 2e-4 rad at 3.2e-6 m/s (abs_tol 1e-10) for psi' = 60 rad/s and |a| = 1 m/s^2; about
/// 5e-13 m of displacement per episode, docs/method.md). The launch also ends where that lag would pass
/// kLaunchMaxLag (near a zero of a, where -a / |a| turns fast).
struct Rhs {
  double a01 = 0.0, a02 = 0.0, as1 = 0.0, as2 = 0.0, g0 = 0.0, gs = 0.0;
  double mu = 0.0;               // kinetic friction coefficient
  double ref1 = 1.0, ref2 = 0.0; // unit reference direction
  bool launch = false;           // friction along -a / |a| (launch phase)

  /// The input over the current step: a = (a01 + as1 sigma, a02 + as2 sigma), g_e = g0 + gs sigma.
  [[gnu::always_inline]] void set_step(double a01_, double a02_, double as1_, double as2_, double g0_, double gs_) {
    a01 = a01_;
    a02 = a02_;
    as1 = as1_;
    as2 = as2_;
    g0 = g0_;
    gs = gs_;
  }

  /// The reference of the stop test at the start tau of a step (state x, w0sq = |w|^2): in a launch the launch direction
  /// -a there (a != 0 in a launch, or the onset direction stays), else w / |w| (kept when w = 0).
  [[gnu::always_inline]] void set_stop_reference(const State& x, double tau, double w0sq) {
    if (launch) {
      const double b1 = a01 + as1 * tau;
      const double b2 = a02 + as2 * tau;
      const double bm = std::sqrt(b1 * b1 + b2 * b2);
      if (bm > 0.0) {
        ref1 = -b1 / bm;
        ref2 = -b2 / bm;
      }
    } else if (w0sq > 0.0) {
      const double inv = 1.0 / std::sqrt(w0sq);
      ref1 = x[kW1] * inv;
      ref2 = x[kW2] * inv;
    }
  }

  void operator()(const State& x, State& dx, double sigma) const {
    const double ax = a01 + as1 * sigma;
    const double ay = a02 + as2 * sigma;
    const double friction = mu * std::max(g0 + gs * sigma, 0.0);  // mu_k g_e+: no friction off the ground
    const double w1 = x[kW1];
    const double w2 = x[kW2];
    const double speed = std::sqrt(w1 * w1 + w2 * w2);
    dx[kPath] = speed;
    dx[kInputWork] = -(ax * w1 + ay * w2);
    dx[kFrictionWork] = friction * speed;
    dx[kU1] = w1;
    dx[kU2] = w2;
    const double amag = launch ? std::sqrt(ax * ax + ay * ay) : 0.0;  // a sqrt saved outside the launch
    if (launch && amag > 0.0) {
      // Slaved to the load's direction n = -a/|a|: w = r n with r' = |a| - mu_k g_e+ and n' = -(a' - n (a'.n))/|a|
      // (eq S5'), so w' = r' n + r n'.
      const double n1 = -ax / amag;
      const double n2 = -ay / amag;
      const double r = w1 * n1 + w2 * n2;
      const double along = as1 * n1 + as2 * n2;
      const double dn1 = -(as1 - n1 * along) / amag;
      const double dn2 = -(as2 - n2 * along) / amag;
      dx[kW1] = (amag - friction) * n1 + r * dn1;
      dx[kW2] = (amag - friction) * n2 + r * dn2;
      return;
    }
    double n1 = ref1;
    double n2 = ref2;
    if (speed > 0.0) {
      const double inv = (w1 * ref1 + w2 * ref2 < 0.0 ? -1.0 : 1.0) / speed;
      n1 = w1 * inv;
      n2 = w2 * inv;
    }
    dx[kW1] = -ax - friction * n1;  // w' = -a - mu_k g_e+ w/|w|  (method.md, eq S2)
    dx[kW2] = -ay - friction * n2;
  }
};

/// Summary and (optionally) history, in the components' frame; rows are mapped to east/north as they are stored.
template <bool kRecord>
struct Recorder {
  Sliding2dSummary summary;
  Sliding2dHistory history;
  double slip_start = 0.0;
  // Columns of the frame change (east, north) of axis 1 and axis 2.
  double e1x = 0.0, e1y = 0.0, e2x = 0.0, e2y = 0.0;

  void row(double t, const State& x, bool slipping) {
    if constexpr (kRecord) {
      history.time_s.push_back(t);
      history.east_m.push_back(e1x * x[kU1] + e2x * x[kU2]);
      history.north_m.push_back(e1y * x[kU1] + e2y * x[kU2]);
      history.east_m_s.push_back(e1x * x[kW1] + e2x * x[kW2]);
      history.north_m_s.push_back(e1y * x[kW1] + e2y * x[kW2]);
      history.slipping.push_back(slipping ? 1 : 0);
    }
  }
  void track_displacement(double t, double u1, double u2) {
    const double r = std::sqrt(u1 * u1 + u2 * u2);
    if (r > summary.max_abs_displacement_m) {
      summary.max_abs_displacement_m = r;
      summary.max_displacement_time_s = t;
    }
  }
  void track_speed(double w1, double w2) {
    summary.max_abs_velocity_m_s = std::max(summary.max_abs_velocity_m_s, std::sqrt(w1 * w1 + w2 * w2));
  }
  void start(double t) {
    ++summary.slip_episodes;
    if (!summary.first_slip_time_s) summary.first_slip_time_s = t;
    slip_start = t;
  }
  void stop(double t) {
    summary.total_slip_duration_s += t - slip_start;
    last_stop = t;
  }
  /// Relative rest at t inside a step (state x): the slip's end, its displacement tracked, a row.
  void rest(double t, const State& x) {
    stop(t);
    track_displacement(t, x[kU1], x[kU2]);
    row(t, x, false);
  }
  double last_stop = 0.0;
};

/// Tables of inverse_fifth_root (below), filled once at start-up.
struct FifthRootTables {
  std::array<double, 5> exponent{};    // 2^(-r/5)
  std::array<double, 256> mantissa{};  // (1 + (j + 1/2) / 256)^(-1/5)
};
const FifthRootTables kFifthRoots = [] {
  FifthRootTables t;
  for (std::size_t r = 0; r < t.exponent.size(); ++r) t.exponent[r] = std::exp2(-static_cast<double>(r) / 5.0);
  for (std::size_t j = 0; j < t.mantissa.size(); ++j) {
    t.mantissa[j] = std::pow(1.0 + (static_cast<double>(j) + 0.5) / 256.0, -0.2);
  }
  return t;
}();

/// x^(-1/5) to 4e-4 relative (half the largest change of m^(-1/5) over a table cell, 0.2 / 512) for x in
/// [1e-7, 1e4], the argument clamped to that range: the factors above saturate outside it (0.9 x^(-1/5) >= 10 for
/// x <= 5.9e-6, <= 0.2 for x >= 1845), so the clamp changes no factor. A step-size factor needs no more digits (it
/// carries the safety factor 0.9): the step's acceptance (err <= 1) is decided exactly by the error checker. With
/// x = m 2^e (m in [1, 2)) and e = 5k + r (r in 0..4): x^(-1/5) = 2^(-k) 2^(-r/5) m^(-1/5), the last two from
/// tables (m^(-1/5) at the midpoints of 256 cells on the top 8 bits of m's fraction).
[[nodiscard]] double inverse_fifth_root(double x) {
  x = std::clamp(x, 1e-7, 1e4);
  if (!(x == x)) return x;  // NaN passes through, as from std::pow
  const auto bits = std::bit_cast<std::uint64_t>(x);
  const int e = static_cast<int>(bits >> 52) - 1023;  // x is positive and normal here
  const int k = (e + 1000) / 5 - 200;                  // floor(e / 5) for e >= -1000
  const int r = e - 5 * k;
  const double two_k = std::bit_cast<double>(static_cast<std::uint64_t>(1023 - k) << 52);  // 2^(-k)
  return two_k * kFifthRoots.exponent[static_cast<std::size_t>(r)] *
         kFifthRoots.mantissa[static_cast<std::size_t>((bits >> 44) & 255U)];
}

/// Boost.Odeint's step adjuster interface with the step law of Hairer, Norsett & Wanner's DOPRI5 (I, II.4, eq 4.13
/// and the code's fac = 0.9, facl = 0.2, facr = 10, with the PI term's beta 0, where the code has 0.04, which took 3 %
/// more tries here): dt *= min(0.9 err^(-1/5), 10) after an
/// accepted step, dt *= max(0.9 err^(-1/5), 0.2) after a rejected one. Odeint's default keeps dt for 0.5 <= err <= 1,
/// grows it at most 4.5x and shrinks it with err^(-1/3); where stability and the direction's relaxation hold the step
/// near its limit (the low speeds) that took 7 % more tries on the benchmark (docs/performance.md).
/// err^(-1/5) is computed by inverse_fifth_root, not std::pow: libm's pow was 15 % of the run time of the 95 %-stuck
/// benchmark (perf, docs/performance.md), one call per try.
struct StepAdjuster {
  using time_type = double;
  using value_type = double;
  [[nodiscard]] double decrease_step(double dt, double error, int /*error_order*/) const {
    return dt * std::max(0.9 * inverse_fifth_root(error), 0.2);
  }
  [[nodiscard]] double increase_step(double dt, double error, int /*stepper_order*/) const {
    return dt * std::min(0.9 * inverse_fifth_root(error), 10.0);
  }
  [[nodiscard]] bool check_step_size_limit(double /*dt*/) const { return true; }
  [[nodiscard]] double get_max_dt() const { return 0.0; }
};

/// Dormand-Prince 5(4) with error control (Boost.Odeint) over one sample interval's local time, with dense output.
class Stepper {
 public:
  using Dopri = odeint::runge_kutta_dopri5<State>;
  using Checker = odeint::default_error_checker<double, Dopri::algebra_type, Dopri::operations_type>;
  using Controlled = odeint::controlled_runge_kutta<Dopri, Checker, StepAdjuster>;

  Stepper(const Sliding2dOptions& o, double dt0)
      : controlled_(Checker(o.abs_tol, o.rel_tol, 1.0, 0.0), StepAdjuster{}), dt_(dt0) {}

  /// One accepted step from (s0, x0, dx0) toward s_limit (never past it). Counts tries in `steps`; false when the
  /// cap is reached.
  // flatten: Odeint's step and the right-hand side inlined into it, as GCC did on its own before integrate's helpers
  // grew the unit (without it, 4 % more instructions in bench_sliding2d: the stages called out of line).
  [[nodiscard, gnu::flatten]] bool step(const Rhs& rhs, double s0, const State& x0, const State& dx0, double s_limit,
                                        std::size_t& steps, std::size_t max_steps) {
    s0_ = s0;
    x0_ = x0;
    dx0_ = dx0;
    const double remaining = s_limit - s0;
    bool rejected = false;
    for (;;) {
      if (++steps > max_steps) return false;
      const bool clamped = dt_ >= remaining;
      double dt = clamped ? remaining : dt_;
      const double tried = dt;
      double s = s0;
      if (controlled_.try_step(std::cref(rhs), x0_, dx0_, s, x1_, dx1_, dt) == odeint::success) {
        s1_ = clamped ? s_limit : s;
        // A step cut short to end on a sample says little about the step the solution allows.
        dt_ = clamped ? std::max(dt_, dt) : dt;
        // No growth right after a rejection (Hairer, Norsett & Wanner I, II.4, after (4.13)): where stability, not
        // accuracy, limits the step (the stiff low speeds), growing again at once is rejected again.
        if (rejected) dt_ = std::min(dt_, tried);
        return true;
      }
      rejected = true;
      dt_ = dt;  // rejected: the controller reduced it
    }
  }
  /// The state at s in [s0, s1] of the last accepted step (4th-order continuous extension, Hairer et al. II.6).
  [[nodiscard]] State dense(double s) const {
    if (s == s1_) return x1_;
    State x{};
    controlled_.stepper().calc_state(s, x, x0_, dx0_, s0_, x1_, dx1_, s1_);
    return x;
  }
  void halve() { dt_ = 0.5 * (s1_ - s0_); }
  [[nodiscard]] double s1() const { return s1_; }
  [[nodiscard]] const State& x1() const { return x1_; }
  [[nodiscard]] const State& dx1() const { return dx1_; }

 private:
  Controlled controlled_;
  double dt_;
  double s0_ = 0.0, s1_ = 0.0;
  State x0_{}, dx0_{}, x1_{}, dx1_{};
};

std::string describe(const SlidingBlock& b) {
  return fmt::format("mu_static = {:.6g}, mu_kinetic = {:.6g}", b.mu_static, b.mu_kinetic);
}

/// Smallest sigma in [0, L] where h(sigma) = |p + q sigma| - mu (g0 + gs sigma) crosses zero upward, given
/// h(0) <= 0 < h(L). h is convex, so there is exactly one crossing; it is the root of the quadratic
/// |p + q sigma|^2 - mu^2 (g0 + gs sigma)^2 with g_e >= 0 there (method.md, eq S4), solved cancellation-free; TOMS 748
/// on h guards the case where round-off puts the closed-form root outside the bracket. NaN when TOMS 748 ran out.
double onset(double p1, double p2, double q1, double q2, double g0, double gs, double mu, double L) {
  const double A = q1 * q1 + q2 * q2 - mu * mu * gs * gs;
  const double B = 2.0 * (p1 * q1 + p2 * q2 - mu * mu * g0 * gs);
  const double C = p1 * p1 + p2 * p2 - mu * mu * g0 * g0;
  double roots[2] = {-1.0, -1.0};
  if (A == 0.0) {
    if (B != 0.0) roots[0] = -C / B;
  } else {
    const double disc = B * B - 4.0 * A * C;
    if (disc >= 0.0) {
      const double qq = -0.5 * (B + std::copysign(std::sqrt(disc), B));  // Press et al., Numerical Recipes 5.6
      roots[0] = qq / A;
      if (qq != 0.0) roots[1] = C / qq;
    }
  }
  const double slack = 1e-12 * L;  // a root within round-off of the bracket's ends is clamped into it
  double best = std::numeric_limits<double>::infinity();
  for (double r : roots) {
    if (!(r >= -slack && r <= L + slack)) continue;
    r = std::clamp(r, 0.0, L);
    if (g0 + gs * r >= 0.0) best = std::min(best, r);  // |a| = +mu g_e, not -mu g_e
  }
  if (best <= L) return best;
  const auto h = [&](double s) { return std::hypot(p1 + q1 * s, p2 + q2 * s) - mu * (g0 + gs * s); };
  boost::uintmax_t iterations = kMaxRootIterations;
  const auto tol = [](double lo, double hi) {
    return std::abs(hi - lo) <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(hi), 1e-300);
  };
  const double h0 = h(0.0);
  if (h0 >= 0.0) return 0.0;
  const double hL = h(L);
  if (!(hL > 0.0)) return L;  // the squared test and h disagree at the end by round-off: slip starts there
  const auto bracket = boost::math::tools::toms748_solve(h, 0.0, L, h0, hL, tol, iterations);
  if (iterations >= kMaxRootIterations) return std::numeric_limits<double>::quiet_NaN();
  return bracket.second;
}

/// Where e = w . ref, positive at the step's start, falls to e1 <= 0 inside the accepted step [tau, s1] (dense output:
/// TOMS 748): the velocity reached zero (a stop) or turned by 90 degrees or more (no stop), told apart by |w| there
/// (w0sq: |w|^2 at the step's start). True for a stop, at s_end with the state x_end there.
[[gnu::noinline]] bool locate_stop(const Stepper& stepper, const Rhs& rhs, const State& x, double tau, double e1, double w0sq,
                        double floor_speed, const Sliding2dOptions& opt, const SlidingBlock& b, double t_i,
                        double& s_end, State& x_end) {
  const double s1 = stepper.s1();
  const State& x1 = stepper.x1();
  const auto e = [&](double s) {
    const State xs = stepper.dense(s);
    return xs[kW1] * rhs.ref1 + xs[kW2] * rhs.ref2;
  };
  double lo = tau;
  double e_lo = x[kW1] * rhs.ref1 + x[kW2] * rhs.ref2;
  if (!(e_lo > 0.0)) {  // onset step (w = 0 at its start): e grows first; the first positive point brackets
    lo = s1;
    for (int k = 1; k < 8; ++k) {
      const double s = tau + (s1 - tau) * k / 8.0;
      const double es = e(s);
      if (es > 0.0) {
        lo = s;
        e_lo = es;
        break;
      }
    }
  }
  bool is_stop = false;
  if (!(lo < s1)) {
    // From rest and never moving forward along the launch direction: the load does not overcome kinetic
    // friction (an onset decided by round-off at |a| = mu_s g_e with |a| falling): the block is at rest at
    // the step's end, having moved no more than |w| x the step (below the tolerance).
    is_stop = true;
  } else {
    boost::uintmax_t iterations = kMaxRootIterations;
    const auto tol = [](double l, double r) {
      return std::abs(r - l) <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(r), 1e-300);
    };
    const auto bracket = boost::math::tools::toms748_solve(e, lo, s1, e_lo, e1, tol, iterations);
    if (iterations >= kMaxRootIterations) {
      throw RootFindingError(fmt::format("bidirectional sliding: the slip stop (TOMS 748) did not converge in {} "
                                         "iterations in the step [{}, {}] s ({})",
                                         kMaxRootIterations, t_i + tau, t_i + s1, describe(b)));
    }
    s_end = bracket.second;
    x_end = stepper.dense(s_end);
    const double scale = std::max(std::sqrt(w0sq), std::hypot(x1[kW1], x1[kW2]));
    const double rest = std::hypot(x_end[kW1], x_end[kW2]);
    // Or at the velocity noise floor (below): a zero of w . ref where |w| is that small is a stop whatever the
    // step's scale, as a block slowing to the floor is (the direction is not resolved there, and halving the
    // step would not resolve it either: EventLimitError at the default tolerances otherwise, seen in
    // Recovery3c).
    is_stop = rest <= kStopSpeedFraction * scale + 10.0 * opt.abs_tol || rest <= floor_speed;
  }
  return is_stop;
}

/// The run-in to rest from the velocity noise floor. Back down to the floor, the integration no longer resolves the
/// direction of w (the direction equation is stiff there: its rate |a| / |w| exceeds the explicit method's stability
/// limit at any step the error test allows, so w would wander at the tolerance level). The block has come to rest:
/// the rest of the run-in, along the current direction, is |w| / (mu_k g_e + a . w/|w|) long and covers |w| times half
/// that (when decelerating at 0.01 m/s^2: 4.5e-11 m from the default floor of 9.5e-7 m/s, 5e-13 m from 1e-7 m/s at
/// abs_tol 1e-10), of which the extrapolation's error, from the deceleration and direction changing over the run-in,
/// is a small fraction (docs/method.md); when w is not decelerating along its own direction the stop is taken at once.
/// From the end s1 of an accepted step (state x1), at most to the step's end h: sets s_end and adds the run-in to x_end
/// (a copy of x1).
[[gnu::noinline]] void run_in_to_rest(const Rhs& rhs, const State& x1, double s1, double h, double& s_end,
                                      State& x_end) {
  const double b1 = rhs.a01 + rhs.as1 * s1;
  const double b2 = rhs.a02 + rhs.as2 * s1;
  const double friction = rhs.mu * std::max(rhs.g0 + rhs.gs * s1, 0.0);
  const double speed = std::hypot(x1[kW1], x1[kW2]);
  const double decel = speed > 0.0 ? friction + (b1 * x1[kW1] + b2 * x1[kW2]) / speed : 0.0;
  double run = decel > 0.0 ? speed / decel : 0.0;
  run = std::min(run, h - s1);
  s_end = s1 + run;
  x_end[kU1] += 0.5 * run * x1[kW1];
  x_end[kU2] += 0.5 * run * x1[kW2];
  x_end[kPath] += 0.5 * run * speed;
  x_end[kInputWork] -= 0.5 * run * (b1 * x1[kW1] + b2 * x1[kW2]);
  x_end[kFrictionWork] += 0.5 * run * friction * speed;
}

/// The extremes inside an accepted step [tau, s_end] (state x, derivative dx at its start; x_end at its end, stopped:
/// the block came to rest there): |w| peaks where w . w' turns from + to -, |u| where u . w does (Brent on the dense
/// output; the ends are checked directly by the caller).
template <bool kRecord>
[[gnu::always_inline]] inline void track_step_extremes(const Stepper& stepper, Recorder<kRecord>& rec, const State& x,
                                                       const State& dx, const State& x_end, double tau, double s_end,
                                                       double t_i, bool stopped) {
  const State& x1 = stepper.x1();
  const double ww0 = x[kW1] * dx[kW1] + x[kW2] * dx[kW2];
  const double ww1 = stopped ? -1.0 : x1[kW1] * stepper.dx1()[kW1] + x1[kW2] * stepper.dx1()[kW2];
  if (ww0 > 0.0 && ww1 < 0.0) {
    const auto neg_speed_sq = [&](double s) {
      const State xs = stepper.dense(s);
      return -(xs[kW1] * xs[kW1] + xs[kW2] * xs[kW2]);
    };
    const auto best = boost::math::tools::brent_find_minima(neg_speed_sq, tau, s_end, kBrentBits);
    rec.summary.max_abs_velocity_m_s = std::max(rec.summary.max_abs_velocity_m_s, std::sqrt(-best.second));
  }
  const double uw0 = x[kU1] * x[kW1] + x[kU2] * x[kW2];
  const double uw1 = x_end[kU1] * x_end[kW1] + x_end[kU2] * x_end[kW2];
  if (uw0 > 0.0 && (stopped || uw1 < 0.0)) {
    const auto neg_disp_sq = [&](double s) {
      const State xs = stepper.dense(s);
      return -(xs[kU1] * xs[kU1] + xs[kU2] * xs[kU2]);
    };
    const auto best = boost::math::tools::brent_find_minima(neg_disp_sq, tau, s_end, kBrentBits);
    const State xs = stepper.dense(best.first);
    rec.track_displacement(t_i + best.first, xs[kU1], xs[kU2]);
  }
}

/// The launch's end and the landing (see Rhs) after an accepted step ending at tau with state x: the launch ends at
/// the launch speed or where its quasi-static direction lags too far; a slow, decelerating block along -a lands
/// (slaved to -a / |a|). Either change of the RHS invalidates its FSAL value (dx_valid).
[[gnu::always_inline]] inline void update_launch(Rhs& rhs, State& x, double tau, double launch_speed, bool& dx_valid) {
  if (rhs.launch) {
    // The launch ends at the launch speed, or earlier where the quasi-static direction stops being a good
    // approximation: its lag behind -a, delta = r psi' / |a| = r |a x a'| / |a|^3 (psi' the turning rate of a),
    // exceeds kLaunchMaxLag (near a zero of a, where -a / |a| turns fast, docs/method.md S5').
    const double c1 = rhs.a01 + rhs.as1 * tau;
    const double c2 = rhs.a02 + rhs.as2 * tau;
    const double cm = std::sqrt(c1 * c1 + c2 * c2);
    const double r = std::sqrt(x[kW1] * x[kW1] + x[kW2] * x[kW2]);
    if (r > launch_speed || r * std::abs(c1 * rhs.as2 - c2 * rhs.as1) > kLaunchMaxLag * cm * cm * cm) {
      rhs.launch = false;  // w / |w| from here on: the RHS changes, so no FSAL
      dx_valid = false;
    }
  } else if (x[kW1] * x[kW1] + x[kW2] * x[kW2] < launch_speed * launch_speed) {
    // Landing (see kLandingEntryLagFraction): below the launch speed, decelerating, w already along -a to within
    // kLaunchMaxLag and the quasi-static lag r |a x a'| / |a|^3 small: slaved to -a / |a| from here (w is put on
    // that direction; what is dropped, r sin(angle) < kLaunchMaxLag r across it, is the lag the quasi-static
    // state neglects anyway), to the stop, or until the lag grows (the launch's exit test above).
    const double c1 = rhs.a01 + rhs.as1 * tau;
    const double c2 = rhs.a02 + rhs.as2 * tau;
    const double cm = std::sqrt(c1 * c1 + c2 * c2);
    const double friction = rhs.mu * std::max(rhs.g0 + rhs.gs * tau, 0.0);
    const double r = std::sqrt(x[kW1] * x[kW1] + x[kW2] * x[kW2]);
    if (cm > 0.0 && cm < friction && r > 0.0) {
      const double n1 = -c1 / cm;
      const double n2 = -c2 / cm;
      const bool along = x[kW1] * n1 + x[kW2] * n2 > 0.0 && std::abs(x[kW1] * n2 - x[kW2] * n1) < kLaunchMaxLag * r;
      if (along && r * std::abs(c1 * rhs.as2 - c2 * rhs.as1) < kLandingEntryLagFraction * kLaunchMaxLag * cm * cm * cm) {
        rhs.launch = true;
        x[kW1] = r * n1;
        x[kW2] = r * n2;
        dx_valid = false;
      }
    }
  }
}

/// After the last point: the run-out on still ground (or the end of the slope's still tail), the totals of the summary
/// and the residual mapped to east/north. x and slipping: the state after the last point; steps: integrator steps.
template <bool kRecord>
[[gnu::noinline]] void finish(const Input& in, const SlidingBlock& b, Recorder<kRecord>& rec, State& x, bool slipping,
            std::size_t steps) {
  const std::size_t n = in.size();
  const double g = b.g_m_s2;
  const double t_end = in.time(in.record_points - 1);
  rec.summary.end_time_s = t_end;
  if (in.size() > in.record_points) {
    // On a slope the still tail carried the run-out (Input::slope_loads); the block is at rest at its end.
    if (slipping) {
      throw std::logic_error(fmt::format("bidirectional sliding: the block still slides at the end of the run-out "
                                         "interval ({} s; {})", in.time(n - 1), describe(b)));
    }
    if (rec.summary.slip_episodes > 0) rec.summary.end_time_s = std::max(t_end, rec.last_stop);
    if constexpr (kRecord) {  // the tail's end point is no sample of the record
      rec.history.time_s.pop_back();
      rec.history.east_m.pop_back();
      rec.history.north_m.pop_back();
      rec.history.east_m_s.pop_back();
      rec.history.north_m_s.pop_back();
      rec.history.slipping.pop_back();
    }
  } else if (slipping && b.slope_rad != 0.0) {
    rec.summary.at_rest_at_end = false;  // tan(beta) >= mu_k: it slides on down the slope
    rec.stop(t_end);
  } else if (slipping) {
    // Run-out on still ground (a = 0, g_e = g): friction alone, along a straight line (eq S7).
    const double speed = std::hypot(x[kW1], x[kW2]);
    const double decel = b.mu_kinetic * g;
    if (decel > 0.0) {
      const double sigma = speed / decel;
      x[kU1] += 0.5 * sigma * x[kW1];
      x[kU2] += 0.5 * sigma * x[kW2];
      x[kPath] += 0.5 * sigma * speed;
      x[kFrictionWork] += 0.5 * speed * speed;
      x[kW1] = 0.0;
      x[kW2] = 0.0;
      rec.stop(t_end + sigma);
      rec.track_displacement(t_end + sigma, x[kU1], x[kU2]);
      rec.row(t_end + sigma, x, false);
      rec.summary.end_time_s = t_end + sigma;
    } else {
      rec.summary.at_rest_at_end = false;
      rec.stop(t_end);
    }
  }
  rec.track_displacement(rec.summary.end_time_s, x[kU1], x[kU2]);
  rec.summary.path_length_m = x[kPath];
  rec.summary.input_work_J_kg = x[kInputWork];
  rec.summary.friction_work_J_kg = x[kFrictionWork];
  rec.summary.integrator_steps = steps;
  // The residual, mapped to east/north.
  const double east = rec.e1x * x[kU1] + rec.e2x * x[kU2];
  const double north = rec.e1y * x[kU1] + rec.e2y * x[kU2];
  rec.summary.residual_east_m = east;
  rec.summary.residual_north_m = north;
  rec.summary.residual_displacement_m = std::hypot(east, north);
  if (east != 0.0 || north != 0.0) {
    double az = rad_to_deg(std::atan2(east, north));  // clockwise from north
    if (az < 0.0) az += 360.0;
    if (az >= 360.0) az -= 360.0;
    rec.summary.residual_azimuth_deg = az;
  }
}

[[noreturn]] void too_many_steps(const Sliding2dOptions& opt, const SlidingBlock& b, double t) {
  throw StepLimitError(fmt::format("bidirectional sliding: more than {} integrator steps (max_steps) by t = {} s "
                                   "({}, rel_tol = {:g}, abs_tol = {:g})",
                                   opt.max_steps, t, describe(b), opt.rel_tol, opt.abs_tol));
}

[[noreturn]] void too_many_events(const SlidingBlock& b, double t) {
  throw EventLimitError(fmt::format("bidirectional sliding: more than {} slip starts and stops in the step at t = {} "
                                    "s ({}): the input is outside the model (check its accelerations)",
                                    kMaxEventsPerStep, t, describe(b)));
}

/// Stick phase from point i, where the block sticks: one comparison per point (the stick test is convex in time over a
/// step, eq S3), to the last point before the test fails (n - 1 when it never does), each point a row of the history.
/// Without history nor vertical input, eight points at a time first, branch-free inside (vectorises); stick_sq is
/// (mu_s g)^2 there.
template <bool kVertical, bool kRecord, class Sticks>
[[gnu::always_inline]] inline std::size_t skip_stuck_points(const Input& in, const double* a1, const double* a2,
                                                            double stick_sq, const Sticks& sticks_at, std::size_t i,
                                                            Recorder<kRecord>& rec, const State& x) {
  const std::size_t n = in.size();
  if constexpr (!kRecord && !kVertical) {
    // Eight points at a time, branch-free inside (vectorises), then one by one to the exceedance.
    while (i + 8 < n) {
      bool out = false;
      for (std::size_t j = 1; j <= 8; ++j) out |= a1[i + j] * a1[i + j] + a2[i + j] * a2[i + j] > stick_sq;
      if (out) break;
      i += 8;
    }
  }
  while (i + 1 < n && sticks_at(i + 1)) {
    ++i;
    rec.row(in.time(i), x, false);
  }
  return i;
}

/// A slip start: at sigma after the offset it was looked for from, in the direction (ref1, ref2) of the inertial load.
struct SlipStart {
  double sigma = 0.0;
  double ref1 = 0.0, ref2 = 0.0;
};

/// Where the stuck block starts to slip in the step [ti, ti + hi] of point i, from the offset tau: the stick test is
/// convex in time over the step (eq S3), so it fails inside it iff it fails at an end, first at the onset's root.
/// None when it holds to the step's end, in a jump (the next point's test decides), or off the ground under a still
/// ground. `gravity(i)` is g_e at point i, `sticks_at(i)` the stick test there.
template <class Gravity, class Sticks>
[[gnu::noinline]] std::optional<SlipStart> slip_onset(const double* a1, const double* a2, const Gravity& gravity,
                                                      const Sticks& sticks_at, std::size_t i, double ti, double hi,
                                                      double tau, double mus, const SlidingBlock& b) {
  const double L = hi - tau;
  const double frac = hi > 0.0 ? tau / hi : 0.0;
  const double p1 = a1[i] + frac * (a1[i + 1] - a1[i]);
  const double p2 = a2[i] + frac * (a2[i + 1] - a2[i]);
  const double g0 = gravity(i) + frac * (gravity(i + 1) - gravity(i));
  const double q1 = L > 0.0 ? (a1[i + 1] - p1) / L : 0.0;
  const double q2 = L > 0.0 ? (a2[i + 1] - p2) / L : 0.0;
  const double gs = L > 0.0 ? (gravity(i + 1) - g0) / L : 0.0;
  const bool stick_now = g0 >= 0.0 && p1 * p1 + p2 * p2 <= mus * mus * g0 * g0;
  if ((stick_now && sticks_at(i + 1)) || !(L > 0.0)) {
    // Stuck to the step's end; or a jump, where nothing moves and the next point's test decides.
    return std::nullopt;
  }
  double sigma = 0.0;
  if (stick_now) {
    sigma = onset(p1, p2, q1, q2, g0, gs, mus, L);
    if (std::isnan(sigma)) {
      throw RootFindingError(fmt::format("bidirectional sliding: the slip onset (TOMS 748) did not converge in {} "
                                         "iterations in the step [{}, {}] s ({})",
                                         kMaxRootIterations, ti, ti + hi, describe(b)));
    }
  }
  // Slip starts at tau + sigma in the direction of the inertial load -a (eq S5).
  const double s1 = p1 + q1 * sigma;
  const double s2 = p2 + q2 * sigma;
  double norm = std::sqrt(s1 * s1 + s2 * s2);
  double d1 = -s1;
  double d2 = -s2;
  if (!(norm > 0.0)) {  // off the ground with a = 0 at the onset: the direction a takes next
    d1 = -q1;
    d2 = -q2;
    norm = std::sqrt(q1 * q1 + q2 * q2);
  }
  if (!(norm > 0.0)) return std::nullopt;  // off the ground under a still ground: nothing moves
  return SlipStart{sigma, d1 / norm, d2 / norm};
}

/// The solver core. kVertical: g_e varies per point; kRecord: store the history.
template <bool kVertical, bool kRecord>
void integrate(const Input& in, const SlidingBlock& b, const Sliding2dOptions& opt, Recorder<kRecord>& rec) {
  const std::size_t n = in.size();
  const double* a1 = in.a1.data();
  const double* a2 = in.a2.data();
  const double* ge = kVertical ? in.gravity.data() : nullptr;
  const double g = b.g_m_s2;
  const double mus = b.mu_static;
  const auto gravity = [&](std::size_t i) { return kVertical ? ge[i] : g; };
  // Stick test at a point: |a| <= mu_s g_e (eq S3), squared; g_e < 0 (off the ground) never sticks.
  const double stick_sq = mus * mus * g * g;
  const auto sticks_at = [&](std::size_t i) {
    const double asq = a1[i] * a1[i] + a2[i] * a2[i];
    if constexpr (kVertical) {
      return ge[i] >= 0.0 && asq <= mus * mus * ge[i] * ge[i];
    } else {
      return asq <= stick_sq;
    }
  };

  State x{};
  State dx{};
  bool slipping = false;
  bool dx_valid = false;  // dx holds the RHS at (tau, x) of the current interval (FSAL across samples)
  double tau = 0.0;       // offset inside the current step, s
  int events_in_step = 0;
  std::size_t steps = 0;
  Rhs rhs;
  rhs.mu = b.mu_kinetic;
  Stepper stepper(opt, in.grid.dt_s());
  // Below this speed, at a slip onset, the friction direction is the onset limit -a / |a| (see Rhs).
  const double launch_speed =
      std::max(std::sqrt(opt.abs_tol * kLaunchSpeedScale), kLaunchSpeedTolerances * opt.abs_tol);
  // A block slowing down to this speed has stopped (see below).
  const double floor_speed = kFloorLaunchFraction * launch_speed;
  rec.row(in.time(0), x, false);
  rec.summary.max_displacement_time_s = in.time(0);

  std::size_t i = 0;
  // On to the next point (the rows at points carry the state there, slipping or not).
  const auto next_point = [&](bool slip) {
    ++i;
    tau = 0.0;
    events_in_step = 0;
    rec.row(in.time(i), x, slip);
  };
  while (i + 1 < n) {
    const double t_i = in.time(i);
    const double h = in.time(i + 1) - t_i;
    if (!slipping) {
      if (tau == 0.0) {
        // Stick phase: one comparison per point (the stick test is convex in time over a step, eq S3).
        if (sticks_at(i)) {
          i = skip_stuck_points<kVertical>(in, a1, a2, stick_sq, sticks_at, i, rec, x);
          if (i + 1 >= n) break;
        }
      }
      const double ti = in.time(i);
      const double hi = in.time(i + 1) - ti;
      const auto start = slip_onset(a1, a2, gravity, sticks_at, i, ti, hi, tau, mus, b);
      if (!start) {  // stuck to the step's end; or a jump, or off the ground under a still ground: nothing moves
        next_point(false);
        continue;
      }
      rhs.ref1 = start->ref1;
      rhs.ref2 = start->ref2;
      rhs.launch = true;
      tau = std::min(tau + start->sigma, hi);
      slipping = true;
      dx_valid = false;
      rec.start(ti + tau);
      rec.row(ti + tau, x, true);
      if (++events_in_step > kMaxEventsPerStep) too_many_events(b, ti);
      continue;
    }

    // Slipping over [tau, h] of step i (local time).
    if (!(h > tau)) {  // a jump: nothing moves during it; the RHS changes across it
      dx_valid = false;
      next_point(true);
      continue;
    }
    rhs.set_step(a1[i], a2[i], (a1[i + 1] - a1[i]) / h, (a2[i + 1] - a2[i]) / h, gravity(i),
                 (gravity(i + 1) - gravity(i)) / h);
    bool stopped = false;
    int halvings = 0;
    while (tau < h) {
      const double w0sq = x[kW1] * x[kW1] + x[kW2] * x[kW2];
      rhs.set_stop_reference(x, tau, w0sq);
      if (!dx_valid) rhs(x, dx, tau);
      if (!stepper.step(rhs, tau, x, dx, h, steps, opt.max_steps)) too_many_steps(opt, b, t_i + tau);
      const State& x1 = stepper.x1();
      const double s1 = stepper.s1();
      const double e1 = x1[kW1] * rhs.ref1 + x1[kW2] * rhs.ref2;
      double s_end = s1;
      State x_end = x1;
      if (e1 <= 0.0) {
        // The velocity reached zero (a stop) or turned by 90 degrees or more (no stop): locate the zero of
        // e = w . ref on the dense output, then tell the two apart by |w| there.
        const bool is_stop = locate_stop(stepper, rhs, x, tau, e1, w0sq, floor_speed, opt, b, t_i, s_end, x_end);
        if (!is_stop) {
          if (++halvings > kMaxTurnHalvings) {
            throw EventLimitError(fmt::format("bidirectional sliding: the relative velocity turns by 90 degrees in "
                                              "steps of {} s at t = {} s ({}): outside the model", s1 - tau,
                                              t_i + tau, describe(b)));
          }
          stepper.halve();
          continue;  // the same start, a shorter step
        }
        stopped = true;
      } else if (!rhs.launch && x1[kW1] * x1[kW1] + x1[kW2] * x1[kW2] <= floor_speed * floor_speed) {
        // Back down to the velocity noise floor: the block has come to rest (run_in_to_rest); the stick test then
        // decides (eq S6).
        run_in_to_rest(rhs, x1, s1, h, s_end, x_end);
        stopped = true;
      }
      // Extremes inside [tau, s_end]: |w| peaks where w . w' turns from + to -, |u| where u . w does (Brent on the
      // dense output; the ends are checked directly).
      track_step_extremes(stepper, rec, x, dx, x_end, tau, s_end, t_i, stopped);
      tau = s_end;
      x = x_end;
      halvings = 0;
      if (stopped) {
        x[kW1] = 0.0;
        x[kW2] = 0.0;
        dx_valid = false;
        break;
      }
      dx = stepper.dx1();
      dx_valid = true;
      update_launch(rhs, x, tau, launch_speed, dx_valid);
      rec.track_speed(x[kW1], x[kW2]);
      rec.track_displacement(t_i + tau, x[kU1], x[kU2]);
    }
    if (stopped) {
      // Relative rest: the stick test at the top of the loop decides whether it holds or slip restarts (eq S6).
      slipping = false;
      rec.rest(t_i + tau, x);
      if (++events_in_step > kMaxEventsPerStep) too_many_events(b, t_i);
      if (tau >= h) {
        next_point(false);
      }
      continue;
    }
    next_point(true);
  }

  finish(in, b, rec, x, slipping, steps);
}

/// First time g_e <= 0 (linear per step).
std::optional<double> contact_lost(const Input& in) {
  if (in.gravity.empty()) return std::nullopt;
  double prev = in.gravity[0];
  if (prev <= 0.0) return in.time(0);
  for (std::size_t i = 1; i < in.size(); ++i) {
    const double cur = in.gravity[i];
    if (cur <= 0.0) return in.time(i - 1) + (in.time(i) - in.time(i - 1)) * prev / (prev - cur);
    prev = cur;
  }
  return std::nullopt;
}

void check_inputs(const ComponentAzimuths& az, const SlidingBlock& b, const Sliding2dOptions& opt) {
  opt.validate();
  for (const auto& [field, value] : {std::pair{"first_azimuth", az.first_deg}, std::pair{"second_azimuth",
                                                                                         az.second_deg}}) {
    if (!std::isfinite(value) || std::abs(value) > 3600.0) {
      throw parameter_error(field, fmt::format("azimuth must be finite degrees (|azimuth| <= 3600), got {}", value));
    }
  }
  const double diff = std::remainder(az.second_deg - az.first_deg, 180.0);  // in [-90, 90]
  if (std::abs(std::abs(diff) - 90.0) > 1e-6) {
    throw parameter_error("second_azimuth", fmt::format("the horizontal components must be perpendicular: azimuths "
                                                        "{} and {} deg differ by {} deg (mod 180), not 90",
                                                        az.first_deg, az.second_deg, std::abs(diff)));
  }
  if (!std::isfinite(az.slope_azimuth_deg) || std::abs(az.slope_azimuth_deg) > 3600.0) {
    throw parameter_error("slope_azimuth", fmt::format("the slope's azimuth must be finite degrees (|azimuth| <= "
                                                       "3600), got {}", az.slope_azimuth_deg));
  }
  if (b.mode != SlidingMode::two_way) {
    throw parameter_error("mode", "bidirectional sliding is two-way (one-way sliding, down the fall line only, has no "
                                  "meaning for a block free to move across the slope)");
  }
}

template <bool kRecord>
Recorder<kRecord> run(const GroundMotion& first, const GroundMotion& second, const ComponentAzimuths& az,
                      const SlidingBlock& block, const GroundMotion* vertical, const Sliding2dOptions& opt) {
  check_inputs(az, block, opt);
  const Input in(first, second, vertical, block, az);
  Recorder<kRecord> rec;
  std::tie(rec.e1x, rec.e1y) = axis(az.first_deg);
  std::tie(rec.e2x, rec.e2y) = axis(az.second_deg);
  if constexpr (kRecord) {
    const std::size_t guess = in.size() + in.size() / 8 + 16;
    for (auto* v : {&rec.history.time_s, &rec.history.east_m, &rec.history.north_m, &rec.history.east_m_s,
                    &rec.history.north_m_s}) {
      v->reserve(guess);
    }
    rec.history.slipping.reserve(guess);
  }
  if (in.gravity.empty()) {
    integrate<false, kRecord>(in, block, opt, rec);
  } else {
    integrate<true, kRecord>(in, block, opt, rec);
  }
  rec.summary.contact_lost_time_s = contact_lost(in);
  return rec;
}

}  // namespace

void Sliding2dOptions::validate() const {
  if (!std::isfinite(rel_tol) || !(rel_tol > 0.0) || rel_tol > 0.1) {
    throw parameter_error("rel_tol", fmt::format("relative tolerance must be in (0, 0.1], got {}", rel_tol));
  }
  if (!std::isfinite(abs_tol) || !(abs_tol > 0.0)) {
    throw parameter_error("abs_tol", fmt::format("absolute tolerance must be positive and finite, got {}", abs_tol));
  }
  if (max_steps == 0) throw parameter_error("max_steps", "the step cap must be at least 1");
}

Sliding2dResult slide_2d(const GroundMotion& first, const GroundMotion& second, const ComponentAzimuths& azimuths,
                         const SlidingBlock& block, const GroundMotion* vertical, const Sliding2dOptions& options) {
  auto rec = run<true>(first, second, azimuths, block, vertical, options);
  return Sliding2dResult{std::move(rec.summary), std::move(rec.history)};
}

Sliding2dSummary slide_2d_summary(const GroundMotion& first, const GroundMotion& second,
                                  const ComponentAzimuths& azimuths, const SlidingBlock& block,
                                  const GroundMotion* vertical, const Sliding2dOptions& options) {
  return run<false>(first, second, azimuths, block, vertical, options).summary;
}

RotatingSteadySliding rotating_steady_sliding(double accel_m_s2, double omega_rad_s, double mu, double g_m_s2) {
  if (!std::isfinite(mu) || mu < 0.0) throw parameter_error("mu", fmt::format("mu must be finite and >= 0, got {}", mu));
  if (!std::isfinite(g_m_s2) || !(g_m_s2 > 0.0)) {
    throw parameter_error("g", fmt::format("g must be positive and finite, got {}", g_m_s2));
  }
  if (!std::isfinite(accel_m_s2) || !(accel_m_s2 > mu * g_m_s2)) {
    throw parameter_error("accel", fmt::format("the rotating acceleration ({} m/s^2) must exceed mu g = {} m/s^2 for "
                                               "steady sliding", accel_m_s2, mu * g_m_s2));
  }
  if (!std::isfinite(omega_rad_s) || !(omega_rad_s > 0.0)) {
    throw parameter_error("omega", fmt::format("angular speed must be positive and finite, got {} rad/s", omega_rad_s));
  }
  const double friction = mu * g_m_s2;
  RotatingSteadySliding s;
  // Eqs S8-S9 (method.md): radial balance A cos(delta) = mu g, tangential A sin(delta) = V omega.
  s.speed_m_s = std::sqrt((accel_m_s2 - friction) * (accel_m_s2 + friction)) / omega_rad_s;
  s.lag_rad = std::acos(friction / accel_m_s2);
  s.radius_m = s.speed_m_s / omega_rad_s;
  s.power_W_kg = friction * s.speed_m_s;
  return s;
}

}  // namespace topple
