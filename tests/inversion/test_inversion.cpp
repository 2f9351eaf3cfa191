// Inversion of field observations: static bounds by hand, honesty, and recovery of known shaking.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/observed_objects.hpp"
#include "support/shared_data.hpp"

#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/inversion/evidence.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/output/plot.hpp"
#include "topple/output/report.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/inversion/matching.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/synthesis.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple {
namespace {

using testing::block;

TEST(StaticBounds, HandComputedValues) {
  Site site;
  site.objects.push_back(block("slid-03", 0.2, 0.2, {0.3, 0.3}, Outcome::slid));             // lower mu g = 0.30
  site.objects.push_back(block("rocked", 0.10, 0.25, {0.6, 0.6}, Outcome::rocked));          // lower a/h = 0.40
  site.objects.push_back(block("fell", 0.05, 0.25, {0.6, 0.6}, Outcome::overturned));        // lower a/h = 0.20
  site.objects.push_back(block("stuck", 0.3, 0.3, {0.5, 0.6}, Outcome::not_slid));           // upper mu_hi = 0.60
  site.objects.push_back(block("standing", 0.1, 0.5, {0.6, 0.6}, Outcome::not_overturned));  // no static bound
  auto amplified = block("shelf", 0.2, 0.2, {0.5, 0.5}, Outcome::slid);
  amplified.amplification = {1.0, 1.25};                                                   // lower 0.5 / 1.25 = 0.40
  site.objects.push_back(amplified);
  const StaticBounds b = static_bounds(site);
  ASSERT_TRUE(b.lower_g && b.upper_g);
  EXPECT_NEAR(*b.lower_g, 0.40, 1e-12);
  EXPECT_NEAR(*b.upper_g, 0.60, 1e-12);
  EXPECT_EQ(b.lower.size(), 4u);
  EXPECT_EQ(b.upper.size(), 1u);
  EXPECT_NEAR(b.lower[2].pga_g, 0.2, 1e-12);
  EXPECT_TRUE(b.contradictions.empty());
}

// "Stood and did not visibly rock" (issue 18): a soft upper threshold g a/h divided by the smallest amplification,
// never called hard (an excursion above g a/h may tilt the body less than kVisibleRockingRad).
TEST(StaticBounds, NotRockedIsASoftUpperThresholdAtGaOverH) {
  Site site;
  auto o = block("candle", 0.05, 0.25, {0.6, 0.6}, Outcome::not_rocked);  // a/h = 0.025/0.125 = 0.20
  o.amplification = {1.25, 1.5};                                          // upper 0.20 / 1.25 = 0.16
  site.objects.push_back(o);
  const StaticBounds b = static_bounds(site);
  ASSERT_EQ(b.upper.size(), 1u);
  EXPECT_TRUE(b.lower.empty());
  EXPECT_NEAR(b.upper[0].pga_g, 0.16, 1e-12);  // hand value; tan(alpha) = a/h exactly for a block
  EXPECT_FALSE(b.upper[0].hard);
  ASSERT_TRUE(b.upper_g.has_value());
  EXPECT_NEAR(*b.upper_g, 0.16, 1e-12);
  EXPECT_FALSE(b.hard_upper_g.has_value());
  EXPECT_NE(b.upper[0].reason.find("did not rock visibly"), std::string::npos) << b.upper[0].reason;
}

// not_rocked, rocked and overturned partition every run (each run matches exactly one), and not_rocked agrees with
// the rocking solver run directly: the peak tilt stayed below kVisibleRockingRad.
TEST(InversionSteps, NotRockedMatchesRunsThatStayBelowTheVisibleTilt) {
  const auto body = RockingBody::block(0.10, 0.40);  // a/h = 0.25
  int below = 0;
  int visible = 0;
  for (const double pga_g : {0.15, 0.24, 0.26, 0.3, 0.5, 0.9}) {
    SynthesisSpec spec;
    spec.pga_m_s2 = pga_g * kStandardGravity;
    spec.predominant_frequency_hz = 3.0;
    spec.duration_s = 8.0;
    spec.dt_s = 0.01;
    spec.seed = 5;
    const GroundMotion motion = synthesize(spec);
    double sum = 0.0;
    for (const Outcome outcome : {Outcome::not_rocked, Outcome::rocked, Outcome::overturned}) {
      ObservedObject o = block("b", 0.10, 0.40, {0.6, 0.6}, outcome);
      sum += observation_match(o, draw_parameters(o, 1, 0, 0), motion, kStandardGravity);
    }
    EXPECT_EQ(sum, 1.0) << pga_g;  // 0/1 outcomes: exactly one matches
    ObservedObject o = block("b", 0.10, 0.40, {0.6, 0.6}, Outcome::not_rocked);
    const DrawnParameters p = draw_parameters(o, 1, 0, 0);
    RockingOptions options;  // as the inversion runs it (src/inversion/inversion.cpp): 1e-6 suffices for a verdict
    options.rel_tol = 1e-6;
    options.max_run_out_s = 20.0;
    if (!o.e_housner) {
      options.restitution = RestitutionMode::given;
      options.e = p.e;
    }
    const RockingSummary s = rock_summary(motion, body, options);
    const bool stayed = !s.overturned && s.max_abs_rotation_rad < kVisibleRockingRad;
    EXPECT_EQ(observation_match(o, p, motion, kStandardGravity), stayed ? 1.0 : 0.0) << pga_g;
    (stayed ? below : visible) += 1;
    if (pga_g < 0.25) {
      EXPECT_TRUE(stayed) << "no uplift below g a/h (Housner), so no visible tilt: " << pga_g;
    }
  }
  EXPECT_GT(below, 0);
  EXPECT_GT(visible, 0);  // the grid exercises both verdicts
}

TEST(StaticBounds, ContradictionsNameBothObjects) {
  Site site;
  site.objects.push_back(block("box", 0.2, 0.2, {0.2, 0.2}, Outcome::not_slid));
  site.objects.push_back(block("pan", 0.2, 0.2, {0.35, 0.35}, Outcome::slid));
  const StaticBounds b = static_bounds(site);
  ASSERT_EQ(b.contradictions.size(), 1u);
  EXPECT_NE(b.contradictions[0].find("pan"), std::string::npos);
  EXPECT_NE(b.contradictions[0].find("box"), std::string::npos);
}

std::string survey_text(const std::string& object) {
  return "[site]\nname = \"t\"\n[[object]]\nid = \"ok\"\nshape = \"block\"\nwidth = \"8cm\"\nheight = \"30cm\"\n"
         "mu = 0.5\noutcome = \"overturned\"\n[[object]]\n" + object;
}

void expect_error(const std::string& object, const std::string& field, const std::string& words) {
  try {
    (void)io::parse_survey(survey_text(object), "survey.toml");
    ADD_FAILURE() << "accepted: " << object;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("survey.toml"), std::string::npos) << msg;
    EXPECT_NE(msg.find(field), std::string::npos) << msg;
    EXPECT_NE(msg.find(words), std::string::npos) << msg;
  }
}

TEST(SurveyFile, BadObjectsAreNamedWithTheirField) {
  expect_error("id = \"b\"\nshape = \"pyramid\"\nwidth = \"1cm\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2](b).shape", "unknown shape 'pyramid'");
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = \"1cm\"\nmu = 0.5\noutcome = \"slid\"\n", "object[2](b).height",
               "needs its height");
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = \"-1cm\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2](b).width", "positive");
  // "fell" and "toppled" are documented aliases of overturned (docs/survey.md); a word outside the list is refused.
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = \"1cm\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"wobbled\"\n",
               "object[2](b).outcome", "unknown outcome 'wobbled'");
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = 8\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2](b).width", "unit");
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = \"8 furlongs\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2](b).width", "unknown length unit");
  expect_error("id = \"b\"\nshape = \"block\"\nwidht = \"8cm\"\nwidth = \"8cm\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2](b).widht", "unknown key");
  expect_error("id = \"b\"\nshape = \"cylinder\"\ndiameter = \"8cm\"\nheight = \"2cm\"\noutcome = \"slid\"\n",
               "object[2](b).mu", "friction coefficient is required");
  expect_error("id = \"b\"\nshape = \"block\"\nwidth = \"8cm\"\nheight = \"2cm\"\nmu = [0.6, 0.4]\noutcome = \"slid\"\n",
               "object[2](b).mu", "low > high");
  expect_error("id = \"ok\"\nshape = \"block\"\nwidth = \"8cm\"\nheight = \"2cm\"\nmu = 0.5\noutcome = \"slid\"\n",
               "object[2].id", "duplicate");
}

TEST(SurveyFile, ExampleParses) {
  const Survey s = io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "survey.toml");
  ASSERT_EQ(s.sites.size(), 1u);
  EXPECT_EQ(s.sites[0].objects.size(), 8u);
  EXPECT_EQ(s.inversion.pga_count, 30);
  EXPECT_EQ(s.inversion.freq_count, 25);
  EXPECT_EQ(s.inversion.motions_per_cell, 40);
  EXPECT_NEAR(s.sites[0].objects[0].body.a_m, 0.04, 1e-15);
  EXPECT_DOUBLE_EQ(s.sites[0].objects[0].amplification.high, 1.3);
}

TEST(SurveyFile, NotRockedIsAnOutcomeOfARockingObject) {
  const Survey s = io::parse_survey("[[object]]\nid = \"vase\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                                    "outcome = \"not_rocked\"\n", "s.toml");
  EXPECT_EQ(s.sites[0].objects[0].outcome, Outcome::not_rocked);
  EXPECT_EQ(outcome_name(Outcome::not_rocked), "not_rocked");
  try {
    (void)io::parse_survey("[[object]]\nid = \"v\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                           "outcome = \"wobbled\"\n", "s.toml");
    FAIL() << "an unknown outcome must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not_rocked"), std::string::npos) << e.what();  // listed among the known
  }
}

// Documented defaults (docs/survey.md) that old surveys rely on: a missing shape is a block, a missing site name is
// "site N". Dangerous guesses are errors (test_cli_invert: a diameter or a/h/D without a shape).
TEST(SurveyFile, MissingShapeIsABlockAndMissingNameIsSiteN) {
  const Survey one = io::parse_survey("[[object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                                      "outcome = \"overturned\"\n", "s.toml");
  ASSERT_EQ(one.sites.size(), 1u);
  EXPECT_EQ(one.sites[0].name, "site 1");
  EXPECT_EQ(one.sites[0].objects[0].body.shape, RockingBody::Shape::block);
  EXPECT_DOUBLE_EQ(one.sites[0].objects[0].body.a_m, 0.05);  // half the width
  const std::string object = "[[sites.object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\n"
                             "outcome = \"overturned\"\n";
  const Survey two = io::parse_survey("[[sites]]\nname = \"north\"\n" + object + "[[sites]]\n" + object, "s.toml");
  ASSERT_EQ(two.sites.size(), 2u);
  EXPECT_EQ(two.sites[0].name, "north");
  EXPECT_EQ(two.sites[1].name, "site 2");
}

// The sliding-distance uncertainty: max(given, 25 % of slid, 2 mm) (docs/survey.md), said in Survey::notes only when
// a given value is raised.
TEST(SurveyFile, SlidingUncertaintyFloorIsDocumentedAndSaid) {
  ObservedObject o;
  o.outcome = Outcome::slid;
  o.slid_m = 0.04;
  EXPECT_DOUBLE_EQ(sliding_sigma_m(o), 0.01);  // 25 % of 4 cm
  o.slid_uncertainty_m = 0.02;
  EXPECT_DOUBLE_EQ(sliding_sigma_m(o), 0.02);  // a larger given value is kept
  o.slid_m = 0.004;
  o.slid_uncertainty_m = 0.0;
  EXPECT_DOUBLE_EQ(sliding_sigma_m(o), kVisibleSlipM);  // 25 % of 4 mm is 1 mm: the 2 mm floor
  const std::string head = "[[object]]\nid = \"pot\"\nshape = \"cylinder\"\ndiameter = \"25cm\"\nheight = \"15cm\"\n"
                           "mu = 0.25\noutcome = \"slid\"\nslid = \"4cm\"\n";
  EXPECT_TRUE(io::parse_survey(head, "s.toml").notes.empty());  // the default: documented, not a change
  EXPECT_TRUE(io::parse_survey(head + "slid_uncertainty = \"1cm\"\n", "s.toml").notes.empty());  // 25 % exactly
  const Survey raised = io::parse_survey(head + "slid_uncertainty = \"3mm\"\n", "s.toml");
  ASSERT_EQ(raised.notes.size(), 1u);
  EXPECT_NE(raised.notes[0].find("s.toml:9: object[1](pot).slid_uncertainty"), std::string::npos) << raised.notes[0];
  EXPECT_NE(raised.notes[0].find("used is 1 cm"), std::string::npos) << raised.notes[0];
}

// The edge loads the records (read_survey), the text parser reads no file (parse_survey: fuzz-safe), and the core
// takes what was loaded.
TEST(SurveyFile, RecordsAreLoadedAtTheEdgeNotByTheParser) {
  if (!test::have_shared()) GTEST_SKIP() << "../shared/records is absent";
  const std::filesystem::path record = test::shared_record("CPM000.AT2");
  const std::string text = "[inversion]\nfamily = \"records\"\nrecords = [\"" + record.string() + "\"]\n"
                           "pga_g = [0.1, 1.0, 3]\nfreq_hz = [1.0, 4.0, 2]\n"
                           "[[object]]\nid = \"b\"\nwidth = \"10cm\"\nheight = \"40cm\"\nmu = 0.5\noutcome = \"overturned\"\n";
  const Survey parsed = io::parse_survey(text, "s.toml");
  EXPECT_EQ(parsed.inversion.records.size(), 1u);
  EXPECT_TRUE(parsed.inversion.record_motions.empty());
  test::TempDir tmp;
  test::write_file(tmp.path() / "s.toml", text);
  const Survey read = io::read_survey(tmp.path() / "s.toml");
  ASSERT_EQ(read.inversion.record_motions.size(), 1u);
  EXPECT_EQ(read.inversion.record_motions[0]->size(), io::read_motion(record).size());
  const FamilyGrid family = build_family(read.inversion, {1.0, 4.0});
  ASSERT_EQ(family.motions_per_column(), 2u);  // one record, both polarities
  EXPECT_NEAR(family.measured_freq_hz[1], 4.0, 4e-3);  // time-scaled onto the column (peak interpolation: 1e-3)
}

TEST(InversionSettingsCheck, FrequencyAxisMustBeWithinTheFamilysReach) {
  InversionSettings st;
  EXPECT_NO_THROW(validate_inversion_settings(st));  // the defaults: 0.3 to 20 Hz
  st.freq_max_hz = 1000.0;
  try {
    validate_inversion_settings(st);
    FAIL() << "1000 Hz accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "inversion.freq_hz");
    EXPECT_NE(e.problem().find("1000 Hz"), std::string::npos) << e.what();
  }
  st.freq_max_hz = 20.0;
  st.freq_min_hz = 0.1;
  EXPECT_THROW(validate_inversion_settings(st), InputError);
  st.freq_min_hz = 0.3;
  st.family = MotionFamily::records;  // records are time-scaled to any frequency, but there must be some
  EXPECT_THROW(validate_inversion_settings(st), InputError);
  st.records = {"a.AT2"};
  EXPECT_NO_THROW(validate_inversion_settings(st));
  EXPECT_THROW((void)build_family(st, {1.0}), InputError);  // named but not loaded: the core reads no file
  InversionOptions bad;
  bad.threads = -1;
  EXPECT_THROW(validate_inversion_options(bad), InputError);
}

// The record-like family (issue 18) is chosen by name; a survey without the key, or naming "synthetic", keeps the
// Clough-Penzien family; an unknown name lists the three.
TEST(InversionSettingsCheck, Rezaeian2010FamilyIsChosenByNameAndOldSurveysKeepTheirMeaning) {
  const std::string objects = "[[object]]\nid = \"a\"\nwidth = \"5cm\"\nheight = \"20cm\"\nmu = 0.5\n"
                              "outcome = \"overturned\"\n";
  const auto family_of = [&](const std::string& inversion) {
    return io::parse_survey("[site]\nname = \"x\"\n" + inversion + objects, "f.toml").inversion.family;
  };
  EXPECT_EQ(family_of(""), MotionFamily::synthetic);
  EXPECT_EQ(family_of("[inversion]\nfamily = \"synthetic\"\n"), MotionFamily::synthetic);
  EXPECT_EQ(family_of("[inversion]\nfamily = \"rezaeian2010\"\n"), MotionFamily::rezaeian2010);
  EXPECT_EQ(motion_family_name(MotionFamily::rezaeian2010), "rezaeian2010");
  try {
    (void)family_of("[inversion]\nfamily = \"boore\"\n");
    FAIL() << "unknown family accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "inversion.family");
    EXPECT_NE(e.problem().find("rezaeian2010"), std::string::npos) << e.what();
  }
  // Its frequency axis: 0.1 to 25 Hz.
  InversionSettings st;
  st.family = MotionFamily::rezaeian2010;
  EXPECT_NO_THROW(validate_inversion_settings(st));
  st.freq_max_hz = 30.0;
  EXPECT_THROW(validate_inversion_settings(st), InputError);
  // Every motion of a column has the column's measured predominant frequency (time-scaled onto it: the measurement
  // moves by less than the spectrum's peak interpolation, 1e-3 relative, as for the other families) and unit PGA.
  st.freq_max_hz = 20.0;
  st.motions_per_cell = 4;
  for (const double f : {0.5, 3.0}) {
    const std::vector<GroundMotion> motions = family_motions(st, f);
    ASSERT_EQ(motions.size(), 4u);
    for (const GroundMotion& m : motions) {
      EXPECT_NEAR(predominant_frequency_hz(m), f, 1e-3 * f);
      EXPECT_NEAR(m.pga_m_s2(), 1.0, 1e-12);
    }
  }
}

// build_family makes each (column, motion) on its own task (issue 32, performance only): the same motions, bit for
// bit, as family_motions column by column, and the same measured frequencies (each motion's, summed in k order), for
// every drawn family.
TEST(InversionSettingsCheck, BuildFamilyIsFamilyMotionsColumnByColumn) {
  for (const MotionFamily family : {MotionFamily::synthetic, MotionFamily::rezaeian2010, MotionFamily::boore2003}) {
    InversionSettings st;
    st.family = family;
    st.motions_per_cell = 3;
    st.duration_s = 10.0;
    const std::vector<double> freq{0.7, 6.0};
    const FamilyGrid grid = build_family(st, freq);
    ASSERT_EQ(grid.motions.size(), freq.size());
    for (std::size_t j = 0; j < freq.size(); ++j) {
      SCOPED_TRACE(fmt::format("{} column {}", motion_family_name(family), j));
      const std::vector<GroundMotion> want = family_motions(st, freq[j]);
      ASSERT_EQ(grid.motions[j].size(), want.size());
      double sum = 0.0;
      for (std::size_t k = 0; k < want.size(); ++k) {
        const GroundMotion& got = *grid.motions[j][k];
        ASSERT_EQ(got.size(), want[k].size());
        EXPECT_EQ(got.dt_s(), want[k].dt_s());
        EXPECT_TRUE(std::equal(got.accel_m_s2().begin(), got.accel_m_s2().end(), want[k].accel_m_s2().begin()));
        sum += predominant_frequency_hz(want[k]);
      }
      EXPECT_EQ(grid.measured_freq_hz[j], sum / static_cast<double>(want.size()));
    }
  }
}

// The stochastic point-source family (issue 32, motion/stochastic.hpp) is chosen by name and listed among the known
// ones; its frequency axis is 0.1-25 Hz; every motion of a column is on the column with unit PGA; the example survey
// inverted with it on a small grid gives finite estimates inside the grid.
TEST(InversionSettingsCheck, Boore2003FamilyIsChosenByNameAndInverts) {
  const std::string objects = "[[object]]\nid = \"a\"\nwidth = \"5cm\"\nheight = \"20cm\"\nmu = 0.5\n"
                              "outcome = \"overturned\"\n";
  const auto family_of = [&](const std::string& inversion) {
    return io::parse_survey("[site]\nname = \"x\"\n" + inversion + objects, "f.toml").inversion.family;
  };
  EXPECT_EQ(family_of("[inversion]\nfamily = \"boore2003\"\n"), MotionFamily::boore2003);
  EXPECT_EQ(motion_family_name(MotionFamily::boore2003), "boore2003");
  try {
    (void)family_of("[inversion]\nfamily = \"boore\"\n");
    FAIL() << "unknown family accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "inversion.family");
    EXPECT_NE(e.problem().find("boore2003"), std::string::npos) << e.what();
  }
  try {
    (void)family_of("[inversion]\nfamily = \"boore2003\"\nfreq_hz = [0.3, 30.0, 10]\n");
    FAIL() << "a 30 Hz column accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "inversion.freq_hz");
    EXPECT_EQ(e.where().line, 5);
  }
  InversionSettings st;
  st.family = MotionFamily::boore2003;
  EXPECT_NO_THROW(validate_inversion_settings(st));
  st.freq_min_hz = 0.05;
  EXPECT_THROW(validate_inversion_settings(st), InputError);
  st.freq_min_hz = 0.3;
  st.motions_per_cell = 4;
  for (const double f : {0.5, 6.0}) {
    const std::vector<GroundMotion> motions = family_motions(st, f);
    ASSERT_EQ(motions.size(), 4u);
    for (const GroundMotion& m : motions) {
      EXPECT_NEAR(predominant_frequency_hz(m), f, 1e-3 * f);
      EXPECT_NEAR(m.pga_m_s2(), 1.0, 1e-12);
    }
  }
  Survey survey = io::read_survey(std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "survey.toml");
  InversionSettings small = testing::small_grid(6);
  small.family = MotionFamily::boore2003;
  const InversionResult r = invert_site(survey.sites.at(0), small);
  for (const Estimate* e : {&r.pga_estimate_g, &r.freq_estimate_hz}) {
    EXPECT_TRUE(std::isfinite(e->median));
    EXPECT_EQ(e->median_edge, 0);
  }
  EXPECT_GT(r.pga_estimate_g.median, 0.1);  // the example's static thresholds put it at 0.40-0.55 g
  EXPECT_LT(r.pga_estimate_g.median, 2.0);
}

using testing::small_grid;

TEST(Inversion, OnlyUnmovedObjectsLeaveTheLowerEndUnconstrained) {
  Site site;
  site.name = "quiet";
  site.objects.push_back(block("tall", 0.05, 0.5, {0.5, 0.5}, Outcome::not_overturned));
  site.objects.push_back(block("box", 0.3, 0.3, {0.5, 0.5}, Outcome::not_slid));
  const InversionResult r = invert_site(site, small_grid(6));
  EXPECT_FALSE(r.bounds.lower_g.has_value());
  EXPECT_FALSE(r.pga_estimate_g.ci95_low.has_value());  // nothing pushes the PGA off the grid's lower end
  EXPECT_TRUE(r.pga_estimate_g.ci95_high.has_value());
  bool said = false;
  for (const auto& note : r.notes) said = said || note.find("no static lower bound") != std::string::npos;
  EXPECT_TRUE(said);
  EXPECT_EQ(r.runs, 14u * 8u * 6u * 2u);
}

TEST(Inversion, ObservationsNeverReproducedAreNamed) {
  Site site;
  site.name = "odd";
  // A 1.5 m wide, 0.5 m tall block cannot even lift off under 2 g, and a pot cannot slide 5 m.
  auto squat = block("squat", 1.5, 0.5, {0.9, 0.9}, Outcome::overturned);  // uplift needs 3 g
  squat.e_housner = false;
  squat.e = {0.5, 0.5};
  site.objects.push_back(squat);
  auto pot = block("pot", 0.2, 0.1, {0.3, 0.3}, Outcome::slid);
  pot.slid_at_least_m = 5.0;
  site.objects.push_back(pot);
  const InversionResult r = invert_site(site, small_grid(4));
  bool named = false;
  for (const auto& note : r.notes) named = named || (note.find("squat") != std::string::npos && note.find("pot") != std::string::npos);
  EXPECT_TRUE(named);
}

// ---- The steps of invert_site, each on inputs small enough to compute by hand ----

MatchTable match_table(std::size_t pga_count, std::size_t freq_count, std::size_t motions, std::size_t objects,
                       std::vector<double> match) {
  MatchTable m;
  m.pga_count = pga_count;
  m.freq_count = freq_count;
  m.motions = motions;
  m.objects = objects;
  m.match = std::move(match);
  return m;
}

TEST(InversionSteps, LikelihoodOfOneCellAveragesProductsOverMotions) {
  // One cell, two motions, two objects: m = (1, 0) under motion 0, (1, 1) under motion 1; eps = 0.02 and 0.10.
  const MatchTable m = match_table(1, 1, 2, 2, {1.0, 0.0, 1.0, 1.0});
  const LikelihoodReduction r = reduce_likelihood(m, {0.02, 0.10});
  // q(k=0) = 0.98 * 0.10 = 0.098, q(k=1) = 0.98 * 0.90 = 0.882: mean 0.49. Tolerance: a few ulps of log-sum-exp.
  ASSERT_EQ(r.log_likelihood.size(), 1u);
  EXPECT_NEAR(r.log_likelihood[0], std::log(0.49), 1e-14);
  // (sum m + 1/2) / (N + 1): object 0 (2 + 0.5) / 3, object 1 (1 + 0.5) / 3.
  EXPECT_NEAR(r.probability[0][0], 2.5 / 3.0, 1e-15);
  EXPECT_NEAR(r.probability[1][0], 1.5 / 3.0, 1e-15);
  EXPECT_TRUE(r.reproduced_anywhere[0]);
  EXPECT_TRUE(r.reproduced_anywhere[1]);
}

TEST(InversionSteps, NeighbourCellsArePooledWithWeightsFourTwoOne) {
  // Two PGA rows, one frequency column, one motion, one object (eps 0.02) that matches in row 0 only.
  const MatchTable m = match_table(2, 1, 1, 1, {1.0, 0.0});
  const LikelihoodReduction r = reduce_likelihood(m, {0.02});
  // Row 0 pools itself (weight 4, q = 0.98) and row 1 (weight 2, q = 0.02): (3.92 + 0.04) / 6 = 0.66.
  EXPECT_NEAR(r.log_likelihood[0], std::log(0.66), 1e-14);
  EXPECT_NEAR(r.log_likelihood[1], std::log((4 * 0.02 + 2 * 0.98) / 6.0), 1e-14);
  // Probability in row 0: (4 * 1 + 2 * 0) / 6 = 2/3 smoothed to (2/3 + 1/2) / 2.
  EXPECT_NEAR(r.probability[0][0], (2.0 / 3.0 + 0.5) / 2.0, 1e-15);
  EXPECT_NEAR(r.probability[0][1], (1.0 / 3.0 + 0.5) / 2.0, 1e-15);
  EXPECT_THROW((void)reduce_likelihood(m, {0.02, 0.1}), std::invalid_argument);  // one rate per object
}

TEST(InversionSteps, NotesNameObservationsThatContradictEachOtherEverywhere) {
  // Two cells; "a" is reproduced only in cell 0, "b" only in cell 1: no cell reproduces both.
  const MatchTable m = match_table(2, 1, 1, 2, {1.0, 0.0, 0.0, 1.0});
  InversionResult r;
  r.pga_g = {0.1, 0.2};
  r.freq_hz = {1.0};
  r.log_likelihood = {-1.0, -2.0};
  r.bounds.lower_g = 0.1;
  r.bounds.upper_g = 0.3;
  r.objects.resize(2);
  r.objects[0].id = "a";
  r.objects[1].id = "b";
  for (auto& o : r.objects) o.probability = {0.5, 0.5};
  fill_posterior_and_estimates(r);
  EXPECT_EQ(r.best_cell, 0u);
  // exp(-1) / (exp(-1) + exp(-2)) = 1 / (1 + e^-1)
  EXPECT_NEAR(r.posterior[0], 1.0 / (1.0 + std::exp(-1.0)), 1e-15);
  const auto notes = inversion_notes(r, m);
  bool named = false;
  for (const auto& n : notes) {
    named = named || (n.find("contradict each other in every cell") != std::string::npos &&
                      n.find("not reproduced: b.") != std::string::npos);
  }
  EXPECT_TRUE(named);
}

TEST(InversionSteps, RecordFamilyTakesLoadedMotionsInBothPolarities) {
  SynthesisSpec spec;
  spec.pga_m_s2 = 2.0;
  spec.predominant_frequency_hz = 2.0;
  spec.duration_s = 10.0;
  spec.seed = 5;
  InversionSettings st;
  st.family = MotionFamily::records;
  EXPECT_THROW((void)family_motions(st, 1.0), InputError);  // the core reads no file: no motions, no family
  st.records = {"a.AT2"};
  st.record_motions = {std::make_shared<const GroundMotion>(synthesize(spec))};
  const auto motions = family_motions(st, 3.0);
  ASSERT_EQ(motions.size(), 2u);
  EXPECT_NEAR(motions[0].pga_m_s2(), 1.0, 1e-12);
  EXPECT_EQ(motions[1].accel_m_s2()[100], -motions[0].accel_m_s2()[100]);
  // Time-scaled onto the column: the measured predominant frequency moves by less than the spectrum's peak
  // interpolation (7e-5 relative on the example's columns), so 1e-3.
  EXPECT_NEAR(predominant_frequency_hz(motions[0]), 3.0, 3e-3);
}

TEST(InversionSteps, SitesSharingTheFamilyGiveTheSameResultsAsSiteBySite) {
  Site a;
  a.name = "a";
  a.objects.push_back(block("tall", 0.05, 0.5, {0.5, 0.5}, Outcome::overturned));
  a.objects.push_back(block("box", 0.3, 0.3, {0.5, 0.5}, Outcome::not_slid));
  Site b;
  b.name = "b";
  b.objects.push_back(block("pan", 0.2, 0.1, {0.2, 0.3}, Outcome::slid));
  InversionSettings st = small_grid(3);
  st.pga_count = 6;
  st.freq_count = 4;
  const std::vector<InversionResult> both = invert_sites({a, b}, st);
  ASSERT_EQ(both.size(), 2u);
  const InversionResult alone = invert_site(b, st);
  // The same motions, parameters and runs in the same order: bit for bit the same numbers.
  EXPECT_EQ(both[1].log_likelihood, alone.log_likelihood);
  EXPECT_EQ(both[1].measured_freq_hz, alone.measured_freq_hz);
  EXPECT_EQ(both[1].pga_estimate_g.median, alone.pga_estimate_g.median);
  EXPECT_EQ(both[0].site, "a");
  EXPECT_EQ(both[0].runs, 6u * 4u * 3u * 2u);
}

// Recovery: draw a true (PGA, f), make a motion of the family (a seed the inversion never uses), observe what a set
// of objects does under it, invert, and check that the truth lies in the 95 % (68 %) HPD region. With a calibrated
// likelihood the coverage is about 95 % (68 %); the test requires at least 85 % (55 %) over 30 trials (the issue's
// criterion). The observations come from the solvers directly (rock_summary, slide_summary), never from the
// observation_match under test. Measured: 30/30 in the 95 % region, 19/30 in the 68 % one (21/30 when the
// observations were made with observation_match itself). The truths and the observations are drawn with fixed seeds,
// so the test is deterministic.
TEST(Inversion, RecoversKnownShakingWithCalibratedIntervals) {
  // What happened, from the solvers themselves (not from observation_match, which is under test): each object's
  // friction drawn uniformly in its range with the test's own generator (777), the truths with 2026
  // (tests/support/observed_objects.hpp: calibration_objects, synthetic_calibration).
  const int trials = 30;
  const testing::RecoveryCoverage c = testing::synthetic_calibration(small_grid(10), trials);
  EXPECT_GE(c.in95, static_cast<int>(std::ceil(0.85 * trials)));
  EXPECT_GE(c.in68, static_cast<int>(std::ceil(0.55 * trials)));
}

// ---- flexible supports (survey.hpp: SupportFilter; flexible.hpp: support_motion) ----------------------------------

std::filesystem::path upper_floor_example() {
  return std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples" / "upper_floor_survey.toml";
}

TEST(SurveyFile, FlexibleSupportOfTheSiteIsTheDefaultAndAnObjectMayGiveItsOwn) {
  const Survey s = io::read_survey(upper_floor_example());
  ASSERT_EQ(s.sites.size(), 1u);
  const Site& site = s.sites[0];
  ASSERT_TRUE(site.support_filter.has_value());
  EXPECT_EQ(site.support_filter->freq_hz.low, 3.0);
  EXPECT_EQ(site.support_filter->freq_hz.high, 5.0);
  EXPECT_EQ(site.support_filter->damping.low, 0.04);
  EXPECT_EQ(site.support_filter->damping.high, 0.06);
  for (const ObservedObject& o : site.objects) {
    ASSERT_TRUE(o.support_filter.has_value()) << o.id;
    if (o.id == "jar") {
      EXPECT_EQ(o.support_filter->freq_hz.low, 6.0);
      EXPECT_EQ(o.support_filter->freq_hz.high, 9.0);
      EXPECT_TRUE(o.support_filter->damping.is_value());
      EXPECT_EQ(o.support, "floor by the wall (6-9 Hz, damping 0.05)");
    } else {
      EXPECT_EQ(o.support_filter->freq_hz.high, 5.0) << o.id;
    }
  }
}

TEST(SurveyFile, FlexibleSupportErrorsNameTheField) {
  const std::string head = "[[object]]\nid = \"a\"\nwidth = \"10cm\"\nheight = \"20cm\"\nmu = 0.5\noutcome = \"slid\"\n";
  const auto field_of = [&](const std::string& extra) -> std::string {
    try {
      (void)io::parse_survey(head + extra, "s.toml", ".");
    } catch (const InputError& e) {
      return e.where().field;
    }
    ADD_FAILURE() << "no InputError for: " << extra;
    return {};
  };
  EXPECT_EQ(field_of("support = { freq_hz = 4.0 }\n"), "object[1](a).support.damping");  // no guessed damping
  EXPECT_EQ(field_of("support = { damping = 0.05 }\n"), "object[1](a).support.freq_hz");
  EXPECT_EQ(field_of("support = { freq_hz = 0.0, damping = 0.05 }\n"), "object[1](a).support.freq_hz");
  EXPECT_EQ(field_of("support = { freq_hz = 4.0, damping = [0.05, 1.0] }\n"), "object[1](a).support.damping");
  EXPECT_EQ(field_of("support = { freq_hz = 4.0, damping = 0.05, frequency = 3 }\n"), "object[1](a).support.frequency");
  EXPECT_EQ(field_of("support = 4.0\n"), "object[1](a).support");
  // A site's default must be a filter (free text there would silently mean nothing).
  try {
    (void)io::parse_survey("[site]\nsupport = \"upper floor\"\n" + head, "s.toml", ".");
    ADD_FAILURE() << "a site's free-text support was accepted";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().field, "site.support");
  }
  // Free text is still a rigid support, as before.
  const Survey plain = io::parse_survey(head + "support = \"furniture\"\n", "s.toml", ".");
  EXPECT_FALSE(plain.sites[0].objects[0].support_filter.has_value());
  EXPECT_EQ(plain.sites[0].objects[0].support, "furniture");
}

TEST(InversionSteps, SupportDrawsComeLastAndLeaveTheOtherDrawsUnchanged) {
  ObservedObject rigid = block("box", 0.3, 0.3, {0.3, 0.7}, Outcome::slid);
  rigid.amplification = {1.0, 2.0};
  ObservedObject flexible = rigid;
  flexible.support_filter = SupportFilter{{3.0, 6.0}, {0.02, 0.08}};
  for (std::size_t k = 0; k < 50; ++k) {
    const DrawnParameters a = draw_parameters(rigid, 7, k, 3);
    const DrawnParameters b = draw_parameters(flexible, 7, k, 3);
    // Bit for bit: common random numbers with the rigid survey (the same generator, the same first draws).
    EXPECT_EQ(a.mu, b.mu);
    EXPECT_EQ(a.amplification, b.amplification);
    EXPECT_GE(b.support_freq_hz, 3.0);
    EXPECT_LE(b.support_freq_hz, 6.0);
    EXPECT_GE(b.support_damping, 0.02);
    EXPECT_LE(b.support_damping, 0.08);
  }
}

TEST(InversionSteps, StiffSupportMatchesTheRigidOneAndAResonantOneSlidesFurther) {
  // A 0.4 g, 3 Hz synthetic motion; a box with mu = 0.3 that slid 5 cm.
  SynthesisSpec spec;
  spec.pga_m_s2 = 0.4 * kStandardGravity;
  spec.predominant_frequency_hz = 3.0;
  spec.duration_s = 10.0;
  spec.dt_s = 0.01;
  spec.seed = 11;
  const GroundMotion motion = synthesize(spec);
  ObservedObject box = block("box", 0.3, 0.3, {0.3, 0.3}, Outcome::slid);
  box.slid_m = 0.05;
  DrawnParameters p = draw_parameters(box, 1, 0, 0);
  const double rigid = observation_match(box, p, motion, kStandardGravity);
  // A 200 Hz support follows the ground: its transmissibility at 3 Hz is 1 + (3/200)^2 = 1.0002, and near the
  // sampling frequency it passes the record's piecewise-linear content to 1e-3 (flexible.hpp): the match, a Gaussian
  // kernel of width 2 cm in the residual, moves by far less than 1e-2.
  ObservedObject stiff = box;
  stiff.support_filter = SupportFilter{{200.0, 200.0}, {0.05, 0.05}};
  DrawnParameters ps = draw_parameters(stiff, 1, 0, 0);
  EXPECT_NEAR(observation_match(stiff, ps, motion, kStandardGravity), rigid, 1e-2);
  // On a 3 Hz, 5 % floor (resonant with the motion) the box slides much further (the library's solvers directly).
  const auto block_mu = SlidingBlock::make(0.3, 0.3, 0.0, SlidingMode::two_way, kStandardGravity);
  const double on_ground = slide_summary(motion, block_mu).max_abs_displacement_m;
  const double on_floor =
      slide_summary(support_motion(motion, SupportOscillator::make(3.0, 0.05)), block_mu).max_abs_displacement_m;
  fmt::print("peak sliding: on the ground {:.4f} m, on the floor {:.4f} m\n", on_ground, on_floor);
  EXPECT_GT(on_floor, 10.0 * on_ground);  // measured 0.0599 m against 0.0008 m
}

TEST(Inversion, ResonantFloorImpliesLowerGroundPga) {
  // The example upper-floor survey (3-5 Hz floor, ground motions of 1-8 Hz) against the same observations on rigid
  // supports. Near resonance the floor amplifies the ground's motion by up to 1 / (2 zeta) ~ 10, so the same
  // overturned and slid objects need a weaker ground motion: the PGA median must be lower (measured: see the print).
  Survey s = io::read_survey(upper_floor_example());
  InversionSettings st = s.inversion;
  st.pga_count = 14;
  st.freq_count = 8;
  st.motions_per_cell = 8;
  st.duration_s = 10.0;
  Site rigid = s.sites[0];
  rigid.support_filter.reset();
  for (ObservedObject& o : rigid.objects) o.support_filter.reset();
  const InversionResult on_floor = invert_site(s.sites[0], st);
  const InversionResult on_ground = invert_site(rigid, st);
  fmt::print("PGA median: on the floor {:.3f} g, on rigid supports {:.3f} g; best {:.3f} g vs {:.3f} g\n",
             on_floor.pga_estimate_g.median, on_ground.pga_estimate_g.median, on_floor.pga_estimate_g.best,
             on_ground.pga_estimate_g.best);
  EXPECT_LT(on_floor.pga_estimate_g.median, on_ground.pga_estimate_g.median);
  // Column by column: the posterior mean of log PGA given the frequency.
  const auto column_log_pga = [](const InversionResult& r, std::size_t j) {
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < r.pga_g.size(); ++i) {
      num += r.posterior[i * r.freq_hz.size() + j] * std::log(r.pga_g[i]);
      den += r.posterior[i * r.freq_hz.size() + j];
    }
    return std::exp(num / den);
  };
  for (std::size_t j = 0; j < on_floor.freq_hz.size(); ++j) {
    const double floor_g = column_log_pga(on_floor, j);
    const double rigid_g = column_log_pga(on_ground, j);
    fmt::print("  {:.2f} Hz: floor {:.3f} g, rigid {:.3f} g\n", on_floor.freq_hz[j], floor_g, rigid_g);
    // Around the floor's 3-5 Hz the ground needed is clearly lower (measured ratios 0.73-0.81 from 2.4 to 5.9 Hz;
    // 0.9 leaves room for the Monte Carlo noise of 8 motions per cell). Elsewhere the synthetic motions' broad
    // spectra still reach the resonance: lower, but by less (0.77-0.85), so only the direction is required there.
    if (on_floor.freq_hz[j] > 2.4 && on_floor.freq_hz[j] < 6.0) EXPECT_LT(floor_g, 0.9 * rigid_g) << on_floor.freq_hz[j];
    else EXPECT_LT(floor_g, rigid_g) << on_floor.freq_hz[j];
  }
  // Static bounds: a flexible support amplifies a peak at most max_peak_amplification(zeta) times (zeta the lowest
  // damping of its range: 0.04 for the floor; the jar, 0.05, sets no lower bound), so the floor's objects give a lower
  // bound that much weaker than on rigid supports, and no upper bound. Same arithmetic: round-off only.
  ASSERT_TRUE(on_floor.bounds.lower_g.has_value());
  ASSERT_TRUE(on_ground.bounds.lower_g.has_value());
  EXPECT_NEAR(*on_floor.bounds.lower_g, *on_ground.bounds.lower_g / max_peak_amplification(0.04),
              1e-12 * *on_ground.bounds.lower_g);
  EXPECT_TRUE(on_floor.bounds.upper.empty());
}

}  // namespace
}  // namespace topple

// ---- Issue 13 / 18: hard and soft thresholds, misfits, information, the summary sentence, the map ----
namespace topple {
namespace {

// Hand values: a lower threshold divides by the largest amplification, an upper one by the smallest, and the text
// shows the amplification used and the result (the old text printed the high one in both).
TEST(StaticThresholds, HardAndSoftWithTheAmplificationUsed) {
  Site site;
  auto stuck = block("tv", 0.3, 0.3, {0.7, 0.7}, Outcome::not_slid);
  stuck.amplification = {1.3, 2.0};  // upper: 0.7 / 1.3 = 0.538 g
  site.objects.push_back(stuck);
  auto fell = block("vase", 0.1, 0.4, {0.5, 0.5}, Outcome::overturned);
  fell.amplification = {1.3, 2.0};  // lower: (0.05 / 0.2) / 2 = 0.125 g
  site.objects.push_back(fell);
  site.objects.push_back(block("pan", 0.2, 0.2, {0.25, 0.25}, Outcome::slid));  // lower 0.25 g, no amplification
  const StaticBounds b = static_bounds(site);
  ASSERT_EQ(b.upper.size(), 1u);
  ASSERT_EQ(b.lower.size(), 2u);
  EXPECT_NEAR(b.upper[0].pga_g, 0.7 / 1.3, 1e-12);
  EXPECT_FALSE(b.upper[0].hard);  // did not slide visibly: soft
  EXPECT_EQ(b.upper[0].reason, "did not slide visibly: PGA <= mu g = 0.7 g / amplification 1.3 = 0.538 g");
  EXPECT_NEAR(b.lower[0].pga_g, 0.125, 1e-12);
  EXPECT_TRUE(b.lower[0].hard);
  EXPECT_EQ(b.lower[0].reason, "overturned: PGA > g a/h = 0.25 g / amplification 2 = 0.125 g");
  EXPECT_TRUE(b.lower[1].hard);
  EXPECT_EQ(b.lower[1].reason, "slid: PGA > mu g = 0.25 g");
  // the old fields keep their meaning (hard and soft together); the hard ones alone beside them
  ASSERT_TRUE(b.lower_g && b.upper_g && b.hard_lower_g);
  EXPECT_NEAR(*b.lower_g, 0.25, 1e-12);
  EXPECT_NEAR(*b.upper_g, 0.7 / 1.3, 1e-12);
  EXPECT_NEAR(*b.hard_lower_g, 0.25, 1e-12);
  EXPECT_FALSE(b.hard_upper_g);
}

/// A match table on a 3 x 3 grid, 4 motions, filled by f(cell, k, object).
template <class F>
MatchTable table_of(std::size_t objects, F f) {
  MatchTable m;
  m.pga_count = 3;
  m.freq_count = 3;
  m.motions = 4;
  m.objects = objects;
  m.match.resize(m.cells() * m.motions * objects);
  for (std::size_t c = 0; c < m.cells(); ++c) {
    for (std::size_t k = 0; k < m.motions; ++k) {
      for (std::size_t o = 0; o < objects; ++o) m.match[(c * m.motions + k) * objects + o] = f(c, k, o);
    }
  }
  return m;
}

InversionResult result_of(const MatchTable& m, const std::vector<double>& rates) {
  InversionResult r;
  r.site = "t";
  r.pga_g = {0.1, 0.3, 0.9};
  r.freq_hz = {1.0, 2.0, 4.0};
  LikelihoodReduction red = reduce_likelihood(m, rates);
  r.log_likelihood = red.log_likelihood;
  r.objects.resize(m.objects);
  for (std::size_t o = 0; o < m.objects; ++o) {
    r.objects[o].id = fmt::format("o{}", o);
    r.objects[o].probability = red.probability[o];
  }
  fill_posterior_and_estimates(r);
  return r;
}

TEST(AssessObjects, PosteriorPredictiveMisfitAndInformation) {
  // o0: informative (matches in the high-PGA row only, 3 of 4 motions); o1: matches in every run (no information);
  // o2: matches in no run (a misfit, whatever the cell); o3: matches in half the runs of every cell.
  const auto f = [](std::size_t c, std::size_t k, std::size_t o) -> double {
    switch (o) {
      case 0: return c / 3 == 2 && k < 3 ? 1.0 : 0.0;
      case 1: return 1.0;
      case 2: return 0.0;
      default: return k % 2 == 0 ? 1.0 : 0.0;
    }
  };
  const MatchTable m = table_of(4, f);
  const std::vector<double> rates{0.02, 0.02, 0.02, 0.02};
  InversionResult r = result_of(m, rates);
  assess_objects(r, m, rates);
  // Posterior-predictive: sum_c posterior(c) x share of the cell's runs that match. o1, o2, o3 are the same in every
  // cell, so the posterior's weights sum to 1 around a constant: 1, 0 and 1/2 (to rounding).
  EXPECT_NEAR(r.objects[1].posterior_predictive, 1.0, 1e-12);
  EXPECT_NEAR(r.objects[2].posterior_predictive, 0.0, 1e-12);
  EXPECT_NEAR(r.objects[3].posterior_predictive, 0.5, 1e-12);
  double expect0 = 0.0;  // o0 by hand: 3/4 in the high row, 0 elsewhere
  for (std::size_t c = 6; c < 9; ++c) expect0 += 0.75 * r.posterior[c];
  EXPECT_NEAR(r.objects[0].posterior_predictive, expect0, 1e-12);
  EXPECT_FALSE(r.objects[0].misfit);
  EXPECT_FALSE(r.objects[1].misfit);
  EXPECT_TRUE(r.objects[2].misfit);
  EXPECT_FALSE(r.objects[3].misfit);
  // Information: an object the same in every run (o1, o2) cannot move the posterior: 0 bits (rounding only).
  EXPECT_NEAR(r.objects[1].constraint_bits, 0.0, 1e-9);
  EXPECT_NEAR(r.objects[2].constraint_bits, 0.0, 1e-9);
  // o0 by an independent route: the posterior of a table that never had o0, and the KL divergence in bits.
  const MatchTable without = table_of(3, [&f](std::size_t c, std::size_t k, std::size_t o) { return f(c, k, o + 1); });
  const InversionResult r_without = result_of(without, {0.02, 0.02, 0.02});
  double kl = 0.0;
  for (std::size_t c = 0; c < 9; ++c) kl += r.posterior[c] * std::log2(r.posterior[c] / r_without.posterior[c]);
  EXPECT_GT(kl, 0.5);  // the high row holds nearly all the mass: far from the flat posterior without o0
  EXPECT_NEAR(r.objects[0].constraint_bits, kl, 1e-9 * kl);
  // o3 correlates with o0 through the shared motions (k even), so it carries a little; less than o0.
  EXPECT_LT(r.objects[3].constraint_bits, r.objects[0].constraint_bits);
  const auto top = most_constraining_objects(r);
  ASSERT_FALSE(top.empty());
  EXPECT_EQ(top.front(), 0u);
  // The notes name the misfit with its probability.
  bool named = false;
  for (const auto& note : inversion_notes(r, m)) named = named || (note.find("Misfit") != std::string::npos &&
                                                                   note.find("o2 (") != std::string::npos);
  EXPECT_TRUE(named);
}

TEST(InversionSummary, LeadsWithTheMedianAndSaysGridEdgesInWords) {
  InversionResult r;
  r.site = "kitchen";
  r.pga_g = {0.02, 0.2, 2.0};
  r.freq_hz = {0.3, 3.0, 20.0};
  r.pga_estimate_g.median = 0.5512;
  r.pga_estimate_g.best = 0.479;
  r.pga_estimate_g.ci68_low = 0.448;
  r.pga_estimate_g.ci68_high = 0.783;
  r.pga_estimate_g.ci95_low = 0.379;  // upper 95 % end open
  r.freq_estimate_hz.median = 0.31;
  r.freq_estimate_hz.median_edge = -1;  // in the first cell: no estimate
  r.freq_estimate_hz.best = 0.3;
  r.objects.resize(2);
  r.objects[0].id = "tv";
  r.objects[0].constraint_bits = 1.7;
  r.objects[1].id = "fridge";
  r.objects[1].outcome = Outcome::slid;
  r.objects[1].constraint_bits = 0.05;  // under 0.1 bit: not named as constraining
  r.objects[1].misfit = true;
  r.objects[1].posterior_predictive = 0.012;
  EXPECT_EQ(inversion_summary(r),
            "The shaking at kitchen most likely had a PGA of about 0.55 g (median; 68 %: 0.45\u20130.78 g, 95 %: from "
            "0.38 g to above the grid) and a predominant frequency below the grid (at most about 0.3 Hz) (median; "
            "68 %: anywhere on the grid, 95 %: anywhere on the grid); the object that constrains it most is tv; not "
            "explained by this answer (posterior-predictive P below 0.05): fridge (slid, P = 0.01).");
}


// The map: log axes ticked at 1-2-5, both credible regions, each object's line in its colour with the side that fits;
// objects without a line do not appear in the legend (the report's caption names them with the reason).
TEST(InversionMap, TicsRegionsAndObjectLines) {
  const auto f = [](std::size_t c, std::size_t k, std::size_t o) -> double {
    if (o == 0) return c / 3 == 2 && k < 3 ? 1.0 : 0.0;  // fits at high PGA
    return o == 1 ? 1.0 : 0.0;                              // fits everywhere / nowhere: no P = 0.5 line
  };
  const MatchTable m = table_of(3, f);
  InversionResult r = result_of(m, {0.02, 0.02, 0.02});
  assess_objects(r, m, {0.02, 0.02, 0.02});
  Site site;
  site.name = "t";
  const plot::MapFigure map = likelihood_map_figure(r, site);
  const std::string script = plot::gnuplot_script(map, "map.svg");
  // PGA cells 0.1, 0.3, 0.9 g span 0.058-1.56 g: labelled tics at 0.1, 0.2, 0.5 and 1.
  for (const char* tic : {"\"0.1\" 0.1", "\"0.2\" 0.2", "\"0.5\" 0.5", "\"1\" 1"}) {
    EXPECT_NE(script.find(tic), std::string::npos) << tic << "\n" << script;
  }
  EXPECT_NE(script.find("title \"68 % credible region\""), std::string::npos);
  EXPECT_NE(script.find("title \"95 % credible region\""), std::string::npos);
  EXPECT_NE(script.find("title \"o0 (not_overturned): fits at higher PGA\""), std::string::npos) << script;
  EXPECT_EQ(script.find("title \"o1 ("), std::string::npos);
  EXPECT_EQ(script.find("title \"o2 ("), std::string::npos);
  // The legend sits beside the plot, not under the x label.
  EXPECT_NE(script.find("set key outside right"), std::string::npos);
}

// The example motion of the maximum-likelihood cell: an object observed standing that falls in that one motion is
// labelled so, never just "(falls)".
TEST(InversionMap, BestCellFigureSaysWhenOneMotionContradictsTheObservation) {
  InversionResult r;
  r.site = "t";
  r.pga_g = {1.5, 2.0};
  r.freq_hz = {1.0, 2.0};
  r.best_cell = 1;  // 1.5 g at 2 Hz
  Site site;
  site.objects.push_back(block("pole", 0.05, 0.5, {0.6, 0.6}, Outcome::not_overturned));  // uplift at 0.1 g
  InversionSettings settings;
  settings.duration_s = 8.0;
  const plot::Figure fig = best_cell_figure(r, site, settings);
  ASSERT_EQ(fig.panels.size(), 2u);  // ground and rocking
  ASSERT_EQ(fig.panels[1].series.size(), 1u);
  EXPECT_EQ(fig.panels[1].series[0].label, "pole (falls in this one motion; observed standing)");
}

// ---- The objects' own evidence, the ridge, what to look for next (evidence.hpp, issue 32) ----

/// A hand-made result on the given axes with the given log-likelihood (index i * nf + j) and no objects.
InversionResult hand_result(std::vector<double> pga, std::vector<double> freq, std::vector<double> ll) {
  InversionResult r;
  r.site = "hand";
  r.pga_g = std::move(pga);
  r.freq_hz = std::move(freq);
  r.log_likelihood = std::move(ll);
  return r;
}

// Under the log-uniform prior (log_prior empty) the objects' own estimate is the posterior's, to the bit.
TEST(Evidence, LikelihoodEstimateEqualsThePosteriorsUnderTheUniformPrior) {
  const std::vector<double> pga = log_spaced(0.05, 2.0, 12), freq = log_spaced(0.5, 12.0, 8);
  std::vector<double> ll;
  for (std::size_t i = 0; i < pga.size(); ++i) {
    for (std::size_t j = 0; j < freq.size(); ++j) {
      const double x = std::log(pga[i] / 0.3), y = std::log(freq[j] / 3.0);
      ll.push_back(-2.0 * x * x - 0.7 * y * y + 0.9 * x * y);
    }
  }
  InversionResult r = hand_result(pga, freq, ll);
  fill_posterior_and_estimates(r);
  EXPECT_EQ(r.prior, "log-uniform");
  EXPECT_EQ(r.marginal_pga_likelihood, r.marginal_pga);
  EXPECT_EQ(r.marginal_freq_likelihood, r.marginal_freq);
  for (const auto& [a, b] : {std::pair{&r.pga_likelihood_g, &r.pga_estimate_g},
                             std::pair{&r.freq_likelihood_hz, &r.freq_estimate_hz}}) {
    EXPECT_EQ(a->median, b->median);
    EXPECT_EQ(a->best, b->best);
    EXPECT_EQ(a->ci68_low, b->ci68_low);
    EXPECT_EQ(a->ci68_high, b->ci68_high);
    EXPECT_EQ(a->ci95_low, b->ci95_low);
    EXPECT_EQ(a->ci95_high, b->ci95_high);
  }
  EXPECT_EQ(likelihood_summary_clause(r), "");  // equal: the summary says nothing more
}

// A non-uniform prior moves the posterior as the prior says and leaves the objects' estimate alone. 2 x 2 grid,
// PGA {0.1, 1} g, frequency {1, 4} Hz; likelihood 1:2:3:4 and prior 4:3:2:1 (index i * 2 + j): posterior 4:6:6:4/20,
// marginals 1/2, 1/2 on both axes, so its medians sit on the cell edge: sqrt(0.1 x 1) g and sqrt(1 x 4) = 2 Hz. The
// likelihood's marginals are 0.3, 0.7 (PGA) and 0.4, 0.6 (frequency); the median spreads the second cell's mass
// uniformly in log over [ln sqrt(0.1), ln sqrt(10)] and [ln 2, ln 8]: 10^(-1/2 + 0.2/0.7) g and 2 x 4^(0.1/0.6) Hz.
TEST(Evidence, NonUniformPriorMovesThePosteriorAndNotTheObjectsEstimate) {
  InversionResult r = hand_result({0.1, 1.0}, {1.0, 4.0}, {std::log(1.0), std::log(2.0), std::log(3.0), std::log(4.0)});
  r.log_prior = {std::log(4.0), std::log(3.0), std::log(2.0), std::log(1.0)};
  r.prior = "hand-made";
  fill_posterior_and_estimates(r);
  const std::vector<double> post{0.2, 0.3, 0.3, 0.2};
  for (std::size_t c = 0; c < 4; ++c) EXPECT_NEAR(r.posterior[c], post[c], 1e-15);
  EXPECT_NEAR(r.marginal_pga[0], 0.5, 1e-15);
  EXPECT_NEAR(r.marginal_freq[0], 0.5, 1e-15);
  EXPECT_NEAR(r.marginal_pga_likelihood[0], 0.3, 1e-15);
  EXPECT_NEAR(r.marginal_freq_likelihood[0], 0.4, 1e-15);
  EXPECT_NEAR(r.pga_estimate_g.median, std::sqrt(0.1), 1e-12);
  EXPECT_NEAR(r.freq_estimate_hz.median, 2.0, 1e-12);
  EXPECT_NEAR(r.pga_likelihood_g.median, std::pow(10.0, -0.5 + 0.2 / 0.7), 1e-12);
  EXPECT_NEAR(r.freq_likelihood_hz.median, 2.0 * std::pow(4.0, 0.1 / 0.6), 1e-12);
  // The prior's own marginals (the report's grey curve): 7/10, 3/10 over PGA; 6/10, 4/10 over frequency.
  const std::vector<double> prior = prior_cells(r);
  EXPECT_NEAR(marginal_over_pga(prior, 2, 2)[0], 0.7, 1e-15);
  EXPECT_NEAR(marginal_over_freq(prior, 2, 2)[0], 0.6, 1e-15);
  // They differ, so the summary says what the objects alone give, naming the prior.
  const std::string clause = likelihood_summary_clause(r);
  EXPECT_NE(clause.find("the objects alone"), std::string::npos) << clause;
  EXPECT_NE(clause.find("hand-made prior"), std::string::npos) << clause;
  EXPECT_NE(inversion_summary(r).find(clause), std::string::npos);
  r.log_prior = {0.0, 0.0, 0.0};
  EXPECT_THROW(fill_posterior_and_estimates(r), std::invalid_argument);
}

// The ridge: log L = -((ln pga - a - b ln f) / s)^2 - 2 (ln f - ln 2)^2. In column f the likelihood over ln PGA is
// normal with mean a + b ln f and sigma s / sqrt 2, so the PGA the objects need is exp(a + b ln f) (median) and
// exp(a + b ln f -+ 0.99446 s / sqrt 2) (16 % and 84 %). The cells are 0.058 wide in ln PGA; the quantiles,
// interpolated uniformly in log within a cell, are within 1.5 % of the continuous ones. The column at 16 Hz holds
// exp(-2 ln(8)^2) = 1.7e-4 of the 2 Hz column's mass (below 1e-3: none); at 8 Hz 0.021 (kept).
TEST(Evidence, PgaGivenFreqRecoversAKnownRidge) {
  const double a = std::log(0.3), b = 0.5, s = 0.3;
  const std::vector<double> pga = log_spaced(0.01, 10.0, 121), freq = log_spaced(0.5, 16.0, 6);
  std::vector<double> ll;
  for (const double p : pga) {
    for (const double f : freq) {
      const double z = (std::log(p) - a - b * std::log(f)) / s;
      ll.push_back(-z * z - 2.0 * std::pow(std::log(f / 2.0), 2));
    }
  }
  const std::vector<PgaGivenFreq> ridge = ridge_pga_given_freq(ll, pga, freq);
  ASSERT_EQ(ridge.size(), freq.size());
  const double z84 = 0.994458;  // Phi^-1(0.84)
  for (std::size_t j = 0; j < freq.size(); ++j) {
    EXPECT_DOUBLE_EQ(ridge[j].freq_hz, freq[j]);
    EXPECT_NEAR(ridge[j].likelihood_share, std::exp(-2.0 * std::pow(std::log(freq[j] / 2.0), 2)), 1e-9) << j;
    if (j == 5) {
      EXPECT_FALSE(ridge[j].pga_g.has_value());  // 16 Hz: negligible
      continue;
    }
    ASSERT_TRUE(ridge[j].pga_g.has_value()) << j;
    const Estimate& e = *ridge[j].pga_g;
    const double mu = a + b * std::log(freq[j]);
    EXPECT_NEAR(e.median / std::exp(mu), 1.0, 0.015) << freq[j];
    ASSERT_TRUE(e.ci68_low && e.ci68_high);
    EXPECT_NEAR(*e.ci68_low / std::exp(mu - z84 * s / std::sqrt(2.0)), 1.0, 0.015) << freq[j];
    EXPECT_NEAR(*e.ci68_high / std::exp(mu + z84 * s / std::sqrt(2.0)), 1.0, 0.015) << freq[j];
  }
  // fill_likelihood_estimates puts the same ridge in the result.
  InversionResult r = hand_result(pga, freq, ll);
  fill_posterior_and_estimates(r);
  ASSERT_EQ(r.pga_given_freq.size(), freq.size());
  EXPECT_EQ(r.pga_given_freq[2].pga_g->median, ridge[2].pga_g->median);
}

// Expected information gain on hand-made tables, 2 x 2 grid, uniform posterior (1 bit on each axis):
// an outcome certain everywhere gives 0; one that says which PGA row gives 1 bit on PGA and 0 on frequency (and the
// other way round); a noisy one (right with probability 0.8) gives 1 - H2(0.8) = 0.278072 bit; never negative.
TEST(Evidence, ExpectedInformationGainOnHandMadeTables) {
  const std::vector<double> uniform(4, 0.25);
  const auto gain = [&](std::vector<double> y0) {
    std::vector<double> y1(4);
    for (std::size_t c = 0; c < 4; ++c) y1[c] = 1.0 - y0[c];
    return expected_information_gain(uniform, 2, 2, {y0, y1});
  };
  const InformationGain certain = gain({1.0, 1.0, 1.0, 1.0});
  EXPECT_NEAR(certain.bits_pga, 0.0, 1e-15);
  EXPECT_NEAR(certain.bits_freq, 0.0, 1e-15);
  const InformationGain rows = gain({1.0, 1.0, 0.0, 0.0});  // index i * 2 + j: y0 exactly when i = 0
  EXPECT_NEAR(rows.bits_pga, 1.0, 1e-15);
  EXPECT_NEAR(rows.bits_freq, 0.0, 1e-15);
  const InformationGain columns = gain({1.0, 0.0, 1.0, 0.0});
  EXPECT_NEAR(columns.bits_pga, 0.0, 1e-15);
  EXPECT_NEAR(columns.bits_freq, 1.0, 1e-15);
  const InformationGain noisy = gain({0.8, 0.8, 0.2, 0.2});
  EXPECT_NEAR(noisy.bits_pga, 1.0 + 0.8 * std::log2(0.8) + 0.2 * std::log2(0.2), 1e-14);
  EXPECT_NEAR(noisy.bits_pga, 0.278072, 1e-6);
  // Three outcomes: y0 on row 0, y1 and y2 split row 1 by column: 1 bit on PGA, and on frequency
  // H(1/2) - [1/2 H(1/2) + 1/4 x 0 + 1/4 x 0] = 1/2 bit.
  const InformationGain three = expected_information_gain(
      uniform, 2, 2, {{1.0, 1.0, 0.0, 0.0}, {0.0, 0.0, 1.0, 0.0}, {0.0, 0.0, 0.0, 1.0}});
  EXPECT_NEAR(three.bits_pga, 1.0, 1e-15);
  EXPECT_NEAR(three.bits_freq, 0.5, 1e-15);
  // Random posteriors and tables: never negative, never above the marginal's entropy.
  std::uint64_t state = 12345;
  const auto next = [&state] {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / 9007199254740992.0;
  };
  for (int t = 0; t < 200; ++t) {
    std::vector<double> post(12), y0(12), y1(12);
    double z = 0.0;
    for (double& p : post) z += p = next() * next();
    for (double& p : post) p /= z;
    for (std::size_t c = 0; c < 12; ++c) y1[c] = 1.0 - (y0[c] = t % 2 ? next() : 0.5);
    const InformationGain g = expected_information_gain(post, 3, 4, {y0, y1});
    EXPECT_GE(g.bits_pga, 0.0);
    EXPECT_GE(g.bits_freq, 0.0);
    EXPECT_LE(g.bits_pga, std::log2(3.0) + 1e-12);
    EXPECT_LE(g.bits_freq, std::log2(4.0) + 1e-12);
  }
  EXPECT_THROW((void)expected_information_gain(uniform, 2, 2, {{1.0, 1.0}}), std::invalid_argument);
}

// The catalogue: every entry cites its documentation row; the rocking ones are the bodies of that row.
TEST(Evidence, HouseholdCatalogueCitesItsRows) {
  const auto& catalogue = household_catalogue();
  ASSERT_GE(catalogue.size(), 10u);
  for (const CatalogueObject& c : catalogue) {
    EXPECT_TRUE(c.source.starts_with("docs/")) << c.name;
    EXPECT_FALSE(c.description.empty()) << c.name;
  }
  EXPECT_EQ(catalogue[0].name, "wine bottle");
  EXPECT_NEAR(catalogue[0].object.body.alpha_rad(), std::atan(0.06 / 0.30), 1e-12);  // a cylinder: tan alpha = D/h
  EXPECT_EQ(catalogue_outcome_count(catalogue[0].object), 3u);
  EXPECT_EQ(catalogue_outcome_count(catalogue.back().object), 2u);
  // One run each way: a tall slender bottle under 1 g at 2 Hz falls or rocks; a glass (mu 0.9-1.0) under 0.05 g
  // does not slide (|a| < mu g throughout: Coulomb).
  const GroundMotion m = family_motions(small_grid(1), 2.0).front();
  const DrawnParameters p = nominal_parameters(catalogue[0].object);
  EXPECT_LE(catalogue_outcome(catalogue[0].object, p, m.scaled(kStandardGravity), kStandardGravity), 1u);
  EXPECT_EQ(catalogue_outcome(catalogue.back().object, nominal_parameters(catalogue.back().object),
                              m.scaled(0.05 * kStandardGravity), kStandardGravity),
            1u);
  // A model = "3d" object's outcome is the three-dimensional engine's (the motion along its +x axis), checked here
  // against rock3d and rock3d_cylinder run directly, over levels where it stands, rocks and falls.
  ObservedObject box = catalogue[0].object;
  box.body = RockingBody::block(0.3, 1.5);
  box.depth_m = 0.4;
  box.model = ObjectModel::three_d;
  box.body_3d = std::make_shared<const RigidBody3D>(RigidBody3D::box(0.3, 0.4, 1.5));
  ObservedObject cyl = catalogue[0].object;  // a column on its rim
  cyl.body = RockingBody::cylinder(0.3, 1.5);
  cyl.model = ObjectModel::three_d;
  std::set<std::size_t> seen;
  for (const double pga_g : {0.05, 0.25, 0.3, 0.4, 0.6, 1.0}) {
    const GroundMotion mg = m.scaled(pga_g * kStandardGravity);
    for (const ObservedObject* o : {&box, &cyl}) {
      const DrawnParameters po = nominal_parameters(*o);
      const Rigid3DOptions ro = rigid3d_options(inversion_rocking_options(*o, po, kStandardGravity));
      const Rigid3DSummary s =
          o->body_3d ? rock3d(mg, nullptr, nullptr, *o->body_3d, ro).summary
                     : rock3d_cylinder(mg, nullptr, nullptr,
                                       CylinderBody3D::solid(2.0 * o->body.a_m, 2.0 * o->body.h_m), ro).summary;
      const std::size_t expected = s.overturned ? 0 : s.max_tilt_rad >= kVisibleRockingRad ? 1 : 2;
      EXPECT_EQ(catalogue_outcome(*o, po, mg, kStandardGravity), expected) << pga_g;
      seen.insert(expected);
      std::printf("catalogue 3-D %s at %.2f g: category %zu (max tilt %.3g rad)\n", o->body_3d ? "box" : "column",
                  pga_g, expected, s.max_tilt_rad);
    }
  }
  EXPECT_EQ(seen.size(), 3u);  // every category met
}

// The summary's sentence on what to look for next: the largest gain on each axis, one object named once when it is
// the best on both, nothing below 0.05 bit.
TEST(Evidence, NextObjectsSentence) {
  InversionResult r;
  EXPECT_EQ(next_objects_summary_clause(r), "");
  r.next_objects = {{"bookend", "block", "whether it fell", 0.30, 0.01}, {"wine bottle", "cylinder", "whether it fell", 0.02, 0.40}};
  EXPECT_EQ(next_objects_summary_clause(r),
            " To narrow the frequency, look for a wine bottle (cylinder) and whether it fell (0.40 bit); to narrow the "
            "PGA, look for a bookend (block) and whether it fell (0.30 bit).");
  r.next_objects = {{"bookend", "block", "whether it fell", 0.30, 0.20}};
  EXPECT_EQ(next_objects_summary_clause(r),
            " To narrow both the frequency (0.20 bit) and the PGA (0.30 bit), look for a bookend (block) and whether it "
            "fell.");
  r.next_objects = {{"bookend", "block", "whether it fell", 0.30, 0.04}};
  EXPECT_EQ(next_objects_summary_clause(r), " To narrow the PGA, look for a bookend (block) and whether it fell (0.30 bit).");
  r.next_objects = {{"bookend", "block", "whether it fell", 0.04, 0.04}};
  EXPECT_EQ(next_objects_summary_clause(r), "");
}

// The pipeline: every catalogue object ranked, by decreasing total bits, each finite and within the marginals'
// entropies; with next_objects off, none; the ridge has a point per column.
TEST(Evidence, InvertSiteRanksTheCatalogue) {
  Site site;
  site.name = "evidence";
  site.objects.push_back(block("fell", 0.08, 0.5, {0.5, 0.5}, Outcome::overturned));
  site.objects.push_back(block("stuck", 0.3, 0.3, {0.5, 0.6}, Outcome::not_slid));
  InversionSettings st = small_grid(4);
  const InversionResult r = invert_site(site, st);
  ASSERT_EQ(r.next_objects.size(), household_catalogue().size());
  ASSERT_EQ(r.pga_given_freq.size(), r.freq_hz.size());
  const auto entropy = [](const std::vector<double>& p) {
    double h = 0.0;
    for (const double v : p) h -= v > 0.0 ? v * std::log2(v) : 0.0;
    return h;
  };
  for (std::size_t x = 0; x < r.next_objects.size(); ++x) {
    const NextObject& n = r.next_objects[x];
    EXPECT_TRUE(std::isfinite(n.bits_pga) && std::isfinite(n.bits_freq)) << n.object;
    EXPECT_GE(n.bits_pga, 0.0);
    EXPECT_GE(n.bits_freq, 0.0);
    EXPECT_LE(n.bits_pga, entropy(r.marginal_pga) + 0.01) << n.object;  // 0.01: the 99.9 % truncation
    EXPECT_LE(n.bits_freq, entropy(r.marginal_freq) + 0.01) << n.object;
    if (x > 0) {
      EXPECT_LE(n.bits_pga + n.bits_freq, r.next_objects[x - 1].bits_pga + r.next_objects[x - 1].bits_freq);
    }
  }
  EXPECT_GT(r.next_objects.front().bits_pga + r.next_objects.front().bits_freq, 0.05);
  InversionOptions off;
  off.next_objects = false;
  EXPECT_TRUE(invert_site(site, st, off).next_objects.empty());
}

// Performance only (issue 32): a survey object whose rocking run is a catalogue object's (the bookend and the mantel
// clock, same bodies, Housner's restitution, rigid support) gives the ranking its outcomes instead of a second run. The
// ranking must be the same, bit for bit, as the one that runs every catalogue object (suggest_next_objects alone);
// and the sharing must have happened (else this test would compare a thing with itself).
TEST(Evidence, SharedCatalogueRunsGiveTheSameRanking) {
  Site site;
  site.name = "shared";
  site.objects.push_back(block("bookend", 0.10, 0.15, {0.6, 0.6}, Outcome::not_overturned));
  site.objects.push_back(block("clock", 0.10, 0.25, {0.5, 0.5}, Outcome::rocked));
  site.objects.push_back(block("fell", 0.07, 0.5, {0.5, 0.5}, Outcome::overturned));  // no catalogue twin
  const InversionSettings st = small_grid(4);
  const InversionResult r = invert_site(site, st);
  const FamilyGrid family = build_family(st, r.freq_hz);
  const std::vector<NextObject> alone = suggest_next_objects(r, st, family);
  ASSERT_EQ(alone.size(), r.next_objects.size());
  for (std::size_t x = 0; x < alone.size(); ++x) {
    EXPECT_EQ(r.next_objects[x].object, alone[x].object);
    EXPECT_EQ(r.next_objects[x].bits_pga, alone[x].bits_pga) << alone[x].object;  // exact: the same outcomes
    EXPECT_EQ(r.next_objects[x].bits_freq, alone[x].bits_freq) << alone[x].object;
  }
  // The share: the bookend and the mantel clock found, and outcomes recorded for some of their runs, equal to a
  // catalogue run's where recorded.
  detail::CatalogueShare share;
  const MatchTable m = detail::simulate_matches(site, st, r.pga_g, family, {}, &share);
  EXPECT_EQ(m.match, simulate_matches(site, st, r.pga_g, family).match);
  const auto& catalogue = household_catalogue();
  std::size_t recorded = 0;
  for (std::size_t x = 0; x < catalogue.size(); ++x) {
    const bool twin = catalogue[x].name == "bookend" || catalogue[x].name == "mantel clock";
    EXPECT_EQ(share.block[x] >= 0, twin) << catalogue[x].name;
    if (!twin) continue;
    for (std::size_t c = 0; c < share.cells; c += 7) {
      for (std::size_t k = 0; k < share.nk; ++k) {
        const std::uint8_t y = share.at(x, c, k);
        if (y == detail::CatalogueShare::kNotRecorded) continue;
        ++recorded;
        const std::size_t nf = r.freq_hz.size();
        const GroundMotion motion = family.motions[c % nf][k]->scaled(r.pga_g[c / nf] * st.g_m_s2);
        EXPECT_EQ(y, catalogue_outcome(catalogue[x].object, draw_parameters(catalogue[x].object, st.seed, k, 1000 + x),
                                       motion, st.g_m_s2));
      }
    }
  }
  EXPECT_GT(recorded, 0u);
}

}  // namespace
}  // namespace topple
