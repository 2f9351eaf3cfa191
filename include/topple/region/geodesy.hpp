#pragma once
// Distances between an epicentre and the sites of a survey (docs/method.md, "Regional joint inversion").

namespace topple {

/// Geodesic distance between two points on the WGS84 ellipsoid (Karney 2013, GeographicLib), km.
[[nodiscard]] double geodesic_distance_km(double lat1_deg, double lon1_deg, double lat2_deg, double lon2_deg);

/// Hypocentral distance sqrt(R_epi^2 + depth^2), km: an approximation (flat Earth between the hypocentre and the
/// surface point), good to well under 1 % for depths and distances of a few tens of km.
[[nodiscard]] double hypocentral_distance_km(double epicentral_km, double depth_km) noexcept;

}  // namespace topple
