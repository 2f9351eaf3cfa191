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
#include "topple/solvers/sliding2d.hpp"
#include "topple/motion/synthesis.hpp"

namespace {
using topple::GroundMotion;

GroundMotion noisy(unsigned seed) {
  return topple::test::noise_record({.seed = seed, .samples = 4000, .dt_s = 0.01, .pga_m_s2 = 0.5 * 9.80665,
                                     .resonance_hz = 3.0, .pole_radius = 0.97, .envelope_peak_s = 5.0});
}

struct Errors {
  double residual, max_u, path;
};
/// Errors of `s` against the reference run `ref`: residual (vector) and max |u| relative to the reference's max |u|,
/// path relative to itself.
Errors errors(const topple::Sliding2dSummary& s, const topple::Sliding2dSummary& ref) {
  const double m = ref.max_abs_displacement_m;
  return {std::hypot(s.residual_east_m - ref.residual_east_m, s.residual_north_m - ref.residual_north_m) / m,
          std::abs(s.max_abs_displacement_m - m) / m, std::abs(s.path_length_m - ref.path_length_m) / ref.path_length_m};
}
constexpr topple::Sliding2dOptions kReference{.rel_tol = 1e-12, .abs_tol = 1e-15};
}  // namespace

/// --tolerances: the Kocaeli pair's errors and tries at looser tolerances than the defaults (abs_tol 1e-8 ... 1e-5,
/// rel_tol = 10 abs_tol), beside bench_sliding2d's BM_Sliding2dLoose (their speed).
int tolerance_table() {
  const GroundMotion& k1 = topple::bench::kocaeli_20000();
  const GroundMotion& k2 = topple::bench::kocaeli_partner_20000();
  std::printf("%6s %8s %10s %10s %10s %8s\n", "mu", "abs_tol", "residual", "max|u|", "path", "tries");
  for (const double mu : {0.113, 0.075}) {
    const auto block = topple::SlidingBlock::make(mu);
    const auto ref = topple::slide_2d_summary(k1, k2, {}, block, nullptr, kReference);
    for (const double abs_tol : {1e-8, 1e-7, 1e-6, 1e-5}) {
      const auto s = topple::slide_2d_summary(k1, k2, {}, block, nullptr, {.rel_tol = 10.0 * abs_tol, .abs_tol = abs_tol});
      const Errors e = errors(s, ref);
      std::printf("%6.3f %8.0e %10.2e %10.2e %10.2e %8zu\n", mu, abs_tol, e.residual, e.max_u, e.path, s.integrator_steps);
    }
  }
  return 0;
}

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--tolerances") return tolerance_table();
  struct Case { const char* name; GroundMotion h1, h2; double mu; };
  std::vector<Case> cases;
  for (double mu : {0.113, 0.075, 0.05}) {
    cases.push_back({"kocaeli", topple::bench::kocaeli_20000(), topple::bench::kocaeli_partner_20000(), mu});
  }
  for (const auto& [seed, mu] : {std::pair{31U, 0.2}, std::pair{31U, 0.05}, std::pair{41U, 0.15}, std::pair{45U, 0.3}}) {
    cases.push_back({"noise", noisy(seed), noisy(seed + 100), mu});
  }
  double worst_res = 0.0, worst_max = 0.0, worst_path = 0.0;
  std::printf("%-8s %6s %8s %10s %10s %10s %8s %8s\n", "record", "mu", "episodes", "residual", "max|u|", "path",
              "tries", "ref");
  for (const auto& c : cases) {
    const auto block = topple::SlidingBlock::make(c.mu);
    const auto ref = topple::slide_2d_summary(c.h1, c.h2, {}, block, nullptr, kReference);
    const auto s = topple::slide_2d_summary(c.h1, c.h2, {}, block);
    const Errors e = errors(s, ref);
    worst_res = std::max(worst_res, e.residual);
    worst_max = std::max(worst_max, e.max_u);
    worst_path = std::max(worst_path, e.path);
    std::printf("%-8s %6.3f %8d %10.2e %10.2e %10.2e %8zu %8zu\n", c.name, c.mu, s.slip_episodes, e.residual, e.max_u, e.path,
                s.integrator_steps, ref.integrator_steps);
  }
  std::printf("worst: residual %.2e  max|u| %.2e  path %.2e  (statement: 1e-6)\n", worst_res, worst_max, worst_path);
  return 0;
}
