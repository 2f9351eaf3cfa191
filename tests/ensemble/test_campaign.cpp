// Shake-table campaigns (ensemble/campaign.hpp): the metrics against hand-computed numbers, and a campaign of blocks
// under rectangular pulses whose outcome is known in closed form (at rest below the static threshold g b / h;
// overturned far above the rectangular pulse's threshold, Housner 1963 linearised), one outcome deliberately
// observed wrong, so that the scores are known exactly.
#include <cmath>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "topple/closed_forms/rocking.hpp"
#include "topple/core/error.hpp"
#include "topple/ensemble/campaign.hpp"
#include "topple/motion/ground_motion.hpp"

namespace topple::ensemble {
namespace {

TEST(CampaignMetrics, HandComputedConfusion) {
  // 7 falls predicted and seen, 2 predicted not seen, 10 standing both ways, 1 fall missed: n = 20.
  const ClassificationMetrics m = classification_metrics(Confusion{7, 2, 10, 1});
  ASSERT_TRUE(m.accuracy && m.recall && m.precision && m.f1);
  EXPECT_DOUBLE_EQ(*m.accuracy, 17.0 / 20.0);
  EXPECT_DOUBLE_EQ(*m.recall, 7.0 / 8.0);
  EXPECT_DOUBLE_EQ(*m.precision, 7.0 / 9.0);
  // F1 = 2 P R / (P + R) = 2 (7/9)(7/8) / (7/9 + 7/8) = 14/17.
  EXPECT_NEAR(*m.f1, 14.0 / 17.0, 1e-15);
  EXPECT_NEAR(*m.f1, 2.0 * *m.precision * *m.recall / (*m.precision + *m.recall), 1e-15);
}

TEST(CampaignMetrics, UndefinedRatiosAreAbsentNotZero) {
  // No fall observed nor predicted: recall, precision and F1 have zero denominators.
  const ClassificationMetrics m = classification_metrics(Confusion{0, 0, 5, 0});
  ASSERT_TRUE(m.accuracy);
  EXPECT_DOUBLE_EQ(*m.accuracy, 1.0);
  EXPECT_FALSE(m.recall);
  EXPECT_FALSE(m.precision);
  EXPECT_FALSE(m.f1);
  EXPECT_FALSE(classification_metrics(Confusion{}).accuracy);
  // Falls observed, none predicted: recall 0 (defined), precision undefined, F1 = 0.
  const ClassificationMetrics missed = classification_metrics(Confusion{0, 0, 3, 2});
  EXPECT_DOUBLE_EQ(*missed.recall, 0.0);
  EXPECT_FALSE(missed.precision);
  EXPECT_DOUBLE_EQ(*missed.f1, 0.0);
}

TEST(CampaignMetrics, AzimuthDifferenceWrapsTheCircle) {
  EXPECT_DOUBLE_EQ(azimuth_difference_deg(350.0, 10.0), 20.0);
  EXPECT_DOUBLE_EQ(azimuth_difference_deg(10.0, 350.0), 20.0);
  EXPECT_DOUBLE_EQ(azimuth_difference_deg(0.0, 180.0), 180.0);
  EXPECT_DOUBLE_EQ(azimuth_difference_deg(90.0, 450.0), 0.0);
  EXPECT_DOUBLE_EQ(azimuth_difference_deg(-30.0, 30.0), 60.0);
}

CampaignRow row(const std::string& id, CampaignModel model, bool predicted, bool observed,
                std::optional<double> predicted_az = std::nullopt, std::optional<double> observed_az = std::nullopt) {
  CampaignRow r;
  r.id = id;
  r.model = model;
  r.predicted_overturned = predicted;
  r.observed_overturned = observed;
  r.overturn_azimuth_deg = predicted_az;
  r.observed_azimuth_deg = observed_az;
  r.cpu_s = 0.001;
  r.duration_s = 10.0;
  return r;
}

TEST(CampaignScore, CountsMedianAzimuthAndSpeedPerModel) {
  const auto P = CampaignModel::planar;
  const auto D = CampaignModel::three_d;
  const std::vector<CampaignRow> rows{
      row("a", P, true, true, 10.0, 20.0),    // TP, error 10
      row("b", P, true, true, 350.0, 20.0),   // TP, error 30 (across north)
      row("c", P, true, true, 100.0, 150.0),  // TP, error 50
      row("d", P, true, true, 100.0),         // TP, no observed azimuth: not compared
      row("e", P, true, false, 5.0),          // FP
      row("f", P, false, false),              // TN
      row("g", P, false, true, std::nullopt, 40.0),  // FN: no predicted azimuth
      row("a", D, false, true),               // another model's rows are not counted
  };
  const CampaignScore s = score_campaign(rows, P);
  EXPECT_EQ(s.confusion.tp, 4u);
  EXPECT_EQ(s.confusion.fp, 1u);
  EXPECT_EQ(s.confusion.tn, 1u);
  EXPECT_EQ(s.confusion.fn, 1u);
  EXPECT_DOUBLE_EQ(*s.metrics.accuracy, 5.0 / 7.0);
  EXPECT_DOUBLE_EQ(*s.metrics.recall, 4.0 / 5.0);
  EXPECT_DOUBLE_EQ(*s.metrics.precision, 4.0 / 5.0);
  EXPECT_EQ(s.azimuths_compared, 3u);
  ASSERT_TRUE(s.median_azimuth_error_deg);
  EXPECT_NEAR(*s.median_azimuth_error_deg, 30.0, 1e-12);
  EXPECT_NEAR(s.cpu_s, 0.007, 1e-15);
  EXPECT_DOUBLE_EQ(s.simulated_s, 70.0);
  EXPECT_NEAR(*s.times_real_time, 10000.0, 1e-9);
  // An even count: the mean of the two middle errors.
  const CampaignScore two = score_campaign({row("a", D, true, true, 0.0, 10.0), row("b", D, true, true, 0.0, 20.0)}, D);
  EXPECT_NEAR(*two.median_azimuth_error_deg, 15.0, 1e-12);
  // No row of the model: nothing defined.
  const CampaignScore none = score_campaign(rows, CampaignModel::coupled);
  EXPECT_EQ(none.confusion.total(), 0u);
  EXPECT_FALSE(none.metrics.accuracy);
  EXPECT_FALSE(none.times_real_time);
  EXPECT_FALSE(none.median_azimuth_error_deg);
}

TEST(CampaignScore, TargetThresholds) {
  CampaignScore s;
  s.metrics = classification_metrics(Confusion{9, 1, 9, 1});  // accuracy 0.9, recall 0.9
  s.times_real_time = 60000.0;
  const CampaignTargetCheck c = check_target(s);
  EXPECT_TRUE(c.accuracy && c.recall && c.speed && c.all());
  s.metrics = classification_metrics(Confusion{4, 0, 4, 1});  // recall 0.8: not above 0.8
  s.times_real_time = 59999.0;
  const CampaignTargetCheck d = check_target(s);
  EXPECT_TRUE(d.accuracy);  // 8/9 >= 0.87
  EXPECT_FALSE(d.recall);
  EXPECT_FALSE(d.speed);
  EXPECT_FALSE(d.all());
}

TEST(CampaignModels, NamesRoundTripAndUnknownRefused) {
  for (const CampaignModel m : {CampaignModel::planar, CampaignModel::coupled, CampaignModel::three_d}) {
    EXPECT_EQ(parse_campaign_model(campaign_model_name(m)), m);
  }
  EXPECT_THROW((void)parse_campaign_model("rocking"), InputError);
}

// The end-to-end campaign. Blocks 0.2 m wide (x), 0.3 m deep (y), 0.8 m tall: b / h = 0.25 along x, 0.375 along y.
constexpr double kWidth = 0.2, kDepth = 0.3, kHeight = 0.8, kDt = 0.005, kPulse = 2.0, kTail = 3.0;

/// A rectangular pulse of `amp` (m/s^2) lasting kPulse, then kTail of still ground.
GroundMotion pulse(double amp) {
  const auto n = static_cast<std::size_t>(std::lround((kPulse + kTail) / kDt)) + 1;
  std::vector<double> a(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) a[i] = static_cast<double>(i) * kDt < kPulse ? amp : 0.0;
  return GroundMotion::uniform(a, kDt);
}

struct Case {
  CampaignTest test;
  double amp = 0.0;
};

std::vector<Case> block_cases() {
  const double g = kStandardGravity;
  // Below the static threshold g b / h the block does not lift at all (moment balance about the edge).
  const double below = 0.4 * g * (0.5 * kWidth) / (0.5 * kHeight);
  // Three times the linearised threshold of a rectangular pulse of kPulse (closed_forms/rocking.hpp): it falls.
  const double above_x = 3.0 * rectangular_pulse_threshold_linearized_m_s2(RockingBody::block(kWidth, kHeight), kPulse, g);
  const double above_y = 3.0 * rectangular_pulse_threshold_linearized_m_s2(RockingBody::block(kDepth, kHeight), kPulse, g);
  const CampaignBlock block{kWidth, kDepth, kHeight};
  return {
      {{"still", block, 0.0, false, std::nullopt}, below},
      {{"falls", block, 0.0, true, 180.0}, above_x},      // toward -x: the ground accelerates toward +x
      {{"wrong", block, 0.0, true, std::nullopt}, below},  // observed overturned: deliberately wrong
      {{"turned", block, 90.0, true, 170.0}, above_y},     // its depth across the motion; observed 10 deg off
  };
}

std::vector<CampaignRow> run_cases(const std::vector<Case>& cases, const CampaignSettings& settings,
                                   std::size_t threads) {
  std::vector<CampaignTest> tests;
  for (const Case& c : cases) tests.push_back(c.test);
  return run_campaign(tests, settings, [&](std::size_t i) { return CampaignInput{pulse(cases[i].amp), {}, {}, {}}; },
                      threads);
}

TEST(CampaignRun, BlocksUnderPulsesScoreExactlyPlanarAnd3dSideBySide) {
  const std::vector<Case> cases = block_cases();
  CampaignSettings settings;  // planar and 3d
  const std::vector<CampaignRow> rows = run_cases(cases, settings, 0);
  ASSERT_EQ(rows.size(), 8u);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].id, cases[i / 2].test.id);
    EXPECT_EQ(rows[i].model, i % 2 == 0 ? CampaignModel::planar : CampaignModel::three_d);
    EXPECT_DOUBLE_EQ(rows[i].duration_s, kPulse + kTail);
    EXPECT_GE(rows[i].cpu_s, 0.0);
  }
  for (const std::size_t still : {0u, 1u, 4u, 5u}) {  // "still" and "wrong": no uplift below g b / h
    EXPECT_FALSE(rows[still].predicted_overturned) << rows[still].id;
    EXPECT_EQ(rows[still].max_tilt_over_limit, 0.0) << rows[still].id;
  }
  for (const std::size_t falls : {2u, 3u, 6u, 7u}) {
    EXPECT_TRUE(rows[falls].predicted_overturned) << rows[falls].id;
    ASSERT_TRUE(rows[falls].overturn_azimuth_deg);
    EXPECT_NEAR(*rows[falls].overturn_azimuth_deg, 180.0, 1e-6) << rows[falls].id;
  }
  // A block under one component in its plane of symmetry: the 3-D engine is the planar one (rigid3d.hpp).
  EXPECT_NEAR(*rows[3].overturn_time_s, *rows[2].overturn_time_s, 1e-6);
  EXPECT_NEAR(*rows[7].overturn_time_s, *rows[6].overturn_time_s, 1e-6);
  for (const CampaignModel model : settings.models) {
    const CampaignScore s = score_campaign(rows, model);
    EXPECT_EQ(s.confusion.tp, 2u);
    EXPECT_EQ(s.confusion.fp, 0u);
    EXPECT_EQ(s.confusion.tn, 1u);
    EXPECT_EQ(s.confusion.fn, 1u);
    EXPECT_DOUBLE_EQ(*s.metrics.accuracy, 3.0 / 4.0);
    EXPECT_DOUBLE_EQ(*s.metrics.recall, 2.0 / 3.0);
    EXPECT_DOUBLE_EQ(*s.metrics.precision, 1.0);
    EXPECT_DOUBLE_EQ(*s.metrics.f1, 4.0 / 5.0);
    EXPECT_EQ(s.azimuths_compared, 2u);
    EXPECT_NEAR(*s.median_azimuth_error_deg, 5.0, 1e-6);  // errors 0 and 10
    EXPECT_DOUBLE_EQ(s.simulated_s, 4.0 * (kPulse + kTail));
  }
}

TEST(CampaignRun, RowsDoNotDependOnThreadsAndCoupledWithHighFrictionAgreesOnVerdicts) {
  const std::vector<Case> cases = block_cases();
  CampaignSettings settings;
  settings.models = {CampaignModel::three_d, CampaignModel::coupled, CampaignModel::planar};
  settings.mu = 2.0;  // far above b / h: the block never slides, the coupled model rocks as the planar one
  const std::vector<CampaignRow> one = run_cases(cases, settings, 1);
  const std::vector<CampaignRow> three = run_cases(cases, settings, 3);
  ASSERT_EQ(one.size(), 12u);
  ASSERT_EQ(three.size(), one.size());
  for (std::size_t i = 0; i < one.size(); ++i) {
    EXPECT_EQ(one[i].id, three[i].id);
    EXPECT_EQ(one[i].model, three[i].model);
    EXPECT_EQ(one[i].predicted_overturned, three[i].predicted_overturned);
    EXPECT_EQ(one[i].max_tilt_over_limit, three[i].max_tilt_over_limit);  // the same arithmetic, bit for bit
    EXPECT_EQ(one[i].overturn_time_s, three[i].overturn_time_s);
    EXPECT_EQ(one[i].model, settings.models[i % 3]);
  }
  for (std::size_t t = 0; t < cases.size(); ++t) {
    const CampaignRow& coupled = one[3 * t + 1];
    const CampaignRow& planar = one[3 * t + 2];
    EXPECT_EQ(coupled.predicted_overturned, planar.predicted_overturned) << coupled.id;
    // (The times differ by a few hundredths of a second: at 3 times the threshold the coupled model lets the body
    // leave the ground, which the rocking model does not; the verdicts agree.)
  }
}

TEST(CampaignRun, CylinderUnderTwoComponentsAndErrorsOfTheFirstFailingTest) {
  const double g = kStandardGravity;
  // A solid cylinder 0.2 x 0.8 m: R / h = 0.25. Under 0.1 g along x and 0.1 g along y (|a| = 0.141 g < 0.25 g) it
  // stands; the planar grid and the rim engine agree.
  CampaignSettings settings;
  const std::vector<CampaignTest> tests{{"cyl", CampaignCylinder{0.2, 0.8}, 0.0, false, std::nullopt},
                                        {"bad", CampaignBlock{-1.0, 0.3, 0.8}, 0.0, false, std::nullopt},
                                        {"worse", CampaignBlock{0.2, 0.3, -1.0}, 0.0, false, std::nullopt}};
  const auto load = [&](std::size_t) {
    return CampaignInput{pulse(0.1 * g), pulse(0.1 * g), {}, {}};
  };
  try {
    (void)run_campaign(tests, settings, load, 2);
    FAIL() << "a block of negative width ran";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "width");  // test 2's error, not test 3's, whatever the threads
    EXPECT_NE(std::string(e.what()).find("test 'bad', model 'planar': "), std::string::npos) << e.what();
  }
  const std::vector<CampaignRow> rows = run_campaign({tests[0]}, settings, load, 0);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_FALSE(rows[0].predicted_overturned);
  EXPECT_FALSE(rows[1].predicted_overturned);
  EXPECT_EQ(rows[0].max_tilt_over_limit, 0.0);
  EXPECT_EQ(rows[1].max_tilt_over_limit, 0.0);
}

}  // namespace
}  // namespace topple::ensemble
