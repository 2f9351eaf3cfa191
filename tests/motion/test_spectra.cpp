// Spectra and the intensity measures built on them: the Nigam-Jennings recurrence against closed forms, the
// Fourier spectrum and its peak, Tp and Tm on signals whose answer is known, D5-95 and CAV, and the peers pyrotd and
// eqsig on the shared records (computed at test time in .venv-test; skipped without it).
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/noise_record.hpp"
#include "support/peer_script.hpp"
#include "support/shared_data.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

GroundMotion sampled(double dt, std::size_t n, const auto& f) {
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) a[i] = f(static_cast<double>(i) * dt);
  return GroundMotion::uniform(std::move(a), dt);
}

// ---- Nigam-Jennings recurrence ----

TEST(SpectrumSdof, RampInputIsExactOnACoarseGrid) {
  // a_g = c t is piecewise linear, so the recurrence must reproduce the closed form to round-off on any step:
  // x'' + 2 z w x' + w^2 x = -c t from rest: x = -c t / w^2 + 2 z c / w^3 + exp(-z w t) (B1 cos wd t + B2 sin wd t),
  // B1 = -2 z c / w^3, B2 = (c / w^2 + z w B1) / wd. Tolerance: 1e-12 of the largest |x| (a few hundred steps).
  const double c = 2.5, period = 0.3, zeta = 0.05, dt = 0.05;
  const double w = 2.0 * kPi / period, wd = w * std::sqrt(1.0 - zeta * zeta);
  const double b1 = -2.0 * zeta * c / (w * w * w), b2 = (c / (w * w) + zeta * w * b1) / wd;
  const auto exact = [&](double t) {
    return -c * t / (w * w) + 2.0 * zeta * c / (w * w * w) +
           std::exp(-zeta * w * t) * (b1 * std::cos(wd * t) + b2 * std::sin(wd * t));
  };
  const GroundMotion m = sampled(dt, 201, [&](double t) { return c * t; });
  const OscillatorHistory h = oscillator_response(m, period, zeta);
  double scale = 0.0;
  for (double x : h.displacement_m) scale = std::max(scale, std::abs(x));
  for (std::size_t i = 0; i < m.size(); ++i) EXPECT_NEAR(h.displacement_m[i], exact(m.time_s(i)), 1e-12 * scale) << i;
}

TEST(SpectrumSdof, HarmonicInputMatchesSteadyStatePlusTransient) {
  // a_g = A sin(W t) from rest: x = C1 sin Wt + C2 cos Wt + exp(-z w t) (B1 cos wd t + B2 sin wd t) with
  // D = (w^2 - W^2)^2 + (2 z w W)^2, C1 = -A (w^2 - W^2) / D, C2 = 2 z w W A / D, B1 = -C2, B2 = (z w B1 - C1 W) / wd.
  // The sampled sine differs from its chords by at most A (W dt)^2 / 8 = 5e-6 A at 1000 samples per cycle, so the
  // response differs from the closed form by about that fraction of its amplitude: tolerance 2e-5 of max |x|.
  const double amp = 3.0, big_w = 2.0 * kPi * 2.0;  // 2 Hz forcing
  for (const auto& [period, zeta] : {std::pair{0.5, 0.05}, {0.4, 0.02}, {1.3, 0.2}, {0.25, 0.0}}) {
    const double w = 2.0 * kPi / period, wd = w * std::sqrt(1.0 - zeta * zeta);
    const double d = (w * w - big_w * big_w) * (w * w - big_w * big_w) + 4.0 * zeta * zeta * w * w * big_w * big_w;
    const double c1 = -amp * (w * w - big_w * big_w) / d, c2 = 2.0 * zeta * w * big_w * amp / d;
    const double b1 = -c2, b2 = (zeta * w * b1 - c1 * big_w) / wd;
    const auto exact = [&](double t) {
      return c1 * std::sin(big_w * t) + c2 * std::cos(big_w * t) +
             std::exp(-zeta * w * t) * (b1 * std::cos(wd * t) + b2 * std::sin(wd * t));
    };
    const double dt = 1.0 / 2000.0;  // 1000 samples per forcing cycle
    const GroundMotion m = sampled(dt, 20001, [&](double t) { return amp * std::sin(big_w * t); });
    const OscillatorHistory h = oscillator_response(m, period, zeta);
    double scale = 0.0;
    for (double x : h.displacement_m) scale = std::max(scale, std::abs(x));
    for (std::size_t i = 0; i < m.size(); i += 37) {
      ASSERT_NEAR(h.displacement_m[i], exact(m.time_s(i)), 2e-5 * scale) << period << " s, t = " << m.time_s(i);
    }
    // The bank (vectorised over periods) is the same arithmetic.
    const ResponseSpectrum r = OscillatorBank({period}, zeta, dt).respond(m);
    EXPECT_DOUBLE_EQ(r.sd_m[0], scale);
    EXPECT_NEAR(r.psa_m_s2[0], w * w * scale, 1e-12 * w * w * scale);
  }
}

TEST(SpectrumSdof, IrregularRecordGivesTheSameSpectrum) {
  // A uniform record given as irregular times goes through the per-step path: same numbers to round-off.
  const GroundMotion u = sampled(0.01, 1500, [](double t) { return std::sin(7.0 * t) * std::exp(-0.2 * t) + 0.3 * std::cos(23.0 * t); });
  const GroundMotion irr = GroundMotion::irregular(u.times_s(), std::vector<double>(u.accel_m_s2().begin(), u.accel_m_s2().end()));
  ASSERT_FALSE(irr.is_uniform());
  const std::vector<double> periods = {0.05, 0.3, 1.0, 3.0};
  const ResponseSpectrum a = response_spectrum(u, periods);
  const ResponseSpectrum b = response_spectrum(irr, periods);
  for (std::size_t p = 0; p < periods.size(); ++p) {
    EXPECT_NEAR(a.sd_m[p], b.sd_m[p], 1e-9 * a.sd_m[p]);
    EXPECT_NEAR(a.sa_m_s2[p], b.sa_m_s2[p], 1e-9 * a.sa_m_s2[p]);
  }
  EXPECT_THROW((void)OscillatorBank({0.5}, 0.05, 0.02).respond(u), InputError);
  EXPECT_THROW((void)OscillatorBank({-0.5}, 0.05, 0.01), InputError);
  EXPECT_THROW((void)OscillatorBank({0.5}, 1.0, 0.01), InputError);
}

// ---- Fourier spectrum, predominant frequency, Tp, Tm ----

TEST(SpectrumFourier, SineAmplitudeAndPredominantFrequency) {
  // A sin(2 pi f t) over whole cycles: |A(f)| = A T / 2 at the bin f (f T integer). The smoothed peak is at f
  // within 1 %: the Konno-Ohmachi window weighs in log f, which pulls the peak of the line (symmetric in f) down by
  // up to 0.5 %, and the parabola on the 1/200-decade grid adds less than 0.1 %.
  const double amp = 2.0, f = 2.5, dt = 0.01;
  const GroundMotion m = sampled(dt, 4000, [&](double t) { return amp * std::sin(2.0 * kPi * f * t); });
  const FourierSpectrum s = fourier_amplitude_spectrum(m);
  const auto k = static_cast<std::size_t>(std::lround(f * 4000 * dt));
  EXPECT_NEAR(s.frequency_hz[k], f, 1e-12);
  EXPECT_NEAR(s.amplitude_m_s[k], amp * 40.0 / 2.0, 1e-9 * amp * 40.0);
  EXPECT_NEAR(predominant_frequency_hz(m), f, 0.01 * f);
  for (double g : {0.3, 1.0, 7.7, 18.0}) {
    const GroundMotion other = sampled(dt, 6000, [&](double t) { return std::sin(2.0 * kPi * g * t); });
    EXPECT_NEAR(predominant_frequency_hz(other), g, 0.01 * g) << g;
  }
}

TEST(SpectrumFourier, KonnoOhmachiKeepsAConstantSpectrum) {
  FourierSpectrum s;
  s.dt_s = 0.01;
  for (int k = 0; k <= 1000; ++k) {
    s.frequency_hz.push_back(0.05 * k);
    s.amplitude_m_s.push_back(3.0);
  }
  const std::vector<double> centres = {0.2, 1.0, 10.0, 40.0};
  for (double v : konno_ohmachi_smooth(s, centres, 40.0)) EXPECT_NEAR(v, 3.0, 1e-12);
  EXPECT_THROW((void)konno_ohmachi_smooth(s, centres, 0.0), InputError);
}

// konno_ohmachi_smooth keeps the weights of a grid it met twice in its last three calls (spectra.cpp,
// KonnoOhmachiTable; issue 32, performance only): smoothing with the table must give, bit for bit, what a thread that
// never met the grid computes. Two grids alternate as build_family's measurements do (a column's raw motions on one
// grid, each time-scaled motion on its own): the first call on grid A computes, the second builds the table, the
// third and later use it; grid B always computes.
TEST(SpectrumSmoothing, KonnoOhmachiTableGivesTheSameBits) {
  const auto spectrum = [](std::uint64_t seed, double dt_s) {
    test::NoiseRecordSpec ns;
    ns.seed = seed;
    ns.samples = 3000;
    ns.dt_s = dt_s;
    ns.pga_m_s2 = 1.0;
    const GroundMotion m = test::noise_record(ns);
    return fourier_amplitude_spectrum(m, predominant_frequency_fft_length(m.size()));
  };
  const std::vector<double> centres = predominant_frequency_centres_hz(0.005);
  std::vector<FourierSpectrum> on_a, on_b;
  for (std::uint64_t k = 0; k < 4; ++k) {
    on_a.push_back(spectrum(k + 1, 0.005));
    on_b.push_back(spectrum(k + 11, 0.005 * (1.1 + 0.1 * static_cast<double>(k))));
  }
  // The reference: each spectrum smoothed on a fresh thread (an empty cache: the direct sums).
  const auto fresh = [&](const FourierSpectrum& s) {
    std::vector<double> out;
    std::thread([&] { out = konno_ohmachi_smooth(s, centres, 40.0); }).join();
    return out;
  };
  std::vector<std::vector<double>> want_a, want_b;
  for (std::size_t k = 0; k < 4; ++k) {
    want_a.push_back(fresh(on_a[k]));
    want_b.push_back(fresh(on_b[k]));
  }
  std::thread([&] {  // one thread, so that its cache sees the sequence A0 B0 A1 B1 A2 B2 A3 B3
    for (std::size_t k = 0; k < 4; ++k) {
      EXPECT_EQ(konno_ohmachi_smooth(on_a[k], centres, 40.0), want_a[k]) << "A" << k;  // computed, built, used, used
      EXPECT_EQ(konno_ohmachi_smooth(on_b[k], centres, 40.0), want_b[k]) << "B" << k;
    }
    // Another bandwidth on grid A is another table.
    const std::vector<double> other = konno_ohmachi_smooth(on_a[0], centres, 20.0);
    EXPECT_NE(other, want_a[0]);
    EXPECT_EQ(konno_ohmachi_smooth(on_a[0], centres, 40.0), want_a[0]);
  }).join();
  // The smoothing is not trivial here: the values differ from spectrum to spectrum.
  EXPECT_NE(want_a[0], want_a[1]);
}

TEST(SpectrumPeriods, TpAndTmOfASine) {
  // Tm of a pure tone at a bin frequency is 1/f exactly (all energy in one bin); Tp is the resonance of the
  // 5 %-damped oscillator with the tone, at T = 1/f within the grid's parabola (0.5 %) and the shift of the
  // damped peak of the transient build-up (about zeta^2: 0.25 %).
  const double f = 2.0;
  const GroundMotion m = sampled(0.01, 3000, [&](double t) { return std::sin(2.0 * kPi * f * t); });
  EXPECT_NEAR(mean_period_s(m), 1.0 / f, 1e-9);
  EXPECT_NEAR(predominant_period_s(m), 1.0 / f, 0.01 / f);
}

TEST(SpectrumPeriods, ZeroRecordHasNoPeriods) {
  const GroundMotion zero = GroundMotion::uniform(std::vector<double>(500, 0.0), 0.01);
  EXPECT_THROW((void)predominant_frequency_hz(zero), InputError);
  EXPECT_THROW((void)mean_period_s(zero), InputError);
  EXPECT_THROW((void)predominant_period_s(zero), InputError);
  EXPECT_THROW((void)significant_duration(zero), InputError);
}

// ---- D5-95 and CAV ----

TEST(IntensityDuration, KnownShapesAreExact) {
  // Constant acceleration over [0, T]: the Husid plot is t / T, so D5-95 = 0.9 T, from 0.05 T.
  const GroundMotion flat = GroundMotion::uniform(std::vector<double>(11, 1.5), 2.0);
  auto d = significant_duration(flat);
  EXPECT_NEAR(d.start_s, 1.0, 1e-13);
  EXPECT_NEAR(d.duration_s, 18.0, 1e-13);
  // A ramp a = t over one step [0, T]: H = (t / T)^3, crossings at T p^(1/3), inside a single step.
  const GroundMotion ramp = GroundMotion::uniform({0.0, 4.0}, 4.0);
  d = significant_duration(ramp);
  EXPECT_NEAR(d.start_s, 4.0 * std::cbrt(0.05), 1e-13);
  EXPECT_NEAR(d.end_s, 4.0 * std::cbrt(0.95), 1e-13);
  // The same ramp split at arbitrary points (an irregular record) gives the same times.
  const GroundMotion split = GroundMotion::irregular({0.0, 0.3, 1.7, 3.1, 4.0}, {0.0, 0.3, 1.7, 3.1, 4.0});
  const auto d2 = significant_duration(split);
  EXPECT_NEAR(d2.start_s, d.start_s, 1e-13);
  EXPECT_NEAR(d2.end_s, d.end_s, 1e-13);
  // A sine burst's Husid plot: for A sin(w t) over n whole cycles, H(t) = (t - sin(2 w t) / (2 w)) / T.
  const double w = 2.0 * kPi;
  const GroundMotion burst = sampled(0.0005, 20001, [&](double t) { return std::sin(w * t); });  // 10 cycles
  const auto h = husid(burst);
  EXPECT_DOUBLE_EQ(h.back(), 1.0);
  for (std::size_t i = 0; i < h.size(); i += 997) {
    const double t = burst.time_s(i);
    EXPECT_NEAR(h[i], (t - std::sin(2.0 * w * t) / (2.0 * w)) / 10.0, 2e-7) << t;  // chords vs sine: (w dt)^2 / 12
  }
  EXPECT_THROW((void)significant_duration(burst, 0.5, 0.4), InputError);
}

TEST(IntensityCav, ExactAcrossZeroCrossings) {
  // A triangle through zero: 0 -> 2 (1 s) -> -2 (1 s): |a| integrates to 1 + 0.5 + 0.5 = 2.
  EXPECT_NEAR(cumulative_absolute_velocity_m_s(GroundMotion::uniform({0.0, 2.0, -2.0}, 1.0)), 2.0, 1e-15);
  // A sin(w t) over 10 whole cycles: CAV = 10 * 4 A / w. Chords under-estimate |sin| by (w dt)^2 / 12 relative.
  const double w = 2.0 * kPi, amp = 3.0;
  const GroundMotion burst = sampled(0.0005, 20001, [&](double t) { return amp * std::sin(w * t); });
  EXPECT_NEAR(cumulative_absolute_velocity_m_s(burst), 40.0 * amp / w, 1e-6 * 40.0 * amp / w);
}

// ---- Peers: eqsig (same recurrence; trapezoid-rule intensity measures) and pyrotd (frequency domain) ----

using test::venv_python;

nlohmann::json run_peers(const GroundMotion& m, const std::vector<double>& periods, int upsample, double pad_s) {
  const test::TempDir dir;
  const auto accel = dir.path() / "accel.txt";
  test::write_column(accel, m.accel_m_s2());
  return test::run_peer_script("peer_spectra.py", fmt::format("'{}' {} '{}' {} {}", accel.string(), m.dt_s(),
                                                              nlohmann::json(periods).dump(), upsample, pad_s));
}

class SpectrumPeers : public ::testing::TestWithParam<const char*> {};

TEST_P(SpectrumPeers, EqsigAndPyrotdOnARecord) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared is absent";
  if (!std::filesystem::exists(venv_python())) GTEST_SKIP() << ".venv-test is absent (scripts/test-venv.sh)";
  const GroundMotion record = io::read_motion(test::shared_record(GetParam()));
  ASSERT_TRUE(record.is_uniform());
  const double dt = record.dt_s();
  // Periods from 10 dt to 4 s.
  std::vector<double> periods;
  for (double t : {0.1, 0.15, 0.2, 0.3, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0}) {
    if (t >= 10.0 * dt) periods.push_back(t);
  }
  // pyrotd sees the record linearly interpolated at dt/10 (the same piecewise-linear function, so topple's answer
  // is unchanged but for the finer sampling of the maximum) and 150 s of zeros (the 5 %-damped 4 s oscillator decays
  // to 1e-5 in 146 s, so its circular response does not wrap). topple gets the same fine, padded record.
  constexpr int kUp = 10;
  constexpr double kPad = 150.0;
  const nlohmann::json peer = run_peers(record, periods, kUp, kPad);
  ASSERT_FALSE(peer.is_null());
  const auto a = record.accel_m_s2();
  const ResponseSpectrum ours_fine = response_spectrum(test::upsampled_padded(record, kUp, kPad), periods);
  const ResponseSpectrum ours = response_spectrum(record, periods);
  double worst_pyrotd = 0.0;
  for (std::size_t p = 0; p < periods.size(); ++p) {
    // eqsig: the same recurrence on the same samples; its w = 6.2831853 / T (2 pi rounded to 8 digits, 5e-9
    // relative) and its own rounding leave about 1e-7 near resonance.
    const double sd_eqsig = peer["eqsig_nj_sd"][p].get<double>();
    EXPECT_NEAR(ours.sd_m[p], sd_eqsig, 1e-6 * sd_eqsig) << GetParam() << " T = " << periods[p];
    // pyrotd: band-limited (FFT) interpolation of the dt/10 samples against their chords differs by about
    // (pi dt / (10 T))^2 / 3 < 4e-4 at T >= 10 dt; the maxima are taken on the same dt/10 grid. 1e-3 relative.
    const double psa_pyrotd = peer["pyrotd_psa"][p].get<double>();
    const double rel = std::abs(ours_fine.psa_m_s2[p] - psa_pyrotd) / psa_pyrotd;
    worst_pyrotd = std::max(worst_pyrotd, rel);
    EXPECT_LT(rel, 1e-3) << GetParam() << " T = " << periods[p] << ": topple " << ours_fine.psa_m_s2[p]
                         << ", pyrotd " << psa_pyrotd;
  }
  RecordProperty("worst_relative_difference_pyrotd", fmt::format("{:.3g}", worst_pyrotd));
  fmt::print("{}: worst |topple - pyrotd| / pyrotd = {:.3g} over {} periods\n", GetParam(), worst_pyrotd,
             periods.size());

  // Intensity measures against eqsig, whose definitions differ: its integrals are trapezoid rules on the samples
  // (topple integrates the piecewise-linear record exactly) and its Arias uses g = 9.81. The differences are known
  // in closed form, so the comparison is exact up to round-off (1e-9 relative):
  //   Arias: trapezoid h (a0^2 + a1^2) / 2 minus exact h (a0^2 + a0 a1 + a1^2) / 3 = h (a1 - a0)^2 / 6 per step;
  //   CAV: trapezoid h (p + q) / 2 minus exact h (p^2 + q^2) / (2 (p + q)) = h p q / (p + q) in steps where a
  //        changes sign (p = |a0|, q = |a1|), zero elsewhere.
  double arias_gap = 0.0;
  double cav_gap = 0.0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    arias_gap += dt * (a[i] - a[i - 1]) * (a[i] - a[i - 1]) / 6.0;
    if (a[i] * a[i - 1] < 0.0) {
      const double p = std::abs(a[i - 1]), q = std::abs(a[i]);
      cav_gap += dt * p * q / (p + q);
    }
  }
  const BasicIntensity im = basic_intensity(record, 9.81);
  const double arias_eqsig = peer["eqsig_arias"].get<double>();
  EXPECT_NEAR(im.arias_m_s + kPi / (2.0 * 9.81) * arias_gap, arias_eqsig, 1e-9 * arias_eqsig);
  const double cav_eqsig = peer["eqsig_cav"].get<double>();
  EXPECT_NEAR(cumulative_absolute_velocity_m_s(record) + cav_gap, cav_eqsig, 1e-9 * cav_eqsig);
  // D5-95: eqsig takes the first and last samples strictly inside (5 %, 95 %) of its trapezoid Husid curve (up to
  // 2 dt shorter than the crossings). Where the two Arias integrals agree within 1 % that is the only difference;
  // where they do not (CPM000 at dt = 0.02 s has energy near Nyquist: 7.7 %), the curves themselves differ and the
  // durations are not comparable (5.82 s exact, 6.19 s from the trapezoid curve, eqsig 6.16 s).
  const double d_eqsig = peer["eqsig_d5_95"].get<double>();
  const double d_ours = significant_duration(record).duration_s;
  fmt::print("{}: Arias exact {:.5g} vs trapezoid {:.5g} m/s; D5-95 {:.4f} s, eqsig {:.4f} s\n", GetParam(),
             im.arias_m_s, arias_eqsig, d_ours, d_eqsig);
  if (arias_gap < 0.01 * im.arias_m_s * 2.0 * 9.81 / kPi) {
    EXPECT_NEAR(d_ours, d_eqsig, 3.0 * dt);
  }
}

INSTANTIATE_TEST_SUITE_P(Records, SpectrumPeers,
                         ::testing::Values("RSN6_IMPVALL.I_I-ELC180.AT2", "Rinaldi228.AT2", "CPM000.AT2",
                                           "RSN763_LOMAP_GIL067.AT2"),
                         [](const auto& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name) {
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace topple
