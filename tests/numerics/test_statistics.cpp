// numerics/statistics.hpp: log-sum-exp, the normal CDF and the cells of a log axis, each against closed forms.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "topple/numerics/statistics.hpp"

namespace topple {
namespace {

// A few ulps of the result: these are sums and logs of a handful of terms.
constexpr double kUlps = 4.0 * std::numeric_limits<double>::epsilon();

TEST(Statistics, LogSumExpIsTheLogOfTheSumWithoutOverflow) {
  const std::vector<double> two_zeros{0.0, 0.0};
  EXPECT_NEAR(log_sum_exp(two_zeros), std::log(2.0), kUlps);
  // exp(1000) overflows a double; the factored sum does not: log(2 e^1000) = 1000 + log 2.
  const std::vector<double> large{1000.0, 1000.0};
  EXPECT_NEAR(log_sum_exp(large), 1000.0 + std::log(2.0), 1000.0 * kUlps);
  // Nor does exp(-1000) underflow to a zero sum: log(e^-1000 + e^-1001) = -1000 + log(1 + 1/e).
  const std::vector<double> small{-1000.0, -1001.0};
  EXPECT_NEAR(log_sum_exp(small), -1000.0 + std::log1p(std::exp(-1.0)), 1000.0 * kUlps);
  // A value of -inf (a cell no run reproduces) adds nothing.
  const std::vector<double> with_minus_inf{std::log(3.0), -std::numeric_limits<double>::infinity()};
  EXPECT_NEAR(log_sum_exp(with_minus_inf), std::log(3.0), kUlps);
}

TEST(Statistics, WeightedLogSumExpIsTheLogOfTheWeightedMean) {
  // log((1 * e^0 + 3 * e^{ln 2}) / 4) = log(7 / 4).
  const std::vector<double> x{0.0, std::log(2.0)};
  const std::vector<double> w{1.0, 3.0};
  EXPECT_NEAR(log_sum_exp(x, w, 4.0), std::log(7.0 / 4.0), kUlps);
  // Unit weights and total 1: the plain log-sum-exp to the bit.
  const std::vector<double> y{0.3, -2.0, 1.7};
  const std::vector<double> ones{1.0, 1.0, 1.0};
  EXPECT_EQ(log_sum_exp(y, ones, 1.0), log_sum_exp(y));
}

TEST(Statistics, NormalCdfAtPublishedPoints) {
  EXPECT_EQ(normal_cdf(0.0), 0.5);
  // Phi(1.959963984540054) = 0.975 (the 95 % two-sided quantile, Abramowitz & Stegun 26.2); symmetry.
  EXPECT_NEAR(normal_cdf(1.959963984540054), 0.975, 1e-15);
  EXPECT_NEAR(normal_cdf(-1.959963984540054), 0.025, 1e-16);
  // The lower tail keeps its relative precision: Phi(-30) = 4.906713927148187e-198 (mpmath, 40 digits), not 0. The
  // tail is ill-conditioned in z: d ln Phi / d ln z ~ -z^2 = -900, so the rounding of -z / sqrt 2 alone moves the
  // result by about 900 eps = 2e-13 relative: 1e-12 allows for that and erfc's own few ulps.
  EXPECT_NEAR(normal_cdf(-30.0) / 4.906713927148187e-198, 1.0, 1e-12);
}

TEST(Statistics, LogCellEdgesAreGeometricMidpoints) {
  const double e = std::exp(1.0);
  const std::vector<double> axis{1.0, e, e * e};  // ln: 0, 1, 2
  const auto closed = log_cell_edges(axis);
  ASSERT_EQ(closed.size(), 4U);
  const std::vector<double> expected{-0.5, 0.5, 1.5, 2.5};
  for (std::size_t i = 0; i < 4; ++i) EXPECT_NEAR(closed[i], expected[i], kUlps) << i;
  const auto open = log_cell_edges(axis, CellEnds::open);
  EXPECT_EQ(open.front(), -std::numeric_limits<double>::infinity());
  EXPECT_EQ(open.back(), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(open[1], 0.5, kUlps);
  // A one-value axis: half a unit of ln either side.
  const auto one = log_cell_edges(std::vector<double>{e});
  EXPECT_NEAR(one[0], 0.5, kUlps);
  EXPECT_NEAR(one[1], 1.5, kUlps);
}

}  // namespace
}  // namespace topple
