#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "topple/intensity.hpp"
#include "topple/units.hpp"

namespace topple {
namespace {

TEST(Intensity, SineClosedForms) {
  // a = A sin(w t) over whole cycles: v = A/w (1 - cos w t), PGV = 2A/w; Arias = pi/(2g) A^2 T/2.
  // 20,000 samples per cycle: the piecewise-linear model differs from the sine by O((w dt)^2) ~ 1e-7 relative.
  const double amp = 3.0;
  const double w = 2.0 * kPi;
  const int n = 20000;
  const double dt = 1.0 / n;
  std::vector<double> a(2 * n + 1);
  for (int i = 0; i <= 2 * n; ++i) a[i] = amp * std::sin(w * i * dt);
  const auto im = basic_intensity(GroundMotion::uniform(a, dt), 9.81);
  EXPECT_NEAR(im.pga_m_s2, amp, 1e-9);
  EXPECT_NEAR(im.pgv_m_s, 2.0 * amp / w, 1e-6 * amp / w);
  EXPECT_NEAR(im.arias_m_s, kPi / (2.0 * 9.81) * amp * amp * 2.0 / 2.0, 1e-6);
  // displacement grows linearly (no baseline correction): d(T) = A T / w at the end of 2 cycles
  EXPECT_NEAR(im.pgd_m, amp / w * 2.0, 1e-3);
}

TEST(Intensity, PiecewiseLinearIntegralsAreExact) {
  // Triangle 0 -> 2 -> 0 over 2 s: v_end = 2, Arias integral = 2 * (4/3) = 8/3.
  const auto im = basic_intensity(GroundMotion::uniform({0.0, 2.0, 0.0}, 1.0), 1.0);
  EXPECT_DOUBLE_EQ(im.pgv_m_s, 2.0);
  EXPECT_NEAR(im.arias_m_s, kPi / 2.0 * 8.0 / 3.0, 1e-14);
  // displacement: first step 2/6 = 1/3, second: v0*h + h^2 (2*2 + 0)/6 = 1 + 2/3 -> 2
  EXPECT_NEAR(im.pgd_m, 2.0, 1e-14);
}


TEST(Intensity, FiniteAtTheCornerOfTheLimits) {
  // The largest acceleration for the longest record (GroundMotionLimits: 1e6 m/s2 for 6 h), constant: every measure is
  // finite and the integrals take their closed forms PGV = a T, PGD = a T^2 / 2, Arias = pi / (2 g) a^2 T. The
  // trapezoid and the cubic per step are exact for a constant, so the tolerance is rounding over 21,600 steps.
  using L = GroundMotionLimits;
  const double a = L::max_abs_accel_m_s2;
  const double dt = 1.0;
  const auto n = static_cast<std::size_t>(L::max_duration_s / dt) + 1;
  const GroundMotion m = GroundMotion::uniform(std::vector<double>(n, a), dt);
  const double t = L::max_duration_s;
  const IntensityMeasures im = intensity_measures(m);
  EXPECT_NEAR(im.basic.pgv_m_s, a * t, 1e-12 * a * t);
  EXPECT_NEAR(im.basic.pgd_m, 0.5 * a * t * t, 1e-10 * a * t * t);
  EXPECT_NEAR(im.basic.arias_m_s, kPi / (2.0 * kStandardGravity) * a * a * t, 1e-10 * a * a * t);
  EXPECT_NEAR(im.cav_m_s, a * t, 1e-10 * a * t);
  EXPECT_NEAR(im.d5_95.duration_s, 0.9 * t, 1e-9 * t);  // constant power: 5 % and 95 % of the time
  for (double v : {im.tp_s, im.tm_s, im.predominant_frequency_hz}) EXPECT_TRUE(std::isfinite(v)) << v;
}
}  // namespace
}  // namespace topple
