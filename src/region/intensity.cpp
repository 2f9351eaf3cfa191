// Macroseismic intensity as evidence on PGA (intensity.hpp has the equations and their sources; docs/method.md,
// "Macroseismic intensity").
#include "topple/region/intensity.hpp"

#include <cmath>
#include <numbers>

#include "topple/core/units.hpp"

namespace topple {
namespace {

/// cm/s^2 per g (standard gravity): WGRW12's Y is in cm/s^2.
constexpr double kCmS2PerG = 100.0 * kStandardGravity;

}  // namespace

std::string_view intensity_scale_name(IntensityScale scale) {
  switch (scale) {
    case IntensityScale::mmi: return "MMI";
    case IntensityScale::ems98: return "EMS-98";
  }
  return "MMI";
}

double wgrw12_mmi_from_pga_g(double pga_g) {
  using C = Wgrw12Pga;
  const double ly = std::log10(pga_g * kCmS2PerG);
  return ly <= C::t1 ? C::c1 + C::c2 * ly : C::c3 + C::c4 * ly;  // eq. I1
}

double wgrw12_pga_g_from_mmi(double mmi) {
  using C = Wgrw12Pga;
  const double ly = mmi <= C::t2 ? (mmi - C::c1) / C::c2 : (mmi - C::c3) / C::c4;  // eq. I2
  return std::pow(10.0, ly) / kCmS2PerG;
}

double intensity_sigma_for_reports(int reports) {
  // Eq. I3, ShakeMap's DYFI rule: 0.53 intensity units for one report, falling to 0.29 for many.
  return 0.25 * std::exp(-static_cast<double>(reports) / 24.02) + 0.09 + 0.2;
}

double IntensityPga::ci95_low_g() const { return std::exp(std::log(pga_g) - 1.959963984540054 * sigma_ln); }
double IntensityPga::ci95_high_g() const { return std::exp(std::log(pga_g) + 1.959963984540054 * sigma_ln); }

IntensityPga intensity_pga(const SiteIntensity& intensity) {
  using C = Wgrw12Pga;
  IntensityPga out;
  out.intensity = intensity;
  out.mmi = intensity.value;  // EMS-98 taken as MMI (Musson, Grunthal & Stucchi 2010)
  out.pga_g = wgrw12_pga_g_from_mmi(out.mmi);
  out.sigma_intensity = intensity_sigma_for_reports(intensity.reports.value_or(1));
  // The inverse relation's slope d log10 Y / d MMI = 1 / c on the segment the intensity falls on (eq. I2).
  const double slope = 1.0 / (out.mmi <= C::t2 ? C::c2 : C::c4);
  const double s_log10 = std::hypot(C::sigma_log10_pga, out.sigma_intensity * slope);
  out.sigma_ln = std::numbers::ln10 * s_log10;
  out.extrapolated = out.mmi > 10.0;
  return out;
}

bool objects_agree_with_intensity(const Estimate& e, const IntensityPga& i) noexcept {
  return (!e.ci95_high || i.ci95_low_g() <= *e.ci95_high) && (!e.ci95_low || *e.ci95_low <= i.ci95_high_g());
}

}  // namespace topple
