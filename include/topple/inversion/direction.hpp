#pragma once
// The direction of strongest shaking and the other results of the three-component inversion (inversion_3c.hpp) that
// InversionResult carries when [inversion] components = 3. Value types only; the method is in inversion_3c.hpp and
// docs/method.md, "Inversion in three components".
#include <optional>
#include <vector>

namespace topple {

/// An arc of directions (axes, mod 180 deg): from low_deg clockwise over width_deg. low_deg in [0, 180); the arc may
/// pass 180 (then it goes on from 0: an axis at 175 deg is the axis at 355 deg).
struct DirectionArc {
  double low_deg = 0.0;    ///< deg clockwise from north, [0, 180)
  double width_deg = 0.0;  ///< deg, (0, 180]
  [[nodiscard]] double high_deg() const noexcept { return low_deg + width_deg; }  ///< may exceed 180 (see above)
  /// Whether the axis `azimuth_deg` (any value, taken mod 180) lies on the arc, ends included.
  [[nodiscard]] bool contains(double azimuth_deg) const noexcept;
};

/// The posterior of the azimuth of the major axis of horizontal motion (deg clockwise from north, mod 180).
struct DirectionEstimate {
  std::vector<double> azimuth_deg;  ///< the bins' centres, deg: 0, w, 2w, ... (w = 180 / bins)
  double bin_width_deg = 15.0;      ///< w, deg
  std::vector<double> posterior;    ///< per bin, sums to 1
  double mode_deg = 0.0;            ///< the most probable bin's centre, deg
  double mean_deg = 0.0;            ///< the axial (doubled-angle) circular mean, deg in [0, 180)
  double resultant_length = 0.0;    ///< |mean of exp(2 i psi)| over the posterior, in [0, 1]: 0 flat, 1 one bin
  DirectionArc ci68;                ///< the shortest arc holding the 68 % highest-posterior bins
  DirectionArc ci95;                ///< the same for 95 %
  /// False when the posterior is near flat: its 95 % arc spans more than kUnconstrainedArcDeg (inversion_3c.hpp).
  bool constrained = false;
};

/// What a three-component inversion adds to InversionResult.
struct ThreeComponentResult {
  DirectionEstimate direction;
  /// The family's mean ratio of the larger as-synthesised horizontal component's PGA to the pair's RotD50 PGA, and of
  /// RotD100 to RotD50 (dimensionless); the PGA axis is RotD50, these convert it.
  double larger_component_ratio = 1.0;
  double rotd100_ratio = 1.0;
  /// The PGA estimates in larger-component PGA (g): the RotD50 estimates times larger_component_ratio.
  double larger_component_median_g = 0.0;
  std::optional<double> larger_component_ci95_low_g, larger_component_ci95_high_g;
  double coherence = 0.0;                ///< the family's horizontal coherence rho (survey.hpp)
  double vertical_pga_ratio = 0.0;       ///< PGA_v / RotD50 PGA_h of the family (synthesis.hpp default 2/3)
  double vertical_frequency_ratio = 0.0; ///< f_v / f_h of the family (synthesis.hpp default 1.5)
  /// rho of the static thresholds (inversion_3c.hpp, item 6): the largest PGA_v / RotD50 PGA_h over the family's
  /// realisations (dimensionless; vertical_pga_ratio up to the 1-degree grid of RotD50 after the rotation).
  double threshold_vertical_ratio = 0.0;
  double slid_direction_kappa = 0.0;     ///< von Mises concentration of the sliding-direction error model
};

}  // namespace topple
