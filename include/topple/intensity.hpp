#pragma once
// Intensity measures of a ground motion.
//
// All integrals treat the acceleration as piecewise linear between samples (the same model the solvers use), so
// velocity is the trapezoid rule, displacement is exact for that model (cubic in each step), and the Arias integral
// of a^2 is exact per step: h (a0^2 + a0 a1 + a1^2) / 3. No baseline correction is applied here: a record's own
// processing is respected, and GroundMotion::baseline_corrected is there when a user wants one.
#include <vector>

#include "topple/ground_motion.hpp"
#include "topple/units.hpp"

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

}  // namespace topple
