// Flexible supports (flexible.hpp): limiting cases against the rigid solver, the harmonic steady state of the
// support, exactness of the coupled solver under up-sampling, second-order convergence of the decoupled analysis to
// the exact coupled one with a massless object, and input validation.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple {
namespace {

/// A smooth, non-harmonic test motion (two tones with an envelope), m/s^2, sampled at dt.
GroundMotion test_motion(double dt, double pga_g = 0.4, double duration = 8.0) {
  const auto n = static_cast<std::size_t>(duration / dt) + 1;
  std::vector<double> a(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) * dt;
    const double env = std::sin(kPi * t / duration);
    a[i] = pga_g * kStandardGravity * env * env * (0.7 * std::sin(2 * kPi * 1.3 * t) + 0.3 * std::sin(2 * kPi * 3.7 * t + 0.4));
  }
  return GroundMotion::uniform(std::move(a), dt);
}

TEST(Flexible, StiffSupportDecoupledEqualsRigid) {
  // A support at 10 kHz (SupportOscillator::kMaxFreqHz) follows the ground: under piecewise-linear input its steady
  // response has Y'' = 0, so its absolute acceleration is the ground's up to the transient after each slope change,
  // which decays as exp(-zeta omega t) (exp(-31) ~ 3e-14 by the next sample) and whose area, 2 zeta da'/omega^2 per
  // change, shifts the slip by ~(f_ground / f)^2: measured 9.3e-8 of the displacement here (below 1e-9 at 100 kHz,
  // the 1/omega^2 scaling). 1e-6 leaves a factor 10.
  const GroundMotion g = test_motion(0.01);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::one_way);
  const double rigid = slide_summary(g, block).residual_displacement_m;
  ASSERT_GT(std::abs(rigid), 0.01);
  const auto s = SupportOscillator::make(1e4, 0.05);
  const FlexibleSummary f = slide_flexible(g, s, block, FlexibleAnalysis::decoupled);
  EXPECT_NEAR(f.sliding.residual_displacement_m, rigid, 1e-6 * std::abs(rigid));
  EXPECT_NEAR(f.kmax, g.pga_m_s2() / kStandardGravity, 1e-9);
}

TEST(Flexible, StiffSupportDecoupledWithVerticalEqualsRigid) {
  // The vertical component reaches the body unfiltered; on a 10 kHz support the decoupled run is the rigid block's
  // with the same vertical record, to the same 1e-6 as without it (measured 9.5e-8). A strong vertical motion must
  // change the answer.
  const GroundMotion g = test_motion(0.01, 0.4);
  const GroundMotion v = test_motion(0.01, 0.3).time_scaled(0.5).trimmed(0.0, 4.0);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::one_way);
  const double rigid = slide_summary(g, block, &v).residual_displacement_m;
  const double plain = slide_summary(g, block).residual_displacement_m;
  ASSERT_GT(std::abs(rigid - plain), 1e-3 * std::abs(plain));
  const FlexibleSummary f = slide_flexible(g, SupportOscillator::make(1e4, 0.05), block, FlexibleAnalysis::decoupled, &v);
  EXPECT_NEAR(f.sliding.residual_displacement_m, rigid, 1e-6 * std::abs(rigid));
}

TEST(Flexible, StiffSupportCoupledApproachesRigid) {
  // Coupled, massless object, support at 1 kHz (omega dt = 63, sub-stepped): the support's absolute acceleration
  // lags the ground's by 2 zeta / omega = 16 us, a relative error 2 zeta W / omega ~ 1e-4 at the motion's 1.3 and
  // 3.7 Hz; the displacement, which integrates the excess over the yield level, moves by a few times that: 1e-3.
  const GroundMotion g = test_motion(0.01);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::one_way);
  const double rigid = slide_summary(g, block).residual_displacement_m;
  const FlexibleSummary f =
      slide_flexible(g, SupportOscillator::make(1000.0, 0.05, 0.0), block, FlexibleAnalysis::coupled);
  EXPECT_NEAR(f.sliding.residual_displacement_m, rigid, 1e-3 * std::abs(rigid));
}

TEST(Flexible, HistoryRunsGiveTheSameSummaryAndEndWhereItSays) {
  // slide_flexible_history is the same analysis with its history kept: the summary must be identical to the bit, the
  // history's last displacement is the residual, its peak |displacement| the summary's maximum (both analyses note
  // the maximum at the points they record), and the slip states change where slip episodes start.
  const GroundMotion g = test_motion(0.01);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::two_way);
  const auto shelf = SupportOscillator::make(2.0, 0.05, 0.1);
  const auto column = SlidingMassColumn::make(30.0, 400.0, 600.0, 0.05);
  for (const auto analysis : {FlexibleAnalysis::decoupled, FlexibleAnalysis::coupled}) {
    for (const bool on_shelf : {true, false}) {
      SCOPED_TRACE(testing::Message() << (analysis == FlexibleAnalysis::coupled ? "coupled" : "decoupled")
                                      << (on_shelf ? " shelf" : " column"));
      const FlexibleSummary plain =
          on_shelf ? slide_flexible(g, shelf, block, analysis)
                   : slide_flexible(g, column, 0.15, analysis, SlidingMode::two_way);
      const FlexibleResult full =
          on_shelf ? slide_flexible_history(g, shelf, block, analysis)
                   : slide_flexible_history(g, column, 0.15, analysis, SlidingMode::two_way);
      EXPECT_EQ(full.summary.sliding.residual_displacement_m, plain.sliding.residual_displacement_m);
      EXPECT_EQ(full.summary.sliding.max_abs_displacement_m, plain.sliding.max_abs_displacement_m);
      EXPECT_EQ(full.summary.sliding.slip_episodes, plain.sliding.slip_episodes);
      EXPECT_EQ(full.summary.kmax, plain.kmax);
      const FlexibleHistory& h = full.history;
      ASSERT_GT(h.sliding.time_s.size(), g.size() / 2);
      ASSERT_EQ(h.support_accel_m_s2.size(), h.sliding.time_s.size());
      EXPECT_EQ(h.sliding.displacement_m.back(), plain.sliding.residual_displacement_m);
      double peak = 0.0;
      double peak_support = 0.0;
      for (std::size_t i = 0; i < h.sliding.time_s.size(); ++i) {
        peak = std::max(peak, std::abs(h.sliding.displacement_m[i]));
        peak_support = std::max(peak_support, std::abs(h.support_accel_m_s2[i]));
        if (i > 0) {
          EXPECT_GE(h.sliding.time_s[i], h.sliding.time_s[i - 1]);
        }
      }
      EXPECT_EQ(peak, plain.sliding.max_abs_displacement_m);
      // Decoupled: the support's peak acceleration is k_max g, read on the same sub-stepped grid (the history adds
      // slip events, where the support's motion is read piecewise linear, never above its grid values): equal.
      // (Coupled: k_max is the decoupled response's peak, SLAMMER's definition; the slip changes the support's.)
      if (analysis == FlexibleAnalysis::decoupled) {
        EXPECT_NEAR(peak_support, plain.kmax * kStandardGravity, 1e-12 * plain.kmax * kStandardGravity);
      }
    }
  }
}

// ---- vertical input in the coupled analysis: normal force m (g + a_v) in the friction capacity -------------------

TEST(FlexibleVertical, ZeroVerticalEqualsNone) {
  // A vertical record of zeros runs the 9-state system (flexible.cpp) instead of the 7-state one: the same equations
  // with two more, zero, inputs. Only the round-off of the larger exponentials differs: 1e-12 relative.
  const GroundMotion g = test_motion(0.01);
  const GroundMotion zero = GroundMotion::uniform(std::vector<double>(g.size(), 0.0), 0.01);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::two_way);
  const auto shelf = SupportOscillator::make(2.0, 0.05, 0.2);
  const auto column = SlidingMassColumn::make(30.0, 400.0, 600.0, 0.05);
  const FlexibleSummary a = slide_flexible(g, shelf, block, FlexibleAnalysis::coupled);
  const FlexibleSummary b = slide_flexible(g, shelf, block, FlexibleAnalysis::coupled, &zero);
  ASSERT_GT(std::abs(a.sliding.residual_displacement_m), 1e-3);
  EXPECT_NEAR(b.sliding.residual_displacement_m, a.sliding.residual_displacement_m,
              1e-12 * std::abs(a.sliding.residual_displacement_m));
  EXPECT_NEAR(b.sliding.max_abs_displacement_m, a.sliding.max_abs_displacement_m, 1e-12 * a.sliding.max_abs_displacement_m);
  EXPECT_EQ(b.sliding.slip_episodes, a.sliding.slip_episodes);
  const FlexibleSummary c = slide_flexible(g, column, 0.15, FlexibleAnalysis::coupled, SlidingMode::one_way);
  const FlexibleSummary d =
      slide_flexible(g, column, 0.15, FlexibleAnalysis::coupled, SlidingMode::one_way, kStandardGravity, &zero);
  ASSERT_GT(std::abs(c.sliding.residual_displacement_m), 1e-3);
  EXPECT_NEAR(d.sliding.residual_displacement_m, c.sliding.residual_displacement_m,
              1e-12 * std::abs(c.sliding.residual_displacement_m));
  EXPECT_FALSE(d.sliding.contact_lost_time_s.has_value());
}

TEST(FlexibleVertical, ConstantVerticalScalesFrictionClosedForm) {
  // A constant a_v makes the capacity mu (g + a_v) = mu' g with mu' = mu (1 + a_v / g), in the body's equation and
  // in the friction force the body puts on the support (r sigma mu (g + a_v)): the coupled run with a_v and mu is the
  // run without vertical input and mu' -- the same closed-form identity as the rigid block's
  // (Sliding.ConstantVerticalScalesFrictionClosedForm). The vertical record lasts beyond the run-out (10 s more).
  // Tolerance: the 9-state exponentials' round-off against the 7-state ones, and events located to ~1e-15 s.
  const GroundMotion g = test_motion(0.01);
  for (const double av_g : {-0.25, 0.3}) {
    SCOPED_TRACE(av_g);
    const double av = av_g * kStandardGravity;
    const GroundMotion vertical = GroundMotion::uniform(std::vector<double>(g.size() + 1000, av), 0.01);
    const double mu = 0.15;
    const double mu_eff = mu * (1.0 + av_g);
    for (const auto mode : {SlidingMode::one_way, SlidingMode::two_way}) {
      const FlexibleSummary with_av = slide_flexible(g, SupportOscillator::make(2.0, 0.05, 0.2),
                                                     SlidingBlock::make(mu, std::nullopt, 0.0, mode),
                                                     FlexibleAnalysis::coupled, &vertical);
      const FlexibleSummary scaled = slide_flexible(g, SupportOscillator::make(2.0, 0.05, 0.2),
                                                    SlidingBlock::make(mu_eff, std::nullopt, 0.0, mode),
                                                    FlexibleAnalysis::coupled);
      ASSERT_GT(scaled.sliding.max_abs_displacement_m, 1e-3);
      EXPECT_NEAR(with_av.sliding.residual_displacement_m, scaled.sliding.residual_displacement_m,
                  1e-11 * scaled.sliding.max_abs_displacement_m);
      EXPECT_EQ(with_av.sliding.slip_episodes, scaled.sliding.slip_episodes);
      const auto column = SlidingMassColumn::make(30.0, 400.0, 600.0, 0.05);
      const FlexibleSummary col_av =
          slide_flexible(g, column, mu, FlexibleAnalysis::coupled, mode, kStandardGravity, &vertical);
      const FlexibleSummary col_scaled = slide_flexible(g, column, mu_eff, FlexibleAnalysis::coupled, mode);
      ASSERT_GT(col_scaled.sliding.max_abs_displacement_m, 1e-3);  // two-way residuals may nearly cancel
      EXPECT_NEAR(col_av.sliding.residual_displacement_m, col_scaled.sliding.residual_displacement_m,
                  1e-11 * col_scaled.sliding.max_abs_displacement_m);
      EXPECT_NEAR(col_av.sliding.max_abs_displacement_m, col_scaled.sliding.max_abs_displacement_m,
                  1e-11 * col_scaled.sliding.max_abs_displacement_m);
    }
  }
}

TEST(FlexibleVertical, StiffSupportCoupledWithVerticalApproachesRigid) {
  // A varying vertical record: on a 1 kHz support with a massless object the coupled run approaches the rigid block's
  // with the same vertical record, to the 1e-3 of StiffSupportCoupledApproachesRigid (the support's lag), and the
  // vertical record changes the answer by far more than that. The vertical record is on the horizontal's grid, so
  // reading it linearly between sub-steps is exact.
  const GroundMotion g = test_motion(0.01, 0.4);
  std::vector<double> av(g.size());
  for (std::size_t i = 0; i < av.size(); ++i) av[i] = 0.5 * kStandardGravity * std::sin(2.0 * kPi * 2.3 * 0.01 * static_cast<double>(i));
  const GroundMotion v = GroundMotion::uniform(std::move(av), 0.01);
  const SlidingBlock block = SlidingBlock::make(0.15, std::nullopt, 0.0, SlidingMode::one_way);
  const double rigid = slide_summary(g, block, &v).residual_displacement_m;
  const double plain = slide_summary(g, block).residual_displacement_m;
  ASSERT_GT(std::abs(rigid - plain), 1e-2 * std::abs(plain));
  const FlexibleSummary f =
      slide_flexible(g, SupportOscillator::make(1000.0, 0.05, 0.0), block, FlexibleAnalysis::coupled, &v);
  EXPECT_NEAR(f.sliding.residual_displacement_m, rigid, 1e-3 * std::abs(rigid));
}

TEST(FlexibleVertical, ContactLossIsReported) {
  // a_v = -1.2 g from t = 1 s: the normal force g + a_v crosses 0 where a_v = -g, located linearly within the
  // sub-step: the vertical record ramps from 0 at t = 1 s to -1.2 g at 1.01 s, so n = 0 at 1 + 0.01 / 1.2 s.
  const GroundMotion g = test_motion(0.01);
  std::vector<double> av(g.size(), 0.0);
  for (std::size_t i = 101; i < av.size(); ++i) av[i] = -1.2 * kStandardGravity;
  const GroundMotion vertical = GroundMotion::uniform(std::move(av), 0.01);
  const FlexibleSummary f = slide_flexible(g, SupportOscillator::make(2.0, 0.05, 0.2), SlidingBlock::make(0.15),
                                           FlexibleAnalysis::coupled, &vertical);
  ASSERT_TRUE(f.sliding.contact_lost_time_s.has_value());
  // The sub-step grid (omega h <= 0.5 on 2 Hz: one sub-step of 0.01 s) puts the ramp inside one sub-step.
  EXPECT_NEAR(*f.sliding.contact_lost_time_s, 1.0 + 0.01 / 1.2, 1e-12);
}

TEST(Flexible, MaxPeakAmplificationIsTheImpulseResponsesL1Norm) {
  // Against an independent midpoint quadrature of |h|, h = exp(-zeta t)(2 zeta cos(wd t) + (1 - 2 zeta^2)/wd
  // sin(wd t)) (omega = 1), to t = 40 / zeta (exp(-40) left): step 1e-4 puts the quadrature within 1e-6 relative.
  for (const double zeta : {0.05, 0.2, 0.6}) {
    const double wd = std::sqrt(1.0 - zeta * zeta);
    double sum = 0.0;
    const double step = 1e-4;
    for (double t = 0.5 * step; t < 40.0 / zeta; t += step) {
      sum += std::abs(std::exp(-zeta * t) * (2.0 * zeta * std::cos(wd * t) + (1.0 - 2.0 * zeta * zeta) / wd * std::sin(wd * t))) * step;
    }
    EXPECT_NEAR(max_peak_amplification(zeta), sum, 1e-5 * sum) << zeta;
    // Above the harmonic steady state's peak transmissibility sqrt(1 + 4 zeta^2) / (2 zeta) (at resonance, ~exact
    // for small zeta) -- a bound over every motion is at least the value for one.
    EXPECT_GT(max_peak_amplification(zeta), std::sqrt(1.0 + 4.0 * zeta * zeta) / (2.0 * zeta));
  }
  EXPECT_NEAR(max_peak_amplification(0.05), 12.8016, 1e-4);  // the figure flexible.hpp quotes
  EXPECT_TRUE(std::isinf(max_peak_amplification(0.0)));
  // The bound is reached: a 2 Hz, 5 % support under the motion sign(h(T - t)) (unit amplitude; T = 10 s, h decayed
  // to exp(-6.3)) peaks at the end at int_0^T |h| = the bound up to the tail exp(-6.3) ~ 0.2 % and the
  // interpolation of the sign changes on the 0.5 ms grid (~0.5 %): within 1 %.
  const double f = 2.0;
  const double zeta = 0.05;
  const double omega = 2.0 * kPi * f;
  const double wd = omega * std::sqrt(1.0 - zeta * zeta);
  const double dt = 5e-4;
  const double T = 10.0;
  const auto n = static_cast<std::size_t>(T / dt) + 1;
  std::vector<double> a(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double tau = T - static_cast<double>(i) * dt;  // time before the end
    const double h = std::exp(-zeta * omega * tau) *
                     (2.0 * zeta * omega * std::cos(wd * tau) + (omega * omega - 2.0 * zeta * zeta * omega * omega) / wd * std::sin(wd * tau));
    a[i] = h >= 0.0 ? 1.0 : -1.0;
  }
  const GroundMotion g = GroundMotion::uniform(std::move(a), dt);
  const GroundMotion s = support_motion(g, SupportOscillator::make(f, zeta));
  EXPECT_NEAR(s.pga_m_s2() / g.pga_m_s2(), max_peak_amplification(zeta), 0.01 * max_peak_amplification(zeta));
}

TEST(Flexible, HarmonicSteadyStateAmplification) {
  // a_g = A sin(W t) on a 4 Hz, 5 % support driven at 3 Hz: after the transient (exp(-zeta omega t) < 1e-9 after
  // 20 s) the absolute acceleration's amplitude is A sqrt((1 + (2 zeta b)^2) / ((1 - b^2)^2 + (2 zeta b)^2)),
  // b = W / omega (Chopra, Dynamics of Structures, eq 3.6.6). The record is the sine sampled at 1 ms and read as
  // piecewise linear, and the peak is read at the samples: both O((W dt)^2) ~ 4e-4, so the tolerance is 1e-3.
  const double dt = 0.001;
  const double f_in = 3.0;
  const double amp = 1.0;
  std::vector<double> a(static_cast<std::size_t>(30.0 / dt) + 1);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = amp * std::sin(2 * kPi * f_in * static_cast<double>(i) * dt);
  const GroundMotion g = GroundMotion::uniform(a, dt);
  const auto s = SupportOscillator::make(4.0, 0.05);
  const auto hea = support_acceleration_m_s2(g, modal_properties(s));
  double peak = 0.0;
  for (std::size_t i = static_cast<std::size_t>(20.0 / dt); i < hea.size(); ++i) peak = std::max(peak, std::abs(hea[i]));
  const double b = f_in / 4.0;
  const double z = 0.05;
  const double tr = std::sqrt((1 + std::pow(2 * z * b, 2)) / (std::pow(1 - b * b, 2) + std::pow(2 * z * b, 2)));
  EXPECT_NEAR(peak / amp, tr, 1e-3 * tr);
}

TEST(Flexible, SupportMotionIsWhatTheDecoupledAnalysisSlidesOn) {
  // support_motion is the filter surveys and sweeps can apply: the rigid solver on it must give the decoupled
  // analysis' number exactly (same samples, same solver), and its samples at the record's times must be the
  // sample-exact support acceleration (the sub-steps of a 2.5 Hz support at dt = 0.02 s are 4: every 4th point).
  const GroundMotion g = test_motion(0.02);
  const auto s = SupportOscillator::make(2.5, 0.05);
  const SlidingBlock block = SlidingBlock::make(0.1);
  const GroundMotion m = support_motion(g, s);
  EXPECT_EQ(slide_summary(m, block).residual_displacement_m,
            slide_flexible(g, s, block, FlexibleAnalysis::decoupled).sliding.residual_displacement_m);
  const auto at_samples = support_acceleration_m_s2(g, modal_properties(s));
  ASSERT_EQ(m.size(), 4 * (g.size() - 1) + 1);
  for (std::size_t i = 0; i < g.size(); i += 97) EXPECT_NEAR(m.accel_m_s2()[4 * i], at_samples[i], 1e-12) << i;
}

TEST(Flexible, ResponseIsCausalWhateverTheRecordLength) {
  // The response at sample k depends on a_0..a_k only, so a record cut after n samples must give the first n points
  // of the full record's response. The recurrence runs in chunks of segments whose lengths depend on n (16 segments of
  // up to 128 points, a short tail alone; the segments' chains advance 2 or 4 steps at a time with the rest one by
  // one), so every n below splits the record differently: lengths around the segment counts and the chunk size
  // (2048), segments of 3 to 8 points, and the short records that take the tail path only. Tolerance 1e-12 of the
  // peak: the segments' sums differ only in round-off (~1e-16 / (omega h)^2, omega h = 0.094 here).
  const GroundMotion full = test_motion(0.005, 0.4, 12.0);  // 2401 samples
  for (const auto& mode : {modal_properties(SupportOscillator::make(3.0, 0.02)),
                           modal_properties(SlidingMassColumn::make(40.0, 480.0, 700.0, 0.1), full)}) {
    const auto ref = support_acceleration_m_s2(full, mode);
    double peak = 0.0;
    for (const double v : ref) peak = std::max(peak, std::abs(v));
    std::vector<std::size_t> lengths;
    for (std::size_t n = 2; n <= 40; ++n) lengths.push_back(n);
    for (std::size_t n = 2 + 16 * 3; n <= 2 + 16 * 8 + 15; ++n) lengths.push_back(n);
    for (std::size_t n = 2040; n <= 2070; ++n) lengths.push_back(n);
    lengths.push_back(2400);
    for (const std::size_t n : lengths) {
      const std::vector<double> head(full.accel_m_s2().begin(), full.accel_m_s2().begin() + static_cast<long>(n));
      const auto cut = support_acceleration_m_s2(GroundMotion::uniform(head, full.dt_s()), mode);
      ASSERT_EQ(cut.size(), n);
      for (std::size_t i = 0; i < n; ++i) ASSERT_NEAR(cut[i], ref[i], 1e-12 * peak) << "n " << n << " at " << i;
    }
  }
}

TEST(Flexible, CoupledIsExactUnderLinearUpSampling) {
  // The coupled solver integrates each phase exactly and locates slip events by root finding, so up-sampling the
  // piecewise-linear record (the same function) changes only round-off and the event search (50-bit tolerance):
  // 1e-9 relative.
  const GroundMotion g = test_motion(0.01, 0.5);
  const SlidingMassColumn col = SlidingMassColumn::make(30.0, 300.0, 600.0, 0.05);
  for (const SlidingMode mode : {SlidingMode::one_way, SlidingMode::two_way}) {
    const double coarse = slide_flexible(g, col, 0.1, FlexibleAnalysis::coupled, mode).sliding.residual_displacement_m;
    const double fine =
        slide_flexible(g.resampled(0.0025), col, 0.1, FlexibleAnalysis::coupled, mode).sliding.residual_displacement_m;
    ASSERT_GT(std::abs(coarse), 1e-3);
    EXPECT_NEAR(fine, coarse, 1e-9 * std::abs(coarse));
  }
}

TEST(Flexible, DecoupledConvergesToCoupledWithMasslessObject) {
  // With mass ratio 0 the coupled shelf is the decoupled one computed exactly; the decoupled analysis reads the
  // support acceleration as piecewise linear between points h apart (h <= 0.1 / omega), an O(h^2) error. At
  // dt <= 5 ms this 2.5 Hz support needs no sub-step (h = dt): halving dt must cut the gap by about 4 (we ask > 3).
  // At the 20 ms record itself (4 sub-steps, h = 5 ms) the gap must be under 0.2 % (the (omega h)^2 / 8 = 0.08 %
  // interpolation bound on the support's part of the demand, with margin for its effect on the slip).
  const GroundMotion g = test_motion(0.02);
  const SlidingBlock block = SlidingBlock::make(0.12, 0.12, 0.0, SlidingMode::one_way);
  const auto s = SupportOscillator::make(2.5, 0.05, 0.0);
  const double exact = slide_flexible(g, s, block, FlexibleAnalysis::coupled).sliding.residual_displacement_m;
  ASSERT_GT(std::abs(exact), 0.01);
  const auto gap = [&](double dt) {
    const GroundMotion r = dt == 0.02 ? g : g.resampled(dt);
    EXPECT_NEAR(slide_flexible(r, s, block, FlexibleAnalysis::coupled).sliding.residual_displacement_m, exact,
                1e-9 * std::abs(exact));
    return std::abs(slide_flexible(r, s, block, FlexibleAnalysis::decoupled).sliding.residual_displacement_m - exact);
  };
  EXPECT_LT(gap(0.02), 2e-3 * std::abs(exact));
  std::vector<double> gaps;
  for (const double dt : {0.005, 0.0025, 0.00125}) gaps.push_back(gap(dt));
  for (std::size_t i = 1; i < gaps.size(); ++i) EXPECT_GT(gaps[i - 1] / gaps[i], 3.0) << i;
}

TEST(Flexible, TwoWayIsOddInThePolarity) {
  // Two-way sliding on a symmetric support is odd in the input: inverting the record negates the displacement. Both
  // runs do the same arithmetic with flipped signs, so the match is to round-off (1e-12 relative).
  const GroundMotion g = test_motion(0.01, 0.6);
  const SlidingBlock block = SlidingBlock::make(0.1);
  const auto s = SupportOscillator::make(3.0, 0.05, 0.3);
  const auto col = SlidingMassColumn::make(20.0, 300.0, 600.0, 0.05);
  for (const auto analysis : {FlexibleAnalysis::decoupled, FlexibleAnalysis::coupled}) {
    const double up = slide_flexible(g, s, block, analysis).sliding.residual_displacement_m;
    const double down = slide_flexible(g.inverted(), s, block, analysis).sliding.residual_displacement_m;
    ASSERT_GT(std::abs(up), 1e-3);
    EXPECT_NEAR(down, -up, 1e-12 * std::abs(up));
    const double c_up = slide_flexible(g, col, 0.1, analysis, SlidingMode::two_way).sliding.residual_displacement_m;
    const double c_down =
        slide_flexible(g.inverted(), col, 0.1, analysis, SlidingMode::two_way).sliding.residual_displacement_m;
    EXPECT_NEAR(c_down, -c_up, 1e-12 * std::abs(c_up));
  }
}

TEST(Flexible, MassRatioToZeroCoupledEqualsDecoupledLimit) {
  // The coupled shelf is continuous in the mass ratio: r = 1e-6 differs from r = 0 by O(r) (1e-5 relative bound).
  const GroundMotion g = test_motion(0.005);
  const SlidingBlock block = SlidingBlock::make(0.12, std::nullopt, 0.0, SlidingMode::one_way);
  const double r0 = slide_flexible(g, SupportOscillator::make(3.0, 0.05, 0.0), block, FlexibleAnalysis::coupled)
                        .sliding.residual_displacement_m;
  const double r1 = slide_flexible(g, SupportOscillator::make(3.0, 0.05, 1e-6), block, FlexibleAnalysis::coupled)
                        .sliding.residual_displacement_m;
  const double r2 = slide_flexible(g, SupportOscillator::make(3.0, 0.05, 0.5), block, FlexibleAnalysis::coupled)
                        .sliding.residual_displacement_m;
  EXPECT_NEAR(r1, r0, 1e-5 * std::abs(r0));
  EXPECT_GT(std::abs(r2 - r0), 1e-3 * std::abs(r0));  // a heavy object does change the answer
}

TEST(Flexible, ColumnModeAndImpedanceDamping) {
  // omega = pi Vs / 2H; SLAMMER's impedance damping 0.55016 (Vb/Vs)^-0.9904 capped at 0.2.
  const GroundMotion g = test_motion(0.01);
  const auto m = modal_properties(SlidingMassColumn::make(50.0, 600.0, 600.0, -0.05), g);
  EXPECT_DOUBLE_EQ(m.omega_rad_s, kPi * 600.0 / 100.0);
  EXPECT_DOUBLE_EQ(m.damping_ratio, 0.15);
  EXPECT_NEAR(SlidingMassColumn::impedance_damping(1200.0, 400.0), 0.55016 * std::pow(3.0, -0.9904), 1e-15);
  EXPECT_NEAR(m.participation, 4.0 / kPi, 1e-15);
  EXPECT_NEAR(m.mass_fraction, 2.0 / kPi, 1e-15);
}

TEST(Flexible, EquivalentLinearSoftensAndDamps) {
  // A strong motion strains the column: the converged V_s is below V_s0 and the damping above the small-strain 1 %
  // plus impedance damping; a tiny reference strain softens more than a large one.
  const GroundMotion g = test_motion(0.01, 0.5);
  const auto soft = modal_properties(SlidingMassColumn::make(50.0, 400.0, 800.0, 0.05, 0.0001), g);
  const auto stiff = modal_properties(SlidingMassColumn::make(50.0, 400.0, 800.0, 0.05, 0.01), g);
  EXPECT_LT(soft.vs_m_s, stiff.vs_m_s);
  EXPECT_LT(stiff.vs_m_s, 400.0);
  EXPECT_GT(soft.damping_ratio, 0.01 + SlidingMassColumn::impedance_damping(800.0, soft.vs_m_s));
  EXPECT_GE(soft.iterations, 2);
}

TEST(Flexible, RejectsBadParameters) {
  const auto msg = [](auto&& f) {
    try {
      f();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    ADD_FAILURE() << "no InputError";
    return std::string();
  };
  EXPECT_NE(msg([] { (void)SupportOscillator::make(0.0, 0.05); }).find("got 0 Hz"), std::string::npos);
  EXPECT_NE(msg([] { (void)SupportOscillator::make(4.0, 1.0); }).find("[0, 1)"), std::string::npos);
  // Issue 31: above 1e4 Hz (from about 2e154 Hz, omega^2 overflowed and expm<4> never returned) the support is
  // refused, naming the field the front ends map to --support-freq, support.freq_hz, support_freq; 1e4 Hz itself runs.
  for (const double f : {1.0000001e4, 2e154, 1e200, 1e300}) {
    try {
      (void)SupportOscillator::make(f, 0.05);
      ADD_FAILURE() << f << " Hz accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.where().field, "support_freq");
      EXPECT_NE(std::string(e.what()).find("above 10000 Hz"), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(SupportOscillator::make(1e4, 0.05).freq_hz, 1e4);
  // The column's first mode V_s / 4H likewise (600 m/s over 1.49 cm: 10067 Hz; over 2 cm: 7500 Hz); 1e-200 m hung.
  EXPECT_NE(msg([] { (void)SlidingMassColumn::make(1e-200, 600.0, 600.0, 0.05); }).find("above 10000 Hz"),
            std::string::npos);
  EXPECT_NE(msg([] { (void)SlidingMassColumn::make(0.0149, 600.0, 600.0, 0.05); }).find("V_s / 4H"), std::string::npos);
  EXPECT_EQ(SlidingMassColumn::make(0.02, 600.0, 600.0, 0.05).height_m, 0.02);
  EXPECT_NE(msg([] { (void)SupportOscillator::make(4.0, 0.05, -1.0); }).find("mass ratio"), std::string::npos);
  EXPECT_NE(msg([] { (void)SlidingMassColumn::make(-1.0, 600.0, 600.0, 0.05); }).find("height"), std::string::npos);
  EXPECT_NE(msg([] { (void)SlidingMassColumn::make(10.0, 600.0, 600.0, -0.3); }).find("[0, 1)"), std::string::npos);
  const GroundMotion g = test_motion(0.01);
  EXPECT_NE(msg([&] {
              (void)slide_flexible(g, SlidingMassColumn::make(10.0, 600.0, 600.0, 0.05), 0.0, FlexibleAnalysis::coupled);
            }).find("yield coefficient"),
            std::string::npos);
  EXPECT_NE(msg([&] {
              (void)slide_flexible(g, SupportOscillator::make(4.0, 0.05), SlidingBlock::make(0.3, 0.2),
                                   FlexibleAnalysis::coupled);
            }).find("mu_kinetic"),
            std::string::npos);
}

TEST(Flexible, SupportMotionBeyondTheAccelerationLimitIsRefused) {
  // The decoupled analysis builds the support's motion from the response's peak instead of checking every sample
  // (GroundMotionFactory); a peak beyond GroundMotionLimits::max_abs_accel_m_s2 must still be refused, with the
  // message GroundMotion::uniform gives. A 4 Hz, 2 % shelf at resonance under a 5e5 m/s^2 sine (an idealised motion,
  // within the limit) amplifies it ~25x at steady state; 2 s (8 cycles) bring it past 2x the limit.
  const double dt = 0.001;
  std::vector<double> a(2001);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] = 5e5 * std::sin(2.0 * kPi * 4.0 * dt * static_cast<double>(i));
  const GroundMotion g = GroundMotion::uniform(std::move(a), dt);
  const auto support = SupportOscillator::make(4.0, 0.02);
  const auto block = SlidingBlock::make(0.2, 0.2);
  try {
    (void)slide_flexible(g, support, block, FlexibleAnalysis::decoupled);
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("beyond the limit of 1e+06 m/s2 of a ground motion"), std::string::npos)
        << e.what();
  }
  // Well within the limit (the same shelf, 5e3 m/s^2: peak ~1e5) the motion is built, its peak the analysis' k_max
  // (k_max = peak / g: two roundings, hence EXPECT_DOUBLE_EQ's 4 ulp).
  std::vector<double> b(2001);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = 5e3 * std::sin(2.0 * kPi * 4.0 * dt * static_cast<double>(i));
  const GroundMotion small = GroundMotion::uniform(std::move(b), dt);
  const GroundMotion m = support_motion(small, support);
  EXPECT_DOUBLE_EQ(m.pga_m_s2(),
                   slide_flexible(small, support, block, FlexibleAnalysis::decoupled).kmax * kStandardGravity);
}

}  // namespace
}  // namespace topple
