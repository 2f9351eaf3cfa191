#include "topple/intensity.hpp"

#include <algorithm>
#include <cmath>

namespace topple {

GroundVelocityDisplacement integrate_ground(const GroundMotion& motion) {
  const auto a = motion.accel_m_s2();
  const std::size_t n = a.size();
  GroundVelocityDisplacement out;
  out.velocity_m_s.assign(n, 0.0);
  out.displacement_m.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    const double v0 = out.velocity_m_s[i - 1];
    out.velocity_m_s[i] = v0 + 0.5 * h * (a[i - 1] + a[i]);
    out.displacement_m[i] = out.displacement_m[i - 1] + v0 * h + h * h * (2.0 * a[i - 1] + a[i]) / 6.0;
  }
  return out;
}

BasicIntensity basic_intensity(const GroundMotion& motion, double g_m_s2) {
  BasicIntensity im;
  im.pga_m_s2 = motion.pga_m_s2();
  im.pga_time_s = motion.pga_time_s();
  const auto vd = integrate_ground(motion);
  for (double v : vd.velocity_m_s) im.pgv_m_s = std::max(im.pgv_m_s, std::abs(v));
  for (double d : vd.displacement_m) im.pgd_m = std::max(im.pgd_m, std::abs(d));
  const auto a = motion.accel_m_s2();
  double integral = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    integral += h * (a[i - 1] * a[i - 1] + a[i - 1] * a[i] + a[i] * a[i]) / 3.0;
  }
  im.arias_m_s = kPi / (2.0 * g_m_s2) * integral;
  return im;
}

}  // namespace topple
