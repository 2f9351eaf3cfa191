#pragma once
// The tests' and benchmarks' broadband record: resonator-filtered white noise under a rise-and-decay envelope, on the
// library's portable generator (PortableRandom, synthesis.hpp), so that every machine draws the same samples. It is a
// fixture, not a model of ground motion (topple::synthesize is that): a cheap, reproducible, non-stationary input.
//
//   w_i       unit normal deviates of PortableRandom(seed)
//   y_i     = 2 r cos(2 pi f dt) y_{i-1} - r^2 y_{i-2} + w_i     (a resonance at f Hz, pole radius r < 1)
//   a_i     = y_i (t_i / t_p) exp(1 - t_i / t_p), t_i = i dt     (peak of the envelope at t_p; none when t_p = 0)
// then scaled so that max |a| = pga.
#include <cstddef>
#include <cstdint>

#include "topple/motion/ground_motion.hpp"

namespace topple::test {

struct NoiseRecordSpec {
  std::uint64_t seed = 1;
  std::size_t samples = 4000;
  double dt_s = 0.01;
  double pga_m_s2 = 0.0;          ///< required, > 0
  double resonance_hz = 2.5;      ///< f
  double pole_radius = 0.97;      ///< r: 0.97 gives a bandwidth of about 0.01 / (pi dt) Hz
  double envelope_peak_s = 0.0;   ///< t_p; 0: no envelope (stationary noise)
};

[[nodiscard]] GroundMotion noise_record(const NoiseRecordSpec& spec);

/// A uniform record linearly interpolated at dt / `upsample` (the same piecewise-linear function) with `pad_s` seconds
/// of zeros appended: what the peer tests give pyrotd (frequency domain, circular response) and topple alike.
[[nodiscard]] GroundMotion upsampled_padded(const GroundMotion& record, int upsample, double pad_s);

}  // namespace topple::test
