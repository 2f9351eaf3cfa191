// Rocking throughput: record samples per second per core (items_per_second) for one body on a 20,000-sample
// record, adaptive Dormand-Prince at rel_tol 1e-8 (the default). The record is the first 20,000 samples
// (dt = 0.005 s, 100 s) of Kocaeli 1999 ATS-090 from ../shared/records/slammer (PGA 0.185 g), the record of
// bench_sliding; without ../shared, a seeded synthetic record of the same length and PGA.
//
// Cases (benchmark arguments: block width in cm, slenderness a/h in percent). None falls, so every run covers the
// whole record:
//   100 cm, a/h 0.15: rocks through the strong motion, ~270 impacts (the typical case: rest phases cost a compare);
//   100 cm, a/h 0.10: rocks for almost the whole record, ~650 impacts (the worst case: one step per sample);
//   100 cm, a/h 0.50: never lifts off (uplift level 0.5 g > PGA): what a sample at rest costs, the floor below the
//   two (docs/performance.md: why the worst/typical ratio is set by the fraction of samples spent rocking).
// Run:  build/release/bench/bench_rocking  (figures in docs/performance.md)
#include <cmath>
#include <filesystem>
#include <vector>

#include <benchmark/benchmark.h>

#include "kocaeli_record.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/threshold_search.hpp"

namespace {

using topple::GroundMotion;

const GroundMotion& record() { return topple::bench::kocaeli_20000(); }

topple::RockingBody body_from(const benchmark::State& state) {
  const double width = static_cast<double>(state.range(0)) / 100.0;
  const double slenderness = static_cast<double>(state.range(1)) / 100.0;
  return topple::RockingBody::block(width, width / slenderness);
}

void counters(benchmark::State& state, const topple::RockingSummary& s, std::size_t samples) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * samples));
  state.counters["impacts"] = static_cast<double>(s.impacts);
  state.counters["max_theta_over_alpha"] = s.max_rotation_over_alpha;
  state.counters["steps_per_sample"] = static_cast<double>(s.steps) / static_cast<double>(samples);
  state.counters["overturned"] = s.overturned ? 1.0 : 0.0;
}

/// Fraction of the record's samples at which the body is rocking (from one untimed run with a history): a sample at
/// rest costs a comparison, a sample spent rocking at least an integrator step, so this fraction sets the ratio of
/// the cases' throughputs.
double rocking_fraction(const GroundMotion& rec, const topple::RockingBody& body,
                        const topple::RockingOptions& options) {
  const topple::RockingHistory h = topple::rock(rec, body, options).history;
  std::size_t rocking = 0;
  std::size_t row = 0;
  for (std::size_t i = 0; i < rec.size(); ++i) {
    // The last history row at or before the sample instant gives the state there.
    while (row + 1 < h.time_s.size() && h.time_s[row + 1] <= rec.time_s(i)) ++row;
    if (h.state[row] != topple::RockingState::rest) ++rocking;
  }
  return static_cast<double>(rocking) / static_cast<double>(rec.size());
}

void BM_Rocking(benchmark::State& state) {
  const GroundMotion& rec = record();
  const auto body = body_from(state);
  const topple::RockingOptions options;  // adaptive, rel_tol 1e-8, Housner's e
  topple::RockingSummary s;
  for (auto _ : state) {
    s = topple::rock_summary(rec, body, options);
    benchmark::DoNotOptimize(s);
  }
  counters(state, s, rec.size());
  state.counters["rocking_fraction"] = rocking_fraction(rec, body, options);
}
BENCHMARK(BM_Rocking)->Args({100, 15})->Args({100, 10})->Args({100, 50})->Unit(benchmark::kMillisecond);

void BM_RockingWithHistory(benchmark::State& state) {
  const GroundMotion& rec = record();
  const auto body = body_from(state);
  const topple::RockingOptions options;
  topple::RockingResult r;
  for (auto _ : state) {
    r = topple::rock(rec, body, options);
    benchmark::DoNotOptimize(r);
  }
  counters(state, r.summary, rec.size());
}
BENCHMARK(BM_RockingWithHistory)->Args({100, 15})->Unit(benchmark::kMillisecond);

void BM_Rigid3DEdge(benchmark::State& state) {
  // The three-dimensional engine (rigid3d.hpp) on the same body with a depth of 0.5 m under the same record along x:
  // it rocks about its edges parallel to y exactly as BM_Rocking's block (tests/solvers/test_rigid3d.cpp), so the
  // ratio of the two figures is the cost of the general engine per sample (issue 29 asks within 5x). Default
  // tolerances, as BM_Rocking.
  const GroundMotion& rec = record();
  const double width = static_cast<double>(state.range(0)) / 100.0;
  const double slenderness = static_cast<double>(state.range(1)) / 100.0;
  const auto body = topple::RigidBody3D::box(width, 0.5, width / slenderness);
  const topple::Rigid3DOptions options;
  topple::Rigid3DSummary s;
  for (auto _ : state) {
    s = topple::rock3d(rec, nullptr, nullptr, body, options).summary;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size()));
  state.counters["impacts"] = static_cast<double>(s.impacts);
  state.counters["max_tilt_over_limit"] = s.max_tilt_over_limit;
  state.counters["steps_per_sample"] = static_cast<double>(s.steps) / static_cast<double>(rec.size());
}
BENCHMARK(BM_Rigid3DEdge)->Args({100, 15})->Args({100, 10})->Args({100, 50})->Unit(benchmark::kMillisecond);

void BM_Rigid3DCorner(benchmark::State& state) {
  // The three-dimensional engine pivoting on the corners of a square box (1 m base, height 1 m / (a/h)) under the
  // record split equally along x and y (its diagonal): the pivot mode (7 components, Euler's equations) for every
  // sample the body moves; the same motion as the planar engine on the diagonal section (test_rigid3d.cpp).
  const GroundMotion& rec = record();
  const double slenderness = static_cast<double>(state.range(1)) / 100.0;
  const double width = static_cast<double>(state.range(0)) / 100.0;
  const auto body = topple::RigidBody3D::box(width, width, width / slenderness);
  std::vector<double> a(rec.accel_m_s2().begin(), rec.accel_m_s2().end());
  for (double& x : a) x /= std::sqrt(2.0);  // each axis carries the record / sqrt(2): the record along the diagonal
  const GroundMotion half = GroundMotion::uniform(a, rec.dt_s(), rec.start_time_s());
  const topple::Rigid3DOptions options;
  topple::Rigid3DSummary s;
  for (auto _ : state) {
    s = topple::rock3d(half, &half, nullptr, body, options).summary;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size()));
  state.counters["impacts"] = static_cast<double>(s.impacts);
  state.counters["max_tilt_over_limit"] = s.max_tilt_over_limit;
  state.counters["steps_per_sample"] = static_cast<double>(s.steps) / static_cast<double>(rec.size());
}
BENCHMARK(BM_Rigid3DCorner)->Args({100, 10})->Unit(benchmark::kMillisecond);

void BM_CylinderPlanar(benchmark::State& state) {
  // A solid cylinder (diameter in cm, a/h = d/H in percent) in the planar engine under the record: the reference for
  // BM_Cylinder3DWobble (issue 29 asks the wobbling cylinder within 10x of the planar engine per sample).
  const GroundMotion& rec = record();
  const double d = static_cast<double>(state.range(0)) / 100.0;
  const double slenderness = static_cast<double>(state.range(1)) / 100.0;
  const auto body = topple::RockingBody::cylinder(d, d / slenderness);
  const topple::RockingOptions options;
  topple::RockingSummary s;
  for (auto _ : state) {
    s = topple::rock_summary(rec, body, options);
    benchmark::DoNotOptimize(s);
  }
  counters(state, s, rec.size());
  // the time in motion (the record and the run-out) over the record's duration, as BM_Cylinder3DWobble's rim_fraction,
  // and the rate of such samples (moving_samples_per_second): the cost per rocking sample is its inverse
  const topple::RockingHistory h = topple::rock(rec, body, options).history;
  double moving_s = 0.0;
  for (std::size_t i = 0; i + 1 < h.time_s.size(); ++i) {
    if (h.state[i] != topple::RockingState::rest) moving_s += h.time_s[i + 1] - h.time_s[i];
  }
  const double duration = rec.end_time_s() - rec.start_time_s();
  state.counters["moving_fraction"] = moving_s / duration;
  state.counters["moving_samples_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * moving_s / rec.dt_s(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_CylinderPlanar)->Args({100, 15})->Args({100, 10})->Args({100, 50})->Unit(benchmark::kMillisecond);

void BM_Cylinder3DWobble(benchmark::State& state) {
  // The same cylinder in the three-dimensional rim engine (rigid3d_disc.hpp) under the record along x and, along y,
  // the record times the third argument (percent) delayed by 1 s: two components, so it wobbles (the contact moves
  // round the rim); with 0 the input of BM_CylinderPlanar (the same planar motion, tests/solvers/test_rigid3d_disc.cpp).
  // A fourth argument, mu in percent (0: absent, the no-slip engine), gives the base Coulomb friction mu_s = mu_k
  // (rigid3d_disc.hpp with friction: it may slip on its rim, slide flat and fly).
  const GroundMotion& rec = record();
  const double d = static_cast<double>(state.range(0)) / 100.0;
  const double slenderness = static_cast<double>(state.range(1)) / 100.0;
  const auto body = topple::CylinderBody3D::solid(d, d / slenderness);
  std::vector<double> a(rec.size(), 0.0);
  const auto delay = static_cast<std::size_t>(std::llround(1.0 / rec.dt_s()));
  const double k = static_cast<double>(state.range(2)) / 100.0;
  for (std::size_t i = delay; i < rec.size(); ++i) a[i] = k * rec.accel_m_s2()[i - delay];
  const GroundMotion y = GroundMotion::uniform(a, rec.dt_s(), rec.start_time_s());
  topple::Rigid3DOptions options;
  if (state.range(3) > 0) options.mu_s = static_cast<double>(state.range(3)) / 100.0;
  topple::Rigid3DSummary s;
  for (auto _ : state) {
    s = topple::rock3d_cylinder(rec, &y, nullptr, body, options).summary;
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size()));
  state.counters["impacts"] = static_cast<double>(s.impacts);
  state.counters["max_tilt_over_limit"] = s.max_tilt_over_limit;
  state.counters["steps_per_sample"] = static_cast<double>(s.steps) / static_cast<double>(rec.size());
  state.counters["overturned"] = s.overturned ? 1.0 : 0.0;
  state.counters["slide_path_mm"] = 1e3 * s.slide_path_length_m;
  // the fraction of the record on the rim (from the mode changes), as BM_Rocking's rocking_fraction
  double on_rim = 0.0;
  for (std::size_t i = 0; i < s.modes.size(); ++i) {
    const double end = i + 1 < s.modes.size() ? s.modes[i + 1].time_s : s.end_time_s;
    const auto m = s.modes[i].mode;
    if (m == topple::Rigid3DMode::rocking || m == topple::Rigid3DMode::slide_rock || m == topple::Rigid3DMode::flight) {
      on_rim += end - s.modes[i].time_s;
    }
  }
  state.counters["rim_fraction"] = on_rim / (rec.end_time_s() - rec.start_time_s());
  state.counters["moving_samples_per_second"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * on_rim / rec.dt_s(), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_Cylinder3DWobble)
    ->Args({100, 15, 70, 0})
    ->Args({100, 10, 70, 0})
    ->Args({100, 15, 0, 0})
    ->Args({100, 10, 0, 0})
    ->Args({100, 15, 70, 50})  // with friction mu = 0.5 (> R / h: it lifts)
    ->Args({100, 10, 70, 50})
    ->Args({100, 10, 70, 20})  // mu = 0.2 > R / h = 0.1: slips on its rim more
    ->Args({100, 50, 70, 0})  // never lifts (uplift level 0.5 g > the pair's peak): the rest scan's cost per sample
    ->Unit(benchmark::kMillisecond);

void BM_RockingRk4Thesis(benchmark::State& state) {
  // The thesis' method for comparison: fixed-step RK4, 10 steps per sample interval.
  const GroundMotion& rec = record();
  const auto body = body_from(state);
  topple::RockingOptions options;
  options.method = topple::RockingMethod::rk4;
  topple::RockingSummary s;
  for (auto _ : state) {
    s = topple::rock_summary(rec, body, options);
    benchmark::DoNotOptimize(s);
  }
  counters(state, s, rec.size());
}
BENCHMARK(BM_RockingRk4Thesis)->Args({100, 15})->Unit(benchmark::kMillisecond);

void BM_ThresholdSearchP1(benchmark::State& state) {
  // First overturning amplitude of rocking.md P1 (one-cycle cosine, p = 2 rad/s, alpha = 15 deg): a whole search
  // (scan and bisection to 1e-7), ~30 responses.
  const double alpha = 15.0 * topple::kPi / 180.0;
  const double R = 3.0 * 9.81 / 16.0;
  const auto body = topple::RockingBody::block(2.0 * R * std::sin(alpha), 2.0 * R * std::cos(alpha));
  topple::RockingOptions options;
  options.g_m_s2 = 9.81;
  const auto motion = [](double x) {
    topple::PulseSpec spec;
    spec.kind = topple::PulseKind::cosine;
    spec.amplitude_m_s2 = x * 9.81;
    spec.duration_s = 2.0;
    return topple::make_pulse(spec);
  };
  topple::ThresholdSearch search;
  search.start = std::tan(alpha);
  search.step = 0.02 * std::tan(alpha);
  search.max = 1.0;
  topple::ThresholdResult found;
  for (auto _ : state) {
    found = topple::first_overturning_amplitude(motion, body, options, topple::OverturnCriterion::falls, search);
    benchmark::DoNotOptimize(found);
  }
  state.counters["amplitude_g"] = found.amplitude.value_or(-1.0);
  state.counters["runs"] = static_cast<double>(found.runs);
}
BENCHMARK(BM_ThresholdSearchP1)->Unit(benchmark::kMillisecond);

}  // namespace
