// Coupled slide-rock engine. See slide_rock.hpp for the model, the sign convention, the impact law and the method.
#include "topple/solvers/slide_rock.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <utility>

#include <boost/numeric/odeint/stepper/controlled_runge_kutta.hpp>
#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <fmt/format.h>

#include "topple/numerics/angle_series.hpp"
#include "topple/numerics/event_root.hpp"
#include "topple/numerics/step_law.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/input_grid.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {
namespace {

namespace odeint = boost::numeric::odeint;
using detail::find_root;
using detail::kMaxRootIterations;
using detail::time_tolerance;

/// Scaled state (u / Lu, u' / (p Lu), theta / alpha, theta' / (p alpha), W / (g Lu)), Lu = h alpha, W the work of
/// kinetic friction since the last restart.
using State = std::array<double, 5>;
using Dopri = odeint::runge_kutta_dopri5<State>;

/// Boost.Odeint's step adjuster interface with its default law (step_law.hpp, the rocking engine's: the same steps,
/// without libm pow, which was 7 % of a rocking run). Orders are dopri5's (error order 4, stepper order 5).
struct StepAdjuster {
  using time_type = double;
  using value_type = double;
  [[nodiscard]] double decrease_step(double dt, double error, int /*error_order*/) const {
    return detail::StepLaw::decrease(dt, error);
  }
  [[nodiscard]] double increase_step(double dt, double error, int /*stepper_order*/) const {
    return detail::StepLaw::increase(dt, error);
  }
  [[nodiscard]] bool check_step_size_limit(double /*dt*/) const { return true; }
  [[nodiscard]] double get_max_dt() const { return 0.0; }
};

using Checker = odeint::default_error_checker<double, Dopri::algebra_type, Dopri::operations_type>;
using Controlled = odeint::controlled_runge_kutta<Dopri, Checker, StepAdjuster>;

constexpr std::size_t side(int s) { return s > 0 ? 1 : 0; }
constexpr std::size_t index(SlideRockMode m) { return static_cast<std::size_t>(m); }
constexpr int sign(double x) { return x > 0.0 ? 1 : (x < 0.0 ? -1 : 0); }

/// The loads per unit mass on a base inclined at beta (cos cb, sin sb) under a_h and g_e (slide_rock.hpp, sliding.hpp;
/// Goodman & Seed 1966): tangential f_t = a_h cos(beta) + g_e sin(beta) toward -x (down-slope), normal
/// n = g_e cos(beta) - a_h sin(beta).
struct BaseLoad {
  double t = 0.0, n = 0.0;
};
constexpr BaseLoad on_base(double ah, double ge, double cb, double sb) { return {ah * cb + ge * sb, ge * cb - ah * sb}; }

/// Cap on events inside one sample interval (a valid input gives a handful).
constexpr int kMaxEventsPerInterval = 100'000;
/// The witness functions of rock and slide-rock, by name (as Drake's WitnessFunction: a signed function of the state
/// and time, positive while the mode holds; a step ends where one falls through 0, located by root finding): their
/// indices in the values of Engine::events.
enum Witness : std::size_t {
  kImpact = 0,      ///< s theta: the body comes back onto its base (impact on the other pivot)
  kFall = 1,        ///< pi/2 - s theta: it has fallen
  kFlight = 2,      ///< N / g: the normal force vanishes, the body leaves the ground
  kSlipOrStop = 3,  ///< rock: the stick limit (mu_s N - |F|) / g (slip starts); slide-rock: sigma u' (the slip stops)
  kPainleve = 4,    ///< slide-rock: den / D_s (the Painleve point, an impact without collision)
};
constexpr std::size_t kEvents = 5;       ///< the witnesses
constexpr std::size_t kStickMargin = 5;  ///< Engine::events' sixth value, not a witness: rock's (mu_s N - |F|) / g

/// What ended a step, as one int (`which` in Engine::rock_phase; one int, not a struct, keeps the step loop as fast as
/// it was): kNoWitness; a Witness (it fell through 0, at its root); or kNotTaken + a Witness (it started at 0 and went
/// the wrong way: a lift-off or a slip that round-off decided, the mode then decided again at the step's end).
constexpr int kNoWitness = -1;
constexpr int kNotTaken = 10;
/// Sub-intervals of a sample interval on which a strike from flight is looked for (slide_rock.hpp).
constexpr int kFlightPieces = 16;

struct Params {
  std::array<double, 2> b{};      // index side(s): O- (b1), O+ (b2)
  std::array<double, 2> D{};      // k2 + b^2 + h^2
  std::array<double, 2> alpha{};  // atan(b / h)
  std::array<double, 2> rest_w2{};  // theta'^2 below which the rest rule applies after landing on the pivot
  double h = 0.0, k2 = 0.0, mus = 0.0, muk = 0.0, g = 0.0;
  double g_t = 0.0, g_n = 0.0;  // still ground's loads on the base: g sin(beta) (toward -x), g cos(beta)
  std::optional<double> e_given;
  double alpha_sc = 0.0, p_sc = 0.0, Lu = 0.0;  // state scales
  std::array<double, 2> inv_D{};  // 1 / D, for the right-hand side
  double to_u = 0.0, to_th = 0.0, to_work = 0.0;  // 1 / (p Lu), 1 / (p alpha), 1 / (g Lu): accelerations to scaled
};

/// Accelerations and contact forces (per unit mass) on one corner: slide_rock.hpp's rock (sigma = 0) and slide-rock
/// (sigma = +-1) equations.
struct Contact {
  double udd = 0.0, thdd = 0.0, N = 0.0, F = 0.0;
  double den = 0.0;       // slide-rock: k2 + c rho_x (m^2)
  bool painleve = false;  // den <= 0: Coulomb friction has no unique solution (Painleve 1895)
};

/// sin and cos of theta near the start of the current step (angle_series.hpp): one libm call per step, not one per
/// stage.
struct Angle {
  double ref = 0.0, sin_ref = 0.0, cos_ref = 1.0;
  int moves = 0;
  void set(double th) {
    ref = th;
    sin_ref = std::sin(th);
    cos_ref = std::cos(th);
    moves = 0;
  }
  /// The reference to theta at the next step's start by the series (angle_series.hpp, as the rocking engine).
  void move(double th) {
    if (!detail::move_reference(th, ref, sin_ref, cos_ref, moves)) set(th);
  }
  void at(double th, double& sn, double& cs) const { detail::sin_cos_near(th, ref, sin_ref, cos_ref, sn, cs); }
};

Contact contact(const Params& P, int s, int sigma, double sn, double c, double w, double ah, double ge);

Contact contact(const Params& P, int s, int sigma, double th, double w, double ah, double ge) {
  return contact(P, s, sigma, std::sin(th), std::cos(th), w, ah, ge);
}

Contact contact(const Params& P, int s, int sigma, double sn, double c, double w, double ah, double ge) {
  const double b = P.b[side(s)];
  const double rx = -s * b * c + P.h * sn;  // CM seen from the pivot
  const double ry = s * b * sn + P.h * c;
  const double w2 = w * w;
  Contact r;
  if (sigma == 0) {
    r.thdd = (rx * ge - ry * ah) * P.inv_D[side(s)];
    r.F = ry * r.thdd - rx * w2 + ah;
    r.N = ge - rx * r.thdd - ry * w2;
    return r;
  }
  const double cc = rx + sigma * P.muk * ry;
  const double den = P.k2 + cc * rx;
  r.den = den;
  if (!(den > 0.0)) {
    r.painleve = true;
    return r;
  }
  r.thdd = cc * (ge - ry * w2) / den;
  r.N = ge - rx * r.thdd - ry * w2;
  r.F = -sigma * P.muk * r.N;
  r.udd = -ah + r.F - ry * r.thdd + rx * w2;
  return r;
}

/// The mode decided on one corner s (theta on side s, or 0 with theta' toward it): slip continues while the pivot
/// slips (v != 0); else stick when N >= 0 and |F| <= mu_s N; else slip against the friction needed; flight when N < 0.
/// Painleve's paradox (slide-rock's den <= 0; docs/method.md): a slipping pivot is stopped by a tangential impact
/// first (`tangential_impact`, then decided again at v = 0); a sticking one whose every slip has den <= 0 is held
/// (rock, `painleve_hold`).
struct Decision {
  SlideRockMode mode = SlideRockMode::rest;
  int s = 1;
  int sigma = 0;
  bool tangential_impact = false;
  bool painleve_hold = false;
};

Decision decide_corner(const Params& P, int s, double v, double th, double w, double ah, double ge) {
  int sigma = sign(v);
  if (sigma == 0) {
    const Contact st = contact(P, s, 0, th, w, ah, ge);
    if (st.N < 0.0) return {SlideRockMode::flight, s, 0};
    if (std::abs(st.F) <= P.mus * st.N) return {SlideRockMode::rock, s, 0};
    sigma = -sign(st.F);
  }
  const Contact sl = contact(P, s, sigma, th, w, ah, ge);
  if (sl.painleve) {
    // Slipping: the impact without collision (Lecornu's jump) stops the pivot. At zero slip: the corner sticks (a slip
    // that started would be stopped at once by that impact, with zero impulse).
    if (v != 0.0) return {SlideRockMode::slide_rock, s, sigma, true, false};
    return {SlideRockMode::rock, s, 0, false, true};
  }
  if (sl.N < 0.0) return {SlideRockMode::flight, s, 0};
  return {SlideRockMode::slide_rock, s, sigma};
}

/// Both corners down, theta = theta' = 0, slide velocity v: the two-contact complementarity problem by enumeration
/// (rest, slide, rock, slide-rock; slide_rock.hpp). From rest, a symmetric body with mu_k = mu_s gets Shenton's modes.
Decision decide_both(const Params& P, double v, double ah, double ge) {
  if (!(ge > 0.0)) return {SlideRockMode::flight, 1, 0};
  const double bsum = P.b[0] + P.b[1];
  if (v != 0.0) {
    const int sigma = sign(v);
    const double np = ge * (P.b[0] + sigma * P.muk * P.h) / bsum;  // N+ while sliding
    const double nm = ge * (P.b[1] - sigma * P.muk * P.h) / bsum;  // N-
    if (np >= 0.0 && nm >= 0.0) return {SlideRockMode::slide, 1, sigma};
    return decide_corner(P, nm < 0.0 ? 1 : -1, v, 0.0, 0.0, ah, ge);  // the unloaded corner lifts
  }
  const double np = (P.b[0] * ge - P.h * ah) / bsum;
  const double nm = (P.b[1] * ge + P.h * ah) / bsum;
  if (np >= 0.0 && nm >= 0.0 && std::abs(ah) <= P.mus * ge) return {SlideRockMode::rest, 1, 0};
  if (std::abs(ah) > P.mus * ge) {  // slide: the base accelerates against a_h
    const int sigma = -sign(ah);
    const double kp = ge * (P.b[0] + sigma * P.muk * P.h) / bsum;
    const double km = ge * (P.b[1] - sigma * P.muk * P.h) / bsum;
    if (kp >= 0.0 && km >= 0.0 && sigma * (-ah - sigma * P.muk * ge) > 0.0) return {SlideRockMode::slide, 1, sigma};
  }
  for (const int s : {1, -1}) {  // rock about the corner the throw lifts the body onto
    const Contact r = contact(P, s, 0, 0.0, 0.0, ah, ge);
    if (s * r.thdd > 0.0 && r.N >= 0.0 && std::abs(r.F) <= P.mus * r.N) return {SlideRockMode::rock, s, 0};
  }
  for (const int s : {1, -1}) {
    for (const int sigma : {1, -1}) {
      const Contact r = contact(P, s, sigma, 0.0, 0.0, ah, ge);
      if (!r.painleve && s * r.thdd > 0.0 && sigma * r.udd > 0.0 && r.N >= 0.0) {
        return {SlideRockMode::slide_rock, s, sigma};
      }
    }
  }
  return {SlideRockMode::rest, 1, 0};  // no consistent motion (marginal input): full contact
}

// ---------------------------------------------------------------------------------------------------------------

/// The forcing over the current interval: a_h = ah0 + ahs (t - t_ref), g_e = ge0 + ges (t - t_ref).
struct Forcing {
  double t_ref = 0.0, ah0 = 0.0, ahs = 0.0, ge0 = 0.0, ges = 0.0;
  [[nodiscard]] double ah(double t) const { return ah0 + ahs * (t - t_ref); }
  [[nodiscard]] double ge(double t) const { return ge0 + ges * (t - t_ref); }
};

/// Right-hand side of rock / slide-rock in the scaled state.
struct Rhs {
  const Params* P = nullptr;
  const Forcing* f = nullptr;
  const Angle* angle = nullptr;
  int s = 1;
  int sigma = 0;
  void operator()(const State& y, State& dy, double t) const {
    const Params& Q = *P;
    const double ps = Q.p_sc;
    const double th = y[2] * Q.alpha_sc;
    const double w = y[3] * ps * Q.alpha_sc;
    double sn = 0.0;
    double cs = 1.0;
    angle->at(th, sn, cs);
    dy[0] = ps * y[1];
    dy[2] = ps * y[3];
    if (sigma == 0) {  // rock: the pivot sticks, only theta'' (slide_rock.hpp)
      const double b = Q.b[side(s)];
      const double rx = -s * b * cs + Q.h * sn;
      const double ry = s * b * sn + Q.h * cs;
      dy[1] = 0.0;
      dy[3] = (rx * f->ge(t) - ry * f->ah(t)) * Q.inv_D[side(s)] * Q.to_th;
      dy[4] = 0.0;
      return;
    }
    const Contact c = contact(Q, s, sigma, sn, cs, w, f->ah(t), f->ge(t));
    dy[1] = c.udd * Q.to_u;
    dy[3] = c.thdd * Q.to_th;
    dy[4] = Q.muk * c.N * std::abs(y[1]) * ps * Q.Lu * Q.to_work;  // mu_k N |u'| / (g Lu)
  }
};

/// Physical state in contact modes (u, u', theta, theta') and, in flight, the CM (X, X', Y, Y').
struct Phys {
  double u = 0.0, v = 0.0, th = 0.0, w = 0.0;
  double work = 0.0;  // friction work since the last restart (rock / slide-rock), J/kg
  double X = 0.0, Xd = 0.0, Y = 0.0, Yd = 0.0;
};

class Engine {
 public:
  /// `accel`, `gravity`: the loads a_h and g_e on the grid, or on an inclined base f_t and n (slide_rock.hpp);
  /// `gravity` empty: g everywhere (level base only).
  Engine(const InputGrid& grid, std::span<const double> accel, std::span<const double> gravity, const Params& P,
         const SlideRockOptions& o)
      : grid_(grid), accel_(accel), gravity_(gravity), P_(P), o_(o),
        stepper_(Controlled(Checker(o.abs_tol, o.rel_tol, 1.0, 0.0), StepAdjuster{})) {
    rhs_.P = &P_;
    rhs_.f = &f_;
    rhs_.angle = &angle_;
  }

  SlideRockResult run() {
    const std::size_t n = grid_.size();
    t_ = grid_.time_s(0);
    dt_ = 0.1 * grid_.dt_s();
    set_forcing(0);
    if (o_.initial_theta_rad != 0.0 || o_.initial_theta_dot_rad_s != 0.0) {
      x_.th = o_.initial_theta_rad;
      x_.w = o_.initial_theta_dot_rad_s;
      x_.v = o_.initial_slide_velocity_m_s;
      const int s = x_.th != 0.0 ? sign(x_.th) : sign(x_.w);
      apply(decide_corner(P_, s, x_.v, x_.th, x_.w, f_.ah(t_), f_.ge(t_)));
    } else if (o_.initial_slide_velocity_m_s != 0.0) {
      x_.v = o_.initial_slide_velocity_m_s;
      apply(decide_both(P_, x_.v, f_.ah(t_), f_.ge(t_)));
    } else {
      enter(SlideRockMode::rest);
    }
    row();
    for (std::size_t i = 0; i + 1 < n && !done_; ++i) {
      if (mode_ == SlideRockMode::rest && gravity_.empty()) {
        // Full contact: one test per sample (the rest region is convex in a_h, so both ends inside keep the whole
        // interval inside).
        const double lim = std::min({P_.mus, P_.b[0] / P_.h, P_.b[1] / P_.h}) * P_.g;
        if (std::abs(accel_[i]) <= lim) {
          while (i + 1 < n && std::abs(accel_[i + 1]) <= lim) {
            ++i;
            t_ = grid_.time_s(i);
            if (o_.record_history) row();
          }
          if (i + 1 >= n) break;
        }
      }
      const double ta = grid_.time_s(i);
      const double tb = grid_.time_s(i + 1);
      t_ = std::max(t_, ta);
      if (!(tb > ta)) {
        restart_ = true;
        continue;
      }
      set_forcing(i);
      interval(tb, false);
      if (!done_) {
        t_ = tb;
        if (o_.record_history) row();
      }
    }
    if (!done_ && o_.max_run_out_s > 0.0 && mode_ != SlideRockMode::rest) {
      // After the record: still ground until rest, fall or the cap (on a slope: its loads g sin(beta), g cos(beta)).
      f_ = Forcing{t_, P_.g_t, 0.0, P_.g_n, 0.0};
      restart_ = true;
      interval(t_ + o_.max_run_out_s, true);
    }
    finish();
    return std::move(out_);
  }

 private:
  void set_forcing(std::size_t i) {
    const double ta = grid_.time_s(i);
    const double tb = grid_.time_s(std::min(i + 1, grid_.size() - 1));
    const double span = tb - ta;
    const double g0 = gravity_.empty() ? P_.g : gravity_[i];
    const double g1 = gravity_.empty() ? P_.g : gravity_[std::min(i + 1, grid_.size() - 1)];
    const double a1 = accel_[std::min(i + 1, grid_.size() - 1)];
    // No restart: the forcing is continuous at a sample instant (only its slope changes), so the derivative the
    // last step ended with holds for the next interval too; jumps (two samples at one instant) restart.
    f_ = Forcing{ta, accel_[i], span > 0.0 ? (a1 - accel_[i]) / span : 0.0, g0, span > 0.0 ? (g1 - g0) / span : 0.0};
  }

  // ---- bookkeeping ----
  /// `from_stick`: the contact starts to slip from zero slip velocity (a new slip episode, as sliding.hpp counts
  /// a reversal through d' = 0).
  void enter(SlideRockMode m, bool from_stick = false) {
    SlideRockSummary& sum = out_.summary;
    restart_ = true;
    const bool slipping = m == SlideRockMode::slide || m == SlideRockMode::slide_rock;
    const bool was_slipping = mode_ == SlideRockMode::slide || mode_ == SlideRockMode::slide_rock;
    if (slipping && (!was_slipping || !started_ || from_stick)) ++sum.slip_episodes;
    if (started_ && m == mode_) return;
    if (mode_ == SlideRockMode::rest && m != SlideRockMode::rest && started_) {
      if (sum.onset_mode == SlideRockMode::rest && !moved_) sum.onset_mode = m;
      if (m == SlideRockMode::rock || m == SlideRockMode::slide_rock) ++sum.uplifts;
    }
    if (m != SlideRockMode::rest) moved_ = true;
    mode_ = m;
    started_ = true;
    ++sum.mode_entries[index(m)];
    if (!sum.mode_first_time_s[index(m)]) sum.mode_first_time_s[index(m)] = t_;
    out_.transitions.push_back({t_, m});
    restart_ = true;
  }

  void apply(const Decision& d) {
    if (d.tangential_impact) {  // Painleve: stop the slipping pivot, then decide at zero slip (never a second impact)
      s_ = d.s;
      tangential_impact();
      apply(decide_corner(P_, s_, 0.0, x_.th, x_.w, f_.ah(t_), f_.ge(t_)));
      return;
    }
    if (d.painleve_hold && !holding_) ++out_.summary.painleve_holds;
    holding_ = d.painleve_hold;
    const bool from_stick = x_.v == 0.0;
    s_ = d.s;
    sigma_ = d.sigma;
    if (d.mode == SlideRockMode::flight) to_flight();
    if (d.mode == SlideRockMode::rest || d.mode == SlideRockMode::slide) {
      x_.th = 0.0;
      x_.w = 0.0;
      if (d.mode == SlideRockMode::rest) x_.v = 0.0;
    }
    if (d.mode == SlideRockMode::rock) x_.v = 0.0;
    enter(d.mode, from_stick);
  }

  /// u of the corner on the side of theta from the CM in flight (slide_rock.hpp's definition of u).
  [[nodiscard]] double flight_u(const Phys& x) const {
    const int s = x.th < 0.0 ? -1 : 1;
    const double b = P_.b[side(s)];
    return x.X + s * b * std::cos(x.th) - P_.h * std::sin(x.th) - s * b;
  }
  [[nodiscard]] double cm_height(const Phys& x) const {
    if (mode_ == SlideRockMode::flight) return x.Y;
    return s_ * P_.b[side(s_)] * std::sin(x.th) + P_.h * std::cos(x.th);
  }
  /// Mechanical energy in the ground's frame, J/kg, with the potential g cos(beta) (Y - h) + g sin(beta) X (X the
  /// CM's displacement along the base: up-slope is +x).
  [[nodiscard]] double energy(const Phys& x) const {
    double vx = x.Xd;
    double vy = x.Yd;
    double X = x.X;
    if (mode_ != SlideRockMode::flight) {
      const double b = P_.b[side(s_)];
      X = x.u + s_ * b * (1.0 - std::cos(x.th)) + P_.h * std::sin(x.th);
    }
    const double along = P_.g_t == 0.0 ? 0.0 : P_.g_t * X;  // level: exactly the potential g (Y - h)
    if (mode_ != SlideRockMode::flight) {
      const double b = P_.b[side(s_)];
      const double ry = s_ * b * std::sin(x.th) + P_.h * std::cos(x.th);
      const double rx = -s_ * b * std::cos(x.th) + P_.h * std::sin(x.th);
      vx = x.v + ry * x.w;
      vy = -rx * x.w;
    }
    return 0.5 * (vx * vx + vy * vy + P_.k2 * x.w * x.w) + P_.g_n * (cm_height(x) - P_.h) + along;
  }

  void track(const Phys& x) {
    SlideRockSummary& sum = out_.summary;
    const double u = mode_ == SlideRockMode::flight ? flight_u(x) : x.u;
    sum.max_abs_slide_m = std::max(sum.max_abs_slide_m, std::abs(u));
    if (x.th > 0.0) sum.max_rotation_positive_rad = std::max(sum.max_rotation_positive_rad, x.th);
    if (x.th < 0.0) sum.max_rotation_negative_rad = std::max(sum.max_rotation_negative_rad, -x.th);
    if (!sum.exceeded_alpha_time_s && x.th != 0.0 && std::abs(x.th) >= P_.alpha[side(sign(x.th))]) {
      sum.exceeded_alpha_time_s = t_;
    }
  }

  void row() { row_at(t_, x_); }
  void row_at(double t, const Phys& x) {
    track(x);
    if (!o_.record_history) return;
    auto& h = out_.history;
    h.time_s.push_back(t);
    h.slide_m.push_back(mode_ == SlideRockMode::flight ? flight_u(x) : x.u);
    h.slide_velocity_m_s.push_back(mode_ == SlideRockMode::flight ? x.Xd + x.w * corner_r(x.th < 0.0 ? -1 : 1, x.th)[1]
                                                                    : x.v);
    h.theta_rad.push_back(x.th);
    h.theta_dot_rad_s.push_back(x.w);
    h.cm_height_m.push_back(cm_height(x));
    h.energy_j_per_kg.push_back(energy(x));
    h.mode.push_back(mode_);
  }

  /// Corner c's position from the CM at rotation theta: (r_x, r_y).
  [[nodiscard]] std::array<double, 2> corner_r(int c, double th) const {
    const double b = P_.b[side(c)];
    return {c * b * std::cos(th) - P_.h * std::sin(th), -c * b * std::sin(th) - P_.h * std::cos(th)};
  }

  [[nodiscard]] std::string describe() const {
    return fmt::format("b1 = {:.6g} m, b2 = {:.6g} m, h = {:.6g} m, k2 = {:.6g} m2, mu_s = {:.6g}, mu_k = {:.6g}, "
                       "rel_tol = {:.3g}",
                       P_.b[0], P_.b[1], P_.h, P_.k2, P_.mus, P_.muk, o_.rel_tol);
  }

  // ---- one interval [t_, tb] of linear forcing ----
  void interval(double tb, bool run_out) {
    int events = 0;
    while (!done_ && t_ < tb) {
      if (run_out && mode_ == SlideRockMode::rest) return;
      if (++events > kMaxEventsPerInterval) {
        throw EventLimitError(fmt::format("slide-rock: more than {} events in the interval ending at {} s ({}): the "
                                          "input is outside the model",
                                          kMaxEventsPerInterval, tb, describe()));
      }
      switch (mode_) {
        case SlideRockMode::rest: rest_phase(tb); break;
        case SlideRockMode::slide: slide_phase(tb); break;
        case SlideRockMode::rock:
        case SlideRockMode::slide_rock: rock_phase(tb); break;
        case SlideRockMode::flight: flight_phase(tb); break;
        case SlideRockMode::fallen: done_ = true; break;
      }
    }
  }

  /// Full contact: leave at the first root of the linear functions mu_s g_e -+ a_h, b1 g_e - h a_h, b2 g_e + h a_h.
  void rest_phase(double tb) {
    const auto fns = [&](double t) {
      const double a = f_.ah(t);
      const double g = f_.ge(t);
      return std::array<double, 4>{P_.mus * g - a, P_.mus * g + a, P_.b[0] * g - P_.h * a, P_.b[1] * g + P_.h * a};
    };
    const auto f0 = fns(t_);
    const auto f1 = fns(tb);
    double te = tb;
    bool leave = false;
    for (std::size_t k = 0; k < 4; ++k) {
      if (f0[k] < 0.0) {
        te = t_;
        leave = true;
      } else if (f1[k] < 0.0) {
        te = std::min(te, t_ + (tb - t_) * f0[k] / (f0[k] - f1[k]));
        leave = true;
      }
    }
    if (!leave) {
      t_ = tb;
      return;
    }
    t_ = std::min(te, tb);
    // The mode is decided just past the exit, where the rest conditions have failed (at the root they hold with
    // equality): the forcing a millionth of the rest of the interval later.
    const double tl = t_ + 1e-6 * (tb - t_);
    const Decision d = decide_both(P_, 0.0, f_.ah(tl), f_.ge(tl));
    if (d.mode == SlideRockMode::rest) {  // marginal: nothing consistent moves; wait to the end of the interval
      t_ = tb;
      return;
    }
    apply(d);
    row();
  }

  /// Slide, exact: u'' = c0 + c1 tau (tau = t - t_), the stop is the first root of sigma u' (a quadratic).
  void slide_phase(double tb) {
    const int sg = sigma_;
    const double L = tb - t_;
    const double c0 = -f_.ah(t_) - sg * P_.muk * f_.ge(t_);
    const double c1 = -f_.ahs - sg * P_.muk * f_.ges;
    // sigma u'(tau) = C + B tau + A tau^2
    const double C = sg * x_.v;
    const double B = sg * c0;
    const double A = 0.5 * sg * c1;
    double tau = L;
    bool stop = false;
    // A slip that starts (C = 0) where the forcing is at the stick limit to round-off may have B <= 0: the speed's
    // quadratic then dips below 0 only by round-off, to its root -B/A, which is not a stop; when it has no later rise
    // (A <= 0) the slip does not start at all and the body stays in contact to the end of the interval.
    const double spurious = C == 0.0 && B <= 0.0 && A > 0.0 ? -B / A : 0.0;
    if (C == 0.0 && B <= 0.0 && A <= 0.0) {
      t_ = tb;
      apply({SlideRockMode::rest, 1, 0});
      row();
      return;
    }
    const auto consider = [&](double r) {
      if (r > spurious * (1.0 + 1e-9) && r <= tau) {
        tau = r;
        stop = true;
      }
    };
    if (A == 0.0) {
      if (B != 0.0) consider(-C / B);
    } else {
      const double disc = B * B - 4.0 * A * C;
      if (disc >= 0.0) {
        const double q = -0.5 * (B + (B >= 0.0 ? 1.0 : -1.0) * std::sqrt(disc));  // stable roots q / A, C / q
        if (q != 0.0) {
          consider(q / A);
          consider(C / q);
        } else {
          consider(0.0);
        }
      }
    }
    // g_e reaching 0 (the body leaves the ground): linear root
    double tg = std::numeric_limits<double>::infinity();
    if (f_.ge(tb) <= 0.0) tg = t_ + (tb - t_) * f_.ge(t_) / (f_.ge(t_) - f_.ge(tb));
    bool fly = false;
    if (tg - t_ < tau) {
      tau = std::max(0.0, tg - t_);
      stop = false;
      fly = true;
    }
    const double G0 = f_.ge(t_);
    const double G1 = f_.ges;
    // friction work mu_k int g_e |u'| dtau, exact for the polynomial integrand
    const double t2 = tau * tau;
    out_.summary.friction_energy_j_per_kg +=
        P_.muk * (G0 * (C * tau + B * t2 / 2.0 + A * t2 * tau / 3.0) + G1 * (C * t2 / 2.0 + B * t2 * tau / 3.0 + A * t2 * t2 / 4.0));
    x_.u += x_.v * tau + c0 * t2 / 2.0 + c1 * t2 * tau / 6.0;
    x_.v = stop ? 0.0 : x_.v + c0 * tau + c1 * t2 / 2.0;
    t_ = stop || fly ? t_ + tau : tb;
    if (fly) {
      apply({SlideRockMode::flight, 1, 0});
      row();
    } else if (stop) {
      apply(decide_both(P_, 0.0, f_.ah(t_), f_.ge(t_)));
      row();
    }
  }

  // ---- rock and slide-rock: Boost.Odeint's controlled Dormand-Prince with dense output ----
  [[nodiscard]] State scaled(const Phys& x) const {
    return {x.u / P_.Lu, x.v / (P_.p_sc * P_.Lu), x.th / P_.alpha_sc, x.w / (P_.p_sc * P_.alpha_sc), 0.0};
  }
  [[nodiscard]] Phys physical(const State& y) const {
    Phys x;
    x.u = y[0] * P_.Lu;
    x.v = y[1] * P_.p_sc * P_.Lu;
    x.th = y[2] * P_.alpha_sc;
    x.w = y[3] * P_.p_sc * P_.alpha_sc;
    x.work = y[4] * P_.g * P_.Lu;
    return x;
  }
  [[nodiscard]] Phys dense(double t) const {
    if (t == t1_) return physical(y1_);
    State y{};
    stepper_.stepper().calc_state(t, y, y0_, dy0_, t0_, y1_, dy1_, t1_);
    return physical(y);
  }

  /// The event functions of rock / slide-rock on a physical state at t: {impact: s theta, fall: pi/2 - s theta,
  /// flight: N / g, slip (rock): (mu_s N - |F|) / g or stop (slide-rock): sigma u', Painleve (slide-rock):
  /// den / D_s}. Rock's slip function is max((mu_s N - |F|) / g, -den / D_s) outside the cone, den that of the slip
  /// that would start: a slip with den <= 0 does not start (the Painleve hold), so the slip event is where the stick
  /// limit is passed with den > 0.
  /// A sixth entry (not an event) is rock's stick margin (mu_s N - |F|) / g, 0 in slide-rock: negative with a positive
  /// slip function means the Painleve hold.
  [[nodiscard]] std::array<double, kEvents + 1> events(const Phys& x, double t) const {
    double sn = 0.0;
    double cs = 1.0;
    angle_.at(x.th, sn, cs);
    const double ah = f_.ah(t);
    const double ge = f_.ge(t);
    const Contact c = contact(P_, s_, sigma_, sn, cs, x.w, ah, ge);
    double last = sigma_ * x.v;
    double painleve = 1.0;
    double margin = 0.0;
    if (sigma_ == 0) {
      last = (P_.mus * c.N - std::abs(c.F)) / P_.g;
      margin = last;
      if (last < 0.0) {
        const Contact sl = contact(P_, s_, c.F > 0.0 ? -1 : 1, sn, cs, x.w, ah, ge);
        last = std::max(last, -sl.den * P_.inv_D[side(s_)]);
      }
    } else {
      painleve = c.den * P_.inv_D[side(s_)];
    }
    return {s_ * x.th, kPi / 2.0 - s_ * x.th, c.N / P_.g, last, painleve, margin};  // the Witness order, kStickMargin
  }

  void rock_phase(double tb) {
    rhs_.s = s_;
    rhs_.sigma = sigma_;
    if (restart_) {
      work_base_ = out_.summary.friction_energy_j_per_kg;
      y1_ = scaled(x_);
      t1_ = t_;
      angle_.set(x_.th);
      rhs_(y1_, dy1_, t_);
      restart_ = false;
      events_cached_ = false;
    }
    if (tb - t_ <= time_tolerance(tb)) {
      t_ = tb;
      return;
    }
    // one accepted step, never past tb
    angle_.move(x_.th);
    y0_ = y1_;
    dy0_ = dy1_;
    t0_ = t_;
    for (;;) {
      if (++out_.summary.steps > o_.max_steps) {
        throw StepLimitError(fmt::format("slide-rock: more than max_steps = {} integrator steps by t = {} s ({})",
                                         o_.max_steps, t_, describe()));
      }
      const bool clamped = dt_ >= tb - t0_;
      double dt = clamped ? tb - t0_ : dt_;
      double t = t0_;
      if (stepper_.try_step(std::cref(rhs_), y0_, dy0_, t, y1_, dy1_, dt) == odeint::success) {
        t1_ = clamped ? tb : t;
        dt_ = clamped ? std::max(dt_, dt) : dt;
        break;
      }
      dt_ = dt;
    }
    const Phys x0 = x_;
    const Phys x1 = physical(y1_);
    const auto e0 = events_cached_ ? events_last_ : events(x0, t0_);
    const auto e1 = events(x1, t1_);
    events_last_ = e1;
    events_cached_ = true;
    if (sigma_ == 0) {  // count the holds (nothing changes in the motion where one starts: not located)
      const bool hold = e1[kStickMargin] < 0.0 && e1[kSlipOrStop] > 0.0;
      if (hold && !holding_) ++out_.summary.painleve_holds;
      holding_ = hold;
    }
    // The earliest of the mode-ending events ends the step.
    // A turning point of s theta inside the step (theta' from s to -s): s theta rises before it, so an impact can
    // only come after it (the step may hold a whole small half-cycle); it is a row (max rotation).
    double tp = t0_;
    if (s_ * x0.w > 0.0 && s_ * x1.w <= 0.0) {
      tp = find_root([&](double t) { return s_ * dense(t).w; }, t0_, t1_, s_ * x0.w, s_ * x1.w);
      if (std::isnan(tp)) tp = t0_;
    }
    double te = t1_;
    int which = kNoWitness;
    for (std::size_t k = 0; k < kEvents; ++k) {
      double ta = t0_;
      double fa = e0[k];
      if (k == kImpact && tp > t0_) {  // the impact function after the peak
        ta = tp;
        fa = s_ * dense(tp).th;
      }
      if (e1[k] < 0.0 || (k != kFall && e1[k] == 0.0 && fa > 0.0)) {
        if (fa <= 0.0) {
          // A mode that did not take (an event function starting at 0 and going the wrong way: a lift-off or a slip
          // that round-off decided): decided again at the step's end.
          if (t0_ < te) {
            te = t0_;
            which = kNotTaken + static_cast<int>(k);
          }
          continue;
        }
        // impact and fall need theta only (events()'s values, without the contact forces: the impact's root is the
        // most frequent one)
        const auto fk = [&](double t) {
          const Phys x = dense(t);
          if (k == kImpact) return s_ * x.th;
          if (k == kFall) return kPi / 2.0 - s_ * x.th;
          return events(x, t)[k];
        };
        const double r = find_root(fk, ta, t1_, fa, e1[k]);
        if (std::isnan(r)) {
          throw RootFindingError(fmt::format("slide-rock: event location did not converge in {} iterations on [{}, {}] "
                                             "s ({})", kMaxRootIterations, ta, t1_, describe()));
        }
        if (r < te || which == kNoWitness) {
          te = r;
          which = static_cast<int>(k);
        }
      }
    }
    locate_alpha(x0, x1, tp, which >= 0 && which < kNotTaken ? te : t1_);
    if (tp > t0_ && tp <= te) row_at(tp, dense(tp));
    if (which == kNoWitness) {
      t_ = t1_;
      x_ = x1;
      out_.summary.friction_energy_j_per_kg = work_base_ + x_.work;
      if (o_.record_history) row();
      else track(x_);
      return;
    }
    if (which >= kNotTaken) {  // did not take: both corners down again (theta = 0) or re-decided on the corner
      t_ = t1_;
      x_ = x1;
      out_.summary.friction_energy_j_per_kg = work_base_ + x_.work;
      if (which == kNotTaken + kImpact) {
        x_.th = 0.0;
        x_.w = 0.0;
        apply(decide_both(P_, x_.v, f_.ah(t_), f_.ge(t_)));
      } else {
        const Decision d =
            decide_corner(P_, s_, which == kNotTaken + kSlipOrStop ? 0.0 : x_.v, x_.th, x_.w, f_.ah(t_), f_.ge(t_));
        if (which == kNotTaken + kSlipOrStop) x_.v = 0.0;
        apply(d);
      }
      row();
      return;
    }
    t_ = te;
    x_ = dense(te);
    out_.summary.friction_energy_j_per_kg = work_base_ + x_.work;
    switch (which) {
      case kImpact:
        x_.th = 0.0;
        impact();
        break;
      case kFall: {
        x_.th = s_ * kPi / 2.0;
        SlideRockSummary& sum = out_.summary;
        sum.overturned = true;
        sum.overturned_side = s_;
        sum.overturn_time_s = te;
        track(x_);
        enter(SlideRockMode::fallen);
        row();
        done_ = true;
        break;
      }
      case kFlight:
        to_flight();
        enter(SlideRockMode::flight);
        row();
        break;
      case kPainleve:  // slide-rock reached den = 0: the impact without collision, then a decision at zero slip
        apply({SlideRockMode::slide_rock, s_, sigma_, true, false});
        row();
        break;
      default:  // kSlipOrStop
        if (sigma_ == 0) {  // the stick limit: slip against the friction needed
          const Contact c = contact(P_, s_, 0, x_.th, x_.w, f_.ah(te), f_.ge(te));
          const int sigma = -sign(c.F);
          const Contact sl = contact(P_, s_, sigma, x_.th, x_.w, f_.ah(te), f_.ge(te));
          if (sl.painleve) apply(decide_corner(P_, s_, 0.0, x_.th, x_.w, f_.ah(te), f_.ge(te)));
          else apply({sl.N < 0.0 ? SlideRockMode::flight : SlideRockMode::slide_rock, s_, sigma});
        } else {  // the slip stopped: stick, or slip the other way
          x_.v = 0.0;
          apply(decide_corner(P_, s_, 0.0, x_.th, x_.w, f_.ah(te), f_.ge(te)));
        }
        row();
        break;
    }
  }

  /// The first |theta| = alpha of its side inside the step [t0_, te] (te: the step's end or its first event), by
  /// TOMS 748 on the dense output (the rocking engine's exceeded-alpha event): on [t0_, tp] when the step holds a
  /// peak tp of s theta above alpha, else on [t0_, te]. x0, x1: the states at t0_ and t1_.
  void locate_alpha(const Phys& x0, const Phys& x1, double tp, double te) {
    SlideRockSummary& sum = out_.summary;
    if (sum.exceeded_alpha_time_s) return;
    const double a = P_.alpha[side(s_)];
    const double ga = s_ * x0.th - a;
    if (!(ga < 0.0)) return;  // at or past alpha at the step's start: noted there (track)
    const auto g = [&](double t) { return s_ * dense(t).th - a; };
    double tb = te;
    double gb = te == t1_ ? s_ * x1.th - a : g(te);
    if (tp > t0_ && tp < te) {
      const double gp = g(tp);
      if (gp >= 0.0) {
        tb = tp;
        gb = gp;
      }
    }
    if (!(gb >= 0.0)) return;
    const double r = find_root(g, t0_, tb, ga, gb);
    if (std::isnan(r)) {
      throw RootFindingError(fmt::format("slide-rock: |theta| = alpha not located in {} iterations on [{}, {}] s ({})",
                                         kMaxRootIterations, t0_, tb, describe()));
    }
    sum.exceeded_alpha_time_s = r;
  }

  /// Contact state on pivot s_ -> flight state (CM position and velocity).
  void to_flight() {
    if (mode_ == SlideRockMode::flight) return;
    const double b = P_.b[side(s_)];
    const double rx = -s_ * b * std::cos(x_.th) + P_.h * std::sin(x_.th);
    const double ry = s_ * b * std::sin(x_.th) + P_.h * std::cos(x_.th);
    x_.X = x_.u + s_ * b + rx;
    x_.Xd = x_.v + ry * x_.w;
    x_.Y = ry;
    x_.Yd = -rx * x_.w;
  }

  /// The kinetic energy per unit mass in the ground's frame of a contact state on pivot s.
  [[nodiscard]] double kinetic(int s, double v, double th, double w) const {
    const double b = P_.b[side(s)];
    const double rx = -s * b * std::cos(th) + P_.h * std::sin(th);
    const double ry = s * b * std::sin(th) + P_.h * std::cos(th);
    const double vx = v + ry * w;
    const double vy = -rx * w;
    return 0.5 * (vx * vx + vy * vy + P_.k2 * w * w);
  }

  /// The impulse (per unit mass) at corner c that brings the corner to rest (both velocity components 0 after), and
  /// theta' after: the angular momentum about the corner is conserved (slide_rock.hpp's stick impact).
  struct Impulse {
    double w = 0.0, pt = 0.0, pn = 0.0;
  };
  [[nodiscard]] Impulse stick_impulse(int c, double th, double Xd, double Yd, double w) const {
    const auto r = corner_r(c, th);
    const double Dc = P_.k2 + r[0] * r[0] + r[1] * r[1];
    const double wp = (P_.k2 * w - r[1] * Xd + r[0] * Yd) / Dc;
    return {wp, -Xd - r[1] * wp, -Yd + r[0] * wp};
  }

  /// Painleve's paradox on the slipping pivot s_ (docs/method.md, "Painleve's paradox"): the impact without collision.
  /// The pivot is in contact (normal velocity 0) and slips at u'; the Darboux-Keller impulse process with the plastic
  /// normal law ends with the pivot at rest, which is the stick impulse: P_t = -u' (k2 + rho_x^2) / D,
  /// P_n = -rho_x rho_y u' / D, inside the cone exactly when den <= 0 (|P_t| / P_n = (k2 + rho_x^2) / |rho_x rho_y|
  /// <= mu_k). The kinetic energy lost, u'^2 (k2 + rho_x^2) / (2 D), is counted with the impacts.
  void tangential_impact() {
    SlideRockSummary& sum = out_.summary;
    const double b = P_.b[side(s_)];
    const double rx = -s_ * b * std::cos(x_.th) + P_.h * std::sin(x_.th);
    const double ry = s_ * b * std::sin(x_.th) + P_.h * std::cos(x_.th);
    const double ke0 = kinetic(s_, x_.v, x_.th, x_.w);
    const Impulse st = stick_impulse(s_, x_.th, x_.v + ry * x_.w, -rx * x_.w, x_.w);
    if (!(st.pn > 0.0)) {  // den <= 0 implies P_n > 0 (the proof above): anything else is a defect here
      throw SolverError(fmt::format("slide-rock: tangential impact with P_n = {} <= 0 at t = {} s ({})", st.pn, t_,
                                    describe()));
    }
    ++sum.tangential_impacts;
    sum.max_tangential_impulse_ratio = std::max(sum.max_tangential_impulse_ratio, std::abs(st.pt) / st.pn);
    x_.w = st.w;
    x_.v = 0.0;
    sum.impact_energy_j_per_kg += ke0 - kinetic(s_, 0.0, x_.th, x_.w);
    restart_ = true;
  }

  /// Corner c strikes with the CM velocity (Xd, Yd), theta' = w at rotation th: the impact law of slide_rock.hpp.
  /// Returns the state on pivot c after (u' = the corner's slip velocity) and counts the energy lost.
  void strike(int c, double th, double X, double Xd, double Yd, double w, bool pure_rocking) {
    SlideRockSummary& sum = out_.summary;
    const auto r = corner_r(c, th);
    const double rx = r[0];
    const double ry = r[1];
    const double ke0 = 0.5 * (Xd * Xd + Yd * Yd + P_.k2 * w * w);
    const Impulse st = stick_impulse(c, th, Xd, Yd, w);
    double wp = st.w;
    const double pt = st.pt;
    double pn = st.pn;
    double vp = 0.0;
    if (std::abs(pt) <= P_.mus * pn) {
      if (pure_rocking && P_.e_given) wp = *P_.e_given * w;
    } else {
      const double vt = Xd + ry * w;  // the corner's tangential velocity before
      const int sigma = vt != 0.0 ? sign(vt) : -sign(pt);
      const double den = P_.k2 + rx * rx + sigma * P_.muk * rx * ry;
      if (den > 0.0) {
        const double pn_s = P_.k2 * (rx * w - Yd) / den;
        const double pt_s = -sigma * P_.muk * pn_s;
        const double w_s = w + (ry * pt_s - rx * pn_s) / P_.k2;
        const double v_s = Xd + pt_s + ry * w_s;
        if (sigma * v_s >= 0.0) {  // the slip kept its direction over the impulse; else it stuck (stick above)
          wp = w_s;
          vp = v_s;
          pn = pn_s;
        }
      }
    }
    (void)pn;
    ++sum.impacts;
    s_ = c;
    x_.th = th;
    x_.w = wp;
    x_.v = vp;
    x_.u = X + rx - c * P_.b[side(c)];
    double ke1 = kinetic(c, vp, th, wp);
    // the rocking engine's rest rule (landing at theta = 0 with too little energy to rock)
    if (th == 0.0 && (c * wp <= 0.0 || wp * wp < P_.rest_w2[side(c)])) {
      x_.w = 0.0;
      ke1 = 0.5 * vp * vp;
      sum.impact_energy_j_per_kg += ke0 - ke1;
      apply(decide_both(P_, vp, f_.ah(t_), f_.ge(t_)));
      return;
    }
    sum.impact_energy_j_per_kg += ke0 - ke1;
    apply(decide_corner(P_, c, vp, th, wp, f_.ah(t_), f_.ge(t_)));
  }

  /// theta = 0 while on pivot s_: the other corner strikes.
  void impact() {
    const double b = P_.b[side(s_)];
    const double Xd = x_.v + P_.h * x_.w;  // rho_y = h, rho_x = -s b at theta = 0
    const double Yd = s_ * b * x_.w;
    const bool pure = sigma_ == 0 && x_.v == 0.0;
    strike(-s_, 0.0, x_.u, Xd, Yd, x_.w, pure);  // X = u at theta = 0
    row();
  }

  // ---- flight: exact parabola, theta linear ----
  [[nodiscard]] Phys fly(double tau) const {
    Phys x = x_;
    const double t2 = tau * tau;
    x.X = x_.X + x_.Xd * tau - f_.ah(t_) * t2 / 2.0 - f_.ahs * t2 * tau / 6.0;
    x.Xd = x_.Xd - f_.ah(t_) * tau - f_.ahs * t2 / 2.0;
    x.Y = x_.Y + x_.Yd * tau - f_.ge(t_) * t2 / 2.0 - f_.ges * t2 * tau / 6.0;
    x.Yd = x_.Yd - f_.ge(t_) * tau - f_.ges * t2 / 2.0;
    x.th = x_.th + x_.w * tau;
    return x;
  }
  [[nodiscard]] double corner_height(const Phys& x, int c) const { return x.Y + corner_r(c, x.th)[1]; }

  void flight_phase(double tb) {
    const double L = tb - t_;
    const auto lowest = [&](double tau) {
      const Phys x = fly(tau);
      return std::min(corner_height(x, 1), corner_height(x, -1));
    };
    const auto fall = [&](double tau) { return kPi / 2.0 - std::abs(fly(tau).th); };
    double a = 0.0;
    double fa = lowest(0.0);
    for (int k = 1; k <= kFlightPieces; ++k) {
      const double bb = L * k / kFlightPieces;
      const double fb = lowest(bb);
      if (fall(bb) <= 0.0) {
        const double r = find_root(fall, a, bb, fall(a), fall(bb));
        alpha_in_flight(std::isnan(r) ? bb : r);
        x_ = fly(std::isnan(r) ? bb : r);
        t_ += std::isnan(r) ? bb : r;
        SlideRockSummary& sum = out_.summary;
        sum.overturned = true;
        sum.overturned_side = sign(x_.th);
        sum.overturn_time_s = t_;
        enter(SlideRockMode::fallen);
        row();
        done_ = true;
        return;
      }
      if (fb <= 0.0 && fa > 0.0) {
        const double r = find_root(lowest, a, bb, fa, fb);
        if (std::isnan(r)) {
          throw RootFindingError(fmt::format("slide-rock: landing not located in {} iterations after t = {} s ({})",
                                             kMaxRootIterations, t_, describe()));
        }
        const Phys x = fly(r);
        alpha_in_flight(r);
        t_ += r;
        land(x);
        return;
      }
      if (o_.record_history && k < kFlightPieces) row_at(t_ + bb, fly(bb));
      a = bb;
      fa = fb;
    }
    alpha_in_flight(L);
    x_ = fly(L);
    t_ = tb;
    track(x_);
  }

  /// |theta| = alpha of its side within the first tau s of the flight from (t_, x_): theta is linear in flight, so
  /// the crossing is exact.
  void alpha_in_flight(double tau) {
    SlideRockSummary& sum = out_.summary;
    if (sum.exceeded_alpha_time_s || x_.w == 0.0) return;
    const int s = sign(x_.w);
    const double a = P_.alpha[side(s)];
    if (!(s * x_.th < a)) return;
    const double tc = (s * a - x_.th) / x_.w;
    if (tc <= tau) sum.exceeded_alpha_time_s = t_ + tc;
  }

  void land(const Phys& x) {
    const double hp = corner_height(x, 1);
    const double hm = corner_height(x, -1);
    if (std::abs(x.th) <= 1e-12 && std::abs(x.w) * P_.h <= 1e-9 * std::max(std::abs(x.Yd), 1e-12)) {
      // flat landing on both corners: plastic normal impulse P_n = -Y', Coulomb tangential impulse
      SlideRockSummary& sum = out_.summary;
      ++sum.impacts;
      const double pn = std::max(0.0, -x.Yd);
      double v = x.Xd;
      if (std::abs(v) <= P_.mus * pn) v = 0.0;
      else v -= sign(v) * P_.muk * pn;
      sum.impact_energy_j_per_kg += 0.5 * (x.Xd * x.Xd + x.Yd * x.Yd + P_.k2 * x.w * x.w) - 0.5 * v * v;
      x_ = Phys{};
      x_.u = x.X;
      x_.v = v;
      s_ = 1;
      apply(decide_both(P_, v, f_.ah(t_), f_.ge(t_)));
      row();
      return;
    }
    const int c = hp <= hm ? 1 : -1;
    x_ = x;
    strike(c, x.th, x.X, x.Xd, x.Yd, x.w, false);
    row();
  }

  void finish() {
    SlideRockSummary& sum = out_.summary;
    sum.end_time_s = t_;
    sum.end_mode = mode_;
    sum.residual_slide_m = mode_ == SlideRockMode::flight ? flight_u(x_) : x_.u;
    if (mode_ != SlideRockMode::rest && mode_ != SlideRockMode::fallen) {
      sum.moving_at_end = true;
      sum.warnings.push_back(fmt::format("the body was still moving ({}) {} s after the record ended "
                                         "(max_run_out_s); the summary covers the response up to then",
                                         slide_rock_mode_name(mode_), o_.max_run_out_s));
    }
    if (sum.tangential_impacts > 0 || sum.painleve_holds > 0) {
      sum.warnings.push_back(fmt::format("Painleve's paradox (slide-rock without a solution) met: {} tangential "
                                         "impacts, {} holds (docs/method.md)",
                                         sum.tangential_impacts, sum.painleve_holds));
    }
    if (o_.record_history && (out_.history.time_s.empty() || out_.history.time_s.back() < t_)) row();
  }

  const InputGrid& grid_;
  std::span<const double> accel_;
  std::span<const double> gravity_;
  const Params& P_;
  const SlideRockOptions& o_;
  SlideRockResult out_;
  Forcing f_;
  Angle angle_;
  Rhs rhs_;
  mutable Controlled stepper_;
  State y0_{}, y1_{}, dy0_{}, dy1_{};
  double t0_ = 0.0, t1_ = 0.0, dt_ = 0.0;
  double work_base_ = 0.0;  // friction work before the current restart, J/kg
  double t_ = 0.0;
  Phys x_;
  SlideRockMode mode_ = SlideRockMode::rest;
  int s_ = 1;
  int sigma_ = 0;
  bool restart_ = true;
  std::array<double, kEvents + 1> events_last_{};  // the event functions at the end of the last step (its start now)
  bool holding_ = false;  // the Painleve hold is on (rock, stick margin < 0, every slip with den <= 0)
  bool events_cached_ = false;
  bool started_ = false;
  bool moved_ = false;
  bool done_ = false;
};

/// The body must stand at rest on the slope (slide_rock.hpp): still ground loads it with f_t = g sin(beta) toward
/// -x and n = g cos(beta), so rest needs tan(beta) <= mu_s (Coulomb) and N+ = (b1 n - h f_t) / (b1 + b2) >= 0, i.e.
/// tan(beta) <= b1 / h (the CM over the down-slope corner O-).
void validate_slope(const SlideRockBody& b, double slope_rad) {
  if (!std::isfinite(slope_rad) || slope_rad < 0.0 || slope_rad >= kPi / 2.0) {
    throw parameter_error("slope", fmt::format("slope must be in [0, 90) deg, got {} deg", rad_to_deg(slope_rad)));
  }
  const double t = std::tan(slope_rad);
  if (t > b.mu_static) {
    throw parameter_error("slope", fmt::format("a slope of {:.6g} deg is steeper than the friction angle atan(mu_s = "
                                               "{:.6g}) = {:.6g} deg: the body cannot stand on it (it slides away)",
                                               rad_to_deg(slope_rad), b.mu_static,
                                               rad_to_deg(std::atan(b.mu_static))));
  }
  if (t * b.h_m > b.b1_m) {
    throw parameter_error("slope", fmt::format("a slope of {:.6g} deg is steeper than alpha- = atan(b1 / h) = {:.6g} "
                                               "deg: the centre of mass is outside the down-slope corner O- and the "
                                               "body topples",
                                               rad_to_deg(slope_rad), rad_to_deg(std::atan2(b.b1_m, b.h_m))));
  }
}

void validate(const SlideRockBody& b, const SlideRockOptions& o) {
  (void)SlideRockBody::make(b.b1_m, b.b2_m, b.h_m, b.inertia_m2, b.mu_static, b.mu_kinetic);
  if (!std::isfinite(o.g_m_s2) || !(o.g_m_s2 > 0.0)) {
    throw parameter_error("g", fmt::format("g must be positive and finite, got {}", o.g_m_s2));
  }
  if (o.restitution == RestitutionMode::given && (!std::isfinite(o.e) || o.e < 0.0 || o.e > 1.0)) {
    throw parameter_error("e", fmt::format("coefficient of restitution must be in [0, 1], got {}", o.e));
  }
  if (o.restitution == RestitutionMode::housner && !b.cannot_uplift()) {  // a body that cannot lift never strikes
    const RockingBody rb = b.rocking_body();
    for (const int onto : {1, -1}) {
      const double e = housner_restitution(rb, onto);
      if (e < 0.0) {
        throw parameter_error("e", fmt::format("Housner's e = {:.6g} on landing on O{} is negative for this squat "
                                               "body; {}", e, onto > 0 ? '+' : '-', kSquatBodyAdvice));
      }
    }
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
  if (!std::isfinite(o.max_run_out_s) || o.max_run_out_s < 0.0) {
    throw parameter_error("max_run_out_s", fmt::format("run-out time must be >= 0 and finite, got {}", o.max_run_out_s));
  }
  if (!std::isfinite(o.initial_theta_rad) || std::abs(o.initial_theta_rad) >= kPi / 2.0) {
    throw parameter_error("initial_theta_rad", fmt::format("must be finite and below pi/2 in magnitude, got {}",
                                                           o.initial_theta_rad));
  }
  if (!std::isfinite(o.initial_theta_dot_rad_s)) {
    throw parameter_error("initial_theta_dot_rad_s", "initial angular velocity must be finite");
  }
  if (!std::isfinite(o.initial_slide_velocity_m_s)) {
    throw parameter_error("initial_slide_velocity_m_s", "initial slide velocity must be finite");
  }
  if (o.max_steps < 1) throw parameter_error("max_steps", "the integrator needs at least 1 step, got 0");
  validate_slope(b, o.slope_rad);
}

Params make_params(const SlideRockBody& b, const SlideRockOptions& o) {
  Params P;
  P.b = {b.b1_m, b.b2_m};
  P.h = b.h_m;
  P.k2 = b.inertia_m2;
  P.mus = b.mu_static;
  P.muk = b.mu_kinetic;
  P.g = o.g_m_s2;
  P.g_t = o.slope_rad == 0.0 ? 0.0 : P.g * std::sin(o.slope_rad);
  P.g_n = o.slope_rad == 0.0 ? P.g : P.g * std::cos(o.slope_rad);
  if (o.restitution == RestitutionMode::given) P.e_given = o.e;
  double pmin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < 2; ++i) {
    P.D[i] = P.k2 + P.b[i] * P.b[i] + P.h * P.h;
    P.alpha[i] = std::atan2(P.b[i], P.h);
    const double R = std::hypot(P.b[i], P.h);
    const double sh = std::sin(0.5 * P.alpha[i]);
    // (D/2) theta'^2 < fraction g R (1 - cos alpha): the rocking engine's rule on the pivot landed on
    P.rest_w2[i] = 2.0 * o.rest_energy_fraction * P.g * R * 2.0 * sh * sh / P.D[i];
    pmin = std::min(pmin, std::sqrt(P.g * R / P.D[i]));
  }
  P.alpha_sc = std::min(P.alpha[0], P.alpha[1]);
  P.p_sc = pmin;
  P.Lu = P.h * P.alpha_sc;
  P.inv_D = {1.0 / P.D[0], 1.0 / P.D[1]};
  P.to_u = 1.0 / (P.p_sc * P.Lu);
  P.to_th = 1.0 / (P.p_sc * P.alpha_sc);
  P.to_work = 1.0 / (P.g * P.Lu);
  return P;
}

/// A body that cannot lift: sliding.hpp's exact solver, its d = -u. The friction work is mu_k g times the distance
/// slid without vertical input; with it (or with a history asked for), mu_k g_e |d'| integrated by Simpson's rule on
/// each piece between history rows (a cubic there: exact).
SlideRockResult via_sliding(const GroundMotion& horizontal, const SlideRockBody& body, const SlideRockOptions& o,
                            const GroundMotion* vertical) {
  const SlidingBlock block =
      SlidingBlock::make(body.mu_static, body.mu_kinetic, o.slope_rad, SlidingMode::two_way, o.g_m_s2);
  // 1 and 0 on level ground, where the formulas below are the level ones exactly
  const double cb = std::cos(o.slope_rad);
  const double sb = std::sin(o.slope_rad);
  SlideRockResult r;
  SlideRockSummary& sum = r.summary;
  sum.used_sliding_kernel = true;
  const auto copy = [&](const SlidingSummary& ss) {
    sum.residual_slide_m = -ss.residual_displacement_m;
    sum.max_abs_slide_m = ss.max_abs_displacement_m;
    sum.slip_episodes = ss.slip_episodes;
    sum.end_time_s = ss.end_time_s;
    sum.onset_mode = ss.first_slip_time_s ? SlideRockMode::slide : SlideRockMode::rest;
    sum.end_mode = ss.at_rest_at_end ? SlideRockMode::rest : SlideRockMode::slide;
    sum.moving_at_end = !ss.at_rest_at_end;
  };
  if (!vertical && !o.record_history && o.slope_rad == 0.0) {  // level: the normal load is g throughout
    const SlidingSummary ss = slide_summary(horizontal, block);
    copy(ss);
    sum.friction_energy_j_per_kg = body.mu_kinetic * o.g_m_s2 * ss.slip_path_m;
    // every episode starts from rest and (but a last one still sliding) ends at rest
    const auto episodes = static_cast<std::size_t>(ss.slip_episodes);
    sum.mode_entries[index(SlideRockMode::slide)] = episodes;
    sum.mode_entries[index(SlideRockMode::rest)] = 1 + episodes - (ss.at_rest_at_end || episodes == 0 ? 0 : 1);
    sum.mode_first_time_s[index(SlideRockMode::rest)] = horizontal.time_s(0);
    sum.mode_first_time_s[index(SlideRockMode::slide)] = ss.first_slip_time_s;
    return r;
  }
  const SlidingResult s = slide(horizontal, block, vertical);
  copy(s.summary);
  const InputGrid grid(horizontal, vertical);
  const std::vector<double> ge = effective_gravity(grid, 1, o.g_m_s2);
  const auto accel = grid.accel_m_s2(0);
  const auto& h = s.history;
  std::size_t gi = 0;
  SlipState prev = SlipState::stuck;
  const auto ge_at = [&](std::size_t i) { return ge.empty() ? o.g_m_s2 : ge[i]; };
  for (std::size_t k = 0; k < h.time_s.size(); ++k) {
    const SlideRockMode m = h.state[k] == SlipState::stuck ? SlideRockMode::rest : SlideRockMode::slide;
    if (k == 0 || h.state[k] != prev) {
      const std::size_t mi = index(m);
      {
        ++sum.mode_entries[mi];
        if (!sum.mode_first_time_s[mi]) sum.mode_first_time_s[mi] = h.time_s[k];
        r.transitions.push_back({h.time_s[k], m});
      }
    }
    prev = h.state[k];
    if (o.record_history) {
      r.history.time_s.push_back(h.time_s[k]);
      r.history.slide_m.push_back(-h.displacement_m[k]);
      r.history.slide_velocity_m_s.push_back(-h.velocity_m_s[k]);
      r.history.theta_rad.push_back(0.0);
      r.history.theta_dot_rad_s.push_back(0.0);
      r.history.cm_height_m.push_back(body.h_m);
      // the potential along the slope: g sin(beta) X with X = u = -d (slide_rock.hpp)
      const double along = o.slope_rad == 0.0 ? 0.0 : -o.g_m_s2 * sb * h.displacement_m[k];
      r.history.energy_j_per_kg.push_back(0.5 * h.velocity_m_s[k] * h.velocity_m_s[k] + along);
      r.history.mode.push_back(m);
    }
    if (k + 1 == h.time_s.size() || h.state[k] == SlipState::stuck) continue;
    const double t0 = h.time_s[k];
    const double t1 = h.time_s[k + 1];
    if (!(t1 > t0)) continue;
    // the grid interval holding [t0, t1] (history rows include every grid point)
    while (gi + 2 < grid.size() && grid.time_s(gi + 1) <= t0) ++gi;
    const bool after = t0 >= grid.time_s(grid.size() - 1);  // the run-out: still ground (a_h = 0, g_e = g)
    const double ta = grid.time_s(gi);
    const double tb = grid.time_s(gi + 1);
    const double span = tb > ta ? tb - ta : 1.0;
    const double ahs = tb > ta && !after ? (accel[gi + 1] - accel[gi]) / span : 0.0;
    const double ges = tb > ta && !after ? (ge_at(gi + 1) - ge_at(gi)) / span : 0.0;
    // the normal load n = g_e cos(beta) - a_h sin(beta) (g_e on level ground), linear over the piece
    const auto ge_t = [&](double t) {
      if (after) return on_base(0.0, o.g_m_s2, cb, sb).n;
      return on_base(accel[gi] + ahs * (t - ta), ge_at(gi) + ges * (t - ta), cb, sb).n;
    };
    const double geat = ge_t(0.5 * (t0 + t1));
    const double dir = static_cast<double>(static_cast<int>(h.state[k]));
    // d''' over the piece: d'' = P a_h + Q g_e (sliding.hpp), P = cos + dir mu_k sin, Q = sin - dir mu_k cos
    const double c1 = (cb + dir * body.mu_kinetic * sb) * ahs + (sb - dir * body.mu_kinetic * cb) * ges;
    const double L = t1 - t0;
    const double v0 = std::abs(h.velocity_m_s[k]);
    const double v1 = std::abs(h.velocity_m_s[k + 1]);
    const double vm = std::abs(0.5 * (h.velocity_m_s[k] + h.velocity_m_s[k + 1]) - c1 * L * L / 8.0);
    const double g0 = ge_t(t0);
    const double g1 = ge_t(t1);
    sum.friction_energy_j_per_kg += body.mu_kinetic * L / 6.0 * (g0 * v0 + 4.0 * geat * vm + g1 * v1);
  }
  if (s.summary.contact_lost_time_s) {
    sum.warnings.push_back(fmt::format("the vertical input makes g + a_v <= 0 at {} s: the body leaves the ground "
                                       "there, which the sliding kernel does not follow (sliding_kernel = false "
                                       "does)",
                                       *s.summary.contact_lost_time_s));
  }
  return r;
}

}  // namespace

constexpr std::array<EnumName<SlideRockMode>, 6> kSlideRockModeNames{{
    {SlideRockMode::rest, "rest"},
    {SlideRockMode::slide, "slide"},
    {SlideRockMode::rock, "rock"},
    {SlideRockMode::slide_rock, "slide-rock"},
    {SlideRockMode::flight, "flight"},
    {SlideRockMode::fallen, "fallen"},
}};

std::string_view slide_rock_mode_name(SlideRockMode mode) { return enum_name(kSlideRockModeNames, mode); }

SlideRockBody SlideRockBody::make(double b1_m, double b2_m, double h_m, double inertia_m2, double mu_static,
                                  std::optional<double> mu_kinetic) {
  (void)RockingBody::general_asymmetric(b1_m, b2_m, h_m, inertia_m2);  // names b1, b2, h, inertia
  if (!std::isfinite(mu_static) || mu_static < 0.0) {
    throw parameter_error("mu", fmt::format("friction coefficient must be finite and >= 0, got {}", mu_static));
  }
  const double muk = mu_kinetic.value_or(mu_static);
  if (!std::isfinite(muk) || muk < 0.0 || muk > mu_static) {
    throw parameter_error("mu_k", fmt::format("kinetic friction must be in [0, mu_s = {}], got {}", mu_static, muk));
  }
  if (!(inertia_m2 > 0.0)) {
    throw parameter_error("inertia", fmt::format("I_cm / m must be > 0 for a body that slides and rocks (a point mass "
                                                 "has no rotational inertia for the slip equations), got {}",
                                                 inertia_m2));
  }
  return SlideRockBody{b1_m, b2_m, h_m, inertia_m2, mu_static, muk};
}

SlideRockBody SlideRockBody::block(double width_m, double height_m, double mu_static,
                                   std::optional<double> mu_kinetic) {
  const RockingBody rb = RockingBody::block(width_m, height_m);  // names width, height
  return make(rb.a_m, rb.a_m, rb.h_m, (width_m * width_m + height_m * height_m) / 12.0, mu_static, mu_kinetic);
}

SlideRockBody SlideRockBody::from_rocking(const RockingBody& body, double mu_static,
                                          std::optional<double> mu_kinetic) {
  const double k2 = body.D_m2 - body.a_m * body.a_m - body.h_m * body.h_m;
  return make(body.pivot_b_m(-1), body.a_m, body.h_m, k2, mu_static, mu_kinetic);
}

RockingBody SlideRockBody::rocking_body() const { return RockingBody::general_asymmetric(b1_m, b2_m, h_m, inertia_m2); }

bool SlideRockBody::cannot_uplift() const noexcept { return mu_static < std::min(b1_m, b2_m) / h_m; }

double SlideRockBody::painleve_friction_limit() const noexcept {
  // About pivot s at tilt theta the CM is at |rho_x| = R |sin phi|, rho_y = R cos phi from it, R^2 = b_s^2 + h^2,
  // phi = alpha_s - theta (tan alpha_s = b_s / h). With t = tan |phi|, (k2 + rho_x^2) / (|rho_x| rho_y) =
  // q / t + (q + 1) t, q = k2 / R^2, least at t = sqrt(q / (q + 1)) < 1, where it is 2 sqrt(q (q + 1)). Over
  // 0 <= theta < pi/2, |phi| runs up to alpha_s or pi/2 - alpha_s, one of which has tan >= 1: that t is reached.
  double limit = std::numeric_limits<double>::infinity();
  for (const double b : {b1_m, b2_m}) {
    const double q = inertia_m2 / (b * b + h_m * h_m);
    limit = std::min(limit, 2.0 * std::sqrt(q * (q + 1.0)));
  }
  return limit;
}

SlideRockMode slide_rock_onset_mode(const SlideRockBody& body, double a_h_m_s2, double g_e_m_s2, double slope_rad) {
  SlideRockOptions o;
  o.slope_rad = slope_rad;
  validate(body, o);
  const Params P = make_params(body, o);
  if (slope_rad == 0.0) return decide_both(P, 0.0, a_h_m_s2, g_e_m_s2).mode;
  const BaseLoad l = on_base(a_h_m_s2, g_e_m_s2, std::cos(slope_rad), std::sin(slope_rad));
  return decide_both(P, 0.0, l.t, l.n).mode;
}

SlideRockResult slide_rock(const GroundMotion& horizontal, const SlideRockBody& body, const SlideRockOptions& o,
                           const GroundMotion* vertical) {
  validate(body, o);
  const bool at_rest = o.initial_theta_rad == 0.0 && o.initial_theta_dot_rad_s == 0.0 &&
                       o.initial_slide_velocity_m_s == 0.0;
  SlideRockResult r;
  const InputGrid grid(horizontal, vertical);
  std::vector<double> gravity = effective_gravity(grid, 1, o.g_m_s2);
  std::span<const double> accel = grid.accel_m_s2(0);
  std::vector<double> tangential;
  if (o.slope_rad != 0.0) {  // an inclined base: the engine runs on the loads f_t, n (slide_rock.hpp)
    const double cb = std::cos(o.slope_rad);
    const double sb = std::sin(o.slope_rad);
    tangential.resize(grid.size());
    gravity.resize(grid.size(), o.g_m_s2);  // no vertical input: g_e = g
    for (std::size_t i = 0; i < grid.size(); ++i) {
      const BaseLoad l = on_base(accel[i], gravity[i], cb, sb);
      tangential[i] = l.t;
      gravity[i] = l.n;
    }
    accel = tangential;
  }
  // the normal load <= 0 somewhere: the body leaves the ground, which the sliding kernel does not follow; neither
  // does sliding.hpp take a slope and friction angle that reach 90 deg (the engine does: up-slope slip never starts)
  const bool grounded = std::all_of(gravity.begin(), gravity.end(), [](double x) { return x > 0.0; });
  const bool kernel_slope = std::atan(body.mu_static) + o.slope_rad < kPi / 2.0;
  if (o.sliding_kernel && body.cannot_uplift() && at_rest && grounded && kernel_slope) {
    r = via_sliding(horizontal, body, o, vertical);
  } else {
    const Params P = make_params(body, o);
    Engine engine(grid, accel, gravity, P, o);
    r = engine.run();
  }
  SlideRockSummary& sum = r.summary;
  sum.alpha_positive_rad = std::atan2(body.b2_m, body.h_m);
  sum.alpha_negative_rad = std::atan2(body.b1_m, body.h_m);
  sum.max_rotation_over_alpha_positive = sum.max_rotation_positive_rad / sum.alpha_positive_rad;
  sum.max_rotation_over_alpha_negative = sum.max_rotation_negative_rad / sum.alpha_negative_rad;
  sum.max_rotation_over_alpha = std::max(sum.max_rotation_over_alpha_positive, sum.max_rotation_over_alpha_negative);
  return r;
}

SlideRockOptions slide_rock_options(const RockingOptions& rocking) {
  SlideRockOptions options;
  options.g_m_s2 = rocking.g_m_s2;
  options.restitution = rocking.restitution;
  options.e = rocking.e;
  options.rel_tol = rocking.rel_tol;
  options.max_run_out_s = rocking.max_run_out_s;
  options.max_steps = rocking.max_steps;
  return options;
}

}  // namespace topple
