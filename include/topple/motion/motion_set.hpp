#pragma once
// MotionSet: one station's ground motion in up to three components on one time grid: a first horizontal component
// (always), a second horizontal one perpendicular to it, and a vertical one, positive up.
//
// Frame. Azimuths in degrees clockwise from north (east = 90), the convention of the agencies' headers (CSMIP "90
// DEG", K-NET "E-W"); a component's acceleration is positive toward its azimuth. The two horizontal components are
// perpendicular (an accelerograph's axes), of either handedness: second = first + 90 or first - 90 (mod 360). The
// horizontal acceleration projected on a direction of azimuth phi is
//   a_phi(t) = a_1(t) cos(phi - alpha_1) + a_2(t) cos(phi - alpha_2)                                        (M1)
// (the dot product of the horizontal vector with the unit vector toward phi; alpha_i the components' azimuths), so
// a_phi = a_1 at phi = alpha_1 and a_phi = a_2 at phi = alpha_2 exactly.
//
// Grid. The components are merged exactly by InputGrid (input_grid.hpp): the union of their sample times, jumps
// kept, each component piecewise linear between its own samples and zero outside its record. Different sampling
// (another dt, irregular times, one more sample at the end) is therefore not an error: it is merged exactly. What
// is refused (InputError naming the component's file and the field "time span"): components whose time spans
// overlap over less than half of the longest span (min end - max start < 0.5 x the longest duration). Channels of
// one recording start together and last about as long; records that do not are not one station's motion (two
// different events, a file from a different trigger), and zero-padding one of them would be a silent guess.
//
// Orientation. The azimuths are the user's or, when the records' headers state them (RecordMetadata::azimuth_deg,
// io::orientation_from_component), the files'. resolve_azimuths() decides: the user's value wins over a header
// (the header of an old record may be wrong, the user may know the sensor was re-oriented), with a warning naming
// both. A component the header calls vertical is refused as a horizontal one, and a header azimuth as the vertical.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "topple/motion/ground_motion.hpp"

namespace topple {

/// The two horizontal components' azimuths, degrees clockwise from north (east = 90). They must be perpendicular
/// (as an accelerograph's axes are); either handedness.
struct ComponentAzimuths {
  double first_deg = 90.0;   ///< typical: 90 (east-west channel, positive east)
  double second_deg = 0.0;   ///< typical: 0 (north-south channel, positive north)
  /// On a slope (SlidingBlock::slope_rad > 0, sliding2d.hpp): the azimuth of the downslope direction (the fall line
  /// seen from above), degrees clockwise from north; unused on level ground and by the motion set itself.
  double slope_azimuth_deg = 0.0;

  /// +1 when second = first + 90 (clockwise, e.g. 0 then 90), -1 when second = first - 90 (e.g. 90 then 0).
  [[nodiscard]] int handedness() const noexcept;
  /// Throws InputError naming `field` (e.g. "--azimuths") for a non-finite azimuth or azimuths that are not
  /// perpendicular to 1e-6 deg.
  void validate(const std::string& field = "azimuths") const;
};

/// The azimuths of a pair: `user` when given, else both headers' (RecordMetadata::azimuth_deg); InputError naming
/// `field` when neither states them (for the files named in the message). A user value that differs from a header
/// by more than 1e-6 deg wins, and a line for each such component is appended to `warnings`. The result is
/// validated (perpendicular).
[[nodiscard]] ComponentAzimuths resolve_azimuths(const GroundMotion& first, const GroundMotion& second,
                                                 const std::optional<ComponentAzimuths>& user,
                                                 std::vector<std::string>& warnings,
                                                 const std::string& field = "--azimuths");

class MotionSet {
 public:
  /// `first` is the first horizontal component; `second` (optional) the second, perpendicular to it; `azimuths`
  /// their azimuths when known (the projection on an azimuth needs them; RotD does not: its angles are measured from
  /// the first component); `vertical` (optional), positive up. Merged exactly (header). Throws InputError for azimuths that
  /// are not perpendicular, time spans that hardly overlap (header), a horizontal component whose header says it
  /// is vertical, or a vertical one whose header gives it an azimuth.
  static MotionSet make(const GroundMotion& first, const GroundMotion* second,
                        const std::optional<ComponentAzimuths>& azimuths, const GroundMotion* vertical = nullptr);

  /// The merged components, each on the common grid (uniform when the inputs share one uniform grid, else
  /// irregular with repeated times at jumps), metadata kept.
  [[nodiscard]] const GroundMotion& first() const noexcept { return first_; }
  [[nodiscard]] bool has_second() const noexcept { return second_.has_value(); }
  [[nodiscard]] const GroundMotion& second() const;   ///< InputError when absent
  [[nodiscard]] bool has_vertical() const noexcept { return vertical_.has_value(); }
  [[nodiscard]] const GroundMotion& vertical() const; ///< InputError when absent
  [[nodiscard]] const GroundMotion* second_ptr() const noexcept { return second_ ? &*second_ : nullptr; }
  [[nodiscard]] const GroundMotion* vertical_ptr() const noexcept { return vertical_ ? &*vertical_ : nullptr; }
  [[nodiscard]] const std::optional<ComponentAzimuths>& azimuths() const noexcept { return azimuths_; }
  /// Number of grid points.
  [[nodiscard]] std::size_t size() const noexcept { return first_.size(); }

  /// The horizontal acceleration projected on the direction `azimuth_deg` (eq. M1), on the common grid, m/s^2.
  /// With one component, only its own azimuth or the opposite one (+180) are defined. Throws InputError naming
  /// "azimuth" when the azimuths are unknown or the direction is not defined.
  [[nodiscard]] GroundMotion projected(double azimuth_deg) const;
  /// The pair rotated to azimuth_deg and azimuth_deg + 90 (same handedness as the set: clockwise).
  [[nodiscard]] std::pair<GroundMotion, GroundMotion> rotated(double azimuth_deg) const;

 private:
  MotionSet(GroundMotion first, std::optional<GroundMotion> second, std::optional<GroundMotion> vertical,
            std::optional<ComponentAzimuths> azimuths)
      : first_(std::move(first)), second_(std::move(second)), vertical_(std::move(vertical)), azimuths_(azimuths) {}
  GroundMotion first_;
  std::optional<GroundMotion> second_;
  std::optional<GroundMotion> vertical_;
  std::optional<ComponentAzimuths> azimuths_;
};

}  // namespace topple
