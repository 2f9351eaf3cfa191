// Sliding throughput: record samples per second per core for a single block, and the 100-coefficient sliding
// spectrum kernel. The record is the first 20,000 samples (dt = 0.005 s) of Kocaeli 1999 ATS-090 from
// ../shared/records/slammer (PGA 0.185 g); without ../shared, a seeded synthetic record of the same length.
// Run:  build/release/bench/bench_sliding  (figures in docs/performance.md)
#include <cmath>
#include <filesystem>
#include <vector>

#include <benchmark/benchmark.h>

#include "kocaeli_record.hpp"
#include "topple/solvers/sliding.hpp"

namespace {

using topple::GroundMotion;

const GroundMotion& record() { return topple::bench::kocaeli_20000(); }

/// mu giving the wanted fraction of time sliding, as a benchmark argument in percent of PGA.
void single_block(benchmark::State& state, topple::SlidingMode mode) {
  const GroundMotion& rec = record();
  const double mu = static_cast<double>(state.range(0)) / 100.0 * rec.pga_m_s2() / topple::kStandardGravity;
  const auto block = topple::SlidingBlock::make(mu, mu, 0.0, mode);
  topple::SlidingSummary s;
  for (auto _ : state) {
    s = topple::slide_summary(rec, block);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size()));
  state.counters["slide_fraction"] = s.total_slip_duration_s / rec.duration_s();
  state.counters["mu"] = mu;
  state.counters["residual_cm"] = 100.0 * s.residual_displacement_m;
}

void BM_TwoWaySliding(benchmark::State& state) { single_block(state, topple::SlidingMode::two_way); }
void BM_OneWaySliding(benchmark::State& state) { single_block(state, topple::SlidingMode::one_way); }
// Argument: mu as a percentage of PGA/g (higher: less sliding).
BENCHMARK(BM_TwoWaySliding)->Arg(90)->Arg(60)->Arg(40)->Arg(20)->Arg(5);
BENCHMARK(BM_OneWaySliding)->Arg(60)->Arg(20);

void BM_TwoWaySlidingWithHistory(benchmark::State& state) {
  const GroundMotion& rec = record();
  const double mu = 0.4 * rec.pga_m_s2() / topple::kStandardGravity;
  const auto block = topple::SlidingBlock::make(mu);
  for (auto _ : state) {
    auto r = topple::slide(rec, block);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size()));
}
BENCHMARK(BM_TwoWaySlidingWithHistory);

void BM_SlidingSpectrum100(benchmark::State& state) {
  // 100 friction coefficients from 1 % to 100 % of PGA/g on one record, two-way.
  const GroundMotion& rec = record();
  std::vector<double> mu(100);
  for (std::size_t i = 0; i < mu.size(); ++i) {
    mu[i] = static_cast<double>(i + 1) / 100.0 * rec.pga_m_s2() / topple::kStandardGravity;
  }
  for (auto _ : state) {
    auto s = topple::slide_summaries(rec, mu);
    benchmark::DoNotOptimize(s);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * rec.size() * mu.size()));
}
BENCHMARK(BM_SlidingSpectrum100)->Unit(benchmark::kMillisecond);

}  // namespace
