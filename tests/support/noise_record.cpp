// See noise_record.hpp.
#include "support/noise_record.hpp"

#include <cmath>
#include <vector>

#include "topple/synthesis.hpp"
#include "topple/units.hpp"

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

}  // namespace topple::test
