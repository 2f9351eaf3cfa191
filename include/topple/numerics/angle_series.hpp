#pragma once
// sin and cos near a reference angle by short series, shared by the ODE-based solvers (rocking.cpp, slide_rock.cpp):
// within a step the angle moves little from the step's start, so sin(ref + d) and cos(ref + d) follow from the
// reference's by the angle-addition formulas with sin d and cos d - 1 from their Taylor series, instead of a libm
// call per stage. Internal to the library (not installed).
#include <cmath>

namespace topple::detail {

inline constexpr double kSeriesRange = 0.1;
inline constexpr double kShortRange = 0.01;


/// sin d and cos d - 1 by their series when |d| <= kSeriesRange (false otherwise: the caller uses libm).
/// |d| <= 0.1 (theta moves less than that within a step but for large steps on slow motions): sin d to d^9 and
/// cos d - 1 to d^10 leave out less than 3e-19. Estrin's scheme keeps the dependency chain short (the stages of a
/// step are sequential, so this function's latency is the step's). Reciprocals are constants: a division by a
/// literal stays a division.
[[gnu::always_inline]] inline bool angle_series(double d, double& sd, double& cd_minus_1) {
  if (std::abs(d) <= kShortRange) {
    // |d| <= 0.01, as for nearly every stage (a step moves phi by p alpha dt theta'/(p alpha), about 1e-3 on a
    // 0.005 s record): sin d to d^5 and cos d - 1 to d^6 leave out |d|^7/5040 < 2e-18, below the round-off of
    // the result's O(1) terms; a shorter dependency chain than the terms to d^9 below.
    constexpr double k6 = 1.0 / 6.0, k120 = 1.0 / 120.0, k24 = 1.0 / 24.0, k720 = 1.0 / 720.0;
    const double d2 = d * d;
    sd = d + (d * d2) * (k120 * d2 - k6);
    cd_minus_1 = d2 * ((k24 * d2 - 0.5) - (k720 * d2) * d2);
    return true;
  }
  if (!(std::abs(d) <= kSeriesRange)) return false;
  constexpr double k6 = 1.0 / 6.0, k120 = 1.0 / 120.0, k5040 = 1.0 / 5040.0, k362880 = 1.0 / 362880.0;
  constexpr double k24 = 1.0 / 24.0, k720 = 1.0 / 720.0, k40320 = 1.0 / 40320.0, k3628800 = 1.0 / 3628800.0;
  const double d2 = d * d;
  const double d4 = d2 * d2;
  sd = d + (d * d2) * ((k120 * d2 - k6) + d4 * (k362880 * d2 - k5040));
  cd_minus_1 = d2 * ((k24 * d2 - 0.5) + d4 * (k40320 * d2 - k720 - k3628800 * d4));
  return true;
}

/// sin and cos of phi near phi_ref (whose sin and cos are given): the angle-addition formulas with the series of
/// phi - phi_ref, or libm when that is beyond kSeriesRange.
[[gnu::always_inline]] inline void sin_cos_near(double phi, double phi_ref, double sin_ref, double cos_ref, double& sn,
                                                double& cs) {
  double sd = 0.0;
  double cd_minus_1 = 0.0;
  if (!angle_series(phi - phi_ref, sd, cd_minus_1)) {
    sn = std::sin(phi);
    cs = std::cos(phi);
    return;
  }
  sn = sin_ref + (sin_ref * cd_minus_1 + cos_ref * sd);
  cs = cos_ref + (cos_ref * cd_minus_1 - sin_ref * sd);
}

/// References moved by the series before an exact sin/cos: each move adds ~1e-17 to sin and cos, so the drift stays
/// below 1e-14.
inline constexpr int kMaxReferenceMoves = 256;

/// Moves the reference (phi_ref, its sin and cos) to phi by the series, for the next step of an integrator (a step
/// moves the angle little). False, and nothing changed, when phi is too far or the reference has moved
/// kMaxReferenceMoves times: the caller then sets it exactly (libm), with moves = 0.
[[gnu::always_inline]] inline bool move_reference(double phi, double& phi_ref, double& sin_ref, double& cos_ref,
                                                  int& moves) {
  if (moves >= kMaxReferenceMoves || !(std::abs(phi - phi_ref) <= kSeriesRange)) return false;
  double sn = 0.0;
  double cs = 0.0;
  sin_cos_near(phi, phi_ref, sin_ref, cos_ref, sn, cs);
  phi_ref = phi;
  sin_ref = sn;
  cos_ref = cs;
  ++moves;
  return true;
}

}  // namespace topple::detail
