// Exact piecewise-linear sliding solver. See sliding.hpp for the model, the sign convention and the method.
#include "topple/solvers/sliding.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The inputs on one time grid (input_grid.hpp: jumps of either component kept): horizontal a_h and, with a vertical
/// record, the effective gravity g_e = g + a_v per point.
struct Input {
  Input(const GroundMotion& horizontal, const GroundMotion* vertical, double g)
      : grid(horizontal, vertical), accel(grid.accel_m_s2(0)), gravity(effective_gravity(grid, 1, g)) {}
  InputGrid grid;
  std::span<const double> accel;
  std::vector<double> gravity;  // g_e per point; empty without vertical input
  [[nodiscard]] std::size_t size() const { return grid.size(); }
  [[nodiscard]] double time(std::size_t i) const { return grid.time_s(i); }
};

/// Friction coefficients turned into the linear forms of sliding.hpp.
struct Coefficients {
  // static (stick test): slip down when Fd = cd*a + qd*g > 0, up when Fu = -(cu*a + qu*g) > 0
  double cd, qd, cu, qu;
  // kinetic slip acceleration, index 0: s = -1 (up), 1: s = +1 (down): d'' = P*a + Q*g
  double p[2], q[2];
  bool one_way;
  double g;
  double yield_down, yield_up;  // thresholds on a for g_e = g
  const SlidingBlock* block;    // for limit messages
};

/// Cap on slip starts and stops inside one step: a stop and a restart the other way make two, and a linear input can
/// reverse the stick test only once per step, so a handful is the most a valid input gives.
constexpr int kMaxEventsPerStep = 64;
/// Cap on TOMS 748 iterations for a slip stop: a quadratic on a certain bracket converges in a few.
constexpr boost::uintmax_t kMaxRootIterations = 100;

std::string describe(const SlidingBlock& b) {
  return fmt::format("mu_static = {:.6g}, mu_kinetic = {:.6g}, slope = {:.6g} deg, {}", b.mu_static, b.mu_kinetic,
                     rad_to_deg(b.slope_rad), sliding_mode_name(b.mode));
}

[[noreturn]] void too_many_events(const Coefficients& k, double t_s) {
  throw EventLimitError(fmt::format("sliding: more than {} slip starts and stops in the step at t = {} s ({}): the "
                                    "input is outside the model (check its accelerations)",
                                    kMaxEventsPerStep, t_s, describe(*k.block)));
}

Coefficients coefficients(const SlidingBlock& b) {
  const double c = std::cos(b.slope_rad);
  const double s = std::sin(b.slope_rad);
  Coefficients k{};
  // Stick test |f_t| <= mu_s n, f_t = a cos + g sin and n = g cos - a sin (thesis eq 2.2, Goodman & Seed's R).
  k.cd = c + b.mu_static * s;
  k.qd = s - b.mu_static * c;
  k.cu = c - b.mu_static * s;
  k.qu = s + b.mu_static * c;
  // d'' = P_s a + Q_s g_e: eq 2.2's equation of motion with kinetic friction, both ways (eq 3.9 on level ground).
  k.p[1] = c + b.mu_kinetic * s;
  k.q[1] = s - b.mu_kinetic * c;
  k.p[0] = c - b.mu_kinetic * s;
  k.q[0] = s + b.mu_kinetic * c;
  k.one_way = b.mode == SlidingMode::one_way;
  k.g = b.g_m_s2;
  k.yield_down = -k.qd * k.g / k.cd;  // g tan(phi - beta), thesis eq 2.2; cd > 0 for 0 <= beta < 90 deg
  k.yield_up = k.one_way ? -kInf : -k.qu * k.g / k.cu;  // -g tan(phi + beta), eq 2.2; cu > 0 is enforced by make()
  k.block = &b;
  return k;
}

/// Smallest sigma in (0, L] where q(sigma) = C + B sigma + A sigma^2 reaches 0, given q(0) = C >= 0; negative when
/// q stays positive on (0, L]; NaN when the root finder ran out of iterations (the caller reports it). q is s*d'
/// (relative speed in the slip direction) over the rest of a step.
double first_stop(double C, double B, double A, double L) {
  const double qL = C + L * (B + A * L);
  if (C == 0.0) {
    // Slip has just started from rest: q = sigma (B + A sigma). The stop, if any, is where the area of the
    // (linear) acceleration returns to zero.
    if (qL > 0.0) return -1.0;
    if (B > 0.0 && A < 0.0) return std::min(-B / A, L);
    return 0.0;  // cannot move in this direction (only reachable through round-off)
  }
  if (qL > 0.0) {
    // Both ends positive: a stop inside needs a convex q whose minimum dips to zero inside (0, L).
    if (!(A > 0.0 && B < 0.0)) return -1.0;
    const double vertex = -B / (2.0 * A);
    if (vertex >= L || C - B * B / (4.0 * A) > 0.0) return -1.0;
  }
  // Exactly one sign change in (0, L] (or a tangency): the smaller positive root, in a cancellation-free form.
  double root;
  if (A == 0.0) {
    root = -C / B;
  } else {
    const double disc = std::max(B * B - 4.0 * A * C, 0.0);
    const double qq = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    const double r1 = qq / A;
    const double r2 = qq != 0.0 ? C / qq : kInf;
    root = kInf;
    if (r1 > 0.0) root = r1;
    if (r2 > 0.0) root = std::min(root, r2);
  }
  if (root > 0.0 && root <= L) return root;
  if (!(qL <= 0.0)) return -1.0;  // tangency lost to round-off: no sign change, keep sliding
  // Round-off pushed the closed-form root out of its bracket (0, L]: TOMS 748 on the bracket, which is certain.
  boost::uintmax_t iterations = kMaxRootIterations;
  const auto q = [&](double x) { return C + x * (B + A * x); };
  const auto tol = [](double lo, double hi) { return std::abs(hi - lo) <= 4.0 * std::numeric_limits<double>::epsilon() * std::abs(hi); };
  const auto bracket = boost::math::tools::toms748_solve(q, 0.0, L, C, qL, tol, iterations);
  if (iterations >= kMaxRootIterations) return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * (bracket.first + bracket.second);
}

/// Collects summary and (optionally) history; the solver core calls these at samples and events.
template <bool kRecord>
struct Recorder {
  SlidingSummary summary;
  SlidingHistory history;
  double slip_start = 0.0;
  double d_start = 0.0;

  void row(double t, double d, double v, int s) {
    if constexpr (kRecord) {
      history.time_s.push_back(t);
      history.displacement_m.push_back(d);
      history.velocity_m_s.push_back(v);
      history.state.push_back(static_cast<SlipState>(s));
    }
  }
  void track(double t, double d) {
    if (std::abs(d) > summary.max_abs_displacement_m) {
      summary.max_abs_displacement_m = std::abs(d);
      summary.max_displacement_time_s = t;
    }
  }
  void start(double t, double d) {
    ++summary.slip_episodes;
    if (!summary.first_slip_time_s) summary.first_slip_time_s = t;
    slip_start = t;
    d_start = d;
  }
  /// d is monotone within an episode (a reversal through d' = 0 starts a new one): its path is |d - d_start|.
  void stop(double t, double d) {
    summary.total_slip_duration_s += t - slip_start;
    summary.slip_path_m += std::abs(d - d_start);
  }
};

/// Extremes of the record over blocks of kBlock samples: lets many friction coefficients on one record skip stick
/// phases a block at a time (block b covers samples b*kBlock .. b*kBlock + kBlock - 1).
constexpr std::size_t kBlock = 64;
struct BlockExtrema {
  std::vector<double> max, min;
  explicit BlockExtrema(std::span<const double> a) {
    for (std::size_t start = 0; start < a.size(); start += kBlock) {
      const auto end = std::min(a.size(), start + kBlock);
      const auto [lo, hi] = std::minmax_element(a.begin() + static_cast<std::ptrdiff_t>(start),
                                                a.begin() + static_cast<std::ptrdiff_t>(end));
      min.push_back(*lo);
      max.push_back(*hi);
    }
  }
};

/// Stick phase, the fast path (no vertical input, no history, at a sample): advances i to the last sample before the
/// input leaves the yield levels [up, down] (n - 1 when it never does). The only work is comparing samples with the
/// yield levels (linear input: the stick test at both ends of a step decides the whole step).
[[gnu::always_inline]] inline void skip_stuck_samples(const double* a, std::size_t n, std::size_t& i, double up,
                                                     double down, const BlockExtrema* blocks) {
  if (blocks != nullptr) {
    // Whole blocks whose extremes stay within the yield levels (shared by many blocks on one record).
    while (i + 1 < n && (i + 1) % kBlock != 0 && a[i + 1] <= down && a[i + 1] >= up) ++i;
    while (i + 1 < n && (i + 1) % kBlock == 0) {
      const std::size_t b = (i + 1) / kBlock;
      if (blocks->max[b] > down || blocks->min[b] < up) break;
      i = std::min(i + kBlock, n - 1);
    }
  }
  // Eight samples at a time, branch-free inside (vectorises), then one by one to the exceedance.
  while (i + 8 < n) {
    bool out = false;
    for (std::size_t j = 1; j <= 8; ++j) out |= (a[i + j] > down) | (a[i + j] < up);
    if (out) break;
    i += 8;
  }
  while (i + 1 < n && a[i + 1] <= down && a[i + 1] >= up) ++i;
}

/// Slip in direction s, the fast path (no vertical input, a uniform grid, at a sample): whole steps from sample i while
/// no stop can occur in them, i.e. while the relative speed keeps its sign at the step's end and the acceleration does
/// not turn from braking to driving inside it (the only way the quadratic speed can touch zero in between). Advances
/// i, d and v; anything else is left to the general path.
template <bool kRecord>
[[gnu::always_inline]] inline void slip_whole_steps(const Input& in, const double* a, std::size_t n,
                                                    const Coefficients& k, Recorder<kRecord>& rec, int s,
                                                    std::size_t& i, double& d_io, double& v_io) {
  // Local copies (written back at the end): the loop keeps them in registers whatever the stores through rec.
  double d = d_io;
  double v = v_io;
  const double h = in.grid.dt_s();
  const double sd = static_cast<double>(s);
  const int idx = s > 0 ? 1 : 0;
  const double p = k.p[idx];
  const double q = k.q[idx] * k.g;
  double acc0 = p * a[i] + q;
  while (i + 1 < n) {
    const double acc1 = p * a[i + 1] + q;
    const double v1 = v + 0.5 * h * (acc0 + acc1);  // trapezoid (eq 3.10): exact for linear d''
    if (sd * v1 <= 0.0 || (sd * acc0 < 0.0 && sd * acc1 > 0.0)) break;
    if (sd * acc0 > 0.0 && sd * acc1 < 0.0) {  // speed peaks inside the step
      const double at = acc0 * h / (acc0 - acc1);
      const double vp = v + at * (acc0 + 0.5 * (acc1 - acc0) / h * at);
      rec.summary.max_abs_velocity_m_s = std::max(rec.summary.max_abs_velocity_m_s, std::abs(vp));
    }
    d += h * (v + h * (2.0 * acc0 + acc1) / 6.0);  // cubic, as eq 3.10's ground term: exact
    v = v1;
    acc0 = acc1;
    ++i;
    rec.summary.max_abs_velocity_m_s = std::max(rec.summary.max_abs_velocity_m_s, std::abs(v));
    rec.row(in.time(i), d, v, s);
  }
  d_io = d;
  v_io = v;
}

/// Run-out on still ground after the record's end t_end (a_h = 0, g_e = g), slipping in direction s at speed v:
/// constant relative acceleration Q_s g.
template <bool kRecord>
void run_out(const Coefficients& k, Recorder<kRecord>& rec, double t_end, int s, double v, double& d) {
  const double acc = k.q[s > 0 ? 1 : 0] * k.g;
  if (static_cast<double>(s) * acc < 0.0) {
    const double sigma = -v / acc;         // Newmark's run-out (thesis eqs 2.5, 2.6): t = v / (N g) on level ground
    d += sigma * (v + 0.5 * acc * sigma);  // ... and v^2 / (2 N g) more displacement
    rec.stop(t_end + sigma, d);
    rec.track(t_end + sigma, d);
    rec.row(t_end + sigma, d, 0.0, 0);
    rec.summary.end_time_s = t_end + sigma;
  } else {
    rec.summary.at_rest_at_end = false;
    rec.stop(t_end, d);
    rec.track(t_end, d);
  }
}

/// The solver core. kVertical: g_e varies per sample; kRecord: store the history. `blocks` (optional) are the
/// record's block extrema.
template <bool kVertical, bool kRecord>
void integrate(const Input& in, const Coefficients& k, Recorder<kRecord>& rec, const BlockExtrema* blocks = nullptr) {
  const std::size_t n = in.size();
  const double* a = in.accel.data();
  const double* ge = kVertical ? in.gravity.data() : nullptr;
  const auto gravity = [&](std::size_t i) { return kVertical ? ge[i] : k.g; };
  const auto f_down = [&](double acc, double grav) { return k.cd * acc + k.qd * grav; };
  const auto f_up = [&](double acc, double grav) { return -(k.cu * acc + k.qu * grav); };

  double d = 0.0;
  double v = 0.0;
  int s = 0;          // -1 up, 0 stuck, +1 down
  double tau = 0.0;   // offset inside the current step, s
  int events_in_step = 0;
  rec.row(in.time(0), 0.0, 0.0, 0);
  rec.summary.max_displacement_time_s = in.time(0);

  // A block that must slip at the very first sample (slope steeper than friction, or a record starting above
  // yield) starts at t0; the step loop below handles that through the stick test at tau = 0.
  std::size_t i = 0;
  while (i + 1 < n) {
    if (s == 0) {
      if constexpr (!kVertical && !kRecord) {
        if (tau == 0.0) {
          // Stick phase: the only work is comparing samples with the yield levels (skip_stuck_samples).
          skip_stuck_samples(a, n, i, k.yield_up, k.yield_down, blocks);
          if (i + 1 >= n) break;
        }
      }
      const double t_i = in.time(i);
      const double h = in.time(i + 1) - t_i;
      const double frac = h > 0.0 ? tau / h : 0.0;
      const double a_tau = a[i] + frac * (a[i + 1] - a[i]);
      const double g_tau = kVertical ? gravity(i) + frac * (gravity(i + 1) - gravity(i)) : k.g;
      const double a1 = a[i + 1];
      const double g1 = gravity(i + 1);
      // The stick test is linear over the step: it fails somewhere in [tau, h] iff it fails at an end.
      double f0 = f_down(a_tau, g_tau);
      double f1 = f_down(a1, g1);
      int dir = 0;
      if (f0 > 0.0 || f1 > 0.0) {
        dir = 1;
      } else if (!k.one_way) {
        f0 = f_up(a_tau, g_tau);
        f1 = f_up(a1, g1);
        if (f0 > 0.0 || f1 > 0.0) dir = -1;
      }
      if (dir == 0) {
        ++i;
        tau = 0.0;
        events_in_step = 0;
        rec.row(in.time(i), d, 0.0, 0);
        continue;
      }
      // Slip starts where the (linear) stick test crosses zero, or now if it is already violated.
      const double start = f0 > 0.0 ? tau : tau + (h - tau) * (-f0) / (f1 - f0);
      tau = std::min(start, h);
      s = dir;
      v = 0.0;
      rec.start(t_i + tau, d);
      rec.row(t_i + tau, d, 0.0, s);
      if (++events_in_step > kMaxEventsPerStep) too_many_events(k, t_i);
      continue;
    }

    if constexpr (!kVertical) {
      if (tau == 0.0 && in.grid.is_uniform()) {
        // Fast slip on a uniform grid, whole steps (slip_whole_steps); anything else goes to the general path below.
        slip_whole_steps(in, a, n, k, rec, s, i, d, v);
        events_in_step = 0;
        if (i + 1 >= n) break;
      }
    }
    // Slipping in direction s over [tau, h] of step i.
    const double t_i = in.time(i);
    const double h = in.time(i + 1) - t_i;
    const double L = h - tau;
    const int idx = s > 0 ? 1 : 0;
    double a_tau = a[i];
    double g_tau = gravity(i);
    if (tau != 0.0) {
      const double frac = tau / h;
      a_tau += frac * (a[i + 1] - a[i]);
      if constexpr (kVertical) g_tau += frac * (gravity(i + 1) - gravity(i));
    }
    const double acc0 = k.p[idx] * a_tau + k.q[idx] * g_tau;
    const double acc1 = k.p[idx] * a[i + 1] + k.q[idx] * gravity(i + 1);
    if (!(L > 0.0)) {  // a jump in the input: nothing moves during it
      ++i;
      tau = 0.0;
      events_in_step = 0;
      rec.row(in.time(i), d, v, s);
      continue;
    }
    const double slope = (acc1 - acc0) / L;
    const double sd = static_cast<double>(s);
    const double sigma = first_stop(sd * v, sd * acc0, 0.5 * sd * slope, L);
    if (std::isnan(sigma)) {
      throw RootFindingError(fmt::format("sliding: the slip stop (TOMS 748) did not converge in {} iterations in the "
                                         "step [{}, {}] s ({})", kMaxRootIterations, t_i, t_i + h, describe(*k.block)));
    }
    const double span = sigma < 0.0 ? L : sigma;
    // Peak speed inside the step, where the acceleration changes sign.
    if (acc0 * acc1 < 0.0) {
      const double at = -acc0 / slope;
      if (at < span) {
        rec.summary.max_abs_velocity_m_s =
            std::max(rec.summary.max_abs_velocity_m_s, std::abs(v + at * (acc0 + 0.5 * slope * at)));
      }
    }
    d += span * (v + span * (0.5 * acc0 + span * slope / 6.0));  // cubic (eq 3.10), exact: method.md
    if (sigma < 0.0) {
      v += span * (acc0 + 0.5 * slope * span);  // d'(sigma), same
      rec.summary.max_abs_velocity_m_s = std::max(rec.summary.max_abs_velocity_m_s, std::abs(v));
      ++i;
      tau = 0.0;
      events_in_step = 0;
      rec.row(in.time(i), d, v, s);
      continue;
    }
    // Relative rest: the stick test decides at the top of the loop whether it holds or slip restarts.
    tau += sigma;
    v = 0.0;
    s = 0;
    rec.stop(t_i + tau, d);
    rec.track(t_i + tau, d);
    rec.row(t_i + tau, d, 0.0, 0);
    if (++events_in_step > kMaxEventsPerStep) too_many_events(k, t_i);
  }

  const double t_end = in.time(n - 1);
  rec.summary.end_time_s = t_end;
  if (s != 0) run_out(k, rec, t_end, s, v, d);
  rec.summary.residual_displacement_m = d;
}

/// First time the normal force n = g_e cos(beta) - a_h sin(beta) is <= 0 (linear per step).
std::optional<double> contact_lost(const Input& in, const SlidingBlock& b) {
  const double c = std::cos(b.slope_rad);
  const double s = std::sin(b.slope_rad);
  if (in.gravity.empty() && s == 0.0) return std::nullopt;
  const auto normal = [&](std::size_t i) {
    const double g = in.gravity.empty() ? b.g_m_s2 : in.gravity[i];
    return g * c - in.accel[i] * s;
  };
  double prev = normal(0);
  if (prev <= 0.0) return in.time(0);
  for (std::size_t i = 1; i < in.size(); ++i) {
    const double cur = normal(i);
    if (cur <= 0.0) return in.time(i - 1) + (in.time(i) - in.time(i - 1)) * prev / (prev - cur);
    prev = cur;
  }
  return std::nullopt;
}

template <bool kRecord>
Recorder<kRecord> run(const GroundMotion& horizontal, const SlidingBlock& block, const GroundMotion* vertical) {
  const Input in(horizontal, vertical, block.g_m_s2);
  const Coefficients k = coefficients(block);
  Recorder<kRecord> rec;
  if constexpr (kRecord) {
    const std::size_t guess = in.size() + in.size() / 8 + 16;
    rec.history.time_s.reserve(guess);
    rec.history.displacement_m.reserve(guess);
    rec.history.velocity_m_s.reserve(guess);
    rec.history.state.reserve(guess);
  }
  if (in.gravity.empty()) {
    integrate<false, kRecord>(in, k, rec);
  } else {
    integrate<true, kRecord>(in, k, rec);
  }
  rec.summary.contact_lost_time_s = contact_lost(in, block);
  return rec;
}

}  // namespace

SlidingBlock SlidingBlock::make(double mu_static, std::optional<double> mu_kinetic_given, double slope_rad,
                                SlidingMode mode, double g_m_s2) {
  const double mu_kinetic = mu_kinetic_given.value_or(mu_static);
  if (!std::isfinite(mu_static) || mu_static < 0.0) {
    throw parameter_error("mu", fmt::format("friction coefficient must be finite and >= 0, got {}", mu_static));
  }
  if (!std::isfinite(mu_kinetic) || mu_kinetic < 0.0 || mu_kinetic > mu_static) {
    throw parameter_error("mu_kinetic", fmt::format("kinetic friction must be finite and between 0 and the static "
                                                    "coefficient {}, got {}", mu_static, mu_kinetic));
  }
  if (!std::isfinite(slope_rad) || slope_rad < 0.0 || slope_rad >= kPi / 2.0) {
    throw parameter_error("slope", fmt::format("slope must be in [0, 90) degrees, got {} deg", rad_to_deg(slope_rad)));
  }
  if (std::atan(mu_static) + slope_rad >= kPi / 2.0) {
    throw parameter_error("slope", fmt::format("slope ({} deg) plus friction angle atan(mu) = {} deg reaches 90 deg: "
                                               "the block cannot slide upslope in this model",
                                               rad_to_deg(slope_rad), rad_to_deg(std::atan(mu_static))));
  }
  if (!std::isfinite(g_m_s2) || !(g_m_s2 > 0.0)) {
    throw parameter_error("g", fmt::format("g must be positive and finite, got {}", g_m_s2));
  }
  return SlidingBlock{mu_static, mu_kinetic, slope_rad, mode, g_m_s2};
}

double SlidingBlock::yield_down_m_s2() const noexcept { return coefficients(*this).yield_down; }
double SlidingBlock::yield_up_m_s2() const noexcept { return coefficients(*this).yield_up; }

SlidingResult slide(const GroundMotion& horizontal, const SlidingBlock& block, const GroundMotion* vertical) {
  auto rec = run<true>(horizontal, block, vertical);
  return SlidingResult{std::move(rec.summary), std::move(rec.history)};
}

SlidingSummary slide_summary(const GroundMotion& horizontal, const SlidingBlock& block, const GroundMotion* vertical) {
  return run<false>(horizontal, block, vertical).summary;
}

std::vector<SlidingSummary> slide_summaries(const GroundMotion& horizontal, std::span<const double> mu,
                                            double slope_rad, SlidingMode mode, double g_m_s2) {
  const Input in(horizontal, nullptr, g_m_s2);
  const BlockExtrema blocks(in.accel);
  std::vector<SlidingSummary> out;
  out.reserve(mu.size());
  for (double m : mu) {
    const SlidingBlock block = SlidingBlock::make(m, m, slope_rad, mode, g_m_s2);
    Recorder<false> rec;
    integrate<false, false>(in, coefficients(block), rec, &blocks);
    rec.summary.contact_lost_time_s = contact_lost(in, block);
    out.push_back(rec.summary);
  }
  return out;
}

}  // namespace topple
