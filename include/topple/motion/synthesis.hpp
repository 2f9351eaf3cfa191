#pragma once
// Synthetic ground motions: filtered white noise under a time envelope, reproducible bit for bit from a seed.
//
// Model (Kanai 1957; Tajimi 1960; Clough & Penzien 1975, sec. 25-3). Unit white noise w(t) drives the ground
// filter; its absolute acceleration, optionally high-passed by a second oscillator, is the stationary motion:
//
//   Kanai-Tajimi     x'' + 2 zeta_g w_g x' + w_g^2 x = -w(t),        a_KT = -(2 zeta_g w_g x' + w_g^2 x)
//   Clough-Penzien   y'' + 2 zeta_f w_f y' + w_f^2 y = -a_KT(t),     a_CP = y''
//
// |H_KT|^2 = (w_g^4 + 4 zeta_g^2 w_g^2 w^2) / ((w_g^2 - w^2)^2 + 4 zeta_g^2 w_g^2 w^2) and
// |H_CP|^2 = w^4 / ((w_f^2 - w^2)^2 + 4 zeta_f^2 w_f^2 w^2): the CP stage removes the KT process' finite
// low-frequency acceleration, which would give unbounded ground velocity and displacement.
// The stationary motion is multiplied by an envelope e(t) (peak 1; the uniformly modulated process of Shinozuka &
// Sato 1967): Saragoni & Hart (1974), e = (t/(eps T))^b exp(b (1 - t/(eps T))) with b from the level eta at T
// (Boore 2003, eq. 11 and its parameterisation by eps and eta), or Jennings, Housner & Tsai (1968):
// (t/t1)^2 rising, 1 between t1 and t2, exp(-c (t - t2)) after, c such that e(T) = eta.
//
// Discretisation (exact). w(t) is piecewise linear between its samples w_i ~ N(0, 1) at t_i = i dt, the same
// model topple uses for every accelerogram. For that input the filter state (x, x', y, y') at t_{i+1} follows from
// the state at t_i exactly: s_{i+1} = Phi s_i + G0 w_i + G1 (w_{i+1} - w_i), with Phi, G0, G1 the blocks of the
// exponential of the augmented matrix [[A dt, B dt, 0], [0, 0, 1], [0, 0, 0]] (Van Loan 1978). No FFT, no
// approximation of the filters; the acceleration at the samples is that of the continuous filters.
//
// Baseline. The enveloped motion is corrected by a - e(t) (c0 + c1 t/T), with c0, c1 chosen so that the ground
// velocity and displacement at T (integrated exactly, piecewise linear) are zero to round-off; then it is scaled
// to the requested PGA. The correction keeps a(0) = 0 and the envelope's shape.
//
// Random numbers (portable by construction). xoshiro256** 1.0 (Blackman & Vigna 2018) seeded with four outputs of
// SplitMix64(seed) (Steele, Lea & Flood 2014); a uniform double is (x >> 11) * 2^-53; normal deviates come from
// the Marsaglia polar method (Marsaglia & Bray 1964) using pairs of uniforms on (-1, 1). Every step uses only IEEE
// 754 binary64 +, -, *, / and sqrt (correctly rounded everywhere) and topple's own exp and log written in those
// operations; synthesis.cpp is compiled with -ffp-contract=off. So (parameters, seed) give the same bits on any
// IEEE 754 machine and any standard library (std::normal_distribution would not: its algorithm is unspecified).
//
// Predominant frequency. The request is the motion's *measured* predominant frequency, predominant_frequency_hz()
// of spectra.hpp. Because the peak of a finite Kanai-Tajimi sample's smoothed spectrum sits below f_g (the PSD
// peak is at f_g sqrt(sqrt(1 + 8 zeta_g^2) - 1) / (2 zeta_g), and the noise of a sample spectrum around a broad
// peak pulls the measured maximum lower still), f_g solves f_request = kappa(zeta_g, model, f_g) f_g, with kappa the
// mean measured-to-f_g ratio from a calibration over seeds (docs/method.md, ground_frequency_for_request_hz).
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"

namespace topple {

enum class FilterModel {
  kanai_tajimi,    ///< one oscillator: the ground's soil column
  clough_penzien,  ///< plus the high-pass oscillator (default)
};

enum class EnvelopeKind {
  saragoni_hart,  ///< gamma-shaped t^b exp(-c t) (default)
  jennings,       ///< quadratic rise, plateau, exponential decay
};

/// "kanai-tajimi" / "clough-penzien"; throws InputError naming `field`.
[[nodiscard]] FilterModel parse_filter_model(std::string_view name, const std::string& field = "--model");
[[nodiscard]] std::string_view filter_model_name(FilterModel model);
/// "saragoni-hart" / "jennings"; throws InputError naming `field`.
[[nodiscard]] EnvelopeKind parse_envelope_kind(std::string_view name, const std::string& field = "--envelope");
[[nodiscard]] std::string_view envelope_kind_name(EnvelopeKind kind);

/// Everything that defines a synthetic motion. (SynthesisSpec, seed) -> the same motion, bit for bit, everywhere.
struct SynthesisSpec {
  double pga_m_s2 = 0.0;                  ///< peak |a| of the result, m/s^2 (> 0 and <= 100 g, GroundMotionLimits; typical 1-10)
  double predominant_frequency_hz = 0.0;  ///< requested measured predominant frequency, Hz (0.1 ... 1/(10 dt))
  double duration_s = 0.0;                ///< record length T, s (>= 5 predominant periods and >= 100 dt; <= 6 h)
  double dt_s = 0.01;                     ///< sample interval, s (in [1e-6, 0.1]; typical 0.005-0.02)
  std::uint64_t seed = 0;                 ///< any 64-bit value
  FilterModel model = FilterModel::clough_penzien;
  EnvelopeKind envelope = EnvelopeKind::saragoni_hart;
  /// Kanai-Tajimi damping zeta_g, in [0.1, 0.5] (the calibrated range). 0.3 by default: a peak clear enough that
  /// a single motion's predominant frequency scatters about 20 % around the request (0.6, Kanai's firm-ground
  /// value, gives a spectrum so flat that the measured peak of one motion is nearly arbitrary).
  double ground_damping = 0.3;
  /// Clough-Penzien corner f_f / f_g, in (0, 0.5]; 0.1 (Clough & Penzien's example).
  double high_pass_ratio = 0.1;
  /// Clough-Penzien damping zeta_f, in [0.5, 2]; 1/sqrt(2) makes the stage a Butterworth high-pass with no
  /// resonance at f_f (a low zeta_f, e.g. zeta_f = zeta_g, puts a spurious spectral peak there).
  double high_pass_damping = 0.70710678118654752;
  /// Saragoni-Hart: the envelope peaks at eps T, eps in [0.05, 0.5] (Boore 2003: 0.2).
  double envelope_peak_fraction = 0.2;
  /// Both envelopes: their level at T relative to the peak, eta in [0.001, 0.5] (Boore 2003: 0.05).
  double envelope_end_level = 0.05;
  /// Jennings: end of the quadratic rise t1 / T and of the plateau t2 / T, 0 < t1/T < t2/T < 1.
  double jennings_rise_fraction = 0.1;
  double jennings_plateau_end_fraction = 0.5;
};

/// Checks a spec; throws InputError naming the offending field and value.
void validate(const SynthesisSpec& spec);

/// Mean measured-to-f_g ratio kappa (predominant_frequency_hz of a motion over its filter frequency f_g) for the
/// given damping, model and f_g: the calibration table of docs/method.md, bilinear in (zeta_g, log f_g) between
/// its nodes (zeta_g 0.1-0.5; f_g 0.5-8 Hz, constant beyond).
[[nodiscard]] double predominant_frequency_ratio(double ground_damping, FilterModel model, double f_g_hz);

/// The filter frequency f_g that makes the mean measured predominant frequency equal `request_hz`: the fixed point
/// of f_g = request / kappa(zeta_g, model, f_g).
[[nodiscard]] double ground_frequency_for_request_hz(double request_hz, double ground_damping, FilterModel model);

/// The envelope e(t) of a spec at time t (0 <= e <= 1, peak 1).
[[nodiscard]] double envelope_at(const SynthesisSpec& spec, double t_s);

/// The stationary filtered noise of a spec before envelope, baseline and scaling: the filter output at
/// t_i = i dt for the unit normal samples w_i of PortableRandom(seed), f_g = ground_frequency_for_request_hz(...).
/// Dimensionless (the white noise has unit variance and no unit; synthesize() scales the enveloped, baseline-
/// corrected result to the PGA in m/s^2).
[[nodiscard]] std::vector<double> filtered_noise(const SynthesisSpec& spec);

/// The synthetic motion: uniform, n = round(T / dt) + 1 samples from t = 0, a(0) = 0, zero final velocity and
/// displacement, max |a| = pga. Metadata: format "synthetic", event describing the parameters and the seed.
/// Throws InputError for an invalid spec.
[[nodiscard]] GroundMotion synthesize(const SynthesisSpec& spec);

// ---- Three components: a pair of horizontal components and a vertical one (docs/method.md, "Synthetic motion
// sets"). ----
//
// Horizontal pair. Both components are the same process (the spec's filter, envelope and baseline), driven by white
// noises w_1 and w_2 with correlation coefficient rho (the coherence, the same at every frequency):
//   w_1 = the normal deviates of PortableRandom(seed) (so the first component's noise is synthesize()'s),
//   w_2 = rho w_1 + sqrt(1 - rho^2) z_2, z_2 the deviates of PortableRandom(seed + 1 * K),
// K = 0x9E3779B97F4A7C15 (2^64 / golden ratio; unsigned arithmetic wraps portably). rho = 0: independent
// components, the usual assumption for the two horizontal components of a stochastic simulation.
// PGA of a pair: SynthesisSpec::pga_m_s2 is the pair's RotD50 PGA (Boore 2010; rotd.hpp), the measure modern
// ground-motion models predict: both components are scaled by one factor so that RotD50 of their PGA equals it
// (each component's own peak is then typically 0.85-1.15 times it).
// Vertical (optional). The same process with its own noise z_3 (PortableRandom(seed + 2 K)), independent of the
// horizontals, at the predominant frequency f_v = frequency_ratio x f_h and scaled to PGA_v = pga_ratio x the pair's
// RotD50 PGA. Defaults V/H = 2/3 (the traditional engineering ratio of peak vertical to horizontal acceleration,
// Newmark, Blume & Kapur 1973, J. Power Div. ASCE 99(2); the ratio Bozorgnia & Campbell 2004, J. Earthquake Eng.
// 8(2), discuss as the conventional assumption, finding it conservative at long periods and unconservative near
// the source at short ones) and f_v / f_h = 1.5 (vertical motion is richer in high frequencies: Bozorgnia &
// Campbell's V/H spectral ratios peak at 0.05-0.1 s; 1.5 is topple's stated simple shift, not a fit).
struct SynthesisSetSpec {
  SynthesisSpec horizontal;        ///< pga_m_s2 is the pair's RotD50 PGA, m/s^2; the seed drives all components
  double coherence = 0.0;          ///< rho, correlation coefficient of the two white noises, in [-1, 1]
  ComponentAzimuths azimuths{90.0, 0.0};  ///< what the components are called (written to the files), perpendicular
  bool vertical = true;            ///< synthesize the vertical component
  double vertical_pga_ratio = 2.0 / 3.0;    ///< PGA_v / RotD50 PGA_h, in (0, 2]
  double vertical_frequency_ratio = 1.5;    ///< f_v / f_h, in [0.5, 4]
};

/// Throws InputError naming the field ("coherence", "vertical_pga_ratio", "vertical_frequency_ratio", "azimuths",
/// or the vertical spec's field prefixed "vertical " when the vertical's frequency or PGA leaves SynthesisSpec's
/// ranges) and the value.
void validate(const SynthesisSetSpec& spec);

struct SynthesizedSet {
  GroundMotion first;                    ///< azimuth spec.azimuths.first_deg (metadata azimuth_deg)
  GroundMotion second;                   ///< azimuth spec.azimuths.second_deg
  std::optional<GroundMotion> vertical;  ///< positive up (metadata vertical)
  double rotd50_pga_m_s2 = 0.0;          ///< the pair's RotD50 PGA (= the request, to round-off)
};

/// The three-component synthetic motion (model above), bit for bit the same for the same spec on every IEEE 754
/// machine.
[[nodiscard]] SynthesizedSet synthesize_set(const SynthesisSetSpec& spec);

// ---- A record-like family: Rezaeian & Der Kiureghian (2010) ----------------------------------------------------
//
// Model (Rezaeian & Der Kiureghian 2010, "Simulation of synthetic ground motions for specified earthquake and site
// characteristics", EESD 39(10):1155-1180; docs/method.md "A record-like family"). A modulated, filtered white noise
//   a(t) = q(t) xhat(t),   xhat = the output of a filter whose frequency drifts, normalised to unit variance,
// then high-passed. Modulating function (their eq. 3, t0 = 0): q(t) = t^(alpha2 - 1) exp(-alpha3 t) up to a factor
// (the factor, set by the Arias intensity, is scaled away: the motion is scaled to its PGA), alpha2 and alpha3 from
// the significant duration D5-95 and t_mid (the time at which 45 % of the Arias intensity has arrived): the Husid
// plot of q^2 is a gamma distribution of shape k = 2 alpha2 - 1 and rate 2 alpha3, so D5-95 / t_mid fixes k and
// then t_mid fixes the rate. Filter frequency f(t) = f_mid + f' (t - t_mid), damping zeta_f; the high-pass is their
// critically damped oscillator (corner f_c).
// Approximations (stated in docs/method.md): the filter is a time-varying oscillator driven by unit pulses at the
// samples, its frequency taken over each step (their eq. 6 takes it at the pulse's time: the same while
// |f'| / f^2 << 1), normalised by its stationary variance at f(t) (theirs: the exact sum of squared responses; they
// differ at the onset, where q is small); f(t) is kept >= f_mid / 4.
// Discretisation: the oscillator's step is its exact homogeneous transition (exp, cos, sin of the step), the pulse
// adds to its velocity; the high-pass is exact for the piecewise-linear signal (Van Loan, as synthesize()). Every
// operation is portable (the header's random numbers; topple's exp, log and a Taylor sin/cos of arguments <= 1).
struct RezaeianSpec {
  double pga_m_s2 = 1.0;        ///< peak |a| of the result, m/s^2 (> 0)
  double dt_s = 0.01;           ///< sample interval, s (> 0; <= 1 / (20 f_max) keeps the step's angle <= 0.32)
  double d5_95_s = 17.3;        ///< significant duration, s (> 0)
  double t_mid_s = 12.4;        ///< time at 45 % of the Arias intensity, s (> 0)
  double f_mid_hz = 5.87;       ///< filter frequency at t_mid, Hz (> 0)
  double f_slope_hz_s = -0.089; ///< its rate of change f', Hz/s
  double zeta_f = 0.213;        ///< filter damping ratio, in [0.02, 0.95]
  double f_c_hz = 0.1;          ///< high-pass corner, Hz (> 0)
  double duration_s = 0.0;      ///< record length, s; 0: the time at which 99.9 % of the Arias intensity has arrived
  std::uint64_t seed = 0;
};

/// Checks a spec; throws InputError naming the offending field and value.
void validate(const RezaeianSpec& spec);

/// The shape k (= 2 alpha2 - 1 >= 1) and rate (1/s) of the gamma distribution whose 5-95 % range is d5_95_s and whose
/// 45 % quantile is t_mid_s; D5-95 / t_mid above the exponential's 4.93 gives k = 1 (the most spread gamma whose q
/// stays finite at t = 0).
struct GammaEnvelope {
  double shape = 1.0;   ///< k, dimensionless
  double rate_s = 1.0;  ///< 1/s
  double t999_s = 0.0;  ///< time at which 99.9 % of the energy has arrived, s
};
[[nodiscard]] GammaEnvelope gamma_envelope(double d5_95_s, double t_mid_s);

/// The motion of a spec: uniform from t = 0, zero final velocity and displacement (the baseline correction of
/// synthesize()), max |a| = pga. Throws InputError for an invalid spec.
[[nodiscard]] GroundMotion synthesize_rezaeian(const RezaeianSpec& spec);

/// One draw of the model's parameters (seeded, portable): D5-95, t_mid / D5-95, the relative drift f' D5-95 / f_mid
/// and zeta_f, from distributions matched to the sample statistics Rezaeian & Der Kiureghian (2010) report for
/// their NGA records (docs/method.md states which, and what was chosen where the paper gives no number). The
/// frequency f_mid (and f' with it) is set by the caller; f_c is f_mid / 10.
[[nodiscard]] RezaeianSpec draw_rezaeian(std::uint64_t seed, double f_mid_hz);

// ---- The portable generator, public so that tests and other modules can reproduce it. ----

/// SplitMix64 (Steele, Lea & Flood 2014): the seeding generator.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) noexcept : state_(seed) {}
  std::uint64_t next() noexcept;

 private:
  std::uint64_t state_;
};

/// xoshiro256** 1.0 (Blackman & Vigna 2018), seeded by four SplitMix64 outputs, with portable normal deviates.
class PortableRandom {
 public:
  explicit PortableRandom(std::uint64_t seed) noexcept;
  std::uint64_t next() noexcept;
  /// Uniform on [0, 1): (next() >> 11) * 2^-53.
  double uniform() noexcept;
  /// Standard normal by the Marsaglia polar method (pairs; the second deviate is kept for the next call).
  double normal();

 private:
  std::uint64_t s_[4];
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// exp and natural log in IEEE +, -, *, / only (so bit-identical on every IEEE 754 machine); within 2 ulp of the
/// true values over the ranges used here. portable_exp: any finite x (0 below -745, inf above 709.8);
/// portable_log: x > 0 and finite.
[[nodiscard]] double portable_exp(double x) noexcept;
[[nodiscard]] double portable_log(double x) noexcept;

}  // namespace topple
