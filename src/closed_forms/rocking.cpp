// Closed forms of free rocking and of the overturning thresholds (Housner 1963): see closed_forms/rocking.hpp.
#include "topple/closed_forms/rocking.hpp"

#include <cmath>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <fmt/format.h>

#include "topple/core/error.hpp"

namespace topple {

namespace {
void require_amplitude(const RockingBody& body, double theta0) {
  if (!std::isfinite(theta0) || !(theta0 > 0.0) || !(theta0 < body.alpha_rad())) {
    throw parameter_error("theta0", fmt::format("free rocking needs 0 < theta0 < alpha = {}, got {}",
                                                body.alpha_rad(), theta0));
  }
}
}  // namespace

double linearized_free_rocking_period_s(const RockingBody& body, double theta0_rad, double g_m_s2) {
  require_amplitude(body, theta0_rad);
  require_positive(g_m_s2, "g", "g");
  return 4.0 / body.p_rad_s(g_m_s2) * std::acosh(1.0 / (1.0 - theta0_rad / body.alpha_rad()));
}

double free_rocking_period_s(const RockingBody& body, double theta0_rad, double g_m_s2) {
  require_amplitude(body, theta0_rad);
  require_positive(g_m_s2, "g", "g");
  const double alpha = body.alpha_rad();
  const double p = body.p_rad_s(g_m_s2);
  const double phi0 = alpha - theta0_rad;
  // theta = theta0 (1 - w^2), w in [0, 1]: dtheta = -2 theta0 w dw, and with delta = theta0 w^2
  // cos(phi0) - cos(phi0 + delta) = 2 sin(phi0 + delta/2) sin(delta/2) ~ w^2: the integrand is smooth in w.
  const auto integrand = [&](double w) {
    if (w == 0.0) return 2.0 * theta0_rad / std::sqrt(2.0 * p * p * std::sin(phi0) * theta0_rad);
    const double delta = theta0_rad * w * w;
    const double diff = 2.0 * std::sin(phi0 + 0.5 * delta) * std::sin(0.5 * delta);
    return 2.0 * theta0_rad * w / std::sqrt(2.0 * p * p * diff);
  };
  const double quarter = boost::math::quadrature::gauss_kronrod<double, 31>::integrate(integrand, 0.0, 1.0, 15, 1e-14);
  return 4.0 * quarter;
}

double free_rocking_impact_speed_rad_s(const RockingBody& body, double theta0_rad, double g_m_s2) {
  require_amplitude(body, theta0_rad);
  require_positive(g_m_s2, "g", "g");
  const double alpha = body.alpha_rad();
  const double p = body.p_rad_s(g_m_s2);
  // cos(alpha - theta0) - cos(alpha) = 2 sin(alpha - theta0/2) sin(theta0/2)
  return std::sqrt(2.0 * p * p * 2.0 * std::sin(alpha - 0.5 * theta0_rad) * std::sin(0.5 * theta0_rad));
}

double free_rocking_amplitude_rad(const RockingBody& body, double theta0_rad, double e, int impacts) {
  require_amplitude(body, theta0_rad);
  if (!std::isfinite(e) || e < 0.0 || e > 1.0) {
    throw parameter_error("e", fmt::format("coefficient of restitution must be in [0, 1], got {}", e));
  }
  if (impacts < 0) throw parameter_error("impacts", fmt::format("must be >= 0, got {}", impacts));
  const double alpha = body.alpha_rad();
  const double ca = std::cos(alpha);
  double theta = theta0_rad;
  for (int k = 0; k < impacts; ++k) {
    theta = alpha - std::acos(ca + e * e * (std::cos(alpha - theta) - ca));
  }
  return theta;
}

double rectangular_pulse_threshold_linearized_m_s2(const RockingBody& body, double duration_s, double g_m_s2) {
  require_positive(duration_s, "duration", "pulse duration");
  require_positive(g_m_s2, "g", "g");
  return g_m_s2 * body.alpha_rad() / (-std::expm1(-body.p_rad_s(g_m_s2) * duration_s));
}

double velocity_impulse_threshold_m_s(const RockingBody& body, double g_m_s2) {
  require_positive(g_m_s2, "g", "g");
  const double alpha = body.alpha_rad();
  const double sh = std::sin(0.5 * alpha);
  // sqrt(2 (1 - cos alpha)) = 2 sin(alpha / 2)
  return g_m_s2 / (body.p_rad_s(g_m_s2) * std::cos(alpha)) * 2.0 * sh;
}

}  // namespace topple
