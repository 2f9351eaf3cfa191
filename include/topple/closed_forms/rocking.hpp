#pragma once
// Closed forms of rocking (library oracles: benchmarks for the rocking engine of solvers/rocking.hpp, whose model,
// symbols and sign convention they share: p and alpha of the body, g given).
//
// Sources: Housner 1963, "The behavior of inverted pendulum structures during earthquakes", Bull. Seismol. Soc. Am.
// 53(2), 403-417 (the period, the impact law, the energy argument); the pulse and impulse thresholds are derived from
// Housner's equation of motion in docs/method.md ("Rocking").
#include "topple/bodies/rocking_body.hpp"

namespace topple {

/// Housner's linearised free-rocking period, s, from rest at theta0 (rad, 0 < theta0 < alpha), e = 1 (Housner 1963):
/// T = (4 / p) acosh(1 / (1 - theta0 / alpha)).
[[nodiscard]] double linearized_free_rocking_period_s(const RockingBody& body, double theta0_rad, double g_m_s2);

/// Exact nonlinear free-rocking period, s, from rest at theta0 (rad), e = 1:
/// T = 4 integral_0^theta0 dtheta / theta'(theta) with
/// theta'^2 = 2 p^2 (cos(alpha - theta0) - cos(alpha - theta)), by Gauss-Legendre quadrature after the substitution
/// that removes the inverse-square-root end point.
[[nodiscard]] double free_rocking_period_s(const RockingBody& body, double theta0_rad, double g_m_s2);

/// |theta'|, rad/s, on reaching theta = 0 from rest at theta0 (rad): sqrt(2 p^2 (cos(alpha - theta0) - cos(alpha)))
/// (conservation of energy).
[[nodiscard]] double free_rocking_impact_speed_rad_s(const RockingBody& body, double theta0_rad, double g_m_s2);

/// Amplitude, rad, after n impacts of free rocking from rest at theta0 (rad) with restitution e, exact recursion
/// cos(alpha - theta_{k+1}) = cos(alpha) + e^2 (cos(alpha - theta_k) - cos(alpha)).
[[nodiscard]] double free_rocking_amplitude_rad(const RockingBody& body, double theta0_rad, double e, int impacts);

/// Linearised overturning threshold of a rectangular acceleration pulse of duration t1 (derived from Housner's
/// linearised equation, docs/method.md): a / (g alpha) = 1 / (1 - exp(-p t1)); returns a in m/s^2.
[[nodiscard]] double rectangular_pulse_threshold_linearized_m_s2(const RockingBody& body, double duration_s,
                                                                 double g_m_s2);

/// Smallest sudden base-velocity change that overturns the body (Housner's impulse argument, 1963): the impulse
/// gives theta'_0 = dv p^2 cos(alpha) / g, which must reach sqrt(2 p^2 (1 - cos alpha)); returns dv in m/s.
[[nodiscard]] double velocity_impulse_threshold_m_s(const RockingBody& body, double g_m_s2);

}  // namespace topple
