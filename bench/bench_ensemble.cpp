// The ensemble engine against bare loops over the sliding solver: runs/s on 1 and 2 threads, and the engine's
// overhead (plan, motion preparation, result rows, formatting, chunk files) per run.
//
// Workloads (10,000 sliding runs each):
//   pulses  : 20 sine pulses (0.2-0.5 g, 0.5-4 Hz, 2000 samples each plus still tail) x 500 friction coefficients
//   records : 20 synthetic broadband records (4000 samples at 0.01 s, PGA 0.4 g) x 500 friction coefficients
// with mu_kinetic = mu (the engine batches a motion's blocks through slide_summaries) or mu_kinetic = 0.9 mu (one
// slide_summary per run, the same call the bare loop makes).
//
// Figures: docs/performance.md, "Ensemble engine".
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "support/noise_record.hpp"
#include "topple/ensemble/sweep.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple::ensemble {
namespace {

constexpr double kG = kStandardGravity;
constexpr std::size_t kMotions = 20;
constexpr std::size_t kMus = 500;

/// The tests' broadband record (tests/support/noise_record.hpp): 40 s at 0.01 s, PGA 0.4 g.
std::shared_ptr<const GroundMotion> noise_record(unsigned seed) {
  return std::make_shared<const GroundMotion>(test::noise_record({.seed = seed, .samples = 4000, .dt_s = 0.01,
                                                                  .pga_m_s2 = 0.4 * kG, .resonance_hz = 2.5,
                                                                  .pole_radius = 0.95, .envelope_peak_s = 8.0}));
}

SweepSpec make_spec(bool records, bool batched) {
  SweepSpec s;
  if (records) {
    for (unsigned i = 0; i < kMotions; ++i) s.records.push_back({"rec" + std::to_string(i), noise_record(i + 1)});
  } else {
    for (const double amp_g : {0.2, 0.3, 0.4, 0.5}) {
      for (const double f : {0.5, 1.0, 2.0, 3.0, 4.0}) {
        PulseInput p;
        p.spec.kind = PulseKind::sine;
        p.spec.amplitude_m_s2 = amp_g * kG;
        p.spec.duration_s = 1.0 / f;
        p.spec.tail_s = 5.0 / f;
        p.name = "sine";
        s.pulses.push_back(p);
      }
    }
  }
  for (std::size_t k = 0; k < kMus; ++k) {
    const double mu = 0.01 + 0.49 * static_cast<double>(k) / static_cast<double>(kMus - 1);
    s.objects.emplace_back(SlideObject{SlidingBlock::make(mu, batched ? mu : 0.9 * mu), 0.0});
  }
  return s;
}

/// The motions of a plan, prepared once (the bare loops do not pay for it either).
std::vector<GroundMotion> motions_of(const Plan& plan) {
  std::vector<GroundMotion> out;
  for (const auto& m : plan.motions) out.push_back(m.transform.apply(*m.base));
  return out;
}

void bare_slide_summary(benchmark::State& state, bool records, bool batched) {
  const SweepSpec spec = make_spec(records, batched);
  const std::vector<GroundMotion> motions = motions_of(make_plan(spec));
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& m : motions) {
      for (const auto& o : spec.objects) sum += slide_summary(m, std::get<SlideObject>(o).block).max_abs_displacement_m;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * motions.size() * spec.objects.size()));
}

void bare_slide_summaries(benchmark::State& state, bool records) {
  const SweepSpec spec = make_spec(records, true);
  const std::vector<GroundMotion> motions = motions_of(make_plan(spec));
  std::vector<double> mus;
  for (const auto& o : spec.objects) mus.push_back(std::get<SlideObject>(o).block.mu_static);
  for (auto _ : state) {
    double sum = 0.0;
    for (const auto& m : motions) {
      for (const auto& s : slide_summaries(m, mus)) sum += s.max_abs_displacement_m;
    }
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * motions.size() * mus.size()));
}

void engine_in_memory(benchmark::State& state, bool records, bool batched) {
  const Plan plan = make_plan(make_spec(records, batched));
  ExecuteOptions o;
  o.threads = static_cast<int>(state.range(0));
  for (auto _ : state) {
    const ResultTable t = run_in_memory(plan, o);
    benchmark::DoNotOptimize(t.rows.data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * plan.runs()));
}

void engine_to_files(benchmark::State& state, bool records, bool batched) {
  const Plan plan = make_plan(make_spec(records, batched));
  const auto dir = std::filesystem::temp_directory_path() / ("topple-bench-ensemble-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  StoreOptions store;
  store.csv_path = dir / "out.csv";
  store.restart = true;
  ExecuteOptions o;
  o.threads = static_cast<int>(state.range(0));
  SingleProcess one;
  for (auto _ : state) {
    const SweepReport r = run_to_files(plan, store, o, one);
    benchmark::DoNotOptimize(r.runs_computed);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * plan.runs()));
  std::filesystem::remove_all(dir);
}

/// Paired measurements, robust to a shared machine: each iteration times the bare loop and the engine (to files, in
/// chunks of 1024 runs) back to back, and the counters report the medians over iterations of the engine's overhead
/// (engine / bare - 1, 1 thread) and of its speed-up on 2 threads (engine 1 thread / engine 2 threads).
/// state.range(0): 0 = bare loop of slide_summary, 1 = bare loop of slide_summaries (one call per motion).
void paired(benchmark::State& state, bool records, bool batched) {
  const SweepSpec spec = make_spec(records, batched);
  const Plan plan = make_plan(spec);
  const std::vector<GroundMotion> motions = motions_of(plan);
  std::vector<double> mus;
  for (const auto& o : spec.objects) mus.push_back(std::get<SlideObject>(o).block.mu_static);
  const auto dir = std::filesystem::temp_directory_path() / ("topple-bench-ensemble-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  StoreOptions store;
  store.csv_path = dir / "out.csv";
  store.restart = true;
  SingleProcess one;
  const auto seconds = [](auto f) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  std::vector<double> overhead;
  std::vector<double> speedup;
  std::vector<double> bare_s;
  std::vector<double> engine1_s;
  for (auto _ : state) {
    const double bare = seconds([&] {
      double sum = 0.0;
      for (const auto& m : motions) {
        if (state.range(0) == 0) {
          for (const auto& o : spec.objects) sum += slide_summary(m, std::get<SlideObject>(o).block).max_abs_displacement_m;
        } else {
          for (const auto& r : slide_summaries(m, mus)) sum += r.max_abs_displacement_m;
        }
      }
      benchmark::DoNotOptimize(sum);
    });
    ExecuteOptions o1;
    o1.threads = 1;
    ExecuteOptions o2;
    o2.threads = 2;
    const double e1 = seconds([&] { benchmark::DoNotOptimize(run_to_files(plan, store, o1, one).runs_computed); });
    const double e2 = seconds([&] { benchmark::DoNotOptimize(run_to_files(plan, store, o2, one).runs_computed); });
    overhead.push_back(e1 / bare - 1.0);
    speedup.push_back(e1 / e2);
    bare_s.push_back(bare);
    engine1_s.push_back(e1);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  state.counters["bare_runs_per_s"] = static_cast<double>(plan.runs()) / median(bare_s);
  state.counters["engine1_runs_per_s"] = static_cast<double>(plan.runs()) / median(engine1_s);
  state.counters["overhead_pct"] = 100.0 * median(overhead);
  state.counters["speedup_2_threads"] = median(speedup);
  std::filesystem::remove_all(dir);
}

BENCHMARK_CAPTURE(paired, records_kinetic, true, false)->Arg(0)->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(paired, records_batched, true, true)->Arg(0)->Arg(1)->Iterations(30)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(paired, pulses_kinetic, false, false)->Arg(0)->Iterations(20)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(paired, pulses_batched, false, true)->Arg(0)->Arg(1)->Iterations(20)->Unit(benchmark::kMillisecond);

/// The engine alone: 100 motions x 1000 objects whose run function only fills 12 result doubles (what a sliding row
/// carries), to files, in chunks of state.range(0) runs. Time per run = the engine's cost per row.
void engine_without_physics(benchmark::State& state) {
  Plan plan;
  plan.motion_columns = {"motion", "pga_g", "polarity"};
  plan.object_columns = {"model", "mu", "mu_kinetic", "slope_deg", "mode"};
  for (int k = 0; k < 12; ++k) plan.result_columns.push_back("result_" + std::to_string(k));
  const auto base = std::make_shared<const GroundMotion>(GroundMotion::uniform({0.0, 1.0, 0.0}, 0.01));
  for (int m = 0; m < 100; ++m) {
    plan.motions.push_back({base, {}, {Value{"records/RSN" + std::to_string(m) + ".AT2"}, Value{0.1 * m}, Value{"normal"}}});
  }
  for (int o = 0; o < 1000; ++o) {
    plan.objects.push_back({{Value{"slide"}, Value{0.001 * o}, Value{0.001 * o}, Value{0.0}, Value{"two-way"}}});
  }
  plan.run = [](const GroundMotion&, std::size_t m, std::size_t b, std::size_t e, std::span<Value> out) {
    for (std::size_t o = b; o < e; ++o) {
      for (std::size_t k = 0; k < 12; ++k) out[(o - b) * 12 + k] = std::sqrt(static_cast<double>(m * 1000 + o + k));
    }
  };
  plan.chunk_runs = static_cast<std::size_t>(state.range(0));
  const auto dir = std::filesystem::temp_directory_path() / ("topple-bench-ensemble-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  StoreOptions store;
  store.csv_path = dir / "out.csv";
  store.restart = true;
  ExecuteOptions o;
  o.threads = 1;
  SingleProcess one;
  for (auto _ : state) {
    const SweepReport r = run_to_files(plan, store, o, one);
    benchmark::DoNotOptimize(r.runs_computed);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * plan.runs()));
  std::filesystem::remove_all(dir);
}
BENCHMARK(engine_without_physics)->Arg(64)->Arg(256)->Arg(1024)->Arg(4096)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(bare_slide_summary, pulses_batchable, false, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bare_slide_summaries, pulses, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_in_memory, pulses_batched, false, true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_to_files, pulses_batched, false, true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bare_slide_summary, pulses_kinetic, false, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_to_files, pulses_kinetic, false, false)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

BENCHMARK_CAPTURE(bare_slide_summary, records_batchable, true, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bare_slide_summaries, records, true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_in_memory, records_batched, true, true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_to_files, records_batched, true, true)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(bare_slide_summary, records_kinetic, true, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(engine_to_files, records_kinetic, true, false)->Arg(1)->Arg(2)->UseRealTime()->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace topple::ensemble
