// Fourier and response spectra (spectra.hpp).
#include "topple/motion/spectra.hpp"

#include <algorithm>
#include <cstdint>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <mutex>

#include <fftw3.h>
#include <fmt/format.h>

#include "motion/fftw_lock.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace detail {

/// FFTW's planner is not thread-safe (FFTW manual, sec. 5.2): plan creation and destruction take this lock; execution
/// of a plan on its own arrays does not need it. The one piece of shared mutable state in the library, and FFTW's
/// (motion/fftw_lock.hpp: stochastic.cpp plans under it too).
std::mutex& fftw_planner_mutex() {
  static std::mutex m;
  return m;
}

}  // namespace detail
namespace {

using detail::fftw_planner_mutex;

/// |DFT| of `x` (length N, real) at k = 0 .. N/2.
std::vector<double> dft_magnitude(std::vector<double> x) {
  const std::size_t n = x.size();
  if (n > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw parameter_error("fft_length", fmt::format("{} samples is beyond FFTW's int sizes", n));
  }
  std::vector<std::complex<double>> out(n / 2 + 1);
  fftw_plan plan = nullptr;
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), x.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                FFTW_ESTIMATE);
  }
  if (plan == nullptr) throw std::runtime_error("FFTW could not plan a real transform");
  fftw_execute(plan);
  {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_destroy_plan(plan);
  }
  std::vector<double> mag(out.size());
  for (std::size_t k = 0; k < out.size(); ++k) mag[k] = std::abs(out[k]);
  return mag;
}

std::size_t next_power_of_two(std::size_t n) {
  std::size_t p = 1;
  while (p < n) p <<= 1;
  return p;
}

/// Vertex of the parabola through (-1, ym), (0, y0), (1, yp), clamped to [-0.5, 0.5]; 0 when not a maximum.
double parabola_vertex(double ym, double y0, double yp) {
  const double curvature = ym - 2.0 * y0 + yp;
  if (!(curvature < 0.0)) return 0.0;
  return std::clamp(0.5 * (ym - yp) / curvature, -0.5, 0.5);
}

}  // namespace

FourierSpectrum fourier_amplitude_spectrum(const GroundMotion& motion, std::size_t fft_length) {
  const GroundMotion uniform = motion.to_uniform();
  const auto a = uniform.accel_m_s2();
  const std::size_t n = fft_length == 0 ? a.size() : fft_length;
  if (n < a.size()) {
    throw parameter_error("fft_length", fmt::format("FFT length {} is shorter than the record ({} samples)", n,
                                                    a.size()));
  }
  std::vector<double> x(n, 0.0);
  std::copy(a.begin(), a.end(), x.begin());
  FourierSpectrum s;
  s.dt_s = uniform.dt_s();
  s.fft_length = n;
  s.amplitude_m_s = dft_magnitude(std::move(x));
  s.frequency_hz.resize(s.amplitude_m_s.size());
  const double df = 1.0 / (static_cast<double>(n) * s.dt_s);
  for (std::size_t k = 0; k < s.frequency_hz.size(); ++k) {
    s.frequency_hz[k] = static_cast<double>(k) * df;
    s.amplitude_m_s[k] *= s.dt_s;
  }
  return s;
}

namespace {

/// Visits the Konno-Ohmachi window of every centre: f(c) before centre c's window, then w(c, k, weight) for each
/// frequency k in it (in increasing k), the one place the weights are formed (konno_ohmachi_smooth below).
template <class BeginCentre, class Weight>
void konno_ohmachi_windows(std::span<const double> f, std::span<const double> centre_hz, double bandwidth,
                           BeginCentre&& begin_centre, Weight&& weight) {
  std::vector<double> log_f(f.size(), 0.0);
  // sin(b (log f - log fc)) = sin(b log f) cos(b log fc) - cos(b log f) sin(b log fc): the sines and cosines of the
  // spectrum's frequencies are computed once, not once per (frequency, centre) pair.
  std::vector<double> sin_f(f.size(), 0.0);
  std::vector<double> cos_f(f.size(), 1.0);
  for (std::size_t k = 1; k < f.size(); ++k) {
    log_f[k] = std::log10(f[k]);
    sin_f[k] = std::sin(bandwidth * log_f[k]);
    cos_f[k] = std::cos(bandwidth * log_f[k]);
  }
  const double half_width = 6.0 * kPi / bandwidth;  // in log10 f
  const double ratio = std::pow(10.0, half_width);
  for (std::size_t c = 0; c < centre_hz.size(); ++c) {
    const double fc = centre_hz[c];
    if (!(fc > 0.0) || !std::isfinite(fc)) {
      throw parameter_error("centre_hz", fmt::format("centre frequencies must be positive, got {} Hz", fc));
    }
    begin_centre(c);
    const double log_fc = std::log10(fc);
    const double sin_c = std::sin(bandwidth * log_fc);
    const double cos_c = std::cos(bandwidth * log_fc);
    auto k = static_cast<std::size_t>(std::lower_bound(f.begin(), f.end(), fc / ratio) - f.begin());
    k = std::max<std::size_t>(k, 1);
    for (; k < f.size() && f[k] <= fc * ratio; ++k) {
      const double x = bandwidth * (log_f[k] - log_fc);
      if (std::abs(x) > 6.0 * kPi) continue;
      double w = 1.0;
      if (std::abs(x) > 1e-8) {  // sin(x)/x = 1 - x^2/6: below 1e-8 the difference is under 1e-16
        const double s = (sin_f[k] * cos_c - cos_f[k] * sin_c) / x;
        w = (s * s) * (s * s);
      }
      weight(c, k, w);
    }
  }
}

/// The weights of one (frequency grid, centres, bandwidth), kept for the next spectra on the same grid: the
/// predominant frequencies of a motion family's column are measured on motions of one length and step, whose weights
/// are the same every time (issue 32: Konno-Ohmachi was 13 % of the default inversion's instructions). Each smoothing
/// with the table adds the same products in the same order as one without it: the same result, bit for bit.
struct KonnoOhmachiTable {
  std::vector<double> frequency_hz;
  std::vector<double> centre_hz;
  double bandwidth = 0.0;
  std::vector<std::size_t> offset;  ///< centre c's weights: [offset[c], offset[c + 1])
  std::vector<std::uint32_t> bin;   ///< their frequency indices
  std::vector<double> weight;
  std::vector<double> den;          ///< per centre: the sum of its weights, in order
  [[nodiscard]] bool is_for(std::span<const double> f, std::span<const double> centres, double b) const {
    return b == bandwidth && std::equal(f.begin(), f.end(), frequency_hz.begin(), frequency_hz.end()) &&
           std::equal(centres.begin(), centres.end(), centre_hz.begin(), centre_hz.end());
  }
};

/// Per thread: the last two grids smoothed (a table is built for a grid seen twice in a row of three calls) and the
/// table of the last grid seen twice. Thread-local: no lock, and each of the family's threads keeps its own column.
struct KonnoOhmachiCache {
  std::array<KonnoOhmachiTable, 2> seen;  ///< keys only (frequency_hz, centre_hz, bandwidth); [0] the most recent
  KonnoOhmachiTable table;
};

}  // namespace

std::vector<double> konno_ohmachi_smooth(const FourierSpectrum& spectrum, std::span<const double> centre_hz,
                                         double bandwidth) {
  if (!(bandwidth > 0.0) || !std::isfinite(bandwidth)) {
    throw parameter_error("bandwidth", fmt::format("the Konno-Ohmachi bandwidth must be positive, got {}", bandwidth));
  }
  const auto& f = spectrum.frequency_hz;
  const auto& amp = spectrum.amplitude_m_s;
  std::vector<double> out(centre_hz.size(), 0.0);
  // The frequency indices are kept in 32 bits: a larger spectrum is smoothed without the table.
  const bool small = f.size() < (std::size_t{1} << 32);
  thread_local KonnoOhmachiCache cache;
  if (small && !cache.table.frequency_hz.empty() && cache.table.is_for(f, centre_hz, bandwidth)) {
    const KonnoOhmachiTable& t = cache.table;
    for (std::size_t c = 0; c < centre_hz.size(); ++c) {
      double num = 0.0;
      for (std::size_t i = t.offset[c]; i < t.offset[c + 1]; ++i) num += t.weight[i] * amp[t.bin[i]];
      out[c] = t.den[c] > 0.0 ? num / t.den[c] : 0.0;
    }
    return out;
  }
  const auto seen_at = [&](std::size_t i) { return cache.seen[i].is_for(f, centre_hz, bandwidth) &&
                                                   !cache.seen[i].frequency_hz.empty(); };
  if (small && (seen_at(0) || seen_at(1))) {
    // The second time of this grid in the last three calls: build its table, then smooth with it (below).
    KonnoOhmachiTable& t = cache.table;
    t.frequency_hz.assign(f.begin(), f.end());
    t.centre_hz.assign(centre_hz.begin(), centre_hz.end());
    t.bandwidth = bandwidth;
    t.offset.assign(centre_hz.size() + 1, 0);
    t.bin.clear();
    t.weight.clear();
    t.den.assign(centre_hz.size(), 0.0);
    konno_ohmachi_windows(
        f, centre_hz, bandwidth, [&](std::size_t c) { t.offset[c] = t.weight.size(); },
        [&](std::size_t c, std::size_t k, double w) {
          t.bin.push_back(static_cast<std::uint32_t>(k));
          t.weight.push_back(w);
          t.den[c] += w;
        });
    t.offset.back() = t.weight.size();
    for (std::size_t c = 0; c < centre_hz.size(); ++c) {
      double num = 0.0;
      for (std::size_t i = t.offset[c]; i < t.offset[c + 1]; ++i) num += t.weight[i] * amp[t.bin[i]];
      out[c] = t.den[c] > 0.0 ? num / t.den[c] : 0.0;
    }
    return out;
  }
  std::vector<double> num(centre_hz.size(), 0.0);
  std::vector<double> den(centre_hz.size(), 0.0);
  konno_ohmachi_windows(
      f, centre_hz, bandwidth, [](std::size_t) {},
      [&](std::size_t c, std::size_t k, double w) {
        num[c] += w * amp[k];
        den[c] += w;
      });
  for (std::size_t c = 0; c < centre_hz.size(); ++c) out[c] = den[c] > 0.0 ? num[c] / den[c] : 0.0;
  if (small) {  // remember this grid (the older of the two keys goes)
    std::swap(cache.seen[0], cache.seen[1]);
    cache.seen[0].frequency_hz.assign(f.begin(), f.end());
    cache.seen[0].centre_hz.assign(centre_hz.begin(), centre_hz.end());
    cache.seen[0].bandwidth = bandwidth;
  }
  return out;
}

std::vector<double> log_spaced(double lo, double hi, std::size_t n) {
  if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi) || n < 2) {
    throw parameter_error("log_spaced", fmt::format("need 0 < lo < hi and n >= 2, got {}, {}, {}", lo, hi, n));
  }
  std::vector<double> v(n);
  const double a = std::log10(lo);
  const double step = (std::log10(hi) - a) / static_cast<double>(n - 1);
  for (std::size_t i = 0; i < n; ++i) v[i] = std::pow(10.0, a + step * static_cast<double>(i));
  v.front() = lo;
  v.back() = hi;
  return v;
}

namespace {
constexpr double kFpBandLow_hz = 0.1;      // predominant frequency band: 0.1 Hz ..
constexpr double kFpBandHigh_hz = 25.0;    // .. min(25 Hz, 0.8 f_Nyquist)
constexpr double kFpPerDecade = 200.0;     // centre frequencies per decade
constexpr double kTpLow_s = 0.02;          // predominant period grid: 0.02 s ..
constexpr double kTpHigh_s = 5.0;          // .. 5 s
constexpr double kTpPerDecade = 100.0;     // periods per decade
}  // namespace

std::size_t predominant_frequency_fft_length(std::size_t samples) { return next_power_of_two(2 * samples); }

std::vector<double> predominant_frequency_centres_hz(double dt_s) {
  const double top = std::min(kFpBandHigh_hz, 0.8 * 0.5 / dt_s);
  if (!(top > kFpBandLow_hz)) return {};
  const auto n_centres = static_cast<std::size_t>(std::floor(kFpPerDecade * std::log10(top / kFpBandLow_hz))) + 1;
  std::vector<double> centres(n_centres);
  for (std::size_t j = 0; j < n_centres; ++j) {
    centres[j] = kFpBandLow_hz * std::pow(10.0, static_cast<double>(j) / kFpPerDecade);
  }
  return centres;
}

double predominant_frequency_hz(const GroundMotion& motion) {
  const GroundMotion uniform = motion.to_uniform();
  const std::vector<double> centres = predominant_frequency_centres_hz(uniform.dt_s());
  if (centres.empty()) {
    throw parameter_error("dt", fmt::format("dt = {} s leaves no frequency in the band 0.1 Hz - 0.8 f_Nyquist",
                                            uniform.dt_s()));
  }
  const FourierSpectrum fas = fourier_amplitude_spectrum(uniform, predominant_frequency_fft_length(uniform.size()));
  const std::vector<double> smooth = konno_ohmachi_smooth(fas, centres, 40.0);
  const auto peak = static_cast<std::size_t>(std::max_element(smooth.begin(), smooth.end()) - smooth.begin());
  if (!(smooth[peak] > 0.0)) {
    throw parameter_error("motion", "the record has no Fourier amplitude in 0.1-25 Hz (identically zero or too "
                                    "short): no predominant frequency");
  }
  double offset = 0.0;
  if (peak > 0 && peak + 1 < smooth.size()) offset = parabola_vertex(smooth[peak - 1], smooth[peak], smooth[peak + 1]);
  return kFpBandLow_hz * std::pow(10.0, (static_cast<double>(peak) + offset) / kFpPerDecade);
}

double mean_period_s(const GroundMotion& motion) {
  const FourierSpectrum fas = fourier_amplitude_spectrum(motion);
  double num = 0.0;
  double den = 0.0;
  for (std::size_t k = 1; k < fas.frequency_hz.size(); ++k) {
    const double f = fas.frequency_hz[k];
    if (f < 0.25 || f > 20.0) continue;
    const double c2 = fas.amplitude_m_s[k] * fas.amplitude_m_s[k];
    num += c2 / f;
    den += c2;
  }
  if (!(den > 0.0)) {
    throw parameter_error("motion", "no Fourier amplitude between 0.25 and 20 Hz: the mean period is undefined");
  }
  return num / den;
}

// ---- Response spectrum -------------------------------------------------------------------------------------------

OscillatorBank::Coefficients OscillatorBank::coefficients(double period, double zeta, double dt) {
  if (!(period > 0.0) || !std::isfinite(period)) {
    throw parameter_error("period", fmt::format("oscillator periods must be positive and finite, got {} s", period));
  }
  if (!(zeta >= 0.0 && zeta < 1.0)) {
    throw parameter_error("damping", fmt::format("the damping ratio must be in [0, 1), got {}", zeta));
  }
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    throw parameter_error("dt", fmt::format("the time step must be positive and finite, got {} s", dt));
  }
  const double w = 2.0 * kPi / period;
  const double beta = std::sqrt(1.0 - zeta * zeta);
  const double wd = w * beta;
  const double e = std::exp(-zeta * w * dt);
  const double sn = std::sin(wd * dt);
  const double cs = std::cos(wd * dt);
  const double w2 = w * w;
  const double k1 = (2.0 * zeta * zeta - 1.0) / (w2 * dt);
  const double k2 = 2.0 * zeta / (w2 * w * dt);
  Coefficients c{};
  // Eq. 2.7d: the free-vibration (A) matrix.
  c.a11 = e * (zeta / beta * sn + cs);
  c.a12 = e * sn / wd;
  c.a21 = -w / beta * e * sn;
  c.a22 = e * (cs - zeta / beta * sn);
  // Eq. 2.7e: the forced (B) matrix for a_g linear in the step, x'' + 2 zeta w x' + w^2 x = -a_g.
  c.b11 = e * ((k1 + zeta / w) * sn / wd + (k2 + 1.0 / w2) * cs) - k2;
  c.b12 = -e * (k1 * sn / wd + k2 * cs) - 1.0 / w2 + k2;
  c.b21 = e * ((k1 + zeta / w) * (cs - zeta / beta * sn) - (k2 + 1.0 / w2) * (wd * sn + zeta * w * cs)) +
          1.0 / (w2 * dt);
  c.b22 = -e * (k1 * (cs - zeta / beta * sn) - k2 * (wd * sn + zeta * w * cs)) - 1.0 / (w2 * dt);
  return c;
}

OscillatorBank::OscillatorBank(std::vector<double> period_s, double damping, double dt_s)
    : period_(std::move(period_s)), damping_(damping), dt_(dt_s) {
  coef_.reserve(period_.size());
  for (double t : period_) coef_.push_back(coefficients(t, damping_, dt_));
}

ResponseSpectrum OscillatorBank::respond(const GroundMotion& motion) const {
  if (!motion.is_uniform() || std::abs(motion.dt_s() - dt_) > 1e-12 * dt_) {
    throw parameter_error("dt", fmt::format("this oscillator bank is for uniform records at dt = {} s; the record is "
                                            "{} at dt = {} s", dt_, motion.is_uniform() ? "uniform" : "irregular",
                                            motion.dt_s()));
  }
  const std::size_t np = period_.size();
  // Structure of arrays so that the inner loop over oscillators vectorises.
  std::vector<double> a11(np), a12(np), a21(np), a22(np), b11(np), b12(np), b21(np), b22(np);
  std::vector<double> two_zeta_w(np), w2(np);
  for (std::size_t p = 0; p < np; ++p) {
    const Coefficients& c = coef_[p];
    a11[p] = c.a11; a12[p] = c.a12; a21[p] = c.a21; a22[p] = c.a22;
    b11[p] = c.b11; b12[p] = c.b12; b21[p] = c.b21; b22[p] = c.b22;
    const double w = 2.0 * kPi / period_[p];
    two_zeta_w[p] = 2.0 * damping_ * w;
    w2[p] = w * w;
  }
  std::vector<double> x(np, 0.0), v(np, 0.0), max_x(np, 0.0), max_v(np, 0.0), max_a(np, 0.0);
  const auto ag = motion.accel_m_s2();
  for (std::size_t i = 0; i + 1 < ag.size(); ++i) {
    const double g0 = ag[i];
    const double g1 = ag[i + 1];
    for (std::size_t p = 0; p < np; ++p) {
      // Eq. 2.7a: (x, x')_{i+1} = A (x, x')_i + B (a_i, a_{i+1}).
      const double xn = a11[p] * x[p] + a12[p] * v[p] + b11[p] * g0 + b12[p] * g1;
      const double vn = a21[p] * x[p] + a22[p] * v[p] + b21[p] * g0 + b22[p] * g1;
      x[p] = xn;
      v[p] = vn;
      max_x[p] = std::max(max_x[p], std::abs(xn));
      max_v[p] = std::max(max_v[p], std::abs(vn));
      max_a[p] = std::max(max_a[p], std::abs(two_zeta_w[p] * vn + w2[p] * xn));
    }
  }
  ResponseSpectrum r;
  r.period_s = period_;
  r.damping = damping_;
  r.sd_m = max_x;
  r.sv_m_s = max_v;
  r.sa_m_s2 = max_a;
  r.psv_m_s.resize(np);
  r.psa_m_s2.resize(np);
  for (std::size_t p = 0; p < np; ++p) {
    const double w = 2.0 * kPi / period_[p];
    r.psv_m_s[p] = w * max_x[p];
    r.psa_m_s2[p] = w * w * max_x[p];
  }
  return r;
}

OscillatorHistory oscillator_response(const GroundMotion& motion, double period, double zeta) {
  const auto ag = motion.accel_m_s2();
  OscillatorHistory h;
  h.displacement_m.assign(ag.size(), 0.0);
  h.velocity_m_s.assign(ag.size(), 0.0);
  h.absolute_accel_m_s2.assign(ag.size(), 0.0);
  const double w = 2.0 * kPi / period;
  // Irregular records: one coefficient set per distinct step length.
  std::map<double, OscillatorBank::Coefficients> cache;
  const auto coefficients_for = [&](double dt) -> const OscillatorBank::Coefficients& {
    auto it = cache.find(dt);
    if (it == cache.end()) it = cache.emplace(dt, OscillatorBank::coefficients(period, zeta, dt)).first;
    return it->second;
  };
  if (motion.is_uniform()) (void)coefficients_for(motion.dt_s());
  else (void)OscillatorBank::coefficients(period, zeta, 1.0);  // validates period and damping
  double x = 0.0;
  double v = 0.0;
  for (std::size_t i = 0; i + 1 < ag.size(); ++i) {
    const double dt = motion.time_s(i + 1) - motion.time_s(i);
    if (dt > 0.0) {
      const auto& c = coefficients_for(motion.is_uniform() ? motion.dt_s() : dt);
      const double xn = c.a11 * x + c.a12 * v + c.b11 * ag[i] + c.b12 * ag[i + 1];  // eq. 2.7a
      const double vn = c.a21 * x + c.a22 * v + c.b21 * ag[i] + c.b22 * ag[i + 1];
      x = xn;
      v = vn;
    }  // a jump (two samples at one instant) leaves x and x' unchanged
    h.displacement_m[i + 1] = x;
    h.velocity_m_s[i + 1] = v;
    h.absolute_accel_m_s2[i + 1] = -(2.0 * zeta * w * v + w * w * x);
  }
  return h;
}

ResponseSpectrum response_spectrum(const GroundMotion& motion, std::span<const double> period_s, double damping) {
  if (motion.is_uniform()) {
    return OscillatorBank(std::vector<double>(period_s.begin(), period_s.end()), damping, motion.dt_s())
        .respond(motion);
  }
  ResponseSpectrum r;
  r.period_s.assign(period_s.begin(), period_s.end());
  r.damping = damping;
  for (double t : period_s) {
    const OscillatorHistory h = oscillator_response(motion, t, damping);
    const auto absmax = [](const std::vector<double>& y) {
      double m = 0.0;
      for (double value : y) m = std::max(m, std::abs(value));
      return m;
    };
    const double w = 2.0 * kPi / t;
    const double sd = absmax(h.displacement_m);
    r.sd_m.push_back(sd);
    r.psv_m_s.push_back(w * sd);
    r.psa_m_s2.push_back(w * w * sd);
    r.sv_m_s.push_back(absmax(h.velocity_m_s));
    r.sa_m_s2.push_back(absmax(h.absolute_accel_m_s2));
  }
  return r;
}

std::vector<double> tp_periods_s() {
  const auto n = static_cast<std::size_t>(std::floor(kTpPerDecade * std::log10(kTpHigh_s / kTpLow_s) + 0.5)) + 1;
  std::vector<double> periods(n);
  for (std::size_t j = 0; j < n; ++j) periods[j] = kTpLow_s * std::pow(10.0, static_cast<double>(j) / kTpPerDecade);
  return periods;
}

double predominant_period_s(const GroundMotion& motion) {
  const std::vector<double> periods = tp_periods_s();
  const std::size_t n = periods.size();
  const ResponseSpectrum r = response_spectrum(motion, periods, 0.05);
  const auto& psa = r.psa_m_s2;
  const auto peak = static_cast<std::size_t>(std::max_element(psa.begin(), psa.end()) - psa.begin());
  if (!(psa[peak] > 0.0)) throw parameter_error("motion", "the record is identically zero: no predominant period");
  double offset = 0.0;
  if (peak > 0 && peak + 1 < n) offset = parabola_vertex(psa[peak - 1], psa[peak], psa[peak + 1]);
  return kTpLow_s * std::pow(10.0, (static_cast<double>(peak) + offset) / kTpPerDecade);
}

}  // namespace topple
