// Rocking and overturning engine. See rocking.hpp for the model, the sign convention, the rest rule and the method;
// the input, the right-hand side and the steppers are in rocking_steppers.hpp, Shenton's onset criteria in shenton.cpp,
// the threshold search in threshold_search.cpp, the closed forms in closed_forms/rocking.cpp.
#include "topple/solvers/rocking.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "solvers/rocking_steppers.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {
namespace {

// ---------------------------------------------------------------------------------------------------------------
// The engine.

struct Params {
  double a = 0.0, h = 0.0, D = 0.0, R = 0.0, alpha = 0.0, p = 0.0, e = 0.0, g = 0.0, tan_alpha = 0.0;
  double w_scale = 0.0;        // p alpha: theta' = w_scale * u[1]
  double rest_w2 = 0.0;        // theta'^2 below which the rest rule applies after an impact
  double overturn_level = 0.0; // (pi / 2) / alpha in the scaled state
  // Per side, index side(s) (0: O-, theta < 0; 1: O+). The state is scaled by alpha and p above (an asymmetric
  // body: the smaller of the two pivots'); a symmetric body has both entries equal to those (alpha_level 1 exactly),
  // so its run is the same as before.
  bool symmetric = true;
  std::array<double, 2> alpha_side{};   // alpha of each pivot, rad
  std::array<double, 2> alpha_level{};  // alpha_side / alpha: |theta| = alpha_side in the scaled state
  std::array<double, 2> tan_side{};     // b_s / h: uplift about pivot s when the throw exceeds (g + a_v) b_s / h
  std::array<double, 2> D_side{};       // I_O / m about each pivot
  std::array<double, 2> k_side{};       // (R_s / D_s) / (p alpha): Rhs::k while on pivot s
  std::array<double, 2> e_onto{};       // restitution on landing on pivot s
  std::array<double, 2> rest_w2_side{}; // rest_w2 on pivot s
};

constexpr std::size_t side(int s) { return s > 0 ? 1 : 0; }

enum class Mode : std::uint8_t { rest, rocking };

template <class Stepper, bool kRecord>
class Engine {
 public:
  Engine(const Input& in, const Params& par, const RockingOptions& opt, Stepper& stepper, Rhs& rhs)
      : in_(in), par_(par), opt_(opt), stepper_(stepper), rhs_(rhs) {}

  RockingResult run() {
    const std::size_t n = in_.size();
    if constexpr (kRecord) {
      const std::size_t guess = n + n / 4 + 16;
      out_.history.time_s.reserve(guess);
      out_.history.theta_rad.reserve(guess);
      out_.history.theta_dot_rad_s.reserve(guess);
      out_.history.state.reserve(guess);
    }
    RockingSummary& sum = out_.summary;
    t_ = in_.time(0);
    sum.max_rotation_time_s = t_;
    // The ground is still before the record, so the first sample is reached by a jump from 0.
    if (opt_.initial_theta_rad != 0.0 || opt_.initial_theta_dot_rad_s != 0.0) {
      started_rocking_ = true;
      s_ = opt_.initial_theta_rad != 0.0 ? (opt_.initial_theta_rad > 0.0 ? 1 : -1)
                                         : (opt_.initial_theta_dot_rad_s > 0.0 ? 1 : -1);
      u_ = {opt_.initial_theta_rad / par_.alpha, opt_.initial_theta_dot_rad_s / par_.w_scale};
      mode_ = Mode::rocking;
      need_restart_ = true;
      track(t_, u_);
      if (std::abs(u_[0]) >= par_.alpha_level[side(s_)]) {  // released beyond alpha
        sum.exceeded_alpha_time_s = t_;
        sum.exceeded_alpha_side = s_;
      }
    }
    row(t_, u_);

    const bool fast_rest = in_.gravity.empty();
    const double* a = in_.accel.data();
    // Uplift thresholds: about O+ when -a_h > g tan(alpha+), about O- when a_h > g tan(alpha-) (equal when symmetric:
    // -x <= t && x <= t is |x| <= t).
    const double threshold_pos = par_.g * par_.tan_side[1];
    const double threshold_neg = par_.g * par_.tan_side[0];
    const auto below = [&](double x) { return -x <= threshold_pos && x <= threshold_neg; };
    std::size_t i = 0;
    at_start_ = true;  // t_ is at the start of interval i
    while (!done_ && i + 1 < n) {
      // The scan checks the end of each interval; the first sample (a jump from still ground) is checked by the
      // general path.
      if (fast_rest && mode_ == Mode::rest && at_start_ && (i > 0 || below(a[0]))) {
        // Full contact: each sample interval costs one comparison (|a| is convex on a linear piece, so both ends
        // below the threshold keep the whole interval below it).
        // A symmetric body's test is one |a| <= threshold (the hot loop of a body at rest: kept as tight as before
        // asymmetric bodies came; bench_rocking's BM_Rocking/100/50).
        if (threshold_pos == threshold_neg) {
          if constexpr (!kRecord) {
            // Blocks of kRestBlock samples first: the block's comparisons have no early exit, so the compiler
            // evaluates them side by side (SIMD); a block with a sample above the threshold is left to the loop
            // below, which stops at that sample. The same i as the loop alone (issue 32: the rest scan was 4 % of
            // the inversion's time).
            while (i + kRestBlock < n) {
              bool all_below = true;
              for (std::size_t j = 1; j <= kRestBlock; ++j) all_below &= std::abs(a[i + j]) <= threshold_pos;
              if (!all_below) break;
              i += kRestBlock;
            }
          }
          while (i + 1 < n && std::abs(a[i + 1]) <= threshold_pos) {
            ++i;
            if constexpr (kRecord) row(in_.time(i), u_);
          }
        } else {
          while (i + 1 < n && below(a[i + 1])) {
            ++i;
            if constexpr (kRecord) row(in_.time(i), u_);
          }
        }
        t_ = in_.time(i);
        if (i + 1 >= n) break;
      }
      const double ta = in_.time(i);
      const double tb = in_.time(i + 1);
      if (!(tb > ta)) {  // a jump: the forcing changes at once
        ++i;
        need_restart_ = true;
        continue;
      }
      const double ahs = (a[i + 1] - a[i]) / (tb - ta);
      const double ge0 = in_.gravity.empty() ? par_.g : in_.gravity[i];
      const double ges = in_.gravity.empty() ? 0.0 : (in_.gravity[i + 1] - in_.gravity[i]) / (tb - ta);
      interval(ta, tb, a[i], ahs, ge0, ges);
      if (done_) break;
      ++i;
      at_start_ = true;
      row(tb, u_);
    }
    const double t_end = in_.time(n - 1);
    if (!done_) {
      t_ = t_end;
      run_out(t_end);
    }
    finish();
    return std::move(out_);
  }

 private:
  // ---- recording ----
  void row(double t, const State& u) {
    if constexpr (kRecord) {
      if (in_run_out_) flush_grid(t, false);
      push_row(t, u);
    }
  }
  void push_row(double t, const State& u) {
    if constexpr (kRecord) {
      auto& h = out_.history;
      const RockingState st = state();
      if (!h.time_s.empty() && h.time_s.back() == t && h.state.back() == st) {
        h.theta_rad.back() = par_.alpha * u[0];
        h.theta_dot_rad_s.back() = par_.w_scale * u[1];
        return;
      }
      h.time_s.push_back(t);
      h.theta_rad.push_back(par_.alpha * u[0]);
      h.theta_dot_rad_s.push_back(par_.w_scale * u[1]);
      h.state.push_back(st);
    }
  }
  void event(RockingEventKind kind, double t, double theta, double w_before, double w_after) {
    if constexpr (kRecord) out_.events.push_back(RockingEvent{kind, t, theta, w_before, w_after});
  }
  [[nodiscard]] RockingState state() const {
    if (fallen_) return RockingState::fallen;
    if (mode_ == Mode::rocking) return s_ > 0 ? RockingState::rocking_positive : RockingState::rocking_negative;
    return RockingState::rest;
  }
  void track(double t, const State& u) {
    RockingSummary& sum = out_.summary;
    const double theta = std::abs(par_.alpha * u[0]);
    if (theta > sum.max_abs_rotation_rad) {
      sum.max_abs_rotation_rad = theta;
      sum.max_rotation_time_s = t;
    }
    double& side_max = u[0] < 0.0 ? sum.max_rotation_negative_rad : sum.max_rotation_positive_rad;
    side_max = std::max(side_max, theta);
    sum.max_abs_theta_dot_rad_s = std::max(sum.max_abs_theta_dot_rad_s, std::abs(par_.w_scale * u[1]));
  }

  // ---- one sample interval [ta, tb] from t_ ----
  void interval(double ta, double tb, double ah0, double ahs, double ge0, double ges) {
    rhs_.t_ref = ta;
    rhs_.ah0 = ah0;
    rhs_.ahs = ahs;
    rhs_.ge0 = ge0;
    rhs_.ges = ges;
    at_start_ = false;
    int events_here = 0;
    while (!done_ && t_ < tb) {
      if (++events_here > kMaxEventsPerInterval) {
        throw EventLimitError(fmt::format("rocking: more than {} events in the sample interval [{}, {}] s ({}): the "
                                          "input is outside the model (check its accelerations)",
                                          kMaxEventsPerInterval, ta, tb, describe()));
      }
      if (mode_ == Mode::rest) {
        rest_phase(ta, tb, ah0, ahs, ge0, ges);
      } else {
        rocking_phase(tb);
      }
    }
  }

  /// Full contact over [t_, tb]: find the uplift, which is the root of a linear function. Uplift about O+ when
  /// f+ = -a_h - (g + a_v) tan(alpha) > 0, about O- when f- = a_h - (g + a_v) tan(alpha) > 0.
  void rest_phase(double ta, double tb, double ah0, double ahs, double ge0, double ges) {
    const auto ah = [&](double t) { return ah0 + ahs * (t - ta); };
    const auto ge = [&](double t) { return ge0 + ges * (t - ta); };
    const double tan_p = par_.tan_side[1];
    const double tan_m = par_.tan_side[0];
    const double fp0 = -ah(t_) - ge(t_) * tan_p;
    const double fm0 = ah(t_) - ge(t_) * tan_m;
    const double fp1 = -ah(tb) - ge(tb) * tan_p;
    const double fm1 = ah(tb) - ge(tb) * tan_m;
    int dir = 0;
    double tu = t_;
    if (fp0 > 0.0) {
      dir = 1;
    } else if (fm0 > 0.0) {
      dir = -1;
    } else if (fp1 > 0.0) {
      dir = 1;
      tu = t_ + (tb - t_) * (-fp0) / (fp1 - fp0);
    } else if (fm1 > 0.0) {
      dir = -1;
      tu = t_ + (tb - t_) * (-fm0) / (fm1 - fm0);
    }
    if (dir == 0) {
      t_ = tb;
      return;
    }
    tu = std::min(tu, tb);
    t_ = tu;
    s_ = dir;
    u_ = {0.0, 0.0};
    mode_ = Mode::rocking;
    need_restart_ = true;
    RockingSummary& sum = out_.summary;
    ++sum.uplifts;
    if (!sum.uplift_time_s) {
      sum.uplift_time_s = tu;
      // Value after a jump when the uplift sits on one; at least a/h, which round-off in the root may undercut.
      if (!started_rocking_) {
        first_uplift_ratio_ = std::max(std::abs(ah(tu)) / ge(tu), par_.tan_side[side(dir)]);
        first_uplift_side_ = dir;
      }
    }
    event(RockingEventKind::uplift, tu, 0.0, 0.0, 0.0);
    row(tu, u_);
  }

  /// One integrator step toward tb while rocking, and the events inside it.
  void rocking_phase(double tb) {
    rhs_.s_alpha = s_ * par_.alpha_side[side(s_)];
    rhs_.k = par_.k_side[side(s_)];
    if (need_restart_) {
      stepper_.restart(t_, u_);
      need_restart_ = false;
    }
    if (tb - t_ <= 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(tb), 1.0)) {
      t_ = tb;  // an event left only round-off of the interval
      return;
    }
    if (!stepper_.step(tb, out_.summary.steps, opt_.max_steps)) {
      throw StepLimitError(fmt::format("rocking: more than max_steps = {} integrator steps (accepted and rejected) by "
                                       "t = {} s ({}): raise max_steps or check the input",
                                       opt_.max_steps, t_, describe()));
    }
    const double t0 = stepper_.t0();
    const double t1 = stepper_.t1();
    const State& x0 = stepper_.x0();
    const State& x1 = stepper_.x1();
    const double s = s_;
    const auto f = [&](double t) { return s * stepper_.dense(t)[0]; };
    const double f0 = s * x0[0];
    const double f1 = s * x1[0];
    const double v0 = s * x0[1];
    const double v1 = s * x1[1];

    // Split the step at a turning point of theta (at most one inside a step: steps end on samples and the error
    // control keeps them short against the motion), so that s theta is monotone on each piece.
    double tp = t1;
    bool split = false;
    if ((v0 > 0.0 && v1 <= 0.0) || (v0 < 0.0 && v1 > 0.0)) {
      if constexpr (!kRecord) {
        if (turning_point_is_moot(v0, f1)) {
          t_ = t1;
          u_ = x1;
          track(t1, x1);
          return;
        }
      }
      tp = v1 == 0.0 ? t1 : root(1, 0.0, t0, t1, v0, v1);
      split = tp < t1;
    }
    const bool first_up = v0 > 0.0 || (v0 == 0.0 && (v1 > 0.0 || (v1 == 0.0 && f1 > f0)));
    const double fp = split ? f(tp) : f1;
    if (piece(t0, tp, f0, fp, first_up)) return;
    if (first_up && (v0 > 0.0 && v1 <= 0.0)) peak(tp);
    if (split && piece(tp, t1, fp, f1, !first_up)) return;

    t_ = t1;
    u_ = x1;
    track(t1, x1);
  }

  /// Summary runs only (no history, no events): true when the turning point inside the step changes nothing, so
  /// that locating it can be skipped with the same summary. A peak (v0 > 0) is moot when the step's bound on s theta
  /// stays below alpha (or alpha was passed before), below the fall level and below the largest |theta| so far, and
  /// the step ends with s theta > 0 (no impact after it); a trough (v0 < 0) when the bound stays above 0 (no impact)
  /// and the step ends below those levels (no level crossed on the way up).
  [[nodiscard]] bool turning_point_is_moot(double v0, double f1) const {
    const RockingSummary& sum = out_.summary;
    const double level = par_.alpha_level[side(s_)];
    const double top = std::min(par_.overturn_level, sum.exceeded_alpha_time_s ? par_.overturn_level : level);
    const auto [lo, hi] = stepper_.range(0);
    const double upper = s_ > 0 ? hi : -lo;  // bounds on s theta / alpha
    const double lower = s_ > 0 ? lo : -hi;
    if (v0 > 0.0) {
      // The margin keeps a peak within round-off of the maximum located, so that the maximum is the same.
      // Against this side's maximum (at most max |theta|), so that the per-side maxima are located too.
      const double side_max = s_ > 0 ? sum.max_rotation_positive_rad : sum.max_rotation_negative_rad;
      return f1 > 0.0 && upper < top && upper * par_.alpha < side_max * (1.0 - 1e-12);
    }
    return lower > 0.0 && f1 < top;
  }

  /// Events on a monotone piece [ta, tb] of s theta (scaled: fa, fb). Returns true when an event ended the step
  /// (impact, fall, rest, or the end of the run).
  bool piece(double ta, double tb, double fa, double fb, bool up) {
    const double s = s_;
    RockingSummary& sum = out_.summary;
    if (up) {
      const double level = par_.alpha_level[side(s_)];  // 1 for a symmetric body
      if (!sum.exceeded_alpha_time_s && fa < level && fb >= level) {
        const double te = root(0, level, ta, tb, fa - level, fb - level);
        sum.exceeded_alpha_time_s = te;
        sum.exceeded_alpha_side = s_;
        const State x = stepper_.dense(te);
        event(RockingEventKind::exceeded_alpha, te, s * par_.alpha_side[side(s_)], par_.w_scale * x[1],
              par_.w_scale * x[1]);
        row(te, State{s * level, x[1]});
        if (opt_.stop_when_alpha_exceeded) {
          t_ = te;
          u_ = {s * level, x[1]};
          track(te, u_);
          done_ = true;
          return true;
        }
      }
      if (fb >= par_.overturn_level) {
        const double tf = root(0, par_.overturn_level, ta, tb, fa - par_.overturn_level,
                                    fb - par_.overturn_level);
        const State x = stepper_.dense(tf);
        before_state_change(tf);
        t_ = tf;
        u_ = {s * par_.overturn_level, x[1]};
        track(tf, u_);
        sum.overturned = true;
        sum.overturn_time_s = tf;
        sum.overturned_side = s_;
        fallen_ = true;
        event(RockingEventKind::overturned, tf, s * kPi / 2.0, par_.w_scale * x[1], 0.0);
        row(tf, u_);
        done_ = true;
        return true;
      }
      return false;
    }
    if (fb > 0.0) return false;
    if (!(fa > 0.0)) {
      // Lift-off that did not happen: the step started at theta = 0 with theta' = 0 and round-off sent it below.
      // The body is still in contact at the end of the piece (time moves on, so this cannot loop).
      before_state_change(tb);
      t_ = tb;
      u_ = {0.0, 0.0};
      mode_ = Mode::rest;
      event(RockingEventKind::rest, tb, 0.0, 0.0, 0.0);
      row(tb, u_);
      return true;
    }
    impact(root(0, 0.0, ta, tb, fa, fb));
    return true;
  }

  void peak(double tp) {
    const State x = stepper_.dense(tp);
    track(tp, x);
    event(RockingEventKind::peak, tp, par_.alpha * x[0], 0.0, 0.0);
    if constexpr (kRecord) {
      // The turning point is a row of its own, between the step's start and end (the state is unchanged by it).
      row(tp, State{x[0], 0.0});
    }
  }

  /// theta = 0: land on the other edge with theta' multiplied by e (Housner; for an asymmetric body the e of the
  /// new pivot), or come to rest (rest rule).
  void impact(double ti) {
    RockingSummary& sum = out_.summary;
    const State x = stepper_.dense(ti);
    before_state_change(ti);
    const std::size_t onto = side(-s_);
    const double w_before = par_.w_scale * x[1];
    const double w_after = par_.e_onto[onto] * w_before;
    ++sum.impacts;
    if (par_.symmetric) {
      sum.energy_lost_j_per_kg += 0.5 * par_.D * (w_before * w_before - w_after * w_after);
    } else {  // the kinetic energy D_s theta'^2 / 2 about the old pivot, then about the new one
      sum.energy_lost_j_per_kg += 0.5 * (par_.D_side[side(s_)] * w_before * w_before - par_.D_side[onto] * w_after * w_after);
    }
    sum.max_abs_theta_dot_rad_s = std::max(sum.max_abs_theta_dot_rad_s, std::abs(w_before));
    event(RockingEventKind::impact, ti, 0.0, w_before, w_after);
    t_ = ti;
    need_restart_ = true;
    if (w_after * w_after < par_.rest_w2_side[onto]) {
      sum.energy_lost_j_per_kg += 0.5 * par_.D_side[onto] * w_after * w_after;
      u_ = {0.0, 0.0};
      mode_ = Mode::rest;
      event(RockingEventKind::rest, ti, 0.0, w_after, 0.0);
      row(ti, u_);
      return;
    }
    s_ = -s_;
    u_ = {0.0, w_after / par_.w_scale};
    row(ti, u_);
  }

  /// The time in [ta, tb] where s theta' (component 1) or s theta (component 0), scaled, equals the level, given
  /// the differences fa, fb at the ends; RootFindingError with the run's parameters when the root finder ran out.
  double root(std::size_t component, double level, double ta, double tb, double fa, double fb) const {
    const double r = stepper_.locate(component, static_cast<double>(s_), level, ta, tb, fa, fb);
    if (std::isnan(r)) {
      throw RootFindingError(fmt::format("rocking: event location did not converge in {} iterations on "
                                         "[{}, {}] s ({})", kMaxRootIterations, ta, tb, describe()));
    }
    return r;
  }

  /// The run's parameters, for limit messages.
  [[nodiscard]] std::string describe() const {
    return fmt::format("a = {:.6g} m, {}h = {:.6g} m, e = {:.6g}, method {}, rel_tol = {:.3g}, rk4_substeps = {}",
                       par_.a,
                       par_.symmetric ? std::string{}
                                      : fmt::format("b1 = {:.6g} m, ", par_.tan_side[0] * par_.h),
                       par_.h, par_.e, opt_.method == RockingMethod::adaptive ? "adaptive" : "rk4", opt_.rel_tol,
                       opt_.rk4_substeps);
  }

  // ---- after the record: still ground until rest, fall, or the run-out cap ----
  void run_out(double t_end) {
    if (mode_ == Mode::rest || opt_.max_run_out_s == 0.0) return;
    rhs_.t_ref = t_end;
    rhs_.ah0 = 0.0;
    rhs_.ahs = 0.0;
    rhs_.ge0 = par_.g;
    rhs_.ges = 0.0;
    need_restart_ = true;  // the ground jumps to rest at the end of the record
    const double t_stop = t_end + opt_.max_run_out_s;
    // The forcing is constant now, so steps need not stop anywhere (the same steps with or without a history).
    // History rows continue the record's spacing (at most 1e5 of them) from the dense output of each step.
    in_run_out_ = true;
    grid_t0_ = t_end;
    grid_dt_ = std::max(in_.dt(), opt_.max_run_out_s * 1e-5);
    std::size_t stalls = 0;
    while (!done_ && mode_ == Mode::rocking && t_ < t_stop) {
      const double before = t_;
      rocking_phase(t_stop);
      if constexpr (kRecord) {
        if (!done_ && mode_ == Mode::rocking && t_ == stepper_.t1()) flush_grid(t_, true);
      }
      if (t_ == before && ++stalls > static_cast<std::size_t>(kMaxEventsPerInterval)) {
        throw EventLimitError(fmt::format("rocking: more than {} events without time advancing in the run-out at "
                                          "t = {} s ({})", kMaxEventsPerInterval, t_, describe()));
      }
    }
    in_run_out_ = false;
  }

  /// Rows due before an event at t carry the state before it.
  void before_state_change(double t) {
    if constexpr (kRecord) {
      if (in_run_out_) flush_grid(t, false);
    } else {
      (void)t;
    }
  }

  /// Run-out rows on the grid up to t (before an event row at t, or at the end of a step), from the current step.
  void flush_grid(double t, bool inclusive) {
    for (;;) {
      const double tg = grid_t0_ + static_cast<double>(next_grid_) * grid_dt_;
      if (tg > t || (!inclusive && tg == t)) return;
      ++next_grid_;
      if (tg < stepper_.t0()) continue;
      push_row(tg, tg == stepper_.t1() ? stepper_.x1() : stepper_.dense(tg));
    }
  }

  void finish() {
    RockingSummary& sum = out_.summary;
    sum.end_time_s = t_;
    sum.end_state = state();
    if (mode_ == Mode::rocking && !fallen_) {
      sum.still_rocking_at_end = true;
      if (!opt_.stop_when_alpha_exceeded) {
        sum.warnings.push_back(fmt::format("the body was still rocking {} s after the record ended "
                                           "(max_run_out_s); the summary covers the response up to then",
                                           opt_.max_run_out_s));
      }
    }
    if constexpr (kRecord) {
      if (out_.history.time_s.empty() || out_.history.time_s.back() < t_) row(t_, u_);
    }
  }

 public:
  std::optional<double> first_uplift_ratio_;
  int first_uplift_side_ = 0;

 private:
  static constexpr int kMaxEventsPerInterval = 1'000'000;
  static constexpr std::size_t kRestBlock = 8;  // samples per block of the rest scan
  const Input& in_;
  const Params& par_;
  const RockingOptions& opt_;
  Stepper& stepper_;
  Rhs& rhs_;
  RockingResult out_;
  double t_ = 0.0;
  State u_{0.0, 0.0};
  int s_ = 1;
  Mode mode_ = Mode::rest;
  bool need_restart_ = true;
  bool at_start_ = true;
  bool fallen_ = false;
  bool started_rocking_ = false;
  bool done_ = false;
  bool in_run_out_ = false;
  double grid_t0_ = 0.0;
  double grid_dt_ = 0.0;
  std::size_t next_grid_ = 1;
};

void validate(const RockingBody& body, const RockingOptions& o) {
  // The factories validate; a body built field by field is checked again here.
  (void)RockingBody::general(body.a_m, body.h_m, body.D_m2);
  if (body.negative_pivot) {
    try {
      (void)RockingBody::general(body.negative_pivot->b_m, body.h_m, body.negative_pivot->D_m2);
    } catch (const InputError& err) {  // name the other pivot's fields
      throw parameter_error(err.where().field == "a" ? "b1" : err.where().field == "D" ? "D-" : err.where().field,
                            err.problem());
    }
    // Both pivots belong to one body: the same I_cm / m = D_s - b_s^2 - h^2 (to round-off of the sums).
    const double k2p = body.D_m2 - body.a_m * body.a_m - body.h_m * body.h_m;
    const double k2m = body.negative_pivot->D_m2 - body.negative_pivot->b_m * body.negative_pivot->b_m -
                       body.h_m * body.h_m;
    if (!(std::abs(k2p - k2m) <= 64.0 * std::numeric_limits<double>::epsilon() *
                                      std::max(body.D_m2, body.negative_pivot->D_m2))) {
      throw parameter_error("inertia", fmt::format("the pivots give different moments of inertia about the centre of "
                                                   "mass per unit mass ({:.6g} and {:.6g} m2): not one body",
                                                   k2p, k2m));
    }
  }
  require_positive(o.g_m_s2, "g", "g");
  if (o.restitution == RestitutionMode::given && (!std::isfinite(o.e) || o.e < 0.0 || o.e > 1.0)) {
    throw parameter_error("e", fmt::format("coefficient of restitution must be in [0, 1], got {}", o.e));
  }
  if (o.restitution == RestitutionMode::housner && body.negative_pivot) {
    for (const int onto : {1, -1}) {
      const double e = housner_restitution(body, onto);
      if (e < 0.0) {
        throw parameter_error("e", fmt::format("Housner's e = 1 - b_new (b_old + b_new) / D_new = {:.6g} on landing "
                                               "on the pivot O{} is negative for this squat body: it cannot rock "
                                               "onto that edge; {}",
                                               e, onto > 0 ? '+' : '-', kSquatBodyAdvice));
      }
    }
  }
  if (o.restitution == RestitutionMode::housner && !body.negative_pivot && housner_restitution(body) < 0.0) {
    throw parameter_error("e", fmt::format("Housner's e = 1 - 2a^2/D = {:.6g} is negative for this squat body "
                                           "(alpha = {:.4g} deg): it cannot rock onto the other edge; {}",
                                           housner_restitution(body), rad_to_deg(body.alpha_rad()),
                                           kSquatBodyAdvice));
  }
  if (o.mu && (!std::isfinite(*o.mu) || *o.mu < 0.0)) {
    throw parameter_error("mu", fmt::format("friction coefficient must be finite and >= 0, got {}", *o.mu));
  }
  if (!std::isfinite(o.rel_tol) || !(o.rel_tol > 0.0) || o.rel_tol >= 1.0) {
    throw parameter_error("rel_tol", fmt::format("relative tolerance must be in (0, 1), got {}", o.rel_tol));
  }
  if (!std::isfinite(o.abs_tol) || !(o.abs_tol > 0.0)) {
    throw parameter_error("abs_tol", fmt::format("absolute tolerance must be positive and finite, got {}", o.abs_tol));
  }
  if (o.rk4_substeps < 1) {
    throw parameter_error("rk4_substeps", fmt::format("RK4 needs at least 1 step per sample, got {}", o.rk4_substeps));
  }
  if (!std::isfinite(o.rest_energy_fraction) || !(o.rest_energy_fraction > 0.0) || o.rest_energy_fraction >= 1.0) {
    throw parameter_error("rest_energy_fraction",
                          fmt::format("must be in (0, 1), got {}", o.rest_energy_fraction));
  }
  if (!std::isfinite(o.max_run_out_s) || o.max_run_out_s < 0.0) {
    throw parameter_error("max_run_out_s", fmt::format("run-out time must be >= 0 and finite, got {}", o.max_run_out_s));
  }
  if (!std::isfinite(o.initial_theta_rad) || std::abs(o.initial_theta_rad) >= kPi / 2.0) {
    throw parameter_error("initial_theta_rad",
                          fmt::format("initial rotation must be finite and below pi/2 in magnitude, got {}",
                                      o.initial_theta_rad));
  }
  if (o.max_steps < 1) throw parameter_error("max_steps", "the integrator needs at least 1 step, got 0");
  if (!std::isfinite(o.initial_theta_dot_rad_s)) {
    throw parameter_error("initial_theta_dot_rad_s", "initial angular velocity must be finite");
  }
}

Params make_params(const RockingBody& body, const RockingOptions& o) {
  Params par;
  par.a = body.a_m;
  par.h = body.h_m;
  par.D = body.D_m2;
  par.R = body.R_m();
  par.alpha = body.alpha_rad();
  par.g = o.g_m_s2;
  par.p = body.p_rad_s(o.g_m_s2);
  par.tan_alpha = body.a_m / body.h_m;
  par.e = o.restitution == RestitutionMode::housner ? housner_restitution(body) : o.e;
  par.w_scale = par.p * par.alpha;
  // (D/2) theta'^2 < fraction * g R (1 - cos alpha), with 1 - cos alpha = 2 sin^2(alpha/2) (no cancellation).
  const double sh = std::sin(0.5 * par.alpha);
  par.rest_w2 = 2.0 * o.rest_energy_fraction * par.g * par.R * 2.0 * sh * sh / par.D;
  par.symmetric = body.symmetric();
  if (!par.symmetric) {
    // The scale of the state: a symmetric function of the two pivots (the smaller alpha and p), so that the mirror
    // body under the negated input takes the very same steps with the state negated (the mirror test is exact).
    const RockingBody neg = body.side_body(-1);
    par.alpha = std::min(par.alpha, neg.alpha_rad());
    par.p = std::min(par.p, neg.p_rad_s(o.g_m_s2));
    par.w_scale = par.p * par.alpha;
  }
  par.overturn_level = (kPi / 2.0) / par.alpha;
  for (const int s : {-1, 1}) {
    const std::size_t i = side(s);
    if (par.symmetric) {  // the very numbers above, so that a symmetric run is the same bit for bit
      par.alpha_side[i] = par.alpha;
      par.alpha_level[i] = 1.0;
      par.tan_side[i] = par.tan_alpha;
      par.D_side[i] = par.D;
      par.e_onto[i] = par.e;
      par.rest_w2_side[i] = par.rest_w2;
      par.k_side[i] = (par.R / par.D) / par.w_scale;
      continue;
    }
    const double b = body.pivot_b_m(s);
    const double D = body.pivot_D_m2(s);
    const double R = std::hypot(b, body.h_m);
    par.alpha_side[i] = std::atan2(b, body.h_m);  // = side_body(s).alpha_rad()
    par.alpha_level[i] = par.alpha_side[i] / par.alpha;
    par.tan_side[i] = b / body.h_m;
    par.D_side[i] = D;
    par.e_onto[i] = o.restitution == RestitutionMode::housner ? housner_restitution(body, s) : o.e;
    const double shs = std::sin(0.5 * par.alpha_side[i]);
    par.rest_w2_side[i] = 2.0 * o.rest_energy_fraction * par.g * R * 2.0 * shs * shs / D;
    par.k_side[i] = (R / D) / par.w_scale;
  }
  return par;
}

/// max over the input of |a_h| / (g + a_v): exact for piecewise-linear inputs (the ratio of two linear functions
/// is monotone on each interval, so its maximum sits on a sample).
double peak_accel_ratio(const Input& in, double g) {
  double peak = 0.0;
  for (std::size_t i = 0; i < in.size(); ++i) {
    peak = std::max(peak, std::abs(in.accel[i]) / (in.gravity.empty() ? g : in.gravity[i]));
  }
  return peak;
}

void onset(RockingSummary& sum, const RockingBody& whole, const RockingOptions& o, const Input& in,
           const std::optional<double>& uplift_ratio, int uplift_side, bool started_rocking) {
  if (!o.mu) return;
  // Shenton's criteria about one pivot involve that pivot only: an asymmetric body is judged on the pivot it lifted
  // about, or, when it did not lift, on the pivot with the lower uplift threshold (it would slide before either).
  const int s = uplift_side != 0 ? uplift_side
                                 : (whole.pivot_b_m(-1) < whole.pivot_b_m(1) ? -1 : 1);
  const RockingBody body = whole.side_body(s);
  const double mu = *o.mu;
  const double beta = body.a_m / body.h_m;
  if (mu < beta) {
    if (uplift_ratio || peak_accel_ratio(in, o.g_m_s2) > mu) {
      sum.onset_mode = OnsetMode::slide;
      sum.onset_accel_ratio = mu;
      sum.warnings.push_back(fmt::format("mu = {:.6g} < a/h = {:.6g}: the body slides before it can rock (Shenton "
                                         "1996); the rocking-only response is not valid for this friction",
                                         mu, beta));
    } else {
      sum.onset_mode = OnsetMode::rest;
    }
    return;
  }
  if (uplift_ratio) {
    sum.onset_accel_ratio = *uplift_ratio;
    sum.critical_mu = shenton_critical_mu(body, *uplift_ratio);
    sum.onset_mode = shenton_onset_mode(body, *uplift_ratio, mu);
    if (sum.onset_mode == OnsetMode::slide_rock) {
      sum.warnings.push_back(fmt::format("mu = {:.6g} < mu_crit = {:.6g} at lift-off (|a_h|/(g+a_v) = {:.6g}): the "
                                         "body starts in slide-rock mode (Shenton 1996); the rocking-only response "
                                         "is not valid for this friction",
                                         mu, *sum.critical_mu, *uplift_ratio));
    }
    return;
  }
  sum.onset_mode = started_rocking ? OnsetMode::unchecked : OnsetMode::rest;
}

template <bool kRecord>
RockingResult run(const GroundMotion& horizontal, const RockingBody& body, const RockingOptions& o,
                  const GroundMotion* vertical) {
  validate(body, o);
  const Input in(horizontal, vertical, o.g_m_s2);
  const Params par = make_params(body, o);
  Rhs rhs;
  rhs.p = par.p;
  rhs.set_alpha(par.alpha, par.alpha_side[0], par.alpha_side[1]);
  rhs.k = (par.R / par.D) / par.w_scale;
  rhs.ge0 = par.g;
  RockingResult result;
  std::optional<double> uplift_ratio;
  int uplift_side = 0;
  const bool started_rocking = o.initial_theta_rad != 0.0 || o.initial_theta_dot_rad_s != 0.0;
  if (o.method == RockingMethod::adaptive) {
    // First step guess: a tenth of the sample interval (the controller adapts it within a few steps).
    AdaptiveStepper stepper(rhs, o.abs_tol, o.rel_tol, 0.1 * in.dt());
    Engine<AdaptiveStepper, kRecord> engine(in, par, o, stepper, rhs);
    result = engine.run();
    uplift_ratio = engine.first_uplift_ratio_;
    uplift_side = engine.first_uplift_side_;
  } else {
    Rk4Stepper stepper(rhs, in.dt() / static_cast<double>(o.rk4_substeps));
    Engine<Rk4Stepper, kRecord> engine(in, par, o, stepper, rhs);
    result = engine.run();
    uplift_ratio = engine.first_uplift_ratio_;
    uplift_side = engine.first_uplift_side_;
  }
  RockingSummary& sum = result.summary;
  sum.alpha_rad = par.alpha_side[1];  // the O+ side's (the scale's for a symmetric body)
  sum.R_m = par.R;
  sum.p_rad_s = body.p_rad_s(par.g);
  sum.e = par.e_onto[1];
  sum.g_m_s2 = par.g;
  sum.e_onto_negative = par.e_onto[0];
  sum.alpha_negative_rad = par.alpha_side[0];
  sum.max_rotation_over_alpha_positive = sum.max_rotation_positive_rad / par.alpha_side[1];
  sum.max_rotation_over_alpha_negative = sum.max_rotation_negative_rad / par.alpha_side[0];
  sum.max_rotation_over_alpha = par.symmetric ? sum.max_abs_rotation_rad / par.alpha
                                              : std::max(sum.max_rotation_over_alpha_positive,
                                                         sum.max_rotation_over_alpha_negative);
  onset(sum, body, o, in, uplift_ratio, uplift_side, started_rocking);
  return result;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------------

double housner_restitution(const RockingBody& body) noexcept {
  // e = 1 - 2 m R^2 sin^2(alpha) / I_O with R sin(alpha) = a. An asymmetric body: the landing on O+.
  if (body.negative_pivot) return housner_restitution(body, 1);
  return 1.0 - 2.0 * body.a_m * body.a_m / body.D_m2;
}

double housner_restitution(const RockingBody& body, int onto) noexcept {
  // Angular momentum about the new pivot is conserved through the impact (docs/method.md, "Asymmetric bodies"):
  // D_new theta'+ = (D_new - b_new (b_old + b_new)) theta'-. (b_old + b_new) = 2a when symmetric, and 2a * a / D is
  // 2.0 * a * a / D bit for bit (doubling is exact).
  const double b_new = body.pivot_b_m(onto);
  const double b_old = body.pivot_b_m(-onto);
  return 1.0 - b_new * (b_old + b_new) / body.pivot_D_m2(onto);
}

constexpr std::array<EnumName<RockingState>, 4> kRockingStateNames{{
    {RockingState::rocking_negative, "rocking-"},
    {RockingState::rest, "rest"},
    {RockingState::rocking_positive, "rocking+"},
    {RockingState::fallen, "fallen"},
}};

std::string_view rocking_state_name(RockingState state) { return enum_name(kRockingStateNames, state); }

constexpr std::array<EnumName<RockingEventKind>, 6> kRockingEventNames{{
    {RockingEventKind::uplift, "uplift"},
    {RockingEventKind::impact, "impact"},
    {RockingEventKind::rest, "rest"},
    {RockingEventKind::peak, "peak"},
    {RockingEventKind::exceeded_alpha, "exceeded-alpha"},
    {RockingEventKind::overturned, "overturned"},
}};

std::string_view rocking_event_name(RockingEventKind kind) { return enum_name(kRockingEventNames, kind); }

RockingResult rock(const GroundMotion& horizontal, const RockingBody& body, const RockingOptions& options,
                   const GroundMotion* vertical) {
  return run<true>(horizontal, body, options, vertical);
}

RockingSummary rock_summary(const GroundMotion& horizontal, const RockingBody& body, const RockingOptions& options,
                            const GroundMotion* vertical) {
  return run<false>(horizontal, body, options, vertical).summary;
}

}  // namespace topple
