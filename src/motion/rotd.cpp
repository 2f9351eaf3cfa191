// RotD50 / RotD100 (Boore 2010). See rotd.hpp for the definitions and the linearity used for the oscillators.
#include "topple/motion/rotd.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <utility>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

constexpr std::size_t kAngles = 180;

/// cos x and sin x for 0 <= x <= pi/4 by their Taylor series (terms to x^20 / 20! and x^21 / 21!; the first omitted, (pi/4)^22 / 22!, is 4e-24), in +, -, *
/// and / only. With rotd.cpp compiled with -ffp-contract=off this table is the same bits on every IEEE 754 machine
/// (a libm's cos is not), which keeps synthesis' RotD50 scaling of a pair portable (synthesis.hpp).
std::pair<double, double> cos_sin_small(double x) {
  const double x2 = x * x;
  double c = 0.0;
  double s = 0.0;
  for (int n = 10; n >= 1; --n) {  // Horner: cos = 1 - x2/(1*2) (1 - x2/(3*4) (...)), sin = x (1 - x2/(2*3) (...))
    c = 1.0 - x2 / static_cast<double>((2 * n - 1) * (2 * n)) * c;
    s = 1.0 - x2 / static_cast<double>((2 * n) * (2 * n + 1)) * s;
  }
  return {c, x * s};
}

/// cos and sin of theta = 0..179 deg, exact at 0 and 90 deg, by symmetry from [0, 45] deg.
struct AngleTable {
  std::array<double, kAngles> c{};
  std::array<double, kAngles> s{};
  AngleTable() {
    std::array<std::pair<double, double>, 46> base{};
    for (int k = 0; k <= 45; ++k) base[k] = cos_sin_small(static_cast<double>(k) * (kPi / 180.0));
    for (int k = 0; k < static_cast<int>(kAngles); ++k) {
      const int m = k <= 90 ? k : 180 - k;  // cos(180 - m) = -cos m, sin(180 - m) = sin m
      const double sign = k <= 90 ? 1.0 : -1.0;
      const auto [cm, sm] = m <= 45 ? base[m] : std::pair{base[90 - m].second, base[90 - m].first};
      c[k] = sign * cm;
      s[k] = sm;
    }
    c[90] = 0.0;
    s[90] = 1.0;
    c[0] = 1.0;
    s[0] = 0.0;
  }
};

/// max_i |c_k y1_i + s_k y2_i| for every angle k (eq. R1's Y(theta) for a peak measure).
std::vector<double> peaks_by_angle(std::span<const double> y1, std::span<const double> y2, const AngleTable& t) {
  assert(y1.size() == y2.size());
  std::array<double, kAngles> peak{};
  for (std::size_t i = 0; i < y1.size(); ++i) {
    const double a = y1[i];
    const double b = y2[i];
    for (std::size_t k = 0; k < kAngles; ++k) peak[k] = std::max(peak[k], std::abs(t.c[k] * a + t.s[k] * b));
  }
  return {peak.begin(), peak.end()};
}

}  // namespace

std::vector<double> rotd_peaks_by_angle(std::span<const double> y1, std::span<const double> y2) {
  if (y1.size() != y2.size()) {
    throw parameter_error("second", fmt::format("the two series must be on one grid: {} and {} samples", y1.size(),
                                                y2.size()));
  }
  return peaks_by_angle(y1, y2, AngleTable{});
}

std::vector<double> rotd_angles_deg() {
  std::vector<double> a(kAngles);
  for (std::size_t k = 0; k < kAngles; ++k) a[k] = static_cast<double>(k);
  return a;
}

RotDValue rotd_of(std::span<const double> value_by_angle) {
  if (value_by_angle.size() != kAngles) {
    throw parameter_error("values", fmt::format("RotD needs one value per angle 0..179 deg ({}), got {}", kAngles,
                                                value_by_angle.size()));
  }
  RotDValue r;
  const auto max_it = std::max_element(value_by_angle.begin(), value_by_angle.end());
  r.rotd100 = *max_it;
  r.rotd100_angle_deg = static_cast<double>(max_it - value_by_angle.begin());
  std::vector<double> sorted(value_by_angle.begin(), value_by_angle.end());
  std::sort(sorted.begin(), sorted.end());
  // 50th percentile, linear interpolation: position 0.5 (n - 1) = 89.5.
  r.rotd50 = 0.5 * (sorted[kAngles / 2 - 1] + sorted[kAngles / 2]);
  return r;
}

std::optional<double> rotd_azimuth_deg(const MotionSet& set, double angle_deg) {
  if (!set.azimuths()) return std::nullopt;
  const ComponentAzimuths& az = *set.azimuths();
  const double a = az.first_deg + az.handedness() * angle_deg;
  return std::fmod(std::fmod(a, 180.0) + 180.0, 180.0);
}

RotDMeasures rotd_measures(const MotionSet& set, std::span<const double> period_s, double damping) {
  const GroundMotion& h1 = set.first();
  const GroundMotion& h2 = set.second();  // throws when absent
  const AngleTable table;
  RotDMeasures m;
  m.damping = damping;
  m.period_s.assign(period_s.begin(), period_s.end());
  m.pga_by_angle_m_s2 = peaks_by_angle(h1.accel_m_s2(), h2.accel_m_s2(), table);
  m.pga_m_s2 = rotd_of(m.pga_by_angle_m_s2);
  for (double t : period_s) {
    // Both components' oscillators once; the rotated responses by linearity (rotd.hpp).
    const OscillatorHistory x1 = oscillator_response(h1, t, damping);
    const OscillatorHistory x2 = oscillator_response(h2, t, damping);
    const double w2 = (2.0 * kPi / t) * (2.0 * kPi / t);
    std::vector<double> psa = peaks_by_angle(x1.displacement_m, x2.displacement_m, table);
    for (double& v : psa) v *= w2;
    m.psa_m_s2.push_back(rotd_of(psa));
    m.psa_by_angle_m_s2.push_back(std::move(psa));
  }
  return m;
}

std::vector<double> rotd_periods_s() { return {0.1, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0}; }

}  // namespace topple
