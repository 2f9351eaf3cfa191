// Synthesis and intensity throughput: the 5 %-damped response spectrum of a 20,000-sample record at 100 periods
// (target < 10 ms on one core), one synthetic motion of 4,000 samples (target < 1 ms), and the spectral measures
// `topple info` prints. The record is the first 20,000 samples (dt = 0.005 s) of Kocaeli 1999 ATS-090 from
// ../shared/records/slammer; without ../shared, a synthetic motion of the same length.
// Run:  build/release/bench/bench_synthesis  (figures in docs/performance.md)
#include <filesystem>
#include <vector>

#include <benchmark/benchmark.h>

#include "topple/motion/intensity.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"

#include "kocaeli_record.hpp"

namespace {

using topple::GroundMotion;

GroundMotion load_record() { return topple::bench::kocaeli_record(20000, 3.0); }

const GroundMotion& record() {
  static const GroundMotion r = load_record();
  return r;
}

std::vector<double> periods() { return topple::log_spaced(0.02, 5.0, 100); }

/// Coefficients computed once (an OscillatorBank reused across records, as an ensemble does).
void BM_ResponseSpectrum_Bank(benchmark::State& state) {
  const GroundMotion& m = record();
  const topple::OscillatorBank bank(periods(), 0.05, m.dt_s());
  for (auto _ : state) benchmark::DoNotOptimize(bank.respond(m));
  state.counters["samples"] = static_cast<double>(m.size());
  state.counters["periods"] = 100;
}
BENCHMARK(BM_ResponseSpectrum_Bank)->Unit(benchmark::kMillisecond);

/// One call, coefficients included.
void BM_ResponseSpectrum_Call(benchmark::State& state) {
  const GroundMotion& m = record();
  const std::vector<double> p = periods();
  for (auto _ : state) benchmark::DoNotOptimize(topple::response_spectrum(m, p, 0.05));
}
BENCHMARK(BM_ResponseSpectrum_Call)->Unit(benchmark::kMillisecond);

/// 4,001 samples: 40 s at dt = 0.01 s, Clough-Penzien, Saragoni-Hart.
void BM_Synthesize4000(benchmark::State& state) {
  topple::SynthesisSpec s;
  s.pga_m_s2 = 0.3 * topple::kStandardGravity;
  s.predominant_frequency_hz = 3.0;
  s.duration_s = 40.0;
  s.dt_s = 0.01;
  std::uint64_t seed = 0;
  for (auto _ : state) {
    s.seed = seed++;
    benchmark::DoNotOptimize(topple::synthesize(s));
  }
}
BENCHMARK(BM_Synthesize4000)->Unit(benchmark::kMicrosecond);

void BM_PredominantFrequency(benchmark::State& state) {
  const GroundMotion& m = record();
  for (auto _ : state) benchmark::DoNotOptimize(topple::predominant_frequency_hz(m));
}
BENCHMARK(BM_PredominantFrequency)->Unit(benchmark::kMillisecond);

void BM_IntensityMeasures(benchmark::State& state) {
  const GroundMotion& m = record();
  for (auto _ : state) benchmark::DoNotOptimize(topple::intensity_measures(m));
}
BENCHMARK(BM_IntensityMeasures)->Unit(benchmark::kMillisecond);

}  // namespace
