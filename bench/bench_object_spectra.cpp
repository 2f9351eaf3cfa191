// Overturning map: 50 PGA levels x 50 block sizes on a 4,000-sample record (issue #5 target: under 2 s on the
// project's 2-core machine), all cores through the ensemble engine. The record is the first 4,000 samples (20 s at
// dt = 0.005 s) of Kocaeli 1999 ATS-090 from ../shared/records/slammer; without ../shared, a seeded synthetic
// motion of the same length (synthesis.hpp). Family: blocks of slenderness alpha = 0.2 rad, heights 10 cm to 4 m
// (log spaced), PGA 0.05 g to 0.8 g (linear); adaptive solver at its default tolerance, each run ending when the
// block falls. Also: the sliding spectrum at 100 friction coefficients on the same record.
// Run:  build/release/bench/bench_object_spectra  (figures in docs/performance.md)
#include <filesystem>
#include <vector>

#include <benchmark/benchmark.h>

#include "topple/io/read.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/motion/synthesis.hpp"

#include "kocaeli_record.hpp"

namespace {

using topple::GroundMotion;

GroundMotion load_record() { return topple::bench::kocaeli_record(4000, 2.0); }

void BM_OverturningMap50x50(benchmark::State& state) {
  const GroundMotion record = load_record();
  topple::BodyFamily family;
  family.alpha_rad = 0.2;
  family.heights_m = topple::log_grid(0.1, 4.0, 50);
  const auto pga = topple::linear_grid(0.05 * topple::kStandardGravity, 0.8 * topple::kStandardGravity, 50);
  std::size_t overturned = 0;
  for (auto _ : state) {
    const topple::OverturningMap map = topple::overturning_map(record, family, pga);
    overturned = 0;
    for (auto v : map.overturned) overturned += v;
    benchmark::DoNotOptimize(overturned);
  }
  state.counters["runs"] = 2500;
  state.counters["overturned"] = static_cast<double>(overturned);
  state.SetItemsProcessed(state.iterations() * 2500);
}
BENCHMARK(BM_OverturningMap50x50)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(3);

void BM_SlidingSpectrum100(benchmark::State& state) {
  const GroundMotion record = load_record();
  const auto mu = topple::linear_grid(0.01, 0.5, 100);
  for (auto _ : state) {
    auto sp = topple::sliding_spectrum(record, mu);
    benchmark::DoNotOptimize(sp.points.data());
  }
}
BENCHMARK(BM_SlidingSpectrum100)->Unit(benchmark::kMicrosecond);

}  // namespace
