#pragma once
// Analytic ground-acceleration pulses.
//
// Pulse motions are GroundMotion values (piecewise linear), so every solver takes them like a record:
// - rectangular, triangular and double-triangular pulses are exactly piecewise linear (a rectangle uses two samples
//   at each edge instant, i.e. a jump), so the exact sliding solver reproduces the closed forms to round-off;
// - sine, cosine and Ricker pulses are sampled at a step the caller chooses; the piecewise-linear model differs from
//   the smooth pulse by O((omega dt)^2).
// Every pulse is followed by `tail_s` seconds of still ground so that a sliding block can come to rest.
//
// The closed-form sliding responses of the thesis to these pulses: closed_forms/sliding_pulses.hpp.
#include <string_view>

#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

namespace topple {

enum class PulseKind {
  rectangular,        ///< a(t) = A for 0 <= t < t0 (thesis Fig. 2.4)
  triangular,         ///< 0 -> A at t0/2 -> 0 at t0 (thesis Fig. 3.3)
  double_triangular,  ///< triangle of +A over [0, t0], then of -A over [t0, 2 t0] (thesis Fig. 3.4)
  sine,               ///< one full cycle A sin(2 pi t / t0), 0 <= t <= t0 (Makris type A)
  cosine,             ///< one full cycle A cos(2 pi t / t0), 0 <= t <= t0 (Makris type B)
  ricker,             ///< Ricker wavelet A (1 - 2 pi^2 f^2 s^2) exp(-pi^2 f^2 s^2), f = 1/t0, s = t - 1.5 t0,
                      ///< over 0 <= t <= 3 t0 (the wavelet is below 1e-5 A outside)
  triangular_train,   ///< continuous triangular wave of period t0, `cycles` cycles (thesis Fig. 3.5): per cycle
                      ///< 0 -> A at t0/4 -> 0 at t0/2 -> -A at 3 t0/4 -> 0 at t0 (double-triangular pulses end to end)
  trapezoidal_train,  ///< continuous trapezoidal wave of period t0, `cycles` cycles (thesis Fig. 3.6): each half
                      ///< cycle rises over r t0/2, holds +-A for (1 - 2r) t0/2, falls over r t0/2,
                      ///< r = trapezoid_ramp_fraction (default 1/3: rise, plateau and fall of equal length)
};

/// "rect", "tri", "double-tri", "sine", "cosine", "ricker" (also the long names); throws InputError naming `field`.
/// The most samples a pulse is sampled with (the cap of synthesis.hpp: 5e7 samples, 400 MB per component); a finer
/// dt_s is refused (InputError naming "dt"), never a silent allocation of unbounded memory.
inline constexpr double kMaxPulseSamples = 5e7;
/// The most cycles of a pulse train (each cycle is at most 6 samples; 1e6 cycles is far beyond any physical train).
inline constexpr int kMaxPulseCycles = 1'000'000;

[[nodiscard]] PulseKind parse_pulse_kind(std::string_view name, const std::string& field = "--pulse");
[[nodiscard]] std::string_view pulse_kind_name(PulseKind kind);

struct PulseSpec {
  PulseKind kind = PulseKind::rectangular;
  double amplitude_m_s2 = 0.0;  ///< peak acceleration A*g, m/s^2 (signed: negative flips the pulse)
  double duration_s = 0.0;      ///< t0: rect/tri width; one period for sine/cosine; for ricker the wavelet's
                                ///< period 1/f_p at its peak frequency f_p (the record lasts 3 t0, centred)
  double tail_s = 0.0;          ///< still ground after the pulse (default 0: caller decides)
  double dt_s = 0.0;            ///< sampling of smooth pulses (sine, cosine, ricker); 0 -> duration / 2000
  int cycles = 1;               ///< trains: number of full cycles (>= 1)
  double trapezoid_ramp_fraction = 1.0 / 3.0;  ///< trapezoidal train: r in (0, 0.5] (0.5 = triangular train)
};

/// The pulse as a ground motion starting at t = 0. Throws InputError for non-positive duration, non-finite values,
/// a train with fewer than one cycle or a ramp fraction outside (0, 0.5].
[[nodiscard]] GroundMotion make_pulse(const PulseSpec& spec);

// ---- Near-fault pulse of Mavroeidis & Papageorgiou (2003), BSSA 93(3), 1099-1131 ----
//
// Velocity (their eq. 1), with the envelope centred at t0 = gamma / (2 f_p) so that the pulse starts at t = 0:
//   v(t) = A/2 [1 + cos(2 pi f_p (t - t0) / gamma)] cos(2 pi f_p (t - t0) + nu),   0 <= t <= gamma / f_p,
// and 0 outside. A is the velocity amplitude (m/s), f_p the prevailing frequency (Hz), nu the phase (rad), gamma > 1
// the oscillatory character (number of half cycles in the envelope; 1 < gamma <= 3 fits most near-fault records).
// The acceleration is its derivative, with u = 2 pi f_p (t - t0):
//   a(t) = -(A pi f_p / gamma) [sin(u / gamma) cos(u + nu) + gamma sin(u + nu) (1 + cos(u / gamma))],
// and the displacement its integral from the pulse start (written out in pulses.cpp). v and a vanish at both ends, so
// the sampled pulse has no jump; the displacement ends at a generally non-zero residual.
struct MavroeidisPapageorgiouPulse {
  double velocity_amplitude_m_s = 0.0;  ///< A, m/s (typical 0.3-2)
  double frequency_hz = 0.0;            ///< f_p, Hz (typical 0.2-2)
  double phase_rad = 0.0;               ///< nu, rad (0: symmetric velocity pulse, peak A at t0)
  double gamma = 2.0;                   ///< > 1

  /// Throws InputError naming the parameter: A finite, f_p > 0, nu finite, gamma > 1.
  void validate() const;
  [[nodiscard]] double duration_s() const { return gamma / frequency_hz; }
  [[nodiscard]] double centre_time_s() const { return 0.5 * gamma / frequency_hz; }
  [[nodiscard]] double velocity_m_s(double t_s) const;
  [[nodiscard]] double acceleration_m_s2(double t_s) const;
  [[nodiscard]] double displacement_m(double t_s) const;  ///< from 0 at t = 0; constant after the pulse
};

/// The MP pulse's acceleration sampled every dt_s (0: duration / 2000) from t = 0 to its end, then tail_s of still
/// ground. Throws InputError for invalid parameters.
[[nodiscard]] GroundMotion make_mavroeidis_papageorgiou_pulse(const MavroeidisPapageorgiouPulse& pulse,
                                                              double dt_s = 0.0, double tail_s = 0.0);

}  // namespace topple
