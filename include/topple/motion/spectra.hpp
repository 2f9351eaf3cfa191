#pragma once
// Spectra of a ground motion: Fourier amplitude, its smoothing and peak (the predominant frequency), the elastic
// response spectrum, and the periods derived from them.
//
// Fourier amplitude spectrum (FAS). |A(f_k)| = dt |sum_i a_i exp(-2 pi i k i' / N)|, f_k = k / (N dt), k = 0 ..
// N/2: the DFT estimate of |integral a(t) exp(-2 pi i f t) dt|, in m/s, by FFTW (r2c, FFTW_ESTIMATE plans). Irregular
// records are first resampled at their smallest interval (GroundMotion::to_uniform).
//
// Konno-Ohmachi smoothing (Konno & Ohmachi 1998, BSSA 88(1)): S(f_c) = sum_k W_k |A(f_k)| / sum_k W_k with
// W_k = [sin(b log10(f_k / f_c)) / (b log10(f_k / f_c))]^4, bandwidth b; W = 1 at f_k = f_c. The window is
// truncated where b |log10(f_k / f_c)| > 6 pi (weights below 3e-5; r in [0.34, 2.96] for b = 40); f_k = 0 is excluded.
//
// Predominant frequency (the one definition topple uses, for synthesis and for the inversion's frequency axis):
// the maximum of the Konno-Ohmachi (b = 40) smoothed FAS of the record zero-padded to the next power of two at
// least twice its length, evaluated at 200 centre frequencies per decade from 0.1 Hz to
// min(25 Hz, 0.8 f_Nyquist), refined by the vertex of the parabola through the largest value and its two
// neighbours in log10 f (not refined at the band's ends).
//
// Elastic response spectrum. The linear oscillator x'' + 2 zeta w x' + w^2 x = -a_g(t) (x relative to the ground),
// from rest, driven by the piecewise-linear accelerogram, is advanced exactly from sample to sample by the
// recurrence of Nigam & Jennings (1968 EERL report eq. 2.7a; A and B matrices eqs 2.7d, 2.7e; published in BSSA
// 1969): (x, x')_{i+1} = A (x, x')_i + B (a_i, a_{i+1}). The coefficients depend only on (period, damping, dt), so an
// OscillatorBank computes them once and runs many periods in one pass over the record. Maxima are taken at the
// samples, over the record only (no free vibration after its end, as in Nigam & Jennings and eqsig): SD = max |x|,
// PSV = w SD, PSA = w^2 SD, SV = max |x'|, SA = max |x'' + a_g| = max |2 zeta w x' + w^2 x|.
//
// Predominant period Tp: the period of the largest 5 %-damped PSA over 100 periods per decade from 0.02 s to 5 s,
// refined by the parabola in log10 T (Rathje et al. 1998 use the peak of the 5 %-damped acceleration spectrum).
// Mean period Tm (Rathje, Abrahamson & Bray 1998, JGGE 124(2)): sum C_i^2 / f_i / sum C_i^2 over the FFT frequencies
// 0.25 Hz <= f_i <= 20 Hz of the unpadded record, C_i its Fourier amplitudes.
#include <cstddef>
#include <span>
#include <vector>

#include "topple/motion/ground_motion.hpp"

namespace topple {

struct FourierSpectrum {
  std::vector<double> frequency_hz;  ///< k / (N dt), k = 0 .. N/2
  std::vector<double> amplitude_m_s; ///< dt |DFT_k|
  double dt_s = 0.0;                 ///< sample interval of the transformed record
  std::size_t fft_length = 0;        ///< N (>= the record's samples; zero padded)
};

/// FAS of the record zero-padded to `fft_length` samples (0: the record's own length). Throws InputError when
/// fft_length is smaller than the record.
[[nodiscard]] FourierSpectrum fourier_amplitude_spectrum(const GroundMotion& motion, std::size_t fft_length = 0);

/// Konno-Ohmachi smoothing of `spectrum` at the centre frequencies (Hz, > 0), bandwidth b (> 0; 40 for the
/// predominant frequency). Returns the smoothed amplitudes at the centres, in m/s (the unit of
/// FourierSpectrum::amplitude_m_s). A centre whose window holds no frequency gives 0.
[[nodiscard]] std::vector<double> konno_ohmachi_smooth(const FourierSpectrum& spectrum,
                                                       std::span<const double> centre_hz, double bandwidth = 40.0);

/// n values from lo to hi (> 0) evenly spaced in log; n >= 2.
[[nodiscard]] std::vector<double> log_spaced(double lo, double hi, std::size_t n);

/// The FFT length of the predominant frequency (definition above): the next power of two at least 2 `samples`.
[[nodiscard]] std::size_t predominant_frequency_fft_length(std::size_t samples);

/// The centre frequencies of the predominant frequency (definition above), Hz, for a record sampled every dt_s: 200
/// per decade from 0.1 Hz to min(25 Hz, 0.8 f_Nyquist); empty when that band is empty.
[[nodiscard]] std::vector<double> predominant_frequency_centres_hz(double dt_s);

/// The predominant frequency of a motion, Hz (definition above). Throws InputError for a record too short to
/// hold any frequency of the band, or an identically zero one.
[[nodiscard]] double predominant_frequency_hz(const GroundMotion& motion);

/// Mean period Tm of Rathje et al. (1998), s. Throws InputError when no FFT frequency lies in 0.25-20 Hz or the
/// record is zero there.
[[nodiscard]] double mean_period_s(const GroundMotion& motion);

/// The damping ratio of a response spectrum when none is given: 5 % of critical, the ratio of design spectra and
/// ground-motion models; also the default of a flexible support's damping (`topple slide --support-freq`).
inline constexpr double kDefaultDampingRatio = 0.05;

struct ResponseSpectrum {
  std::vector<double> period_s;
  double damping = kDefaultDampingRatio;  ///< damping ratio zeta (dimensionless fraction of critical; 0.05 = 5 %)
  std::vector<double> sd_m;       ///< max |x|
  std::vector<double> psv_m_s;    ///< w SD
  std::vector<double> psa_m_s2;   ///< w^2 SD
  std::vector<double> sv_m_s;     ///< max |x'|
  std::vector<double> sa_m_s2;    ///< max |x'' + a_g| (absolute acceleration)
};

/// Linear oscillators of the given periods (> 0) and damping ratio (0 <= zeta < 1) for records sampled at dt:
/// the Nigam-Jennings coefficients, computed once. Throws InputError for invalid values.
class OscillatorBank {
 public:
  OscillatorBank(std::vector<double> period_s, double damping, double dt_s);
  [[nodiscard]] const std::vector<double>& period_s() const noexcept { return period_; }
  [[nodiscard]] double damping() const noexcept { return damping_; }  ///< damping ratio (dimensionless)
  [[nodiscard]] double dt_s() const noexcept { return dt_; }
  /// Spectrum of a uniform record sampled at dt_s() (throws InputError otherwise).
  [[nodiscard]] ResponseSpectrum respond(const GroundMotion& motion) const;

  /// The recurrence's coefficients of one oscillator (eqs 2.7d, 2.7e): x_{i+1} = a11 x + a12 v + b11 ag_i +
  /// b12 ag_{i+1}; v_{i+1} = a21 x + a22 v + b21 ag_i + b22 ag_{i+1}.
  struct Coefficients {
    double a11, a12, a21, a22, b11, b12, b21, b22;
  };
  [[nodiscard]] static Coefficients coefficients(double period_s, double damping, double dt_s);

 private:
  std::vector<double> period_;
  double damping_;
  double dt_;
  std::vector<Coefficients> coef_;
};

/// Response spectrum of any record (irregular ones: coefficients per distinct step, still exact).
[[nodiscard]] ResponseSpectrum response_spectrum(const GroundMotion& motion, std::span<const double> period_s,
                                                 double damping = kDefaultDampingRatio);

/// Time history of one oscillator at the record's samples (relative displacement, velocity, absolute acceleration).
struct OscillatorHistory {
  std::vector<double> displacement_m;
  std::vector<double> velocity_m_s;
  std::vector<double> absolute_accel_m_s2;
};
[[nodiscard]] OscillatorHistory oscillator_response(const GroundMotion& motion, double period_s, double damping);

/// The periods of the predominant period Tp (definition above), s: 100 per decade from 0.02 s to 5 s (271 periods).
[[nodiscard]] std::vector<double> tp_periods_s();

/// Predominant period Tp, s (definition above).
[[nodiscard]] double predominant_period_s(const GroundMotion& motion);

}  // namespace topple
