// Fragility: the maximum-likelihood lognormal fit recovers known parameters from binomial data drawn from them, its
// band contains the truth, degenerate data are handled, and the ensemble analysis counts what single runs give.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/fragility/fragility.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/motion/synthesis.hpp"

namespace topple {
namespace {

const boost::math::normal kN{};

struct Truth {
  double theta = 0.5;
  double beta = 0.4;
  [[nodiscard]] double p(double x) const { return boost::math::cdf(kN, std::log(x / theta) / beta); }
};

/// Binomial draws by counting uniforms (portable generator: the same data everywhere).
FragilityData draw(const Truth& t, const std::vector<double>& levels, int n, std::uint64_t seed) {
  PortableRandom rng(seed);
  FragilityData d;
  for (double x : levels) {
    int z = 0;
    for (int i = 0; i < n; ++i) z += rng.uniform() < t.p(x) ? 1 : 0;
    d.im.push_back(x);
    d.trials.push_back(n);
    d.failures.push_back(z);
  }
  return d;
}

/// Expected (Fisher) information of (mu, beta) at the truth: sum_j n_j phi(u_j)^2 / (p_j (1 - p_j)) g_j g_j^T,
/// g_j = (-1/beta, -u_j/beta). Its inverse is the asymptotic covariance of the MLE.
std::array<double, 3> expected_covariance(const Truth& t, const std::vector<double>& levels, int n) {
  double i00 = 0.0, i01 = 0.0, i11 = 0.0;
  for (double x : levels) {
    const double u = std::log(x / t.theta) / t.beta;
    const double p = boost::math::cdf(kN, u);
    const double w = n * std::pow(boost::math::pdf(kN, u), 2) / (p * (1.0 - p));
    i00 += w / (t.beta * t.beta);
    i01 += w * u / (t.beta * t.beta);
    i11 += w * u * u / (t.beta * t.beta);
  }
  const double det = i00 * i11 - i01 * i01;
  return {i11 / det, -i01 / det, i00 / det};
}

TEST(FragilityFit, RecoversKnownParametersWithinTheSamplingError) {
  const Truth t;
  const std::vector<double> levels = log_grid(0.1, 2.0, 12);
  constexpr int n = 100;
  const auto cov = expected_covariance(t, levels, n);
  const double sd_mu = std::sqrt(cov[0]);
  const double sd_beta = std::sqrt(cov[2]);
  int inside = 0;
  constexpr int kTrials = 20;
  for (std::uint64_t seed = 1; seed <= kTrials; ++seed) {
    const FragilityData d = draw(t, levels, n, seed);
    const LognormalFragilityFit fit = fit_lognormal_fragility(d);
    ASSERT_FALSE(fit.beta_at_bound);
    // 4 standard deviations of the asymptotic sampling distribution (n = 100 per level, 12 levels): a failure here
    // has probability ~6e-5 per parameter and seed.
    EXPECT_NEAR(std::log(fit.theta), std::log(t.theta), 4.0 * sd_mu) << seed;
    EXPECT_NEAR(fit.beta, t.beta, 4.0 * sd_beta) << seed;
    // The observed-information standard errors agree with the expected information to 25 % at this sample size.
    EXPECT_NEAR(fit.se_ln_theta, sd_mu, 0.25 * sd_mu) << seed;
    EXPECT_NEAR(fit.se_beta, sd_beta, 0.25 * sd_beta) << seed;
    // The optimum: no small step improves the likelihood.
    for (const auto& [dt, db] : {std::pair{1e-4, 0.0}, {-1e-4, 0.0}, {0.0, 1e-4}, {0.0, -1e-4}}) {
      EXPECT_GE(fit.log_likelihood + 1e-9, fragility_log_likelihood(d, fit.theta * std::exp(dt), fit.beta + db));
    }
    // Band at 95 %: count how often it holds the true curve at the median.
    const auto [lo, hi] = fit.band(t.theta, 0.95);
    inside += (lo <= 0.5 && 0.5 <= hi) ? 1 : 0;
  }
  // Coverage of a 95 % band over 20 seeds: at least 16 (binomial(20, 0.95) is below 16 with probability 0.3 %).
  EXPECT_GE(inside, 16);
}

TEST(FragilityFit, BandContainsTheTruthAndNarrowsWithTheSampleSize) {
  // One draw per sample size, five IM values: the truth must lie in the 99.95 % band (z = 3.48; a pointwise miss
  // has probability 5e-4), and the 95 % band must lie around the fitted curve and shrink as 1/sqrt(n).
  const Truth t;
  const std::vector<double> levels = log_grid(0.1, 2.0, 10);
  const LognormalFragilityFit small = fit_lognormal_fragility(draw(t, levels, 40, 7));
  const LognormalFragilityFit large = fit_lognormal_fragility(draw(t, levels, 4000, 7));
  for (double x : {0.2, 0.35, 0.5, 0.8, 1.3}) {
    for (const LognormalFragilityFit* fit : {&small, &large}) {
      const auto [lo, hi] = fit->band(x, 0.9995);
      EXPECT_LE(lo, t.p(x)) << x;
      EXPECT_GE(hi, t.p(x)) << x;
      const auto [lo95, hi95] = fit->band(x, 0.95);
      EXPECT_LE(lo95, fit->probability(x));
      EXPECT_GE(hi95, fit->probability(x));
      EXPECT_GT(lo95, lo);
      EXPECT_LT(hi95, hi);
    }
    // 100 times the data: about a tenth of the width (factor 3 margin).
    const auto [lo, hi] = small.band(x, 0.95);
    const auto [lo2, hi2] = large.band(x, 0.95);
    EXPECT_LT(hi2 - lo2, 0.3 * (hi - lo)) << x;
  }
}

TEST(FragilityFit, ExactFractionsGiveTheParametersBack) {
  // Fractions equal to the true curve (n large, rounded counts): the MLE is the truth to the rounding, 1/n.
  const Truth t{0.3, 0.6};
  FragilityData d;
  constexpr int n = 1'000'000;
  for (double x : log_grid(0.05, 2.0, 9)) {
    d.im.push_back(x);
    d.trials.push_back(n);
    d.failures.push_back(static_cast<int>(std::lround(n * t.p(x))));
  }
  const LognormalFragilityFit fit = fit_lognormal_fragility(d);
  EXPECT_NEAR(fit.theta, t.theta, 1e-4);
  EXPECT_NEAR(fit.beta, t.beta, 1e-4);
}

TEST(FragilityFit, DegenerateData) {
  FragilityData none{{0.1, 0.2}, {10, 10}, {0, 0}};
  try {
    (void)fit_lognormal_fragility(none);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "failures");
  }
  FragilityData all{{0.1, 0.2}, {10, 10}, {10, 10}};
  EXPECT_THROW((void)fit_lognormal_fragility(all), InputError);
  EXPECT_THROW((void)fit_lognormal_fragility({{0.1, -0.2}, {10, 10}, {1, 2}}), InputError);
  EXPECT_THROW((void)fit_lognormal_fragility({{0.1, 0.2}, {10, 10}, {1, 12}}), InputError);
  // Perfectly separated: beta runs to its bound; the median sits between the last safe and first failing level.
  const LognormalFragilityFit sep = fit_lognormal_fragility({{0.1, 0.2, 0.4, 0.8}, {10, 10, 10, 10}, {0, 0, 10, 10}});
  EXPECT_TRUE(sep.beta_at_bound);
  EXPECT_GT(sep.theta, 0.2);
  EXPECT_LT(sep.theta, 0.4);
}

/// The ensembles' synthetic motion: PGA 0.3 g (of a pair: RotD50) at 2 Hz.
SynthesisSpec ensemble_spec(std::uint64_t seed, double duration_s) {
  SynthesisSpec s;
  s.pga_m_s2 = 0.3 * kStandardGravity;
  s.predominant_frequency_hz = 2.0;
  s.duration_s = duration_s;
  s.seed = seed;
  return s;
}

/// Overturning of `body` under Housner's rocking model, every other choice at its default (value-initialised, so
/// that the members added since, coupled, body_3d, cylinder_3d, mu_3d, mu_k_3d, stay unset without being listed).
OverturnFailure rocking(const RockingBody& body) {
  OverturnFailure failure{};
  failure.body = body;
  return failure;
}

/// Record `m` along east (azimuth 90) with a still north partner: a collinear pair, whose projection on bearing 90 is
/// the record bit for bit (MotionSet::projected).
std::shared_ptr<const MotionSet> collinear_pair(const GroundMotion& m) {
  const GroundMotion quiet = GroundMotion::uniform(std::vector<double>(m.size(), 0.0), m.dt_s());
  return std::make_shared<const MotionSet>(MotionSet::make(m, &quiet, ComponentAzimuths{90.0, 0.0}));
}

/// The collinear pairs of the synthetic records of seeds 1..count (ensemble_spec, 8 s).
std::vector<std::shared_ptr<const MotionSet>> collinear_pairs(std::uint64_t count) {
  std::vector<std::shared_ptr<const MotionSet>> sets;
  for (std::uint64_t seed = 1; seed <= count; ++seed) {
    sets.push_back(collinear_pair(synthesize(ensemble_spec(seed, 8.0))));
  }
  return sets;
}

/// The box 0.15 x 0.3 x 0.6 m (width along its +x axis, depth, height) in three dimensions at bearing 90 under
/// `sets`, at `levels` PGAs log-spaced from 0.1 to 1.2 g; its planar body is the block of its width.
FragilitySpec box_3d_under(const std::vector<std::shared_ptr<const MotionSet>>& sets, std::size_t levels) {
  FragilitySpec spec;
  spec.motion_sets = sets;
  spec.levels_si = log_grid(0.1 * kStandardGravity, 1.2 * kStandardGravity, levels);
  spec.bearing_deg = 90.0;
  spec.overturning = rocking(RockingBody::block(0.15, 0.6));
  spec.overturning->body_3d = RigidBody3D::box(0.15, 0.3, 0.6);
  return spec;
}

/// The field of the InputError fragility_analysis refuses `spec` with; "(none)" when it accepts it.
std::string refused_field(const FragilitySpec& spec) {
  try {
    (void)fragility_analysis(spec);
  } catch (const InputError& e) {
    return e.where().field;
  }
  return "(none)";
}

TEST(FragilityAnalysis, CountsEqualSingleRuns) {
  std::vector<std::shared_ptr<const GroundMotion>> motions;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    motions.push_back(std::make_shared<const GroundMotion>(synthesize(ensemble_spec(seed, 8.0))));
  }
  FragilitySpec spec;
  spec.motions = motions;
  spec.im = IntensityMeasure::pga;
  spec.levels_si = log_grid(0.05 * kStandardGravity, 1.5 * kStandardGravity, 6);
  spec.sliding = SlidingFailure{SlidingBlock::make(0.2), 0.02};
  spec.overturning = rocking(RockingBody::block(0.1, 0.4));
  const FragilityResult r = fragility_analysis(spec);
  ASSERT_EQ(r.curves.size(), 2u);
  EXPECT_EQ(r.runs, 4u * 6u * 2u);
  EXPECT_EQ(r.curves[0].name, "slide");
  EXPECT_EQ(r.curves[1].name, "overturn");
  for (std::size_t j = 0; j < spec.levels_si.size(); ++j) {
    int slid = 0;
    int fell = 0;
    for (const auto& m : motions) {
      const GroundMotion scaled = m->scaled(spec.levels_si[j] / m->pga_m_s2());
      slid += slide_summary(scaled, spec.sliding->block).max_abs_displacement_m > 0.02 ? 1 : 0;
      fell += rock_summary(scaled, spec.overturning->body).overturned ? 1 : 0;
    }
    EXPECT_EQ(r.curves[0].data.failures[j], slid) << j;
    EXPECT_EQ(r.curves[1].data.failures[j], fell) << j;
    EXPECT_EQ(r.curves[0].data.trials[j], 4);
  }
  // Sliding grows with the level here: the lowest level (0.05 g < mu) never slides, the highest always does.
  EXPECT_EQ(r.curves[0].data.failures.front(), 0);
  EXPECT_EQ(r.curves[0].data.failures.back(), 4);
  // PGV as the measure: each motion scaled so that its PGV is the level.
  spec.im = IntensityMeasure::pgv;
  spec.levels_si = {0.1, 0.5};
  spec.overturning.reset();
  const FragilityResult v = fragility_analysis(spec);
  EXPECT_EQ(v.curves.size(), 1u);
  spec.sliding.reset();
  EXPECT_THROW((void)fragility_analysis(spec), InputError);
}

// Pairs (fragility.hpp, "Pairs"). Each record with a zero second component at 90 deg is collinear input: a block at
// bearing 90 (the record's azimuth) rocks under the record itself (the projection on a component's azimuth is that
// component bit for bit, MotionSet::projected), a sliding block slides as the 1-D block to 1e-9 relative
// (sliding2d.hpp). The pair's RotD50 PGA is the record's PGA x r, r = cos 45 deg to rounding (rotd.hpp, closed
// forms), so the pair's counts at levels x_j r are the 1-D counts at x_j (the scale factors x_j r / RotD50 and
// x_j / PGA agree to rounding; no run sits within 1e-9 of the threshold here), and the fitted median is theta r.
TEST(FragilityAnalysis, PairsWithAZeroSecondComponentAtTheRecordsAzimuthAreThe1dFragility) {
  std::vector<std::shared_ptr<const GroundMotion>> motions;
  std::vector<std::shared_ptr<const MotionSet>> sets;
  std::vector<double> ratio;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const auto m = std::make_shared<const GroundMotion>(synthesize(ensemble_spec(seed, 8.0)));
    motions.push_back(m);
    sets.push_back(collinear_pair(*m));
    ratio.push_back(rotd_measures(*sets.back(), {}).pga_m_s2.rotd50 / m->pga_m_s2());
    EXPECT_NEAR(ratio.back(), std::cos(kPi / 4.0), 1e-15);
  }
  FragilitySpec one;
  one.motions = motions;
  one.levels_si = log_grid(0.1 * kStandardGravity, 1.2 * kStandardGravity, 8);
  one.sliding = SlidingFailure{SlidingBlock::make(0.2), 0.02};
  one.overturning = rocking(RockingBody::block(0.15, 0.6));
  const FragilityResult r1 = fragility_analysis(one);
  FragilitySpec two = one;
  two.motions.clear();
  two.motion_sets = sets;
  two.bearing_deg = 90.0;
  for (double& x : two.levels_si) x *= ratio.front();
  const FragilityResult r2 = fragility_analysis(two);
  EXPECT_TRUE(r2.rotd50);
  EXPECT_EQ(r2.bearings_deg, std::vector<double>(6, 90.0));
  ASSERT_EQ(r2.curves.size(), 2u);
  for (std::size_t c = 0; c < 2; ++c) {
    SCOPED_TRACE(r1.curves[c].name);
    EXPECT_EQ(r2.curves[c].data.failures, r1.curves[c].data.failures);
    ASSERT_TRUE(r1.curves[c].fit.has_value());
    ASSERT_TRUE(r2.curves[c].fit.has_value());
    // The same counts on levels scaled by r: ln L is the same function shifted by ln r; the optimiser stops at 1e-12
    // relative steps (Newton polish), far inside 1e-8.
    EXPECT_NEAR(r2.curves[c].fit->theta, r1.curves[c].fit->theta * ratio.front(), 1e-8 * r1.curves[c].fit->theta);
    EXPECT_NEAR(r2.curves[c].fit->beta, r1.curves[c].fit->beta, 1e-8);
  }
  // The failures vary over the levels (the test is not vacuous).
  EXPECT_EQ(r1.curves[0].data.failures.front(), 0);
  EXPECT_EQ(r1.curves[0].data.failures.back(), 6);
  EXPECT_GT(r1.curves[1].data.failures.back(), 0);

  // Across the record (bearing 0, along the zero component) the block never rocks.
  two.bearing_deg = 0.0;
  two.sliding.reset();
  EXPECT_EQ(fragility_analysis(two).curves[0].data.failures, std::vector<int>(8, 0));
}

// A body in three dimensions (OverturnFailure::body_3d) under the same collinear pairs: a box at bearing 90 (its +x
// axis, the width, along the record) rocks in its plane of symmetry, where the three-dimensional engine is the planar
// one (rigid3d.hpp; 1e-6 in test_rigid3d), so its counts are the planar block's of its width; at bearing 0 the record
// lies along its depth, and its counts are the planar block's of its depth. Under single components it is refused.
TEST(FragilityAnalysis, AThreeDimensionalBoxUnderCollinearPairsIsThePlanarBlockOfItsSection) {
  const std::vector<std::shared_ptr<const MotionSet>> sets = collinear_pairs(6);
  FragilitySpec box = box_3d_under(sets, 8);
  FragilitySpec planar = box;  // its body is set per bearing below
  planar.overturning->body_3d.reset();
  int varied = 0;
  for (const double bearing : {90.0, 0.0}) {
    SCOPED_TRACE(bearing);
    planar.overturning = rocking(RockingBody::block(bearing == 90.0 ? 0.15 : 0.3, 0.6));
    box.bearing_deg = bearing;
    const FragilityResult a = fragility_analysis(planar), b = fragility_analysis(box);
    ASSERT_EQ(b.curves.size(), 1U);
    EXPECT_EQ(b.curves[0].data.failures, a.curves[0].data.failures);
    varied += a.curves[0].data.failures.front() != a.curves[0].data.failures.back();
  }
  EXPECT_EQ(varied, 2);  // the failures vary over the levels at both bearings (the test is not vacuous)
  FragilitySpec single = box;
  single.motion_sets.clear();
  single.motions.push_back(std::make_shared<const GroundMotion>(sets.front()->first()));
  single.bearing_deg.reset();
  EXPECT_EQ(refused_field(single), "model");  // a 3-D body under single components
}

// Friction for a three-dimensional box (OverturnFailure::mu_3d): with mu < b / h it can never lift (Shenton 1996; in
// three dimensions the centre of pressure of a base sticking or sliding flat lies within h mu of c's plan, rigid3d.hpp:
// here h = 0.3 m, mu = 0.2, h mu = 0.06 m < b = 0.075 m, the half-width along the record), so no pair overturns it at
// any level, where without friction the same box falls; likewise a cylinder (rigid3d_disc.hpp). A bad mu is refused by
// name, before any run.
TEST(FragilityAnalysis, AThreeDimensionalBoxWithFrictionBelowItsAspectRatioNeverFalls) {
  const std::vector<std::shared_ptr<const MotionSet>> sets = collinear_pairs(4);
  FragilitySpec box = box_3d_under(sets, 6);
  const std::vector<int> no_slip = fragility_analysis(box).curves.at(0).data.failures;
  EXPECT_GT(no_slip.back(), 0);  // without friction it falls: the limit below is not vacuous
  box.overturning->mu_3d = 0.2;  // b / h = 0.075 / 0.3 = 0.25
  EXPECT_EQ(fragility_analysis(box).curves.at(0).data.failures, std::vector<int>(6, 0));

  FragilitySpec bad = box;
  bad.overturning->mu_3d = -0.1;
  EXPECT_NE(refused_field(bad).find("mu"), std::string::npos) << refused_field(bad);  // a negative mu
  // A cylinder with friction (rigid3d_disc.hpp): below Shenton's mu_s = R / h (0.1 / 0.4 = 0.25) it never lifts,
  // at any scale; a negative mu is refused by name.
  FragilitySpec cyl = box;
  cyl.overturning->body_3d.reset();
  cyl.overturning->cylinder_3d = CylinderBody3D::solid(0.2, 0.8);
  cyl.overturning->mu_3d.reset();
  EXPECT_GT(fragility_analysis(cyl).curves.at(0).data.failures.back(), 0);
  cyl.overturning->mu_3d = 0.2;
  EXPECT_EQ(fragility_analysis(cyl).curves.at(0).data.failures, std::vector<int>(6, 0));
  cyl.overturning->mu_3d = -0.1;
  EXPECT_NE(refused_field(cyl).find("mu"), std::string::npos) << refused_field(cyl);  // a negative mu
}

// A cylinder in three dimensions (OverturnFailure::cylinder_3d, the rim engine rigid3d_disc.hpp) under collinear
// pairs: it rocks in the vertical plane of the record, where the rim engine is the planar cylinder (test_rigid3d_disc:
// 1e-6), so its counts are those of the planar cylinder's section (a, h, D as a general body) rocking in the record's
// plane (bearing 90). Not those of model "rocking" for a cylinder under pairs: that takes the worst of its 12
// directions, and overturning is not monotonic in the amplitude, so a direction that sees cos(phi) of the record can
// fall where the record's own does not (here 5 of 6 against 3 of 6 at one level). No bearing: a cylinder is
// axisymmetric. Under single components it is refused.
TEST(FragilityAnalysis, AThreeDimensionalCylinderUnderCollinearPairsIsThePlanarCylinder) {
  const std::vector<std::shared_ptr<const MotionSet>> sets = collinear_pairs(6);
  FragilitySpec planar;
  planar.motion_sets = sets;
  planar.levels_si = log_grid(0.1 * kStandardGravity, 1.2 * kStandardGravity, 8);
  const RockingBody section = RockingBody::cylinder(0.2, 0.8);
  FragilitySpec cyl = planar;
  cyl.overturning = rocking(section);
  cyl.overturning->cylinder_3d = CylinderBody3D::solid(0.2, 0.8);
  planar.overturning = rocking(RockingBody::general(section.a_m, section.h_m, section.D_m2));
  planar.bearing_deg = 90.0;
  const FragilityResult a = fragility_analysis(planar), b = fragility_analysis(cyl);
  ASSERT_EQ(b.curves.size(), 1U);
  EXPECT_EQ(b.curves[0].data.failures, a.curves[0].data.failures);
  EXPECT_NE(a.curves[0].data.failures.front(), a.curves[0].data.failures.back());  // not vacuous
  FragilitySpec worst = cyl;  // model "rocking" for the cylinder: the worst of its directions
  worst.overturning->cylinder_3d.reset();
  std::printf("cylinder 0.2 x 0.8 m under collinear pairs: 3-D %s, worst planar direction %s\n",
              testing::PrintToString(b.curves[0].data.failures).c_str(),
              testing::PrintToString(fragility_analysis(worst).curves[0].data.failures).c_str());
  FragilitySpec single = cyl;
  single.motion_sets.clear();
  single.motions.push_back(std::make_shared<const GroundMotion>(sets.front()->first()));
  EXPECT_EQ(refused_field(single), "model");  // a 3-D cylinder under single components
}

TEST(FragilityAnalysis, PairsWithoutABearingDrawOnePerMotionAndBadInputIsNamed) {
  std::vector<std::shared_ptr<const MotionSet>> sets;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    SynthesisSetSpec ss;
    ss.horizontal = ensemble_spec(seed, 6.0);
    ss.vertical = false;
    const SynthesizedSet syn = synthesize_set(ss);
    sets.push_back(std::make_shared<const MotionSet>(MotionSet::make(syn.first, &syn.second, ss.azimuths)));
  }
  FragilitySpec spec;
  spec.motion_sets = sets;
  spec.levels_si = {0.2 * kStandardGravity, 0.8 * kStandardGravity};
  spec.overturning = rocking(RockingBody::block(0.15, 0.6));
  const FragilityResult a = fragility_analysis(spec);
  // PortableRandom(1)'s first five uniforms x 360 deg: the same bearings on every machine and every call.
  PortableRandom random(1);
  ASSERT_EQ(a.bearings_deg.size(), 5u);
  for (const double b : a.bearings_deg) {
    EXPECT_EQ(b, 360.0 * random.uniform());
    EXPECT_GE(b, 0.0);
    EXPECT_LT(b, 360.0);
  }
  EXPECT_EQ(fragility_analysis(spec).bearings_deg, a.bearings_deg);
  spec.bearing_seed = 2;
  EXPECT_NE(fragility_analysis(spec).bearings_deg, a.bearings_deg);
  // Each count is the oriented run at the motion's bearing, the pair scaled by its RotD50 PGA.
  for (std::size_t j = 0; j < 2; ++j) {
    int fell = 0;
    for (std::size_t i = 0; i < sets.size(); ++i) {
      const double f = spec.levels_si[j] / rotd_measures(*sets[i], {}).pga_m_s2.rotd50;
      const GroundMotion h1 = sets[i]->first().scaled(f);
      const GroundMotion h2 = sets[i]->second().scaled(f);
      const MotionSet scaled = MotionSet::make(h1, &h2, sets[i]->azimuths());
      fell += rock_oriented_summary(scaled, OrientedBody::planar(spec.overturning->body), a.bearings_deg[i])
                      .governing_response().summary.overturned ? 1 : 0;
    }
    EXPECT_EQ(a.curves[0].data.failures[j], fell) << j;
  }

  FragilitySpec bad = spec;
  bad.im = IntensityMeasure::pgv;
  EXPECT_EQ(refused_field(bad), "im");
  bad = spec;
  bad.motions.push_back(std::make_shared<const GroundMotion>(sets[0]->first()));
  EXPECT_EQ(refused_field(bad), "motions");
  bad = spec;
  bad.motion_sets.push_back(std::make_shared<const MotionSet>(MotionSet::make(sets[0]->first(), nullptr, std::nullopt)));
  EXPECT_EQ(refused_field(bad), "motions");
  bad = spec;
  bad.sliding = SlidingFailure{SlidingBlock::make(0.3, 0.3, 0.1, SlidingMode::one_way), 0.02};
  EXPECT_EQ(refused_field(bad), "mode");
  bad.sliding = SlidingFailure{SlidingBlock::make(0.3, 0.3, 0.1), 0.02};
  EXPECT_EQ(refused_field(bad), "slope");
  bad = spec;
  bad.overturning->body = RockingBody::cylinder(0.15, 0.6);
  bad.bearing_deg = 10.0;
  EXPECT_EQ(refused_field(bad), "bearing");
  bad = spec;
  bad.bearing_deg = std::nan("");
  EXPECT_EQ(refused_field(bad), "bearing");
}

// Pairs with a vertical under the rocking model (fragility.cpp, check_rocking_contact): pair i leaves the ground from
// L_i = RotD50_i g / max(-a_v,i) up (the vertical scales with the pair). L_i is computed here from each synthetic
// triple's own samples; the levels are put 1e-9 relative either side of the lowest L_i.
TEST(FragilityAnalysis, PairsWithAVerticalRefuseLevelsWhereTheRockingBodyWouldLeaveTheGround) {
  std::vector<std::shared_ptr<const MotionSet>> sets;
  std::vector<double> lift_off;  // L_i, m/s2 (RotD50 PGA)
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    SynthesisSetSpec ss;
    ss.horizontal = ensemble_spec(seed, 6.0);
    const SynthesizedSet syn = synthesize_set(ss);
    ASSERT_TRUE(syn.vertical.has_value());
    sets.push_back(std::make_shared<const MotionSet>(MotionSet::make(syn.first, &syn.second, ss.azimuths,
                                                                     &*syn.vertical)));
    const auto a_v = syn.vertical->accel_m_s2();
    const double lowest = *std::min_element(a_v.begin(), a_v.end());
    ASSERT_LT(lowest, 0.0);
    lift_off.push_back(rotd_measures(*sets.back(), {}).pga_m_s2.rotd50 * kStandardGravity / -lowest);
  }
  const double allowed = *std::min_element(lift_off.begin(), lift_off.end());
  const auto first = static_cast<std::size_t>(std::min_element(lift_off.begin(), lift_off.end()) - lift_off.begin());
  FragilitySpec spec;
  spec.motion_sets = sets;
  spec.bearing_deg = 30.0;
  spec.overturning = rocking(RockingBody::block(0.15, 0.6));
  // Just below the lowest lift-off level every run keeps contact and the analysis runs (each count 0..3).
  spec.levels_si = {0.2 * kStandardGravity, allowed * (1.0 - 1e-9)};
  const FragilityResult ok = fragility_analysis(spec);
  ASSERT_EQ(ok.curves.size(), 1u);
  EXPECT_EQ(ok.curves[0].data.trials, std::vector<int>(2, 3));
  // At it the pair that sets it is named, with the highest allowed level (4 significant digits, in g), before any run.
  spec.levels_si.back() = allowed * (1.0 + 1e-9);
  try {
    (void)fragility_analysis(spec);
    FAIL() << "no error at the lift-off level";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "levels");
    EXPECT_NE(e.problem().find(fmt::format("pair {} of the ensemble", first + 1)), std::string::npos) << e.problem();
    EXPECT_NE(e.problem().find(fmt::format("every pair keeps contact below {:.4g} g", allowed / kStandardGravity)),
              std::string::npos)
        << e.problem();
  }
  // Sliding alone keeps running there: the 2-D block's friction uses g_e^+ and reports the loss (sliding2d.hpp).
  spec.overturning.reset();
  spec.sliding = SlidingFailure{SlidingBlock::make(0.3), 0.02};
  EXPECT_EQ(fragility_analysis(spec).curves[0].data.trials, std::vector<int>(2, 3));
}

// ---- The fragility surface in PGA and PGV/PGA (fragility.hpp, "As recorded") ----

/// The truth of the surface tests: ln theta(v) = ln 2 m/s2 - 0.5 ln(v / 0.1 s), beta = 0.3.
struct SurfaceTruth {
  double ln_theta_01 = std::log(2.0);
  double gamma = -0.5;
  double beta = 0.3;
  [[nodiscard]] double ln_theta(double v_s) const { return ln_theta_01 + gamma * std::log(v_s / 0.1); }
  [[nodiscard]] double p(double pga, double v_s) const {
    return boost::math::cdf(kN, (std::log(pga) - ln_theta(v_s)) / beta);
  }
};

/// n records, PGA log-uniform on [0.3, 15] m/s2 and PGV/PGA log-uniform on [0.03, 0.4] s, each failing with the
/// truth's probability (PortableRandom: the same draws on every machine).
std::vector<SurfaceOutcome> draw_surface(std::size_t n, std::uint64_t seed, const SurfaceTruth& t = {}) {
  PortableRandom random(seed);
  std::vector<SurfaceOutcome> out;
  for (std::size_t i = 0; i < n; ++i) {
    const double pga = std::exp(std::log(0.3) + random.uniform() * std::log(15.0 / 0.3));
    const double v = std::exp(std::log(0.03) + random.uniform() * std::log(0.4 / 0.03));
    out.push_back({pga, pga * v, random.uniform() < t.p(pga, v)});
  }
  return out;
}

// 4000 records drawn from a known surface: the fit recovers each parameter within 4 of its own standard errors,
// and within stated absolute tolerances (beta 0.03, gamma 0.06, ln theta_ref 0.04: about 3 standard errors at this
// n). The probability it gives at a point is the truth's to 0.03.
TEST(FragilitySurface, RecoversKnownParameters) {
  const SurfaceTruth t;
  const auto data = draw_surface(4000, 7);
  const FragilitySurfaceFit f = fit_fragility_surface(data);
  const double truth_ref = t.ln_theta(f.v_ref_s);  // the truth's median at the fit's reference PGV/PGA
  EXPECT_NEAR(f.beta, t.beta, 4 * f.se_beta);
  EXPECT_NEAR(f.gamma, t.gamma, 4 * f.se_gamma);
  EXPECT_NEAR(f.ln_theta_ref, truth_ref, 4 * f.se_ln_theta_ref);
  EXPECT_NEAR(f.beta, t.beta, 0.03);
  EXPECT_NEAR(f.gamma, t.gamma, 0.06);
  EXPECT_NEAR(f.ln_theta_ref, truth_ref, 0.04);
  EXPECT_GT(f.v_ref_s, 0.03);
  EXPECT_LT(f.v_ref_s, 0.4);
  EXPECT_EQ(f.records, 4000u);
  EXPECT_NEAR(f.probability(3.0, 0.1), t.p(3.0, 0.1), 0.03);
  EXPECT_NEAR(std::log(f.median_pga_m_s2(0.2)), t.ln_theta(0.2), 0.06);
  // The standard errors shrink as 1/sqrt(n): a quarter of the records, about twice the error.
  const FragilitySurfaceFit q = fit_fragility_surface(draw_surface(1000, 8));
  EXPECT_NEAR(q.se_beta / f.se_beta, 2.0, 0.4);
  EXPECT_NEAR(q.se_gamma / f.se_gamma, 2.0, 0.4);
}

// The standard errors are the sampling spread: over 200 data sets of 300 records, the truth lies within 1.96
// standard errors of the estimate in 95 % of them (binomial sampling of 200 at 0.95: 0.90 to 0.99 holds with
// probability above 0.999; the delta-method interval is asymptotic, hence the slack below 0.95).
TEST(FragilitySurface, StandardErrorsCoverTheTruth) {
  const SurfaceTruth t;
  int beta_in = 0;
  int gamma_in = 0;
  int theta_in = 0;
  constexpr int kSets = 200;
  for (int k = 0; k < kSets; ++k) {
    const FragilitySurfaceFit f = fit_fragility_surface(draw_surface(300, 1000 + static_cast<std::uint64_t>(k)));
    beta_in += std::abs(f.beta - t.beta) < 1.96 * f.se_beta ? 1 : 0;
    gamma_in += std::abs(f.gamma - t.gamma) < 1.96 * f.se_gamma ? 1 : 0;
    theta_in += std::abs(f.ln_theta_ref - t.ln_theta(f.v_ref_s)) < 1.96 * f.se_ln_theta_ref ? 1 : 0;
  }
  for (const int in : {beta_in, gamma_in, theta_in}) {
    EXPECT_GE(in, 180) << in;  // 0.90
    EXPECT_LE(in, 198) << in;  // 0.99
  }
}

TEST(FragilitySurface, DegenerateDataAreRefusedNamingTheOutcomes) {
  const auto refused = [](const std::vector<SurfaceOutcome>& d, const std::string& words) {
    try {
      (void)fit_fragility_surface(d);
      ADD_FAILURE() << "accepted: " << words;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, "outcomes");
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  auto d = draw_surface(200, 3);
  auto none = d;
  for (auto& o : none) o.failed = false;
  refused(none, "0 of 200");
  auto all = d;
  for (auto& o : all) o.failed = true;
  refused(all, "200 of 200");
  auto two = none;
  two[0].failed = two[1].failed = true;
  refused(two, "at least 3");
  auto same_v = d;  // PGV/PGA the same for every record: a curve, not a surface
  for (auto& o : same_v) o.pgv_m_s = 0.1 * o.pga_m_s2;
  refused(same_v, "same PGV/PGA");
  auto separated = d;  // fails exactly when PGA > 3 m/s2: beta -> 0
  for (auto& o : separated) o.failed = o.pga_m_s2 > 3.0;
  refused(separated, "separated");
  auto backwards = d;  // failures only at low PGA
  for (auto& o : backwards) o.failed = !o.failed;
  refused(backwards, "not positive");
  auto bad = d;
  bad[5].pga_m_s2 = 0.0;
  refused(bad, "record 6");
  bad[5].pga_m_s2 = std::nan("");
  refused(bad, "record 6");
  // PGA and PGV/PGA moving together (every record's PGV the same): the two regressors are collinear.
  auto collinear = d;
  for (auto& o : collinear) o.pgv_m_s = 0.5;
  refused(collinear, "move together");
}

// As recorded: each record run once, unscaled; the outcomes are single runs', the PGA and PGV the record's; the
// coupled model's outcome is slide_rock's.
TEST(FragilityAsRecorded, OutcomesAreSingleRunsAndTheCoupledModelIsSlideRock) {
  FragilitySpec spec;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    SynthesisSpec s = ensemble_spec(seed, 8.0);
    s.pga_m_s2 = (0.1 + 0.1 * static_cast<double>(seed)) * kStandardGravity;
    spec.motions.push_back(std::make_shared<const GroundMotion>(synthesize(s)));
  }
  const RockingBody body = RockingBody::general_asymmetric(0.05, 0.08, 0.3, 0.02);
  spec.overturning = rocking(body);
  spec.sliding = SlidingFailure{SlidingBlock::make(0.3), 0.01};
  const AsRecordedResult r = as_recorded_analysis(spec);
  ASSERT_EQ(r.curves.size(), 2u);
  EXPECT_EQ(r.runs, 12u);
  int fell = 0;
  for (std::size_t i = 0; i < spec.motions.size(); ++i) {
    const GroundMotion& m = *spec.motions[i];
    EXPECT_EQ(r.pga_m_s2[i], m.pga_m_s2());
    EXPECT_NEAR(r.pga_m_s2[i], (0.2 + 0.1 * static_cast<double>(i)) * kStandardGravity, 1e-9);
    EXPECT_EQ(r.pgv_m_s[i], basic_intensity(m).pgv_m_s);
    EXPECT_EQ(r.curves[0].failed[i], slide_summary(m, spec.sliding->block).max_abs_displacement_m > 0.01);
    EXPECT_EQ(r.curves[1].failed[i], rock_summary(m, body).overturned);
    fell += r.curves[1].failed[i] ? 1 : 0;
  }
  // Six records cannot give a surface with both outcomes three times over here: the note says why.
  EXPECT_FALSE(r.curves[1].fit.has_value() && fell < 3);
  spec.overturning->coupled = SlideRockBody::from_rocking(body, 0.6, 0.5);
  const AsRecordedResult c = as_recorded_analysis(spec);
  for (std::size_t i = 0; i < spec.motions.size(); ++i) {
    const SlideRockSummary s =
        slide_rock(*spec.motions[i], *spec.overturning->coupled, slide_rock_options(RockingOptions{})).summary;
    EXPECT_EQ(c.curves[1].failed[i], s.overturned) << i;
  }
  // The scaled fragility runs the coupled model too (one level, the same as a single run at that scale).
  spec.levels_si = {0.5 * kStandardGravity};
  spec.sliding.reset();
  const FragilityResult scaled = fragility_analysis(spec);
  int scaled_fell = 0;
  for (const auto& m : spec.motions) {
    scaled_fell += slide_rock(m->scaled(0.5 * kStandardGravity / m->pga_m_s2()), *spec.overturning->coupled,
                              slide_rock_options(RockingOptions{})).summary.overturned ? 1 : 0;
  }
  EXPECT_EQ(scaled.curves[0].data.failures[0], scaled_fell);
  // Refusals name the field.
  FragilitySpec empty;
  empty.overturning = spec.overturning;
  EXPECT_THROW((void)as_recorded_analysis(empty), InputError);
  FragilitySpec still = spec;
  still.motions = {std::make_shared<const GroundMotion>(GroundMotion::uniform({0.0, 0.0, 0.0}, 0.01))};
  try {
    (void)as_recorded_analysis(still);
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "motions");
  }
}

}  // namespace
}  // namespace topple
