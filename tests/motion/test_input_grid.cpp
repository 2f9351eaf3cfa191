// The shared input grid (input_grid.hpp): several components on one time grid, jumps kept.
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "topple/motion/input_grid.hpp"

namespace topple {
namespace {

std::vector<double> to_vector(std::span<const double> s) { return {s.begin(), s.end()}; }
std::vector<double> times(const InputGrid& g) {
  std::vector<double> t;
  for (std::size_t i = 0; i < g.size(); ++i) t.push_back(g.time_s(i));
  return t;
}

TEST(InputGrid, AloneOrOnTheSameUniformGridReferencesTheSamples) {
  const auto h = GroundMotion::uniform({1.0, 2.0, 3.0}, 0.5, 1.0);
  const auto v = GroundMotion::uniform({4.0, 5.0, 6.0}, 0.5, 1.0);
  const InputGrid alone(h, nullptr);
  EXPECT_TRUE(alone.is_uniform());
  EXPECT_FALSE(alone.has(1));
  EXPECT_EQ(alone.accel_m_s2(0).data(), h.accel_m_s2().data());
  const InputGrid both(h, &v);
  EXPECT_TRUE(both.is_uniform());
  EXPECT_EQ(both.size(), 3u);
  EXPECT_EQ(both.start_time_s(), 1.0);
  EXPECT_EQ(both.dt_s(), 0.5);
  EXPECT_EQ(both.accel_m_s2(1).data(), v.accel_m_s2().data());
}

TEST(InputGrid, AJumpOfTheHorizontalSurvivesAVerticalOnAnotherGrid) {
  // Horizontal: 2 on [0, 0.3), jump to 0 at 0.3 (a rectangular pulse), linear to 0 at 1. Vertical every 0.25 s.
  const auto h = GroundMotion::irregular({0.0, 0.3, 0.3, 1.0}, {2.0, 2.0, 0.0, 0.0});
  const auto v = GroundMotion::uniform({0.0, 1.0, 2.0, 3.0, 4.0}, 0.25);
  const InputGrid g(h, &v);
  EXPECT_FALSE(g.is_uniform());
  // Exact values: every point is a sample time of one of the two records (no arithmetic on times).
  EXPECT_EQ(times(g), (std::vector<double>{0.0, 0.25, 0.3, 0.3, 0.5, 0.75, 1.0}));
  EXPECT_EQ(to_vector(g.accel_m_s2(0)), (std::vector<double>{2.0, 2.0, 2.0, 0.0, 0.0, 0.0, 0.0}));
  // The vertical at 0.3 is interpolated: 1 + (0.3 - 0.25) / 0.25 = 1.2; 0.3 - 0.25 is inexact in binary, so a few
  // ulp (1e-15 relative is about 4 ulp of 1.2).
  const auto av = to_vector(g.accel_m_s2(1));
  ASSERT_EQ(av.size(), 7u);
  EXPECT_NEAR(av[2], 1.2, 1e-15 * 1.2);
  EXPECT_EQ(av[2], av[3]);  // continuous component: the same value on both sides of the other's jump
  EXPECT_EQ(av[1], 1.0);
  EXPECT_EQ(av[6], 4.0);
}

TEST(InputGrid, SampleTimesThatDifferByRoundOffAreOneInstant) {
  // A flexible support's demand motion is on the ground's grid refined s times (flexible.hpp): i dt / s and j dt are
  // the same instants computed two ways. Before, they were kept apart (0.1 + 1e-17 s), and GroundMotion refused the
  // merged record (two samples closer than 1e-6 s): a three-component box on a flexible support failed to run.
  const double dt = 0.01;
  std::vector<double> fine(61), coarse(21);
  for (std::size_t i = 0; i < fine.size(); ++i) fine[i] = std::sin(0.1 * static_cast<double>(i));
  for (std::size_t j = 0; j < coarse.size(); ++j) coarse[j] = static_cast<double>(j);
  const auto h = GroundMotion::uniform(fine, dt / 3.0);
  const auto v = GroundMotion::uniform(coarse, dt);
  std::size_t apart = 0;  // the premise: some instants do differ by round-off
  for (std::size_t j = 0; j < coarse.size(); ++j) apart += h.time_s(3 * j) != v.time_s(j) ? 1u : 0u;
  ASSERT_GT(apart, 0u);
  const InputGrid g(h, &v);
  ASSERT_EQ(g.size(), fine.size());  // one point per instant: the fine grid's
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_NEAR(g.time_s(i), h.time_s(i), 1e-15);
    EXPECT_EQ(g.accel_m_s2(0)[i], fine[i]);
    EXPECT_NEAR(g.accel_m_s2(1)[i], static_cast<double>(i) / 3.0, 1e-12);  // the vertical's linear interpolant
  }
}

TEST(InputGrid, ComponentsStartingLateOrEndingEarlyJumpFromAndToStillGround) {
  const auto h = GroundMotion::uniform({1.0, 1.0, 1.0}, 1.0);        // 0..2 s
  const auto v = GroundMotion::uniform({5.0, 5.0}, 0.5, 0.5);        // 0.5..1 s
  const InputGrid g(h, &v);
  EXPECT_EQ(times(g), (std::vector<double>{0.0, 0.5, 0.5, 1.0, 1.0, 2.0}));
  EXPECT_EQ(to_vector(g.accel_m_s2(0)), (std::vector<double>{1.0, 1.0, 1.0, 1.0, 1.0, 1.0}));
  EXPECT_EQ(to_vector(g.accel_m_s2(1)), (std::vector<double>{0.0, 0.0, 5.0, 5.0, 0.0, 0.0}));
  // The grid spans every component: a vertical longer than the horizontal extends it with a_h = 0.
  const auto long_v = GroundMotion::uniform({0.0, 0.0, 0.0, 0.0}, 1.0);  // 0..3 s
  const InputGrid g2(h, &long_v);
  EXPECT_EQ(times(g2), (std::vector<double>{0.0, 1.0, 2.0, 2.0, 3.0}));
  EXPECT_EQ(to_vector(g2.accel_m_s2(0)), (std::vector<double>{1.0, 1.0, 1.0, 0.0, 0.0}));
}

TEST(InputGrid, ThreeComponentsAndAbsentOnes) {
  // Two horizontal components and a vertical, as bidirectional sliding will use; an absent component stays empty.
  const auto x = GroundMotion::uniform({0.0, 1.0, 2.0}, 1.0);
  const auto y = GroundMotion::irregular({0.0, 1.0, 1.0, 2.0}, {0.0, 0.0, 3.0, 3.0});
  const std::array<const GroundMotion*, 3> parts{&x, &y, nullptr};
  const InputGrid g(parts);
  EXPECT_EQ(g.components(), 3u);
  EXPECT_FALSE(g.has(2));
  EXPECT_TRUE(g.accel_m_s2(2).empty());
  EXPECT_EQ(times(g), (std::vector<double>{0.0, 1.0, 1.0, 2.0}));
  EXPECT_EQ(to_vector(g.accel_m_s2(0)), (std::vector<double>{0.0, 1.0, 1.0, 2.0}));
  EXPECT_EQ(to_vector(g.accel_m_s2(1)), (std::vector<double>{0.0, 0.0, 3.0, 3.0}));
}

TEST(InputGrid, EffectiveGravity) {
  const auto h = GroundMotion::uniform({1.0, 2.0}, 1.0);
  const auto v = GroundMotion::uniform({-1.0, 0.5}, 1.0);
  EXPECT_TRUE(effective_gravity(InputGrid(h, nullptr), 1, 9.0).empty());
  EXPECT_EQ(effective_gravity(InputGrid(h, &v), 1, 9.0), (std::vector<double>{8.0, 9.5}));
}

}  // namespace
}  // namespace topple
