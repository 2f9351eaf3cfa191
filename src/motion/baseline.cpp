// Baseline removal (motion/baseline.hpp; docs/method.md, "Baseline removal").
#include "topple/motion/baseline.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {

namespace {

/// A bare number of seconds or a duration with a unit ("2", "2s", "500ms").
double parse_window_s(std::string_view text, const std::string& field) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc{} && ptr == text.data() + text.size()) return value;
  return parse_duration_s(text, field);
}

[[noreturn]] void refuse(const std::string& field, std::string_view text) {
  throw parameter_error(field, fmt::format("unknown baseline '{}' (known: none, mean, pre-event:T with T the window "
                                           "in s, poly:N with N = 0..{})",
                                           text, kMaxBaselineOrder));
}

/// Legendre polynomials P_0..P_3 at x (Abramowitz & Stegun 22.7.10: (k+1) P_{k+1} = (2k+1) x P_k - k P_{k-1}).
std::array<double, kMaxBaselineOrder + 1> legendre(double x) noexcept {
  std::array<double, kMaxBaselineOrder + 1> p{};
  p[0] = 1.0;
  p[1] = x;
  for (int k = 1; k < kMaxBaselineOrder; ++k) {
    p[k + 1] = ((2.0 * k + 1.0) * x * p[k] - k * p[k - 1]) / (k + 1.0);
  }
  return p;
}

/// Solves the k x k system g c = r (k <= 4) by Gaussian elimination with partial pivoting; g is the Gram matrix of
/// the Legendre basis, symmetric positive definite and well conditioned (see polynomial_fit).
std::vector<double> solve_small(std::vector<double> g, std::vector<double> r, std::size_t k) {
  for (std::size_t col = 0; col < k; ++col) {
    std::size_t pivot = col;
    for (std::size_t row = col + 1; row < k; ++row) {
      if (std::abs(g[row * k + col]) > std::abs(g[pivot * k + col])) pivot = row;
    }
    if (pivot != col) {
      for (std::size_t c = 0; c < k; ++c) std::swap(g[col * k + c], g[pivot * k + c]);
      std::swap(r[col], r[pivot]);
    }
    for (std::size_t row = col + 1; row < k; ++row) {
      const double f = g[row * k + col] / g[col * k + col];
      for (std::size_t c = col; c < k; ++c) g[row * k + c] -= f * g[col * k + c];
      r[row] -= f * r[col];
    }
  }
  std::vector<double> x(k, 0.0);
  for (std::size_t row = k; row-- > 0;) {
    double s = r[row];
    for (std::size_t c = row + 1; c < k; ++c) s -= g[row * k + c] * x[c];
    x[row] = s / g[row * k + row];
  }
  return x;
}

/// The least-squares polynomial of degree `order` through (t_i, y_i), evaluated at every t_i. The basis is the
/// Legendre polynomials in x = (t - t_mid) / (T / 2) in [-1, 1]: on (nearly) uniform samples they are (nearly)
/// orthogonal, the Gram matrix is close to n diag(1, 1/3, 1/5, 1/7) (condition number about 7 for degree 3), so the
/// normal equations lose no accuracy worth the name, while monomials in t would give a Hilbert-like matrix. The
/// sums are streamed (no n x 4 matrix for a 5e7-sample record), and one step of iterative refinement (the fit of
/// the residual, added) takes the solution to working accuracy.
std::vector<double> polynomial_fit(const GroundMotion& m, const std::vector<double>& y, int order) {
  const auto k = static_cast<std::size_t>(order) + 1;
  const std::size_t n = m.size();
  const double mid = 0.5 * (m.start_time_s() + m.end_time_s());
  const double half = 0.5 * m.duration_s();
  const auto x_of = [&](std::size_t i) { return (m.time_s(i) - mid) / half; };
  std::vector<double> gram(k * k, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto p = legendre(x_of(i));
    for (std::size_t r = 0; r < k; ++r) {
      for (std::size_t c = 0; c < k; ++c) gram[r * k + c] += p[r] * p[c];
    }
  }
  std::vector<double> fit(n, 0.0);
  std::vector<double> residual = y;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<double> rhs(k, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = legendre(x_of(i));
      for (std::size_t r = 0; r < k; ++r) rhs[r] += p[r] * residual[i];
    }
    const std::vector<double> coef = solve_small(gram, std::move(rhs), k);
    for (std::size_t i = 0; i < n; ++i) {
      const auto p = legendre(x_of(i));
      double v = 0.0;
      for (std::size_t r = 0; r < k; ++r) v += coef[r] * p[r];
      fit[i] += v;
      residual[i] = y[i] - fit[i];
    }
  }
  return fit;
}

/// The mean of y_0..y_{count-1}, summed with Neumaier's compensation so that a constant comes back exactly to
/// rounding however long the record.
double mean_of(std::span<const double> y, std::size_t count) {
  double sum = 0.0;
  double c = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const double t = sum + y[i];
    c += std::abs(sum) >= std::abs(y[i]) ? (sum - t) + y[i] : (y[i] - t) + sum;
    sum = t;
  }
  return (sum + c) / static_cast<double>(count);
}

}  // namespace

Baseline parse_baseline(std::string_view text, const std::string& field) {
  Baseline b;
  if (text == "none") return b;
  if (text == "mean") {
    b.method = BaselineMethod::mean;
    return b;
  }
  const std::size_t colon = text.find(':');
  if (colon == std::string_view::npos) refuse(field, text);
  const std::string_view kind = text.substr(0, colon);
  const std::string_view value = text.substr(colon + 1);
  if (kind == "pre-event") {
    b.method = BaselineMethod::pre_event;
    b.window_s = parse_window_s(value, field);
    if (!(b.window_s > 0.0) || !std::isfinite(b.window_s)) {
      throw parameter_error(field, fmt::format("the pre-event window must be positive, got '{}'", value));
    }
    return b;
  }
  if (kind == "poly") {
    int order = -1;
    const auto [ptr, ec] = std::from_chars(value.data(), value.data() + value.size(), order);
    if (value.empty() || ec != std::errc{} || ptr != value.data() + value.size() || order < 0 ||
        order > kMaxBaselineOrder) {
      throw parameter_error(field, fmt::format("the polynomial degree must be 0..{}, got '{}' (poly:N)",
                                               kMaxBaselineOrder, value));
    }
    b.method = BaselineMethod::polynomial;
    b.order = order;
    return b;
  }
  refuse(field, text);
}

std::string baseline_name(const Baseline& b) {
  switch (b.method) {
    case BaselineMethod::none: return "none";
    case BaselineMethod::mean: return "mean";
    case BaselineMethod::pre_event: return fmt::format("pre-event:{:g}", b.window_s);
    case BaselineMethod::polynomial: return fmt::format("poly:{}", b.order);
  }
  return "none";
}

std::vector<double> baseline_values(const GroundMotion& motion, const Baseline& b, const std::string& field) {
  const std::size_t n = motion.size();
  const std::span<const double> a = motion.accel_m_s2();
  switch (b.method) {
    case BaselineMethod::none: return std::vector<double>(n, 0.0);
    case BaselineMethod::mean: return std::vector<double>(n, mean_of(a, n));
    case BaselineMethod::pre_event: {
      if (!(b.window_s > 0.0) || !std::isfinite(b.window_s)) {
        throw parameter_error(field, fmt::format("the pre-event window must be positive, got {} s", b.window_s));
      }
      // A window longer than the record has no "after": nothing tells the offset from the shaking.
      if (b.window_s > motion.duration_s() * (1.0 + 1e-12)) {
        throw parameter_error(field, fmt::format("the pre-event window of {:g} s is longer than the record ({:g} s)",
                                                 b.window_s, motion.duration_s()));
      }
      // The samples at t - t0 <= T (to a relative 1e-9 of T: "2" takes the sample at 2.00 s of a 0.01 s grid).
      const double end = motion.start_time_s() + b.window_s * (1.0 + 1e-9);
      std::size_t count = 0;
      while (count < n && motion.time_s(count) <= end) ++count;
      if (count < 2) {
        throw parameter_error(field, fmt::format("the pre-event window of {:g} s holds {} sample (the time step is "
                                                 "{:g} s): give a longer window",
                                                 b.window_s, count, motion.dt_s()));
      }
      return std::vector<double>(n, mean_of(a, count));
    }
    case BaselineMethod::polynomial: {
      if (b.order < 0 || b.order > kMaxBaselineOrder) {
        throw parameter_error(field, fmt::format("the polynomial degree must be 0..{}, got {}", kMaxBaselineOrder,
                                                 b.order));
      }
      if (n < static_cast<std::size_t>(b.order) + 1 || !(motion.duration_s() > 0.0)) {
        throw parameter_error(field, fmt::format("a polynomial of degree {} needs at least {} samples at distinct "
                                                 "times; the record has {}",
                                                 b.order, b.order + 1, n));
      }
      return polynomial_fit(motion, std::vector<double>(a.begin(), a.end()), b.order);
    }
  }
  return std::vector<double>(n, 0.0);
}

GroundMotion remove_baseline(const GroundMotion& motion, const Baseline& b, const std::string& field) {
  if (b.method == BaselineMethod::none) return motion;
  const std::vector<double> base = baseline_values(motion, b, field);
  const std::span<const double> a = motion.accel_m_s2();
  std::vector<double> out(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = a[i] - base[i];
  if (motion.is_uniform()) {
    return GroundMotion::uniform(std::move(out), motion.dt_s(), motion.start_time_s(), motion.metadata());
  }
  return GroundMotion::irregular(motion.times_s(), std::move(out), motion.metadata());
}

}  // namespace topple
