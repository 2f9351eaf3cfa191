#include "topple/motion/ground_motion.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "motion/ground_motion_detail.hpp"

namespace topple {
namespace {

void require_finite_samples(const std::vector<double>& values, const char* field) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      throw parameter_error(field, fmt::format("sample {} is not finite ({})", i, values[i]));
    }
  }
}

using Limits = GroundMotionLimits;

/// |a| within the acceleration limit, for the samples of a record (field "accel") or a scaled one ("scale").
void require_accel_within_limit(const std::vector<double>& values, const char* field, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (std::abs(values[i]) > Limits::max_abs_accel_m_s2) {
      throw parameter_error(field, fmt::format("{} {} is {:.6g} m/s2 ({:.6g} g), beyond the limit of {:.6g} m/s2 "
                                               "of a ground motion",
                                               what, i, values[i], values[i] / kStandardGravity, Limits::max_abs_accel_m_s2));
    }
  }
}

/// Both checks above on accelerations, in one branch-free pass when every sample passes (|a| <= limit is false for NaN
/// and inf too); on a failure the two checks run in their order, so the error is the one they give.
/// Pairs of samples at once (GCC/Clang vector extension, SSE2 on x86-64): GCC does not vectorise the scalar form (the
/// comparison may trap), and the scalar pass cost as much as a flexible support's whole response.
void require_finite_accel_within_limit(const std::vector<double>& values, const char* field, const char* what) {
  using V2 = double __attribute__((vector_size(16)));
  using M2 = std::int64_t __attribute__((vector_size(16)));
  constexpr double kLimit = Limits::max_abs_accel_m_s2;
  const V2 limit = {kLimit, kLimit};
  const M2 magnitude = {INT64_MAX, INT64_MAX};  // every bit but the sign
  M2 all = {-1, -1};  // lanes stay all-ones while every |a| <= limit (false for NaN and inf)
  M2 all2 = all;       // a second accumulator: two independent chains
  std::size_t i = 0;
  for (; i + 4 <= values.size(); i += 4) {
    V2 v;
    V2 w;
    std::memcpy(&v, values.data() + i, sizeof v);
    std::memcpy(&w, values.data() + i + 2, sizeof w);
    all &= reinterpret_cast<V2>(reinterpret_cast<M2>(v) & magnitude) <= limit;
    all2 &= reinterpret_cast<V2>(reinterpret_cast<M2>(w) & magnitude) <= limit;
  }
  all &= all2;
  bool ok = all[0] != 0 && all[1] != 0;
  for (; i < values.size(); ++i) ok &= std::abs(values[i]) <= kLimit;
  if (ok) return;
  require_finite_samples(values, field);
  require_accel_within_limit(values, field, what);
}

void require_sample_count(std::size_t n, const char* field) {
  if (n > Limits::max_samples) {
    throw parameter_error(field, fmt::format("{} samples, more than the limit of {} samples of a ground motion", n,
                                             Limits::max_samples));
  }
}

void require_duration(double duration_s, double start_s, const char* field) {
  if (!(duration_s <= Limits::max_duration_s)) {
    throw parameter_error(field, fmt::format("the record lasts {:.6g} s, more than the limit of {:.6g} s (6 h) of a "
                                             "ground motion",
                                             duration_s, Limits::max_duration_s));
  }
  if (!(std::abs(start_s) <= Limits::max_abs_start_time_s)) {
    throw parameter_error(field, fmt::format("the record starts at {:.6g} s, beyond the limit of +-{:.6g} s (1 day); "
                                             "shift its times",
                                             start_s, Limits::max_abs_start_time_s));
  }
}

void require_uniform_dt(double dt_s, const char* field) {
  if (!(dt_s >= Limits::min_dt_s && dt_s <= Limits::max_dt_s)) {
    throw parameter_error(field, fmt::format("time step {:.6g} s is outside the limits [{:.6g}, {:.6g}] s of a ground "
                                             "motion",
                                             dt_s, Limits::min_dt_s, Limits::max_dt_s));
  }
}

/// Solves the small dense system A x = b (Gaussian elimination with partial pivoting); A is n x n row-major.
std::vector<double> solve_dense(std::vector<double> a, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t col = 0; col < n; ++col) {
    std::size_t pivot = col;
    for (std::size_t r = col + 1; r < n; ++r) {
      if (std::abs(a[r * n + col]) > std::abs(a[pivot * n + col])) pivot = r;
    }
    for (std::size_t c = 0; c < n; ++c) std::swap(a[col * n + c], a[pivot * n + c]);
    std::swap(b[col], b[pivot]);
    const double diag = a[col * n + col];
    for (std::size_t r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / diag;
      for (std::size_t c = col; c < n; ++c) a[r * n + c] -= f * a[col * n + c];
      b[r] -= f * b[col];
    }
  }
  std::vector<double> x(n);
  for (std::size_t i = n; i-- > 0;) {
    double s = b[i];
    for (std::size_t c = i + 1; c < n; ++c) s -= a[i * n + c] * x[c];
    x[i] = s / a[i * n + i];
  }
  return x;
}

}  // namespace

namespace {

/// "12.3 m/s2 (1.25 g)", or what an overflowed product means.
std::string describe_accel(double a_m_s2) {
  if (!std::isfinite(a_m_s2)) return "beyond the range of double precision";
  return fmt::format("{:.6g} m/s2 ({:.6g} g)", a_m_s2, a_m_s2 / kStandardGravity);
}

}  // namespace

void require_record_acceleration(double pga_m_s2, const std::string& field) {
  if (!(pga_m_s2 <= Limits::max_record_accel_m_s2)) {
    throw parameter_error(field, fmt::format("the PGA would be {}, beyond the limit of {:.6g} m/s2 (100 g) of a record",
                                             describe_accel(pga_m_s2), Limits::max_record_accel_m_s2));
  }
}

namespace {

/// GroundMotion::uniform's checks that do not read the samples: their number, the step, the start and the duration.
void require_uniform_grid(std::size_t samples, double dt_s, double start_time_s) {
  if (samples == 0) throw parameter_error("accel", "a ground motion needs at least one sample");
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw parameter_error("dt_s", fmt::format("time step must be positive and finite, got {}", dt_s));
  }
  if (!std::isfinite(start_time_s)) throw parameter_error("start_time_s", "start time must be finite");
  require_uniform_dt(dt_s, "dt_s");
  require_sample_count(samples, "accel");
  require_duration(dt_s * static_cast<double>(samples - 1), start_time_s, "dt_s");
}

}  // namespace

GroundMotion GroundMotion::uniform(std::vector<double> accel_m_s2, double dt_s, double start_time_s,
                                   RecordMetadata metadata) {
  require_uniform_grid(accel_m_s2.size(), dt_s, start_time_s);
  require_finite_accel_within_limit(accel_m_s2, "accel", "sample");
  return detail::GroundMotionFactory::assemble_uniform(std::move(accel_m_s2), dt_s, start_time_s, std::move(metadata));
}

GroundMotion detail::GroundMotionFactory::assemble_uniform(std::vector<double> accel_m_s2, double dt_s,
                                                           double start_time_s, RecordMetadata metadata) {
  GroundMotion m;
  m.accel_ = std::move(accel_m_s2);
  m.dt_ = dt_s;
  m.t0_ = start_time_s;
  m.meta_ = std::move(metadata);
  return m;
}

GroundMotion detail::GroundMotionFactory::uniform_with_peak(std::vector<double> accel_m_s2, double peak_abs_m_s2,
                                                           double dt_s, double start_time_s, RecordMetadata metadata) {
  // max |a_i| = peak (the caller's precondition) and peak <= limit together say what the per-sample pass checks:
  // every |a_i| <= limit, hence finite. Otherwise the full construction, which throws with the sample it refuses.
  if (!(peak_abs_m_s2 <= Limits::max_abs_accel_m_s2)) {
    return GroundMotion::uniform(std::move(accel_m_s2), dt_s, start_time_s, std::move(metadata));
  }
  require_uniform_grid(accel_m_s2.size(), dt_s, start_time_s);
  assert(std::all_of(accel_m_s2.begin(), accel_m_s2.end(), [&](double a) { return std::abs(a) <= peak_abs_m_s2; }));
  return assemble_uniform(std::move(accel_m_s2), dt_s, start_time_s, std::move(metadata));
}

GroundMotion GroundMotion::irregular(std::vector<double> time_s, std::vector<double> accel_m_s2,
                                     RecordMetadata metadata) {
  if (time_s.size() != accel_m_s2.size()) {
    throw parameter_error("time", fmt::format("{} times but {} accelerations", time_s.size(), accel_m_s2.size()));
  }
  if (time_s.size() < 2) throw parameter_error("time", "an irregular record needs at least two samples");
  require_sample_count(time_s.size(), "time");
  require_finite_samples(time_s, "time");
  require_finite_samples(accel_m_s2, "accel");
  require_accel_within_limit(accel_m_s2, "accel", "sample");
  for (std::size_t i = 1; i < time_s.size(); ++i) {
    if (time_s[i] < time_s[i - 1]) {
      throw parameter_error("time", fmt::format("times decrease at sample {} ({} after {})", i, time_s[i],
                                                time_s[i - 1]));
    }
    if (time_s[i] > time_s[i - 1] && time_s[i] - time_s[i - 1] < Limits::min_dt_s) {
      throw parameter_error("time", fmt::format("samples {} and {} are {:.6g} s apart, closer than the limit of {:.6g} "
                                                "s (equal times, a jump, are allowed)",
                                                i - 1, i, time_s[i] - time_s[i - 1], Limits::min_dt_s));
    }
  }
  if (!(time_s.back() > time_s.front())) throw parameter_error("time", "the record has zero duration");
  require_duration(time_s.back() - time_s.front(), time_s.front(), "time");
  GroundMotion m;
  m.t0_ = time_s.front();
  m.dt_ = (time_s.back() - time_s.front()) / static_cast<double>(time_s.size() - 1);
  m.accel_ = std::move(accel_m_s2);
  m.time_ = std::move(time_s);
  m.meta_ = std::move(metadata);
  return m;
}

std::vector<double> GroundMotion::times_s() const {
  if (!time_.empty()) return time_;
  std::vector<double> t(size());
  for (std::size_t i = 0; i < t.size(); ++i) t[i] = time_s(i);
  return t;
}

double GroundMotion::accel_at(double t) const noexcept {
  const std::size_t n = size();
  if (n == 0 || t < t0_ || t > end_time_s()) return 0.0;
  std::size_t hi = 0;
  if (time_.empty()) {
    const double x = (t - t0_) / dt_;
    const auto lo = std::min(static_cast<std::size_t>(x), n - 1);
    if (lo + 1 >= n) return accel_[n - 1];
    const double f = x - static_cast<double>(lo);
    return accel_[lo] + f * (accel_[lo + 1] - accel_[lo]);
  }
  // first sample strictly after t: at a jump this picks the value after it
  hi = static_cast<std::size_t>(std::upper_bound(time_.begin(), time_.end(), t) - time_.begin());
  if (hi >= n) return accel_[n - 1];
  const std::size_t lo = hi - 1;
  const double span = time_[hi] - time_[lo];
  const double f = span > 0.0 ? (t - time_[lo]) / span : 1.0;
  return accel_[lo] + f * (accel_[hi] - accel_[lo]);
}

double GroundMotion::pga_m_s2() const noexcept {
  double peak = 0.0;
  for (double a : accel_) peak = std::max(peak, std::abs(a));
  return peak;
}

double GroundMotion::pga_time_s() const noexcept {
  double peak = -1.0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < accel_.size(); ++i) {
    if (std::abs(accel_[i]) > peak) {
      peak = std::abs(accel_[i]);
      at = i;
    }
  }
  return time_s(at);
}

GroundMotion GroundMotion::scaled(double factor) const {
  if (!std::isfinite(factor)) throw parameter_error("scale", fmt::format("scale factor must be finite, got {}", factor));
  // Checked before multiplying: 1e308 x a record would overflow to inf.
  if (std::abs(factor) * pga_m_s2() > Limits::max_abs_accel_m_s2) {
    throw parameter_error("scale", fmt::format("scale factor {:.6g} makes the PGA {}, beyond the limit of {:.6g} m/s2 "
                                               "of a ground motion",
                                               factor, describe_accel(std::abs(factor) * pga_m_s2()),
                                               Limits::max_abs_accel_m_s2));
  }
  GroundMotion m = *this;
  for (double& a : m.accel_) a *= factor;
  return m;
}

GroundMotion GroundMotion::scaled_to_pga(double pga_m_s2) const {
  if (!(pga_m_s2 > 0.0) || !std::isfinite(pga_m_s2)) {
    throw parameter_error("pga", fmt::format("target PGA must be positive and finite, got {} m/s^2", pga_m_s2));
  }
  const double peak = this->pga_m_s2();
  if (peak == 0.0) throw parameter_error("pga", "cannot scale a record that is zero everywhere to a PGA");
  return scaled(pga_m_s2 / peak);
}

GroundMotion GroundMotion::time_scaled(double factor) const {
  if (!(factor > 0.0) || !std::isfinite(factor)) {
    throw parameter_error("time_scale", fmt::format("time scale factor must be positive and finite, got {}", factor));
  }
  if (is_uniform()) {
    return uniform(accel_, dt_ * factor, t0_, meta_);  // checks the new dt and duration
  }
  std::vector<double> t = time_;
  for (double& ti : t) ti = t0_ + factor * (ti - t0_);
  return irregular(std::move(t), accel_, meta_);
}

GroundMotion GroundMotion::trimmed(double t_begin, double t_end) const {
  if (!(t_end > t_begin) || !std::isfinite(t_begin) || !std::isfinite(t_end)) {
    throw parameter_error("trim", fmt::format("trim window [{}, {}] s is empty or not finite", t_begin, t_end));
  }
  const double lo = std::max(t_begin, t0_);
  const double hi = std::min(t_end, end_time_s());
  if (!(hi > lo)) {
    throw parameter_error("trim", fmt::format("trim window [{}, {}] s lies outside the record [{}, {}] s", t_begin,
                                              t_end, t0_, end_time_s()));
  }
  std::vector<double> t{lo};
  std::vector<double> a{accel_at(lo)};
  for (std::size_t i = 0; i < size(); ++i) {
    const double ti = time_s(i);
    if (ti > lo && ti < hi) {
      t.push_back(ti);
      a.push_back(accel_[i]);
    }
  }
  t.push_back(hi);
  a.push_back(accel_at(hi));
  if (is_uniform()) {
    // Keep the uniform grid when the window falls on samples; otherwise the result is irregular by nature.
    const double first = (lo - t0_) / dt_;
    const double last = (hi - t0_) / dt_;
    if (std::abs(first - std::round(first)) < 1e-9 && std::abs(last - std::round(last)) < 1e-9) {
      const auto i0 = static_cast<std::size_t>(std::llround(first));
      const auto i1 = static_cast<std::size_t>(std::llround(last));
      std::vector<double> part(accel_.begin() + static_cast<std::ptrdiff_t>(i0),
                               accel_.begin() + static_cast<std::ptrdiff_t>(i1) + 1);
      return uniform(std::move(part), dt_, time_s(i0), meta_);
    }
  }
  return irregular(std::move(t), std::move(a), meta_);
}

GroundMotion GroundMotion::resampled(double dt_s) const {
  if (!(dt_s > 0.0) || !std::isfinite(dt_s)) {
    throw parameter_error("dt_s", fmt::format("resampling step must be positive and finite, got {}", dt_s));
  }
  require_uniform_dt(dt_s, "dt_s");
  const double steps = std::floor(duration_s() / dt_s * (1.0 + 1e-12));
  if (!(steps < static_cast<double>(Limits::max_samples))) {
    throw parameter_error("dt_s", fmt::format("resampling {:.6g} s at {:.6g} s gives {:.6g} samples, more than the "
                                              "limit of {} samples of a ground motion",
                                              duration_s(), dt_s, steps + 1.0, Limits::max_samples));
  }
  const auto n = static_cast<std::size_t>(steps) + 1;
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = accel_at(t0_ + static_cast<double>(i) * dt_s);
  return uniform(std::move(a), dt_s, t0_, meta_);
}

GroundMotion GroundMotion::baseline_corrected(int order) const {
  if (order < 0 || order > 6) {
    throw parameter_error("baseline_order", fmt::format("polynomial order must be 0..6, got {}", order));
  }
  const auto k = static_cast<std::size_t>(order) + 1;
  // Least squares in the scaled time x in [-1, 1], which keeps the normal equations well conditioned.
  const double mid = 0.5 * (t0_ + end_time_s());
  const double half = std::max(0.5 * duration_s(), 1e-300);
  std::vector<double> gram(k * k, 0.0);
  std::vector<double> rhs(k, 0.0);
  std::array<double, 13> powers{};
  for (std::size_t i = 0; i < size(); ++i) {
    const double x = (time_s(i) - mid) / half;
    powers[0] = 1.0;
    for (std::size_t p = 1; p < 2 * k - 1; ++p) powers[p] = powers[p - 1] * x;
    for (std::size_t r = 0; r < k; ++r) {
      rhs[r] += powers[r] * accel_[i];
      for (std::size_t c = 0; c < k; ++c) gram[r * k + c] += powers[r + c];
    }
  }
  if (size() < k) throw parameter_error("baseline_order", "record has fewer samples than polynomial coefficients");
  const std::vector<double> coef = solve_dense(std::move(gram), std::move(rhs));
  GroundMotion m = *this;
  for (std::size_t i = 0; i < size(); ++i) {
    const double x = (time_s(i) - mid) / half;
    double poly = 0.0;
    for (std::size_t p = k; p-- > 0;) poly = poly * x + coef[p];
    m.accel_[i] -= poly;
  }
  return m;
}

GroundMotion GroundMotion::to_uniform() const {
  if (is_uniform()) return *this;
  double smallest = duration_s();
  for (std::size_t i = 1; i < time_.size(); ++i) {
    const double step = time_[i] - time_[i - 1];
    if (step > 0.0) smallest = std::min(smallest, step);
  }
  return resampled(smallest);
}

double amplitude_factor(const GroundMotion& original, const GroundMotion& transformed) noexcept {
  const double before = original.pga_m_s2();
  return before > 0.0 ? std::abs(transformed.pga_m_s2() / before) : 1.0;
}

}  // namespace topple
