#pragma once
// The ground-motion model of Boore, Stewart, Seyhan & Atkinson (2014), "NGA-West2 equations for predicting PGA, PGV,
// and 5 % damped PSA for shallow crustal earthquakes", Earthquake Spectra 30(3):1057-1085 (BSSA14), for PGA only:
// the median and the total standard deviation of ln PGA (g, RotD50), with the linear and nonlinear site terms, the
// basin term off (delta z1 = 0), the style of faulting unspecified (e0) and the global anelastic attenuation
// (Delta c3 = 0). Equations (paper numbering): ln Y = F_E(M) + F_P(R_JB, M) + F_S(Vs30, R_JB, M) (1); F_E (2);
// F_P with R = sqrt(R_JB^2 + h^2) (3, 4); F_S = ln F_lin + ln F_nl (5-8); sigma = sqrt(tau^2 + phi^2) (13-17).
// Coefficients: the paper's Table for PGA, as tabulated in OpenQuake's hazardlib (openquake/hazardlib/gsim/
// boore_2014.py, BooreEtAl2014); docs/method.md, "Priors", has the equations.

namespace topple {

/// BSSA14's answer for PGA at one (M, R_JB, Vs30).
struct Bssa14Pga {
  double median_g = 0.0;   ///< exp(mean ln PGA), g (RotD50)
  double ln_mean = 0.0;    ///< mean of ln(PGA / 1 g)
  double sigma_ln = 0.0;   ///< total standard deviation of ln PGA, sqrt(tau^2 + phi^2)
  double tau = 0.0;        ///< between-event standard deviation (eq. 14)
  double phi = 0.0;        ///< within-event standard deviation (eqs. 15-17)
  double pga_rock_g = 0.0; ///< the median PGA on the reference rock (Vs30 = 760 m/s) that drives F_nl (eq. 8), g
};

/// BSSA14 for PGA. magnitude: moment magnitude (the model's range 3 to 8.5, not enforced); rjb_km >= 0: Joyner-Boore
/// distance, km; vs30_m_s > 0, m/s. Throws std::invalid_argument for a negative distance or a non-positive Vs30.
[[nodiscard]] Bssa14Pga bssa14_pga(double magnitude, double rjb_km, double vs30_m_s);

}  // namespace topple
