#pragma once
// Private to the library (not installed): construction paths of GroundMotion for code that produced the samples
// itself and knows what GroundMotion::uniform would otherwise find by reading all of them.
#include <vector>

#include "topple/motion/ground_motion.hpp"

namespace topple::detail {

struct GroundMotionFactory {
  /// GroundMotion::uniform for samples whose peak the caller computed: peak_abs_m_s2 = max_i |accel_m_s2[i]|
  /// (precondition: asserted in debug builds). The limits on the samples are checked on the peak alone, instead of
  /// in a pass over every sample; an out-of-limit or non-finite peak goes through GroundMotion::uniform and its
  /// InputError. For the decoupled flexible analysis, whose support response yields its peak as it is computed: the
  /// pass cost ~3 us of the ~48 us analysis of a 20,000-sample record (docs/performance.md).
  static GroundMotion uniform_with_peak(std::vector<double> accel_m_s2, double peak_abs_m_s2, double dt_s,
                                        double start_time_s, RecordMetadata metadata);

 private:
  friend class topple::GroundMotion;
  /// The motion from samples and a grid already checked (GroundMotion::uniform, uniform_with_peak): no checks.
  static GroundMotion assemble_uniform(std::vector<double> accel_m_s2, double dt_s, double start_time_s,
                                       RecordMetadata metadata);
};

}  // namespace topple::detail
