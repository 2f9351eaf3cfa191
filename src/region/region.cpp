// The regional joint inversion (fit.hpp has the model; docs/method.md, "Regional joint inversion", the equations).
#include "topple/region/fit.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "topple/core/error.hpp"
#include "topple/numerics/statistics.hpp"

namespace topple {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// f(i, mass_i) for each cell [edges_i, edges_i+1] with mass_i the N(m, s^2) mass on it, Phi(b) - Phi(a) of the
/// standardised edges a <= b computed in the tail nearer to the cell, so that two CDF values near 1 are not
/// subtracted (erfc keeps the relative precision of a small tail): both ends' upper tails when a >= 0, both lower
/// tails when b <= 0, 1 minus both outer tails otherwise. Each edge's tail is then always its far one, so one erfc per
/// edge serves both cells beside it (the grid fit's inner loop).
template <class F>
void for_each_cell_mass(const std::vector<double>& edges, double m, double s, F&& f) {
  const auto tail = [](double z) { return 0.5 * std::erfc(std::abs(z) / std::numbers::sqrt2); };
  double za = (edges[0] - m) / s;
  double ta = tail(za);
  for (std::size_t i = 0; i + 1 < edges.size(); ++i) {
    const double zb = (edges[i + 1] - m) / s;
    const double tb = tail(zb);
    f(i, za >= 0.0 ? ta - tb : (zb <= 0.0 ? tb - ta : 1.0 - (ta + tb)));
    za = zb;
    ta = tb;
  }
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

/// One grid over (x_ref, slope, tau): n[d] points per parameter from lo to hi (n[d] = 1: the parameter fixed at lo).
struct Grid3 {
  std::array<double, 3> lo{}, hi{};
  std::array<int, 3> n{};
  [[nodiscard]] double step(int d) const { return n[d] > 1 ? (hi[d] - lo[d]) / (n[d] - 1) : 0.0; }
  [[nodiscard]] double value(int d, int i) const { return lo[d] + step(d) * i; }
  [[nodiscard]] std::size_t size() const { return static_cast<std::size_t>(n[0]) * n[1] * n[2]; }
  [[nodiscard]] std::size_t index(int i, int j, int k) const { return (static_cast<std::size_t>(i) * n[1] + j) * n[2] + k; }
  [[nodiscard]] std::array<double, 3> theta(std::size_t c) const {
    const int k = static_cast<int>(c % n[2]);
    const int j = static_cast<int>((c / n[2]) % n[1]);
    const int i = static_cast<int>(c / (static_cast<std::size_t>(n[1]) * n[2]));
    return {value(0, i), value(1, j), value(2, k)};
  }
};

/// One site's evidence on one axis (ln PGA or ln frequency): cells (edges, likelihood; empty: none) and an optional
/// direct lognormal observation of the log value (an instrument's PGA, an intensity's, or both combined) with its
/// own sigma (natural-log units; 0: the problem's direct_sigma).
struct AxisSite {
  const std::vector<double>* edges = nullptr;
  const std::vector<double>* likelihood = nullptr;
  std::optional<double> direct_ln;
  double direct_sigma = 0.0;
};

/// A lognormal relation ln v_s = x + sign * p * dx_s + e_s, e_s ~ N(0, tau^2), dx_s = ln rho_s - ln rho_ref, fitted
/// by grid integration over (x, p, tau) with a uniform prior on the box [lo, hi] (header; docs/method.md eqs. R2-R3, F1).
struct RelationProblem {
  std::vector<AxisSite> sites;
  std::vector<double> dx;
  double sign = -1.0;
  std::array<double, 3> prior_lo{}, prior_hi{};
  bool fixed_slope = false;  ///< p fixed at prior_lo[1] (the constant model of the frequency comparison)
  double direct_sigma = 0.05;
  int fine_points = 41;
};

struct RelationPosterior {
  Grid3 fine;
  std::vector<double> w;                ///< normalised posterior weights on the fine grid
  std::array<Interval95, 3> est;        ///< x, p, tau
  Interval95 intercept;                 ///< x - sign p ln rho_ref (c0 or d0)
  double log_evidence = 0.0;            ///< ln of the marginal likelihood (prior-averaged), header
  std::size_t grid_points = 0;
  std::array<bool, 3> at_edge{};        ///< the 95 % interval reaches the prior's edge
};

/// The Gaussian over ln v_s that the relation (mu, tau) and the direct observation, if any, give together: N(m, s^2)
/// times the constant exp(log_scale) (docs/method.md eq. R3: the product of two normal densities in ln v).
struct SiteGaussian {
  double m = 0.0, s = 1.0, log_scale = 0.0;
};

SiteGaussian site_gaussian(const AxisSite& e, double mu, double tau, double sigma_i) noexcept {
  if (!e.direct_ln) return {mu, tau, 0.0};
  const double y = *e.direct_ln;
  if (e.direct_sigma > 0.0) sigma_i = e.direct_sigma;
  const double v = tau * tau + sigma_i * sigma_i;
  SiteGaussian g;
  g.log_scale = -0.5 * (y - mu) * (y - mu) / v - 0.5 * std::log(2.0 * std::numbers::pi * v);
  g.m = (mu * sigma_i * sigma_i + y * tau * tau) / v;
  g.s = std::sqrt(tau * tau * sigma_i * sigma_i / v);
  return g;
}

bool has_cells(const AxisSite& e) noexcept { return e.edges != nullptr && !e.edges->empty(); }

/// ln of the site's marginal likelihood given (mu, tau): eq. R3, sum over cells of L_i times the Gaussian's mass.
double site_log_marginal(const AxisSite& e, double mu, double tau, double sigma_i) noexcept {
  const SiteGaussian g = site_gaussian(e, mu, tau, sigma_i);
  if (!has_cells(e)) return g.log_scale;
  const std::vector<double>& edges = *e.edges;
  const std::vector<double>& lik = *e.likelihood;
  double sum = 0.0;
  for_each_cell_mass(edges, g.m, g.s, [&](std::size_t i, double mass) {
    if (lik[i] != 0.0) sum += lik[i] * mass;
  });
  return g.log_scale + (sum > 0.0 ? std::log(sum) : -kInf);
}

RelationPosterior fit_relation(const RelationProblem& pr) {
  const auto log_post = [&](double x, double p, double tau) {
    double lp = 0.0;
    for (std::size_t s = 0; s < pr.sites.size(); ++s) {
      lp += site_log_marginal(pr.sites[s], x + pr.sign * p * pr.dx[s], tau, pr.direct_sigma);
    }
    return lp;  // flat prior on the box
  };
  const auto evaluate = [&](const Grid3& g) {
    std::vector<double> lp(g.size());
    // Rows in parallel (oneTBB): every point is computed alone, so the result does not depend on the threads.
    tbb::parallel_for(0, g.n[0], [&](int i) {
      for (int j = 0; j < g.n[1]; ++j) {
        for (int k = 0; k < g.n[2]; ++k) lp[g.index(i, j, k)] = log_post(g.value(0, i), g.value(1, j), g.value(2, k));
      }
    });
    return lp;
  };
  const int n_slope = pr.fixed_slope ? 1 : 25;
  // Pass 1: the whole prior box, coarse (25 points a side), to find where the posterior lives.
  Grid3 coarse{pr.prior_lo, pr.prior_hi, {25, n_slope, 25}};
  const std::vector<double> lp1 = evaluate(coarse);
  const double max1 = *std::max_element(lp1.begin(), lp1.end());
  if (!std::isfinite(max1)) {
    throw InputError(InputLocation{{}, {}, "region"}, "no relation in the prior box explains every site (the sites' "
                                                      "likelihoods vanish everywhere)");
  }
  std::array<int, 3> imin{coarse.n[0], coarse.n[1], coarse.n[2]}, imax{-1, -1, -1};
  for (int i = 0; i < coarse.n[0]; ++i) {
    for (int j = 0; j < coarse.n[1]; ++j) {
      for (int k = 0; k < coarse.n[2]; ++k) {
        if (lp1[coarse.index(i, j, k)] < max1 - 20.0) continue;
        const std::array<int, 3> idx{i, j, k};
        for (int d = 0; d < 3; ++d) {
          imin[d] = std::min(imin[d], idx[d]);
          imax[d] = std::max(imax[d], idx[d]);
        }
      }
    }
  }
  // Pass 2: that box widened by one coarse step (a posterior narrower than a coarse step still gets a fine grid).
  RelationPosterior out;
  Grid3& fine = out.fine;
  for (int d = 0; d < 3; ++d) {
    fine.n[d] = coarse.n[d] == 1 ? 1 : pr.fine_points;
    fine.lo[d] = coarse.value(d, std::max(0, imin[d] - 1));
    fine.hi[d] = coarse.value(d, std::min(coarse.n[d] - 1, imax[d] + 1));
  }
  const std::vector<double> lp2 = evaluate(fine);
  out.grid_points = lp1.size() + lp2.size();
  const double max2 = *std::max_element(lp2.begin(), lp2.end());
  std::vector<double>& w = out.w;
  w.resize(lp2.size());
  double total = 0.0;
  for (std::size_t c = 0; c < w.size(); ++c) total += (w[c] = std::exp(lp2[c] - max2));
  // The marginal likelihood Z = (1 / V_prior) * integral of exp(ln L) over the free parameters (eq. F3): trapezoid
  // weights on the fine grid (it holds all but e^-20 of the mass), the prior's density 1 / V_prior.
  {
    double z = 0.0;
    for (std::size_t c = 0; c < w.size(); ++c) {
      const int k = static_cast<int>(c % fine.n[2]);
      const int j = static_cast<int>((c / fine.n[2]) % fine.n[1]);
      const int i = static_cast<int>(c / (static_cast<std::size_t>(fine.n[1]) * fine.n[2]));
      double t = 1.0;
      const std::array<int, 3> idx{i, j, k};
      for (int d = 0; d < 3; ++d) {
        if (fine.n[d] > 1 && (idx[d] == 0 || idx[d] == fine.n[d] - 1)) t *= 0.5;
      }
      z += t * w[c];
    }
    out.log_evidence = max2 + std::log(z);
    for (int d = 0; d < 3; ++d) {
      if (fine.n[d] > 1) out.log_evidence += std::log(fine.step(d)) - std::log(pr.prior_hi[d] - pr.prior_lo[d]);
    }
  }
  for (double& v : w) v /= total;

  // Marginals: each grid value's mass spread over its cell (half a step each side), cut at the prior's edges.
  std::array<std::vector<std::pair<double, double>>, 3> marg;
  for (int d = 0; d < 3; ++d) {
    marg[d].resize(static_cast<std::size_t>(fine.n[d]));
    for (int i = 0; i < fine.n[d]; ++i) marg[d][static_cast<std::size_t>(i)] = {fine.value(d, i), 0.0};
  }
  for (int i = 0; i < fine.n[0]; ++i) {
    for (int j = 0; j < fine.n[1]; ++j) {
      for (int k = 0; k < fine.n[2]; ++k) {
        const std::size_t c = fine.index(i, j, k);
        marg[0][static_cast<std::size_t>(i)].second += w[c];
        marg[1][static_cast<std::size_t>(j)].second += w[c];
        marg[2][static_cast<std::size_t>(k)].second += w[c];
      }
    }
  }
  for (int d = 0; d < 3; ++d) {
    out.est[d] = quantiles(marg[d], 0.5 * fine.step(d));
    for (double* v : {&out.est[d].median, &out.est[d].ci68_low, &out.est[d].ci68_high, &out.est[d].ci95_low,
                      &out.est[d].ci95_high}) {
      *v = std::clamp(*v, pr.prior_lo[d], pr.prior_hi[d]);
    }
    const double h = fine.step(d);
    out.at_edge[d] = fine.n[d] > 1 && (out.est[d].ci95_low <= pr.prior_lo[d] + h || out.est[d].ci95_high >= pr.prior_hi[d] - h);
  }
  return out;
}

/// The intercept (c0 or d0) x - sign p ln rho_ref over the fine grid's points.
Interval95 intercept_of(const RelationPosterior& post, double sign, double ln_rho_ref) {
  std::vector<std::pair<double, double>> mass(post.w.size());
  for (std::size_t c = 0; c < post.w.size(); ++c) {
    const auto t = post.fine.theta(c);
    mass[c] = {t[0] - sign * t[1] * ln_rho_ref, post.w[c]};
  }
  return quantiles(std::move(mass), 0.0);
}

/// Draws of theta by systematic resampling of the fine grid (deterministic: u_m = (m + 1/2) / M).
std::vector<std::size_t> systematic_draws(const std::vector<double>& w, int count) {
  std::vector<std::size_t> draws(static_cast<std::size_t>(count));
  double cum = 0.0;
  std::size_t c = 0;
  for (std::size_t m = 0; m < draws.size(); ++m) {
    const double u = (static_cast<double>(m) + 0.5) / static_cast<double>(draws.size());
    while (c + 1 < w.size() && cum + w[c] < u) cum += w[c++];
    draws[m] = c;
  }
  return draws;
}

/// A site's pooled posterior of ln v (the posterior average of its conditional given theta and its own evidence),
/// tabulated as a CDF on xs, and the relation's prediction mu_s over the posterior: both as quantiles in ln v.
std::pair<Interval95, Interval95> pooled_site(const RelationProblem& pr, const RelationPosterior& post,
                                              const std::vector<std::size_t>& draws, std::size_t s,
                                              const std::vector<double>& xs) {
  const AxisSite& e = pr.sites[s];
  const std::vector<double>& w = post.w;
  std::vector<double> cdf(xs.size(), 0.0);
  std::vector<std::pair<double, double>> mu_mass(w.size());
  for (std::size_t c = 0; c < w.size(); ++c) {
    const auto t = post.fine.theta(c);
    mu_mass[c] = {t[0] + pr.sign * t[1] * pr.dx[s], w[c]};
  }
  const bool cells = has_cells(e);
  const std::vector<double> edges = cells ? *e.edges : std::vector<double>{-kInf, kInf};
  const std::vector<double> lik = cells ? *e.likelihood : std::vector<double>{1.0};
  std::vector<double> cell_mass(lik.size());
  for (const std::size_t c : draws) {
    const auto t = post.fine.theta(c);
    const SiteGaussian g = site_gaussian(e, t[0] + pr.sign * t[1] * pr.dx[s], t[2], pr.direct_sigma);
    double z = 0.0;
    for_each_cell_mass(edges, g.m, g.s, [&](std::size_t i, double mass) {
      cell_mass[i] = lik[i] * mass;
      z += cell_mass[i];
    });
    if (!(z > 0.0)) continue;
    // F(x | theta) = (sum of the cells wholly below x + the part of x's cell below x) / z.
    std::size_t cell = 0;
    double below = 0.0;
    double cdf_at_edge = normal_cdf((edges[0] - g.m) / g.s);  // Phi at the current cell's lower edge
    for (std::size_t k = 0; k < xs.size(); ++k) {
      while (cell + 1 < lik.size() && edges[cell + 1] <= xs[k]) {
        below += cell_mass[cell++];
        cdf_at_edge = normal_cdf((edges[cell] - g.m) / g.s);
      }
      const double part = lik[cell] * (normal_cdf((xs[k] - g.m) / g.s) - cdf_at_edge);
      cdf[k] += (below + std::max(0.0, part)) / z / static_cast<double>(draws.size());
    }
  }
  for (std::size_t k = 1; k < cdf.size(); ++k) cdf[k] = std::max(cdf[k], cdf[k - 1]);  // rounding: keep it monotone
  return {cdf_quantiles(xs, cdf), quantiles(std::move(mu_mass), 0.0)};
}

/// A note for each parameter whose 95 % interval reaches its prior's edge.
void edge_notes(const RelationProblem& pr, const RelationPosterior& post, const std::array<const char*, 3>& names,
                std::vector<std::string>& notes) {
  for (int d = 0; d < 3; ++d) {
    if (!post.at_edge[d]) continue;
    notes.push_back(fmt::format("{}'s 95 % interval [{:.3g}, {:.3g}] reaches its prior's edge ([{:.3g}, {:.3g}]): the "
                                "sites do not constrain it there; that end is the prior's",
                                names[d], post.est[d].ci95_low, post.est[d].ci95_high, pr.prior_lo[d], pr.prior_hi[d]));
  }
}

/// ln v from ln lo to ln hi in steps of 0.01 (a 1 % step in the value).
std::vector<double> log_axis(double lo, double hi) {
  std::vector<double> xs;
  for (double x = std::log(lo); x <= std::log(hi); x += 0.01) xs.push_back(x);
  return xs;
}

}  // namespace

double relation_pga_g(double c0, double c1, double c2_km, double distance_km) noexcept {
  return std::exp(c0 - c1 * std::log(std::hypot(distance_km, c2_km)));
}

bool objects_agree_with_instrument(const Estimate& e, double pga_g) noexcept {
  return (!e.ci95_low || *e.ci95_low <= pga_g) && (!e.ci95_high || pga_g <= *e.ci95_high);
}

SiteEvidence site_evidence(const std::string& name, double distance_km, const InversionResult* objects,
                           std::optional<double> instrument_pga_g, const std::optional<SiteIntensity>& intensity) {
  SiteEvidence e;
  e.name = name;
  e.distance_km = distance_km;
  e.instrument_pga_g = instrument_pga_g;
  if (intensity) e.intensity = intensity_pga(*intensity);
  if (objects == nullptr) return e;
  const std::size_t np = objects->pga_g.size(), nf = objects->freq_hz.size();
  double max_ll = -kInf;
  for (double v : objects->log_likelihood) max_ll = std::max(max_ll, v);
  // L_i = sum over the frequency columns of exp(log_likelihood): the frequency marginalised with its prior (uniform
  // in log frequency, the inversion's own), up to a constant (R2); the frequency axis likewise, the PGA marginalised
  // (F2).
  e.likelihood.assign(np, 0.0);
  e.freq_likelihood.assign(nf, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      const double l = std::exp(objects->log_likelihood[i * nf + j] - max_ll);
      e.likelihood[i] += l;
      e.freq_likelihood[j] += l;
    }
  }
  // Each scaled to a maximum of 1, on cells with edges at the geometric midpoints of the grid values, ends open.
  const auto cells = [](std::vector<double>& lik, std::vector<double>& edges, const std::vector<double>& values) {
    const double peak = *std::max_element(lik.begin(), lik.end());
    for (double& l : lik) l /= peak;
    edges = log_cell_edges(values, CellEnds::open);
  };
  cells(e.likelihood, e.ln_edges, objects->pga_g);
  cells(e.freq_likelihood, e.ln_freq_edges, objects->freq_hz);
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
  std::vector<double> dx(sites.size());
  for (std::size_t s = 0; s < sites.size(); ++s) dx[s] = ln_rho[s] - mean_ln_rho;

  // The PGA relation (R1): mu_s = ln a_ref - c1 dx_s.
  RelationProblem pga;
  pga.dx = dx;
  pga.sign = -1.0;
  pga.prior_lo = {st.ln_a_ref_min, st.c1_min, st.tau_min};
  pga.prior_hi = {st.ln_a_ref_max, st.c1_max, st.tau_max};
  pga.direct_sigma = st.instrument_sigma_ln;
  pga.fine_points = st.fine_points;
  for (const SiteEvidence& e : sites) {
    AxisSite a{&e.ln_edges, &e.likelihood, std::nullopt, 0.0};
    // The direct observations (header): an instrument (sigma st.instrument_sigma_ln), an intensity through its
    // conversion, or both as one normal in ln a (precision-weighted mean, precisions added). An instrument alone is
    // taken as it was before intensities existed (no arithmetic on it: old surveys keep their bits).
    if (e.instrument_pga_g && !e.intensity) {
      a.direct_ln = std::log(*e.instrument_pga_g);
    } else if (e.intensity && !e.instrument_pga_g) {
      a.direct_ln = std::log(e.intensity->pga_g);
      a.direct_sigma = e.intensity->sigma_ln;
    } else if (e.intensity && e.instrument_pga_g) {
      const double p_inst = 1.0 / (st.instrument_sigma_ln * st.instrument_sigma_ln);
      const double p_int = 1.0 / (e.intensity->sigma_ln * e.intensity->sigma_ln);
      a.direct_ln = (p_inst * std::log(*e.instrument_pga_g) + p_int * std::log(e.intensity->pga_g)) / (p_inst + p_int);
      a.direct_sigma = 1.0 / std::sqrt(p_inst + p_int);
    }
    pga.sites.push_back(a);
  }
  const RelationPosterior post = fit_relation(pga);
  const Grid3& fine = post.fine;
  const std::vector<double>& w = post.w;
  out.grid_points = post.grid_points;
  out.ln_a_ref = post.est[0];
  out.c1 = post.est[1];
  out.tau = post.est[2];
  out.c0 = intercept_of(post, pga.sign, mean_ln_rho);
  edge_notes(pga, post, {"ln a_ref", "c1", "tau"}, out.notes);

  // The relation's band for the attenuation figure.
  {
    double r_lo = 1.0, r_hi = 0.0;
    for (const SiteEvidence& e : sites) {
      r_lo = std::min(r_lo, e.distance_km);
      r_hi = std::max(r_hi, e.distance_km);
    }
    r_lo = std::max(r_lo, 0.1);
    r_hi = std::max(1.5 * r_hi, 2.0 * r_lo);
    std::vector<std::pair<double, double>> mass(static_cast<std::size_t>(fine.n[0]) * fine.n[1]);
    for (int q = 0; q < 40; ++q) {
      const double r = r_lo * std::pow(r_hi / r_lo, q / 39.0);
      const double lr = std::log(std::hypot(r, st.c2_km)) - mean_ln_rho;
      for (int i = 0; i < fine.n[0]; ++i) {
        for (int j = 0; j < fine.n[1]; ++j) {
          const double mu = fine.value(0, i) - fine.value(1, j) * lr;
          double wij = 0.0;
          for (int k = 0; k < fine.n[2]; ++k) wij += w[fine.index(i, j, k)];
          mass[static_cast<std::size_t>(i) * fine.n[1] + j] = {mu, wij};
        }
      }
      out.curve_distance_km.push_back(r);
      out.curve_pga_g.push_back(exp_of(quantiles(mass, 0.0)));
    }
  }

  // Each site's pooled PGA: the CDF on ln a from ln 1e-4 g to ln 20 g over draws of theta.
  const std::vector<std::size_t> draws = systematic_draws(w, st.draws);
  const std::vector<double> xs = log_axis(1e-4, 20.0);
  out.sites.resize(sites.size());
  // Sites in parallel (oneTBB): each site's pooled posterior is computed alone (deterministic).
  tbb::parallel_for(std::size_t{0}, sites.size(), [&](std::size_t s) {
    const SiteEvidence& e = sites[s];
    const auto [pooled, relation] = pooled_site(pga, post, draws, s, xs);
    PooledSite p;
    p.name = e.name;
    p.site_index = s;
    p.distance_km = e.distance_km;
    p.instrument_pga_g = e.instrument_pga_g;
    p.intensity = e.intensity;
    p.pga_g = exp_of(pooled);
    p.relation_pga_g = exp_of(relation);
    out.sites[s] = p;
  });

  // The frequency relation (F1), if the data support it (F3): fitted when at least 3 sites have a frequency
  // likelihood over more than one frequency cell, against the constant-frequency model.
  RelationProblem freq;
  freq.dx = dx;
  freq.sign = 1.0;
  freq.prior_lo = {st.ln_f_ref_min, st.d1_min, st.tau_f_min};
  freq.prior_hi = {st.ln_f_ref_max, st.d1_max, st.tau_f_max};
  freq.fine_points = st.fine_points;
  std::size_t informative = 0;
  for (const SiteEvidence& e : sites) {
    freq.sites.push_back({&e.ln_freq_edges, &e.freq_likelihood, std::nullopt, 0.0});
    informative += e.freq_likelihood.size() > 1 ? 1 : 0;
  }
  if (informative < 3) {
    out.notes.push_back(fmt::format("no frequency relation: it needs at least 3 sites whose objects constrain the "
                                    "frequency (a grid of more than one frequency), the survey has {}", informative));
    return out;
  }
  FrequencyRelation fr;
  fr.sites_with_frequency = informative;
  const RelationPosterior post1 = fit_relation(freq);
  RelationProblem constant = freq;
  constant.fixed_slope = true;
  constant.prior_lo[1] = constant.prior_hi[1] = 0.0;
  const RelationPosterior post0 = fit_relation(constant);
  fr.ln_f_ref = post1.est[0];
  fr.d1 = post1.est[1];
  fr.tau = post1.est[2];
  fr.d0 = intercept_of(post1, freq.sign, mean_ln_rho);
  fr.constant_f_hz = exp_of(post0.est[0]);
  fr.constant_tau = post0.est[2];
  fr.log_evidence_relation = post1.log_evidence;
  fr.log_evidence_constant = post0.log_evidence;
  fr.ln_bayes_factor = post1.log_evidence - post0.log_evidence;
  fr.supported = fr.ln_bayes_factor >= std::log(st.frequency_bayes_factor);
  edge_notes(freq, post1, {"ln f_ref", "d1", "tau_f"}, fr.notes);
  if (fr.supported) {
    // Each site's pooled frequency through the relation: the CDF on ln f from ln 0.01 Hz to ln 200 Hz.
    const std::vector<std::size_t> fdraws = systematic_draws(post1.w, st.draws);
    const std::vector<double> fxs = log_axis(0.01, 200.0);
    tbb::parallel_for(std::size_t{0}, sites.size(), [&](std::size_t s) {
      const auto [pooled, relation] = pooled_site(freq, post1, fdraws, s, fxs);
      out.sites[s].freq_hz = exp_of(pooled);
      out.sites[s].relation_freq_hz = exp_of(relation);
    });
  }
  out.frequency = std::move(fr);
  return out;
}

}  // namespace topple
