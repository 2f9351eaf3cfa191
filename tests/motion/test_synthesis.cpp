// Synthetic motions: the portable generator, the exact filter discretisation, envelope, baseline, PGA, and the
// calibration that makes the measured predominant frequency equal the request.
#include <bit>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace topple {
namespace {

SynthesisSpec spec_at(double f_hz, std::uint64_t seed, FilterModel model = FilterModel::clough_penzien,
                      EnvelopeKind envelope = EnvelopeKind::saragoni_hart) {
  SynthesisSpec s;
  s.pga_m_s2 = 0.3 * kStandardGravity;
  s.predominant_frequency_hz = f_hz;
  s.duration_s = 20.0;
  s.dt_s = 0.01;
  s.seed = seed;
  s.model = model;
  s.envelope = envelope;
  return s;
}

/// FNV-1a over the bit patterns: a fingerprint of a motion, equal on every machine when the generator is portable.
std::uint64_t fingerprint(std::span<const double> values) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (double v : values) {
    const auto bits = std::bit_cast<std::uint64_t>(v);
    for (int k = 0; k < 64; k += 8) {
      h ^= (bits >> k) & 0xffU;
      h *= 0x100000001b3ULL;
    }
  }
  return h;
}

// ---- The generator ----

TEST(SynthRandom, SplitMix64AndXoshiroReferenceOutputs) {
  // SplitMix64 from 0: the first outputs of the reference C code (Vigna, splitmix64.c); xoshiro256** seeded from it:
  // the reference C code (xoshiro256starstar.c) run on that state, checked with an independent Python transcription.
  SplitMix64 sm(0);
  EXPECT_EQ(sm.next(), 0xe220a8397b1dcdafULL);
  EXPECT_EQ(sm.next(), 0x6e789e6aa1b965f4ULL);
  EXPECT_EQ(sm.next(), 0x06c45d188009454fULL);
  PortableRandom rng(0);
  EXPECT_EQ(rng.next(), 0x99ec5f36cb75f2b4ULL);
  EXPECT_EQ(rng.next(), 0xbf6e1f784956452aULL);
}

TEST(SynthRandom, NormalDeviatesHaveNormalMoments) {
  // 10^6 deviates: the standard errors of mean, variance and kurtosis are 1e-3, 1.4e-3 and 2.4e-3 (times 3 for the
  // excess kurtosis' variance 24/n); tolerances are 5 standard errors.
  PortableRandom rng(12345);
  constexpr int n = 1000000;
  double s1 = 0.0, s2 = 0.0, s4 = 0.0;
  int beyond3 = 0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.normal();
    s1 += x;
    s2 += x * x;
    s4 += x * x * x * x;
    if (std::abs(x) > 3.0) ++beyond3;
  }
  EXPECT_NEAR(s1 / n, 0.0, 5e-3);
  EXPECT_NEAR(s2 / n, 1.0, 7e-3);
  EXPECT_NEAR(s4 / n, 3.0, 5.0 * std::sqrt(96.0 / n));
  // P(|x| > 3) = 0.0026998; binomial standard error 5.2e-5.
  EXPECT_NEAR(static_cast<double>(beyond3) / n, 0.0026998, 2.6e-4);
}

TEST(SynthRandom, PortableExpAndLogWithinTwoUlp) {
  // The libm of this machine is accurate to < 1 ulp; the portable versions must stay within 2 ulp of it.
  for (double x = -700.0; x < 700.0; x += 0.7371) {
    const double ref = std::exp(x);
    EXPECT_NEAR(portable_exp(x), ref, 2.5 * std::numeric_limits<double>::epsilon() * ref) << x;
  }
  for (double x = 1e-300; x < 1e300; x *= 1.8731) {
    const double ref = std::log(x);
    EXPECT_NEAR(portable_log(x), ref, 2.5 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(ref)))
        << x;
  }
  EXPECT_EQ(portable_log(1.0), 0.0);
  EXPECT_EQ(portable_exp(0.0), 1.0);
  EXPECT_EQ(portable_exp(-800.0), 0.0);
  EXPECT_TRUE(std::isinf(portable_exp(800.0)));
}

// ---- The motion ----

TEST(SynthMotion, SameSeedSameBitsOtherSeedOtherMotion) {
  const GroundMotion a = synthesize(spec_at(3.0, 7));
  const GroundMotion b = synthesize(spec_at(3.0, 7));
  const GroundMotion c = synthesize(spec_at(3.0, 8));
  ASSERT_EQ(a.size(), 2001U);
  EXPECT_EQ(fingerprint(a.accel_m_s2()), fingerprint(b.accel_m_s2()));
  EXPECT_NE(fingerprint(a.accel_m_s2()), fingerprint(c.accel_m_s2()));
}

TEST(SynthMotion, GoldenFingerprintsArePortable) {
  // These numbers were produced on x86-64 (GCC 12, glibc 2.36). The generator uses only correctly rounded IEEE
  // operations and no FMA contraction, so every IEEE 754 machine must reproduce them bit for bit: a failure here
  // on another machine or compiler is a portability bug, not a tolerance to relax.
  EXPECT_EQ(fingerprint(synthesize(spec_at(3.0, 7)).accel_m_s2()), 5605603584186514496ULL);
  EXPECT_EQ(fingerprint(synthesize(spec_at(1.0, 42, FilterModel::kanai_tajimi, EnvelopeKind::jennings)).accel_m_s2()),
            11707605567583348990ULL);
}

TEST(SynthMotion, PgaStartAndBaseline) {
  for (auto model : {FilterModel::kanai_tajimi, FilterModel::clough_penzien}) {
    for (auto env : {EnvelopeKind::saragoni_hart, EnvelopeKind::jennings}) {
      const SynthesisSpec spec = spec_at(2.0, 11, model, env);
      const GroundMotion m = synthesize(spec);
      EXPECT_TRUE(m.is_uniform());
      EXPECT_DOUBLE_EQ(m.dt_s(), 0.01);
      EXPECT_NEAR(m.pga_m_s2(), spec.pga_m_s2, 2e-16 * spec.pga_m_s2);  // one multiplication: <= 1 ulp
      EXPECT_EQ(m.accel_m_s2()[0], 0.0);
      const auto vd = integrate_ground(m);
      const auto im = basic_intensity(m);
      // The correction zeroes the end velocity and displacement up to the round-off of sums of 2000 terms.
      EXPECT_LT(std::abs(vd.velocity_m_s.back()), 1e-12 * im.pgv_m_s) << filter_model_name(model);
      EXPECT_LT(std::abs(vd.displacement_m.back()), 1e-12 * im.pgd_m) << filter_model_name(model);
      EXPECT_EQ(m.metadata().format, "synthetic");
    }
  }
}

TEST(SynthMotion, KanaiTajimiDiscretisationIsTheExactOscillator) {
  // The Kanai-Tajimi stage is the oscillator x'' + 2 zeta w x' + w^2 x = -w(t) driven by the piecewise-linear noise,
  // output its absolute acceleration: exactly what the Nigam-Jennings recurrence computes with the noise as ground
  // acceleration. Two exact methods (matrix exponential; closed-form recurrence) agree to round-off: the noise has
  // unit variance and the outputs are O(1), so 1e-10 absolute leaves a factor 1e5 over the accumulated rounding.
  SynthesisSpec spec = spec_at(3.0, 5, FilterModel::kanai_tajimi);
  const std::vector<double> out = filtered_noise(spec);
  PortableRandom rng(spec.seed);
  std::vector<double> noise(out.size());
  for (double& w : noise) w = rng.normal();
  const double f_g = ground_frequency_for_request_hz(3.0, spec.ground_damping, spec.model);
  const OscillatorHistory h =
      oscillator_response(GroundMotion::uniform(noise, spec.dt_s), 1.0 / f_g, spec.ground_damping);
  double peak = 0.0;
  for (std::size_t i = 0; i < out.size(); ++i) {
    ASSERT_NEAR(out[i], h.absolute_accel_m_s2[i], 1e-10) << i;
    peak = std::max(peak, std::abs(out[i]));
  }
  EXPECT_GT(peak, 1.0);
}

TEST(SynthMotion, CloughPenzienDiscretisationMatchesAFineCascade) {
  // Reference: the Kanai-Tajimi output on a grid 40 times finer (exact: the noise is the same piecewise-linear
  // function there), then the high-pass oscillator by Nigam-Jennings on that fine, nearly linear input. The
  // reference's own error is O((w_g dt/40)^2) ~ 1e-5 of the signal; 1e-4 of the peak is the test's tolerance.
  SynthesisSpec spec = spec_at(3.0, 9, FilterModel::clough_penzien);
  spec.duration_s = 5.0;
  const std::vector<double> out = filtered_noise(spec);
  PortableRandom rng(spec.seed);
  std::vector<double> noise(out.size());
  for (double& w : noise) w = rng.normal();
  constexpr int kFine = 40;
  std::vector<double> fine((noise.size() - 1) * kFine + 1);
  for (std::size_t i = 0; i + 1 < noise.size(); ++i) {
    for (int k = 0; k < kFine; ++k) {
      fine[i * kFine + k] = noise[i] + (noise[i + 1] - noise[i]) * k / static_cast<double>(kFine);
    }
  }
  fine.back() = noise.back();
  const double h = spec.dt_s / kFine;
  const double f_g = ground_frequency_for_request_hz(3.0, spec.ground_damping, spec.model);
  const OscillatorHistory kt = oscillator_response(GroundMotion::uniform(fine, h), 1.0 / f_g, spec.ground_damping);
  // y'' + 2 zeta_f w_f y' + w_f^2 y = -a_KT: the NJ oscillator with a_KT as ground acceleration; a_CP = y''.
  const OscillatorHistory cp = oscillator_response(GroundMotion::uniform(kt.absolute_accel_m_s2, h),
                                                   1.0 / (f_g * spec.high_pass_ratio), spec.high_pass_damping);
  double peak = 0.0;
  for (double v : out) peak = std::max(peak, std::abs(v));
  for (std::size_t i = 0; i < out.size(); ++i) {
    const std::size_t j = i * kFine;
    const double y_ddot = cp.absolute_accel_m_s2[j] - kt.absolute_accel_m_s2[j];
    ASSERT_NEAR(out[i], y_ddot, 1e-4 * peak) << i;
  }
}

TEST(SynthMotion, Envelopes) {
  SynthesisSpec s = spec_at(3.0, 1);
  // Saragoni-Hart: peak 1 at eps T, eta at T, zero at 0.
  EXPECT_NEAR(envelope_at(s, 0.2 * 20.0), 1.0, 1e-15);
  EXPECT_NEAR(envelope_at(s, 20.0), 0.05, 1e-15);
  EXPECT_EQ(envelope_at(s, 0.0), 0.0);
  EXPECT_LT(envelope_at(s, 3.9), 1.0);
  EXPECT_LT(envelope_at(s, 4.1), 1.0);
  s.envelope = EnvelopeKind::jennings;
  EXPECT_DOUBLE_EQ(envelope_at(s, 1.0), 0.25);  // (t / t1)^2, t1 = 2 s
  EXPECT_DOUBLE_EQ(envelope_at(s, 5.0), 1.0);
  EXPECT_NEAR(envelope_at(s, 20.0), 0.05, 1e-15);
}

TEST(SynthMotion, InvalidSpecsNameTheField) {
  const auto expect_field = [](SynthesisSpec s, const std::string& field, const std::string& text) {
    try {
      (void)synthesize(s);
      ADD_FAILURE() << "no error for " << field;
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, field);
      EXPECT_NE(std::string(e.what()).find(text), std::string::npos) << e.what();
    }
  };
  SynthesisSpec s = spec_at(3.0, 1);
  s.pga_m_s2 = -1.0;
  expect_field(s, "pga", "got -1 m/s2");
  s = spec_at(12.0, 1);
  expect_field(s, "freq", "got 12 Hz");
  s = spec_at(3.0, 1);
  s.duration_s = 1.0;
  expect_field(s, "duration", "got 1 s");
  s = spec_at(3.0, 1);
  s.ground_damping = 0.6;
  expect_field(s, "ground_damping", "got 0.6");
  s = spec_at(3.0, 1);
  s.jennings_rise_fraction = 0.7;
  expect_field(s, "jennings_rise_fraction", "t1/T = 0.7");
  EXPECT_THROW((void)parse_filter_model("kanai"), InputError);
  EXPECT_EQ(parse_envelope_kind("jennings"), EnvelopeKind::jennings);
}

// ---- The calibration ----

double mean_measured(double f_hz, int seeds, FilterModel model, EnvelopeKind env, double duration_s = 20.0) {
  double sum = 0.0;
  for (int seed = 0; seed < seeds; ++seed) {
    SynthesisSpec s = spec_at(f_hz, static_cast<std::uint64_t>(seed) + 1000, model, env);
    s.duration_s = duration_s;
    sum += predominant_frequency_hz(synthesize(s));
  }
  return sum / seeds;
}

TEST(SynthPredominantFrequency, MeanOverHundredSeedsMatchesRequest) {
  // The acceptance test: over 100 seeds the mean measured predominant frequency is within 10 % of the
  // request. Seeds 1000-1099 are not those of the calibration (0-199), so this is out of sample.
  for (double f : {1.0, 3.0, 8.0}) {
    const double mean = mean_measured(f, 100, FilterModel::clough_penzien, EnvelopeKind::saragoni_hart);
    EXPECT_NEAR(mean / f, 1.0, 0.10) << f << " Hz requested, mean measured " << mean;
    RecordProperty(fmt::format("mean_measured_{}hz", f), fmt::format("{:.4f}", mean));
    fmt::print("requested {} Hz: mean measured predominant frequency over 100 seeds {:.4f} Hz ({:+.1f} %)\n", f, mean,
               100.0 * (mean / f - 1.0));
  }
}

TEST(SynthPredominantFrequency, OtherModelsEnvelopesAndDurations) {
  // Same criterion for the Kanai-Tajimi model, the Jennings envelope and 10 s / 40 s records (the calibration was
  // made at 20 s with Saragoni-Hart). 50 seeds each to keep the suite fast; 100 for Kanai-Tajimi, whose flat
  // low-frequency plateau scatters a single motion's peak most (coefficient of variation about 0.35).
  struct Case { double f; FilterModel model; EnvelopeKind env; double duration; int seeds; };
  for (const Case& c : {Case{3.0, FilterModel::kanai_tajimi, EnvelopeKind::saragoni_hart, 20.0, 100},
                        Case{3.0, FilterModel::clough_penzien, EnvelopeKind::jennings, 20.0, 50},
                        Case{5.0, FilterModel::clough_penzien, EnvelopeKind::saragoni_hart, 10.0, 50},
                        Case{1.5, FilterModel::clough_penzien, EnvelopeKind::saragoni_hart, 40.0, 50}}) {
    const double mean = mean_measured(c.f, c.seeds, c.model, c.env, c.duration);
    fmt::print("{} Hz, {}, {}, {} s: mean measured {:.4f} Hz ({:+.1f} %)\n", c.f, filter_model_name(c.model),
               envelope_kind_name(c.env), c.duration, mean, 100.0 * (mean / c.f - 1.0));
    EXPECT_NEAR(mean / c.f, 1.0, 0.10) << c.f << " Hz, " << filter_model_name(c.model) << ", "
                                       << envelope_kind_name(c.env) << ", " << c.duration << " s: mean " << mean;
  }
}

// Produces the calibration table of synthesis.cpp (run with --gtest_also_run_disabled_tests). kappa at each node
// (zeta_g, f_g) is the mean over 200 seeds (0-199) of predominant_frequency_hz / f_g, f_g being the frequency the
// generator actually used for the request (independent of the table's current values up to round-off).
TEST(SynthPredominantFrequency, DISABLED_CalibrationTable) {
  for (auto model : {FilterModel::kanai_tajimi, FilterModel::clough_penzien}) {
    for (double zeta : {0.1, 0.2, 0.3, 0.4, 0.5}) {
      std::string row = fmt::format("{} zeta_g {:.1f}:", filter_model_name(model), zeta);
      for (double f_target : {0.5, 1.0, 2.0, 4.0, 8.0}) {
        const double request = f_target * predominant_frequency_ratio(zeta, model, f_target);
        const double f_g = ground_frequency_for_request_hz(request, zeta, model);
        double sum = 0.0;
        for (int seed = 0; seed < 200; ++seed) {
          SynthesisSpec s = spec_at(request, static_cast<std::uint64_t>(seed), model);
          s.ground_damping = zeta;
          sum += predominant_frequency_hz(synthesize(s)) / f_g;
        }
        row += fmt::format(" {:.3f}", sum / 200.0);
      }
      fmt::print("{}\n", row);
    }
  }
}

}  // namespace
}  // namespace topple

// ---- The record-like family of Rezaeian & Der Kiureghian (2010) (synthesis.hpp) ----------------------------------
namespace topple {
namespace {

/// Quantile p of the gamma distribution of integer shape k and rate 1, from its closed-form CDF
/// 1 - exp(-x) sum_{j<k} x^j / j!, by bisection to 1e-13: an oracle independent of gamma_envelope's quadrature.
double gamma_quantile_closed_form(int k, double p) {
  const auto cdf = [k](double x) {
    double term = 1.0;
    double sum = 1.0;
    for (int j = 1; j < k; ++j) {
      term *= x / j;
      sum += term;
    }
    return 1.0 - std::exp(-x) * sum;
  };
  double lo = 0.0;
  double hi = 200.0;
  while (hi - lo > 1e-13) {
    const double mid = 0.5 * (lo + hi);
    (cdf(mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(SynthRezaeian, GammaEnvelopeReproducesClosedFormQuantiles) {
  // Shape 3 (alpha2 = 2): t_mid = 10 s and D5-95 from the closed-form quantiles must give back k = 3 and the rate
  // Q45 / t_mid. Tolerance 1e-3 relative: the quadrature has 1000 steps (error ~1e-4) and k is found by bisection.
  const double q05 = gamma_quantile_closed_form(3, 0.05);
  const double q45 = gamma_quantile_closed_form(3, 0.45);
  const double q95 = gamma_quantile_closed_form(3, 0.95);
  const GammaEnvelope g = gamma_envelope(10.0 * (q95 - q05) / q45, 10.0);
  EXPECT_NEAR(g.shape, 3.0, 3e-3);
  EXPECT_NEAR(g.rate_s, q45 / 10.0, 1e-3 * q45 / 10.0);
  EXPECT_NEAR(g.t999_s, gamma_quantile_closed_form(3, 0.999) / g.rate_s, 1e-3 * g.t999_s);
  // Wider than the exponential's spread (D5-95 / t_mid > 4.93): shape 1, rate -ln(0.55) / t_mid exactly in closed form.
  const GammaEnvelope e = gamma_envelope(6.0 * 5.5, 6.0);
  EXPECT_DOUBLE_EQ(e.shape, 1.0);
  EXPECT_NEAR(e.rate_s, -std::log(0.55) / 6.0, 1e-3 * e.rate_s);
  EXPECT_THROW((void)gamma_envelope(0.0, 6.0), InputError);
}

TEST(SynthRezaeian, MotionIsReproducibleScaledAndBaselineCorrected) {
  const RezaeianSpec spec = draw_rezaeian(5, 2.0);
  const GroundMotion a = synthesize_rezaeian(spec);
  const GroundMotion b = synthesize_rezaeian(spec);
  RezaeianSpec other = spec;
  other.seed = spec.seed + 1;
  const GroundMotion c = synthesize_rezaeian(other);
  EXPECT_EQ(fingerprint(a.accel_m_s2()), fingerprint(b.accel_m_s2()));
  EXPECT_NE(fingerprint(a.accel_m_s2()), fingerprint(c.accel_m_s2()));
  // Produced on x86-64 (GCC 12, glibc 2.36); only correctly rounded IEEE operations, topple's exp/log and a Taylor
  // sin/cos, no FMA contraction: every IEEE 754 machine must reproduce it (as GoldenFingerprintsArePortable).
  EXPECT_EQ(fingerprint(a.accel_m_s2()), 17512443798881407456ULL);
  EXPECT_NEAR(a.pga_m_s2(), spec.pga_m_s2, 2e-16 * spec.pga_m_s2);  // one multiplication: <= 1 ulp
  const auto vd = integrate_ground(a);
  const auto im = basic_intensity(a);
  // The shared baseline correction zeroes the end velocity and displacement up to round-off (as for synthesize()).
  EXPECT_LT(std::abs(vd.velocity_m_s.back()), 1e-11 * im.pgv_m_s);
  EXPECT_LT(std::abs(vd.displacement_m.back()), 1e-11 * im.pgd_m);
  // The draw: durations within the clipped ranges, f_c a tenth of f_mid, 20 samples per period at least.
  EXPECT_GE(spec.d5_95_s, 5.0);
  EXPECT_LE(spec.d5_95_s, 45.0);
  EXPECT_DOUBLE_EQ(spec.f_c_hz, 0.2);
  EXPECT_LE(spec.dt_s, 1.0 / (20.0 * 2.0));
}

TEST(SynthRezaeian, SignificantDurationFollowsTheEnvelope) {
  // The gamma envelope sets the Husid plot of the *expected* a^2; a single motion scatters around it. Over 20 seeds
  // the mean measured D5-95 / requested must be within 15 % of 1 (measured 0.980; the filter's memory and the
  // high-pass stretch the strong phase a little).
  double sum = 0.0;
  const int n = 20;
  for (int s = 0; s < n; ++s) {
    RezaeianSpec spec;
    spec.d5_95_s = 12.0;
    spec.t_mid_s = 9.0;
    spec.f_mid_hz = 4.0;
    spec.f_slope_hz_s = -0.05;
    spec.zeta_f = 0.3;
    spec.f_c_hz = 0.2;
    spec.dt_s = 0.01;
    spec.seed = static_cast<std::uint64_t>(s) + 100;
    sum += significant_duration(synthesize_rezaeian(spec)).duration_s / spec.d5_95_s;
  }
  fmt::print("mean D5-95 measured / requested: {:.3f}\n", sum / n);
  EXPECT_NEAR(sum / n, 1.0, 0.15);
}

TEST(SynthRezaeian, InvalidSpecsNameTheField) {
  RezaeianSpec spec;
  spec.zeta_f = 0.99;
  try {
    (void)synthesize_rezaeian(spec);
    FAIL() << "zeta_f 0.99 accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "zeta_f");
  }
  spec = RezaeianSpec{};
  spec.dt_s = 0.2;  // 5.87 Hz at 0.2 s: the step's angle is over 1 rad
  try {
    (void)synthesize_rezaeian(spec);
    FAIL() << "dt 0.2 s accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "dt_s");
  }
}

}  // namespace
}  // namespace topple
