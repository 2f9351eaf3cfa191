#pragma once
// Macroseismic intensity as evidence on PGA (issue 30; docs/method.md, "Macroseismic intensity").
//
// Conversion. Worden, Gerstenberger, Rhoades & Wald (2012, BSSA 102(1), 204-221; "WGRW12"), their bilinear
// relation between MMI and PGA (Y in cm/s^2, log10), without the distance and magnitude terms:
//     MMI = c1 + c2 log10 Y    for log10 Y <= t1,     MMI = c3 + c4 log10 Y    for log10 Y > t1,         (I1)
// c1 = 1.78, c2 = 1.55, c3 = -1.60, c4 = 3.70, t1 = 1.57, and its inverse as they give it (their relation is fitted
// so as to be invertible):
//     log10 Y = (MMI - c1) / c2  for MMI <= t2,         log10 Y = (MMI - c3) / c4  for MMI > t2,          (I2)
// t2 = 4.22 (the MMI at the knee). The coefficients as in ShakeMap 4's implementation (shakelib/gmice/wgrw12.py),
// checked against that implementation's published test values (tests/region/test_intensity.cpp). Below MMI 2 the
// lower segment is extrapolated (ShakeMap adds a steeper segment there; WGRW12 have few data below MMI 2).
// PGA in g is Y / (100 g_standard) (980.665 cm/s^2; ShakeMap divides by 981: 0.03 % apart).
//
// Uncertainty (I3). The MMI-to-PGA direction's scatter sigma_Y = 0.35 in log10 (ShakeMap's getMI2GMsd for WGRW12's
// PGA), and the intensity's own uncertainty sigma_I(n) for n reports, as ShakeMap's DYFI module sets it
// (shakemap_modules/coremods/dyfi.py, stddev_function: "from the ShakeMap paper, then add 0.2"):
//     sigma_I(n) = 0.25 exp(-n / 24.02) + 0.09 + 0.2   (intensity units),
// carried to log10 PGA through the inverse relation's slope 1/c (c = c2 or c4 by segment), the two independent:
//     sigma_ln = ln 10 * sqrt(sigma_Y^2 + (sigma_I(n) / c)^2).
// An intensity without a stated number of reports counts as one report (the widest). EMS-98 is taken as MMI: Musson,
// Grunthal & Stucchi (2010, J. Seismol. 14, 413-428) find the two scales equivalent in practice up to X; above X the
// equivalence and the conversion's data both end, and a note says the value is extrapolated.
#include <optional>
#include <string>
#include <string_view>

#include "topple/inversion/inversion.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// WGRW12's PGA coefficients (header, eqs. I1-I2) and the uncertainty terms (I3).
struct Wgrw12Pga {
  static constexpr double c1 = 1.78, c2 = 1.55, c3 = -1.60, c4 = 3.70;
  static constexpr double t1 = 1.57;   ///< log10(cm/s^2) at the knee
  static constexpr double t2 = 4.22;   ///< MMI at the knee
  static constexpr double sigma_log10_pga = 0.35;  ///< MMI -> PGA scatter, log10 units
  static constexpr double sigma_mmi = 0.66;        ///< PGA -> MMI scatter, intensity units (reported, not used)
};

/// "MMI", "EMS-98": the names the survey's intensity_scale key takes.
[[nodiscard]] std::string_view intensity_scale_name(IntensityScale scale);

/// Eq. I1: the MMI of a PGA (g), WGRW12 without distance and magnitude terms (not clipped).
[[nodiscard]] double wgrw12_mmi_from_pga_g(double pga_g);

/// Eq. I2: the median PGA (g) of an MMI.
[[nodiscard]] double wgrw12_pga_g_from_mmi(double mmi);

/// Eq. I3: an intensity's own uncertainty (intensity units) for n >= 1 reports (ShakeMap's DYFI rule).
[[nodiscard]] double intensity_sigma_for_reports(int reports);

/// An intensity as PGA evidence: a lognormal observation ln a_obs ~ N(ln a_s, sigma_ln^2) (fit.hpp).
struct IntensityPga {
  SiteIntensity intensity;
  double mmi = 0.0;         ///< the intensity on MMI (EMS-98 taken as MMI)
  double pga_g = 0.0;       ///< the conversion's median PGA, g (eq. I2)
  double sigma_ln = 0.0;    ///< eq. I3, natural-log units
  double sigma_intensity = 0.0;  ///< sigma_I(n), intensity units
  bool extrapolated = false;     ///< MMI above 10: beyond the conversion's data and the EMS-98 = MMI equivalence
  [[nodiscard]] double ci95_low_g() const;   ///< exp(ln pga_g - 1.96 sigma_ln)
  [[nodiscard]] double ci95_high_g() const;  ///< exp(ln pga_g + 1.96 sigma_ln)
};

/// The site's intensity through eqs. I2-I3.
[[nodiscard]] IntensityPga intensity_pga(const SiteIntensity& intensity);

/// A site with objects and an intensity: do they agree? Yes when the objects' own 95 % PGA interval (an
/// unconstrained end counts as open) overlaps the intensity's 95 % interval exp(ln a_I +- 1.96 sigma_ln) (the
/// calibration test of an instrument, objects_agree_with_instrument, with the measured value widened to the
/// conversion's interval).
[[nodiscard]] bool objects_agree_with_intensity(const Estimate& objects_pga_g, const IntensityPga& intensity) noexcept;

/// How the agreement is tested, for the JSON and the report.
inline constexpr std::string_view kIntensityAgreementTest =
    "the objects' own 95 % PGA interval overlaps the intensity's 95 % interval through WGRW12 (open ends count as "
    "open)";

/// The conversion's name, for the JSON and the report.
inline constexpr std::string_view kIntensityConversion =
    "Worden, Gerstenberger, Rhoades & Wald (2012) MMI-PGA, bilinear, no distance/magnitude terms; sigma log10 PGA "
    "0.35 and sigma_I(n) = 0.25 exp(-n/24.02) + 0.29 (ShakeMap); EMS-98 taken as MMI (Musson et al. 2010)";

}  // namespace topple
