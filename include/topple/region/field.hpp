#pragma once
// The pooled PGA field on a map and its iso-acceleration contours (docs/method.md, "Iso-acceleration contours"): what
// a regional fit (fit.hpp) says between and around its sites.
#include <array>
#include <vector>

#include "topple/region/fit.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// The pooled PGA field on a lat/lon grid (docs/method.md, "Iso-acceleration contours"): the relation at the posterior
/// medians of (ln a_ref, c1) plus the sites' residuals ln(pooled median) - mu_s interpolated by simple kriging with
/// the exponential correlation rho(h) = exp(-3 h / range_km) of Jayaram & Baker (2009) (range 8.5 km for PGA), sill
/// tau^2 (its posterior median) and each site's pooled variance as its nugget. Far from every site the field is the
/// relation.
struct PooledField {
  std::vector<double> lat_deg;  ///< grid rows, increasing
  std::vector<double> lon_deg;  ///< grid columns, increasing
  std::vector<double> pga_g;    ///< index row * lon_deg.size() + column, g
  double range_km = 0.0;        ///< the correlation range used, km
};

/// Jayaram & Baker (2009)'s range for PGA without clustered Vs30 (b = 8.5 + 17.2 T at T = 0), km.
inline constexpr double kPgaCorrelationRangeKm = 8.5;

/// The field over the box of the fitted sites and the epicentre, widened by a fifth of its size each side (at least
/// 10 km), `points` x `points` nodes. Needs survey.epicentre and the sites' coordinates (fit_survey_region's sites).
[[nodiscard]] PooledField pooled_field(const RegionalResult& fit, const Survey& survey,
                                       double range_km = kPgaCorrelationRangeKm, int points = 121);

/// One level's iso-acceleration lines: polylines of [lon, lat] points (closed ones end where they start).
struct Contour {
  double level_g = 0.0;
  std::vector<std::vector<std::array<double, 2>>> lines;
};

/// Contours of the field at the given levels (g) by marching squares on ln PGA (linear interpolation along the cell
/// edges; a saddle cell is resolved by its centre's mean), the segments joined into polylines.
[[nodiscard]] std::vector<Contour> contour_field(const PooledField& field, const std::vector<double>& levels_g);

/// A polyline of [lon, lat] points in the grid's continuous longitudes (which may pass +-180 where the sites straddle
/// the antimeridian, pooled_field) as GeoJSON wants it (RFC 7946 section 3.1.9): longitudes in [-180, 180), and cut
/// into pieces wherever it crosses the antimeridian, each cut at the latitude interpolated along its segment, the
/// piece ending at +-180 and the next one starting at -+180. A line that crosses nothing comes back whole.
[[nodiscard]] std::vector<std::vector<std::array<double, 2>>> split_at_antimeridian(
    const std::vector<std::array<double, 2>>& line);

}  // namespace topple
