#pragma once
// Closed-form sliding responses to the thesis' pulses (library oracles: benchmarks for the sliding solvers of
// solvers/sliding.hpp and solvers/sliding2d.hpp; the pulses themselves are made by motion/pulses.hpp).
//
// Closed forms (Mittal 1971, thesis section 2.3 and 3.2; Newmark 1965). Notation of the thesis: A = pulse
// amplitude in g, t0 = duration, N = friction coefficient (mu), g. Relative displacement and velocity are those of
// the block with respect to the ground, positive in the direction the pulse pushes the block (see sliding.hpp).
#include "topple/core/units.hpp"

namespace topple {

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
