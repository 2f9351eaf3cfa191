// Synthetic ground motions (synthesis.hpp). Compiled with -ffp-contract=off (src/CMakeLists.txt): the bits of a
// motion depend on the order of IEEE operations written here and on nothing else.
#include "topple/motion/synthesis.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/core/units.hpp"
#include "topple/core/enum_names.hpp"

namespace topple {

// ---- Portable elementary functions -------------------------------------------------------------------------------
namespace {

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^20 (fdlibm's constants).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kInvLn2 = 1.44269504088896338700e+00;
constexpr double kSqrtHalf = 0.70710678118654752440;

}  // namespace

double portable_exp(double x) noexcept {
  if (std::isnan(x)) return x;
  if (x > 709.782712893383973096) return std::numeric_limits<double>::infinity();
  if (x < -745.13321910194110842) return 0.0;
  // x = k ln2 + r, |r| <= ln2 / 2 (Cody & Waite reduction): floor is exact, the products below are exact or
  // correctly rounded.
  const double k = std::floor(x * kInvLn2 + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  // Taylor series of e^r to r^14 / 14!: |r|^15 / 15! < 2e-19 for |r| <= 0.35.
  double p = 1.0 / 87178291200.0;  // 1/14!
  constexpr std::array<double, 14> kInvFactorial = {
      1.0 / 6227020800.0, 1.0 / 479001600.0, 1.0 / 39916800.0, 1.0 / 3628800.0, 1.0 / 362880.0,
      1.0 / 40320.0,      1.0 / 5040.0,      1.0 / 720.0,      1.0 / 120.0,     1.0 / 24.0,
      1.0 / 6.0,          0.5,               1.0,              1.0};
  for (double c : kInvFactorial) p = p * r + c;
  return std::ldexp(p, static_cast<int>(k));  // exact scaling (one rounding for subnormal results)
}

double portable_log(double x) noexcept {
  if (std::isnan(x) || x < 0.0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return -std::numeric_limits<double>::infinity();
  if (std::isinf(x)) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // x = m 2^e, m in [0.5, 1): exact
  if (m < kSqrtHalf) {
    m *= 2.0;
    --e;
  }
  // log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716: series in z = s^2 to z^11 / 23 (< 2e-19).
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double z = s * s;
  double q = 1.0 / 23.0;
  for (double c : {1.0 / 21.0, 1.0 / 19.0, 1.0 / 17.0, 1.0 / 15.0, 1.0 / 13.0, 1.0 / 11.0, 1.0 / 9.0, 1.0 / 7.0,
                   1.0 / 5.0, 1.0 / 3.0}) {
    q = q * z + c;
  }
  const double log_m = 2.0 * s + 2.0 * s * (z * q);
  const double k = static_cast<double>(e);
  return k * kLn2Hi + (k * kLn2Lo + log_m);
}

// ---- Random numbers ----------------------------------------------------------------------------------------------

std::uint64_t SplitMix64::next() noexcept {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

PortableRandom::PortableRandom(std::uint64_t seed) noexcept {
  SplitMix64 sm(seed);
  for (auto& word : s_) word = sm.next();  // never all zero: SplitMix64 is a bijection of distinct states
}

namespace {
constexpr std::uint64_t rotl(std::uint64_t x, int k) noexcept { return (x << k) | (x >> (64 - k)); }
}  // namespace

std::uint64_t PortableRandom::next() noexcept {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double PortableRandom::uniform() noexcept {
  return static_cast<double>(next() >> 11) * 0x1.0p-53;  // exact: 53-bit integer times a power of two
}

double PortableRandom::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  // Rejection accepts pi/4 of the pairs; 200 rejections in a row has probability 0.2146^200 < 1e-133.
  constexpr int kMaxTries = 200;
  for (int attempt = 0; attempt < kMaxTries; ++attempt) {
    const double u = 2.0 * uniform() - 1.0;
    const double v = 2.0 * uniform() - 1.0;
    const double s = u * u + v * v;
    if (s >= 1.0 || s == 0.0) continue;
    const double factor = std::sqrt(-2.0 * portable_log(s) / s);
    spare_ = v * factor;
    has_spare_ = true;
    return u * factor;
  }
  throw std::runtime_error("PortableRandom::normal: no pair accepted in 200 tries (generator broken)");
}

// ---- Names -------------------------------------------------------------------------------------------------------

FilterModel parse_filter_model(std::string_view name, const std::string& field) {
  if (name == "kanai-tajimi" || name == "kt") return FilterModel::kanai_tajimi;
  if (name == "clough-penzien" || name == "cp") return FilterModel::clough_penzien;
  throw parameter_error(field, fmt::format("unknown filter model '{}' (known: kanai-tajimi, clough-penzien)", name));
}

constexpr std::array<EnumName<FilterModel>, 2> kFilterModelNames{{
    {FilterModel::kanai_tajimi, "kanai-tajimi"},
    {FilterModel::clough_penzien, "clough-penzien"},
}};

std::string_view filter_model_name(FilterModel model) { return enum_name(kFilterModelNames, model); }

EnvelopeKind parse_envelope_kind(std::string_view name, const std::string& field) {
  if (name == "saragoni-hart") return EnvelopeKind::saragoni_hart;
  if (name == "jennings") return EnvelopeKind::jennings;
  throw parameter_error(field, fmt::format("unknown envelope '{}' (known: saragoni-hart, jennings)", name));
}

constexpr std::array<EnumName<EnvelopeKind>, 2> kEnvelopeKindNames{{
    {EnvelopeKind::saragoni_hart, "saragoni-hart"},
    {EnvelopeKind::jennings, "jennings"},
}};

std::string_view envelope_kind_name(EnvelopeKind kind) { return enum_name(kEnvelopeKindNames, kind); }

// ---- Calibration -------------------------------------------------------------------------------------------------
namespace {

// kappa = mean over seeds of predominant_frequency_hz(motion) / f_g at the nodes zeta_g x f_g below (T = 20 s,
// dt = 0.01 s, Saragoni-Hart envelope, 200 seeds per node). Produced by
// `test_synthesis --gtest_also_run_disabled_tests --gtest_filter='*DISABLED_CalibrationTable*'`; docs/method.md.
// Bilinear in (zeta_g, log f_g), constant beyond the f_g nodes. Rows: zeta_g; in each, the Kanai-Tajimi filter's
// kappa over the f_g nodes, then the Clough-Penzien filter's (FilterModel order).
constexpr std::array<double, 5> kCalibrationDamping = {0.1, 0.2, 0.3, 0.4, 0.5};
constexpr std::array<double, 5> kCalibrationFrequency = {0.5, 1.0, 2.0, 4.0, 8.0};
using KappaRow = std::array<double, 5>;                     // [frequency]
using KappaTable = std::array<std::array<KappaRow, 2>, 5>;  // [damping][filter: Kanai-Tajimi, Clough-Penzien]
constexpr KappaTable kKappa = {{
    {{{0.941, 0.953, 0.975, 0.978, 0.977}, {0.941, 0.953, 0.975, 0.978, 0.977}}},
    {{{0.871, 0.858, 0.901, 0.900, 0.896}, {0.872, 0.869, 0.904, 0.915, 0.941}}},
    {{{0.824, 0.785, 0.770, 0.705, 0.681}, {0.824, 0.786, 0.802, 0.790, 0.843}}},
    {{{0.805, 0.732, 0.660, 0.539, 0.455}, {0.808, 0.744, 0.713, 0.658, 0.692}}},
    {{{0.782, 0.680, 0.592, 0.442, 0.335}, {0.794, 0.698, 0.641, 0.578, 0.580}}},
}};

/// Index j >= 1 and weight w of x between nodes[j - 1] and nodes[j] (w clamped to [0, 1]).
template <std::size_t N>
std::pair<std::size_t, double> bracket(const std::array<double, N>& nodes, double x) {
  std::size_t j = 1;
  while (j + 1 < N && x > nodes[j]) ++j;
  const double w = (x - nodes[j - 1]) / (nodes[j] - nodes[j - 1]);
  return {j, std::clamp(w, 0.0, 1.0)};
}

}  // namespace

double predominant_frequency_ratio(double zeta_g, FilterModel model, double f_g_hz) {
  if (!(zeta_g >= kCalibrationDamping.front() && zeta_g <= kCalibrationDamping.back())) {
    throw parameter_error("ground_damping", fmt::format("zeta_g = {} is outside the calibrated range [{}, {}]",
                                                        zeta_g, kCalibrationDamping.front(),
                                                        kCalibrationDamping.back()));
  }
  if (!(f_g_hz > 0.0) || !std::isfinite(f_g_hz)) {
    throw parameter_error("f_g", fmt::format("the filter frequency must be positive, got {} Hz", f_g_hz));
  }
  const std::size_t filter = model == FilterModel::kanai_tajimi ? 0 : 1;
  const auto [i, wz] = bracket(kCalibrationDamping, zeta_g);
  std::array<double, 5> log_f{};
  for (std::size_t k = 0; k < log_f.size(); ++k) log_f[k] = portable_log(kCalibrationFrequency[k]);
  // Not a structured binding: a lambda may not capture one before C++20 compilers caught up (clang < 16, which the
  // fuzz preset uses).
  const std::pair<std::size_t, double> jf = bracket(log_f, portable_log(f_g_hz));
  const std::size_t j = jf.first;
  const double wf = jf.second;
  const auto row = [&](std::size_t r) {
    const KappaRow& kappa = kKappa[r][filter];
    return kappa[j - 1] + wf * (kappa[j] - kappa[j - 1]);
  };
  return row(i - 1) + wz * (row(i) - row(i - 1));
}

double ground_frequency_for_request_hz(double request_hz, double zeta_g, FilterModel model) {
  if (!(request_hz > 0.0) || !std::isfinite(request_hz)) {
    throw parameter_error("freq", fmt::format("the requested frequency must be positive, got {} Hz", request_hz));
  }
  // Fixed point f_g = request / kappa(f_g): kappa changes by at most 0.12 per doubling of f_g around 0.3-0.98, so the
  // map contracts by a factor below 0.3 and 100 iterations are far more than round-off needs.
  double f_g = request_hz / predominant_frequency_ratio(zeta_g, model, request_hz);
  for (int it = 0; it < 100; ++it) {
    const double next = request_hz / predominant_frequency_ratio(zeta_g, model, f_g);
    const bool converged = std::abs(next - f_g) <= 1e-13 * f_g;
    f_g = next;
    if (converged) return f_g;
  }
  throw std::runtime_error(fmt::format("ground_frequency_for_request_hz: no convergence in 100 iterations for {} Hz, "
                                       "zeta_g = {}", request_hz, zeta_g));
}

// ---- Validation --------------------------------------------------------------------------------------------------

void validate(const SynthesisSpec& s) {
  const auto finite_positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  using Limits = GroundMotionLimits;
  if (!finite_positive(s.pga_m_s2) || s.pga_m_s2 > Limits::max_record_accel_m_s2) {
    throw parameter_error("pga", fmt::format("the PGA must be positive and at most {:.6g} m/s2 (100 g, the limit of a "
                                             "ground motion), got {} m/s2",
                                             Limits::max_record_accel_m_s2, s.pga_m_s2));
  }
  if (!(s.dt_s >= Limits::min_dt_s && s.dt_s <= 0.1)) {
    throw parameter_error("dt", fmt::format("the time step must be in [{:.6g}, 0.1] s, got {} s", Limits::min_dt_s,
                                            s.dt_s));
  }
  const double f = s.predominant_frequency_hz;
  const double f_max = std::min(20.0, 0.1 / s.dt_s);
  if (!std::isfinite(f) || f < 0.2 || f > f_max) {
    throw parameter_error("freq", fmt::format("the predominant frequency must be in [0.2, {:.6g}] Hz (20 Hz, and "
                                              "at least 10 samples per period at dt = {} s), got {} Hz",
                                              f_max, s.dt_s, f));
  }
  const double t_min = std::max(5.0 / f, 100.0 * s.dt_s);
  if (!std::isfinite(s.duration_s) || s.duration_s < t_min) {
    throw parameter_error("duration", fmt::format("the duration must be at least {:.6g} s (5 predominant periods "
                                                  "and 100 samples), got {} s", t_min, s.duration_s));
  }
  if (s.duration_s > Limits::max_duration_s) {
    throw parameter_error("duration", fmt::format("the duration must be at most {:.6g} s (6 h, the limit of a ground "
                                                  "motion), got {} s",
                                                  Limits::max_duration_s, s.duration_s));
  }
  if (s.duration_s / s.dt_s > static_cast<double>(Limits::max_samples)) {
    throw parameter_error("duration", fmt::format("{} s at dt = {} s is more than {} samples (the limit of a ground "
                                                  "motion)",
                                                  s.duration_s, s.dt_s, Limits::max_samples));
  }
  if (!(s.ground_damping >= 0.1 && s.ground_damping <= 0.5)) {
    throw parameter_error("ground_damping", fmt::format("zeta_g must be in [0.1, 0.5] (the calibrated range), got {}",
                                                        s.ground_damping));
  }
  if (!(s.high_pass_ratio > 0.0 && s.high_pass_ratio <= 0.5)) {
    throw parameter_error("high_pass_ratio", fmt::format("f_f / f_g must be in (0, 0.5], got {}", s.high_pass_ratio));
  }
  if (!(s.high_pass_damping >= 0.5 && s.high_pass_damping <= 2.0)) {
    throw parameter_error("high_pass_damping", fmt::format("zeta_f must be in [0.5, 2], got {}", s.high_pass_damping));
  }
  if (!(s.envelope_peak_fraction >= 0.05 && s.envelope_peak_fraction <= 0.5)) {
    throw parameter_error("envelope_peak_fraction",
                          fmt::format("eps must be in [0.05, 0.5], got {}", s.envelope_peak_fraction));
  }
  if (!(s.envelope_end_level >= 0.001 && s.envelope_end_level <= 0.5)) {
    throw parameter_error("envelope_end_level",
                          fmt::format("eta must be in [0.001, 0.5], got {}", s.envelope_end_level));
  }
  if (!(s.jennings_rise_fraction > 0.0 && s.jennings_rise_fraction < s.jennings_plateau_end_fraction &&
        s.jennings_plateau_end_fraction < 1.0)) {
    throw parameter_error("jennings_rise_fraction",
                          fmt::format("the Jennings envelope needs 0 < t1/T < t2/T < 1, got t1/T = {}, t2/T = {}",
                                      s.jennings_rise_fraction, s.jennings_plateau_end_fraction));
  }
}

// ---- Envelope ----------------------------------------------------------------------------------------------------

double envelope_at(const SynthesisSpec& s, double t) {
  const double T = s.duration_s;
  if (!(t > 0.0)) return 0.0;
  const double eta = s.envelope_end_level;
  if (s.envelope == EnvelopeKind::saragoni_hart) {
    // e = (t / tp)^b exp(b (1 - t / tp)), tp = eps T; e(T) = eta gives b = ln eta / (1 - 1/eps - ln eps)
    // (Boore 2003, eq. 11: b = -eps ln eta / (1 + eps (ln eps - 1)), the same number).
    const double eps = s.envelope_peak_fraction;
    const double b = portable_log(eta) / (1.0 - 1.0 / eps - portable_log(eps));
    const double x = t / (eps * T);
    return portable_exp(b * (portable_log(x) + 1.0 - x));
  }
  const double t1 = s.jennings_rise_fraction * T;
  const double t2 = s.jennings_plateau_end_fraction * T;
  if (t < t1) return (t / t1) * (t / t1);
  if (t <= t2) return 1.0;
  const double c = -portable_log(eta) / (T - t2);  // e(T) = eta
  return portable_exp(-c * (t - t2));
}

// ---- Exact discretisation of the filters -------------------------------------------------------------------------
namespace {

constexpr std::size_t kMaxAug = 6;  // 4 states + input + input slope
using Matrix = std::array<std::array<double, kMaxAug>, kMaxAug>;

Matrix multiply(const Matrix& a, const Matrix& b, std::size_t n) {
  Matrix c{};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) sum = sum + a[i][k] * b[k][j];
      c[i][j] = sum;
    }
  }
  return c;
}

/// exp(M) by scaling and squaring of the Taylor series (Moler & Van Loan 2003, method 3): M / 2^s has norm <= 1/2,
/// the series to degree 20 leaves < 1e-25 of it, then s squarings. Only +, -, *, / and ldexp: portable.
Matrix expm(Matrix m, std::size_t n) {
  double norm = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    double row = 0.0;
    for (std::size_t j = 0; j < n; ++j) row = row + std::abs(m[i][j]);
    norm = std::max(norm, row);
  }
  int s = 0;
  while (norm > 0.5 && s < 1000) {
    norm = norm * 0.5;
    ++s;
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) m[i][j] = std::ldexp(m[i][j], -s);
  Matrix result{};
  Matrix term{};
  for (std::size_t i = 0; i < n; ++i) result[i][i] = term[i][i] = 1.0;
  for (int k = 1; k <= 20; ++k) {
    term = multiply(term, m, n);
    const double inv_k = 1.0 / static_cast<double>(k);
    for (std::size_t i = 0; i < n; ++i) {
      for (std::size_t j = 0; j < n; ++j) {
        term[i][j] = term[i][j] * inv_k;
        result[i][j] = result[i][j] + term[i][j];
      }
    }
  }
  for (int k = 0; k < s; ++k) result = multiply(result, result, n);
  return result;
}

/// s_{i+1} = phi s_i + g0 w_i + g1 (w_{i+1} - w_i); a_i = c . s_i.
struct Discrete {
  std::size_t states = 0;
  std::array<std::array<double, 4>, 4> phi{};
  std::array<double, 4> g0{};
  std::array<double, 4> g1{};
  std::array<double, 4> c{};
};

Discrete discretise(const SynthesisSpec& spec, double f_g) {
  const double wg = 2.0 * kPi * f_g;
  const double zg = spec.ground_damping;
  const bool cp = spec.model == FilterModel::clough_penzien;
  const std::size_t n = cp ? 4 : 2;
  // Continuous system s' = A s + B w. States: x, x' (ground), y, y' (high-pass).
  Matrix a{};
  std::array<double, 4> b{};
  a[0][1] = 1.0;
  a[1][0] = -wg * wg;
  a[1][1] = -2.0 * zg * wg;
  b[1] = -1.0;
  Discrete d;
  d.states = n;
  d.c = {-wg * wg, -2.0 * zg * wg, 0.0, 0.0};  // a_KT = -(w_g^2 x + 2 zeta_g w_g x')
  if (cp) {
    const double wf = wg * spec.high_pass_ratio;
    const double zf = spec.high_pass_damping;
    // y'' = -2 zeta_f w_f y' - w_f^2 y - a_KT = -2 zeta_f w_f y' - w_f^2 y + w_g^2 x + 2 zeta_g w_g x'
    a[2][3] = 1.0;
    a[3][0] = wg * wg;
    a[3][1] = 2.0 * zg * wg;
    a[3][2] = -wf * wf;
    a[3][3] = -2.0 * zf * wf;
    d.c = {wg * wg, 2.0 * zg * wg, -wf * wf, -2.0 * zf * wf};  // a_CP = y''
  }
  // Augmented matrix in normalised time tau = t / dt: [s; u; du]' = [[A dt, B dt, 0]; [0, 0, 1]; [0, 0, 0]].
  const double h = spec.dt_s;
  Matrix m{};
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) m[i][j] = a[i][j] * h;
    m[i][n] = b[i] * h;
  }
  m[n][n + 1] = 1.0;
  const Matrix e = expm(m, n + 2);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) d.phi[i][j] = e[i][j];
    d.g0[i] = e[i][n];
    d.g1[i] = e[i][n + 1];
  }
  return d;
}

/// Exact end velocity and displacement of a piecewise-linear acceleration from rest (intensity.hpp's integrals).
std::array<double, 2> end_velocity_displacement(const std::vector<double>& a, double h) {
  double v = 0.0;
  double d = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    d = d + v * h + h * h * (2.0 * a[i - 1] + a[i]) / 6.0;
    v = v + 0.5 * h * (a[i - 1] + a[i]);
  }
  return {v, d};
}

}  // namespace

namespace {

std::size_t sample_count(const SynthesisSpec& spec) {
  return static_cast<std::size_t>(std::floor(spec.duration_s / spec.dt_s + 0.5)) + 1;
}

/// n unit normal deviates of PortableRandom(seed).
std::vector<double> white_noise(std::uint64_t seed, std::size_t n) {
  PortableRandom rng(seed);
  std::vector<double> w(n);
  for (double& x : w) x = rng.normal();
  return w;
}

/// The filter output for the noise samples w (filtered_noise's recurrence).
std::vector<double> filter(const SynthesisSpec& spec, const std::vector<double>& w) {
  const double f_g = ground_frequency_for_request_hz(spec.predominant_frequency_hz, spec.ground_damping, spec.model);
  const Discrete d = discretise(spec, f_g);
  const std::size_t n = w.size();
  std::vector<double> a(n, 0.0);
  std::array<double, 4> s{};
  double w_prev = w[0];
  for (std::size_t i = 1; i < n; ++i) {
    const double wi = w[i];
    const double dw = wi - w_prev;
    std::array<double, 4> next{};
    for (std::size_t r = 0; r < d.states; ++r) {
      double sum = d.g0[r] * w_prev + d.g1[r] * dw;
      for (std::size_t c = 0; c < d.states; ++c) sum = sum + d.phi[r][c] * s[c];
      next[r] = sum;
    }
    s = next;
    double out = 0.0;
    for (std::size_t c = 0; c < d.states; ++c) out = out + d.c[c] * s[c];
    a[i] = out;
    w_prev = wi;
  }
  return a;
}

/// Baseline correction shared by both generators (synthesis.hpp), in place: a -= e (c0 + c1 t/T) with
/// v(T) = d(T) = 0, where `a` already carries the envelope e. Returns max |a|.
double correct_baseline(std::vector<double>& a, const std::vector<double>& e, double h) {
  const std::size_t n = a.size();
  std::vector<double> e_t(n);
  const double t_end = static_cast<double>(n - 1) * h;
  for (std::size_t i = 0; i < n; ++i) e_t[i] = e[i] * (static_cast<double>(i) * h / t_end);
  const auto [va, da] = end_velocity_displacement(a, h);
  const auto [v0, d0] = end_velocity_displacement(e, h);
  const auto [v1, d1] = end_velocity_displacement(e_t, h);
  const double det = v0 * d1 - v1 * d0;
  assert(det != 0.0);  // e and e t/T are linearly independent positive shapes
  const double c0 = (va * d1 - v1 * da) / det;
  const double c1 = (v0 * da - va * d0) / det;
  double peak = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    a[i] = a[i] - (c0 * e[i] + c1 * e_t[i]);
    peak = std::max(peak, std::abs(a[i]));
  }
  if (!(peak > 0.0)) throw std::runtime_error("synthesize: the filtered noise is identically zero");
  return peak;
}

/// Baseline correction, then scaling to max |a| = pga_m_s2.
void correct_baseline_and_scale(std::vector<double>& a, const std::vector<double>& e, double h, double pga_m_s2) {
  const double factor = pga_m_s2 / correct_baseline(a, e, h);
  for (double& x : a) x = x * factor;
}

/// Envelope and baseline correction (synthesis.hpp) of the stationary motion a, in place; returns max |a|.
double envelope_and_baseline(const SynthesisSpec& spec, std::vector<double>& a) {
  const double h = spec.dt_s;
  const std::size_t n = a.size();
  std::vector<double> e(n);
  for (std::size_t i = 0; i < n; ++i) {
    e[i] = envelope_at(spec, static_cast<double>(i) * h);
    a[i] = a[i] * e[i];
  }
  return correct_baseline(a, e, h);
}

std::string describe(const SynthesisSpec& spec, const char* what) {
  const double f_g = ground_frequency_for_request_hz(spec.predominant_frequency_hz, spec.ground_damping, spec.model);
  return fmt::format("synthetic {} motion, {} envelope: {} {:.6g} m/s2, requested predominant frequency "
                     "{:.6g} Hz (f_g {:.6g} Hz, zeta_g {:.3g}), T {:.6g} s, dt {:.6g} s, seed {}",
                     filter_model_name(spec.model), envelope_kind_name(spec.envelope), what, spec.pga_m_s2,
                     spec.predominant_frequency_hz, f_g, spec.ground_damping, spec.duration_s, spec.dt_s, spec.seed);
}

}  // namespace

std::vector<double> filtered_noise(const SynthesisSpec& spec) {
  validate(spec);
  return filter(spec, white_noise(spec.seed, sample_count(spec)));
}

GroundMotion synthesize(const SynthesisSpec& spec) {
  std::vector<double> a = filtered_noise(spec);  // validates
  const double factor = spec.pga_m_s2 / envelope_and_baseline(spec, a);
  for (double& x : a) x = x * factor;
  RecordMetadata meta;
  meta.format = "synthetic";
  meta.units_as_read = "m/s2";
  meta.event = describe(spec, "PGA");
  return GroundMotion::uniform(std::move(a), spec.dt_s, 0.0, std::move(meta));
}

namespace {
constexpr std::uint64_t kStreamStep = 0x9E3779B97F4A7C15ULL;  // 2^64 / golden ratio (synthesis.hpp)

SynthesisSpec vertical_spec(const SynthesisSetSpec& s) {
  SynthesisSpec v = s.horizontal;
  v.pga_m_s2 = s.vertical_pga_ratio * s.horizontal.pga_m_s2;
  v.predominant_frequency_hz = s.vertical_frequency_ratio * s.horizontal.predominant_frequency_hz;
  v.seed = s.horizontal.seed + 2 * kStreamStep;
  return v;
}
}  // namespace

void validate(const SynthesisSetSpec& s) {
  validate(s.horizontal);
  if (!(s.coherence >= -1.0 && s.coherence <= 1.0)) {
    throw parameter_error("coherence", fmt::format("the coherence (correlation of the two components' white noises) "
                                                   "must be in [-1, 1], got {}", s.coherence));
  }
  s.azimuths.validate("azimuths");
  if (!s.vertical) return;
  if (!(s.vertical_pga_ratio > 0.0 && s.vertical_pga_ratio <= 2.0)) {
    throw parameter_error("vertical_pga_ratio", fmt::format("the V/H PGA ratio must be in (0, 2], got {}",
                                                            s.vertical_pga_ratio));
  }
  if (!(s.vertical_frequency_ratio >= 0.5 && s.vertical_frequency_ratio <= 4.0)) {
    throw parameter_error("vertical_frequency_ratio", fmt::format("the vertical's frequency ratio f_v / f_h must be "
                                                                  "in [0.5, 4], got {}", s.vertical_frequency_ratio));
  }
  try {
    validate(vertical_spec(s));
  } catch (const InputError& e) {
    throw parameter_error("vertical " + e.where().field, "the vertical component: " + e.problem());
  }
}

SynthesizedSet synthesize_set(const SynthesisSetSpec& spec) {
  validate(spec);
  const SynthesisSpec& h = spec.horizontal;
  const std::size_t n = sample_count(h);
  const std::vector<double> w1 = white_noise(h.seed, n);
  std::vector<double> w2 = white_noise(h.seed + kStreamStep, n);
  const double rho = spec.coherence;
  const double rest = std::sqrt(1.0 - rho * rho);
  for (std::size_t i = 0; i < n; ++i) w2[i] = rho * w1[i] + rest * w2[i];
  std::vector<double> a1 = filter(h, w1);
  std::vector<double> a2 = filter(h, w2);
  (void)envelope_and_baseline(h, a1);
  (void)envelope_and_baseline(h, a2);
  // One factor for both: the pair's RotD50 PGA equals the request (rotd.cpp is portable too).
  const auto rotd50_pga = [&] {
    std::vector<double> peaks = rotd_peaks_by_angle(a1, a2);
    return rotd_of(peaks).rotd50;
  };
  const double factor = h.pga_m_s2 / rotd50_pga();
  for (double& x : a1) x = x * factor;
  for (double& x : a2) x = x * factor;
  SynthesizedSet out{GroundMotion::uniform({0.0, 0.0}, h.dt_s), GroundMotion::uniform({0.0, 0.0}, h.dt_s),
                     std::nullopt, rotd50_pga()};
  RecordMetadata meta;
  meta.format = "synthetic";
  meta.units_as_read = "m/s2";
  meta.event = describe(h, "RotD50 PGA") + fmt::format(", coherence {:g}", rho);
  meta.component = "H1";
  meta.azimuth_deg = spec.azimuths.first_deg;
  out.first = GroundMotion::uniform(std::move(a1), h.dt_s, 0.0, meta);
  meta.component = "H2";
  meta.azimuth_deg = spec.azimuths.second_deg;
  out.second = GroundMotion::uniform(std::move(a2), h.dt_s, 0.0, meta);
  if (spec.vertical) {
    const SynthesisSpec v = vertical_spec(spec);
    std::vector<double> av = filter(v, white_noise(v.seed, n));
    const double fv = v.pga_m_s2 / envelope_and_baseline(v, av);
    for (double& x : av) x = x * fv;
    RecordMetadata vm;
    vm.format = "synthetic";
    vm.units_as_read = "m/s2";
    vm.event = describe(v, "PGA") + fmt::format(" (vertical: V/H {:g}, f_v/f_h {:g})", spec.vertical_pga_ratio,
                                                spec.vertical_frequency_ratio);
    vm.component = "V";
    vm.vertical = true;
    out.vertical = GroundMotion::uniform(std::move(av), h.dt_s, 0.0, std::move(vm));
  }
  return out;
}

// ---- Rezaeian & Der Kiureghian (2010) ----------------------------------------------------------------------------
namespace {

/// sin and cos of |x| <= 1 by their Taylor series to degree 19/18 (the remainder < 1/20! < 5e-19): +, -, *, / only.
std::pair<double, double> portable_sin_cos_small(double x) noexcept {
  assert(std::abs(x) <= 1.0);
  const double x2 = x * x;
  double sin_sum = 0.0;
  double cos_sum = 0.0;
  // Horner from the highest term: sin = x (1 - x^2/(2*3) (1 - x^2/(4*5) (...))), cos likewise with (1*2), (3*4).
  for (int k = 9; k >= 1; --k) {
    const double ks = static_cast<double>(2 * k);
    sin_sum = x2 / (ks * (ks + 1.0)) * (1.0 - sin_sum);
    cos_sum = x2 / ((ks - 1.0) * ks) * (1.0 - cos_sum);
  }
  return {x * (1.0 - sin_sum), 1.0 - cos_sum};
}

/// The 5 %, 45 %, 95 % and 99.9 % quantiles of the gamma distribution of shape k and rate 1, by the trapezoidal
/// rule on 1000 steps of [0, k + 14 sqrt(k) + 20] (the density beyond is < 1e-12 of its peak): errors of order
/// 1e-4 relative, far under the parameters' own scatter (tens of per cent).
std::array<double, 4> gamma_quantiles(double k) {
  constexpr int kSteps = 1000;
  const double top = k + 14.0 * std::sqrt(k) + 20.0;
  const double h = top / kSteps;
  std::vector<double> cdf(kSteps + 1, 0.0);
  double prev = k == 1.0 ? 1.0 : 0.0;  // t^(k-1) e^-t at t = 0
  for (int i = 1; i <= kSteps; ++i) {
    const double t = static_cast<double>(i) * h;
    const double f = portable_exp((k - 1.0) * portable_log(t) - t);
    cdf[static_cast<std::size_t>(i)] = cdf[static_cast<std::size_t>(i - 1)] + 0.5 * h * (prev + f);
    prev = f;
  }
  const double total = cdf.back();
  std::array<double, 4> q{};
  const std::array<double, 4> levels{0.05, 0.45, 0.95, 0.999};
  std::size_t i = 0;
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const double target = levels[l] * total;
    while (i < static_cast<std::size_t>(kSteps) && cdf[i + 1] < target) ++i;
    const double frac = (target - cdf[i]) / (cdf[i + 1] - cdf[i]);
    q[l] = (static_cast<double>(i) + frac) * h;
  }
  return q;
}

double spread_ratio(double k) {
  const std::array<double, 4> q = gamma_quantiles(k);
  return (q[2] - q[0]) / q[1];
}

}  // namespace

GammaEnvelope gamma_envelope(double d5_95_s, double t_mid_s) {
  if (!(d5_95_s > 0.0) || !std::isfinite(d5_95_s)) throw parameter_error("d5_95_s", fmt::format("must be positive, got {} s", d5_95_s));
  if (!(t_mid_s > 0.0) || !std::isfinite(t_mid_s)) throw parameter_error("t_mid_s", fmt::format("must be positive, got {} s", t_mid_s));
  const double ratio = d5_95_s / t_mid_s;
  // (Q95 - Q05) / Q45 falls from 4.93 at k = 1 towards 0 as k grows (the gamma narrows): bisection in log k.
  double lo = 0.0;             // log k
  double hi = portable_log(4000.0);
  if (ratio >= spread_ratio(1.0)) {
    hi = 0.0;
  } else {
    for (int it = 0; it < 32; ++it) {  // log k to 8.3 / 2^32: far below the quadrature's error
      const double mid = 0.5 * (lo + hi);
      if (spread_ratio(portable_exp(mid)) > ratio) lo = mid;
      else hi = mid;
    }
  }
  GammaEnvelope g;
  g.shape = portable_exp(hi);
  const std::array<double, 4> q = gamma_quantiles(g.shape);
  g.rate_s = q[1] / t_mid_s;
  g.t999_s = q[3] / g.rate_s;
  return g;
}

void validate(const RezaeianSpec& s) {
  const auto positive = [](const char* field, double v, const char* unit) {
    if (!(v > 0.0) || !std::isfinite(v)) throw parameter_error(field, fmt::format("must be positive, got {} {}", v, unit));
  };
  positive("pga_m_s2", s.pga_m_s2, "m/s2");
  positive("dt_s", s.dt_s, "s");
  positive("d5_95_s", s.d5_95_s, "s");
  positive("t_mid_s", s.t_mid_s, "s");
  positive("f_mid_hz", s.f_mid_hz, "Hz");
  positive("f_c_hz", s.f_c_hz, "Hz");
  if (!std::isfinite(s.f_slope_hz_s)) throw parameter_error("f_slope_hz_s", "must be finite");
  if (!(s.zeta_f >= 0.02 && s.zeta_f <= 0.95)) {
    throw parameter_error("zeta_f", fmt::format("must be in [0.02, 0.95], got {}", s.zeta_f));
  }
  if (!(s.duration_s >= 0.0) || !(s.duration_s <= 6.0 * 3600.0)) {
    throw parameter_error("duration_s", fmt::format("must be in [0, 21600] s, got {}", s.duration_s));
  }
}

GroundMotion synthesize_rezaeian(const RezaeianSpec& spec) {
  validate(spec);
  const GammaEnvelope g = gamma_envelope(spec.d5_95_s, spec.t_mid_s);
  const double h = spec.dt_s;
  const double t_total = spec.duration_s > 0.0 ? spec.duration_s : g.t999_s;
  const auto n = static_cast<std::size_t>(std::floor(t_total / h + 0.5)) + 1;
  if (n < 100 || n > 50'000'000) {
    throw parameter_error("duration_s", fmt::format("{} s at dt {} s gives {} samples (need 100 to 5e7)", t_total, h, n));
  }
  const double f_floor = 0.25 * spec.f_mid_hz;
  const auto freq_at = [&](double t) { return std::max(f_floor, spec.f_mid_hz + spec.f_slope_hz_s * (t - spec.t_mid_s)); };
  const double zeta = spec.zeta_f;
  const double root = std::sqrt(1.0 - zeta * zeta);

  // Time-varying oscillator x'' + 2 zeta w x' + w^2 x = sum_i u_i delta(t - t_i), u_i ~ N(0, 1); xhat = x w^(3/2)
  // (the stationary standard deviation of x is proportional to w^(-3/2) for constant zeta).
  PortableRandom rng(spec.seed);
  std::vector<double> a(n, 0.0);
  std::vector<double> e(n, 0.0);
  double x = 0.0;
  double v = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * h;
    v = v + rng.normal();
    // Envelope q(t) = (rate t)^((k-1)/2) exp(-rate t / 2): the square root of the gamma density's shape.
    const double rt = g.rate_s * t;
    e[i] = t > 0.0 ? portable_exp(0.5 * ((g.shape - 1.0) * portable_log(rt) - rt)) : (g.shape == 1.0 ? 1.0 : 0.0);
    const double w_now = 2.0 * kPi * freq_at(t);
    a[i] = e[i] * x * w_now * std::sqrt(w_now);
    // Exact homogeneous step with the frequency of the step's middle.
    const double w = 2.0 * kPi * freq_at(t + 0.5 * h);
    const double wd = w * root;
    if (wd * h > 1.0) {
      throw parameter_error("dt_s", fmt::format("{} s is too coarse for a filter frequency of {} Hz", h, w / (2.0 * kPi)));
    }
    const auto [sn, cs] = portable_sin_cos_small(wd * h);
    const double decay = portable_exp(-zeta * w * h);
    const double x1 = decay * ((cs + zeta * w / wd * sn) * x + sn / wd * v);
    const double v1 = decay * (-(w * w) / wd * sn * x + (cs - zeta * w / wd * sn) * v);
    x = x1;
    v = v1;
  }
  // The envelope's peak is 1 for the baseline's shapes (any factor would do: it is scaled away).
  const double e_peak = *std::max_element(e.begin(), e.end());
  for (double& ei : e) ei = ei / e_peak;

  // High-pass: z'' + 2 w_c z' + w_c^2 z = a(t), corrected = z'' = a - 2 w_c z' - w_c^2 z (critically damped), exact
  // for piecewise-linear a (augmented matrix exponential, as discretise()).
  {
    const double wc = 2.0 * kPi * spec.f_c_hz;
    Matrix m{};
    m[0][1] = h;
    m[1][0] = -wc * wc * h;
    m[1][1] = -2.0 * wc * h;
    m[1][2] = h;
    m[2][3] = 1.0;
    const Matrix ex = expm(m, 4);
    double z = 0.0;
    double zv = 0.0;
    std::vector<double> out(n, 0.0);
    out[0] = a[0];
    for (std::size_t i = 1; i < n; ++i) {
      const double u0 = a[i - 1];
      const double du = a[i] - a[i - 1];
      const double z1 = ex[0][0] * z + ex[0][1] * zv + ex[0][2] * u0 + ex[0][3] * du;
      const double zv1 = ex[1][0] * z + ex[1][1] * zv + ex[1][2] * u0 + ex[1][3] * du;
      z = z1;
      zv = zv1;
      out[i] = a[i] - 2.0 * wc * zv - wc * wc * z;
    }
    a = std::move(out);
  }
  correct_baseline_and_scale(a, e, h, spec.pga_m_s2);

  RecordMetadata meta;
  meta.format = "synthetic";
  meta.units_as_read = "m/s2";
  meta.event = fmt::format("synthetic Rezaeian-Der Kiureghian (2010) motion: PGA {:.6g} m/s2, D5-95 {:.6g} s, t_mid "
                           "{:.6g} s, f_mid {:.6g} Hz, f' {:.6g} Hz/s, zeta_f {:.3g}, f_c {:.6g} Hz, T {:.6g} s, "
                           "dt {:.6g} s, seed {}",
                           spec.pga_m_s2, spec.d5_95_s, spec.t_mid_s, spec.f_mid_hz, spec.f_slope_hz_s, spec.zeta_f,
                           spec.f_c_hz, t_total, h, spec.seed);
  return GroundMotion::uniform(std::move(a), h, 0.0, std::move(meta));
}

RezaeianSpec draw_rezaeian(std::uint64_t seed, double f_mid_hz) {
  // Lognormal draws with a given mean m and standard deviation s: sigma^2 = ln(1 + s^2/m^2), mu = ln m - sigma^2/2.
  PortableRandom rng(seed);
  const auto lognormal = [&](double mean, double sd) {
    const double s2 = portable_log(1.0 + sd * sd / (mean * mean));
    return portable_exp(portable_log(mean) - 0.5 * s2 + std::sqrt(s2) * rng.normal());
  };
  RezaeianSpec r;
  r.f_mid_hz = f_mid_hz;
  r.d5_95_s = std::clamp(lognormal(17.3, 9.31), 5.0, 45.0);
  r.t_mid_s = r.d5_95_s * std::clamp(lognormal(0.72, 0.30), 0.21, 2.0);
  // Relative drift over the strong phase: f' D5-95 / f_mid with f' ~ N(-0.089, 0.185) Hz/s and f_mid ~ lognormal
  // (5.87, 2.39) Hz, D5-95 as drawn above.
  const double f_slope = -0.089 + 0.185 * rng.normal();
  const double f_mid_paper = lognormal(5.87, 2.39);
  r.f_slope_hz_s = f_slope / f_mid_paper * f_mid_hz;
  // zeta_f: NOT the paper's (mean 0.213, standard deviation 0.143). With it the family carries 1.8 times the PGV/PGA
  // of the real records at the same measured predominant frequency, as Clough-Penzien's does (docs/method.md, "A
  // record-like family"); a broad filter, mean 0.8 with the paper's standard deviation, puts the records' PGV/PGA
  // in the middle of the family's (median rank 0.53 over the 25 records of shared/records).
  r.zeta_f = std::clamp(lognormal(0.8, 0.143), 0.02, 0.95);
  r.f_c_hz = 0.1 * f_mid_hz;
  // 20 samples per period of the highest filter frequency reached (at t = 0 when f' < 0), at most 0.01 s.
  const GammaEnvelope g = gamma_envelope(r.d5_95_s, r.t_mid_s);
  const double f_top = std::max(f_mid_hz + std::abs(r.f_slope_hz_s) * std::max(r.t_mid_s, g.t999_s - r.t_mid_s), f_mid_hz);
  r.dt_s = std::min(0.01, 1.0 / (20.0 * f_top));
  r.seed = rng.next();
  return r;
}

}  // namespace topple
