// The pooled PGA field and its iso-acceleration contours (field.hpp; docs/method.md, "Iso-acceleration contours").
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include <tbb/parallel_for.h>

#include <numbers>
#include <optional>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/region/field.hpp"
#include "topple/region/geodesy.hpp"

namespace topple {
namespace {

/// Solves K x = b for a symmetric positive-definite K by Cholesky (a dozen sites: no library needed; Boost.uBLAS,
/// the packaged option, does not compile under C++20's allocator). Throws InputError when K is not positive definite.
std::vector<double> solve_spd(std::vector<std::vector<double>> k, std::vector<double> b) {
  const std::size_t n = b.size();
  for (std::size_t j = 0; j < n; ++j) {
    for (std::size_t p = 0; p < j; ++p) k[j][j] -= k[j][p] * k[j][p];
    if (!(k[j][j] > 0.0)) throw InputError(InputLocation{{}, {}, "region"}, "the kriging matrix is not positive definite");
    k[j][j] = std::sqrt(k[j][j]);
    for (std::size_t i = j + 1; i < n; ++i) {
      for (std::size_t p = 0; p < j; ++p) k[i][j] -= k[i][p] * k[j][p];
      k[i][j] /= k[j][j];
    }
  }
  for (std::size_t i = 0; i < n; ++i) {  // L y = b
    for (std::size_t p = 0; p < i; ++p) b[i] -= k[i][p] * b[p];
    b[i] /= k[i][i];
  }
  for (std::size_t i = n; i-- > 0;) {  // L^T x = y
    for (std::size_t p = i + 1; p < n; ++p) b[i] -= k[p][i] * b[p];
    b[i] /= k[i][i];
  }
  return b;
}

}  // namespace

PooledField pooled_field(const RegionalResult& fit, const Survey& survey, double range_km, int points) {
  if (!survey.epicentre_lat_deg || !survey.epicentre_lon_deg) {
    throw InputError(InputLocation{{}, {}, "event.epicentre"}, "the pooled field needs the epicentre");
  }
  if (points < 2 || !(range_km > 0.0)) {
    throw InputError(InputLocation{{}, {}, "region"}, "the field needs >= 2 points a side and a positive range");
  }
  const double lat0 = *survey.epicentre_lat_deg, lon0 = *survey.epicentre_lon_deg;
  const double depth = survey.epicentre_depth_km.value_or(0.0);
  const std::size_t n = fit.sites.size();
  std::vector<double> slat(n), slon(n), resid(n), nugget(n);
  double lat_lo = lat0, lat_hi = lat0, lon_lo = lon0, lon_hi = lon0;
  // The relation at the posterior medians of (ln a_ref, c1): the medians of c0 and c1 taken separately are not a
  // consistent pair (c0 and c1 are strongly correlated); ln a_ref and c1 nearly are not.
  const double c1 = fit.c1.median;
  const double c0 = fit.ln_a_ref.median + c1 * std::log(fit.reference_distance_km);
  const double tau = fit.tau.median;
  for (std::size_t s = 0; s < n; ++s) {
    const Site& site = survey.sites.at(fit.sites[s].site_index);
    slat[s] = site.lat_deg.value();
    slon[s] = site.lon_deg.value();
    lat_lo = std::min(lat_lo, slat[s]);
    lat_hi = std::max(lat_hi, slat[s]);
    // The box in longitudes taken within 180 degrees of the epicentre's (issue 31): sites at 179.9 and -179.9 are
    // neighbours, not 360 degrees apart. The grid's longitudes may then pass +-180 (contours_for_geojson folds them).
    const double lon_u = lon0 + std::remainder(slon[s] - lon0, 360.0);
    lon_lo = std::min(lon_lo, lon_u);
    lon_hi = std::max(lon_hi, lon_u);
    resid[s] = std::log(fit.sites[s].pga_g.median) - std::log(relation_pga_g(c0, c1, fit.c2_km, fit.sites[s].distance_km));
    const double sd = std::log(fit.sites[s].pga_g.ci95_high / fit.sites[s].pga_g.ci95_low) / (2.0 * 1.959964);
    nugget[s] = sd * sd;
  }
  // Simple kriging (mean 0) of the residuals: weights K^-1 k(p), K = tau^2 rho(h_ij) + diag(nugget).
  std::vector<std::vector<double>> k(n, std::vector<double>(n, 0.0));
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      const double h = geodesic_distance_km(slat[i], slon[i], slat[j], slon[j]);
      k[i][j] = tau * tau * std::exp(-3.0 * h / range_km) + (i == j ? nugget[i] : 0.0);
    }
  }
  const std::vector<double> alpha = solve_spd(std::move(k), resid);

  PooledField f;
  f.range_km = range_km;
  const double pad_lat = std::max(0.2 * (lat_hi - lat_lo), 10.0 / 111.0);
  const double pad_lon = std::max(0.2 * (lon_hi - lon_lo), 10.0 / (111.0 * std::cos(deg_to_rad(lat0))));
  // Near a pole (issue 31) the padded box would pass latitude +-90 (where the geodesic is undefined: NaN nodes) and
  // the 10 km longitude pad grows without bound (1/cos(lat)): the latitudes stop at the pole, and a box whose
  // longitudes span 360 degrees or more (or whose pad is not finite) is the whole circle around the epicentre: a
  // polar cap, which the lat/lon grid represents exactly (docs/method.md, "Iso-acceleration contours").
  const double grid_lat_lo = std::max(lat_lo - pad_lat, -90.0), grid_lat_hi = std::min(lat_hi + pad_lat, 90.0);
  double grid_lon_lo = lon_lo - pad_lon, grid_lon_hi = lon_hi + pad_lon;
  if (!(grid_lon_hi - grid_lon_lo < 360.0)) {
    grid_lon_lo = lon0 - 180.0;
    grid_lon_hi = lon0 + 180.0;
  }
  for (int i = 0; i < points; ++i) {
    f.lat_deg.push_back(grid_lat_lo + (grid_lat_hi - grid_lat_lo) * i / (points - 1));
    f.lon_deg.push_back(grid_lon_lo + (grid_lon_hi - grid_lon_lo) * i / (points - 1));
  }
  f.pga_g.resize(static_cast<std::size_t>(points) * points);
  // Rows in parallel (oneTBB): every node is computed alone (deterministic).
  tbb::parallel_for(0, points, [&](int i) {
    for (int j = 0; j < points; ++j) {
      const double la = f.lat_deg[static_cast<std::size_t>(i)], lo = f.lon_deg[static_cast<std::size_t>(j)];
      const double rr = hypocentral_distance_km(geodesic_distance_km(lat0, lon0, la, lo), depth);
      double dz = 0.0;
      for (std::size_t s = 0; s < n; ++s) {
        dz += tau * tau * std::exp(-3.0 * geodesic_distance_km(la, lo, slat[s], slon[s]) / range_km) *
              alpha[s];
      }
      f.pga_g[static_cast<std::size_t>(i) * points + j] = relation_pga_g(c0, c1, fit.c2_km, rr) * std::exp(dz);
    }
  });
  return f;
}

std::vector<Contour> contour_field(const PooledField& f, const std::vector<double>& levels_g) {
  const std::size_t ny = f.lat_deg.size(), nx = f.lon_deg.size();
  std::vector<Contour> out;
  using Point = std::array<double, 2>;
  for (double level : levels_g) {
    Contour c;
    c.level_g = level;
    const double z0 = std::log(level);
    const auto z = [&](std::size_t i, std::size_t j) { return std::log(f.pga_g[i * nx + j]) - z0; };
    // Edge points keyed by the edge they lie on (so that neighbouring cells share them exactly): (i, j, dir), dir 0 =
    // the edge from node (i, j) to (i, j+1), dir 1 = from (i, j) to (i+1, j).
    using Key = std::array<std::size_t, 3>;
    const auto point = [&](const Key& e) -> Point {
      const std::size_t i = e[0], j = e[1];
      const std::size_t i2 = e[2] == 1 ? i + 1 : i, j2 = e[2] == 0 ? j + 1 : j;
      const double a = z(i, j), b = z(i2, j2);
      const double t = a / (a - b);
      return {f.lon_deg[j] + t * (f.lon_deg[j2] - f.lon_deg[j]), f.lat_deg[i] + t * (f.lat_deg[i2] - f.lat_deg[i])};
    };
    std::vector<std::pair<Key, Key>> segments;
    for (std::size_t i = 0; i + 1 < ny; ++i) {
      for (std::size_t j = 0; j + 1 < nx; ++j) {
        // Corners counter-clockwise: 0 (i, j), 1 (i, j+1), 2 (i+1, j+1), 3 (i+1, j); edges between them.
        const std::array<double, 4> v{z(i, j), z(i, j + 1), z(i + 1, j + 1), z(i + 1, j)};
        const std::array<Key, 4> edge{Key{i, j, 0}, Key{i, j + 1, 1}, Key{i + 1, j, 0}, Key{i, j, 1}};
        std::vector<int> crossed;
        for (int e = 0; e < 4; ++e) {
          if ((v[e] >= 0.0) != (v[(e + 1) % 4] >= 0.0)) crossed.push_back(e);
        }
        if (crossed.size() == 2) {
          segments.emplace_back(edge[crossed[0]], edge[crossed[1]]);
        } else if (crossed.size() == 4) {
          // A saddle: the centre's mean says which pairs of edges connect.
          const bool centre_above = (v[0] + v[1] + v[2] + v[3]) / 4.0 >= 0.0;
          if (centre_above == (v[0] >= 0.0)) {
            segments.emplace_back(edge[0], edge[1]);
            segments.emplace_back(edge[2], edge[3]);
          } else {
            segments.emplace_back(edge[3], edge[0]);
            segments.emplace_back(edge[1], edge[2]);
          }
        }
      }
    }
    // Join the segments into polylines through their shared edge points.
    std::multimap<Key, std::size_t> at;
    for (std::size_t s = 0; s < segments.size(); ++s) {
      at.emplace(segments[s].first, s);
      at.emplace(segments[s].second, s);
    }
    std::vector<bool> used(segments.size(), false);
    const auto next = [&](const Key& k, std::size_t from) -> std::optional<std::size_t> {
      const auto [lo, hi] = at.equal_range(k);
      for (auto it = lo; it != hi; ++it) {
        if (it->second != from && !used[it->second]) return it->second;
      }
      return std::nullopt;
    };
    for (std::size_t s = 0; s < segments.size(); ++s) {
      if (used[s]) continue;
      used[s] = true;
      std::vector<Key> keys{segments[s].first, segments[s].second};
      for (int dir = 0; dir < 2; ++dir) {  // grow forward from the end, then backward from the start
        std::size_t last = s;
        while (true) {
          const Key tip = keys.back();
          const auto n = next(tip, last);
          if (!n) break;
          used[*n] = true;
          keys.push_back(segments[*n].first == tip ? segments[*n].second : segments[*n].first);
          last = *n;
          if (keys.back() == keys.front()) break;  // closed
        }
        if (keys.back() == keys.front()) break;
        std::reverse(keys.begin(), keys.end());
      }
      std::vector<Point> line;
      line.reserve(keys.size());
      for (const Key& k : keys) line.push_back(point(k));
      c.lines.push_back(std::move(line));
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<std::vector<std::array<double, 2>>> split_at_antimeridian(const std::vector<std::array<double, 2>>& line) {
  using Point = std::array<double, 2>;
  // The 360-degree window [-180 + 360 w, 180 + 360 w) a longitude lies in, and the longitude within [-180, 180).
  const auto window = [](double lon) { return std::floor((lon + 180.0) / 360.0); };
  const auto wrap = [&](double lon) { return lon - 360.0 * window(lon); };
  std::vector<std::vector<Point>> out;
  std::vector<Point> piece;
  const auto add = [&](const Point& p) {
    if (piece.empty() || piece.back() != p) piece.push_back(p);
  };
  const auto close = [&] {
    if (piece.size() >= 2) out.push_back(std::move(piece));
    piece.clear();
  };
  for (std::size_t k = 0; k < line.size(); ++k) {
    const Point& b = line[k];
    if (k > 0) {
      // Each antimeridian (180 + 360 m, unwrapped) the segment from the previous point crosses cuts the line there,
      // at the latitude interpolated linearly along the segment (as the grid interpolates): one piece ends at +-180,
      // the next starts at -+180 (RFC 7946 section 3.1.9).
      const Point& a = line[k - 1];
      const double wa = window(a[0]), wb = window(b[0]);
      const bool east = wb > wa;
      for (double w = wa; w != wb; w += east ? 1.0 : -1.0) {
        const double cut = east ? 180.0 + 360.0 * w : -180.0 + 360.0 * w;
        const double lat = a[1] + (cut - a[0]) / (b[0] - a[0]) * (b[1] - a[1]);
        add({east ? 180.0 : -180.0, lat});
        close();
        add({east ? -180.0 : 180.0, lat});
      }
    }
    add({wrap(b[0]), b[1]});
  }
  close();
  return out;
}

}  // namespace topple
