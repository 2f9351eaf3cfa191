#pragma once
// Small statistics shared by the inversion, the fragility fit and the regional fit: log-sum-exp, the standard normal
// CDF and the cell edges of a log-spaced axis. One definition each (issue 27); header-only.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <span>
#include <vector>

namespace topple {

/// log(sum_i w_i exp(x_i) / total_weight), finite for any x (the log-sum-exp trick: the largest x_i is factored out,
/// so the largest term is w exp(0) and nothing overflows or underflows to a zero sum). With w_i = 1 and
/// total_weight = 1 it is log(sum_i exp(x_i)) to the bit. x and w have the same size, which is at least 1.
[[nodiscard]] inline double log_sum_exp(std::span<const double> x, std::span<const double> w, double total_weight) {
  double top = -std::numeric_limits<double>::infinity();
  for (const double v : x) top = std::max(top, v);
  double sum = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) sum += w[i] * std::exp(x[i] - top);
  return top + std::log(sum / total_weight);
}

/// log(sum_i exp(x_i)), finite for any x (see above); x holds at least one value. The normaliser of a
/// log-likelihood: log posterior = ll - log_sum_exp(ll).
[[nodiscard]] inline double log_sum_exp(std::span<const double> x) {
  const double top = *std::max_element(x.begin(), x.end());
  double sum = 0.0;
  for (const double v : x) sum += std::exp(v - top);
  return top + std::log(sum);
}

/// Phi(z), the standard normal cumulative distribution function, 1/2 erfc(-z / sqrt 2): erfc keeps the relative
/// precision of the lower tail (Phi(-30) ~ 5e-198, not 0).
[[nodiscard]] inline double normal_cdf(double z) noexcept { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

/// The ends of log_cell_edges: half a step beyond the first and last value (a closed grid), or -inf and +inf (the
/// first and last cells reach out for ever).
enum class CellEnds { half_step, open };

/// The edges, in natural log, of the cells of a log-spaced axis `values` (ascending, > 0): the geometric midpoints
/// 0.5 (ln v_{i-1} + ln v_i) between neighbours, and the two ends by `ends` (half_step: half the neighbouring step
/// beyond the end value, or 0.5 in log for a one-value axis). values.size() + 1 edges; values holds at least one.
[[nodiscard]] inline std::vector<double> log_cell_edges(const std::vector<double>& values,
                                                        CellEnds ends = CellEnds::half_step) {
  const std::size_t n = values.size();
  std::vector<double> e(n + 1, 0.0);
  for (std::size_t i = 1; i < n; ++i) e[i] = 0.5 * (std::log(values[i - 1]) + std::log(values[i]));
  if (ends == CellEnds::open) {
    e.front() = -std::numeric_limits<double>::infinity();
    e.back() = std::numeric_limits<double>::infinity();
    return e;
  }
  e[0] = std::log(values[0]) - (n > 1 ? 0.5 * (std::log(values[1]) - std::log(values[0])) : 0.5);
  e[n] = std::log(values[n - 1]) + (n > 1 ? 0.5 * (std::log(values[n - 1]) - std::log(values[n - 2])) : 0.5);
  return e;
}

}  // namespace topple
