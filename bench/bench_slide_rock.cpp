// The coupled slide-rock model against the specialised engines, side by side in one run (issue 15: within 3x of each
// in its regime). Record: the first 20,000 samples of Kocaeli 1999 ATS-090 (bench_rocking's and bench_sliding's,
// dt = 0.005 s, PGA 0.185 g; a seeded synthetic stand-in without ../shared), scaled by the argument (percent).
//   Rocking regime: a 100 cm block, a/h = 0.10, mu = 5 (never slips): topple::rock_summary vs topple::slide_rock
//     (both adaptive Dormand-Prince at rel_tol 1e-8). Argument 100: the record as is (~650 impacts, rocking for most
//     of it: the worst case of bench_rocking).
//   Sliding regime: a 100 x 40 cm block (b/h = 2.5), mu = 0.1 (cannot lift): topple::slide_summary vs
//     topple::slide_rock (its sliding kernel path: the same solver plus its history for the friction work) and
//     slide_rock with sliding_kernel = false (the coupled engine's own exact slide phase).
// Run:  build/release/bench/bench_slide_rock --benchmark_min_time=0.2   (figures in docs/performance.md)
#include <benchmark/benchmark.h>

#include "kocaeli_record.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"

namespace {

using topple::GroundMotion;

const GroundMotion& record() { return topple::bench::kocaeli_20000(); }

topple::SlideRockBody rocking_body() { return topple::SlideRockBody::block(1.0, 10.0, 5.0); }
topple::SlideRockBody sliding_body() { return topple::SlideRockBody::block(1.0, 0.4, 0.1); }

void items(benchmark::State& state) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * record().size()));
}

void BM_RockingRegime_RockingEngine(benchmark::State& state) {
  const auto body = rocking_body().rocking_body();
  for (auto _ : state) {
    const auto s = topple::rock_summary(record(), body);
    benchmark::DoNotOptimize(s.max_rotation_over_alpha);
    state.counters["impacts"] = static_cast<double>(s.impacts);
  }
  items(state);
}

void BM_RockingRegime_Coupled(benchmark::State& state) {
  const auto body = rocking_body();
  for (auto _ : state) {
    const auto s = topple::slide_rock(record(), body).summary;
    benchmark::DoNotOptimize(s.max_rotation_over_alpha);
    state.counters["impacts"] = static_cast<double>(s.impacts);
    state.counters["slip_episodes"] = static_cast<double>(s.slip_episodes);
  }
  items(state);
}

void BM_SlidingRegime_SlidingSolver(benchmark::State& state) {
  const auto block = topple::SlidingBlock::make(0.1);
  for (auto _ : state) {
    const auto s = topple::slide_summary(record(), block);
    benchmark::DoNotOptimize(s.residual_displacement_m);
    state.counters["slip_episodes"] = s.slip_episodes;
  }
  items(state);
}

void BM_SlidingRegime_Coupled(benchmark::State& state) {
  const auto body = sliding_body();
  topple::SlideRockOptions o;
  o.sliding_kernel = state.range(0) != 0;
  for (auto _ : state) {
    const auto s = topple::slide_rock(record(), body, o).summary;
    benchmark::DoNotOptimize(s.residual_slide_m);
    state.counters["slip_episodes"] = s.slip_episodes;
  }
  items(state);
}

}  // namespace

BENCHMARK(BM_RockingRegime_RockingEngine)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RockingRegime_Coupled)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SlidingRegime_SlidingSolver)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_SlidingRegime_Coupled)->Arg(1)->Arg(0)->ArgName("kernel")->Unit(benchmark::kMillisecond);
