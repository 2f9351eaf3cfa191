#pragma once
// Observed objects for the inversion's tests (test_inversion.cpp, test_prior.cpp, test_inversion_3c.cpp,
// test_inversion_coupled.cpp), and the synthetic calibration they share.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "topple/inversion/inversion.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/survey/survey.hpp"
#include "topple/motion/synthesis.hpp"
#include "regional_scenario.hpp"

namespace topple::testing {

/// A block of full width w and height h (m) with friction mu (a value or a range) and an observed outcome.
inline ObservedObject block(const std::string& id, double w, double h, Interval mu, Outcome outcome) {
  ObservedObject o;
  o.id = id;
  o.body = RockingBody::block(w, h);
  o.width_m = w;
  o.height_m = h;
  o.mu = mu;
  o.outcome = outcome;
  return o;
}

/// The small grid of the recovery tests: 14 PGA values from 0.05 to 2 g x 8 frequencies from 0.5 to 12 Hz, 10 s
/// motions, `motions` per cell.
inline InversionSettings small_grid(int motions = 10) {
  InversionSettings st = small_grid(0.05, 14, 0.5, 12.0, 8, motions);  // regional_scenario.hpp
  st.duration_s = 10.0;
  return st;
}

/// A recovery test's true motion (PGA in g, frequency in Hz), built as the family's members are (inversion.hpp):
/// synthesised with `seed`, then time-scaled so that its measured predominant frequency is `freq_hz`.
inline GroundMotion true_motion(const InversionSettings& st, double pga_g, double freq_hz, std::uint64_t seed) {
  SynthesisSpec spec;
  spec.pga_m_s2 = pga_g * st.g_m_s2;
  spec.predominant_frequency_hz = freq_hz;
  spec.duration_s = std::max(st.duration_s, 8.0 / freq_hz);
  spec.dt_s = std::min(0.01, 1.0 / (20.0 * freq_hz));
  spec.seed = seed;
  const GroundMotion raw = synthesize(spec);
  return raw.time_scaled(predominant_frequency_hz(raw) / freq_hz);
}

/// What a field engineer saw of a rocking witness (overturned or not) or a sliding one (slid visibly or not) under
/// `truth`, from the solvers themselves at their default tolerances and run-out (tighter than the inversion's rel_tol
/// 1e-6 and 20 s run-out), with Housner's restitution and the true friction `mu`.
inline ObservedObject observe_uncoupled(ObservedObject obj, double mu, const GroundMotion& truth,
                                        const InversionSettings& st) {
  if (obj.outcome == Outcome::overturned || obj.outcome == Outcome::not_overturned) {
    RockingOptions ro;
    ro.g_m_s2 = st.g_m_s2;
    const RockingSummary s = rock_summary(truth, obj.body, ro);
    obj.outcome = s.overturned ? Outcome::overturned : Outcome::not_overturned;
  } else {
    const SlidingSummary s = slide_summary(truth, SlidingBlock::make(mu, mu, 0.0, SlidingMode::two_way, st.g_m_s2));
    obj.outcome = s.max_abs_displacement_m >= kVisibleSlipM ? Outcome::slid : Outcome::not_slid;
  }
  return obj;
}

struct RecoveryCoverage {
  int in95 = 0;  ///< trials whose truth lies in the 95 % region
  int in68 = 0;  ///< ... in the 68 % region
};

/// The recovery loop (test_inversion.cpp, test_inversion_coupled.cpp): `trials` truths drawn log-uniformly in
/// [0.12, 1.2] g x [0.8, 8] Hz by PortableRandom(truth_seed), each synthesised by true_motion with the seed
/// 0xC0FFEE00 + t (a seed the inversion never uses); every object's true friction drawn uniformly in its range by
/// PortableRandom(friction_seed), in order; `observe(object, mu, truth)` gives what was seen (from the solvers, never
/// from observation_match, which is under test); then invert_site, and whether the truth lies in the 95 % and 68 %
/// credible regions. Prints each trial (with the observed outcomes) and the coverage.
template <class Observe>
RecoveryCoverage recovery_coverage(const InversionSettings& st, const std::vector<ObservedObject>& objects, int trials,
                                   std::uint64_t truth_seed, std::uint64_t friction_seed, Observe observe) {
  PortableRandom rng(truth_seed);
  PortableRandom params(friction_seed);
  RecoveryCoverage c;
  for (int t = 0; t < trials; ++t) {
    const double pga = std::exp(std::log(0.12) + (std::log(1.2) - std::log(0.12)) * rng.uniform());
    const double freq = std::exp(std::log(0.8) + (std::log(8.0) - std::log(0.8)) * rng.uniform());
    const GroundMotion truth = true_motion(st, pga, freq, 0xC0FFEE00ULL + static_cast<std::uint64_t>(t));
    const double true_freq = predominant_frequency_hz(truth);
    Site site;
    site.name = fmt::format("trial {}", t);
    std::string seen;
    for (const ObservedObject& proto : objects) {
      const double mu = proto.mu.low + (proto.mu.high - proto.mu.low) * params.uniform();
      site.objects.push_back(observe(proto, mu, truth));
      seen += fmt::format(" {}", outcome_name(site.objects.back().outcome));
    }
    // The recovery scores the estimates: the ranking of what to look for next (evidence.hpp) is not run.
    const InversionResult r = invert_site(site, st, InversionOptions{.next_objects = false});
    const bool c95 = in_credible_region(r, pga, true_freq, 0.95);
    const bool c68 = in_credible_region(r, pga, true_freq, 0.68);
    c.in95 += c95;
    c.in68 += c68;
    fmt::print("trial {:2}: truth {:.3f} g {:.2f} Hz; median {:.3f} g {:.2f} Hz; in95 {} in68 {};{}\n", t, pga,
               true_freq, r.pga_estimate_g.median, r.freq_estimate_hz.median, c95, c68, seen);
  }
  fmt::print("coverage: 95 % region {}/{}, 68 % region {}/{}\n", c.in95, trials, c.in68, trials);
  return c;
}

/// The witnesses of the synthetic calibration (test_inversion.cpp, RecoversKnownShakingWithCalibratedIntervals;
/// test_prior.cpp, under other priors and families): four blocks seen overturned (friction 0.5-0.7) and three seen
/// slid, of low, middling and high friction.
inline std::vector<ObservedObject> calibration_objects() {
  return {block("slender", 0.06, 0.40, {0.5, 0.7}, Outcome::overturned),
          block("medium", 0.10, 0.30, {0.5, 0.7}, Outcome::overturned),
          block("stocky", 0.15, 0.25, {0.5, 0.7}, Outcome::overturned),
          block("tall-box", 0.25, 1.00, {0.5, 0.7}, Outcome::overturned),
          block("pan", 0.2, 0.1, {0.15, 0.25}, Outcome::slid),
          block("crate", 0.3, 0.3, {0.4, 0.6}, Outcome::slid),
          block("bin", 0.3, 0.3, {0.7, 0.9}, Outcome::slid)};
}

/// The synthetic calibration under settings `st`: recovery_coverage of calibration_objects over `trials` truths
/// drawn with seed 2026, each object's friction drawn with 777, what was seen from the uncoupled solvers
/// (observe_uncoupled, never observation_match, which is under test).
inline RecoveryCoverage synthetic_calibration(const InversionSettings& st, int trials) {
  return recovery_coverage(st, calibration_objects(), trials, 2026, 777,
                           [&st](const ObservedObject& o, double mu, const GroundMotion& truth) {
                             return observe_uncoupled(o, mu, truth, st);
                           });
}

}  // namespace topple::testing
