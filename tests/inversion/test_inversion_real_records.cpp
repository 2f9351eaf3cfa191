// The recovery test on real records, fast variant (issue 18): a few surveys made from real accelerograms (outcomes
// from the solvers, 5 % of the observations misreported), inverted on a small grid, scored
// (tests/support/real_record_recovery.hpp). The full set (25 records x 4 PGAs on the default grid) is
// bench/recovery_real_records.cpp, its figures in docs/verification.md.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/real_record_recovery.hpp"
#include "support/shared_data.hpp"

#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"

namespace topple {
namespace {

// A small grid (12 x 10 cells, 12 motions) so that the six surveys take a few seconds on 2 cores.
const char* kSmallGrid = "pga_g = [0.02, 2.0, 12]\nfreq_hz = [0.3, 20.0, 10]\nmotions_per_cell = 12\n";

std::vector<recovery::RecordCase> three_records() {
  std::vector<recovery::RecordCase> out;
  for (const recovery::RecordCase& rc : recovery::real_records(test::shared_dir())) {
    // A low (Chi-Chi TCU068, 0.4 Hz), a middle (Kobe TAK, 1 Hz) and a high predominant frequency (Landers LCN, 4 Hz).
    if (rc.label == "Chi-Chi_1999_TCU068-090" || rc.label == "Kobe_1995_TAK-090" ||
        rc.label == "Landers_1992_LCN-345") {
      out.push_back(rc);
    }
  }
  return out;
}

// The survey says what the solvers say: the truth of a survey is the scaled record's PGA and its measured
// predominant frequency, and each object's outcome follows from slide_summary / rock_summary (checked here for one
// object of each kind against a direct call; no misreport at rate 0).
TEST(InversionRealRecords, SurveysHoldTheSolversOutcomesAndTheRecordsTruth) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared/records is absent";
  const recovery::RecordCase kobe = three_records().at(1);
  const GroundMotion record = io::read_motion(kobe.path);
  recovery::SurveyOptions options;
  options.misreport_rate = 0.0;
  options.inversion_toml = kSmallGrid;
  const recovery::SurveyCase sc = recovery::make_survey(record, kobe.label, 0.5, options);
  const GroundMotion scaled = record.scaled_to_pga(0.5 * kStandardGravity);
  EXPECT_EQ(sc.freq_hz, predominant_frequency_hz(scaled));  // the same function on the same samples: exact
  EXPECT_EQ(sc.misreports, 0);
  const Survey survey = io::parse_survey(sc.toml, "kobe.toml");
  ASSERT_EQ(survey.sites.size(), 1u);
  EXPECT_EQ(static_cast<int>(survey.sites[0].objects.size()), sc.objects);
  for (const ObservedObject& o : survey.sites[0].objects) {
    if (o.id == "bookend") {  // 10 x 15 cm block, b/h 0.67: at 0.5 g it cannot even uplift (needs 0.67 g)
      EXPECT_EQ(o.outcome, Outcome::not_rocked);
    }
    if (o.id == "lamp") {  // 8 x 50 cm block: compare with the rocking solver directly
      const RockingSummary s = rock_summary(scaled, RockingBody::block(0.08, 0.5), RockingOptions{});
      const Outcome expected = s.overturned ? Outcome::overturned
                               : s.max_abs_rotation_rad >= kVisibleRockingRad ? Outcome::rocked
                                                                               : Outcome::not_rocked;
      EXPECT_EQ(o.outcome, expected);
    }
    if (o.id == "pot") {  // mu in [0.15, 0.25] at 0.5 g: slides whatever mu was drawn
      EXPECT_EQ(o.outcome, Outcome::slid);
    }
  }
  EXPECT_TRUE(sc.moved);
}

recovery::Summary six_surveys(const std::string& family_line) {
  recovery::SurveyOptions options;
  options.inversion_toml = family_line + kSmallGrid;
  const std::vector<recovery::CaseScore> scores =
      recovery::run(three_records(), {0.2, 0.5}, options, InversionOptions{});
  const recovery::Summary m = recovery::summarise(scores);
  fmt::print("{}", recovery::markdown(scores, m));
  return m;
}

// Six surveys (three records at 0.2 and 0.5 g) on a small grid, scored against the targets. The figures
// measured are asserted with the margins stated at each line (one survey of six is 17 %); the issue's own targets
// only where they already hold. Clough-Penzien family (the default), measured: PGA 95 % 6/6, 68 % 4/6, median/truth
// median 0.71, frequency 95 % 6/6, closed 0/6.
TEST(InversionRealRecords, SixSurveysWithTheCloughPenzienFamily) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared/records is absent";
  const recovery::Summary m = six_surveys("");
  ASSERT_EQ(m.surveys, 6);
  EXPECT_GE(m.pga_cov95, 5.0 / 6.0 - 1e-9);  // the issue's >= 90 % (one miss of six allowed: 83 %)
  EXPECT_GE(m.pga_cov68, 3.0 / 6.0 - 1e-9);  // measured 4/6; one survey of margin
  EXPECT_GE(m.freq_cov95, 5.0 / 6.0 - 1e-9);  // the issue's >= 85 %, one miss of six allowed
  EXPECT_GT(m.median_ratio_median, 0.5);      // measured 0.71: the coarse grid (1.5x cells) snaps the medians
  EXPECT_LT(m.median_ratio_median, 1.0);
}

// The same six surveys with the stochastic point-source family (issue 32; motion/stochastic.hpp), asserted as above
// with the same margins. Measured: PGA 95 % 6/6, 68 % 4/6, median/truth median 0.77 (Clough-Penzien 0.71), frequency
// 95 % 6/6, closed 0/6; the 75-survey figures are in docs/verification.md.
TEST(InversionRealRecords, SixSurveysWithTheBoore2003Family) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared/records is absent";
  const recovery::Summary m = six_surveys("family = \"boore2003\"\n");
  ASSERT_EQ(m.surveys, 6);
  EXPECT_GE(m.pga_cov95, 5.0 / 6.0 - 1e-9);
  EXPECT_GE(m.pga_cov68, 3.0 / 6.0 - 1e-9);
  EXPECT_GE(m.freq_cov95, 5.0 / 6.0 - 1e-9);
  EXPECT_GT(m.median_ratio_median, 0.5);
  EXPECT_LT(m.median_ratio_median, 1.0);
}

}  // namespace
}  // namespace topple
