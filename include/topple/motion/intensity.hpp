#pragma once
// Intensity measures of a ground motion.
//
// All integrals treat the acceleration as piecewise linear between samples (the same model the solvers use), so
// velocity is the trapezoid rule, displacement is exact for that model (cubic in each step), and the Arias integral
// of a^2 is exact per step: h (a0^2 + a0 a1 + a1^2) / 3. No baseline correction is applied here: a record's own
// processing is respected, and GroundMotion::baseline_corrected is there when a user wants one.
//
// Durations and cumulative measures, same model:
// - Husid plot H(t) = integral_0^t a^2 / integral_0^T a^2 (Husid 1969). Within a step with a linear in time,
//   integral a^2 is the cubic a0^2 s + a0 (a1 - a0) s^2 / h + (a1 - a0)^2 s^3 / (3 h^2); the times where H reaches
//   5 % and 95 % are roots of that cubic, found by safeguarded Newton to round-off: significant duration
//   D5-95 = t_95 - t_5 (Trifunac & Brady 1975), exact for the piecewise-linear record.
// - Cumulative absolute velocity CAV = integral |a| dt (EPRI 1988, without its 0.025 g threshold), exact per step:
//   h (|a0| + |a1|) / 2 without a sign change, h (a0^2 + a1^2) / (2 (|a0| + |a1|)) across a zero.
// The spectral measures (predominant frequency, predominant and mean period) are defined in spectra.hpp.
#include <optional>
#include <string>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/core/units.hpp"

namespace topple {

struct GroundVelocityDisplacement {
  std::vector<double> velocity_m_s;  ///< at each sample
  std::vector<double> displacement_m;
};

/// Ground velocity and displacement by exact integration of the piecewise-linear acceleration, from rest at the
/// first sample.
[[nodiscard]] GroundVelocityDisplacement integrate_ground(const GroundMotion& motion);

struct BasicIntensity {
  double pga_m_s2 = 0.0;
  double pga_time_s = 0.0;
  double pgv_m_s = 0.0;
  double pgd_m = 0.0;
  double arias_m_s = 0.0;  ///< Arias (1970): I_A = pi / (2 g) * integral a^2 dt
};

/// PGA, PGV, PGD and Arias intensity; g is used only for Arias' pi/(2g).
[[nodiscard]] BasicIntensity basic_intensity(const GroundMotion& motion, double g_m_s2 = kStandardGravity);

/// Husid plot at the samples: integral_0^{t_i} a^2 dt / integral_0^T a^2 dt, from 0 to 1. Throws InputError for an
/// identically zero record.
[[nodiscard]] std::vector<double> husid(const GroundMotion& motion);

/// The times at which the Husid plot first reaches `low` and `high` (0 <= low < high <= 1), and their difference.
struct SignificantDuration {
  double start_s = 0.0;
  double end_s = 0.0;
  double duration_s = 0.0;
};
/// Significant duration, exact for the piecewise-linear record (D5-95 with the defaults). Throws InputError for an
/// identically zero record or fractions outside 0 <= low < high <= 1.
[[nodiscard]] SignificantDuration significant_duration(const GroundMotion& motion, double low = 0.05,
                                                       double high = 0.95);

/// Cumulative absolute velocity integral |a| dt, m/s, exact for the piecewise-linear record.
[[nodiscard]] double cumulative_absolute_velocity_m_s(const GroundMotion& motion);

/// A measure that some records lack (an identically zero record, one too short for the band): its value, or the
/// reason it has none.
struct OptionalMeasure {
  std::optional<double> value;
  std::string undefined_reason;  ///< empty when value is set
};

/// Everything `topple info` prints (and `topple.intensity` returns).
struct IntensityMeasures {
  BasicIntensity basic;
  std::optional<SignificantDuration> d5_95;  ///< none for an identically zero record
  double cav_m_s = 0.0;
  OptionalMeasure tp_s;                      ///< predominant period, s (spectra.hpp)
  OptionalMeasure tm_s;                      ///< mean period, s, Rathje et al. 1998 (spectra.hpp)
  OptionalMeasure predominant_frequency_hz;  ///< Hz (spectra.hpp)
};

/// All measures of a record; g (m/s^2) is used only for Arias' pi/(2g). A measure the record does not define is
/// left empty with its reason (never an exception for an identically zero or a short record).
[[nodiscard]] IntensityMeasures intensity_measures(const GroundMotion& motion, double g_m_s2 = kStandardGravity);

}  // namespace topple
