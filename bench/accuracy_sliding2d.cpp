// The accuracy table of docs/method.md ("Accuracy of the defaults"), as a plain program: for the benchmark's Kocaeli
// pair (bench_sliding2d's records, mu = 0.113, 0.075, 0.05) and three pairs of the tests' noise records (seeds 31,
// 41, 45 with +100 for the second component; mu as in Sliding2d.DefaultsMeetTheStatedAccuracy), the errors of a run
// at the defaults against a run at rel_tol 1e-12, abs_tol 1e-15: residual (vector) and max |u| relative to max |u| of
// the reference, path relative to itself; and the integrator tries of both. Prints one line per case and the worst.
// Run:  build/release/bench/accuracy_sliding2d  [--tolerances: the errors at looser tolerances, see tolerance_table]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "kocaeli_record.hpp"
#include "support/noise_record.hpp"
#include "topple/sliding2d.hpp"
#include "topple/synthesis.hpp"

namespace {
using topple::GroundMotion;

GroundMotion noisy(unsigned seed) {
  return topple::test::noise_record({.seed = seed, .samples = 4000, .dt_s = 0.01, .pga_m_s2 = 0.5 * 9.80665,
                                     .resonance_hz = 3.0, .pole_radius = 0.97, .envelope_peak_s = 5.0});
}

GroundMotion synthetic_second() {
  const GroundMotion& first = topple::bench::kocaeli_20000();
  topple::SynthesisSpec s;
  s.pga_m_s2 = first.pga_m_s2();
  s.predominant_frequency_hz = 3.0;
  s.dt_s = first.dt_s();
  s.duration_s = first.duration_s();
  s.seed = 7;
  return topple::synthesize(s);
}
}  // namespace

/// --tolerances: the Kocaeli pair's errors and tries at looser tolerances than the defaults (abs_tol 1e-8 ... 1e-5,
/// rel_tol = 10 abs_tol), beside bench_sliding2d's BM_Sliding2dLoose (their speed).
int tolerance_table() {
  const GroundMotion k2 = synthetic_second();
  std::printf("%6s %8s %10s %10s %10s %8s\n", "mu", "abs_tol", "residual", "max|u|", "path", "tries");
  for (const double mu : {0.113, 0.075}) {
    const auto block = topple::SlidingBlock::make(mu);
    const auto ref = topple::slide_2d_summary(topple::bench::kocaeli_20000(), k2, {}, block, nullptr,
                                              {.rel_tol = 1e-12, .abs_tol = 1e-15});
    const double m = ref.max_abs_displacement_m;
    for (const double abs_tol : {1e-8, 1e-7, 1e-6, 1e-5}) {
      const auto s = topple::slide_2d_summary(topple::bench::kocaeli_20000(), k2, {}, block, nullptr,
                                              {.rel_tol = 10.0 * abs_tol, .abs_tol = abs_tol});
      std::printf("%6.3f %8.0e %10.2e %10.2e %10.2e %8zu\n", mu, abs_tol,
                  std::hypot(s.residual_east_m - ref.residual_east_m, s.residual_north_m - ref.residual_north_m) / m,
                  std::abs(s.max_abs_displacement_m - m) / m,
                  std::abs(s.path_length_m - ref.path_length_m) / ref.path_length_m, s.integrator_steps);
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--tolerances") return tolerance_table();
  if (argc > 1) {  // diagnosis: where the error of the Kocaeli pair at mu = argv[1] grows (largest jumps of |du|)
    const double mu = std::atof(argv[1]);
    const GroundMotion k2 = synthetic_second();
    const auto block = topple::SlidingBlock::make(mu);
    const auto s = topple::slide_2d(topple::bench::kocaeli_20000(), k2, {}, block);
    const auto ref = topple::slide_2d(topple::bench::kocaeli_20000(), k2, {}, block, nullptr, {.rel_tol = 1e-12, .abs_tol = 1e-15});
    std::vector<std::pair<double, double>> jumps;
    double prev = 0.0;
    std::size_t j = 0;
    for (std::size_t k = 0; k < s.history.time_s.size(); ++k) {
      while (j + 1 < ref.history.time_s.size() && ref.history.time_s[j] < s.history.time_s[k]) ++j;
      if (ref.history.time_s[j] != s.history.time_s[k]) continue;
      const double e = std::hypot(s.history.east_m[k] - ref.history.east_m[j], s.history.north_m[k] - ref.history.north_m[j]);
      const double v = std::hypot(s.history.east_m_s[k] - ref.history.east_m_s[j], s.history.north_m_s[k] - ref.history.north_m_s[j]);
      jumps.push_back({e - prev, s.history.time_s[k]});
      if (v > 3e-8) std::printf("t %.4f dv %.2e speed %.2e\n", s.history.time_s[k], v, std::hypot(ref.history.east_m_s[j], ref.history.north_m_s[j]));
      prev = e;
    }
    std::sort(jumps.begin(), jumps.end());
    for (std::size_t k = jumps.size() - 5; k < jumps.size(); ++k) std::printf("jump %.2e at t %.4f\n", jumps[k].first, jumps[k].second);
    std::printf("path %.10e ref %.10e  max %.3e\n", s.summary.path_length_m, ref.summary.path_length_m, ref.summary.max_abs_displacement_m);
    return 0;
  }
  struct Case { const char* name; GroundMotion h1, h2; double mu; };
  std::vector<Case> cases;
  const GroundMotion k2 = synthetic_second();
  for (double mu : {0.113, 0.075, 0.05}) cases.push_back({"kocaeli", topple::bench::kocaeli_20000(), k2, mu});
  for (const auto& [seed, mu] : {std::pair{31U, 0.2}, std::pair{31U, 0.05}, std::pair{41U, 0.15}, std::pair{45U, 0.3}}) {
    cases.push_back({"noise", noisy(seed), noisy(seed + 100), mu});
  }
  double worst_res = 0.0, worst_max = 0.0, worst_path = 0.0;
  std::printf("%-8s %6s %8s %10s %10s %10s %8s %8s\n", "record", "mu", "episodes", "residual", "max|u|", "path",
              "tries", "ref");
  for (const auto& c : cases) {
    const auto block = topple::SlidingBlock::make(c.mu);
    const auto ref = topple::slide_2d_summary(c.h1, c.h2, {}, block, nullptr, {.rel_tol = 1e-12, .abs_tol = 1e-15});
    const auto s = topple::slide_2d_summary(c.h1, c.h2, {}, block);
    const double m = ref.max_abs_displacement_m;
    const double res = std::hypot(s.residual_east_m - ref.residual_east_m, s.residual_north_m - ref.residual_north_m) / m;
    const double mx = std::abs(s.max_abs_displacement_m - m) / m;
    const double path = std::abs(s.path_length_m - ref.path_length_m) / ref.path_length_m;
    worst_res = std::max(worst_res, res);
    worst_max = std::max(worst_max, mx);
    worst_path = std::max(worst_path, path);
    std::printf("%-8s %6.3f %8d %10.2e %10.2e %10.2e %8zu %8zu\n", c.name, c.mu, s.slip_episodes, res, mx, path,
                s.integrator_steps, ref.integrator_steps);
  }
  std::printf("worst: residual %.2e  max|u| %.2e  path %.2e  (statement: 1e-6)\n", worst_res, worst_max, worst_path);
  return 0;
}
