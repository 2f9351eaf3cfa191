// Peer check against USGS SLAMMER 1.1's published rigid-block results (../shared/verification/slammer, README
// there): 90 cases x 2 polarities, one-way sliding, each record scaled as SLAMMER did (target PGA / the PGA in
// eq.sql rounded to 3 decimals).
//
// Criterion. SLAMMER integrates with the trapezoid rule at the record's dt and decides slip start and stop once per
// sample, so it carries a discretisation error of its own; its one-way results lie 0.01 % to 8 % above the exact
// piecewise-linear solution. We assert pySLAMMER's published criterion for every case (within 2 % or 1 cm, and
// within 0.05 cm when SLAMMER's value is below 0.5 cm) and, tighter, that the median relative difference on cases
// above 0.5 cm is under 1 %. The distribution is written to docs/verification.md by hand from this test's output.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/shared_data.hpp"
#include "support/slammer_suite.hpp"
#include "topple/io/read.hpp"
#include "topple/solvers/sliding.hpp"

namespace topple {
namespace {

TEST(SlammerVerification, RigidBlockOneWayAll180Results) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  test::SlammerSuite suite;
  std::vector<double> rel_diffs;  // (topple - SLAMMER) / SLAMMER for SLAMMER >= 0.5 cm
  std::vector<std::pair<double, std::string>> largest;
  int cases = 0;
  int failures = 0;
  double worst_small_abs = 0.0;
  for (const auto& analysis : suite.results().at("analyses")) {
    if (analysis.at("analysis").at("method") != "rigid") continue;
    const std::string file = test::SlammerSuite::record_file(analysis);
    const double target = analysis.at("ground_motion_parameters").at("target_pga_g").get<double>();
    const double ky = analysis.at("site_parameters").at("ky_g").get<double>();
    const GroundMotion scaled = suite.scaled_record(analysis);  // target / the rounded eq.sql PGA, as SLAMMER
    const SlidingBlock block = SlidingBlock::make(ky, ky, 0.0, SlidingMode::one_way);
    for (const bool inverse : {false, true}) {
      const double slammer_cm =
          analysis.at("results").at(inverse ? "inverse_displacement_cm" : "normal_displacement_cm").get<double>();
      const double ours_cm =
          100.0 * slide_summary(inverse ? scaled.inverted() : scaled, block).residual_displacement_m;
      const double diff = ours_cm - slammer_cm;
      bool ok;
      if (slammer_cm < 0.5) {
        ok = std::abs(diff) <= 0.05;
        worst_small_abs = std::max(worst_small_abs, std::abs(diff));
      } else {
        ok = std::abs(diff) <= std::max(0.02 * slammer_cm, 1.0);
        rel_diffs.push_back(diff / slammer_cm);
        largest.emplace_back(std::abs(diff / slammer_cm),
                             fmt::format("{} PGA {} g ky {} {}: topple {:.4f} cm, SLAMMER {:.4f} cm", file, target, ky,
                                         inverse ? "inverse" : "normal", ours_cm, slammer_cm));
      }
      ++cases;
      if (!ok) {
        ++failures;
        ADD_FAILURE() << fmt::format("{} PGA {} g ky {} {}: topple {:.5f} cm, SLAMMER {:.5f} cm", file, target, ky,
                                     inverse ? "inverse" : "normal", ours_cm, slammer_cm);
      }
    }
  }
  EXPECT_EQ(cases, 180);
  EXPECT_EQ(failures, 0);
  std::sort(rel_diffs.begin(), rel_diffs.end());
  ASSERT_FALSE(rel_diffs.empty());
  const auto pct = [&](double q) { return 100.0 * rel_diffs[static_cast<std::size_t>(q * static_cast<double>(rel_diffs.size() - 1))]; };
  fmt::print("SLAMMER rigid one-way: {} results, {} >= 0.5 cm; (topple - SLAMMER)/SLAMMER in %: min {:.3f}, "
             "p10 {:.3f}, median {:.3f}, p90 {:.3f}, max {:.3f}; below 0.5 cm: max |diff| {:.4f} cm\n",
             cases, rel_diffs.size(), pct(0.0), pct(0.1), pct(0.5), pct(0.9), pct(1.0), worst_small_abs);
  std::sort(largest.rbegin(), largest.rend());
  for (std::size_t i = 0; i < std::min<std::size_t>(5, largest.size()); ++i) {
    fmt::print("  largest relative difference {}: {:.2f} %  {}\n", i + 1, 100.0 * largest[i].first, largest[i].second);
  }
  EXPECT_LT(std::abs(pct(0.5)), 1.0);
  // SLAMMER's per-sample slip decisions only ever add displacement relative to the exact solution (README): a
  // topple result above SLAMMER's by more than round-off would be a bug of ours.
  EXPECT_LT(pct(1.0), 1e-6);
}

/// SLAMMER's rigid-block scheme, as pySLAMMER 0.2.3 writes it (rigid_analysis.py): per sample, trapezoidal
/// velocity and displacement, slip decided once per sample with a 1e-5 m/s velocity tolerance. Here only to show
/// where the differences above come from; never used by topple.
double slammer_scheme_cm(const GroundMotion& m, double ky_m_s2) {
  const auto a = m.accel_m_s2();
  const double dt = m.dt_s();
  double acc0 = 0.0, vel0 = 0.0, pos = 0.0;
  for (double ag : a) {
    double n;
    if (vel0 < 1e-5) {
      n = std::abs(ag) > ky_m_s2 ? ag / std::abs(ag) : ag / ky_m_s2;
    } else {
      n = 1.0;
    }
    double acc1 = ag - n * ky_m_s2;
    double vel1 = vel0 + dt / 2.0 * (acc1 + acc0);
    if (vel1 > 0.0) {
      pos += dt / 2.0 * (vel1 + vel0);
    } else {
      vel1 = 0.0;
      acc1 = 0.0;
    }
    vel0 = vel1;
    acc0 = acc1;
  }
  return 100.0 * pos;
}

TEST(SlammerVerification, LargestDifferenceIsSlammersDiscretisation) {
  // The largest gap (Northridge PAC-175, dt = 0.02 s, PGA 0.4 g, ky = 0.2, topple 7.5 % below SLAMMER): run
  // pySLAMMER's per-sample scheme on the same record linearly up-sampled by 1, 4, 16, 64. At factor 1 it lies
  // above the exact value as the published SLAMMER and pySLAMMER results do; as the step shrinks it converges to
  // topple's exact answer (which does not change under linear up-sampling).
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto dir = test::shared_dir() / "verification" / "slammer" / "slammer_library";
  io::ReadOptions opt;
  opt.format = io::Format::plain;
  opt.dt_s = 0.02;
  opt.units = "g";
  const GroundMotion rec = io::read_motion(dir / "Northridge_1994_PAC-175.txt", opt).scaled(0.4 / 0.415);  // eq.sql PGA 0.415 g
  const double ky = 0.2 * kStandardGravity;
  const double exact = 100.0 * slide_summary(rec, SlidingBlock::make(0.2, 0.2, 0.0, SlidingMode::one_way))
                                   .residual_displacement_m;
  std::vector<double> gaps;
  for (int factor : {1, 4, 16, 64}) {
    const GroundMotion fine = factor == 1 ? rec : rec.resampled(rec.dt_s() / factor);
    const double scheme = slammer_scheme_cm(fine, ky);
    if (factor == 1) {
      // At the record's own step the scheme overshoots like SLAMMER (1.6171 cm) and pySLAMMER (1.5614 cm) do.
      EXPECT_GT(scheme, exact + 0.03);
    }
    gaps.push_back(scheme - exact);
  }
  fmt::print("SLAMMER scheme minus exact on PAC-175 (cm), dt/1, /4, /16, /64: {:.5f} {:.5f} {:.5f} {:.5f}\n", gaps[0],
             gaps[1], gaps[2], gaps[3]);
  for (std::size_t i = 1; i < gaps.size(); ++i) EXPECT_LT(std::abs(gaps[i]), 0.5 * std::abs(gaps[i - 1]));
  EXPECT_LT(std::abs(gaps.back()), 0.005 * exact);
}

}  // namespace
}  // namespace topple
