// Fragility curves: lognormal maximum-likelihood fit with a delta-method band, and the ensemble analysis
// (fragility.hpp).
#include "topple/fragility/fragility.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <boost/math/distributions/normal.hpp>
#include <fmt/format.h>

#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/enum_names.hpp"
#include "topple/numerics/statistics.hpp"

namespace topple {

IntensityMeasure parse_intensity_measure(std::string_view name, const std::string& field) {
  if (name == "pga") return IntensityMeasure::pga;
  if (name == "pgv") return IntensityMeasure::pgv;
  if (name == "pgd") return IntensityMeasure::pgd;
  if (name == "cav") return IntensityMeasure::cav;
  throw parameter_error(field, fmt::format("unknown intensity measure '{}' (known: pga, pgv, pgd, cav)", name));
}

constexpr std::array<EnumName<IntensityMeasure>, 4> kIntensityMeasureNames{{
    {IntensityMeasure::pga, "pga"},
    {IntensityMeasure::pgv, "pgv"},
    {IntensityMeasure::pgd, "pgd"},
    {IntensityMeasure::cav, "cav"},
}};

std::string_view intensity_measure_name(IntensityMeasure im) { return enum_name(kIntensityMeasureNames, im); }

std::string_view intensity_measure_unit(IntensityMeasure im) {
  switch (im) {
    case IntensityMeasure::pga: return "g";
    case IntensityMeasure::pgv: return "m/s";
    case IntensityMeasure::pgd: return "m";
    case IntensityMeasure::cav: return "m/s";
  }
  return "?";
}

double intensity_measure_display_factor(IntensityMeasure im, double g_m_s2) {
  return im == IntensityMeasure::pga ? 1.0 / g_m_s2 : 1.0;
}

std::string_view intensity_measure_column(IntensityMeasure im) {
  switch (im) {
    case IntensityMeasure::pga: return "im_pga_g";
    case IntensityMeasure::pgv: return "im_pgv_m_s";
    case IntensityMeasure::pgd: return "im_pgd_m";
    case IntensityMeasure::cav: return "im_cav_m_s";
  }
  return "im";
}

double intensity_measure_si(const GroundMotion& motion, IntensityMeasure im) {
  switch (im) {
    case IntensityMeasure::pga: return motion.pga_m_s2();
    case IntensityMeasure::pgv: return basic_intensity(motion).pgv_m_s;
    case IntensityMeasure::pgd: return basic_intensity(motion).pgd_m;
    case IntensityMeasure::cav: return cumulative_absolute_velocity_m_s(motion);
  }
  return 0.0;
}

namespace {

const boost::math::normal kStandardNormal{};

/// ln Phi(u), accurate in the far lower tail by the asymptotic Mills-ratio series (Abramowitz & Stegun 26.2.12).
double log_cdf(double u) {
  if (u > -30.0) return std::log(boost::math::cdf(kStandardNormal, u));
  const double r = 1.0 / (u * u);
  return -0.5 * u * u - 0.5 * std::log(2.0 * kPi) - std::log(-u) + std::log(1.0 - r + 3.0 * r * r);
}

/// phi(u) / Phi(u) (the inverse Mills ratio), same series below -30.
double hazard(double u) {
  if (u > -30.0) return boost::math::pdf(kStandardNormal, u) / boost::math::cdf(kStandardNormal, u);
  const double r = 1.0 / (u * u);
  return -u / (1.0 - r + 3.0 * r * r);
}

/// Log-likelihood in (mu = ln theta, beta) with ln x precomputed.
struct Likelihood {
  std::vector<double> ln_x;
  std::vector<double> n;
  std::vector<double> z;

  /// ln L of Baker (2015) eq 11 (binomial counts per level), p_j = Phi(u_j), 1 - p_j = Phi(-u_j).
  [[nodiscard]] double value(double mu, double beta) const {
    double sum = 0.0;
    for (std::size_t j = 0; j < ln_x.size(); ++j) {
      const double u = (ln_x[j] - mu) / beta;
      if (z[j] > 0.0) sum += z[j] * log_cdf(u);
      if (n[j] > z[j]) sum += (n[j] - z[j]) * log_cdf(-u);
    }
    return sum;
  }
  /// d lnL / d(mu, beta): dlnL/du_j = z phi/Phi(u) - (n - z) phi/Phi(-u); du/dmu = -1/beta, du/dbeta = -u/beta.
  [[nodiscard]] std::array<double, 2> gradient(double mu, double beta) const {
    std::array<double, 2> g{0.0, 0.0};
    for (std::size_t j = 0; j < ln_x.size(); ++j) {
      const double u = (ln_x[j] - mu) / beta;
      double d = 0.0;
      if (z[j] > 0.0) d += z[j] * hazard(u);
      if (n[j] > z[j]) d -= (n[j] - z[j]) * hazard(-u);
      g[0] += -d / beta;
      g[1] += -d * u / beta;
    }
    return g;
  }
  /// Hessian by central differences of the analytic gradient (step ~1e-5 relative).
  [[nodiscard]] std::array<double, 4> hessian(double mu, double beta) const {
    const double hm = 1e-5 * std::max(1.0, std::abs(mu));
    const double hb = 1e-5 * beta;
    const auto gp0 = gradient(mu + hm, beta);
    const auto gm0 = gradient(mu - hm, beta);
    const auto gp1 = gradient(mu, beta + hb);
    const auto gm1 = gradient(mu, beta - hb);
    const double h00 = (gp0[0] - gm0[0]) / (2.0 * hm);
    const double h11 = (gp1[1] - gm1[1]) / (2.0 * hb);
    const double h01 = 0.5 * ((gp0[1] - gm0[1]) / (2.0 * hm) + (gp1[0] - gm1[0]) / (2.0 * hb));
    return {h00, h01, h01, h11};
  }
};

void check_data(const FragilityData& d) {
  if (d.im.empty()) throw parameter_error("im", "no IM level");
  if (d.trials.size() != d.im.size() || d.failures.size() != d.im.size()) {
    throw parameter_error("trials", fmt::format("{} levels but {} trial counts and {} failure counts", d.im.size(),
                                                d.trials.size(), d.failures.size()));
  }
  long total = 0;
  long failed = 0;
  for (std::size_t j = 0; j < d.im.size(); ++j) {
    if (!std::isfinite(d.im[j]) || !(d.im[j] > 0.0)) {
      throw parameter_error("im", fmt::format("level {} must be positive and finite, got {}", j + 1, d.im[j]));
    }
    if (d.trials[j] < 1) throw parameter_error("trials", fmt::format("level {}: {} trials", j + 1, d.trials[j]));
    if (d.failures[j] < 0 || d.failures[j] > d.trials[j]) {
      throw parameter_error("failures", fmt::format("level {}: {} failures out of {} trials", j + 1, d.failures[j],
                                                    d.trials[j]));
    }
    total += d.trials[j];
    failed += d.failures[j];
  }
  if (failed == 0) throw parameter_error("failures", "no failure at any level: the fragility cannot be fitted");
  if (failed == total) throw parameter_error("failures", "failures at every trial: the fragility cannot be fitted");
}

/// The likelihood of the counts (ln x per level, trials and failures as doubles).
Likelihood likelihood_of(const FragilityData& data) {
  Likelihood L;
  for (std::size_t j = 0; j < data.im.size(); ++j) {
    L.ln_x.push_back(std::log(data.im[j]));
    L.n.push_back(data.trials[j]);
    L.z.push_back(data.failures[j]);
  }
  return L;
}

/// Perfectly separated data (every level all-safe or all-fail, the safe ones below): ln L -> 0 as beta -> 0 for any
/// theta between the last safe and the first failing level. Report beta at its bound and theta at the geometric
/// middle of that interval (none when the data are not separated).
std::optional<LognormalFragilityFit> separated_fit(const Likelihood& L) {
  double last_safe = -std::numeric_limits<double>::infinity();
  double first_fail = std::numeric_limits<double>::infinity();
  bool separated = true;
  for (std::size_t j = 0; j < L.ln_x.size() && separated; ++j) {
    if (L.z[j] == 0.0) {
      last_safe = std::max(last_safe, L.ln_x[j]);
    } else if (L.z[j] == L.n[j]) {
      first_fail = std::min(first_fail, L.ln_x[j]);
    } else {
      separated = false;
    }
  }
  if (separated && last_safe < first_fail) {
    LognormalFragilityFit fit;
    fit.theta = std::exp(0.5 * (last_safe + first_fail));
    fit.beta = kMinimumBeta;
    fit.beta_at_bound = true;
    fit.log_likelihood = L.value(std::log(fit.theta), fit.beta);
    return fit;
  }
  return std::nullopt;
}

/// Start: probit least squares ln x = mu + beta u through the levels with 0 < z/n < 1. Returns {mu0, beta0};
/// without two such levels, the middle of the IM range (or the one level) and beta = 0.4.
std::array<double, 2> probit_start(const Likelihood& L) {
  double mu0 = 0.0;
  double beta0 = 0.4;
  std::vector<double> us;
  std::vector<double> xs;
  for (std::size_t j = 0; j < L.ln_x.size(); ++j) {
    if (L.z[j] > 0.0 && L.z[j] < L.n[j]) {
      us.push_back(boost::math::quantile(kStandardNormal, L.z[j] / L.n[j]));
      xs.push_back(L.ln_x[j]);
    }
  }
  const auto [lo, hi] = std::minmax_element(L.ln_x.begin(), L.ln_x.end());
  mu0 = 0.5 * (*lo + *hi);
  if (us.size() >= 2) {
    double mu_u = 0.0;
    double mu_x = 0.0;
    for (std::size_t i = 0; i < us.size(); ++i) {
      mu_u += us[i];
      mu_x += xs[i];
    }
    mu_u /= static_cast<double>(us.size());
    mu_x /= static_cast<double>(us.size());
    double sxu = 0.0;
    double suu = 0.0;
    for (std::size_t i = 0; i < us.size(); ++i) {
      sxu += (us[i] - mu_u) * (xs[i] - mu_x);
      suu += (us[i] - mu_u) * (us[i] - mu_u);
    }
    if (suu > 0.0 && sxu > 0.0) {
      beta0 = std::clamp(sxu / suu, 0.05, 3.0);
      mu0 = mu_x - beta0 * mu_u;
    } else {
      mu0 = mu_x;
    }
  } else if (us.size() == 1) {
    mu0 = xs.front();
  }
  return {mu0, beta0};
}

/// Nelder-Mead on (mu, ln beta), minimising -ln L; ln beta is clamped at its lower bound. Returns the best vertex
/// (mu, ln beta) and sets `iterations`.
std::array<double, 2> nelder_mead(const Likelihood& L, double mu0, double beta0, int& iterations) {
  const double lb_min = std::log(kMinimumBeta);
  const auto f = [&](const std::array<double, 2>& q) {
    return -L.value(q[0], std::exp(std::max(q[1], lb_min)));
  };
  std::array<std::array<double, 2>, 3> s{{{mu0, std::log(beta0)}, {mu0 + 0.3, std::log(beta0)},
                                          {mu0, std::log(beta0) + 0.3}}};
  std::array<double, 3> fs{f(s[0]), f(s[1]), f(s[2])};
  constexpr int kMaxIterations = 5000;
  int it = 0;
  for (; it < kMaxIterations; ++it) {
    std::array<int, 3> idx{0, 1, 2};
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return fs[static_cast<std::size_t>(a)] < fs[static_cast<std::size_t>(b)]; });
    const auto b = static_cast<std::size_t>(idx[0]);
    const auto m = static_cast<std::size_t>(idx[1]);
    const auto w = static_cast<std::size_t>(idx[2]);
    const double size = std::max({std::abs(s[w][0] - s[b][0]), std::abs(s[w][1] - s[b][1]),
                                  std::abs(s[m][0] - s[b][0]), std::abs(s[m][1] - s[b][1])});
    if (size < 1e-10 && std::abs(fs[w] - fs[b]) <= 1e-12 * (1.0 + std::abs(fs[b]))) break;
    const std::array<double, 2> c{0.5 * (s[b][0] + s[m][0]), 0.5 * (s[b][1] + s[m][1])};
    const auto along = [&](double t) {
      return std::array<double, 2>{c[0] + t * (s[w][0] - c[0]), c[1] + t * (s[w][1] - c[1])};
    };
    const auto r = along(-1.0);
    const double fr = f(r);
    if (fr < fs[b]) {
      const auto e = along(-2.0);
      const double fe = f(e);
      if (fe < fr) { s[w] = e; fs[w] = fe; } else { s[w] = r; fs[w] = fr; }
    } else if (fr < fs[m]) {
      s[w] = r;
      fs[w] = fr;
    } else {
      const auto k = fr < fs[w] ? along(-0.5) : along(0.5);
      const double fk = f(k);
      if (fk < std::min(fr, fs[w])) {
        s[w] = k;
        fs[w] = fk;
      } else {  // shrink toward the best
        for (std::size_t i = 0; i < 3; ++i) {
          if (i == b) continue;
          s[i] = {s[b][0] + 0.5 * (s[i][0] - s[b][0]), s[b][1] + 0.5 * (s[i][1] - s[b][1])};
          fs[i] = f(s[i]);
        }
      }
    }
  }
  iterations = it;
  return s[static_cast<std::size_t>(std::min_element(fs.begin(), fs.end()) - fs.begin())];
}

/// Newton polish in (mu, beta) on the analytic gradient, with step halving (at most 20 steps).
void newton_polish(const Likelihood& L, double& mu, double& beta) {
  for (int k = 0; k < 20; ++k) {
    const auto g = L.gradient(mu, beta);
    const auto H = L.hessian(mu, beta);
    const double det = H[0] * H[3] - H[1] * H[2];
    if (!(det > 0.0) || !(H[0] < 0.0)) break;  // not concave here: keep the Nelder-Mead point
    double dmu = -(H[3] * g[0] - H[1] * g[1]) / det;
    double dbeta = -(-H[2] * g[0] + H[0] * g[1]) / det;
    const double f0 = L.value(mu, beta);
    double t = 1.0;
    while (t > 1e-4 && (!(beta + t * dbeta > kMinimumBeta) || L.value(mu + t * dmu, beta + t * dbeta) < f0)) t *= 0.5;
    if (t <= 1e-4) break;
    mu += t * dmu;
    beta += t * dbeta;
    if (std::abs(t * dmu) < 1e-12 * (1.0 + std::abs(mu)) && std::abs(t * dbeta) < 1e-12 * beta) break;
  }
}

/// Observed information I = -H; covariance C = I^-1.
void set_standard_errors(const Likelihood& L, double mu, double beta, LognormalFragilityFit& fit) {
  const auto H = L.hessian(mu, beta);
  const double i00 = -H[0];
  const double i01 = -H[1];
  const double i11 = -H[3];
  const double det = i00 * i11 - i01 * i01;
  if (det > 0.0 && i00 > 0.0) {
    fit.se_ln_theta = std::sqrt(i11 / det);
    fit.se_beta = std::sqrt(i00 / det);
    fit.cov_ln_theta_beta = -i01 / det;
  }
}

}  // namespace

double fragility_log_likelihood(const FragilityData& data, double theta, double beta) {
  check_data(data);
  return likelihood_of(data).value(std::log(theta), beta);
}

double LognormalFragilityFit::probability(double im) const {
  if (!(im > 0.0)) return 0.0;
  return normal_cdf(std::log(im / theta) / beta);  // Phi(ln(x / theta) / beta), Baker (2015) eq 1
}

std::pair<double, double> LognormalFragilityFit::band(double im, double level) const {
  if (!(im > 0.0)) return {0.0, 0.0};
  const double u = std::log(im / theta) / beta;
  // var u = g^T C g, g = (-1/beta, -u/beta) (delta method; header)
  const double var = (se_ln_theta * se_ln_theta + 2.0 * u * cov_ln_theta_beta + u * u * se_beta * se_beta) /
                     (beta * beta);
  const double z = boost::math::quantile(kStandardNormal, 0.5 * (1.0 + level));  // z = Phi^-1((1 + c) / 2)
  const double s = std::sqrt(std::max(0.0, var));
  return {normal_cdf(u - z * s), normal_cdf(u + z * s)};
}

LognormalFragilityFit fit_lognormal_fragility(const FragilityData& data) {
  check_data(data);
  const Likelihood L = likelihood_of(data);
  if (std::optional<LognormalFragilityFit> fit = separated_fit(L)) return *fit;
  const auto [mu0, beta0] = probit_start(L);
  LognormalFragilityFit fit;
  const std::array<double, 2> best = nelder_mead(L, mu0, beta0, fit.iterations);
  const double lb_min = std::log(kMinimumBeta);
  double mu = best[0];
  double beta = std::exp(std::max(best[1], lb_min));
  const bool at_bound = best[1] <= lb_min + 1e-6;
  if (!at_bound) newton_polish(L, mu, beta);
  fit.theta = std::exp(mu);
  fit.beta = beta;
  fit.log_likelihood = L.value(mu, beta);
  fit.beta_at_bound = at_bound;
  if (!at_bound) set_standard_errors(L, mu, beta, fit);
  return fit;
}

namespace {

/// Whether the body falls under `m`: Housner's rocking, or the coupled slide-rock model when given.
bool overturns(const GroundMotion& m, const OverturnFailure& f) {
  if (f.coupled) return slide_rock(m, *f.coupled, slide_rock_options(f.options)).summary.overturned;
  return rock_summary(m, f.body, f.options).overturned;
}

/// A three-dimensional body at `bearing_deg` (its +x axis, degrees clockwise from north) under a pair: the pair along
/// east and north (eq. M1) and the vertical, the body turned by 90 - bearing degrees counter-clockwise seen from above
/// (as `topple rock --model 3d --h2 --bearing-deg`), so that its azimuths are the ground's.
/// A cylinder (cylinder_3d) is axisymmetric: the pair as it is, whatever the bearing.
bool overturns_3d(const MotionSet& set, const OverturnFailure& f, double bearing_deg) {
  Rigid3DOptions o = rigid3d_options(f.options);
  o.mu_s = f.mu_3d;
  o.mu_k = f.mu_k_3d;
  const GroundMotion east = set.projected(90.0);
  const GroundMotion north = set.projected(0.0);
  if (f.cylinder_3d) return rock3d_cylinder(east, &north, set.vertical_ptr(), *f.cylinder_3d, o).summary.overturned;
  const RigidBody3D turned = f.body_3d->rotated_about_vertical((90.0 - bearing_deg) * kPi / 180.0);
  return rock3d(east, &north, set.vertical_ptr(), turned, o).summary.overturned;
}

/// The objects: at least one, a valid threshold; the rocking options (and the coupled body) checked on a still
/// record in the caller's thread, so that a bad option is an InputError here, not a worker's.
void check_objects(const FragilitySpec& spec) {
  if (!spec.sliding && !spec.overturning) {
    throw parameter_error("object", "give a sliding block with a threshold, a rocking body, or both");
  }
  if (spec.sliding && (!std::isfinite(spec.sliding->threshold_m) || spec.sliding->threshold_m < 0.0)) {
    throw parameter_error("threshold", fmt::format("must be >= 0 m, got {}", spec.sliding->threshold_m));
  }
  if (spec.overturning) (void)overturns(GroundMotion::uniform({0.0, 0.0}, 1.0), *spec.overturning);
  if (spec.overturning && (spec.overturning->mu_3d || spec.overturning->mu_k_3d)) {
    const OverturnFailure& f = *spec.overturning;
    if (!f.body_3d && !f.cylinder_3d) {
      throw parameter_error("mu", "friction applies to a three-dimensional body (model 3d)");
    }
    // The engine's own checks of mu and mu_k (InputError naming them), on a still pair, before any worker runs.
    const GroundMotion still = GroundMotion::uniform({0.0, 0.0}, 1.0);
    const MotionSet set = MotionSet::make(still, &still, ComponentAzimuths{90.0, 0.0});
    (void)overturns_3d(set, f, 0.0);
  }
}

/// Under pairs: checks the sets and the objects, and gives each motion's bearing (header, "Pairs").
std::vector<double> check_pairs(const FragilitySpec& spec) {
  if (!spec.motions.empty()) {
    throw parameter_error("motions", "give single-component motions or pairs (motion sets), not both");
  }
  if (spec.im != IntensityMeasure::pga) {
    throw parameter_error("im", fmt::format("an ensemble of pairs is scaled by its RotD50 PGA: the IM must be pga, got "
                                            "{}", intensity_measure_name(spec.im)));
  }
  for (std::size_t i = 0; i < spec.motion_sets.size(); ++i) {
    const auto& set = spec.motion_sets[i];
    if (!set || !set->has_second() || !set->azimuths()) {
      throw parameter_error("motions", fmt::format("pair {} needs two horizontal components with known azimuths",
                                                   i + 1));
    }
  }
  if (spec.sliding && (spec.sliding->block.mode != SlidingMode::two_way || spec.sliding->block.slope_rad != 0.0)) {
    throw parameter_error(spec.sliding->block.mode != SlidingMode::two_way ? "mode" : "slope",
                          "under pairs the block slides in two dimensions: two-way, on level ground");
  }
  if (spec.bearing_deg && spec.overturning) {
    check_orientation(OrientedBody::planar(spec.overturning->body), spec.bearing_deg, false);
  }
  if (spec.bearing_deg && !std::isfinite(*spec.bearing_deg)) {
    throw parameter_error("bearing", fmt::format("must be finite, got {}", *spec.bearing_deg));
  }
  std::vector<double> bearings(spec.motion_sets.size(), spec.bearing_deg.value_or(0.0));
  if (!spec.bearing_deg) {
    PortableRandom random(spec.bearing_seed);
    for (double& b : bearings) b = 360.0 * random.uniform();
  }
  return bearings;
}

// The rocking model excludes lift-off (g + a_v <= 0, rocking.hpp). A pair's vertical scales with the pair, so pair i
// leaves the ground at every level from L_i = RotD50_i * g / max(-a_v,i) up (the scaled vertical's lowest value
// reaches -g there; the input is piecewise linear, so its lowest value is a sample's). Checked here, before any run,
// so that the error names the pair and the highest level the whole ensemble allows instead of stopping a worker
// part-way with the rocking engine's bare "vertical" message.
void check_rocking_contact(const FragilitySpec& spec, const std::vector<double>& base_im) {
  const double g = spec.overturning->options.g_m_s2;
  const double top = *std::max_element(spec.levels_si.begin(), spec.levels_si.end());
  double allowed = std::numeric_limits<double>::infinity();
  std::size_t first_bad = 0;
  bool any_bad = false;
  for (std::size_t i = 0; i < spec.motion_sets.size(); ++i) {
    if (!spec.motion_sets[i]->has_vertical()) continue;
    const auto a_v = spec.motion_sets[i]->vertical().accel_m_s2();
    const double lowest = *std::min_element(a_v.begin(), a_v.end());
    if (!(lowest < 0.0)) continue;
    const double lift_off = base_im[i] * g / -lowest;
    allowed = std::min(allowed, lift_off);
    if (!any_bad && lift_off <= top) {
      any_bad = true;
      first_bad = i;
    }
  }
  if (any_bad) {
    const auto a_v = spec.motion_sets[first_bad]->vertical().accel_m_s2();
    const double scaled_lowest = *std::min_element(a_v.begin(), a_v.end()) * top / base_im[first_bad];
    throw parameter_error(
        "levels", fmt::format("at RotD50 PGA {:.4g} g, pair {} of the ensemble has a vertical of {:.4g} g, so g + a_v "
                              "<= 0: the body would leave the ground, which the rocking model excludes; every pair "
                              "keeps contact below {:.4g} g: lower the top of the IM range below that, or leave out "
                              "the vertical",
                              top / g, first_bad + 1, scaled_lowest / g, allowed / g));
  }
}

}  // namespace

FragilityResult fragility_analysis(const FragilitySpec& spec) {
  const bool pairs = !spec.motion_sets.empty();
  if (spec.motions.empty() && !pairs) throw parameter_error("motions", "the ensemble has no motion");
  const std::vector<double> bearings = pairs ? check_pairs(spec) : std::vector<double>{};
  if (spec.levels_si.empty()) throw parameter_error("levels", "no IM level");
  for (double x : spec.levels_si) {
    if (!std::isfinite(x) || !(x > 0.0)) throw parameter_error("levels", fmt::format("must be positive, got {}", x));
  }
  check_objects(spec);
  if (pairs && spec.overturning && spec.overturning->coupled) {
    throw parameter_error("model", "the coupled model runs single-component motions; pairs rock an oriented body "
                                   "(the rocking model)");
  }
  if (spec.overturning && spec.overturning->three_d() && (!pairs || spec.overturning->coupled)) {
    throw parameter_error("model", spec.overturning->coupled
                                       ? "a body is coupled or three-dimensional, not both"
                                       : "the three-dimensional model runs under pairs (two horizontal components "
                                         "and, optionally, a vertical), not single-component motions");
  }
  // Each motion's base: the record, or a pair's first component (aliasing the set, which owns it).
  std::vector<std::shared_ptr<const GroundMotion>> bases = spec.motions;
  for (const auto& set : spec.motion_sets) bases.emplace_back(set, &set->first());
  std::vector<double> base_im;
  for (std::size_t i = 0; i < bases.size(); ++i) {
    const double v = pairs ? rotd_measures(*spec.motion_sets[i], {}).pga_m_s2.rotd50
                           : intensity_measure_si(*bases[i], spec.im);
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw parameter_error("motions", fmt::format("motion {} has {} = {}: it cannot be scaled", i + 1,
                                                   intensity_measure_name(spec.im), v));
    }
    base_im.push_back(v);
  }
  if (pairs && spec.overturning) check_rocking_contact(spec, base_im);

  ensemble::Plan plan;
  plan.motion_columns = {"level", "motion"};
  plan.object_columns = {"object"};
  plan.result_columns = {"failed"};
  plan.identity = "topple fragility v1";
  for (std::size_t j = 0; j < spec.levels_si.size(); ++j) {
    for (std::size_t i = 0; i < bases.size(); ++i) {
      ensemble::MotionCase mc;
      mc.base = bases[i];
      mc.transform.factor = spec.levels_si[j] / base_im[i];
      mc.values = {ensemble::Value(static_cast<std::int64_t>(j)), ensemble::Value(static_cast<std::int64_t>(i))};
      plan.motions.push_back(std::move(mc));
    }
  }
  std::vector<std::string> names;
  if (spec.sliding) names.emplace_back("slide");
  if (spec.overturning) names.emplace_back("overturn");
  for (const auto& n : names) plan.objects.push_back({{ensemble::Value(n)}});
  plan.chunk_runs = std::max<std::size_t>(1, plan.runs() / 64);
  const bool has_slide = spec.sliding.has_value();
  const std::size_t n_bases = bases.size();
  plan.run = [&spec, &plan, &bearings, has_slide, pairs, n_bases](const GroundMotion& m, std::size_t motion_index,
                                                                  std::size_t o0, std::size_t o1,
                                                                  std::span<ensemble::Value> results) {
    if (pairs) {
      // The pair scaled as a whole (the case's transform on every component), its objects oriented.
      const std::size_t i = motion_index % n_bases;
      const MotionSet set = ensemble::transformed_set(*spec.motion_sets[i], plan.motions[motion_index].transform, m);
      for (std::size_t o = o0; o < o1; ++o) {
        bool failed = false;
        if (has_slide && o == 0) {
          failed = slide_2d_summary(set.first(), set.second(), *set.azimuths(), spec.sliding->block,
                                    set.vertical_ptr()).max_abs_displacement_m > spec.sliding->threshold_m;
        } else if (spec.overturning->three_d()) {
          failed = overturns_3d(set, *spec.overturning, bearings[i]);
        } else {
          failed = rock_oriented_summary(set, OrientedBody::planar(spec.overturning->body), bearings[i],
                                         spec.overturning->options).governing_response().summary.overturned;
        }
        results[o - o0] = ensemble::Value(failed);
      }
      return;
    }
    for (std::size_t o = o0; o < o1; ++o) {
      bool failed = false;
      if (has_slide && o == 0) {
        failed = slide_summary(m, spec.sliding->block).max_abs_displacement_m > spec.sliding->threshold_m;
      } else {
        failed = overturns(m, *spec.overturning);
      }
      results[o - o0] = ensemble::Value(failed);
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = spec.threads;
  exec.progress = spec.progress;
  const ensemble::ResultTable table = ensemble::run_in_memory(plan, exec);

  FragilityResult out;
  out.im = spec.im;
  out.rotd50 = pairs;
  out.bearings_deg = bearings;
  out.runs = table.rows.size();
  const std::size_t nm = bases.size();
  const std::size_t no = names.size();
  const std::size_t col = table.columns.size() - 1;
  for (std::size_t o = 0; o < no; ++o) {
    FragilityCurve c;
    c.name = names[o];
    for (std::size_t j = 0; j < spec.levels_si.size(); ++j) {
      int failures = 0;
      for (std::size_t i = 0; i < nm; ++i) {
        if (std::get<bool>(table.rows[(j * nm + i) * no + o][col])) ++failures;
      }
      c.data.im.push_back(spec.levels_si[j]);
      c.data.trials.push_back(static_cast<int>(nm));
      c.data.failures.push_back(failures);
    }
    try {
      c.fit = fit_lognormal_fragility(c.data);
    } catch (const InputError& e) {
      c.fit_note = fmt::format("{} (widen the IM range)", e.problem());
    }
    out.curves.push_back(std::move(c));
  }
  return out;
}

// ---- The fragility surface (fragility.hpp, "As recorded") ----

namespace {

/// The inverse of a symmetric 3x3 matrix by cofactors; false when it is singular to round-off (|det| below 1e-12 of
/// the product of the diagonal's magnitudes).
bool invert3(const std::array<std::array<double, 3>, 3>& m, std::array<std::array<double, 3>, 3>& inv) {
  const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
  const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
  const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
  const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
  const double scale = std::abs(m[0][0] * m[1][1] * m[2][2]);
  if (!(std::abs(det) > 1e-12 * scale) || !std::isfinite(det)) return false;
  inv[0][0] = c00 / det;
  inv[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / det;
  inv[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / det;
  inv[1][0] = c01 / det;
  inv[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / det;
  inv[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / det;
  inv[2][0] = c02 / det;
  inv[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / det;
  inv[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / det;
  return true;
}

/// The probit GLM's Bernoulli log-likelihood at a = (a0, a1, a2) on rows x = (1, ln PGA, ln(v / v_ref)), with its
/// gradient and Hessian: d/du ln Phi(s u) = s lambda(s u) (lambda = phi / Phi, the inverse Mills ratio, `hazard`),
/// d2/du2 ln Phi(s u) = -lambda(s u) (s u + lambda(s u)), s = +1 for a failure, -1 for a survival.
struct ProbitLikelihood {
  std::vector<std::array<double, 3>> x;
  std::vector<bool> y;

  double value(const std::array<double, 3>& a, std::array<double, 3>* g = nullptr,
               std::array<std::array<double, 3>, 3>* H = nullptr) const {
    double sum = 0.0;
    if (g) *g = {0.0, 0.0, 0.0};
    if (H) *H = {};
    for (std::size_t i = 0; i < x.size(); ++i) {
      const double u = a[0] * x[i][0] + a[1] * x[i][1] + a[2] * x[i][2];
      const double sgn = y[i] ? 1.0 : -1.0;
      sum += log_cdf(sgn * u);
      const double lam = hazard(sgn * u);
      if (g) {
        for (std::size_t k = 0; k < 3; ++k) (*g)[k] += sgn * lam * x[i][k];
      }
      if (H) {
        const double w = lam * (sgn * u + lam);  // > 0: the log-likelihood is concave (probit)
        for (std::size_t k = 0; k < 3; ++k) {
          for (std::size_t l = 0; l < 3; ++l) (*H)[k][l] -= w * x[i][k] * x[i][l];
        }
      }
    }
    return sum;
  }
};

InputError outcome_error(const std::string& problem) { return parameter_error("outcomes", problem); }

}  // namespace

double FragilitySurfaceFit::median_pga_m_s2(double pgv_over_pga_s) const {
  return std::exp(ln_theta_ref + gamma * std::log(pgv_over_pga_s / v_ref_s));
}

double FragilitySurfaceFit::probability(double pga_m_s2, double pgv_over_pga_s) const {
  if (!(pga_m_s2 > 0.0) || !(pgv_over_pga_s > 0.0)) return 0.0;
  return normal_cdf((std::log(pga_m_s2) - std::log(median_pga_m_s2(pgv_over_pga_s))) / beta);
}

FragilitySurfaceFit fit_fragility_surface(std::span<const SurfaceOutcome> outcomes) {
  std::size_t failures = 0;
  double mean_ln_v = 0.0;
  double lo_v = std::numeric_limits<double>::infinity();
  double hi_v = -lo_v;
  for (std::size_t i = 0; i < outcomes.size(); ++i) {
    const SurfaceOutcome& o = outcomes[i];
    if (!(o.pga_m_s2 > 0.0) || !std::isfinite(o.pga_m_s2) || !(o.pgv_m_s > 0.0) || !std::isfinite(o.pgv_m_s)) {
      throw outcome_error(fmt::format("record {}: PGA {} m/s2 and PGV {} m/s must be positive and finite", i + 1,
                                      o.pga_m_s2, o.pgv_m_s));
    }
    const double ln_v = std::log(o.pgv_m_s / o.pga_m_s2);
    mean_ln_v += ln_v;
    lo_v = std::min(lo_v, ln_v);
    hi_v = std::max(hi_v, ln_v);
    if (o.failed) ++failures;
  }
  const std::size_t n = outcomes.size();
  if (failures == 0 || failures == n) {
    throw outcome_error(fmt::format("{} of {} records failed: the surface cannot be fitted without both outcomes",
                                    failures, n));
  }
  if (failures < 3 || n - failures < 3) {
    throw outcome_error(fmt::format("{} failures and {} survivals: the surface has three parameters, give at least "
                                    "3 records of each outcome", failures, n - failures));
  }
  if (hi_v - lo_v < 1e-9) {
    throw outcome_error("every record has the same PGV/PGA: the surface is a curve in PGA (run the scaled fragility)");
  }
  mean_ln_v /= static_cast<double>(n);
  ProbitLikelihood L;
  for (const SurfaceOutcome& o : outcomes) {
    L.x.push_back({1.0, std::log(o.pga_m_s2), std::log(o.pgv_m_s / o.pga_m_s2) - mean_ln_v});
    L.y.push_back(o.failed);
  }
  // Start at the constant model (a1 = a2 = 0: P = the failure fraction), then Newton with step halving; the probit
  // log-likelihood is concave, so every Newton step from a point where H is negative definite ascends for small t.
  const double fraction = static_cast<double>(failures) / static_cast<double>(n);
  std::array<double, 3> a{boost::math::quantile(kStandardNormal, fraction), 0.0, 0.0};
  FragilitySurfaceFit fit;
  std::array<double, 3> g{};
  std::array<std::array<double, 3>, 3> H{};
  std::array<std::array<double, 3>, 3> Hinv{};
  double f = L.value(a, &g, &H);
  bool converged = false;
  constexpr int kMaxIterations = 200;
  for (int it = 0; it < kMaxIterations; ++it) {
    fit.iterations = it + 1;
    if (!invert3(H, Hinv)) {
      throw outcome_error("ln PGA and ln(PGV/PGA) move together over the records (the information matrix is "
                          "singular): the surface cannot be told from a curve");
    }
    std::array<double, 3> step{};
    for (std::size_t k = 0; k < 3; ++k) {
      for (std::size_t l = 0; l < 3; ++l) step[k] -= Hinv[k][l] * g[l];
    }
    const double decrement = step[0] * g[0] + step[1] * g[1] + step[2] * g[2];  // g^T (-H)^-1 g >= 0
    if (decrement < 1e-12 * (1.0 + std::abs(f))) {  // ln L within ~1e-12 relative of its maximum
      converged = true;
      break;
    }
    double t = 1.0;
    std::array<double, 3> trial{};
    double ft = 0.0;
    for (int halving = 0; halving < 60; ++halving, t *= 0.5) {
      for (std::size_t k = 0; k < 3; ++k) trial[k] = a[k] + t * step[k];
      ft = L.value(trial);
      if (ft >= f) break;
    }
    if (!(ft >= f)) {
      converged = true;  // no ascent left at round-off: the maximum
      break;
    }
    a = trial;
    f = L.value(a, &g, &H);
  }
  // Separated outcomes: the likelihood rises toward 0 as |a| grows without bound; the iteration stops where the gain
  // is below round-off, or runs to its cap.
  // Complete separation shows as ln L -> 0 (every outcome predicted with certainty) with |a| large; quasi-complete
  // separation as beta = 1 / a1 -> 0.
  const bool separated = a[1] > 0.0 && (1.0 / a[1] < kMinimumBeta || -f < 1e-6);
  if (!converged || !(a[1] > 0.0) || separated) {
    if (separated) {
      throw outcome_error(fmt::format("the outcomes are separated by a line in ln PGA and ln(PGV/PGA) (beta -> 0 after "
                                      "{} Newton steps): no finite maximum-likelihood surface; more records near the "
                                      "boundary are needed", fit.iterations));
    }
    throw outcome_error(!converged ? "the maximum-likelihood iteration did not converge (separated outcomes?)"
                                   : "failures do not become likelier with PGA (the fitted slope in ln PGA is not "
                                     "positive): no fragility surface");
  }
  (void)L.value(a, &g, &H);
  std::array<std::array<double, 3>, 3> info{};
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t l = 0; l < 3; ++l) info[k][l] = -H[k][l];
  }
  std::array<std::array<double, 3>, 3> ca{};
  if (!invert3(info, ca)) throw outcome_error("singular information matrix at the maximum");
  fit.beta = 1.0 / a[1];
  fit.ln_theta_ref = -a[0] / a[1];
  fit.gamma = -a[2] / a[1];
  fit.v_ref_s = std::exp(mean_ln_v);
  fit.log_likelihood = f;
  fit.records = n;
  fit.failures = failures;
  // Delta method: J = d(ln theta_ref, gamma, beta) / d(a0, a1, a2).
  const double a1 = a[1];
  const std::array<std::array<double, 3>, 3> J{{{-1.0 / a1, a[0] / (a1 * a1), 0.0},
                                                {0.0, a[2] / (a1 * a1), -1.0 / a1},
                                                {0.0, -1.0 / (a1 * a1), 0.0}}};
  for (std::size_t r = 0; r < 3; ++r) {
    for (std::size_t c = 0; c < 3; ++c) {
      double sum = 0.0;
      for (std::size_t k = 0; k < 3; ++k) {
        for (std::size_t l = 0; l < 3; ++l) sum += J[r][k] * ca[k][l] * J[c][l];
      }
      fit.covariance[r][c] = sum;
    }
  }
  fit.se_ln_theta_ref = std::sqrt(std::max(0.0, fit.covariance[0][0]));
  fit.se_gamma = std::sqrt(std::max(0.0, fit.covariance[1][1]));
  fit.se_beta = std::sqrt(std::max(0.0, fit.covariance[2][2]));
  return fit;
}

AsRecordedResult as_recorded_analysis(const FragilitySpec& spec) {
  if (!spec.motion_sets.empty()) {
    throw parameter_error("motions", "records as recorded are single components (pairs are scaled by their RotD50 "
                                     "PGA: the scaled fragility)");
  }
  if (spec.motions.empty()) throw parameter_error("motions", "the ensemble has no motion");
  if (spec.overturning && spec.overturning->three_d()) {
    throw parameter_error("model", "the three-dimensional model runs under pairs; records as recorded are single "
                                   "components");
  }
  check_objects(spec);
  AsRecordedResult out;
  for (std::size_t i = 0; i < spec.motions.size(); ++i) {
    const GroundMotion& m = *spec.motions[i];
    const double pga = m.pga_m_s2();
    const double pgv = basic_intensity(m).pgv_m_s;
    if (!(pga > 0.0) || !(pgv > 0.0) || !std::isfinite(pga) || !std::isfinite(pgv)) {
      throw parameter_error("motions", fmt::format("motion {} has PGA {} m/s2 and PGV {} m/s: PGV/PGA is not defined",
                                                   i + 1, pga, pgv));
    }
    out.pga_m_s2.push_back(pga);
    out.pgv_m_s.push_back(pgv);
  }
  ensemble::Plan plan;
  plan.motion_columns = {"motion"};
  plan.object_columns = {"object"};
  plan.result_columns = {"failed"};
  plan.identity = "topple fragility as recorded v1";
  for (std::size_t i = 0; i < spec.motions.size(); ++i) {
    ensemble::MotionCase mc;
    mc.base = spec.motions[i];
    mc.values = {ensemble::Value(static_cast<std::int64_t>(i))};
    plan.motions.push_back(std::move(mc));
  }
  std::vector<std::string> names;
  if (spec.sliding) names.emplace_back("slide");
  if (spec.overturning) names.emplace_back("overturn");
  for (const auto& name : names) plan.objects.push_back({{ensemble::Value(name)}});
  plan.chunk_runs = std::max<std::size_t>(1, plan.runs() / 64);
  const bool has_slide = spec.sliding.has_value();
  plan.run = [&spec, has_slide](const GroundMotion& m, std::size_t, std::size_t o0, std::size_t o1,
                                std::span<ensemble::Value> results) {
    for (std::size_t o = o0; o < o1; ++o) {
      const bool failed = has_slide && o == 0
                              ? slide_summary(m, spec.sliding->block).max_abs_displacement_m > spec.sliding->threshold_m
                              : overturns(m, *spec.overturning);
      results[o - o0] = ensemble::Value(failed);
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = spec.threads;
  exec.progress = spec.progress;
  const ensemble::ResultTable table = ensemble::run_in_memory(plan, exec);
  out.runs = table.rows.size();
  const std::size_t no = names.size();
  const std::size_t col = table.columns.size() - 1;
  for (std::size_t o = 0; o < no; ++o) {
    AsRecordedCurve c;
    c.name = names[o];
    std::vector<SurfaceOutcome> points;
    for (std::size_t i = 0; i < spec.motions.size(); ++i) {
      const bool failed = std::get<bool>(table.rows[i * no + o][col]);
      c.failed.push_back(failed);
      points.push_back({out.pga_m_s2[i], out.pgv_m_s[i], failed});
    }
    try {
      c.fit = fit_fragility_surface(points);
    } catch (const InputError& e) {
      c.fit_note = e.problem();
    }
    out.curves.push_back(std::move(c));
  }
  return out;
}

}  // namespace topple
