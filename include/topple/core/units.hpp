#pragma once
// Units at the edges of topple.
//
// Everything inside the library is SI: metres, seconds, m/s^2, radians. Users type "4cm", "0.5g", "20s", "3Hz";
// these helpers turn such strings into SI numbers and refuse anything without a unit where one is required, so that
// "0.3" never silently means 0.3 m when the user meant 0.3 g.
#include <string>
#include <string_view>

namespace topple {

/// Standard gravity (CGPM 1901; ISO 80000-3), m/s^2. The default g of every model; each model takes g explicitly so
/// that the thesis' g = 981 cm/s^2 can be used where its tables are reproduced.
inline constexpr double kStandardGravity = 9.80665;

inline constexpr double kPi = 3.141592653589793238462643383279502884;

/// Degrees to radians, (deg * pi) / 180: the one conversion of the library and its front ends (it was written inline
/// in this order at every site, so the move to it changed no bit of any result).
[[nodiscard]] constexpr double deg_to_rad(double deg) noexcept { return deg * kPi / 180.0; }
/// Radians to degrees, (rad * 180) / pi.
[[nodiscard]] constexpr double rad_to_deg(double rad) noexcept { return rad * 180.0 / kPi; }

/// A length such as "4cm", "0.04 m", "40mm", "1.5in", "2ft". Throws InputError naming `field` when the string has
/// no number, no unit, an unknown unit, or is not finite.
[[nodiscard]] double parse_length_m(std::string_view text, const std::string& field);

/// An area such as "0.011m2", "110cm2", "0.011 m^2" (m2, cm2, mm2); a bare number is refused, as for lengths.
[[nodiscard]] double parse_area_m2(std::string_view text, const std::string& field);

/// An acceleration such as "0.5g", "4.9m/s2", "490gal", "490cm/s2". Multiples of g use `g_m_s2`.
[[nodiscard]] double parse_acceleration_m_s2(std::string_view text, const std::string& field,
                                             double g_m_s2 = kStandardGravity);

/// A duration such as "20s", "0.1 s", "150ms".
[[nodiscard]] double parse_duration_s(std::string_view text, const std::string& field);

/// A frequency such as "3Hz", "2.5 hz".
[[nodiscard]] double parse_frequency_hz(std::string_view text, const std::string& field);

/// An angle such as "10deg", "0.2rad"; a bare number is refused.
[[nodiscard]] double parse_angle_rad(std::string_view text, const std::string& field);

/// Acceleration unit of a stored record, as read from a file header or given by the user ("g", "m/s2", "cm/s2",
/// "gal", "mm/s2"). Returns the factor that converts one unit to m/s^2 (uses g_m_s2 for "g").
[[nodiscard]] double acceleration_unit_factor(std::string_view unit, const std::string& field,
                                              double g_m_s2 = kStandardGravity);

}  // namespace topple
