#pragma once
// Orientation-independent measures of two horizontal components: RotD50 and RotD100 (Boore 2010, "Orientation-
// independent, nongeometric-mean measures of seismic intensity from two horizontal components of motion", BSSA
// 100(4), 1830-1835).
//
// Definition. The pair (a_1, a_2) rotated by the angle theta (from the first component toward the second) is the
// single component a_theta(t) = a_1(t) cos theta + a_2(t) sin theta: the projection on azimuth alpha_1 + h theta
// (motion_set.hpp eq. M1, h the pair's handedness). For a measure Y (the peak |a|, the peak |x| of a linear
// oscillator), Y(theta) is computed at theta = 0, 1, ..., 179 deg (theta and theta + 180 give the same peak);
//   RotD100 = max_theta Y(theta),   RotD50 = the median of the 180 values,                               (R1)
// the median being the 50th percentile with linear interpolation between order statistics (the mean of the 90th
// and 91st smallest of 180; numpy's default, as pyrotd computes it).
//
// Oscillators by linearity (Boore 2010, p. 1832). The oscillator response x_theta to a_theta is
// x_1 cos theta + x_2 sin theta, x_i the responses to the two components (the oscillator equation is linear), so
// each component's oscillator runs once (Nigam-Jennings, exact for the piecewise-linear record, spectra.hpp) and
// the 180 rotated responses are combinations of the two histories at the samples. PSA(theta) = w^2 max |x_theta|,
// maxima at the samples over the record (as spectra.hpp's response_spectrum, which returns the same number for the
// projected record to round-off: tests/motion/test_motion_set.cpp). The peak ground acceleration's rotated component is
// piecewise linear on the merged grid, so its peak lies at a grid point: RotD of PGA is exact.
//
// Closed forms (tests). With a_2 = 0: Y(theta) = Y_1 |cos theta|, RotD100 = Y_1 and RotD50 = Y_1 cos 45 deg
// (|cos theta| over theta = 0..179 takes 1 and 0 once and cos k deg, k = 1..89, twice: its 90th and 91st smallest
// are both cos 45 deg). A circularly polarised pair a_1 = A cos wt, a_2 = A sin wt: a_theta = A cos(wt - theta),
// the same peak A at every angle.
#include <optional>
#include <span>
#include <vector>

#include "topple/motion/motion_set.hpp"

namespace topple {

/// RotD of one measure.
struct RotDValue {
  double rotd50 = 0.0;           ///< median over the angles (unit of the measure)
  double rotd100 = 0.0;          ///< largest over the angles
  double rotd100_angle_deg = 0.0;  ///< theta of the largest (first one), deg from the first component toward the second
};

/// The rotation angles, deg: 0, 1, ..., 179.
[[nodiscard]] std::vector<double> rotd_angles_deg();

/// Y(theta) of a peak measure of two series on one grid (the same samples): max_i |y1_i cos theta + y2_i sin theta|
/// at theta = 0..179 deg (cos and sin tabulated portably, rotd.cpp). InputError naming "second" for different lengths.
[[nodiscard]] std::vector<double> rotd_peaks_by_angle(std::span<const double> y1, std::span<const double> y2);

/// RotD50 and RotD100 of the values of a measure at the angles of rotd_angles_deg() (180 values, >= 0).
[[nodiscard]] RotDValue rotd_of(std::span<const double> value_by_angle);

/// The azimuth (deg clockwise from north, in [0, 180): a direction, not a sense) of the rotation angle theta for a
/// set whose azimuths are known; none otherwise.
[[nodiscard]] std::optional<double> rotd_azimuth_deg(const MotionSet& set, double angle_deg);

struct RotDMeasures {
  std::vector<double> pga_by_angle_m_s2;  ///< peak |a_theta| at each angle, m/s^2
  RotDValue pga_m_s2;                     ///< RotD of the PGA, m/s^2
  std::vector<double> period_s;
  double damping = 0.05;                  ///< damping ratio zeta (dimensionless fraction of critical)
  std::vector<RotDValue> psa_m_s2;        ///< RotD of the PSA at each period, m/s^2
  std::vector<std::vector<double>> psa_by_angle_m_s2;  ///< [period][angle]: w^2 max |x_theta|, m/s^2
};

/// RotD of the PGA and of the PSA (damping ratio `damping`, 0 <= zeta < 1) at `period_s` (> 0) of a set with two
/// horizontal components (InputError naming "second" otherwise; the vertical is ignored).
[[nodiscard]] RotDMeasures rotd_measures(const MotionSet& set, std::span<const double> period_s,
                                         double damping = 0.05);

/// The periods at which `topple info` reports RotD PSA, s: 0.1, 0.2, 0.3, 0.5, 0.75, 1, 1.5, 2, 3, 4 (the span of
/// the objects topple models: rocking and sliding respond to 0.1-4 s).
[[nodiscard]] std::vector<double> rotd_periods_s();

}  // namespace topple
