// Distances on the WGS84 ellipsoid (geodesy.hpp).
#include "topple/region/geodesy.hpp"

#include <cmath>

#include <GeographicLib/Geodesic.hpp>

namespace topple {

double geodesic_distance_km(double lat1, double lon1, double lat2, double lon2) {
  double s12_m = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, s12_m);
  return s12_m / 1000.0;
}

double hypocentral_distance_km(double epicentral_km, double depth_km) noexcept {
  return std::hypot(epicentral_km, depth_km);
}

}  // namespace topple
