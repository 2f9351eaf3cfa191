#include "topple/motion/intensity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/spectra.hpp"

namespace topple {

GroundVelocityDisplacement integrate_ground(const GroundMotion& motion) {
  const auto a = motion.accel_m_s2();
  const std::size_t n = a.size();
  GroundVelocityDisplacement out;
  out.velocity_m_s.assign(n, 0.0);
  out.displacement_m.assign(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    const double v0 = out.velocity_m_s[i - 1];
    out.velocity_m_s[i] = v0 + 0.5 * h * (a[i - 1] + a[i]);
    out.displacement_m[i] = out.displacement_m[i - 1] + v0 * h + h * h * (2.0 * a[i - 1] + a[i]) / 6.0;
  }
  return out;
}

BasicIntensity basic_intensity(const GroundMotion& motion, double g_m_s2) {
  BasicIntensity im;
  im.pga_m_s2 = motion.pga_m_s2();
  im.pga_time_s = motion.pga_time_s();
  const auto vd = integrate_ground(motion);
  for (double v : vd.velocity_m_s) im.pgv_m_s = std::max(im.pgv_m_s, std::abs(v));
  for (double d : vd.displacement_m) im.pgd_m = std::max(im.pgd_m, std::abs(d));
  const auto a = motion.accel_m_s2();
  double integral = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    integral += h * (a[i - 1] * a[i - 1] + a[i - 1] * a[i] + a[i] * a[i]) / 3.0;
  }
  im.arias_m_s = kPi / (2.0 * g_m_s2) * integral;
  return im;
}

}  // namespace topple

// ---- Durations and cumulative measures ----
namespace topple {
namespace {

/// integral_0^s (a0 + (a1 - a0) sigma / h)^2 d sigma.
double step_energy(double a0, double a1, double h, double s) {
  const double d = a1 - a0;
  return s * (a0 * a0 + s * (a0 * d / h + s * d * d / (3.0 * h * h)));
}

/// Cumulative integral of a^2 at each sample (exact per step).
std::vector<double> cumulative_energy(const GroundMotion& motion) {
  const auto a = motion.accel_m_s2();
  std::vector<double> c(a.size(), 0.0);
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    c[i] = c[i - 1] + h * (a[i - 1] * a[i - 1] + a[i - 1] * a[i] + a[i] * a[i]) / 3.0;
  }
  return c;
}

/// First time at which the cumulative energy reaches `target` (0 < target <= total).
double energy_crossing_time(const GroundMotion& motion, const std::vector<double>& c, double target) {
  const auto a = motion.accel_m_s2();
  const auto it = std::lower_bound(c.begin(), c.end(), target);
  const auto i = static_cast<std::size_t>(it - c.begin());
  if (i == 0) return motion.time_s(0);
  if (i >= c.size()) return motion.end_time_s();
  const double t0 = motion.time_s(i - 1);
  const double h = motion.time_s(i) - t0;
  if (!(h > 0.0)) return t0;
  const double a0 = a[i - 1];
  const double a1 = a[i];
  const double goal = target - c[i - 1];
  // Safeguarded Newton on the monotone cubic F(s) = step_energy(s) - goal over [0, h].
  double lo = 0.0;
  double hi = h;
  double s = 0.5 * h;
  constexpr int kMaxIterations = 200;
  for (int it_count = 0; it_count < kMaxIterations; ++it_count) {
    const double f = step_energy(a0, a1, h, s) - goal;
    if (f == 0.0) break;
    if (f < 0.0) lo = s;
    else hi = s;
    const double slope = (a0 + (a1 - a0) * s / h) * (a0 + (a1 - a0) * s / h);
    double next = slope > 0.0 ? s - f / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - s) <= 4.0 * std::numeric_limits<double>::epsilon() * h || hi - lo <= 1e-15 * h) {
      s = next;
      break;
    }
    s = next;
  }
  return t0 + s;
}

}  // namespace

std::vector<double> husid(const GroundMotion& motion) {
  std::vector<double> c = cumulative_energy(motion);
  const double total = c.back();
  if (!(total > 0.0)) throw parameter_error("motion", "the record is identically zero: no Husid plot");
  for (double& x : c) x /= total;
  return c;
}

SignificantDuration significant_duration(const GroundMotion& motion, double low, double high) {
  if (!(low >= 0.0 && low < high && high <= 1.0)) {
    throw parameter_error("significant duration", fmt::format("need 0 <= low < high <= 1, got {} and {}", low, high));
  }
  const std::vector<double> c = cumulative_energy(motion);
  const double total = c.back();
  if (!(total > 0.0)) throw parameter_error("motion", "the record is identically zero: no significant duration");
  SignificantDuration d;
  d.start_s = low == 0.0 ? motion.start_time_s() : energy_crossing_time(motion, c, low * total);
  d.end_s = energy_crossing_time(motion, c, high * total);
  d.duration_s = d.end_s - d.start_s;
  return d;
}

double cumulative_absolute_velocity_m_s(const GroundMotion& motion) {
  const auto a = motion.accel_m_s2();
  double cav = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const double h = motion.time_s(i) - motion.time_s(i - 1);
    const double p = std::abs(a[i - 1]);
    const double q = std::abs(a[i]);
    if (a[i - 1] * a[i] >= 0.0) {
      cav += 0.5 * h * (p + q);
    } else {
      cav += 0.5 * h * (p * p + q * q) / (p + q);  // two triangles meeting at the zero crossing
    }
  }
  return cav;
}

namespace {

/// The measure, or the reason the record does not define it (the library's InputError text).
template <class F>
OptionalMeasure optional_measure(F f) {
  try {
    return {f(), {}};
  } catch (const InputError& e) {
    return {std::nullopt, e.problem()};
  }
}

}  // namespace

IntensityMeasures intensity_measures(const GroundMotion& motion, double g_m_s2) {
  IntensityMeasures m;
  m.basic = basic_intensity(motion, g_m_s2);
  try {
    m.d5_95 = significant_duration(motion);
  } catch (const InputError&) {
    m.d5_95.reset();  // identically zero record
  }
  m.cav_m_s = cumulative_absolute_velocity_m_s(motion);
  m.tp_s = optional_measure([&] { return predominant_period_s(motion); });
  m.tm_s = optional_measure([&] { return mean_period_s(motion); });
  m.predominant_frequency_hz = optional_measure([&] { return predominant_frequency_hz(motion); });
  return m;
}

}  // namespace topple
