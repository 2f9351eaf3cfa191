#include "topple/inversion/prior.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "topple/motion/bssa14.hpp"
#include "topple/numerics/statistics.hpp"

namespace topple {

MeanPeriodModel mean_period_rathje(double magnitude, double distance_km) {
  // Bray & Rathje (1998), eq. for Tm on rock (from Rathje, Abrahamson & Bray 1998), as coded in SLAMMER's
  // decoupled simplified method: linear in M up to 7.25 and in r; lognormal scatter sigma_ln = 0.437.
  const double m = std::min(magnitude, 7.25);
  MeanPeriodModel out;
  out.median_s = 0.411 + 0.0837 * (m - 6.0) + 0.00208 * std::max(distance_km, 0.0);
  out.median_s = std::max(out.median_s, 0.05);  // M < 1.7 only; the floor keeps ln finite outside the model's range
  out.sigma_ln = 0.437;
  return out;
}

namespace {

/// One (M, R) node of the prior's mixture: the Gaussians in ln A and ln f, and the node's weight.
struct Node {
  double mu_a, sigma_a, mu_f, sigma_f, weight;
};

Node node(double m, double rjb_km, double r_km, double vs30, double weight) {
  const Bssa14Pga a = bssa14_pga(m, rjb_km, vs30);
  const MeanPeriodModel t = mean_period_rathje(m, r_km);
  // f_p = kFpTmRatio / Tm, the ratio's own lognormal scatter added to Tm's (independent): prior.hpp.
  return {a.ln_mean, a.sigma_ln, std::log(kFpTmRatio) - std::log(t.median_s),
          std::hypot(t.sigma_ln, kFpTmRatioSigmaLn), weight};
}

}  // namespace

std::vector<double> earthquake_log_prior(const std::vector<double>& pga_g, const std::vector<double>& freq_hz,
                                         const Site& site, const std::optional<EventSource>& event) {
  const double vs30 = site.vs30_m_s.value_or(kPriorDefaultVs30MS);
  const double depth = event ? event->depth_km : 0.0;
  // The magnitudes and distances to mix over, with midpoint-rule weights (equal: uniform M, log-uniform R).
  std::vector<double> mags;
  if (event) {
    mags.push_back(event->magnitude);
  } else {
    constexpr int nm = 31;
    for (int k = 0; k < nm; ++k) {
      mags.push_back(kPriorMagnitudeMin + (kPriorMagnitudeMax - kPriorMagnitudeMin) * (k + 0.5) / nm);
    }
  }
  std::vector<double> dists;  // epicentral (R_JB)
  if (event && site.epicentral_distance_km) {
    dists.push_back(*site.epicentral_distance_km);
  } else {
    constexpr int nr = 41;
    const double l0 = std::log(kPriorDistanceMinKm), l1 = std::log(kPriorDistanceMaxKm);
    for (int k = 0; k < nr; ++k) dists.push_back(std::exp(l0 + (l1 - l0) * (k + 0.5) / nr));
  }
  std::vector<Node> nodes;
  const double w = 1.0 / static_cast<double>(mags.size() * dists.size());
  for (double m : mags) {
    for (double r : dists) nodes.push_back(node(m, r, std::sqrt(r * r + depth * depth), vs30, w));
  }
  // Without the event the PGA part is left out (uniform in ln A): see the header, "Without the event".
  const bool with_pga = event.has_value();
  const std::size_t np = pga_g.size(), nf = freq_hz.size();
  std::vector<double> out(np * nf);
  std::vector<double> terms(nodes.size());
  for (std::size_t i = 0; i < np; ++i) {
    const double la = std::log(pga_g[i]);
    for (std::size_t j = 0; j < nf; ++j) {
      const double lf = std::log(freq_hz[j]);
      for (std::size_t n = 0; n < nodes.size(); ++n) {
        const Node& q = nodes[n];
        const double za = with_pga ? (la - q.mu_a) / q.sigma_a : 0.0, zf = (lf - q.mu_f) / q.sigma_f;
        // ln of weight x N(za) / sigma_a x N(zf) / sigma_f; the 2 pi drops out with the normalisation.
        terms[n] = std::log(q.weight) - 0.5 * (za * za + zf * zf) -
                   std::log((with_pga ? q.sigma_a : 1.0) * q.sigma_f);
      }
      out[i * nf + j] = log_sum_exp(terms);
    }
  }
  const double top = *std::max_element(out.begin(), out.end());
  for (double& v : out) v -= top;
  return out;
}

std::vector<double> log_prior_for(const std::vector<double>& pga_g, const std::vector<double>& freq_hz,
                                  const Site& site, const InversionSettings& settings) {
  if (settings.prior == InversionPrior::log_uniform) return {};
  return earthquake_log_prior(pga_g, freq_hz, site, settings.event);
}

std::string prior_description(const Site& site, const InversionSettings& st) {
  if (st.prior == InversionPrior::log_uniform) return "uniform in log PGA and log frequency over the grid";
  const std::string vs30 =
      site.vs30_m_s ? fmt::format("Vs30 {:.0f} m/s", *site.vs30_m_s)
                    : fmt::format("Vs30 {:.0f} m/s (none given)", kPriorDefaultVs30MS);
  std::string mr;
  if (!st.event) {
    mr = fmt::format("M uniform on [{}, {}], R log-uniform on [{}, {}] km", kPriorMagnitudeMin, kPriorMagnitudeMax,
                     kPriorDistanceMinKm, kPriorDistanceMaxKm);
  } else if (site.epicentral_distance_km) {
    mr = fmt::format("M {:.1f} at {:.1f} km", st.event->magnitude, *site.epicentral_distance_km);
  } else {
    mr = fmt::format("M {:.1f}, R log-uniform on [{}, {}] km (no site location)", st.event->magnitude,
                     kPriorDistanceMinKm, kPriorDistanceMaxKm);
  }
  if (!st.event) {
    return fmt::format("earthquake prior on the frequency (the Bray-Rathje mean period, {}), uniform in log PGA", mr);
  }
  return fmt::format("earthquake prior: BSSA14 PGA and the Bray-Rathje mean period, {}, {}", mr, vs30);
}

}  // namespace topple
