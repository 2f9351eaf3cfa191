// Flexible supports side by side with the rigid block in one run: record samples per second per core on the first
// 20,000 samples (dt = 0.005 s) of Kocaeli 1999 ATS-090 (bench/kocaeli_record.hpp), k_y = mu = 20 % of PGA, one-way.
//   BM_Rigid                         topple's exact rigid solver (the reference of the 2x target)
//   BM_ShelfDecoupled / Coupled      object on a 4 Hz, 5 % shelf (coupled: mass ratio 0.2)
//   BM_SlammerDecoupled / Coupled    SLAMMER's sliding mass, H = 50 m, V_s = V_b = 600 m/s, 15 % damping in all
//   BM_SlammerEquivalentLinear       the same, equivalent linear (reference strain 0.05 %), decoupled
//   BM_SupportResponseOnly           the sliding mass' demand alone (the decoupled analysis without its sliding)
// Run:  build/release/bench/bench_flexible --benchmark_min_time=0.5  (figures in docs/performance.md)
#include <benchmark/benchmark.h>

#include "kocaeli_record.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/solvers/sliding.hpp"

namespace {

using topple::FlexibleAnalysis;
using topple::GroundMotion;

const GroundMotion& record() {
  static const GroundMotion r = topple::bench::kocaeli_record(20000, 3.0);
  return r;
}

double ky_g() { return 0.2 * record().pga_m_s2() / topple::kStandardGravity; }

void report(benchmark::State& state, double residual_m) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * record().size()));
  state.counters["residual_cm"] = 100.0 * residual_m;
}

void BM_Rigid(benchmark::State& state) {
  const auto block = topple::SlidingBlock::make(ky_g(), ky_g(), 0.0, topple::SlidingMode::one_way);
  topple::SlidingSummary s;
  for (auto _ : state) {
    s = topple::slide_summary(record(), block);
    benchmark::DoNotOptimize(s);
  }
  report(state, s.residual_displacement_m);
}

void shelf(benchmark::State& state, FlexibleAnalysis analysis) {
  const auto block = topple::SlidingBlock::make(ky_g(), ky_g(), 0.0, topple::SlidingMode::one_way);
  const auto support = topple::SupportOscillator::make(4.0, 0.05, analysis == FlexibleAnalysis::coupled ? 0.2 : 0.0);
  topple::FlexibleSummary s;
  for (auto _ : state) {
    s = topple::slide_flexible(record(), support, block, analysis);
    benchmark::DoNotOptimize(s);
  }
  report(state, s.sliding.residual_displacement_m);
}

void slammer(benchmark::State& state, FlexibleAnalysis analysis, bool equivalent_linear) {
  const auto column = topple::SlidingMassColumn::make(50.0, 600.0, 600.0, -0.05,
                                                      equivalent_linear ? std::optional<double>(0.0005) : std::nullopt);
  topple::FlexibleSummary s;
  const double ky = ky_g();  // outside the loop, as BM_Rigid's block: ky_g() scans the record for its PGA
  for (auto _ : state) {
    s = topple::slide_flexible(record(), column, ky, analysis);
    benchmark::DoNotOptimize(s);
  }
  report(state, s.sliding.residual_displacement_m);
  state.counters["eql_iterations"] = s.mode.iterations;
  state.counters["slip_episodes"] = s.sliding.slip_episodes;
}

void BM_ShelfDecoupled(benchmark::State& state) { shelf(state, FlexibleAnalysis::decoupled); }
void BM_ShelfCoupled(benchmark::State& state) { shelf(state, FlexibleAnalysis::coupled); }
void BM_SlammerDecoupled(benchmark::State& state) { slammer(state, FlexibleAnalysis::decoupled, false); }
void BM_SlammerCoupled(benchmark::State& state) { slammer(state, FlexibleAnalysis::coupled, false); }
void BM_SlammerEquivalentLinear(benchmark::State& state) { slammer(state, FlexibleAnalysis::decoupled, true); }

BENCHMARK(BM_Rigid);
BENCHMARK(BM_ShelfDecoupled);
BENCHMARK(BM_SlammerDecoupled);
BENCHMARK(BM_ShelfCoupled);
BENCHMARK(BM_SlammerCoupled);
BENCHMARK(BM_SlammerEquivalentLinear);

}  // namespace
namespace {
/// The decoupled analysis' first half alone: the support's demand on the record's samples.
void BM_SupportResponseOnly(benchmark::State& state) {
  const auto m = topple::modal_properties(topple::SlidingMassColumn::make(50.0, 600.0, 600.0, -0.05), record());
  for (auto _ : state) {
    auto h = topple::support_acceleration_m_s2(record(), m);
    benchmark::DoNotOptimize(h);
  }
  report(state, 0.0);
}
BENCHMARK(BM_SupportResponseOnly);
}  // namespace
