#include "topple/motion/bssa14.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace topple {

namespace {

// BSSA14's PGA row (the paper's coefficient table; hazardlib's BooreEtAl2014 COEFFS, row "pga") and its
// IMT-independent constants. Units: distances km, velocities m/s, accelerations g.
constexpr double e0 = 0.4473;  // unspecified style of faulting (U = 1)
constexpr double e4 = 1.431, e5 = 0.05053, e6 = -0.1662, Mh = 5.5;
constexpr double c1 = -1.134, c2 = 0.1917, c3 = -0.008088, h = 4.5;
constexpr double c = -0.600, Vc = 1500.0, f4 = -0.150, f5 = -0.00701;
constexpr double R1 = 110.0, R2 = 270.0, DfR = 0.100, DfV = 0.070;
constexpr double phi1 = 0.695, phi2 = 0.495, tau1 = 0.398, tau2 = 0.348;
constexpr double Mref = 4.5, Rref = 1.0, Vref = 760.0, f1 = 0.0, f3 = 0.1, v1 = 225.0, v2 = 300.0;

/// Linear interpolation in M between the values at M <= 4.5 and M >= 5.5 (eqs. 14 and 17).
double in_magnitude(double at45, double at55, double m) {
  if (m <= 4.5) return at45;
  if (m >= 5.5) return at55;
  return at45 + (at55 - at45) * (m - 4.5);
}

}  // namespace

Bssa14Pga bssa14_pga(double magnitude, double rjb_km, double vs30_m_s) {
  if (!(rjb_km >= 0.0)) throw std::invalid_argument("bssa14_pga: the distance R_JB must be >= 0 km");
  if (!(vs30_m_s > 0.0)) throw std::invalid_argument("bssa14_pga: Vs30 must be > 0 m/s");
  const double m = magnitude;
  // Eq. 2, the event term with the style of faulting unspecified.
  const double fe = m <= Mh ? e0 + e4 * (m - Mh) + e5 * (m - Mh) * (m - Mh) : e0 + e6 * (m - Mh);
  // Eqs. 3-4, the path term (global: Delta c3 = 0).
  const double r = std::sqrt(rjb_km * rjb_km + h * h);
  const double fp = (c1 + c2 * (m - Mref)) * std::log(r / Rref) + c3 * (r - Rref);
  Bssa14Pga out;
  // The rock PGA that drives the nonlinear term is the PGA row's F_E + F_P (Vs30 = Vref, F_S = 0).
  out.pga_rock_g = std::exp(fe + fp);
  // Eq. 6, the linear site term; eqs. 7-8, the nonlinear one (f2 uses min(Vs30, 760)).
  const double flin = c * std::log(std::min(vs30_m_s, Vc) / Vref);
  const double f2 = f4 * (std::exp(f5 * (std::min(vs30_m_s, 760.0) - 360.0)) - std::exp(f5 * (760.0 - 360.0)));
  const double fnl = f1 + f2 * std::log((out.pga_rock_g + f3) / f3);
  out.ln_mean = fe + fp + flin + fnl;  // basin term off (delta z1 = 0)
  out.median_g = std::exp(out.ln_mean);
  // Eqs. 14-17: tau(M), phi(M, R_JB, Vs30).
  out.tau = in_magnitude(tau1, tau2, m);
  double phi = in_magnitude(phi1, phi2, m);
  if (rjb_km > R2) {
    phi += DfR;
  } else if (rjb_km > R1) {
    phi += DfR * std::log(rjb_km / R1) / std::log(R2 / R1);
  }
  if (vs30_m_s <= v1) {
    phi -= DfV;
  } else if (vs30_m_s < v2) {
    phi -= DfV * std::log(v2 / vs30_m_s) / std::log(v2 / v1);
  }
  out.phi = phi;
  out.sigma_ln = std::sqrt(out.tau * out.tau + phi * phi);
  return out;
}

}  // namespace topple
