// Fragility: the maximum-likelihood lognormal fit recovers known parameters from binomial data drawn from them, its
// band contains the truth, degenerate data are handled, and the ensemble analysis counts what single runs give.
#include <cmath>
#include <memory>
#include <vector>

#include <boost/math/distributions/normal.hpp>
#include <gtest/gtest.h>

#include "topple/error.hpp"
#include "topple/fragility.hpp"
#include "topple/object_spectra.hpp"
#include "topple/synthesis.hpp"

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

TEST(FragilityAnalysis, CountsEqualSingleRuns) {
  std::vector<std::shared_ptr<const GroundMotion>> motions;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    SynthesisSpec s;
    s.pga_m_s2 = 0.3 * kStandardGravity;
    s.predominant_frequency_hz = 2.0;
    s.duration_s = 8.0;
    s.seed = seed;
    motions.push_back(std::make_shared<const GroundMotion>(synthesize(s)));
  }
  FragilitySpec spec;
  spec.motions = motions;
  spec.im = IntensityMeasure::pga;
  spec.levels_si = log_grid(0.05 * kStandardGravity, 1.5 * kStandardGravity, 6);
  spec.sliding = SlidingFailure{SlidingBlock::make(0.2), 0.02};
  spec.overturning = OverturnFailure{RockingBody::block(0.1, 0.4), RockingOptions{}};
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

}  // namespace
}  // namespace topple
