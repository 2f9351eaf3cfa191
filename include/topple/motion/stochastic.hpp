#pragma once
// The stochastic point-source method (Boore 2003, "Simulation of ground motion using the stochastic method", Pure
// Appl. Geophys. 160:635-676; docs/method.md "A motion family from earthquake source, path and site"): ground
// motions from an earthquake's moment magnitude M and its distance R.
//
// Target Fourier amplitude spectrum of acceleration (Boore 2003, eqs. 2-5), in m/s:
//   A(f) = C M0 (2 pi f)^2 / (1 + (f/fc)^2) Z(R) exp(-pi f R / (Q(f) beta)) exp(-pi kappa0 f) G(f)
//   C  = R_tp V F / (4 pi rho beta^3 R0), R_tp = 0.55, V = 1/sqrt(2), F = 2, R0 = 1 km (rho g/cm^3, beta km/s,
//        M0 dyne-cm: A in cm/s after the factor 1e-20 of the units, then / 100)
//   M0 = 10^(1.5 M + 16.05) dyne-cm (Hanks & Kanamori 1979, JGR 84(B5), the constant of Boore 2003, eq. 4)
//   fc = 4.906e6 beta (dsigma / M0)^(1/3), beta km/s, dsigma bar (Brune 1970; Boore 2003, eq. 6)
//   Z  = R0/R for R <= 40 km, (R0/40) (40/R)^0.5 beyond;  Q(f) = 180 f^0.45 (Raoof, Herrmann & Malagnini 1999,
//        BSSA 89(4); the WNA path of Boore 2003's examples); kappa0 = 0.04 s; dsigma = 70 bar; beta = 3.5 km/s,
//        rho = 2.72 g/cm^3
//   G(f) = the generic rock amplification for Vs30 = 760 m/s of Boore (2016, BSSA 106(1):316-320; the update of
//        Boore & Joyner 1997), log-log interpolated, constant beyond its 0.01-80 Hz table.
// Duration (Boore 2003, eq. 9 with the WNA path term of Atkinson & Silva 2000, BSSA 90(2)): T_gm = 1/fc + 0.05 R.
//
// Time series (Boore 2003, sec. 3, "time-domain simulation"): Gaussian white noise (PortableRandom(seed), unit
// variance) under the Saragoni-Hart window (Boore 2003, eq. 11) w(t) = a (t/t_eta)^b exp(-c t/t_eta),
// b = -eps ln eta / (1 + eps (ln eps - 1)), c = b/eps, a = (e/eps)^b, eps = 0.2, eta = 0.05, t_eta = 2 T_gm (peak 1
// at eps t_eta, eta at t_eta); zero padding of p = max(2 s, 1/(2 fc)) before and after; its DFT (FFTW,
// FFTW_ESTIMATE) normalised to unit mean square amplitude over the frequencies 0 < f_k < f_Nyquist, multiplied by
// A(f_k), its f = 0 and Nyquist terms set to 0, and transformed back. The expected squared Fourier amplitude of the
// result is A(f)^2 (the normalised noise spectrum has unit mean square), and its velocity returns to zero at the
// end (the DC term is 0 and the whole periodic buffer is returned).
// Reproducible: the same spec gives the same samples on the same machine and FFTW build (the noise is portable; the
// FFT's rounding may differ between FFTW builds, unlike synthesize()'s portable bits).
#include <cstdint>

#include "topple/motion/ground_motion.hpp"

namespace topple {

/// The seismological parameters (defaults as in the header comment, WNA generic rock).
struct StochasticModel {
  double stress_drop_bar = 70.0;       ///< Brune stress parameter dsigma, bar (> 0)
  double beta_km_s = 3.5;              ///< shear-wave velocity at the source, km/s (> 0)
  double rho_g_cm3 = 2.72;             ///< density at the source, g/cm^3 (> 0)
  double q0 = 180.0;                   ///< Q(f) = q0 f^q_eta (> 0)
  double q_eta = 0.45;                 ///< in [0, 1)
  double kappa0_s = 0.04;              ///< site diminution kappa0, s (>= 0)
  double spreading_transition_km = 40.0;  ///< Z = 1/R to here, then R^-0.5
  double path_duration_s_per_km = 0.05;   ///< T_gm = 1/fc + this x R
  bool generic_rock_site = true;       ///< G(f) of Boore (2016) for Vs30 760 m/s; false: G = 1
};

struct StochasticSpec {
  double magnitude = 6.0;      ///< moment magnitude M, in [2, 9]
  double distance_km = 20.0;   ///< hypocentral distance R, km, in [1, 1000]
  double dt_s = 0.01;          ///< sample interval, s, in [1e-4, 0.05]
  std::uint64_t seed = 0;
  StochasticModel model;
};

/// Throws InputError naming the field ("magnitude", "distance_km", "dt_s", "stress_drop_bar", ...) and its value.
void validate(const StochasticSpec& spec);

/// M0 = 10^(1.5 M + 16.05) dyne-cm (Hanks & Kanamori 1979 with Boore 2003's constant).
[[nodiscard]] double seismic_moment_dyne_cm(double magnitude);
/// Brune corner frequency fc = 4.906e6 beta (dsigma / M0)^(1/3), Hz.
[[nodiscard]] double corner_frequency_hz(double magnitude, const StochasticModel& model);
/// T_gm = 1/fc + path_duration_s_per_km x R, s.
[[nodiscard]] double stochastic_duration_s(double magnitude, double distance_km, const StochasticModel& model);
/// G(f): Boore (2016) generic rock, Vs30 = 760 m/s (or 1 when the model says so).
[[nodiscard]] double site_amplification(double f_hz, const StochasticModel& model);
/// The target A(f) of the header, m/s (the Fourier amplitude of acceleration).
[[nodiscard]] double target_fas_m_s(double f_hz, double magnitude, double distance_km, const StochasticModel& model);
/// The frequency at which A(f) peaks, Hz: the zero of d ln A / d ln f (decreasing in R, M and kappa0), by bisection on
/// [0.01, 100] Hz.
[[nodiscard]] double fas_peak_frequency_hz(double magnitude, double distance_km, const StochasticModel& model);

/// The motion: uniform from t = 0, n samples (the FFT length, >= (t_eta + 2 p) / dt), m/s^2. Metadata: format
/// "synthetic", the event naming M, R and the seed. Throws InputError for an invalid spec.
[[nodiscard]] GroundMotion synthesize_stochastic(const StochasticSpec& spec);

// ---- The inversion's family (family = "boore2003"): a scenario whose spectrum peaks at a given frequency ----
//
// A weak prior: M uniform on [4, 7.5], R in [5, 150] km, kappa0 = 0.04 s. For a frequency f the magnitude is drawn
// uniformly over the magnitudes of [4, 7.5] whose peak can be f for some R in [5, 150] km (the peak falls with M and
// with R), and R then solves fas_peak_frequency_hz(M, R) = f. Where f lies above the peak of M = 4 at R = 5 km, kappa0
// is lowered (down to 0.005 s, hard rock) to reach it, and beyond that the scenario stays at (4, 5 km, 0.005 s);
// below the peak of M = 7.5 at 150 km it stays there. (The caller time-scales the motion onto f in every case.)
inline constexpr double kBooreMagnitudeMin = 4.0, kBooreMagnitudeMax = 7.5;
inline constexpr double kBooreDistanceMinKm = 5.0, kBooreDistanceMaxKm = 150.0;
inline constexpr double kBooreKappaMinS = 0.005;

/// The scenario (M, R, kappa0) for `u_magnitude` in [0, 1) and the frequency f_hz (> 0), as above; dt_s =
/// min(0.01, 1 / (20 f_hz)), the model's other parameters the defaults.
[[nodiscard]] StochasticSpec boore_scenario_for_peak(double u_magnitude, double f_hz, std::uint64_t seed);

/// One motion of the family at frequency f (> 0): scenarios drawn for the peak at f (boore_scenario_for_peak with u
/// from PortableRandom(mix of seed and the try)), each synthesised with its own noise, until one's measured
/// predominant frequency (spectra.hpp) lies within a factor kBooreAcceptRatio of f, at most kBooreMaxTries tries; the
/// one nearest f (in log) is kept. A rejection sampler of the prior's motions given their measured predominant
/// frequency: the analytic peak alone scatters by a factor 2 either way from a single motion's measured one (the
/// acceleration spectrum has a broad plateau between fc and the kappa roll-off). The caller time-scales the motion
/// onto f (a factor within kBooreAcceptRatio of 1 for accepted draws).
inline constexpr double kBooreAcceptRatio = 1.15;
inline constexpr int kBooreMaxTries = 8;

struct BooreDraw {
  GroundMotion motion;     ///< m/s^2, as synthesised (not scaled)
  StochasticSpec spec;     ///< the scenario kept
  double measured_hz = 0;  ///< its predominant frequency, Hz
  int tries = 0;           ///< how many were drawn (1 .. kBooreMaxTries)
};
[[nodiscard]] BooreDraw draw_boore2003(std::uint64_t seed, double f_hz);

}  // namespace topple
