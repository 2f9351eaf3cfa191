#include <cmath>

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

}  // namespace
}  // namespace topple
