// Peer check against USGS SLAMMER 1.1's published flexible sliding-mass results (../shared/verification/slammer):
// 1026 + 1026 linear-elastic and 234 + 234 equivalent-linear decoupled and coupled analyses, each in normal and
// inverse polarity, one-way sliding, records scaled as SLAMMER did (target PGA / eq.sql's rounded PGA).
//
// Criteria (pySLAMMER's verification_config.toml): displacement within 2 % or 1 cm (0.05 cm when SLAMMER's value is
// below 0.5 cm); k_max within 5 %, final V_s within 2 %, final damping within 10 %. topple integrates the modal
// response exactly for the piecewise-linear record and locates slip events inside steps; SLAMMER uses Newmark's
// average-acceleration scheme and per-sample slip decisions at the record's dt, so the two differ by SLAMMER's
// discretisation error (docs/verification.md shows it converging to topple's numbers as dt shrinks).
//
// The ctest case runs every 7th analysis (all four kinds, about 1/7 of the suite); the full suite is the disabled
// case, run by scripts/verify-slammer-flexible.sh, whose output docs/verification.md quotes.
#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/shared_data.hpp"
#include "support/slammer_suite.hpp"
#include "topple/solvers/flexible.hpp"

namespace topple {
namespace {

struct KindStats {
  int analyses = 0;
  int results = 0;            // displacement results (2 per analysis)
  int pass = 0;
  int kmax_pass = 0, vs_pass = 0, damping_pass = 0;
  std::vector<double> rel;    // (topple - SLAMMER) / SLAMMER, SLAMMER >= 0.5 cm
  std::vector<std::string> failures;
};

std::map<std::string, KindStats> run_suite(int stride) {
  test::SlammerSuite suite;
  std::map<std::string, KindStats> stats;
  int index = 0;
  for (const auto& analysis : suite.results().at("analyses")) {
    const std::string method = analysis.at("analysis").at("method");
    if (method == "rigid") continue;
    if (index++ % stride != 0) continue;
    const std::string soil = analysis.at("analysis").at("mode");
    const auto& site = analysis.at("site_parameters");
    const auto& res = analysis.at("results");
    std::optional<double> ref_strain;
    if (site.contains("reference_strain")) ref_strain = site.at("reference_strain").get<double>() / 100.0;  // %
    const SlidingMassColumn column =
        SlidingMassColumn::make(site.at("height_m").get<double>(), site.at("vs_slope_mps").get<double>(),
                                site.at("vs_base_mps").get<double>(), site.at("damping_ratio").get<double>(), ref_strain);
    const double ky = site.at("ky_g").get<double>();
    const FlexibleAnalysis kind = method == "coupled" ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled;
    const GroundMotion record = suite.scaled_record(analysis);
    KindStats& st = stats[method + " " + soil];
    ++st.analyses;
    FlexibleSummary first;
    for (const bool inverse : {false, true}) {
      const FlexibleSummary r = slide_flexible(inverse ? record.inverted() : record, column, ky, kind);
      if (!inverse) first = r;
      const double ours = 100.0 * r.sliding.residual_displacement_m;
      const double theirs = res.at(inverse ? "inverse_displacement_cm" : "normal_displacement_cm").get<double>();
      ++st.results;
      if (test::within_slammer_criterion(ours, theirs)) {
        ++st.pass;
      } else {
        st.failures.push_back(fmt::format("{} {} H {} ky {} PGA {} {} ref {}: topple {:.4f} cm, SLAMMER {:.4f} cm",
                                          analysis.at("analysis_id").get<std::string>(),
                                          test::SlammerSuite::record_file(analysis), site.at("height_m").get<double>(),
                                          ky, analysis.at("ground_motion_parameters").at("target_pga_g").get<double>(),
                                          inverse ? "inverse" : "normal", ref_strain.value_or(0.0), ours, theirs));
      }
      if (theirs >= 0.5) st.rel.push_back((ours - theirs) / theirs);
    }
    const auto rel_ok = [](double ours, double theirs, double tol) { return std::abs(ours - theirs) <= tol * std::abs(theirs); };
    if (rel_ok(first.kmax, res.at("kmax").get<double>(), 0.05)) {
      ++st.kmax_pass;
    } else {
      st.failures.push_back(fmt::format("{} kmax: topple {:.5f}, SLAMMER {:.5f}", analysis.at("analysis_id").get<std::string>(),
                                        first.kmax, res.at("kmax").get<double>()));
    }
    if (rel_ok(first.mode.vs_m_s, res.at("vs_final_mps").get<double>(), 0.02)) ++st.vs_pass;
    if (rel_ok(first.mode.damping_ratio, res.at("damping_final").get<double>(), 0.10)) ++st.damping_pass;
  }
  for (auto& [name, st] : stats) {
    std::sort(st.rel.begin(), st.rel.end());
    const auto pct = [&](double q) {
      return st.rel.empty() ? 0.0 : 100.0 * st.rel[static_cast<std::size_t>(q * static_cast<double>(st.rel.size() - 1))];
    };
    fmt::print("SLAMMER {:<28} {:4d} analyses, displacement {:4d}/{:4d} pass; kmax {}/{}, Vs {}/{}, damping {}/{}; "
               "(topple - SLAMMER)/SLAMMER over 0.5 cm in %: p1 {:.2f} p10 {:.2f} median {:.3f} p90 {:.2f} p99 {:.2f}\n",
               name, st.analyses, st.pass, st.results, st.kmax_pass, st.analyses, st.vs_pass, st.analyses,
               st.damping_pass, st.analyses, pct(0.01), pct(0.1), pct(0.5), pct(0.9), pct(0.99));
    for (std::size_t i = 0; i < st.failures.size(); ++i) fmt::print("   fails: {}\n", st.failures[i]);
  }
  return stats;
}

/// SLAMMER's flexible schemes, as pySLAMMER 0.2.3 writes them (decoupled_analysis.py, coupled_analysis.py), in
/// topple's sign convention: Newmark's average-acceleration method (beta = 1/4, gamma = 1/2) on the modal equation at
/// the record's dt; decoupled sliding by SLAMMER's per-sample rule; coupled sliding with the effective modal mass
/// switched per sample, trapezoidal slip integration and a linear sub-step at slip stop. Here only to show where
/// the differences with topple come from (SLAMMER's discretisation); never used by topple.
struct SchemeInput {
  double omega = 0.0, zeta = 0.0, ky_m_s2 = 0.0;
};
constexpr double kP = 4.0 / kPi;  // L1/M1
constexpr double kQ = 2.0 / kPi;  // L1/m

double slammer_decoupled_scheme_cm(const GroundMotion& m, const SchemeInput& in) {
  const auto a = m.accel_m_s2();
  const double dt = m.dt_s();
  const double beta = 0.25, gamma = 0.5, w2 = in.omega * in.omega, c = 2.0 * in.zeta * in.omega;
  const double k_eff = w2 + c * gamma / (beta * dt) + 1.0 / (beta * dt * dt);
  const double a_coef = 1.0 / (beta * dt) + c * gamma / beta;
  const double b_coef = 1.0 / (2.0 * beta) + dt * c * (gamma / (2.0 * beta) - 1.0);
  std::vector<double> hea(a.size());
  double u = 0.0, v = 0.0, acc = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double da = i == 0 ? 0.0 : a[i] - a[i - 1];
    const double du = (-kP * da + a_coef * v + b_coef * acc) / k_eff;
    const double dv = gamma / (beta * dt) * du - gamma / beta * v + dt * (1.0 - gamma / (2.0 * beta)) * acc;
    const double dacc = du / (beta * dt * dt) - v / (beta * dt) - 0.5 / beta * acc;
    u += du;
    v += dv;
    acc += dacc;
    hea[i] = a[i] + kQ * acc;
  }
  // Sliding: the block lags with relative velocity w >= 0 while sliding; trapezoid-exact on linear HEA per sample.
  bool slide = false;
  double w = 0.0, d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const std::size_t prev = i == 0 ? 0 : i - 1;
    const double excess = hea[prev] - in.ky_m_s2;
    const double dh = hea[i] - hea[prev];
    if (!slide) {
      if (hea[i] > in.ky_m_s2) slide = true;
    } else {
      const double w_new = w + (excess + 0.5 * dh) * dt;
      d += w * dt + 0.5 * (excess - dh / 6.0) * dt * dt;  // SLAMMER's sign on the dh term, kept
      w = w_new;
      if (w <= 0.0) {
        slide = false;
        w = 0.0;
      }
    }
  }
  return 100.0 * d;
}

double slammer_coupled_scheme_cm(const GroundMotion& m, const SchemeInput& in) {
  const auto a = m.accel_m_s2();
  const double dt = m.dt_s();
  const double beta = 0.25, gamma = 0.5, w2 = in.omega * in.omega, c = 2.0 * in.zeta * in.omega;
  const double d1_slip = 1.0 - kP * kQ;
  const double ky = in.ky_m_s2;
  bool slide = false;
  double y1 = 0, v1 = 0, acc1 = 0, s1 = 0, sd1 = 0, sdd1 = 0;
  double y2 = 0, v2 = 0, acc2 = 0, s2 = 0, sd2 = 0, sdd2 = 0;
  // One Newmark step of the modal equation m_eff Y'' + c Y' + w2 Y = -p f from (y1, v1, acc1), load f1 -> f2.
  const auto newmark = [&](double f1, double f2, double h) {
    const double me = slide ? d1_slip : 1.0;
    const double khat = w2 + c * gamma / (beta * h) + me / (beta * h * h);
    const double ac = me / (beta * h) + c * gamma / beta;
    const double bc = me / (2.0 * beta) + h * c * (gamma / (2.0 * beta) - 1.0);
    const double du = (-kP * (f2 - f1) + ac * v1 + bc * acc1) / khat;
    const double dv = gamma / (beta * h) * du - gamma / beta * v1 + h * (1.0 - gamma / (2.0 * beta)) * acc1;
    y2 = y1 + du;
    v2 = v1 + dv;
    acc2 = (-kP * f2 - c * v2 - w2 * y2) / me;
  };
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (i > 0) {
      y1 = y2; v1 = v2; acc1 = acc2; s1 = s2; sd1 = sd2; sdd1 = sdd2;
    }
    // Load of the mode: the ground acceleration while stuck, the friction level while slipping.
    const double f1 = i == 0 ? 0.0 : (slide ? ky : a[i - 1]);
    const double f2 = slide ? ky : a[i];
    newmark(f1, f2, dt);
    if (slide) {
      sdd2 = a[i] - ky + kQ * acc2;
      sd2 = sd1 + 0.5 * dt * (sdd2 + sdd1);
      s2 = s1 + 0.5 * dt * (sd2 + sd1);
    }
    const double demand = a[i] + kQ * acc2;
    if (!slide) {
      if (demand > ky) slide = true;
    } else if (sd2 <= 0.0) {
      // Slip stop inside the step, at the fraction where the trapezoidal velocity crosses zero.
      const double frac = -sd1 / (sd2 - sd1);
      if (frac != 0.0) {
        const double h = frac * dt;
        const double a_stop = a[i - 1] + frac * (a[i] - a[i - 1]);
        y1 = y2; v1 = v2; acc1 = acc2;  // SLAMMER carries the end-of-step slipping state into the sub-step
        sdd2 = a_stop - ky + kQ * acc2;
        sd2 = sd1 + 0.5 * h * (sdd2 + sdd1);
        s2 = s1 + 0.5 * h * (sd1 + sd2);
        // The rest of the step stuck: Newmark in acceleration form from the friction load to the ground's.
        const double rest = (1.0 - frac) * dt;
        const double khat = 1.0 + c * gamma * rest + w2 * beta * rest * rest;
        const double ac = d1_slip + c * rest * (gamma - 1.0) + w2 * rest * rest * (beta - 0.5);
        const double dp = -kP * (a[i] - ky) + ac * acc1 - w2 * rest * v1;
        acc2 = dp / khat;
        v2 = v1 + (1.0 - gamma) * rest * acc1 + gamma * rest * acc2;
        y2 = y1 + v1 * rest + (0.5 - beta) * rest * rest * acc1 + beta * rest * rest * acc2;
      }
      slide = false;
      sd2 = 0.0;
      sdd2 = 0.0;
    }
  }
  return 100.0 * s2;
}

/// pySLAMMER's group criterion (95 % of results within the individual criterion), applied per analysis kind, and the
/// same share for k_max, V_s and damping; the median signed difference over 0.5 cm must be under 0.5 % (topple is
/// not biased against SLAMMER where SLAMMER's own discretisation error is small).
void expect_group_criteria(const KindStats& st) {
  EXPECT_GE(st.pass, 0.95 * st.results);
  EXPECT_GE(st.kmax_pass, 0.95 * st.analyses);
  EXPECT_GE(st.vs_pass, 0.95 * st.analyses);
  EXPECT_GE(st.damping_pass, 0.95 * st.analyses);
  ASSERT_FALSE(st.rel.empty());
  EXPECT_LT(std::abs(st.rel[st.rel.size() / 2]), 0.005);
}

TEST(SlammerFlexible, EverySeventhAnalysis) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto stats = run_suite(7);
  ASSERT_EQ(stats.size(), 4u);
  for (const auto& [name, st] : stats) {
    SCOPED_TRACE(name);
    EXPECT_GE(st.analyses, 33);
    expect_group_criteria(st);
  }
}

/// One published case against SLAMMER's scheme run at the record's dt / f.
struct SchemeCase {
  const char* id;
  bool inverse;
};

TEST(SlammerFlexible, LargestDifferencesAreSlammersDiscretisation) {
  // The largest coupled gaps (H = 5 m: omega dt = 3.8 at dt = 0.02 s, where Newmark's period error is large) and two
  // large decoupled ones. SLAMMER's scheme (above) at the record's own dt reproduces SLAMMER's published coupled
  // linear-elastic numbers to their printed digits and its decoupled ones within 1.5 %; on the record linearly up-sampled by 4,
  // 16 and 64 it converges to topple's answer, which does not depend on the up-sampling.
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  test::SlammerSuite suite;
  const std::vector<SchemeCase> cases{{"analysis_0018_coupled", false}, {"analysis_0028_coupled", false},
                                      {"analysis_0108_coupled", true},  {"analysis_1180_coupled", true},
                                      {"analysis_0036_decoupled", true}, {"analysis_0190_decoupled", true}};
  int found = 0;
  for (const auto& an : suite.results().at("analyses")) {
    const std::string id = an.at("analysis_id");
    const auto c = std::find_if(cases.begin(), cases.end(), [&](const SchemeCase& x) { return id == x.id; });
    if (c == cases.end()) continue;
    ++found;
    const auto& site = an.at("site_parameters");
    std::optional<double> ref;
    if (site.contains("reference_strain")) ref = site.at("reference_strain").get<double>() / 100.0;
    const SlidingMassColumn col = SlidingMassColumn::make(site.at("height_m").get<double>(), site.at("vs_slope_mps").get<double>(),
                                                          site.at("vs_base_mps").get<double>(), site.at("damping_ratio").get<double>(), ref);
    GroundMotion rec = suite.scaled_record(an);
    if (c->inverse) rec = rec.inverted();
    const double ky = site.at("ky_g").get<double>();
    const bool coupled = an.at("analysis").at("method") == "coupled";
    const FlexibleSummary r = slide_flexible(rec, col, ky, coupled ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled);
    const double ours = 100.0 * r.sliding.residual_displacement_m;
    const double slammer = an.at("results").at(c->inverse ? "inverse_displacement_cm" : "normal_displacement_cm").get<double>();
    const SchemeInput in{r.mode.omega_rad_s, r.mode.damping_ratio, ky * kStandardGravity};
    std::vector<double> scheme;
    for (const int f : {1, 4, 16, 64}) {
      const GroundMotion fine = f == 1 ? rec : rec.resampled(rec.dt_s() / f);
      scheme.push_back(coupled ? slammer_coupled_scheme_cm(fine, in) : slammer_decoupled_scheme_cm(fine, in));
    }
    fmt::print("{} {}: topple {:.4f} cm, SLAMMER {:.4f} cm; SLAMMER's scheme at dt/1, /4, /16, /64: {:.4f} {:.4f} "
               "{:.4f} {:.4f}\n", id, c->inverse ? "inverse" : "normal", ours, slammer, scheme[0], scheme[1], scheme[2], scheme[3]);
    SCOPED_TRACE(id);
    // Reproduction: the coupled scheme gives SLAMMER's printed digits on linear-elastic cases (1e-4 is their last
    // digit) and within 0.1 % on equivalent-linear ones (we feed it topple's converged properties, from an exact
    // rather than a Newmark response); the decoupled port is within 1.5 % of SLAMMER.
    EXPECT_NEAR(scheme[0], slammer, (coupled ? (ref ? 1e-3 : 1e-4) : 0.015) * slammer);
    EXPECT_GT(std::abs(scheme[0] - ours), 0.02 * ours);  // the published gap is real at dt...
    // ... and closes as the scheme's dt shrinks: to 0.1 % of topple's value, a tenth of the gap at dt. (topple's own
    // decoupled value carries its O(h^2) interpolation error, 0.07 % here, so the closing need not be monotone.)
    EXPECT_LT(std::abs(scheme[3] - ours), 1e-3 * ours);
    EXPECT_LT(std::abs(scheme[3] - ours), 0.1 * std::abs(scheme[0] - ours));
  }
  EXPECT_EQ(found, 6);
}

TEST(SlammerFlexible, DISABLED_FullSuite) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared not present";
  const auto stats = run_suite(1);
  int analyses = 0;
  for (const auto& [name, st] : stats) {
    SCOPED_TRACE(name);
    analyses += st.analyses;
    expect_group_criteria(st);
  }
  EXPECT_EQ(analyses, 2520);
}

}  // namespace
}  // namespace topple

