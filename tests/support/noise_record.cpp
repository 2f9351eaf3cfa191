// See noise_record.hpp.
#include "support/noise_record.hpp"

#include <cmath>
#include <vector>

#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace topple::test {

GroundMotion noise_record(const NoiseRecordSpec& spec) {
  PortableRandom rng(spec.seed);
  std::vector<double> a(spec.samples);
  const double w = 2.0 * kPi * spec.resonance_hz * spec.dt_s;
  const double c1 = 2.0 * spec.pole_radius * std::cos(w);
  const double c2 = spec.pole_radius * spec.pole_radius;
  double y1 = 0.0;
  double y2 = 0.0;
  for (std::size_t i = 0; i < spec.samples; ++i) {
    const double y = c1 * y1 - c2 * y2 + rng.normal();
    y2 = y1;
    y1 = y;
    const double t = static_cast<double>(i) * spec.dt_s;
    const double tp = spec.envelope_peak_s;
    a[i] = tp > 0.0 ? y * (t / tp) * portable_exp(1.0 - t / tp) : y;  // IEEE-portable, as the generator
  }
  return GroundMotion::uniform(std::move(a), spec.dt_s).scaled_to_pga(spec.pga_m_s2);
}

GroundMotion upsampled_padded(const GroundMotion& record, int upsample, double pad_s) {
  std::vector<double> f;
  const auto a = record.accel_m_s2();
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    for (int k = 0; k < upsample; ++k) f.push_back(a[i] + (a[i + 1] - a[i]) * k / static_cast<double>(upsample));
  }
  f.push_back(a.back());
  const double dt = record.dt_s() / upsample;
  f.resize(f.size() + static_cast<std::size_t>(std::lround(pad_s / dt)), 0.0);
  return GroundMotion::uniform(std::move(f), dt);
}

}  // namespace topple::test
