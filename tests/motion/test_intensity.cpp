#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "topple/motion/intensity.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/core/units.hpp"

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

TEST(Intensity, MeasuresOfARecordAreTheSingleFunctions) {
  // A 2 Hz sine of 0.3 g for 10 s at 0.01 s: intensity_measures() is each measure's own function, to the bit.
  std::vector<double> a(1001);
  for (std::size_t i = 0; i < a.size(); ++i) {
    a[i] = 0.3 * kStandardGravity * std::sin(2.0 * kPi * 2.0 * 0.01 * static_cast<double>(i));
  }
  const GroundMotion m = GroundMotion::uniform(a, 0.01);
  const IntensityMeasures im = intensity_measures(m, 9.81);
  EXPECT_EQ(im.basic.arias_m_s, basic_intensity(m, 9.81).arias_m_s);
  ASSERT_TRUE(im.d5_95);
  EXPECT_EQ(im.d5_95->duration_s, significant_duration(m).duration_s);
  EXPECT_EQ(im.cav_m_s, cumulative_absolute_velocity_m_s(m));
  ASSERT_TRUE(im.tp_s.value && im.tm_s.value && im.predominant_frequency_hz.value);
  EXPECT_EQ(*im.tp_s.value, predominant_period_s(m));
  EXPECT_EQ(*im.tm_s.value, mean_period_s(m));
  EXPECT_EQ(*im.predominant_frequency_hz.value, predominant_frequency_hz(m));
  // The sine's own period and frequency within the grids' spacing (1 % per step of 100 and 200 per decade).
  EXPECT_NEAR(*im.tp_s.value, 0.5, 0.5 * 0.025);
  EXPECT_NEAR(*im.predominant_frequency_hz.value, 2.0, 2.0 * 0.012);
  EXPECT_TRUE(im.tp_s.undefined_reason.empty());
}

TEST(Intensity, ZeroRecordLeavesTheUndefinedMeasuresEmptyWithTheirReason) {
  const GroundMotion zero = GroundMotion::uniform(std::vector<double>(100, 0.0), 0.01);
  const IntensityMeasures im = intensity_measures(zero);
  EXPECT_EQ(im.basic.pga_m_s2, 0.0);
  EXPECT_EQ(im.cav_m_s, 0.0);
  EXPECT_FALSE(im.d5_95);
  EXPECT_FALSE(im.tp_s.value);
  EXPECT_NE(im.tp_s.undefined_reason.find("identically zero"), std::string::npos) << im.tp_s.undefined_reason;
  EXPECT_FALSE(im.predominant_frequency_hz.value);
  EXPECT_FALSE(im.predominant_frequency_hz.undefined_reason.empty());
}

TEST(Spectra, TpAndFpGridsAreThoseOfTheDefinitions) {
  // Tp: 100 per decade from 0.02 s: floor(100 log10(250) + 0.5) + 1 = 241 periods, the last 0.02 * 10^2.4 = 5.02 s
  // (1e-12 and 1e-15: a few roundings of pow).
  const auto tp = tp_periods_s();
  ASSERT_EQ(tp.size(), 241u);
  EXPECT_DOUBLE_EQ(tp.front(), 0.02);
  EXPECT_NEAR(tp[100], 0.2, 1e-15);
  EXPECT_NEAR(tp.back(), 0.02 * std::pow(10.0, 2.4), 1e-12);
  // f_p centres at dt = 0.01 s: 0.1 Hz to min(25, 0.8 * 50) = 25 Hz, 200 per decade: floor(200 log10(250)) + 1.
  const auto fc = predominant_frequency_centres_hz(0.01);
  ASSERT_EQ(fc.size(), static_cast<std::size_t>(std::floor(200.0 * std::log10(250.0))) + 1);
  EXPECT_DOUBLE_EQ(fc.front(), 0.1);
  EXPECT_LE(fc.back(), 25.0);
  // At dt = 2 s the band 0.1 Hz .. 0.8 f_Nyquist = 0.2 Hz is still there; at dt = 5 s (0.08 Hz) it is empty.
  EXPECT_FALSE(predominant_frequency_centres_hz(2.0).empty());
  EXPECT_TRUE(predominant_frequency_centres_hz(5.0).empty());
  // FFT length: the next power of two at least twice the samples.
  EXPECT_EQ(predominant_frequency_fft_length(1000), 2048u);
  EXPECT_EQ(predominant_frequency_fft_length(1024), 2048u);
  EXPECT_EQ(predominant_frequency_fft_length(1025), 4096u);
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
  ASSERT_TRUE(im.d5_95);
  EXPECT_NEAR(im.d5_95->duration_s, 0.9 * t, 1e-9 * t);  // constant power: 5 % and 95 % of the time
  for (const OptionalMeasure* v : {&im.tp_s, &im.tm_s, &im.predominant_frequency_hz}) {
    if (v->value) {
      EXPECT_TRUE(std::isfinite(*v->value)) << *v->value;
    }
  }
}
}  // namespace
}  // namespace topple
