#include <cmath>

#include <gtest/gtest.h>

#include "topple/error.hpp"
#include "topple/ground_motion.hpp"

namespace topple {
namespace {

GroundMotion ramp() { return GroundMotion::uniform({0.0, 1.0, 2.0, -4.0, 0.0}, 0.5); }

TEST(GroundMotion, UniformRecordBasics) {
  const auto m = ramp();
  EXPECT_TRUE(m.is_uniform());
  EXPECT_EQ(m.size(), 5u);
  EXPECT_DOUBLE_EQ(m.duration_s(), 2.0);
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 4.0);
  EXPECT_DOUBLE_EQ(m.pga_time_s(), 1.5);
  EXPECT_DOUBLE_EQ(m.accel_at(0.25), 0.5);
  EXPECT_DOUBLE_EQ(m.accel_at(1.25), -1.0);
  EXPECT_DOUBLE_EQ(m.accel_at(-1.0), 0.0);  // still ground before the record
  EXPECT_DOUBLE_EQ(m.accel_at(3.0), 0.0);
}

TEST(GroundMotion, InvalidConstructionThrows) {
  EXPECT_THROW((void)GroundMotion::uniform({}, 0.01), InputError);
  EXPECT_THROW((void)GroundMotion::uniform({1.0}, 0.0), InputError);
  EXPECT_THROW((void)GroundMotion::uniform({1.0}, -0.01), InputError);
  EXPECT_THROW((void)GroundMotion::uniform({1.0, NAN}, 0.01), InputError);
  EXPECT_THROW((void)GroundMotion::irregular({0.0, 1.0}, {1.0}), InputError);
  EXPECT_THROW((void)GroundMotion::irregular({0.0, 1.0, 0.5}, {1.0, 2.0, 3.0}), InputError);
  EXPECT_THROW((void)GroundMotion::irregular({0.0, 0.0}, {1.0, 2.0}), InputError);
}

TEST(GroundMotion, JumpsAreAllowedAndTakeTheValueAfter) {
  const auto m = GroundMotion::irregular({0.0, 0.0, 1.0, 1.0, 2.0}, {0.0, 3.0, 3.0, 0.0, 0.0});
  EXPECT_DOUBLE_EQ(m.accel_at(0.0), 3.0);
  EXPECT_DOUBLE_EQ(m.accel_at(0.5), 3.0);
  EXPECT_DOUBLE_EQ(m.accel_at(1.0), 0.0);
  EXPECT_DOUBLE_EQ(m.accel_at(1.5), 0.0);
}

TEST(GroundMotion, ScalingAndPolarity) {
  const auto m = ramp();
  EXPECT_DOUBLE_EQ(m.scaled_to_pga(2.0).pga_m_s2(), 2.0);
  EXPECT_DOUBLE_EQ(m.inverted().accel_m_s2()[3], 4.0);
  EXPECT_THROW((void)m.scaled_to_pga(0.0), InputError);
  EXPECT_THROW((void)GroundMotion::uniform({0.0, 0.0}, 0.1).scaled_to_pga(1.0), InputError);
}

TEST(GroundMotion, TimeScalingStretchesTheAxisOnly) {
  const auto m = ramp().time_scaled(2.0);
  EXPECT_DOUBLE_EQ(m.dt_s(), 1.0);
  EXPECT_DOUBLE_EQ(m.duration_s(), 4.0);
  EXPECT_DOUBLE_EQ(m.pga_m_s2(), 4.0);
  const auto irr = GroundMotion::irregular({1.0, 2.0, 4.0}, {0.0, 1.0, 0.0}).time_scaled(0.5);
  EXPECT_DOUBLE_EQ(irr.time_s(2), 2.5);
}

TEST(GroundMotion, TrimKeepsUniformGridWhenOnSamples) {
  const auto m = ramp().trimmed(0.5, 1.5);
  EXPECT_TRUE(m.is_uniform());
  EXPECT_EQ(m.size(), 3u);
  EXPECT_DOUBLE_EQ(m.start_time_s(), 0.5);
  const auto off = ramp().trimmed(0.25, 1.25);
  EXPECT_FALSE(off.is_uniform());
  EXPECT_DOUBLE_EQ(off.accel_m_s2().front(), 0.5);
  EXPECT_DOUBLE_EQ(off.accel_m_s2().back(), -1.0);
  EXPECT_THROW((void)ramp().trimmed(5.0, 6.0), InputError);
}

TEST(GroundMotion, ResamplingIsLinearInterpolation) {
  const auto m = ramp().resampled(0.25);
  ASSERT_EQ(m.size(), 9u);
  EXPECT_DOUBLE_EQ(m.accel_m_s2()[1], 0.5);
  EXPECT_DOUBLE_EQ(m.accel_m_s2()[7], -2.0);
  const auto irr = GroundMotion::irregular({0.0, 0.1, 0.3}, {0.0, 1.0, 0.0}).to_uniform();
  EXPECT_TRUE(irr.is_uniform());
  EXPECT_DOUBLE_EQ(irr.dt_s(), 0.1);
  EXPECT_NEAR(irr.accel_m_s2()[2], 0.5, 1e-15);
}

TEST(GroundMotion, BaselineCorrectionRemovesPolynomials) {
  // a(t) = 1 + 2t - 3t^2 + a zero-mean wiggle orthogonal to nothing in particular: after order-2 removal, the
  // polynomial part is gone to round-off (1e-12 is 1e4 ulps of the O(10) values).
  std::vector<double> a;
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.01 * i;
    a.push_back(1.0 + 2.0 * t - 3.0 * t * t);
  }
  const auto m = GroundMotion::uniform(a, 0.01).baseline_corrected(2);
  for (double v : m.accel_m_s2()) EXPECT_NEAR(v, 0.0, 1e-12);
  const auto mean = GroundMotion::uniform({1.0, 2.0, 3.0}, 0.1).baseline_corrected(0);
  EXPECT_NEAR(mean.accel_m_s2()[0], -1.0, 1e-15);
  EXPECT_THROW((void)mean.baseline_corrected(7), InputError);
}

}  // namespace
}  // namespace topple
