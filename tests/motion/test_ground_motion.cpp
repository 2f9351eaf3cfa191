#include <cmath>
#include <initializer_list>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

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


// ---- Limits (GroundMotionLimits; issue 11): beyond them a record is refused, naming the limit ----

/// Expects an InputError whose message holds every one of `parts`.
template <class F>
void expect_limit(F f, std::initializer_list<const char*> parts) {
  try {
    (void)f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const char* p : parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
  }
}

TEST(GroundMotionLimits, AccelerationAtAndBeyondTheLimit) {
  // Two tiers: 1e6 m/s2 for any GroundMotion (idealised impulses, rocking.md R8), 100 g for a record.
  using L = GroundMotionLimits;
  EXPECT_DOUBLE_EQ(L::max_record_accel_m_s2, 100.0 * kStandardGravity);
  EXPECT_DOUBLE_EQ(L::max_abs_accel_m_s2, 1e6);
  EXPECT_DOUBLE_EQ(GroundMotion::uniform({0.0, -L::max_abs_accel_m_s2}, 0.01).pga_m_s2(), L::max_abs_accel_m_s2);
  expect_limit([] { return GroundMotion::uniform({0.0, 1e300}, 0.01); }, {"accel", "sample 1", "1e+06 m/s2"});
  expect_limit([] { return GroundMotion::irregular({0.0, 1.0}, {-1.1e6, 0.0}); }, {"accel", "1e+06 m/s2"});
  EXPECT_NO_THROW((void)GroundMotion::uniform({0.0, 1000.0}, 0.01));  // 102 g: a GroundMotion, not a record
  expect_limit([] { require_record_acceleration(1000.0, "--scale"); return 0; }, {"--scale", "100 g", "101.972 g"});
  expect_limit([] { require_record_acceleration(INFINITY, "--scale"); return 0; }, {"--scale", "beyond the range"});
  EXPECT_NO_THROW(require_record_acceleration(980.665, "--scale"));
}

TEST(GroundMotionLimits, ScalingIsCheckedBeforeItOverflows) {
  // --scale 1e308 used to give PGA inf and Arias NaN.
  const auto m = ramp();  // PGA 4 m/s2
  expect_limit([&] { return m.scaled(1e308); }, {"scale", "1e+308", "1e+06 m/s2"});
  expect_limit([&] { return m.scaled(-250001.0); }, {"scale", "1e+06 m/s2"});
  EXPECT_DOUBLE_EQ(m.scaled(-250000.0).pga_m_s2(), 1e6);  // 250000 x 4 = the limit, accepted
  expect_limit([&] { return m.scaled_to_pga(1.1e6); }, {"1e+06 m/s2"});
  EXPECT_DOUBLE_EQ(m.scaled(0.0).pga_m_s2(), 0.0);
}

TEST(GroundMotionLimits, TimeStepDurationStartAndSamples) {
  using L = GroundMotionLimits;
  expect_limit([] { return GroundMotion::uniform({0.0, 1.0}, 1e-7); }, {"dt_s", "outside the limits"});
  expect_limit([] { return GroundMotion::uniform({0.0, 1.0}, 10.5); }, {"dt_s", "outside the limits"});
  EXPECT_NO_THROW((void)GroundMotion::uniform({0.0, 1.0}, L::min_dt_s));
  EXPECT_NO_THROW((void)GroundMotion::uniform(std::vector<double>(2161, 1.0), L::max_dt_s));  // 6 h exactly
  expect_limit([] { return GroundMotion::uniform(std::vector<double>(2162, 1.0), L::max_dt_s); }, {"6 h"});
  expect_limit([] { return GroundMotion::irregular({0.0, 1e300}, {0.0, 1.0}); }, {"time", "6 h"});
  expect_limit([] { return GroundMotion::irregular({1.7e9, 1.7e9 + 1.0}, {0.0, 1.0}); }, {"time", "1 day"});
  expect_limit([] { return GroundMotion::uniform({0.0, 1.0}, 0.01, -1e6); }, {"1 day"});
  // Positive steps shorter than 1 us are refused; a zero step is a jump and stays allowed.
  expect_limit([] { return GroundMotion::irregular({0.0, 1e-9, 1.0}, {0.0, 1.0, 0.0}); }, {"closer than the limit"});
  EXPECT_NO_THROW((void)GroundMotion::irregular({0.0, 0.0, 1.0, 1.0}, {0.0, 1.0, 1.0, 0.0}));
  // Operations that change dt or length are checked too, before allocating.
  const auto six_hours = GroundMotion::uniform(std::vector<double>(2161, 1.0), L::max_dt_s);
  expect_limit([&] { return six_hours.resampled(1e-4); }, {"dt_s", "samples"});
  const auto six_hours_at_1s = GroundMotion::uniform(std::vector<double>(21601, 1.0), 1.0);
  expect_limit([&] { return six_hours_at_1s.time_scaled(1.5); }, {"6 h"});
  expect_limit([] { return ramp().time_scaled(1e-9); }, {"outside the limits"});
  EXPECT_DOUBLE_EQ(ramp().time_scaled(2.0).duration_s(), 4.0);
}
}  // namespace
}  // namespace topple
