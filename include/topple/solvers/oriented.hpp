#pragma once
// Oriented rocking objects: a rocking body standing at a bearing under a motion set (two horizontal components and,
// optionally, a vertical one; motion_set.hpp).
//
// Bearing. The direction across the object's narrow side, degrees clockwise from north (east = 90): the direction in
// which it rocks most easily. The planar body of rocking.hpp is placed with its +x axis toward the bearing, so that
// theta > 0 (rocking about O+) moves its top toward the bearing and a ground acceleration toward the bearing (a_h > 0)
// drives theta < 0 (rocking.hpp, "Sign convention"). An asymmetric body's O+ (b2) edge is the one toward the bearing.
//
// Model (planar projection; docs/method.md, "Oriented objects"). The body rocks in the vertical plane of its bearing
// phi under the horizontal acceleration projected on that direction,
//   a_h(t) = a_1(t) cos(phi - alpha_1) + a_2(t) cos(phi - alpha_2)                    (eq. M1, MotionSet::projected)
// with the vertical a_v(t) (g -> g + a_v). The horizontal component perpendicular to the plane is ignored: this is
// the two-dimensional rocking model of Housner (1963) applied along one axis (the thesis' own model, which its
// section 1.2 says is not enough in general). It is exact when the motion across the plane is zero; otherwise the
// out-of-plane motion and any three-dimensional response (rocking about a corner, wobbling) are neglected.
//
// Box (a rectangular block with its depth given). Rocking about either pair of base edges is checked: along the
// bearing with half-width a = width / 2, and along bearing + 90 with half-width depth / 2 (each a planar run under
// its own projection); the response reported is the more severe of the two ("Severity" below) and the result says
// which axis governed. A block without a depth is checked along its bearing only (a wall-like object that does not
// rock the other way).
//
// Cylinder (axisymmetric: no bearing). Taken in its worst direction over the azimuths 0, s, 2 s, ... < 180 deg
// (OrientationOptions::cylinder_step_deg, default s = 15: twelve planar runs). Directions phi and phi + 180 give the
// same planar body under the opposite input, the mirror image (theta -> -theta) of the same response, so half a turn
// covers the circle. This is an approximation of three-dimensional rocking: a cylinder rolling on its rim (wobbling;
// Koh & Mustafa 1990, J. Eng. Mech. 116(1); Srinivasan & Ruina 2008, Phys. Rev. E 78) responds to both components
// together, and three-dimensional analyses find the planar estimate close under pulses but not always conservative
// under records (Vassiliou et al. 2017, Earthquake Eng. Struct. Dyn. 46; "Response of 3D free axisymmetric rigid
// objects under seismic excitations", arXiv 2009); a direction between two grid azimuths is not run either.
//
// Severity. Direction x is more severe than y when x overturned and y did not; when both overturned, when x fell
// first; when neither did, when x's max |theta| / alpha is larger. Ties keep the earlier direction (the bearing
// before the other axis; the smaller azimuth on the cylinder grid).
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {

/// A rocking body with what its orientation needs: the planar body along the bearing and, for a box, the one across.
struct OrientedBody {
  RockingBody body;                   ///< the planar body along the bearing (+x toward the bearing)
  std::optional<RockingBody> across;  ///< a box: the planar body along bearing + 90 (half-width depth / 2)

  /// The body rocks along its bearing only (any shape but a cylinder; a cylinder is always taken in its worst
  /// direction).
  [[nodiscard]] static OrientedBody planar(const RockingBody& body);
  /// A box: width across the narrow side (along the bearing), depth along it (bearing + 90), height (m, > 0, finite).
  /// Throws InputError naming "width", "depth" or "height".
  [[nodiscard]] static OrientedBody box(double width_m, double depth_m, double height_m);
  /// `body` with its depth when given: a block with a depth is a box; a depth on another shape throws InputError
  /// naming "depth" (a cylinder's section is its diameter; a general body has one plane).
  [[nodiscard]] static OrientedBody make(const RockingBody& body, std::optional<double> depth_m);

  [[nodiscard]] bool axisymmetric() const noexcept { return body.shape == RockingBody::Shape::cylinder; }
};

struct OrientationOptions {
  /// Cylinder: spacing of the azimuths tried, deg; in (0, 180] and 180 / step a whole number (to 1e-9).
  double cylinder_step_deg = 15.0;
};

/// Which planar analysis a direction is.
enum class OrientedAxis : std::uint8_t {
  bearing,  ///< along the bearing (the narrow side)
  across,   ///< a box's other axis, bearing + 90
  grid,     ///< one azimuth of a cylinder's direction grid
};
[[nodiscard]] std::string_view oriented_axis_name(OrientedAxis axis);  ///< "bearing", "across", "grid"

/// One planar analysis.
struct DirectionResponse {
  double azimuth_deg = 0.0;  ///< direction of the planar body's +x axis, degrees clockwise from north, in [0, 360)
  OrientedAxis axis = OrientedAxis::bearing;
  RockingSummary summary;
};

struct OrientedRockingSummary {
  std::vector<DirectionResponse> directions;  ///< every planar analysis, in the order of the header
  std::size_t governing = 0;                  ///< index of the most severe one in `directions`

  [[nodiscard]] const DirectionResponse& governing_response() const { return directions.at(governing); }
};

struct OrientedRockingResult {
  OrientedRockingSummary orientation;
  RockingResult governing;  ///< the governing direction's full response (history and events)
};

/// The orientation inputs an object takes: a bearing for every body but a cylinder (required), none for a cylinder
/// (refused: it is taken in its worst direction), and a direction step for a cylinder only. Throws InputError naming
/// "bearing" or "cylinder_step" (`step_given`: the caller chose a step rather than the default).
void check_orientation(const OrientedBody& body, std::optional<double> bearing_deg, bool step_given);

/// The planar body run along a direction of `body` (the body itself, or a box's other axis).
[[nodiscard]] const RockingBody& planar_body_of(const OrientedBody& body, OrientedAxis axis);

/// The azimuths a body is analysed along, with their axes: the bearing (planar body); the bearing and bearing + 90
/// (box); the cylinder grid (the bearing is not used). Azimuths in [0, 360). Throws InputError naming "bearing" when
/// it is not finite, "cylinder_step" for a step outside OrientationOptions' rule.
[[nodiscard]] std::vector<std::pair<double, OrientedAxis>> oriented_directions(const OrientedBody& body,
                                                                              double bearing_deg,
                                                                              const OrientationOptions& orientation = {});

/// True when `x` is more severe than `y` (header, "Severity").
[[nodiscard]] bool more_severe(const RockingSummary& x, const RockingSummary& y) noexcept;

/// Summaries of every planar analysis of `body` standing at `bearing_deg` under `set` (header), each by
/// rock_summary on set.projected(azimuth) with set.vertical(), and the governing one. Throws InputError naming
/// "second" when the set has one horizontal component (the projection on another direction needs both), "azimuth"
/// when its azimuths are unknown, and what rock_summary throws.
[[nodiscard]] OrientedRockingSummary rock_oriented_summary(const MotionSet& set, const OrientedBody& body,
                                                           double bearing_deg, const RockingOptions& options = {},
                                                           const OrientationOptions& orientation = {});

/// Same, with the governing direction's full response (rock(), whose summary equals rock_summary's).
[[nodiscard]] OrientedRockingResult rock_oriented(const MotionSet& set, const OrientedBody& body, double bearing_deg,
                                                  const RockingOptions& options = {},
                                                  const OrientationOptions& orientation = {});

}  // namespace topple
