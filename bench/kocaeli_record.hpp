#pragma once
// The benchmarks' record: the first n samples (dt = 0.005 s) of Kocaeli 1999 ATS-090 from ../shared/records/slammer
// (PGA 0.185 g), the record of bench_sliding; without ../shared, a seeded synthetic motion of the same length, step
// and PGA at the given predominant frequency (so the benchmark still runs, with figures that are not comparable).
#include <filesystem>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace topple::bench {

inline GroundMotion kocaeli_record(std::size_t n, double fallback_frequency_hz) {
  const std::filesystem::path path =
      std::filesystem::path(TOPPLE_SHARED_DIR) / "records" / "slammer" / "Kocaeli_1999_ATS-090.csv";
  if (std::filesystem::exists(path)) {
    const GroundMotion full = io::read_motion(path);
    std::vector<double> a(full.accel_m_s2().begin(), full.accel_m_s2().begin() + static_cast<std::ptrdiff_t>(n));
    return GroundMotion::uniform(std::move(a), full.dt_s());
  }
  SynthesisSpec s;
  s.pga_m_s2 = 0.185 * kStandardGravity;
  s.predominant_frequency_hz = fallback_frequency_hz;
  s.duration_s = 0.005 * static_cast<double>(n - 1);
  s.dt_s = 0.005;
  s.seed = 42;
  return synthesize(s);
}

/// The 20,000-sample record (100 s) that bench_sliding and bench_rocking time, loaded once per process.
inline const GroundMotion& kocaeli_20000() {
  static const GroundMotion r = kocaeli_record(20000, 4.0);
  return r;
}

/// The second horizontal component that bench_sliding2d and accuracy_sliding2d pair with kocaeli_20000(): a seeded
/// synthetic motion of the same length, step and PGA (3 Hz, seed 7), loaded once per process.
inline const GroundMotion& kocaeli_partner_20000() {
  static const GroundMotion r = [] {
    SynthesisSpec s;
    s.pga_m_s2 = kocaeli_20000().pga_m_s2();
    s.predominant_frequency_hz = 3.0;
    s.dt_s = kocaeli_20000().dt_s();
    s.duration_s = kocaeli_20000().duration_s();
    s.seed = 7;
    return synthesize(s);
  }();
  return r;
}

}  // namespace topple::bench
