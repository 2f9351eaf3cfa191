// Bidirectional sliding throughput beside the exact 1-D solver, in one run: record samples per second per core, for a
// block stuck 95 % of the time and one slipping 15 % of the time. First component: the first 20,000 samples (dt =
// 0.005 s) of Kocaeli 1999 ATS-090 (bench_sliding's record); second: a seeded synthetic motion of the same length,
// step and PGA (topple::synthesize, 3 Hz, seed 7), at right angles. The friction coefficient of each case is found
// at start-up by bisection on the fraction of time slipping (the 1-D case on the first component alone).
// Run:  build/release/bench/bench_sliding2d --benchmark_min_time=0.3  (figures in docs/performance.md)
#include <cmath>
#include <map>
#include <vector>

#include <benchmark/benchmark.h>

#include "kocaeli_record.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/motion/synthesis.hpp"

namespace {

using topple::GroundMotion;

const GroundMotion& first() { return topple::bench::kocaeli_20000(); }

const GroundMotion& second() { return topple::bench::kocaeli_partner_20000(); }

double fraction_2d(double mu) {
  const auto s = topple::slide_2d_summary(first(), second(), {}, topple::SlidingBlock::make(mu));
  return s.total_slip_duration_s / first().duration_s();
}
double fraction_1d(double mu) {
  const auto s = topple::slide_summary(first(), topple::SlidingBlock::make(mu));
  return s.total_slip_duration_s / first().duration_s();
}

/// mu (mu_s = mu_k) at which the fraction of time slipping is `target` (percent), by bisection (fraction falls with mu).
double mu_for(bool two_d, int target_percent) {
  static std::map<std::pair<bool, int>, double> cache;
  const auto key = std::pair{two_d, target_percent};
  if (const auto it = cache.find(key); it != cache.end()) return it->second;
  double lo = 0.001;
  double hi = 2.0 * first().pga_m_s2() / topple::kStandardGravity;
  for (int k = 0; k < 40; ++k) {
    const double mid = 0.5 * (lo + hi);
    ((two_d ? fraction_2d(mid) : fraction_1d(mid)) > target_percent / 100.0 ? lo : hi) = mid;
  }
  return cache[key] = 0.5 * (lo + hi);
}

void BM_Sliding1d(benchmark::State& state) {
  const double mu = mu_for(false, static_cast<int>(state.range(0)));
  const auto block = topple::SlidingBlock::make(mu);
  topple::SlidingSummary s;
  for (auto _ : state) {
    s = topple::slide_summary(first(), block);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * first().size()));
  state.counters["slip_fraction"] = s.total_slip_duration_s / first().duration_s();
  state.counters["mu"] = mu;
}

void BM_Sliding2d(benchmark::State& state) {
  const double mu = mu_for(true, static_cast<int>(state.range(0)));
  const auto block = topple::SlidingBlock::make(mu);
  topple::Sliding2dSummary s;
  for (auto _ : state) {
    s = topple::slide_2d_summary(first(), second(), {}, block);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * first().size()));
  state.counters["slip_fraction"] = s.total_slip_duration_s / first().duration_s();
  state.counters["mu"] = mu;
  state.counters["second_samples"] = static_cast<double>(second().size());
  state.counters["steps"] = static_cast<double>(s.integrator_steps);
  state.counters["episodes"] = s.slip_episodes;
}

/// The 2-D cases at looser tolerances than the defaults (abs_tol = 10^-range(1), rel_tol = 10 abs_tol; mu of the
/// defaults' case): how far the explicit integration's cost falls when accuracy is given up (docs/performance.md;
/// the errors of the same runs: build/release/bench/accuracy_sliding2d --tolerances).
void BM_Sliding2dLoose(benchmark::State& state) {
  const double mu = mu_for(true, static_cast<int>(state.range(0)));
  const auto block = topple::SlidingBlock::make(mu);
  const double abs_tol = std::pow(10.0, -static_cast<double>(state.range(1)));
  const topple::Sliding2dOptions options{.rel_tol = 10.0 * abs_tol, .abs_tol = abs_tol};
  topple::Sliding2dSummary s;
  for (auto _ : state) {
    s = topple::slide_2d_summary(first(), second(), {}, block, nullptr, options);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * first().size()));
  state.counters["steps"] = static_cast<double>(s.integrator_steps);
  state.counters["abs_tol"] = abs_tol;
}

/// Never slipping (mu above max |a| / g): the cost of the stick test alone, both solvers.
void BM_StuckOnly1d(benchmark::State& state) {
  const auto block = topple::SlidingBlock::make(0.5);
  for (auto _ : state) benchmark::DoNotOptimize(topple::slide_summary(first(), block));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * first().size()));
}
void BM_StuckOnly2d(benchmark::State& state) {
  const auto block = topple::SlidingBlock::make(0.5);
  for (auto _ : state) benchmark::DoNotOptimize(topple::slide_2d_summary(first(), second(), {}, block));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * first().size()));
}
BENCHMARK(BM_StuckOnly1d);
BENCHMARK(BM_StuckOnly2d);

// Argument: the percentage of the record's duration spent slipping.
BENCHMARK(BM_Sliding1d)->Arg(5)->Arg(15);
BENCHMARK(BM_Sliding2d)->Arg(5)->Arg(15);
// Arguments: slipping percentage, -log10(abs_tol).
BENCHMARK(BM_Sliding2dLoose)->ArgsProduct({{5, 15}, {7, 6, 5}});

}  // namespace
