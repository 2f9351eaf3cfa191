#pragma once
// A rigid body that rocks or slides and rocks: its two pivots (O+ at +x, O- at -x; one when symmetric), the height of
// its centre of mass and its moment of inertia about each pivot, built by factories that validate (block, cylinder,
// general, general asymmetric), and the dimensions a user gives. The symbols and sign conventions are those of
// topple/solvers/rocking.hpp's header (Housner 1963; thesis section 3): every solver that moves a body
// (rocking.hpp, slide_rock.hpp), the oriented objects (oriented.hpp), the mesh bodies (body.hpp), the survey and the
// sweep share this one type.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace topple {

/// A rigid body that rocks. Build it with a factory, which validates.
struct RockingBody {
  enum class Shape : std::uint8_t { block, cylinder, general };

  /// The pivot O- (theta < 0, the -x edge) of an asymmetric body (b1 of a general body).
  struct Pivot {
    double b_m = 0.0;   ///< CM to O-, horizontal, m
    double D_m2 = 0.0;  ///< I_O- / m, m^2
  };

  Shape shape = Shape::block;
  double a_m = 0.0;   ///< CM to pivot edge, horizontal, m (a 4 cm wide block: 0.02); an asymmetric body: CM to O+
                      ///< (theta > 0, the +x edge; b2)
  double h_m = 0.0;   ///< CM height above the base, m (a 20 cm tall block: 0.10)
  double D_m2 = 0.0;  ///< pivot moment of inertia per unit mass I_O / m, m^2 (asymmetric: about O+)
  /// Unset: the body is symmetric (O- mirrors O+: a_m, D_m2). Set: the other pivot of an asymmetric body. The
  /// symmetric members (alpha_rad, R_m, p_rad_s, the closed forms, Shenton) then describe the O+ side; the rocking
  /// engine uses both (see "Asymmetric bodies" above).
  std::optional<Pivot> negative_pivot;

  /// Rectangular block of full width and height (m, > 0, finite): a = w/2, h = H/2, D = (4/3)(a^2 + h^2).
  /// Throws InputError naming "width" or "height".
  [[nodiscard]] static RockingBody block(double width_m, double height_m);
  /// Solid circular cylinder standing on its end: a = d/2, h = H/2, D = (15 a^2 + 16 h^2) / 12 (thesis eq 3.13).
  /// Throws InputError naming "diameter" or "height".
  [[nodiscard]] static RockingBody cylinder(double diameter_m, double height_m);
  /// Any body given by a, h (> 0) and D >= a^2 + h^2 (equality: all the mass at the CM). Throws InputError naming
  /// "a", "h" or "D" (D below a^2 + h^2 is no real body: its moment of inertia about the CM would be negative).
  [[nodiscard]] static RockingBody general(double a_m, double h_m, double D_m2);
  /// Asymmetric general body: b1 = CM to the pivot O- (the -x edge, theta < 0), b2 = CM to O+ (theta > 0), h the
  /// CM height (all m, > 0) and k2 = I_cm / m, the moment of inertia about the CM per unit mass (m^2, >= 0): then
  /// D- = k2 + b1^2 + h^2 and D+ = k2 + b2^2 + h^2 (parallel axes). negative_pivot is set even when b1 = b2 (the
  /// asymmetric path then reproduces general(b, h, D) to round-off). Throws InputError naming "b1", "b2", "h" or
  /// "inertia".
  [[nodiscard]] static RockingBody general_asymmetric(double b1_m, double b2_m, double h_m, double k2_m2);

  [[nodiscard]] bool symmetric() const noexcept { return !negative_pivot; }
  /// CM to the pivot of side s (s > 0: O+, s < 0: O-), m.
  [[nodiscard]] double pivot_b_m(int side) const noexcept {
    return side < 0 && negative_pivot ? negative_pivot->b_m : a_m;
  }
  /// I_O / m about the pivot of side s, m^2.
  [[nodiscard]] double pivot_D_m2(int side) const noexcept {
    return side < 0 && negative_pivot ? negative_pivot->D_m2 : D_m2;
  }
  /// The symmetric body that rocks about the pivot of side s exactly as this one does while on that pivot (b_s, h,
  /// D_s): the equation of motion, the uplift threshold and Shenton's onset about one pivot involve that pivot only.
  [[nodiscard]] RockingBody side_body(int side) const;

  [[nodiscard]] double alpha_rad() const noexcept;        ///< atan(a / h)
  [[nodiscard]] double R_m() const noexcept;              ///< sqrt(a^2 + h^2)
  [[nodiscard]] double p_rad_s(double g_m_s2) const noexcept;  ///< sqrt(g R / D)
};

[[nodiscard]] std::string_view shape_name(RockingBody::Shape shape);  ///< "block", "cylinder", "general"
/// "block", "cylinder" or "general"; throws InputError naming `field` otherwise.
[[nodiscard]] RockingBody::Shape parse_shape(std::string_view name, const std::string& field = "shape");

/// The largest body dimension topple accepts, m: a free-standing object of a kilometre is no object, and the limit
/// keeps D = (4/3)(a^2 + h^2) and every quantity derived from it finite.
inline constexpr double kMaxBodyDimension_m = 1000.0;

/// A body's dimensions as a user gives them, by shape: block {width_m, height_m}, cylinder {diameter_m, height_m},
/// general {a_m, h_m, D_m2} or, asymmetric, {b1_m, b2_m, h_m, inertia_m2} (m, m^2; inertia = I_cm / m). Unset: not
/// given.
struct BodyDimensions {
  std::optional<double> width_m;
  std::optional<double> height_m;
  std::optional<double> diameter_m;
  std::optional<double> a_m;
  std::optional<double> h_m;
  std::optional<double> D_m2;
  std::optional<double> b1_m;        ///< CM to the pivot O- (theta < 0, the -x edge)
  std::optional<double> b2_m;        ///< CM to the pivot O+ (theta > 0, the +x edge)
  std::optional<double> inertia_m2;  ///< I_cm / m, moment of inertia about the CM per unit mass
};

/// The body of `shape` from its dimensions. Throws InputError naming the field ("width", "height", "diameter", "a",
/// "h", "D", "b1", "b2", "inertia"; a general body takes {a, h, D} or {b1, b2, h, inertia}) that the shape needs and
/// lacks, that does not apply to it, that exceeds kMaxBodyDimension_m (D: its
/// square), or that the factory refuses.
[[nodiscard]] RockingBody make_rocking_body(RockingBody::Shape shape, const BodyDimensions& dimensions);

}  // namespace topple
