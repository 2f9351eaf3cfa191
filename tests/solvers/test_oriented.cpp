// Oriented rocking objects (oriented.hpp): the planar projection model against single-component runs, the mirror
// of the opposite bearing, a box's governing axis, a cylinder's worst direction, and the refusals.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "support/input_errors.hpp"
#include "support/noise_record.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

constexpr double kG = kStandardGravity;

using test::expect_input_error;

/// Two different broadband components and a vertical on one uniform grid (20 s at 100 Hz).
GroundMotion component(std::uint64_t seed, double pga_g, double resonance_hz) {
  test::NoiseRecordSpec spec;
  spec.seed = seed;
  spec.samples = 2000;
  spec.dt_s = 0.01;
  spec.pga_m_s2 = pga_g * kG;
  spec.resonance_hz = resonance_hz;
  spec.envelope_peak_s = 4.0;
  return test::noise_record(spec);
}

/// Every number of a summary that the orientation could disturb, compared exactly (the projection on a component's
/// own azimuth is that component bit for bit, MotionSet::projected, so the runs must be identical).
void expect_same_summary(const RockingSummary& x, const RockingSummary& y) {
  EXPECT_EQ(x.max_abs_rotation_rad, y.max_abs_rotation_rad);
  EXPECT_EQ(x.max_rotation_over_alpha, y.max_rotation_over_alpha);
  EXPECT_EQ(x.max_rotation_time_s, y.max_rotation_time_s);
  EXPECT_EQ(x.max_rotation_positive_rad, y.max_rotation_positive_rad);
  EXPECT_EQ(x.max_rotation_negative_rad, y.max_rotation_negative_rad);
  EXPECT_EQ(x.max_abs_theta_dot_rad_s, y.max_abs_theta_dot_rad_s);
  EXPECT_EQ(x.impacts, y.impacts);
  EXPECT_EQ(x.uplifts, y.uplifts);
  EXPECT_EQ(x.uplift_time_s, y.uplift_time_s);
  EXPECT_EQ(x.overturned, y.overturned);
  EXPECT_EQ(x.overturn_time_s, y.overturn_time_s);
  EXPECT_EQ(x.energy_lost_j_per_kg, y.energy_lost_j_per_kg);
  EXPECT_EQ(x.end_time_s, y.end_time_s);
  EXPECT_EQ(x.steps, y.steps);
}

class Oriented : public ::testing::Test {
 protected:
  // Slender block: alpha = atan(0.1 / 0.4) = 0.245 rad, uplift at 0.25 g; both components exceed it.
  const RockingBody block = RockingBody::block(0.2, 0.8);
  const GroundMotion h1 = component(11, 0.35, 2.0);
  const GroundMotion h2 = component(12, 0.30, 3.0);
  const GroundMotion v = component(13, 0.15, 6.0);
};

TEST_F(Oriented, BearingAlongTheFirstComponentIsTheFirstComponentAlone) {
  for (const ComponentAzimuths az : {ComponentAzimuths{90.0, 0.0}, ComponentAzimuths{30.0, 120.0}}) {
    const MotionSet set = MotionSet::make(h1, &h2, az, &v);
    const auto o = rock_oriented_summary(set, OrientedBody::planar(block), az.first_deg);
    ASSERT_EQ(o.directions.size(), 1U);
    EXPECT_EQ(o.directions[0].axis, OrientedAxis::bearing);
    EXPECT_EQ(o.directions[0].azimuth_deg, az.first_deg);
    const RockingSummary alone = rock_summary(h1, block, {}, &v);
    ASSERT_GT(alone.uplifts, 0U) << "the fixture must rock for the comparison to mean anything";
    expect_same_summary(o.governing_response().summary, alone);
  }
}

TEST_F(Oriented, BearingAlongTheSecondComponentIsTheSecondComponentAlone) {
  // Both handednesses: second = first + 90 and first - 90; the bearing given as an equivalent angle (+360).
  for (const ComponentAzimuths az : {ComponentAzimuths{90.0, 0.0}, ComponentAzimuths{0.0, 90.0}}) {
    const MotionSet set = MotionSet::make(h1, &h2, az, &v);
    const auto o = rock_oriented_summary(set, OrientedBody::planar(block), az.second_deg + 360.0);
    EXPECT_EQ(o.governing_response().azimuth_deg, az.second_deg);
    const RockingSummary alone = rock_summary(h2, block, {}, &v);
    ASSERT_GT(alone.uplifts, 0U);
    expect_same_summary(o.governing_response().summary, alone);
  }
}

TEST_F(Oriented, TheOppositeBearingMirrorsTheSides) {
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0}, &v);
  const auto body = OrientedBody::planar(block);
  // 37 deg: a projection that mixes both components (neither cosine is 0 or 1).
  const RockingSummary x = rock_oriented_summary(set, body, 37.0).governing_response().summary;
  const RockingSummary y = rock_oriented_summary(set, body, 217.0).governing_response().summary;
  ASSERT_GT(x.max_rotation_positive_rad, 0.0);
  ASSERT_GT(x.max_rotation_negative_rad, 0.0);
  ASSERT_NE(x.max_rotation_positive_rad, x.max_rotation_negative_rad) << "a mirror must be visible";
  // The equation of motion is odd in (theta, a_h) for a symmetric body and the projection on phi + 180 is the exact
  // negative of that on phi (cos(x + 180) = -cos x to one rounding), so the sides swap. 1e-12 relative: the two
  // projections may differ in the last bit of each sample (the cosines are computed, not negated).
  const double tol = 1e-12;
  EXPECT_NEAR(y.max_rotation_positive_rad, x.max_rotation_negative_rad, tol * x.max_rotation_negative_rad);
  EXPECT_NEAR(y.max_rotation_negative_rad, x.max_rotation_positive_rad, tol * x.max_rotation_positive_rad);
  EXPECT_NEAR(y.max_abs_rotation_rad, x.max_abs_rotation_rad, tol * x.max_abs_rotation_rad);
  EXPECT_EQ(y.impacts, x.impacts);
  EXPECT_EQ(y.uplifts, x.uplifts);
  EXPECT_EQ(y.overturned, x.overturned);
  EXPECT_EQ(y.overturned_side, -x.overturned_side);
  EXPECT_EQ(y.exceeded_alpha_side, -x.exceeded_alpha_side);
}

TEST_F(Oriented, ABoxReportsItsWeakerAxis) {
  // Width 0.2 m along the bearing, depth 0.4 m across it, height 0.8 m: alpha 0.245 rad along, 0.464 rad across.
  const OrientedBody box = OrientedBody::box(0.2, 0.4, 0.8);
  ASSERT_TRUE(box.across.has_value());
  EXPECT_DOUBLE_EQ(box.across->a_m, 0.2);
  // The same shaking on both axes: the narrow side governs.
  {
    const MotionSet set = MotionSet::make(h1, &h1, ComponentAzimuths{90.0, 180.0});
    const auto o = rock_oriented_summary(set, box, 90.0);
    ASSERT_EQ(o.directions.size(), 2U);
    EXPECT_EQ(o.directions[1].azimuth_deg, 180.0);
    EXPECT_EQ(o.directions[1].axis, OrientedAxis::across);
    EXPECT_EQ(o.governing_response().axis, OrientedAxis::bearing);
    EXPECT_GT(o.directions[0].summary.max_rotation_over_alpha, o.directions[1].summary.max_rotation_over_alpha);
  }
  // No shaking along the bearing (a zero first component at the bearing) and 0.7 g across, above the wide axis'
  // uplift level (0.5 g): the wide axis, the only one rocking, governs.
  {
    const GroundMotion still = GroundMotion::uniform(std::vector<double>(h1.size(), 0.0), h1.dt_s());
    const GroundMotion strong = component(11, 0.7, 2.0);
    const MotionSet set = MotionSet::make(still, &strong, ComponentAzimuths{0.0, 90.0});
    const auto o = rock_oriented_summary(set, box, 0.0);
    EXPECT_EQ(o.directions[0].summary.uplifts, 0U);
    ASSERT_GT(o.directions[1].summary.uplifts, 0U);
    EXPECT_EQ(o.governing_response().axis, OrientedAxis::across);
    EXPECT_EQ(o.governing_response().azimuth_deg, 90.0);
    expect_same_summary(o.governing_response().summary, rock_summary(strong, RockingBody::block(0.4, 0.8)));
  }
}

TEST_F(Oriented, ACylinderTakesItsWorstDirection) {
  const RockingBody cylinder = RockingBody::cylinder(0.2, 0.8);
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0}, &v);
  const auto o = rock_oriented_summary(set, OrientedBody::planar(cylinder), 0.0);
  ASSERT_EQ(o.directions.size(), 12U);
  double largest = 0.0;
  double smallest = 1e9;
  double first_fall_s = 1e9;
  for (std::size_t k = 0; k < o.directions.size(); ++k) {
    const DirectionResponse& d = o.directions[k];
    EXPECT_EQ(d.azimuth_deg, 15.0 * static_cast<double>(k));
    EXPECT_EQ(d.axis, OrientedAxis::grid);
    // Each direction is an independent planar run of the projection.
    expect_same_summary(d.summary, rock_summary(set.projected(d.azimuth_deg), cylinder, {}, &v));
    EXPECT_FALSE(more_severe(d.summary, o.governing_response().summary)) << d.azimuth_deg << " deg";
    largest = std::max(largest, d.summary.max_rotation_over_alpha);
    smallest = std::min(smallest, d.summary.max_rotation_over_alpha);
    if (d.summary.overturned) first_fall_s = std::min(first_fall_s, *d.summary.overturn_time_s);
  }
  // The fixture is built so that some directions fall (75-120 deg) and others only rock: the worst is the one that
  // falls first, and its max |theta| / alpha (pi / 2 / alpha) the largest.
  ASSERT_TRUE(o.governing_response().summary.overturned);
  EXPECT_EQ(*o.governing_response().summary.overturn_time_s, first_fall_s);
  EXPECT_EQ(o.governing_response().summary.max_rotation_over_alpha, largest);
  EXPECT_LT(smallest, 0.9 * largest) << "the directions must differ for the worst one to mean anything";
  // No bearing: any bearing gives the same grid and the same answer.
  const auto other = rock_oriented_summary(set, OrientedBody::planar(cylinder), 123.0);
  EXPECT_EQ(other.governing, o.governing);
  // A finer grid contains the coarse one (every 5 deg): its worst is at least as severe.
  const auto fine = rock_oriented_summary(set, OrientedBody::planar(cylinder), 0.0, {}, {.cylinder_step_deg = 5.0});
  ASSERT_EQ(fine.directions.size(), 36U);
  EXPECT_FALSE(more_severe(o.governing_response().summary, fine.governing_response().summary));
  // Without falls (the pair at 0.9 times its amplitude) the worst is the largest max |theta| / alpha.
  const GroundMotion h1_weak = h1.scaled(0.9), h2_weak = h2.scaled(0.9);
  const MotionSet weaker = MotionSet::make(h1_weak, &h2_weak, ComponentAzimuths{90.0, 0.0}, &v);
  const auto w = rock_oriented_summary(weaker, OrientedBody::planar(cylinder), 0.0);
  double weaker_largest = 0.0;
  for (const DirectionResponse& d : w.directions) {
    ASSERT_FALSE(d.summary.overturned) << d.azimuth_deg;
    weaker_largest = std::max(weaker_largest, d.summary.max_rotation_over_alpha);
  }
  ASSERT_GT(weaker_largest, 0.0);
  EXPECT_EQ(w.governing_response().summary.max_rotation_over_alpha, weaker_largest);
}

TEST_F(Oriented, FullResponseOfTheGoverningDirection) {
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0}, &v);
  const OrientedBody box = OrientedBody::box(0.2, 0.3, 0.8);
  const auto r = rock_oriented(set, box, 60.0);
  const RockingSummary& s = r.orientation.governing_response().summary;
  // rock() and rock_summary() give the same summary (rocking.hpp); history ends at the run's end.
  EXPECT_EQ(r.governing.summary.max_abs_rotation_rad, s.max_abs_rotation_rad);
  EXPECT_EQ(r.governing.summary.impacts, s.impacts);
  ASSERT_FALSE(r.governing.history.time_s.empty());
  EXPECT_EQ(r.governing.history.time_s.back(), s.end_time_s);
}

TEST_F(Oriented, SweepPlanSeesEveryComponentOfASet) {
  // The engine's fingerprint hashes base motions (a set's first component); the second and the vertical enter the
  // plan's identity: a set that differs only there is another plan (its stored chunks are not reused).
  const auto plan_of = [&](const GroundMotion& second, const GroundMotion* vertical) {
    ensemble::SweepSpec spec;
    spec.record_sets.push_back(
        {"station", std::make_shared<const MotionSet>(MotionSet::make(h1, &second, ComponentAzimuths{90.0, 0.0},
                                                                      vertical))});
    spec.bearings_deg = {0.0, 45.0};
    spec.objects.emplace_back(ensemble::RockObject{block, {}, 0.2, 0.8, std::nullopt});
    return ensemble::make_plan(spec);
  };
  const ensemble::Plan base = plan_of(h2, &v);
  EXPECT_EQ(base.motions.size(), 2U);
  EXPECT_EQ(ensemble::plan_fingerprint(base), ensemble::plan_fingerprint(plan_of(h2, &v)));
  EXPECT_NE(ensemble::plan_fingerprint(base), ensemble::plan_fingerprint(plan_of(h2.scaled(1.01), &v)));
  EXPECT_NE(ensemble::plan_fingerprint(base), ensemble::plan_fingerprint(plan_of(h2, nullptr)));
  // The rows are the oriented runs: run 1 is the block at bearing 45 deg.
  ensemble::ExecuteOptions one_thread;
  one_thread.threads = 1;
  const ensemble::ResultTable t = ensemble::run_in_memory(base, one_thread);
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(t.columns.begin(), t.columns.end(), name) - t.columns.begin());
  };
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0}, &v);
  const auto single = rock_oriented_summary(set, OrientedBody::planar(block), 45.0);
  EXPECT_EQ(std::get<double>(t.rows[1][column("bearing_deg")]), 45.0);
  EXPECT_EQ(std::get<double>(t.rows[1][column("max_abs_rotation_rad")]),
            single.governing_response().summary.max_abs_rotation_rad);
}

TEST_F(Oriented, MoreSevereRanksFallsThenRotation) {
  RockingSummary a, b;
  a.max_rotation_over_alpha = 0.5;
  b.max_rotation_over_alpha = 0.7;
  EXPECT_TRUE(more_severe(b, a));
  EXPECT_FALSE(more_severe(a, a));
  a.overturned = true;
  a.overturn_time_s = 3.0;
  EXPECT_TRUE(more_severe(a, b));
  b.overturned = true;
  b.overturn_time_s = 2.0;
  EXPECT_TRUE(more_severe(b, a)) << "the earlier fall is the more severe";
}

TEST_F(Oriented, Refusals) {
  const auto body = OrientedBody::planar(block);
  const MotionSet one = MotionSet::make(h1, nullptr, ComponentAzimuths{90.0, 0.0});
  expect_input_error([&] { return rock_oriented_summary(one, body, 90.0); }, "second", "both horizontal components");
  const MotionSet unknown = MotionSet::make(h1, &h2, std::nullopt);
  expect_input_error([&] { return rock_oriented_summary(unknown, body, 90.0); }, "azimuth", "unknown");
  const MotionSet set = MotionSet::make(h1, &h2, ComponentAzimuths{90.0, 0.0});
  expect_input_error([&] { return rock_oriented_summary(set, body, std::nan("")); }, "bearing", "finite");
  expect_input_error([&] { return OrientedBody::make(RockingBody::cylinder(0.2, 0.8), 0.3); }, "depth", "cylinder");
  expect_input_error([&] { return OrientedBody::box(0.2, -0.3, 0.8); }, "depth", "-0.3");
  expect_input_error(
      [&] {
        return rock_oriented_summary(set, OrientedBody::planar(RockingBody::cylinder(0.2, 0.8)), 0.0, {},
                                     {.cylinder_step_deg = 7.0});
      },
      "cylinder_step", "divide 180");
  // Bearings: required but for a cylinder, refused for one; a direction step for cylinders only.
  const OrientedBody cyl = OrientedBody::planar(RockingBody::cylinder(0.2, 0.8));
  expect_input_error([&] { check_orientation(body, std::nullopt, false); return 0; }, "bearing", "required");
  expect_input_error([&] { check_orientation(cyl, 10.0, false); return 0; }, "bearing", "no bearing");
  expect_input_error([&] { check_orientation(body, 10.0, true); return 0; }, "cylinder_step", "cylinder only");
  check_orientation(cyl, std::nullopt, true);
  check_orientation(body, 10.0, false);
  // A block with a depth is a box whose axes are the two blocks.
  const OrientedBody made = OrientedBody::make(block, 0.5);
  ASSERT_TRUE(made.across.has_value());
  EXPECT_DOUBLE_EQ(made.across->a_m, 0.25);
  EXPECT_DOUBLE_EQ(made.across->h_m, block.h_m);
  EXPECT_EQ(oriented_axis_name(OrientedAxis::across), "across");
}

}  // namespace
}  // namespace topple
