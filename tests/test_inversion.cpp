// Inversion of field observations: static bounds by hand, honesty, and recovery of known shaking.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/shared_data.hpp"

#include "topple/error.hpp"
#include "topple/inversion.hpp"
#include "topple/io/read.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"
#include "topple/spectra.hpp"
#include "topple/synthesis.hpp"

namespace topple {
namespace {

ObservedObject block(const std::string& id, double w, double h, Interval mu, Outcome outcome) {
  ObservedObject o;
  o.id = id;
  o.body = RockingBody::block(w, h);
  o.width_m = w;
  o.height_m = h;
  o.mu = mu;
  o.outcome = outcome;
  return o;
}

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

InversionSettings small_grid(int motions = 10) {
  InversionSettings st;
  st.pga_min_g = 0.05;
  st.pga_max_g = 2.0;
  st.pga_count = 14;
  st.freq_min_hz = 0.5;
  st.freq_max_hz = 12.0;
  st.freq_count = 8;
  st.motions_per_cell = motions;
  st.duration_s = 10.0;
  return st;
}

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
  const InversionSettings st = small_grid(10);
  std::vector<ObservedObject> objects;
  objects.push_back(block("slender", 0.06, 0.40, {0.5, 0.7}, Outcome::overturned));
  objects.push_back(block("medium", 0.10, 0.30, {0.5, 0.7}, Outcome::overturned));
  objects.push_back(block("stocky", 0.15, 0.25, {0.5, 0.7}, Outcome::overturned));
  objects.push_back(block("tall-box", 0.25, 1.00, {0.5, 0.7}, Outcome::overturned));
  objects.push_back(block("pan", 0.2, 0.1, {0.15, 0.25}, Outcome::slid));
  objects.push_back(block("crate", 0.3, 0.3, {0.4, 0.6}, Outcome::slid));
  objects.push_back(block("bin", 0.3, 0.3, {0.7, 0.9}, Outcome::slid));
  PortableRandom rng(2026);     // the truths
  PortableRandom params(777);   // the objects' true friction coefficients
  int in95 = 0;
  int in68 = 0;
  const int trials = 30;
  for (int t = 0; t < trials; ++t) {
    const double pga = std::exp(std::log(0.12) + (std::log(1.2) - std::log(0.12)) * rng.uniform());
    const double freq = std::exp(std::log(0.8) + (std::log(8.0) - std::log(0.8)) * rng.uniform());
    SynthesisSpec spec;
    spec.pga_m_s2 = pga * st.g_m_s2;
    spec.predominant_frequency_hz = freq;
    spec.duration_s = std::max(st.duration_s, 8.0 / freq);
    spec.dt_s = std::min(0.01, 1.0 / (20.0 * freq));
    spec.seed = 0xC0FFEE00ULL + static_cast<std::uint64_t>(t);
    // Built as the family's members are (inversion.hpp): time-scaled so that its measured predominant frequency is
    // the drawn one.
    const GroundMotion raw = synthesize(spec);
    const GroundMotion truth = raw.time_scaled(predominant_frequency_hz(raw) / freq);
    const double true_freq = predominant_frequency_hz(truth);
    Site site;
    site.name = fmt::format("trial {}", t);
    // What happened, from the solvers themselves (not from observation_match, which is under test): each object's
    // friction drawn uniformly in its range with the test's own generator, Housner's restitution, the solvers'
    // default tolerances and run-out (tighter than the inversion's rel_tol 1e-6 and 20 s run-out).
    for (const ObservedObject& proto : objects) {
      ObservedObject obj = proto;
      const double mu = obj.mu.low + (obj.mu.high - obj.mu.low) * params.uniform();
      if (obj.outcome == Outcome::overturned || obj.outcome == Outcome::not_overturned) {
        RockingOptions ro;
        ro.g_m_s2 = st.g_m_s2;
        const RockingSummary s = rock_summary(truth, obj.body, ro);
        obj.outcome = s.overturned ? Outcome::overturned : Outcome::not_overturned;
      } else {
        const SlidingSummary s = slide_summary(truth, SlidingBlock::make(mu, mu, 0.0, SlidingMode::two_way, st.g_m_s2));
        obj.outcome = s.max_abs_displacement_m >= kVisibleSlipM ? Outcome::slid : Outcome::not_slid;
      }
      site.objects.push_back(obj);
    }
    const InversionResult r = invert_site(site, st);
    const bool c95 = in_credible_region(r, pga, true_freq, 0.95);
    const bool c68 = in_credible_region(r, pga, true_freq, 0.68);
    in95 += c95;
    in68 += c68;
    fmt::print("trial {:2}: truth {:.3f} g {:.2f} Hz; median {:.3f} g {:.2f} Hz; in95 {} in68 {}\n", t, pga, true_freq,
               r.pga_estimate_g.median, r.freq_estimate_hz.median, c95, c68);
  }
  fmt::print("coverage: 95 % region {}/{}, 68 % region {}/{}\n", in95, trials, in68, trials);
  EXPECT_GE(in95, static_cast<int>(std::ceil(0.85 * trials)));
  EXPECT_GE(in68, static_cast<int>(std::ceil(0.55 * trials)));
}

}  // namespace
}  // namespace topple
