// Closed-form sliding responses to the thesis' pulses: see closed_forms/sliding_pulses.hpp.
#include "topple/closed_forms/sliding_pulses.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "topple/core/error.hpp"

// ---- Closed forms (thesis section 3.2). Everything below is in the thesis' notation: A and N in g, t0 in s; the
// signs are those of topple (displacement positive in the direction the pulse pushes the block). ----
namespace topple {
namespace {

void check_closed_form_inputs(double amplitude_g, double duration_s, double mu, double g) {
  if (!std::isfinite(amplitude_g) || !(amplitude_g > 0.0)) {
    throw parameter_error("amplitude_g", fmt::format("closed forms need a positive amplitude, got {}", amplitude_g));
  }
  if (!std::isfinite(duration_s) || !(duration_s > 0.0)) {
    throw parameter_error("duration_s", fmt::format("closed forms need a positive duration, got {}", duration_s));
  }
  if (!std::isfinite(mu) || !(mu > 0.0)) {
    throw parameter_error("mu", fmt::format("closed forms need a positive friction coefficient, got {}", mu));
  }
  if (!std::isfinite(g) || !(g > 0.0)) throw parameter_error("g", "g must be positive and finite");
}

/// Smallest positive root of c2 u^2 + c1 u + c0 = 0 (c0 > 0 > at the far end), cancellation-free.
double positive_root(double c2, double c1, double c0) {
  if (c2 == 0.0) return -c0 / c1;
  const double disc = c1 * c1 - 4.0 * c2 * c0;
  if (disc < 0.0) return -1.0;
  const double q = -0.5 * (c1 + std::copysign(std::sqrt(disc), c1));
  double r = std::numeric_limits<double>::infinity();
  if (q / c2 > 0.0) r = q / c2;
  if (q != 0.0 && c0 / q > 0.0) r = std::min(r, c0 / q);
  return std::isfinite(r) ? r : -1.0;
}

}  // namespace

PulseSlidingResponse rectangular_pulse_sliding(double A, double t0, double N, double g) {
  check_closed_form_inputs(A, t0, N, g);
  PulseSlidingResponse r;
  if (A <= N) return r;
  r.end_velocity_m_s = (A - N) * g * t0;                 // eq 2.5 less the friction: (A - N) g t0
  r.end_displacement_m = 0.5 * (A - N) * g * t0 * t0;
  const double v = A * g * t0;                           // eq 2.5: velocity the pulse gives the ground
  r.max_displacement_m = 0.5 * v * v / (g * N) * (1.0 - N / A);  // eq 2.6
  r.stop_time_s = v / (N * g);                           // t_m = v / (N g)
  return r;
}

PulseSlidingResponse triangular_pulse_sliding(double A, double t0, double N, double g) {
  check_closed_form_inputs(A, t0, N, g);
  PulseSlidingResponse r;
  if (A <= N) return r;
  // Eqs 3.1, 3.2 at t0/2 (slip began at t = N t0 / (2A)).
  const double v1 = g * t0 / 4.0 * (A - N) * (1.0 - N / A);
  const double u1 = g * t0 * t0 / 8.0 * (A / 3.0 - N * (1.0 - N / A + N * N / (3.0 * A * A)));
  // Eqs 3.3, 3.4 at t0, valid while the block still slides there (V0 > 0).
  const double v0 = g * t0 * (A / 2.0 - N * (1.0 - N / (4.0 * A)));
  const double u0 = g * t0 * t0 * (A / 4.0 - N / 2.0 * (1.0 - N / (2.0 * A) + N * N / (12.0 * A * A)));
  if (v0 > 0.0) {
    r.end_velocity_m_s = v0;
    r.end_displacement_m = u0;
    r.max_displacement_m = u0 + v0 * v0 / (2.0 * N * g);  // still ground after t0: deceleration N g
    r.stop_time_s = t0 + v0 / (N * g);
    return r;
  }
  // The block stops inside the falling half: with u = t - t0/2, V = V1 + (A - N) g u - A g u^2 / t0.
  const double u = positive_root(-A * g / t0, (A - N) * g, v1);
  const double um = u1 + v1 * u + 0.5 * (A - N) * g * u * u - A * g * u * u * u / (3.0 * t0);
  r.end_velocity_m_s = 0.0;
  r.end_displacement_m = um;
  r.max_displacement_m = um;
  r.stop_time_s = 0.5 * t0 + u;
  return r;
}

SlidingState double_triangular_pulse_sliding(double A, double t0, double N, double t, double g) {
  check_closed_form_inputs(A, t0, N, g);
  if (!std::isfinite(t)) throw parameter_error("time_s", "time must be finite");
  const auto fail = [&](const char* what) {
    return parameter_error("double triangular pulse",
                           fmt::format("A = {}, N = {}: {}; the closed form of thesis Fig. 3.4 assumes the phase "
                                       "sequence slip forward, stop in the last quarter, slip back", A, N, what));
  };
  if (A <= N) throw fail("A <= N, the block does not slide");
  const double ts = N * t0 / (2.0 * A);
  if (t <= ts) return {};
  // Phase 1, [ts, t0/2]: a = 2 A g t / t0 (eq 3.1 and 3.2 integrated from the slip start).
  if (t <= 0.5 * t0) {
    const double v = A * g * (t * t - ts * ts) / t0 - N * g * (t - ts);
    const double u = A * g * (t * t * t - ts * ts * ts) / (3.0 * t0) - N * g * (t * t - ts * ts) / 2.0 +
                     (-(A * g * ts * ts / t0) + N * g * ts) * (t - ts);
    return {u, v};
  }
  const double v1 = g * t0 / 4.0 * (A - N) * (1.0 - N / A);
  const double u1 = g * t0 * t0 / 8.0 * (A / 3.0 - N * (1.0 - N / A + N * N / (3.0 * A * A)));
  // Phase 2, [t0/2, t0]: a = 2 A g (1 - t/t0).
  const double v0 = g * t0 * (A / 2.0 - N * (1.0 - N / (4.0 * A)));  // eq 3.3
  if (v0 <= 0.0) throw fail("the block stops before t0");
  if (t <= t0) {
    const double w = t - 0.5 * t0;
    return {u1 + v1 * w + 0.5 * (A - N) * g * w * w - A * g * w * w * w / (3.0 * t0),
            v1 + (A - N) * g * w - A * g * w * w / t0};
  }
  const double u0 = g * t0 * t0 * (A / 4.0 - N / 2.0 * (1.0 - N / (2.0 * A) + N * N / (12.0 * A * A)));  // eq 3.4
  // Phase 3, [t0, 1.5 t0]: a = -2 A g (t/t0 - 1), still sliding forward (friction -N g).
  const auto phase3 = [&](double w) {
    return SlidingState{u0 + v0 * w - A * g * w * w * w / (3.0 * t0) - 0.5 * N * g * w * w,
                        v0 - A * g * w * w / t0 - N * g * w};
  };
  const SlidingState s15 = phase3(0.5 * t0);  // eqs 3.5, 3.6
  if (s15.velocity_m_s <= 0.0) throw fail("the block stops before 1.5 t0");
  if (t <= 1.5 * t0) return phase3(t - t0);
  // Phase 4, [1.5 t0, 2 t0]: a = -A g (1 - 2w/t0); forward slip until V = 0 (eq 3.7), then back slip (+N g).
  const auto fwd = [&](double w) {
    return SlidingState{s15.displacement_m + s15.velocity_m_s * w - 0.5 * (A + N) * g * w * w + A * g * w * w * w / (3.0 * t0),
                        s15.velocity_m_s - (A + N) * g * w + A * g * w * w / t0};
  };
  const double w_stop = positive_root(A * g / t0, -(A + N) * g, s15.velocity_m_s);
  if (!(w_stop > 0.0) || w_stop > 0.5 * t0) throw fail("the block does not stop before 2 t0");
  const SlidingState at_stop = fwd(w_stop);
  if (A * (1.0 - 2.0 * w_stop / t0) <= N) throw fail("the ground acceleration at the stop does not exceed N g");
  if (t <= 1.5 * t0 + w_stop) return fwd(t - 1.5 * t0);
  // Back slip from rest at w_stop: V' = -A g (1 - 2w/t0) + N g.
  const auto back = [&](double w) {
    const double x = w - w_stop;
    const double acc0 = -A * g * (1.0 - 2.0 * w_stop / t0) + N * g;
    const double jerk = 2.0 * A * g / t0;
    return SlidingState{at_stop.displacement_m + 0.5 * acc0 * x * x + jerk * x * x * x / 6.0,
                        acc0 * x + 0.5 * jerk * x * x};
  };
  const SlidingState s20 = back(0.5 * t0);
  if (s20.velocity_m_s >= 0.0) throw fail("the back slip stops before 2 t0");
  if (t <= 2.0 * t0) return back(t - 1.5 * t0);
  // After the pulse: still ground, deceleration N g until rest.
  const double stop = -s20.velocity_m_s / (N * g);
  const double x = std::min(t - 2.0 * t0, stop);
  return {s20.displacement_m + s20.velocity_m_s * x + 0.5 * N * g * x * x, s20.velocity_m_s + N * g * x};
}

}  // namespace topple
