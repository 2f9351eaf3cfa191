// Object spectra: the sliding spectrum equals single runs and the thesis' closed forms; the overturning map equals
// single rocking runs; a body that cannot lift off never falls.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/closed_forms/sliding_pulses.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/motion/motion_set.hpp"

namespace topple {
namespace {

GroundMotion synthetic(std::uint64_t seed, double pga_g, double duration_s = 10.0) {
  SynthesisSpec s;
  s.pga_m_s2 = pga_g * kStandardGravity;
  s.predominant_frequency_hz = 2.0;
  s.duration_s = duration_s;
  s.dt_s = 0.01;
  s.seed = seed;
  return synthesize(s);
}

TEST(SlidingSpectrum, EntriesEqualSingleSlideRuns) {
  const GroundMotion m = synthetic(11, 0.4);
  const std::vector<double> mu{0.02, 0.05, 0.1, 0.2, 0.3, 0.45};
  for (const SlidingMode mode : {SlidingMode::two_way, SlidingMode::one_way}) {
    const double slope = mode == SlidingMode::one_way ? 10.0 * kPi / 180.0 : 0.0;
    const SlidingSpectrum sp = sliding_spectrum(m, mu, slope, mode);
    ASSERT_EQ(sp.points.size(), mu.size());
    EXPECT_DOUBLE_EQ(sp.pga_m_s2, m.pga_m_s2());
    for (std::size_t i = 0; i < mu.size(); ++i) {
      const SlidingBlock block = SlidingBlock::make(mu[i], std::nullopt, slope, mode);
      const SlidingSummary one = slide_summary(m, block);
      // Same exact solver on the same samples: equal to a few ulps of the displacement (the kernel skips stick
      // blocks, which changes no arithmetic of the slip phases).
      const double tol = 1e-12 * std::max(1e-3, one.max_abs_displacement_m);
      EXPECT_NEAR(sp.points[i].max_abs_displacement_m, one.max_abs_displacement_m, tol) << mu[i];
      EXPECT_NEAR(sp.points[i].residual_displacement_m, one.residual_displacement_m, tol) << mu[i];
      EXPECT_EQ(sp.points[i].slip_episodes, one.slip_episodes) << mu[i];
      EXPECT_NEAR(sp.points[i].yield_over_pga * m.pga_m_s2(), block.yield_down_m_s2(), 1e-12);
    }
    // More friction, less sliding (level and one-way: monotone in mu for a fixed record).
    for (std::size_t i = 1; i < mu.size(); ++i) {
      EXPECT_LE(sp.points[i].max_abs_displacement_m, sp.points[i - 1].max_abs_displacement_m + 1e-15);
    }
  }
}

// The bidirectional spectrum: each point is slide_2d_summary and slide_summary of each component (the same calls:
// equal exactly); a collinear pair (the second component zero) is the 1-D spectrum of the first, to 1e-9 relative
// (the 2-D solver's agreement with the exact 1-D one, test_sliding2d); the k_y axis is mu g / RotD50 PGA, and the
// RotD50 PGA of a synthetic pair is the one it was scaled to (synthesis.hpp, to round-off).
TEST(SlidingSpectrum2d, PointsAreTheSingleRunsAndACollinearPairIsThe1dSpectrum) {
  SynthesisSetSpec spec;
  spec.horizontal.pga_m_s2 = 0.35 * kStandardGravity;
  spec.horizontal.predominant_frequency_hz = 2.0;
  spec.horizontal.duration_s = 10.0;
  spec.horizontal.dt_s = 0.01;
  spec.horizontal.seed = 5;
  const SynthesizedSet syn = synthesize_set(spec);
  const MotionSet set = MotionSet::make(syn.first, &syn.second, spec.azimuths, &*syn.vertical);
  const std::vector<double> mu{0.05, 0.1, 0.2};
  const SlidingSpectrum2d sp = sliding_spectrum_2d(set, mu);
  EXPECT_NEAR(sp.rotd50_pga_m_s2, spec.horizontal.pga_m_s2, 1e-12 * spec.horizontal.pga_m_s2);
  EXPECT_TRUE(sp.with_vertical);
  ASSERT_EQ(sp.points.size(), mu.size());
  for (std::size_t i = 0; i < mu.size(); ++i) {
    const SlidingBlock block = SlidingBlock::make(mu[i]);
    const Sliding2dSummary two = slide_2d_summary(set.first(), set.second(), spec.azimuths, block, set.vertical_ptr());
    EXPECT_EQ(sp.points[i].bidirectional.residual_displacement_m, two.residual_displacement_m);
    EXPECT_EQ(sp.points[i].bidirectional.max_abs_displacement_m, two.max_abs_displacement_m);
    EXPECT_EQ(sp.points[i].bidirectional.path_length_m, two.path_length_m);
    EXPECT_EQ(sp.points[i].first_alone.residual_displacement_m,
              slide_summary(set.first(), block, set.vertical_ptr()).residual_displacement_m);
    EXPECT_EQ(sp.points[i].second_alone.max_abs_displacement_m,
              slide_summary(set.second(), block, set.vertical_ptr()).max_abs_displacement_m);
    EXPECT_NEAR(sp.points[i].yield_over_rotd50_pga * sp.rotd50_pga_m_s2, mu[i] * kStandardGravity, 1e-12);
  }
  EXPECT_GT(sp.points[0].bidirectional.residual_displacement_m, 1e-3);  // the pair slides the block

  const GroundMotion quiet = GroundMotion::uniform(std::vector<double>(syn.first.size(), 0.0), syn.first.dt_s());
  const MotionSet collinear = MotionSet::make(syn.first, &quiet, ComponentAzimuths{90.0, 0.0});
  const SlidingSpectrum2d c = sliding_spectrum_2d(collinear, mu);
  const SlidingSpectrum one = sliding_spectrum(syn.first, mu);
  // RotD50 of (a, 0) is PGA cos 45 deg (rotd.hpp, closed forms).
  EXPECT_NEAR(c.rotd50_pga_m_s2, syn.first.pga_m_s2() * std::cos(kPi / 4.0), 1e-12 * syn.first.pga_m_s2());
  for (std::size_t i = 0; i < mu.size(); ++i) {
    const double scale = one.points[i].max_abs_displacement_m;
    const double d = one.points[i].residual_displacement_m;
    EXPECT_NEAR(c.points[i].bidirectional.max_abs_displacement_m, scale, 1e-9 * scale) << mu[i];
    EXPECT_NEAR(c.points[i].bidirectional.residual_east_m, -d, 1e-9 * scale) << mu[i];
    EXPECT_NEAR(c.points[i].bidirectional.residual_north_m, 0.0, 1e-9 * scale) << mu[i];
    EXPECT_EQ(c.points[i].second_alone.max_abs_displacement_m, 0.0);
  }
  EXPECT_THROW((void)sliding_spectrum_2d(set, std::vector<double>{}), InputError);
  EXPECT_THROW((void)sliding_spectrum_2d(MotionSet::make(syn.first, nullptr, std::nullopt), mu), InputError);
}

TEST(SlidingSpectrum, RectangularPulseMatchesTheClosedForm) {
  // Newmark 1965 / thesis Table 3.1: U_m = v^2 / (2 g N) (1 - N / A), v = A g t0; the rectangle is exactly piecewise
  // linear, so the exact solver reproduces it to round-off (tolerance 1e-9 relative).
  constexpr double A = 2.0;
  constexpr double t0 = 0.1;
  const GroundMotion m = make_pulse({PulseKind::rectangular, A * kStandardGravity, t0, 1.0, 0.0});
  const std::vector<double> mu{0.1, 0.3, 0.5, 1.0, 1.5};
  const SlidingSpectrum sp = sliding_spectrum(m, mu);
  for (std::size_t i = 0; i < mu.size(); ++i) {
    const double um = rectangular_pulse_sliding(A, t0, mu[i]).max_displacement_m;
    EXPECT_NEAR(sp.points[i].max_abs_displacement_m, um, 1e-9 * um) << mu[i];
    EXPECT_NEAR(sp.points[i].residual_displacement_m, um, 1e-9 * um) << mu[i];
    EXPECT_NEAR(sp.points[i].yield_over_pga, mu[i] / A, 1e-14);
  }
  // Above the pulse amplitude nothing moves.
  EXPECT_EQ(sliding_spectrum(m, std::vector<double>{2.5}).points[0].max_abs_displacement_m, 0.0);
}

TEST(SlidingSpectrum, YieldRatioGivesTheFrictionCoefficient) {
  const double pga = 0.3 * kStandardGravity;
  EXPECT_NEAR(mu_for_yield_ratio(0.5, pga), 0.15, 1e-15);  // level: mu = k_y = r PGA / g
  const double slope = 15.0 * kPi / 180.0;
  for (double r : {0.0, 0.2, 0.7, 1.5}) {
    const double mu = mu_for_yield_ratio(r, pga, slope);
    EXPECT_NEAR(SlidingBlock::make(mu, std::nullopt, slope).yield_down_m_s2() / pga, r, 1e-12) << r;
  }
  EXPECT_THROW((void)mu_for_yield_ratio(-0.1, pga), InputError);
  EXPECT_THROW((void)sliding_spectrum(make_pulse({PulseKind::rectangular, 1.0, 0.1, 0.1, 0.0}), std::vector<double>{}),
               InputError);
  try {
    (void)sliding_spectrum(make_pulse({PulseKind::rectangular, 1.0, 0.1, 0.1, 0.0}), std::vector<double>{0.2, -1.0});
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "mu");
  }
}

TEST(OverturningMap, EntriesEqualSingleRockRuns) {
  const GroundMotion m = make_pulse({PulseKind::sine, 1.0, 0.5, 2.0, 0.0005});
  BodyFamily family;
  family.alpha_rad = 0.2;
  family.heights_m = {0.2, 0.5, 1.2};
  const std::vector<double> pga = linear_grid(0.1 * kStandardGravity, 1.6 * kStandardGravity, 6);
  const OverturningMap map = overturning_map(m, family, pga);
  ASSERT_EQ(map.sizes.size(), 3u);
  ASSERT_EQ(map.pga_m_s2.size(), 6u);
  int overturned = 0;
  for (std::size_t s = 0; s < 3; ++s) {
    const RockingBody body = family.body(s);
    EXPECT_NEAR(body.a_m / body.h_m, std::tan(0.2), 1e-14);
    EXPECT_NEAR(map.sizes[s].height_m, family.heights_m[s], 1e-15);
    std::optional<double> first;
    bool standing_above = false;
    for (std::size_t k = 0; k < 6; ++k) {
      const RockingSummary one = rock_summary(m.scaled_to_pga(pga[k]), body);
      EXPECT_EQ(map.at(s, k), one.overturned) << s << ' ' << k;
      EXPECT_DOUBLE_EQ(map.max_rotation_over_alpha[s * 6 + k], one.max_rotation_over_alpha);
      if (one.overturned && !first) first = pga[k];
      if (!one.overturned && first) standing_above = true;
      overturned += one.overturned ? 1 : 0;
    }
    EXPECT_EQ(map.sizes[s].first_overturn_pga_m_s2, first);
    EXPECT_EQ(map.sizes[s].standing_above_first, standing_above);
  }
  // The grid is chosen so that the map is not trivial.
  EXPECT_GT(overturned, 0);
  EXPECT_LT(overturned, 18);
}

TEST(OverturningMap, BodyThatCannotLiftOffNeverFalls) {
  // Uplift needs |a_h| > g tan(alpha) (rocking.hpp); every grid PGA is below it.
  const GroundMotion m = synthetic(5, 1.0, 8.0);
  BodyFamily family;
  family.alpha_rad = 0.4;
  family.heights_m = log_grid(0.05, 3.0, 5);
  const double limit = kStandardGravity * std::tan(0.4);
  const OverturningMap map = overturning_map(m, family, linear_grid(0.1 * limit, 0.99 * limit, 5));
  for (std::size_t s = 0; s < 5; ++s) {
    EXPECT_FALSE(map.sizes[s].first_overturn_pga_m_s2);
    EXPECT_EQ(map.sizes[s].overturn_count, 0u);
    for (std::size_t k = 0; k < 5; ++k) EXPECT_EQ(map.max_rotation_over_alpha[s * 5 + k], 0.0);
  }
}

TEST(OverturningMap, RefusesBadFamilies) {
  const GroundMotion m = make_pulse({PulseKind::sine, 5.0, 0.5, 1.0, 0.001});
  const std::vector<double> pga{3.0};
  const auto field_of = [&](const BodyFamily& f, std::span<const double> p) {
    try {
      (void)overturning_map(m, f, p);
    } catch (const InputError& e) {
      return e.where().field;
    }
    return std::string("no error");
  };
  EXPECT_EQ(field_of({RockingBody::Shape::block, 0.0, {1.0}}, pga), "alpha");
  EXPECT_EQ(field_of({RockingBody::Shape::block, 0.2, {}}, pga), "height");
  EXPECT_EQ(field_of({RockingBody::Shape::block, 0.2, {-1.0}}, pga), "height");
  EXPECT_EQ(field_of({RockingBody::Shape::general, 0.2, {1.0}}, pga), "shape");
  EXPECT_EQ(field_of({RockingBody::Shape::block, 0.2, {1.0}}, std::vector<double>{-2.0}), "pga");
  EXPECT_THROW((void)log_grid(0.0, 1.0, 3), InputError);
  EXPECT_THROW((void)linear_grid(2.0, 1.0, 3), InputError);
}

}  // namespace
}  // namespace topple
