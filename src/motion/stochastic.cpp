// The stochastic point-source method of Boore (2003) (stochastic.hpp; docs/method.md).
#include "topple/motion/stochastic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <mutex>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include <fftw3.h>
#include <fmt/format.h>

#include "motion/fftw_lock.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"

namespace topple {
namespace {

// Boore (2016), BSSA 106(1):316-320, the generic amplification for Vs30 = 760 m/s relative to a source with beta =
// 3.5 km/s and rho = 2.72 g/cm^3 (the model's defaults): frequency (Hz) and amplification.
constexpr std::array<double, 25> kSiteF = {0.010, 0.015, 0.021, 0.031, 0.045, 0.065, 0.095, 0.138, 0.200,
                                           0.291, 0.423, 0.615, 0.894, 1.301, 1.892, 2.751, 4.000, 5.817,
                                           8.459, 12.301, 17.889, 26.014, 37.830, 55.012, 80.000};
constexpr std::array<double, 25> kSiteA = {1.00, 1.01, 1.02, 1.02, 1.04, 1.06, 1.09, 1.13, 1.18, 1.25, 1.32, 1.41, 1.51,
                                           1.64, 1.80, 1.99, 2.18, 2.38, 2.56, 2.75, 2.95, 3.17, 3.42, 3.68, 3.96};

/// The segment of the site table holding f: index i with kSiteF[i] <= f < kSiteF[i + 1]; -1 below, 24 above.
int site_segment(double f) {
  if (f < kSiteF.front()) return -1;
  if (f >= kSiteF.back()) return static_cast<int>(kSiteF.size()) - 1;
  const auto it = std::upper_bound(kSiteF.begin(), kSiteF.end(), f);
  return static_cast<int>(it - kSiteF.begin()) - 1;
}

/// d ln G / d ln f (piecewise constant: G is log-log linear between the nodes, constant outside).
double site_log_slope(double f, const StochasticModel& model) {
  if (!model.generic_rock_site) return 0.0;
  const int i = site_segment(f);
  if (i < 0 || i >= static_cast<int>(kSiteF.size()) - 1) return 0.0;
  return std::log(kSiteA[i + 1] / kSiteA[i]) / std::log(kSiteF[i + 1] / kSiteF[i]);
}

/// d ln A / d ln f at f (the header's A): source 2 / (1 + (f/fc)^2), anelastic -(1 - eta) pi R f^(1-eta) / (q0 beta),
/// kappa -pi kappa0 f, site.
double log_slope(double f, double fc, double r_km, const StochasticModel& m) {
  const double x = f / fc;
  return 2.0 / (1.0 + x * x) - (1.0 - m.q_eta) * kPi * r_km * std::pow(f, 1.0 - m.q_eta) / (m.q0 * m.beta_km_s) -
         kPi * m.kappa0_s * f + site_log_slope(f, m);
}

/// Bisection of a decreasing function g on [lo, hi] in log: the root, or an end where g keeps its sign.
template <class G>
double log_bisect(G g, double lo, double hi, int iterations) {
  if (g(lo) <= 0.0) return lo;
  if (g(hi) >= 0.0) return hi;
  double a = std::log(lo), b = std::log(hi);
  for (int i = 0; i < iterations; ++i) {
    const double mid = 0.5 * (a + b);
    if (g(std::exp(mid)) > 0.0) a = mid;
    else b = mid;
  }
  return std::exp(0.5 * (a + b));
}

/// The smallest 2^a 3^b 5^c >= n, even (FFTW's fast sizes).
std::size_t smooth_length(std::size_t n) {
  std::size_t best = std::numeric_limits<std::size_t>::max();
  for (std::size_t p2 = 2; p2 < 2 * n + 2; p2 *= 2) {
    for (std::size_t p3 = p2; p3 < 2 * n + 2; p3 *= 3) {
      for (std::size_t p5 = p3; p5 < 2 * n + 2; p5 *= 5) {
        if (p5 >= n) {
          best = std::min(best, p5);
          break;
        }
      }
    }
  }
  return best;
}

void check_range(const char* field, double v, double lo, double hi, const char* unit) {
  if (!(v >= lo && v <= hi)) {
    throw parameter_error(field, fmt::format("must lie in [{}, {}] {}, got {}", lo, hi, unit, v));
  }
}

}  // namespace

void validate(const StochasticSpec& s) {
  check_range("magnitude", s.magnitude, 2.0, 9.0, "");
  check_range("distance_km", s.distance_km, 1.0, 1000.0, "km");
  check_range("dt_s", s.dt_s, 1e-4, 0.05, "s");
  const StochasticModel& m = s.model;
  check_range("stress_drop_bar", m.stress_drop_bar, 1.0, 1000.0, "bar");
  check_range("beta_km_s", m.beta_km_s, 1.0, 5.0, "km/s");
  check_range("rho_g_cm3", m.rho_g_cm3, 1.5, 4.0, "g/cm3");
  check_range("q0", m.q0, 10.0, 10000.0, "");
  check_range("q_eta", m.q_eta, 0.0, 0.95, "");
  check_range("kappa0_s", m.kappa0_s, 0.0, 0.2, "s");
  check_range("spreading_transition_km", m.spreading_transition_km, 1.0, 1000.0, "km");
  check_range("path_duration_s_per_km", m.path_duration_s_per_km, 0.0, 1.0, "s/km");
}

double seismic_moment_dyne_cm(double magnitude) { return std::pow(10.0, 1.5 * magnitude + 16.05); }

double corner_frequency_hz(double magnitude, const StochasticModel& model) {
  return 4.906e6 * model.beta_km_s * std::cbrt(model.stress_drop_bar / seismic_moment_dyne_cm(magnitude));
}

double stochastic_duration_s(double magnitude, double distance_km, const StochasticModel& model) {
  return 1.0 / corner_frequency_hz(magnitude, model) + model.path_duration_s_per_km * distance_km;
}

double site_amplification(double f_hz, const StochasticModel& model) {
  if (!model.generic_rock_site) return 1.0;
  const int i = site_segment(f_hz);
  if (i < 0) return kSiteA.front();
  if (i >= static_cast<int>(kSiteF.size()) - 1) return kSiteA.back();
  const double w = std::log(f_hz / kSiteF[i]) / std::log(kSiteF[i + 1] / kSiteF[i]);
  return std::exp((1.0 - w) * std::log(kSiteA[i]) + w * std::log(kSiteA[i + 1]));
}

double target_fas_m_s(double f_hz, double magnitude, double distance_km, const StochasticModel& m) {
  // C M0 in cm/s per (2 pi f)^2 s^2: R_tp V F / (4 pi rho beta^3 R0) with beta^3 in km^3/s^3 and R0 = 1 km, the
  // factor 1e-20 turning (dyne cm) / (g/cm^3 km^3/s^3 km) into cm s (Boore 2003, eq. 3; SMSIM's constant).
  const double c = 0.55 * std::numbers::sqrt2 / 2.0 * 2.0 /
                   (4.0 * kPi * m.rho_g_cm3 * m.beta_km_s * m.beta_km_s * m.beta_km_s) * 1e-20;
  const double fc = corner_frequency_hz(magnitude, m);
  const double w = 2.0 * kPi * f_hz;
  const double source = c * seismic_moment_dyne_cm(magnitude) * w * w / (1.0 + (f_hz / fc) * (f_hz / fc));
  const double rt = m.spreading_transition_km;
  const double z = distance_km <= rt ? 1.0 / distance_km : (1.0 / rt) * std::sqrt(rt / distance_km);
  const double q = m.q0 * std::pow(f_hz, m.q_eta);
  const double path = z * std::exp(-kPi * f_hz * distance_km / (q * m.beta_km_s));
  const double site = std::exp(-kPi * m.kappa0_s * f_hz) * site_amplification(f_hz, m);
  return source * path * site / 100.0;  // cm/s -> m/s
}

double fas_peak_frequency_hz(double magnitude, double distance_km, const StochasticModel& model) {
  const double fc = corner_frequency_hz(magnitude, model);
  return log_bisect([&](double f) { return log_slope(f, fc, distance_km, model); }, 0.01, 100.0, 40);
}

GroundMotion synthesize_stochastic(const StochasticSpec& spec) {
  validate(spec);
  const StochasticModel& m = spec.model;
  const double fc = corner_frequency_hz(spec.magnitude, m);
  const double t_gm = stochastic_duration_s(spec.magnitude, spec.distance_km, m);
  // Saragoni-Hart window (Boore 2003, eq. 11) to t_eta = 2 T_gm (his f_TB = 2), eps 0.2, eta 0.05.
  constexpr double eps = 0.2, eta = 0.05;
  const double b = -eps * std::log(eta) / (1.0 + eps * (std::log(eps) - 1.0));
  const double c = b / eps;
  const double a = std::pow(std::numbers::e / eps, b);
  const double t_eta = 2.0 * t_gm;
  // Padding: the filter A(f) is zero-phase, so it spreads each sample both ways; its slowest part (the source's
  // corner) decays as exp(-2 pi fc |t|): e^-pi within 1/(2 fc). At least 2 s, so that objects come to rest.
  const double pad = std::max(2.0, 0.5 / fc);
  const double dt = spec.dt_s;
  const auto n_window = static_cast<std::size_t>(std::ceil(t_eta / dt)) + 1;
  const auto n_pad = static_cast<std::size_t>(std::ceil(pad / dt));
  const std::size_t n = smooth_length(n_window + 2 * n_pad);
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max()) ||
      static_cast<double>(n) * dt > GroundMotionLimits::max_duration_s) {
    throw parameter_error("dt_s", fmt::format("{} samples of {} s are too many for one motion", n, dt));
  }

  std::vector<double> x(n, 0.0);
  PortableRandom rng(spec.seed);
  for (std::size_t i = 0; i < n_window; ++i) {
    const double t = static_cast<double>(i) * dt / t_eta;
    const double w = t > 0.0 ? a * std::pow(t, b) * std::exp(-c * t) : 0.0;
    x[n_pad + i] = w * rng.normal();
  }
  std::vector<std::complex<double>> spec_c(n / 2 + 1);
  fftw_plan fwd = nullptr, inv = nullptr;
  {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    fwd = fftw_plan_dft_r2c_1d(static_cast<int>(n), x.data(), reinterpret_cast<fftw_complex*>(spec_c.data()),
                               FFTW_ESTIMATE);
    inv = fftw_plan_dft_c2r_1d(static_cast<int>(n), reinterpret_cast<fftw_complex*>(spec_c.data()), x.data(),
                               FFTW_ESTIMATE);
  }
  const auto destroy = [&] {
    const std::lock_guard<std::mutex> lock(detail::fftw_planner_mutex());
    if (fwd != nullptr) fftw_destroy_plan(fwd);
    if (inv != nullptr) fftw_destroy_plan(inv);
  };
  if (fwd == nullptr || inv == nullptr) {
    destroy();
    throw std::runtime_error("FFTW could not plan the stochastic method's transforms");
  }
  // FFTW_ESTIMATE plans do not touch the arrays: the noise is still in x.
  fftw_execute(fwd);
  // Unit mean square amplitude over 0 < f_k < f_Nyquist (Boore 2003, sec. 3). The dt of the continuous transform
  // cancels in the normalisation.
  double sum_sq = 0.0;
  for (std::size_t k = 1; k < n / 2; ++k) sum_sq += std::norm(spec_c[k]);
  const double rms = std::sqrt(sum_sq / static_cast<double>(n / 2 - 1));
  const double df = 1.0 / (static_cast<double>(n) * dt);
  spec_c[0] = 0.0;
  spec_c[n / 2] = 0.0;
  for (std::size_t k = 1; k < n / 2; ++k) {
    spec_c[k] *= target_fas_m_s(static_cast<double>(k) * df, spec.magnitude, spec.distance_km, m) / rms;
  }
  fftw_execute(inv);
  destroy();
  // The c2r sum is unnormalised: a_i = (1 / (n dt)) sum_k Y_k exp(2 pi i k i / n), Y_k in m/s, so that the motion's
  // Fourier amplitude dt |sum_i a_i exp(-...)| is |Y_k|.
  const double scale = 1.0 / (static_cast<double>(n) * dt);
  for (double& v : x) v *= scale;

  RecordMetadata meta;
  meta.format = "synthetic";
  meta.units_as_read = "m/s2";
  meta.event = fmt::format("synthetic stochastic point-source motion (Boore 2003): M {:.4g}, R {:.4g} km, stress "
                           "{:.4g} bar, kappa0 {:.4g} s, T_gm {:.4g} s, seed {}",
                           spec.magnitude, spec.distance_km, m.stress_drop_bar, m.kappa0_s, t_gm, spec.seed);
  return GroundMotion::uniform(std::move(x), dt, 0.0, std::move(meta));
}

StochasticSpec boore_scenario_for_peak(double u_magnitude, double f_hz, std::uint64_t seed) {
  if (!(f_hz > 0.0) || !std::isfinite(f_hz)) {
    throw parameter_error("freq_hz", fmt::format("must be positive and finite, got {}", f_hz));
  }
  StochasticSpec s;
  s.seed = seed;
  s.dt_s = std::min(0.01, 1.0 / (20.0 * f_hz));
  StochasticModel& m = s.model;
  const auto peak = [&](double mag, double r) { return fas_peak_frequency_hz(mag, r, m); };
  // The peak falls with M and with R: the magnitudes that can peak at f for some R in [R_min, R_max] are those with
  // peak(M, R_max) <= f <= peak(M, R_min), an interval [m_lo, m_hi] (bisection in M, 30 steps: 3e-9 of the range).
  const auto bisect_m = [&](double r) {  // the M at which peak(M, r) = f, clamped to the prior's range
    double lo = kBooreMagnitudeMin, hi = kBooreMagnitudeMax;
    if (peak(lo, r) <= f_hz) return lo;
    if (peak(hi, r) >= f_hz) return hi;
    for (int i = 0; i < 30; ++i) {
      const double mid = 0.5 * (lo + hi);
      if (peak(mid, r) > f_hz) lo = mid;
      else hi = mid;
    }
    return 0.5 * (lo + hi);
  };
  const double m_lo = bisect_m(kBooreDistanceMaxKm);
  const double m_hi = bisect_m(kBooreDistanceMinKm);
  const double u = std::clamp(u_magnitude, 0.0, 1.0);
  s.magnitude = m_lo + u * (std::max(m_hi, m_lo) - m_lo);
  s.distance_km = log_bisect([&](double r) { return peak(s.magnitude, r) - f_hz; }, kBooreDistanceMinKm,
                             kBooreDistanceMaxKm, 30);
  if (peak(s.magnitude, kBooreDistanceMinKm) < f_hz) {
    // Beyond the prior's reach at kappa0 = 0.04 s: a harder site (smaller kappa0) moves the peak up.
    s.distance_km = kBooreDistanceMinKm;
    const auto with_kappa = [&](double k) {
      StochasticModel mk = m;
      mk.kappa0_s = k;
      return fas_peak_frequency_hz(s.magnitude, s.distance_km, mk) - f_hz;
    };
    // Decreasing in kappa0: bisect on [kappa_min, 0.04] (the function rises as kappa0 falls).
    double lo = kBooreKappaMinS, hi = m.kappa0_s;
    if (with_kappa(lo) <= 0.0) {
      m.kappa0_s = lo;
    } else {
      for (int i = 0; i < 30; ++i) {
        const double mid = 0.5 * (lo + hi);
        if (with_kappa(mid) > 0.0) lo = mid;
        else hi = mid;
      }
      m.kappa0_s = 0.5 * (lo + hi);
    }
  }
  return s;
}

BooreDraw draw_boore2003(std::uint64_t seed, double f_hz) {
  std::optional<GroundMotion> best;
  StochasticSpec best_spec;
  double best_measured = 0.0, best_miss = std::numeric_limits<double>::infinity();
  int tries = 0;
  SplitMix64 seeds(seed);  // try t: its own u and noise seed, the same for every f (common random numbers)
  for (int t = 1; t <= kBooreMaxTries; ++t) {
    PortableRandom rng(seeds.next());
    const double u = rng.uniform();
    const StochasticSpec spec = boore_scenario_for_peak(u, f_hz, rng.next());
    GroundMotion m = synthesize_stochastic(spec);
    const double measured = predominant_frequency_hz(m);
    const double miss = std::abs(std::log(measured / f_hz));
    if (miss < best_miss) {
      best_miss = miss;
      best.emplace(std::move(m));
      best_spec = spec;
      best_measured = measured;
    }
    tries = t;
    if (miss <= std::log(kBooreAcceptRatio)) break;
  }
  return BooreDraw{std::move(*best), best_spec, best_measured, tries};
}

}  // namespace topple
