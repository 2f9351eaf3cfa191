#pragma once
// Analytic ground-acceleration pulses, and the closed-form sliding responses the thesis derives for some of them.
//
// Pulse motions are GroundMotion values (piecewise linear), so every solver takes them like a record:
// - rectangular, triangular and double-triangular pulses are exactly piecewise linear (a rectangle uses two samples
//   at each edge instant, i.e. a jump), so the exact sliding solver reproduces the closed forms to round-off;
// - sine, cosine and Ricker pulses are sampled at a step the caller chooses; the piecewise-linear model differs from
//   the smooth pulse by O((omega dt)^2).
// Every pulse is followed by `tail_s` seconds of still ground so that a sliding block can come to rest.
//
// Closed forms (Mittal 1971, thesis section 2.3 and 3.2; Newmark 1965). Notation of the thesis: A = pulse
// amplitude in g, t0 = duration, N = friction coefficient (mu), g. Relative displacement and velocity are those of
// the block with respect to the ground, positive in the direction the pulse pushes the block (see sliding.hpp).
#include <string_view>

#include "topple/ground_motion.hpp"
#include "topple/units.hpp"

namespace topple {

enum class PulseKind {
  rectangular,        ///< a(t) = A for 0 <= t < t0 (thesis Fig. 2.4)
  triangular,         ///< 0 -> A at t0/2 -> 0 at t0 (thesis Fig. 3.3)
  double_triangular,  ///< triangle of +A over [0, t0], then of -A over [t0, 2 t0] (thesis Fig. 3.4)
  sine,               ///< one full cycle A sin(2 pi t / t0), 0 <= t <= t0 (Makris type A)
  cosine,             ///< one full cycle A cos(2 pi t / t0), 0 <= t <= t0 (Makris type B)
  ricker,             ///< Ricker wavelet A (1 - 2 pi^2 f^2 s^2) exp(-pi^2 f^2 s^2), f = 1/t0, s = t - 1.5 t0,
                      ///< over 0 <= t <= 3 t0 (the wavelet is below 1e-5 A outside)
};

/// "rect", "tri", "double-tri", "sine", "cosine", "ricker" (also the long names); throws InputError naming `field`.
[[nodiscard]] PulseKind parse_pulse_kind(std::string_view name, const std::string& field = "--pulse");
[[nodiscard]] std::string_view pulse_kind_name(PulseKind kind);

struct PulseSpec {
  PulseKind kind = PulseKind::rectangular;
  double amplitude_m_s2 = 0.0;  ///< peak acceleration A*g, m/s^2 (signed: negative flips the pulse)
  double duration_s = 0.0;      ///< t0: rect/tri width; one period for sine/cosine; for ricker the wavelet's
                                ///< period 1/f_p at its peak frequency f_p (the record lasts 3 t0, centred)
  double tail_s = 0.0;          ///< still ground after the pulse (default 0: caller decides)
  double dt_s = 0.0;            ///< sampling of smooth pulses (sine, cosine, ricker); 0 -> duration / 2000
};

/// The pulse as a ground motion starting at t = 0. Throws InputError for non-positive duration, non-finite values.
[[nodiscard]] GroundMotion make_pulse(const PulseSpec& spec);

// ---- Closed-form sliding responses (level ground, mu_static = mu_kinetic = N, two-way) ----

/// Response at the end of a pulse and its maximum.
struct PulseSlidingResponse {
  double end_displacement_m = 0.0;  ///< U0: relative displacement when the pulse ends (t = t0)
  double end_velocity_m_s = 0.0;    ///< V0: relative velocity when the pulse ends
  double max_displacement_m = 0.0;  ///< U_m: displacement when the block comes to rest again
  double stop_time_s = 0.0;         ///< t_m: when it comes to rest
};

/// Rectangular pulse of amplitude A g lasting t0 (Newmark 1965; thesis eqs 2.5, 2.6 and Table 3.1).
/// Requires A > N > 0 (otherwise the block does not slide and everything is zero).
[[nodiscard]] PulseSlidingResponse rectangular_pulse_sliding(double amplitude_g, double duration_s, double mu,
                                                             double g_m_s2 = kStandardGravity);

/// Single triangular pulse (thesis eqs 3.1-3.4, Table 3.2): slip starts at t = N t0 / (2A); when the block is still
/// sliding at t0, U_m = U0 + V0^2 / (2 N g); when it stops before t0 (V0 of eq 3.3 negative), the stop is found from
/// the same quadratic and U_m is the displacement then.
[[nodiscard]] PulseSlidingResponse triangular_pulse_sliding(double amplitude_g, double duration_s, double mu,
                                                            double g_m_s2 = kStandardGravity);

/// State (relative displacement, velocity) at time t under the double triangular pulse of thesis Fig. 3.4
/// (eqs 3.1-3.8, Table 3.3), including the stop and the reverse slip that follow, as a piecewise-polynomial closed
/// form. Valid for A > N (so that both directions slip; A > 2N/...): throws when the pulse does not match the
/// phase sequence the closed form assumes.
struct SlidingState {
  double displacement_m = 0.0;
  double velocity_m_s = 0.0;
};
[[nodiscard]] SlidingState double_triangular_pulse_sliding(double amplitude_g, double duration_s, double mu,
                                                           double time_s, double g_m_s2 = kStandardGravity);

}  // namespace topple
