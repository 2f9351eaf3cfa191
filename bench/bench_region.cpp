// The regional example end to end (issue 17: "under 2 minutes on this 2-core machine"): read
// examples/regional_survey.toml, invert its twelve sites (the ensemble engine, all cores), fit the relation jointly,
// make the pooled field and its contours. And the joint part alone, to show its share. The report's figures (gnuplot)
// are left out: `topple invert ... --report` adds about a second.
//   build/release/bench/bench_region --benchmark_min_time=0.01
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <filesystem>

#include "topple/inversion/inversion.hpp"
#include "topple/output/region_output.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/region/region.hpp"

namespace {

/// The example, or the survey named by TOPPLE_BENCH_REGION_SURVEY (e.g. a larger one from
/// `build/release/tests/make_regional_example 48`: the MPI scale figures in docs/performance.md).
const std::filesystem::path kExample = std::getenv("TOPPLE_BENCH_REGION_SURVEY") != nullptr
                                           ? std::filesystem::path(std::getenv("TOPPLE_BENCH_REGION_SURVEY"))
                                           : std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples/regional_survey.toml";

std::vector<const topple::InversionResult*> pointers(const std::vector<topple::InversionResult>& results) {
  std::vector<const topple::InversionResult*> out;
  for (const auto& r : results) out.push_back(&r);
  return out;
}

void BM_RegionalExample(benchmark::State& state) {
  for (auto _ : state) {
    const topple::Survey survey = topple::io::read_survey(kExample);
    const auto results = topple::invert_sites(survey.sites, survey.inversion);
    std::vector<std::string> notes;
    const auto fit = topple::fit_survey_region(survey, pointers(results), notes);
    const auto field = topple::pooled_field(*fit, survey);
    benchmark::DoNotOptimize(topple::contour_field(field, topple::io::contour_levels_g()));
  }
}
BENCHMARK(BM_RegionalExample)->Unit(benchmark::kSecond)->UseRealTime();

void BM_RegionalJointFitOnly(benchmark::State& state) {
  const topple::Survey survey = topple::io::read_survey(kExample);
  const auto results = topple::invert_sites(survey.sites, survey.inversion);
  for (auto _ : state) {
    std::vector<std::string> notes;
    const auto fit = topple::fit_survey_region(survey, pointers(results), notes);
    const auto field = topple::pooled_field(*fit, survey);
    benchmark::DoNotOptimize(topple::contour_field(field, topple::io::contour_levels_g()));
  }
}
BENCHMARK(BM_RegionalJointFitOnly)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The sites' own inversions alone on one thread: the part `topple invert` splits across MPI ranks.
void BM_RegionalSitesOneThread(benchmark::State& state) {
  const topple::Survey survey = topple::io::read_survey(kExample);
  for (auto _ : state) benchmark::DoNotOptimize(topple::invert_sites(survey.sites, survey.inversion, {1}));
}
BENCHMARK(BM_RegionalSitesOneThread)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace
