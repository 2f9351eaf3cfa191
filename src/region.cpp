// The regional joint inversion (region.hpp has the model; docs/method.md, "Regional joint inversion", the equations).
#include "topple/region.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>

#include <GeographicLib/Geodesic.hpp>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "topple/error.hpp"

namespace topple {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Phi(b) - Phi(a) for a <= b, the standard normal's mass on [a, b], computed in the tail nearer to the interval so
/// that two CDF values near 1 are not subtracted (erfc keeps the relative precision of a small tail).
double normal_mass(double a, double b) noexcept {
  if (a >= 0.0) return 0.5 * (std::erfc(a / std::numbers::sqrt2) - std::erfc(b / std::numbers::sqrt2));
  if (b <= 0.0) return 0.5 * (std::erfc(-b / std::numbers::sqrt2) - std::erfc(-a / std::numbers::sqrt2));
  return 1.0 - 0.5 * (std::erfc(-a / std::numbers::sqrt2) + std::erfc(b / std::numbers::sqrt2));
}

double normal_cdf(double z) noexcept { return 0.5 * std::erfc(-z / std::numbers::sqrt2); }

/// The Gaussian over ln a_s that the relation (mu, tau) and the instrument, if any, give together: N(m, s^2) times
/// the constant exp(log_scale) (docs/method.md eq. R3: the product of two normal densities in ln a).
struct SiteGaussian {
  double m = 0.0, s = 1.0, log_scale = 0.0;
};

SiteGaussian site_gaussian(const SiteEvidence& e, double mu, double tau, double sigma_i) noexcept {
  if (!e.instrument_pga_g) return {mu, tau, 0.0};
  const double y = std::log(*e.instrument_pga_g);
  const double v = tau * tau + sigma_i * sigma_i;
  SiteGaussian g;
  g.log_scale = -0.5 * (y - mu) * (y - mu) / v - 0.5 * std::log(2.0 * std::numbers::pi * v);
  g.m = (mu * sigma_i * sigma_i + y * tau * tau) / v;
  g.s = std::sqrt(tau * tau * sigma_i * sigma_i / v);
  return g;
}

/// ln of the site's marginal likelihood given (mu, tau): eq. R3, sum over cells of L_i times the Gaussian's mass.
double site_log_marginal(const SiteEvidence& e, double mu, double tau, double sigma_i) noexcept {
  const SiteGaussian g = site_gaussian(e, mu, tau, sigma_i);
  if (e.ln_edges.empty()) return g.log_scale;
  double sum = 0.0;
  for (std::size_t i = 0; i < e.likelihood.size(); ++i) {
    if (e.likelihood[i] == 0.0) continue;
    sum += e.likelihood[i] * normal_mass((e.ln_edges[i] - g.m) / g.s, (e.ln_edges[i + 1] - g.m) / g.s);
  }
  return g.log_scale + (sum > 0.0 ? std::log(sum) : -kInf);
}

/// Quantiles of a distribution given as point masses (value, weight), each spread uniformly over value +- half
/// (half = 0: points). Linear interpolation of the CDF between the cells' ends.
Interval95 quantiles(std::vector<std::pair<double, double>> mass, double half) {
  std::sort(mass.begin(), mass.end());
  double total = 0.0;
  for (const auto& [v, w] : mass) total += w;
  // The CDF at cell ends: for point masses, the midpoints between successive values (a standard interpolation).
  const auto q = [&](double p) {
    double cum = 0.0;
    for (std::size_t i = 0; i < mass.size(); ++i) {
      const double w = mass[i].second / total;
      if (cum + w >= p && w > 0.0) {
        const double lo = half > 0.0 ? mass[i].first - half : (i == 0 ? mass[i].first : 0.5 * (mass[i - 1].first + mass[i].first));
        const double hi = half > 0.0 ? mass[i].first + half
                                     : (i + 1 == mass.size() ? mass[i].first : 0.5 * (mass[i].first + mass[i + 1].first));
        return lo + (hi - lo) * (p - cum) / w;
      }
      cum += w;
    }
    return mass.back().first + half;
  };
  return {q(0.5), q(0.16), q(0.84), q(0.025), q(0.975)};
}

/// Quantiles of a CDF tabulated on an increasing grid x (linear interpolation; clamped to the grid's ends).
Interval95 cdf_quantiles(const std::vector<double>& x, const std::vector<double>& cdf) {
  const auto q = [&](double p) {
    const auto it = std::lower_bound(cdf.begin(), cdf.end(), p);
    if (it == cdf.begin()) return x.front();
    if (it == cdf.end()) return x.back();
    const std::size_t k = static_cast<std::size_t>(it - cdf.begin());
    const double f = (p - cdf[k - 1]) / std::max(cdf[k] - cdf[k - 1], 1e-300);
    return x[k - 1] + f * (x[k] - x[k - 1]);
  };
  return {q(0.5), q(0.16), q(0.84), q(0.025), q(0.975)};
}

Interval95 exp_of(const Interval95& v) {
  return {std::exp(v.median), std::exp(v.ci68_low), std::exp(v.ci68_high), std::exp(v.ci95_low), std::exp(v.ci95_high)};
}

/// One grid over (ln a_ref, c1, tau): n points per parameter from lo to hi.
struct Grid3 {
  std::array<double, 3> lo{}, hi{};
  int n = 0;
  [[nodiscard]] double step(int d) const { return (hi[d] - lo[d]) / (n - 1); }
  [[nodiscard]] double value(int d, int i) const { return lo[d] + step(d) * i; }
};

}  // namespace

double geodesic_distance_km(double lat1, double lon1, double lat2, double lon2) {
  double s12_m = 0.0;
  GeographicLib::Geodesic::WGS84().Inverse(lat1, lon1, lat2, lon2, s12_m);
  return s12_m / 1000.0;
}

double hypocentral_distance_km(double epicentral_km, double depth_km) noexcept {
  return std::hypot(epicentral_km, depth_km);
}

double relation_pga_g(double c0, double c1, double c2_km, double distance_km) noexcept {
  return std::exp(c0 - c1 * std::log(std::hypot(distance_km, c2_km)));
}

bool objects_agree_with_instrument(const Estimate& e, double pga_g) noexcept {
  return (!e.ci95_low || *e.ci95_low <= pga_g) && (!e.ci95_high || pga_g <= *e.ci95_high);
}

SiteEvidence site_evidence(const std::string& name, double distance_km, const InversionResult* objects,
                           std::optional<double> instrument_pga_g) {
  SiteEvidence e;
  e.name = name;
  e.distance_km = distance_km;
  e.instrument_pga_g = instrument_pga_g;
  if (objects == nullptr) return e;
  const std::size_t np = objects->pga_g.size(), nf = objects->freq_hz.size();
  double max_ll = -kInf;
  for (double v : objects->log_likelihood) max_ll = std::max(max_ll, v);
  // L_i = mean over the frequency columns of exp(log_likelihood): the frequency marginalised with its prior (uniform
  // in log frequency, the inversion's own), up to a constant.
  e.likelihood.assign(np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) e.likelihood[i] += std::exp(objects->log_likelihood[i * nf + j] - max_ll);
  }
  const double peak = *std::max_element(e.likelihood.begin(), e.likelihood.end());
  for (double& l : e.likelihood) l /= peak;
  e.ln_edges.assign(np + 1, 0.0);
  e.ln_edges.front() = -kInf;
  e.ln_edges.back() = kInf;
  for (std::size_t i = 1; i < np; ++i) e.ln_edges[i] = 0.5 * (std::log(objects->pga_g[i - 1]) + std::log(objects->pga_g[i]));
  return e;
}

RegionalResult fit_region(const std::vector<SiteEvidence>& sites, const RegionalSettings& st) {
  if (sites.size() < 3) {
    throw InputError(InputLocation{{}, {}, "region"},
                     fmt::format("a regional fit needs at least 3 located sites (c0, c1 and tau), got {}", sites.size()));
  }
  RegionalResult out;
  out.c2_km = st.c2_km;
  std::vector<double> ln_rho(sites.size());
  double mean_ln_rho = 0.0;
  for (std::size_t s = 0; s < sites.size(); ++s) {
    ln_rho[s] = std::log(std::hypot(sites[s].distance_km, st.c2_km));
    mean_ln_rho += ln_rho[s] / static_cast<double>(sites.size());
  }
  out.reference_distance_km = std::exp(mean_ln_rho);
  const double sigma_i = st.instrument_sigma_ln;

  const auto log_post = [&](double x, double c1, double tau) {
    double lp = 0.0;
    for (std::size_t s = 0; s < sites.size(); ++s) {
      lp += site_log_marginal(sites[s], x - c1 * (ln_rho[s] - mean_ln_rho), tau, sigma_i);
    }
    return lp;  // flat prior on the box
  };
  const auto evaluate = [&](const Grid3& g) {
    std::vector<double> lp(static_cast<std::size_t>(g.n) * g.n * g.n);
    // Rows in parallel (oneTBB): every point is computed alone, so the result does not depend on the threads.
    tbb::parallel_for(0, g.n, [&](int i) {
      for (int j = 0; j < g.n; ++j) {
        for (int k = 0; k < g.n; ++k) {
          lp[(static_cast<std::size_t>(i) * g.n + j) * g.n + k] = log_post(g.value(0, i), g.value(1, j), g.value(2, k));
        }
      }
    });
    return lp;
  };
  // Pass 1: the whole prior box, coarse (25 points a side), to find where the posterior lives.
  Grid3 coarse{{st.ln_a_ref_min, st.c1_min, st.tau_min}, {st.ln_a_ref_max, st.c1_max, st.tau_max}, 25};
  const std::vector<double> lp1 = evaluate(coarse);
  const double max1 = *std::max_element(lp1.begin(), lp1.end());
  if (!std::isfinite(max1)) {
    throw InputError(InputLocation{{}, {}, "region"}, "no relation in the prior box explains every site (the sites' "
                                                      "likelihoods vanish everywhere)");
  }
  std::array<int, 3> imin{coarse.n, coarse.n, coarse.n}, imax{-1, -1, -1};
  for (int i = 0; i < coarse.n; ++i) {
    for (int j = 0; j < coarse.n; ++j) {
      for (int k = 0; k < coarse.n; ++k) {
        if (lp1[(static_cast<std::size_t>(i) * coarse.n + j) * coarse.n + k] < max1 - 20.0) continue;
        const std::array<int, 3> idx{i, j, k};
        for (int d = 0; d < 3; ++d) {
          imin[d] = std::min(imin[d], idx[d]);
          imax[d] = std::max(imax[d], idx[d]);
        }
      }
    }
  }
  // Pass 2: that box widened by one coarse step (a posterior narrower than a coarse step still gets a fine grid).
  Grid3 fine;
  fine.n = st.fine_points;
  for (int d = 0; d < 3; ++d) {
    fine.lo[d] = coarse.value(d, std::max(0, imin[d] - 1));
    fine.hi[d] = coarse.value(d, std::min(coarse.n - 1, imax[d] + 1));
  }
  const std::vector<double> lp2 = evaluate(fine);
  out.grid_points = lp1.size() + lp2.size();
  const double max2 = *std::max_element(lp2.begin(), lp2.end());
  std::vector<double> w(lp2.size());
  double total = 0.0;
  for (std::size_t c = 0; c < w.size(); ++c) total += (w[c] = std::exp(lp2[c] - max2));
  for (double& v : w) v /= total;

  // Marginals: each grid value's mass spread over its cell (half a step each side), cut at the prior's edges.
  std::array<std::vector<std::pair<double, double>>, 3> marg;
  for (int d = 0; d < 3; ++d) {
    marg[d].resize(static_cast<std::size_t>(fine.n));
    for (int i = 0; i < fine.n; ++i) marg[d][static_cast<std::size_t>(i)] = {fine.value(d, i), 0.0};
  }
  std::vector<std::pair<double, double>> c0_mass(w.size());
  for (int i = 0; i < fine.n; ++i) {
    for (int j = 0; j < fine.n; ++j) {
      for (int k = 0; k < fine.n; ++k) {
        const std::size_t c = (static_cast<std::size_t>(i) * fine.n + j) * fine.n + k;
        marg[0][static_cast<std::size_t>(i)].second += w[c];
        marg[1][static_cast<std::size_t>(j)].second += w[c];
        marg[2][static_cast<std::size_t>(k)].second += w[c];
        c0_mass[c] = {fine.value(0, i) + fine.value(1, j) * mean_ln_rho, w[c]};
      }
    }
  }
  const std::array<double, 3> prior_lo{st.ln_a_ref_min, st.c1_min, st.tau_min};
  const std::array<double, 3> prior_hi{st.ln_a_ref_max, st.c1_max, st.tau_max};
  std::array<Interval95, 3> est;
  for (int d = 0; d < 3; ++d) {
    est[d] = quantiles(marg[d], 0.5 * fine.step(d));
    for (double* v : {&est[d].median, &est[d].ci68_low, &est[d].ci68_high, &est[d].ci95_low, &est[d].ci95_high}) {
      *v = std::clamp(*v, prior_lo[d], prior_hi[d]);
    }
  }
  out.ln_a_ref = est[0];
  out.c1 = est[1];
  out.tau = est[2];
  out.c0 = quantiles(std::move(c0_mass), 0.0);
  const std::array<const char*, 3> names{"ln a_ref", "c1", "tau"};
  for (int d = 0; d < 3; ++d) {
    const double h = fine.step(d);
    if (est[d].ci95_low <= prior_lo[d] + h || est[d].ci95_high >= prior_hi[d] - h) {
      out.notes.push_back(fmt::format("{}'s 95 % interval [{:.3g}, {:.3g}] reaches its prior's edge ([{:.3g}, {:.3g}]): "
                                      "the sites do not constrain it there; that end is the prior's",
                                      names[d], est[d].ci95_low, est[d].ci95_high, prior_lo[d], prior_hi[d]));
    }
  }

  // The relation's band for the attenuation figure.
  {
    double r_lo = 1.0, r_hi = 0.0;
    for (const SiteEvidence& e : sites) {
      r_lo = std::min(r_lo, e.distance_km);
      r_hi = std::max(r_hi, e.distance_km);
    }
    r_lo = std::max(r_lo, 0.1);
    r_hi = std::max(1.5 * r_hi, 2.0 * r_lo);
    std::vector<std::pair<double, double>> mass(static_cast<std::size_t>(fine.n) * fine.n);
    for (int q = 0; q < 40; ++q) {
      const double r = r_lo * std::pow(r_hi / r_lo, q / 39.0);
      const double lr = std::log(std::hypot(r, st.c2_km)) - mean_ln_rho;
      for (int i = 0; i < fine.n; ++i) {
        for (int j = 0; j < fine.n; ++j) {
          const double mu = fine.value(0, i) - fine.value(1, j) * lr;
          double wij = 0.0;
          for (int k = 0; k < fine.n; ++k) wij += w[(static_cast<std::size_t>(i) * fine.n + j) * fine.n + k];
          mass[static_cast<std::size_t>(i) * fine.n + j] = {mu, wij};
        }
      }
      out.curve_distance_km.push_back(r);
      out.curve_pga_g.push_back(exp_of(quantiles(mass, 0.0)));
    }
  }

  // Draws of theta by systematic resampling of the fine grid (deterministic: u_m = (m + 1/2) / M).
  std::vector<std::size_t> draws(static_cast<std::size_t>(st.draws));
  {
    double cum = 0.0;
    std::size_t c = 0;
    for (std::size_t m = 0; m < draws.size(); ++m) {
      const double u = (static_cast<double>(m) + 0.5) / static_cast<double>(draws.size());
      while (c + 1 < w.size() && cum + w[c] < u) cum += w[c++];
      draws[m] = c;
    }
  }
  const auto theta = [&](std::size_t c) {
    const int k = static_cast<int>(c % fine.n);
    const int j = static_cast<int>((c / fine.n) % fine.n);
    const int i = static_cast<int>(c / (static_cast<std::size_t>(fine.n) * fine.n));
    return std::array<double, 3>{fine.value(0, i), fine.value(1, j), fine.value(2, k)};
  };
  // The pooled CDF on ln a from ln 1e-4 g to ln 20 g, step 0.01 (a 1 % step in PGA).
  std::vector<double> xs;
  for (double x = std::log(1e-4); x <= std::log(20.0); x += 0.01) xs.push_back(x);
  out.sites.resize(sites.size());
  // Sites in parallel (oneTBB): each site's pooled posterior is computed alone (deterministic).
  tbb::parallel_for(std::size_t{0}, sites.size(), [&](std::size_t s) {
    const SiteEvidence& e = sites[s];
    std::vector<double> cdf(xs.size(), 0.0);
    std::vector<std::pair<double, double>> mu_mass(w.size());
    for (std::size_t c = 0; c < w.size(); ++c) {
      const auto t = theta(c);
      mu_mass[c] = {t[0] - t[1] * (ln_rho[s] - mean_ln_rho), w[c]};
    }
    const bool cells = !e.ln_edges.empty();
    const std::vector<double> edges = cells ? e.ln_edges : std::vector<double>{-kInf, kInf};
    const std::vector<double> lik = cells ? e.likelihood : std::vector<double>{1.0};
    std::vector<double> cell_mass(lik.size());
    for (const std::size_t c : draws) {
      const auto t = theta(c);
      const SiteGaussian g = site_gaussian(e, t[0] - t[1] * (ln_rho[s] - mean_ln_rho), t[2], sigma_i);
      double z = 0.0;
      for (std::size_t i = 0; i < lik.size(); ++i) {
        cell_mass[i] = lik[i] * normal_mass((edges[i] - g.m) / g.s, (edges[i + 1] - g.m) / g.s);
        z += cell_mass[i];
      }
      if (!(z > 0.0)) continue;
      // F(x | theta) = (sum of the cells wholly below x + the part of x's cell below x) / z.
      std::size_t cell = 0;
      double below = 0.0;
      for (std::size_t k = 0; k < xs.size(); ++k) {
        while (cell + 1 < lik.size() && edges[cell + 1] <= xs[k]) below += cell_mass[cell++];
        const double part = lik[cell] * (normal_cdf((xs[k] - g.m) / g.s) - normal_cdf((edges[cell] - g.m) / g.s));
        cdf[k] += (below + std::max(0.0, part)) / z / static_cast<double>(draws.size());
      }
    }
    for (std::size_t k = 1; k < cdf.size(); ++k) cdf[k] = std::max(cdf[k], cdf[k - 1]);  // rounding: keep it monotone
    PooledSite p;
    p.name = e.name;
    p.site_index = s;
    p.distance_km = e.distance_km;
    p.instrument_pga_g = e.instrument_pga_g;
    p.pga_g = exp_of(cdf_quantiles(xs, cdf));
    p.relation_pga_g = exp_of(quantiles(std::move(mu_mass), 0.0));
    out.sites[s] = p;
  });
  return out;
}

std::optional<RegionalResult> fit_survey_region(const Survey& survey,
                                                const std::vector<const InversionResult*>& results,
                                                std::vector<std::string>& notes, const RegionalSettings& settings) {
  if (survey.sites.size() < 2) return std::nullopt;  // a one-site survey: no regional picture, nothing to say
  if (!survey.epicentre_lat_deg || !survey.epicentre_lon_deg) {
    notes.push_back("no regional fit: the survey gives no [event] epicentre = [lat, lon]");
    return std::nullopt;
  }
  const double depth = survey.epicentre_depth_km.value_or(0.0);
  std::vector<SiteEvidence> evidence;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < survey.sites.size(); ++i) {
    const Site& site = survey.sites[i];
    if (!site.lat_deg || !site.lon_deg) {
      notes.push_back(fmt::format("regional fit: site '{}' has no lat/lon and is left out", site.name));
      continue;
    }
    const double r = hypocentral_distance_km(
        geodesic_distance_km(*survey.epicentre_lat_deg, *survey.epicentre_lon_deg, *site.lat_deg, *site.lon_deg), depth);
    evidence.push_back(site_evidence(site.name, r, results.at(i), site.instrument_pga_g));
    index.push_back(i);
  }
  if (evidence.size() < 3) {
    notes.push_back(fmt::format("no regional fit: it needs at least 3 located sites, the survey has {}", evidence.size()));
    return std::nullopt;
  }
  RegionalResult fit = fit_region(evidence, settings);
  for (std::size_t k = 0; k < fit.sites.size(); ++k) fit.sites[k].site_index = index[k];
  return fit;
}

}  // namespace topple
