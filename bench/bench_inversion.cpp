// The main job's budget: `topple invert examples/survey.toml` (8 objects, 30 PGA x 25 frequencies x 40 motions per
// cell = 240,000 runs) must finish in under 30 s on the project's 2-core machine (issue #6). This benchmark times
// invert_site on that survey, wall clock, with every core (threads = 0) and with one (the per-core rate, for
// clusters), and reports runs per second. Synthesis of the family's motions (25 columns x 40 motions) is included:
// it is part of every inversion.
// Run:  build/release/bench/bench_inversion  (figures in docs/performance.md)
#include <filesystem>

#include <benchmark/benchmark.h>

#include "topple/inversion/inversion.hpp"
#include "topple/io/survey_file.hpp"

namespace {

const topple::Survey& example_survey() {
  static const topple::Survey survey =
      topple::io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "survey.toml");
  return survey;
}

void BM_InvertExampleSurvey(benchmark::State& state) {
  const topple::Survey& survey = example_survey();
  const topple::InversionOptions options{static_cast<int>(state.range(0))};
  std::size_t runs = 0;
  for (auto _ : state) {
    const topple::InversionResult r = topple::invert_site(survey.sites.front(), survey.inversion, options);
    runs += r.runs;
    benchmark::DoNotOptimize(r.pga_estimate_g.median);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(runs));
  state.counters["objects"] = static_cast<double>(survey.sites.front().objects.size());
}
// Argument: worker threads (0 = every core).
BENCHMARK(BM_InvertExampleSurvey)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

/// A quarter of the work (motions_per_cell 10): the same per-run mix, for quick comparisons.
void BM_InvertExampleSurveyTenMotions(benchmark::State& state) {
  topple::InversionSettings settings = example_survey().inversion;
  settings.motions_per_cell = 10;
  std::size_t runs = 0;
  for (auto _ : state) {
    const topple::InversionResult r = topple::invert_site(example_survey().sites.front(), settings, {});
    runs += r.runs;
    benchmark::DoNotOptimize(r.pga_estimate_g.median);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(runs));
}
BENCHMARK(BM_InvertExampleSurveyTenMotions)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(3);

/// The three-component example (examples/survey_3c.toml: 16 x 10 cells, 16 motions, 12 direction bins, 8 objects),
/// one thread, as given (Arg 3) and as the one-component survey of the same objects and grid (Arg 1: bearings and
/// the sliding direction dropped): the cost of the third dimension side by side.
void BM_InvertThreeComponentExample(benchmark::State& state) {
  static const topple::Survey survey =
      topple::io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "survey_3c.toml");
  topple::Site site = survey.sites.front();
  topple::InversionSettings settings = survey.inversion;
  if (state.range(0) == 1) {
    settings.components = 1;
    for (topple::ObservedObject& o : site.objects) {
      o.azimuth_deg.reset();
      o.slid_azimuth_deg.reset();
    }
  }
  std::size_t runs = 0;
  for (auto _ : state) {
    const topple::InversionResult r = topple::invert_site(site, settings, topple::InversionOptions{1});
    runs += r.runs;
    benchmark::DoNotOptimize(r.pga_estimate_g.median);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(runs));
}
BENCHMARK(BM_InvertThreeComponentExample)->Arg(1)->Arg(3)->Unit(benchmark::kSecond)->UseRealTime()->Iterations(1);

}  // namespace
