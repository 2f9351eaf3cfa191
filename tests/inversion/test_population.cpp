// Populations of objects (survey/population.hpp, docs/method.md "Populations of objects"): the multinomial against
// its closed form, the members' rule, the reader's refusals (file, line, field), and the 200-object equivalence.
#include <chrono>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/observed_objects.hpp"
#include "support/shared_data.hpp"

#include "topple/core/error.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/io/survey_file.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/output/report.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/survey/population.hpp"

namespace topple {
namespace {

Population stones(int count, int overturned) {
  Population p;
  p.id = "stones";
  p.count = count;
  p.overturned = overturned;
  p.width_m = Interval{0.2, 0.4};
  p.height_m = Interval{0.8, 1.2};
  p.prototype.mu = {0.6, 0.6};
  return p;
}

TEST(PopulationMembers, StratifiedQuantilesOfTheRanges) {
  Population p = stones(10, 3);
  p.members = 5;
  const std::vector<ObservedObject> m = population_members(p);
  ASSERT_EQ(m.size(), 5U);
  // Heights at the strata's middles (i + 1/2) / 5 of [0.8, 1.2]: 0.84, 0.92, 1.00, 1.08, 1.16 m; the stride for K = 5
  // is the coprime nearest 0.618 * 5 = 3.09: 3, so widths at strata 0, 3, 1, 4, 2 of [0.2, 0.4]: 0.22, 0.34, 0.26,
  // 0.38, 0.30 m.
  const double h[] = {0.84, 0.92, 1.00, 1.08, 1.16};
  const double w[] = {0.22, 0.34, 0.26, 0.38, 0.30};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_NEAR(*m[i].height_m, h[i], 1e-12);
    EXPECT_NEAR(*m[i].width_m, w[i], 1e-12);
    EXPECT_EQ(m[i].outcome, Outcome::overturned);
  }
}

TEST(PopulationMembers, LargeSampleStratifiedBySlenderness) {
  Population p = stones(100, 3);
  p.width_m.reset();
  p.height_m.reset();
  for (int i = 0; i < 10; ++i) p.sample.push_back({0.1 * (10 - i), 1.0, std::nullopt});  // b/h = 1.0, 0.9, ..., 0.1
  p.members = 2;
  const std::vector<ObservedObject> m = population_members(p);
  ASSERT_EQ(m.size(), 2U);
  // Sorted by b/h (0.1 ... 1.0), strata middles floor(0.5 * 10 / 2) = 2 and floor(1.5 * 10 / 2) = 7: b/h 0.3 and 0.8.
  EXPECT_NEAR(*m[0].width_m, 0.3, 1e-12);
  EXPECT_NEAR(*m[1].width_m, 0.8, 1e-12);
  EXPECT_NEAR(population_min_slenderness(p), 0.1, 1e-12);
}

TEST(PopulationLikelihood, BinomialAndMultinomialClosedForms) {
  // 3 of 10 overturned, a model share 0.4, evidence certain (eps 0.02): p = 0.02 + 0.96 * 0.4 = 0.404;
  // ln C(10, 3) + 3 ln 0.404 + 7 ln 0.596 = ln 120 - 2.7191 - 3.6233 = -1.5576.
  Population p = stones(10, 3);
  const double share[4] = {0.6, 0.0, 0.0, 0.4};  // stayed, rocked, slid, overturned
  EXPECT_NEAR(population_log_likelihood(p, share), std::log(120.0) + 3 * std::log(0.404) + 7 * std::log(0.596),
              1e-12);
  // With rocked counted (2 of 10): three categories, p_j = 0.02 + 0.94 f_j; shares 0.4 overturned, 0.25 rocked, rest
  // 0.35; ln (10! / (3! 2! 5!)) = ln 2520.
  p.rocked = 2;
  const double share3[4] = {0.35, 0.25, 0.0, 0.4};
  EXPECT_NEAR(population_log_likelihood(p, share3),
              std::log(2520.0) + 3 * std::log(0.02 + 0.94 * 0.4) + 2 * std::log(0.02 + 0.94 * 0.25) +
                  5 * std::log(0.02 + 0.94 * 0.35),
              1e-12);
}

/// The reader's refusal of `population` keys: the message names the file, the line of the key and the field.
void expect_refused(const std::string& keys, int line, const std::string& field) {
  const std::string text = "[site]\nname = \"c\"\n\n[[population]]\nid = \"stones\"\nmu = 0.6\n" + keys;
  try {
    (void)io::parse_survey(text, "pop.toml", ".");
    ADD_FAILURE() << "accepted: " << keys;
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().file, "pop.toml") << keys;
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(line)) << keys << ": " << e.what();
    EXPECT_EQ(e.where().field, "population[1](stones)." + field) << keys << ": " << e.what();
  }
}

TEST(PopulationReader, BadCountsAndSizesRefusedWithFileLineField) {
  const std::string sizes = "width = [\"0.2m\", \"0.4m\"]\nheight = [\"0.8m\", \"1.2m\"]\n";
  expect_refused("count = 10\noverturned = 11\n" + sizes, 8, "overturned");   // more toppled than present
  expect_refused("count = 10\noverturned = -1\n" + sizes, 8, "overturned");   // negative
  expect_refused("count = -3\noverturned = 0\n" + sizes, 7, "count");
  expect_refused("count = 10\noverturned = 4\nrocked = 4\nslid = 3\n" + sizes, 10, "slid");  // 11 > 10
  expect_refused("count = 10\noverturned = 2\nfallen_azimuths_deg = [10, 20, 30]\n" + sizes, 9,
                 "fallen_azimuths_deg");
  expect_refused("count = 10\noverturned = 2\nsample = []\n", 9, "sample");  // an empty sample
  expect_refused("count = 10\noverturned = 2\nheight = [\"0.8m\", \"1.2m\"]\nwidth = [\"0.2m\", \"0.4m\"]\n"
                 "sample = [{width = \"0.3m\", height = \"1.0m\"},\n  {width = \"0.3m\", height = \"1.5m\"}]\n",
                 12, "sample[2].height");  // a measured size out of the stated range, at its member's line
  expect_refused("count = 10\noverturned = 2\nwidth = [\"0.2m\", \"0.4m\"]\n", 4, "height");  // no height: the table's line
  expect_refused("count = 10.5\noverturned = 2\n" + sizes, 7, "count");
}

TEST(PopulationReader, KeysAsDocumented) {
  const Survey s = io::parse_survey(
      "[site]\nname = \"c\"\n[[population]]\nid = \"stones\"\nshape = \"block\"\ncount = 212\noverturned = 71\n"
      "rocked = 20\nmu = [0.5, 0.7]\nevidence = \"likely\"\nmembers = 5\n"
      "sample = [{width = \"30cm\", height = \"1.0m\"}, {width = \"0.4m\", height = \"90cm\"}]\n",
      "pop.toml", ".");
  ASSERT_EQ(s.sites.front().populations.size(), 1U);
  const Population& p = s.sites.front().populations.front();
  EXPECT_EQ(p.count, 212);
  EXPECT_EQ(p.overturned, 71);
  EXPECT_EQ(p.rocked, std::optional<int>(20));
  EXPECT_FALSE(p.slid);
  EXPECT_EQ(p.members, 5);
  ASSERT_EQ(p.sample.size(), 2U);
  EXPECT_NEAR(*p.sample[0].width_m, 0.30, 1e-12);
  EXPECT_NEAR(*p.sample[1].height_m, 0.90, 1e-12);
  EXPECT_EQ(p.prototype.evidence, Evidence::likely);
  EXPECT_NEAR(p.prototype.mu.high, 0.7, 1e-12);
}

TEST(PopulationReader, CsvRowsAreTheTomlPopulation) {
  // A row with a count is the population (ranges in the header's unit), rows tagged population = its id its sample.
  const Survey csv = io::parse_survey(
      "site.name,c\nid,shape,width_cm,height_cm,mu,count,overturned,rocked,population\n"
      "stones,block,\"[25, 45]\",\"[70, 130]\",\"[0.5, 0.7]\",150,18,4,\n"
      "s1,,30,100,,,,,stones\ns2,,40,90,,,,,stones\n",
      "pop.csv", ".");
  const Survey toml = io::parse_survey(
      "[site]\nname = \"c\"\n[[population]]\nid = \"stones\"\nshape = \"block\"\nwidth = [\"25cm\", \"45cm\"]\n"
      "height = [\"70cm\", \"130cm\"]\nmu = [0.5, 0.7]\ncount = 150\noverturned = 18\nrocked = 4\n"
      "sample = [{width = \"30cm\", height = \"100cm\"}, {width = \"40cm\", height = \"90cm\"}]\n",
      "pop.toml", ".");
  ASSERT_EQ(csv.sites.front().populations.size(), 1U);
  EXPECT_TRUE(csv.sites.front().objects.empty());
  const Population& a = csv.sites.front().populations.front();
  const Population& b = toml.sites.front().populations.front();
  EXPECT_EQ(a.count, b.count);
  EXPECT_EQ(a.overturned, b.overturned);
  EXPECT_EQ(a.rocked, b.rocked);
  EXPECT_EQ(a.width_m->low, b.width_m->low);
  EXPECT_EQ(a.height_m->high, b.height_m->high);
  ASSERT_EQ(a.sample.size(), 2U);
  EXPECT_EQ(*a.sample[1].width_m, *b.sample[1].width_m);
  EXPECT_EQ(*a.sample[0].height_m, *b.sample[0].height_m);
  // A member of no population is refused at its cell.
  try {
    (void)io::parse_survey("id,width_cm,height_cm,mu,count,overturned,population\nst,30,90,0.6,10,2,\n"
                           "m1,30,100,,,,stone\n", "bad.csv", ".");
    ADD_FAILURE() << "accepted a member of an unknown population";
  } catch (const InputError& e) {
    EXPECT_EQ(e.where().line, std::optional<std::size_t>(3)) << e.what();
    EXPECT_NE(std::string(e.what()).find("population"), std::string::npos) << e.what();
  }
}

TEST(PopulationInversion, JsonAndReportShowObservedAgainstModel) {
  // A population only, on a 4 x 3 grid with 3 motions: the JSON's observed fraction is the count's, the model's
  // fractions are shares in [0, 1], and the report writes its table and Figure 5.
  InversionSettings st = testing::small_grid(3);
  st.pga_count = 4;
  st.freq_count = 3;
  Site site;
  site.name = "cemetery";
  Population p = stones(40, 10);
  p.members = 4;
  site.populations.push_back(p);
  InversionOptions options;
  options.next_objects = false;
  const InversionResult r = invert_site(site, st, options);
  ASSERT_EQ(r.populations.size(), 1U);
  const auto j = io::inversion_json(r, site);
  const auto& pj = j.at("populations").at(0);
  EXPECT_EQ(pj.at("count").get<int>(), 40);
  EXPECT_DOUBLE_EQ(pj.at("observed_fraction").get<double>(), 0.25);
  EXPECT_EQ(pj.at("model_fraction_over_pga").at("fraction").size(), 4U);
  EXPECT_EQ(pj.at("model_fraction_over_freq").at("fraction").size(), 3U);
  for (const double f : r.populations.front().model_fraction) {
    EXPECT_GE(f, 0.0);
    EXPECT_LE(f, 1.0);
  }
  // The highest PGA (2 g) topples more of the class than the lowest (0.05 g, below every member's g b/h >= 0.17 g:
  // none can even lift there).
  EXPECT_EQ(r.populations.front().model_fraction[0], 0.0);
  EXPECT_GT(r.populations.front().model_fraction[3 * 3 + 0], 0.0);
  test::TempDir tmp;
  Survey survey;
  survey.sites = {site};
  survey.inversion = st;
  write_report(tmp.path(), survey, site, r);
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "population.svg"));
  const std::string html = test::slurp(tmp.path() / "index.html");
  EXPECT_NE(html.find("populations-table"), std::string::npos);
  EXPECT_NE(html.find("Figure 5"), std::string::npos);
}

TEST(PopulationInversion, SlidCountedRunsTheCoupledModel) {
  // Counting the ones that slid makes the members coupled slide-rock bodies (the only model that does both): with
  // mu 0.15 below every member's b/h >= 0.17, members slide before they lift (Shenton 1996), so at 2 g some slide and
  // at 0.05 g (below mu g = 0.15 g) none moves; the likelihood stays finite everywhere.
  InversionSettings st = testing::small_grid(2);
  st.pga_count = 3;
  st.freq_count = 2;
  Site site;
  Population p = stones(20, 2);
  p.rocked = 3;
  p.slid = 6;
  p.prototype.mu = {0.15, 0.15};
  p.members = 3;
  site.populations.push_back(p);
  InversionOptions options;
  options.next_objects = false;
  const InversionResult r = invert_site(site, st, options);
  for (const double ll : r.log_likelihood) EXPECT_TRUE(std::isfinite(ll));
  // The static threshold: some overturned, so some lifted, PGA > g min(b/h) = 0.2 / 1.2 g (the smallest width over
  // the largest height), above the slip's g min(mu, b/h) = 0.15 g.
  ASSERT_TRUE(r.bounds.hard_lower_g);
  EXPECT_NEAR(*r.bounds.hard_lower_g, 0.2 / 1.2, 1e-12);
  // Only slid counted: the slip's threshold.
  site.populations.front().overturned = 0;
  site.populations.front().rocked = 0;
  EXPECT_NEAR(*static_bounds(site).hard_lower_g, 0.15, 1e-12);
}

TEST(PopulationInversion, FallenAzimuthsPointTheDirectionInThreeComponents) {
  // Three components (eq. P2): 40 tombstone-like cylinders (diameter 0.15-0.25 m, height 0.6-1.0 m), 20 fallen, five
  // of them towards 35-50 deg (and 220 deg, the same axis). The direction of strongest shaking is then found near that
  // axis (the mode within one bin, 30 deg, of 42 deg) and its 95 % arc is narrower than from the count alone.
  InversionSettings st = testing::small_grid(0.1, 4, 1.0, 4.0, 2, 3);
  st.components = 3;
  st.directions = 6;
  st.duration_s = 6.0;
  st.coherence = 0.5;
  Population p;
  p.id = "tombs";
  p.shape = "cylinder";
  p.count = 40;
  p.overturned = 20;
  p.diameter_m = Interval{0.15, 0.25};
  p.height_m = Interval{0.6, 1.0};
  p.prototype.mu = {0.6, 0.6};
  p.members = 4;
  Site counted;
  counted.populations.push_back(p);
  p.fallen_azimuths_deg = {40.0, 45.0, 35.0, 220.0, 50.0};
  Site directed;
  directed.populations.push_back(p);
  InversionOptions options;
  options.next_objects = false;
  const InversionResult a = invert_site(counted, st, options);
  const InversionResult b = invert_site(directed, st, options);
  ASSERT_TRUE(a.three_component && b.three_component);
  ASSERT_EQ(b.populations.size(), 1U);
  const DirectionEstimate& da = a.three_component->direction;
  const DirectionEstimate& db = b.three_component->direction;
  const double off = std::abs(std::remainder(db.mode_deg - 42.0, 180.0));
  EXPECT_LE(off, 30.0) << "mode " << db.mode_deg;
  EXPECT_LT(db.ci95.width_deg, da.ci95.width_deg);
  std::printf("[ population 3c ] direction mode %.0f deg, 95 %% arc %.0f deg (count alone: mode %.0f, arc %.0f deg)\n",
              db.mode_deg, db.ci95.width_deg, da.mode_deg, da.ci95.width_deg);
}

TEST(PopulationInversion, TwoHundredCountedInvertAsTightlyAsListedAndFaster) {
  // 200 gravestones, width U(0.2, 0.45) m and height U(0.6, 1.2) m (PortableRandom(2030), in order), under one true
  // motion (0.45 g, 2 Hz, seed 0xC0FFEE30, never a family seed). Listed: 200 objects, each overturned or not (from
  // the rocking solver itself). Counted: one population, its count and overturned, the same 200 sizes as its measured
  // sample, K = 20 members (the middle of 20 slenderness strata).
  InversionSettings st = testing::small_grid(6);
  st.pga_count = 10;
  st.freq_count = 5;
  const GroundMotion truth = testing::true_motion(st, 0.45, 2.0, 0xC0FFEE30);
  PortableRandom rng(2030);
  Site listed;
  listed.name = "listed";
  Site counted;
  counted.name = "counted";
  Population pop;
  pop.id = "stones";
  pop.count = 200;
  pop.members = 20;
  pop.prototype.mu = {0.6, 0.6};
  for (int i = 0; i < 200; ++i) {
    const double w = 0.2 + 0.25 * rng.uniform();
    const double h = 0.6 + 0.6 * rng.uniform();
    ObservedObject o = testing::block(fmt::format("s{}", i), w, h, {0.6, 0.6}, Outcome::not_overturned);
    o = testing::observe_uncoupled(o, 0.6, truth, st);
    if (o.outcome == Outcome::overturned) ++pop.overturned;
    listed.objects.push_back(o);
    pop.sample.push_back({w, h, std::nullopt});
  }
  counted.populations.push_back(pop);
  InversionOptions options;
  options.next_objects = false;
  const auto t0 = std::chrono::steady_clock::now();
  const InversionResult a = invert_site(listed, st, options);
  const auto t1 = std::chrono::steady_clock::now();
  const InversionResult b = invert_site(counted, st, options);
  const auto t2 = std::chrono::steady_clock::now();
  const double listed_s = std::chrono::duration<double>(t1 - t0).count();
  const double counted_s = std::chrono::duration<double>(t2 - t1).count();
  // The overturned fraction must be informative (neither none nor all), or the test would prove nothing.
  ASSERT_GT(pop.overturned, 20);
  ASSERT_LT(pop.overturned, 180);
  // One grid cell: the PGA axis' ratio (2 / 0.05)^(1/9) = 1.507. The medians within one cell and the lower 95 % ends
  // within one and a half. The upper 95 % end: the count alone leaves it wider (measured: listed 0.69 g, counted open
  // at the grid's top with K = 20 and with K = 200, all 200 members: what is lost is which stones fell, their sizes'
  // scale at a given b/h, which separates high frequency and high PGA; not the K-member approximation). So it must be
  // no tighter than the listed one's (tighter would claim information the count does not hold).
  const double cell = std::pow(st.pga_max_g / st.pga_min_g, 1.0 / (st.pga_count - 1));
  const auto log_ratio = [](double x, double y) { return std::abs(std::log(x / y)); };
  EXPECT_LT(log_ratio(a.pga_estimate_g.median, b.pga_estimate_g.median), std::log(cell));
  ASSERT_TRUE(a.pga_estimate_g.ci95_low && b.pga_estimate_g.ci95_low);
  EXPECT_LT(log_ratio(*a.pga_estimate_g.ci95_low, *b.pga_estimate_g.ci95_low), 1.5 * std::log(cell));
  ASSERT_TRUE(a.pga_estimate_g.ci95_high);
  EXPECT_TRUE(!b.pga_estimate_g.ci95_high || *b.pga_estimate_g.ci95_high >= *a.pga_estimate_g.ci95_high / cell);
  // Frequency is weakly constrained by either (the listed median 0.58 Hz, the counted 1.4 Hz, truth 2 Hz): the
  // medians within two cells of the frequency axis ((12 / 0.5)^(1/4) = 2.21).
  const double fcell = std::pow(st.freq_max_hz / st.freq_min_hz, 1.0 / (st.freq_count - 1));
  EXPECT_LT(log_ratio(a.freq_estimate_hz.median, b.freq_estimate_hz.median), 2.0 * std::log(fcell));
  // The truth inside the listed objects' 95 % interval of PGA.
  EXPECT_TRUE(*a.pga_estimate_g.ci95_low < 0.45 && *a.pga_estimate_g.ci95_high > 0.45);
  // The truth inside the counted population's 95 % interval of PGA.
  EXPECT_TRUE(!b.pga_estimate_g.ci95_low || *b.pga_estimate_g.ci95_low < 0.45);
  EXPECT_TRUE(!b.pga_estimate_g.ci95_high || *b.pga_estimate_g.ci95_high > 0.45);
  // Far faster: 20 members' runs instead of 200 objects' (and no 200-object leave-one-out): at least 4 times.
  EXPECT_LT(counted_s * 4.0, listed_s);
  ASSERT_EQ(b.populations.size(), 1U);
  EXPECT_NEAR(b.populations.front().observed_fraction, pop.overturned / 200.0, 1e-15);
  // The model's posterior-predictive fraction reproduces the observed one within 0.1 (a calibrated answer).
  EXPECT_NEAR(b.populations.front().posterior_predictive_fraction, b.populations.front().observed_fraction, 0.1);
  std::printf("[ population ] %d of 200 overturned; listed: median %.3f g, 95 %% [%s, %s] g, %.3f Hz, %.2f s; "
              "counted: median %.3f g, 95 %% [%s, %s] g, %.3f Hz, %.2f s; posterior-predictive fraction %.3f\n",
              pop.overturned, a.pga_estimate_g.median,
              a.pga_estimate_g.ci95_low ? fmt::format("{:.3f}", *a.pga_estimate_g.ci95_low).c_str() : "open",
              a.pga_estimate_g.ci95_high ? fmt::format("{:.3f}", *a.pga_estimate_g.ci95_high).c_str() : "open",
              a.freq_estimate_hz.median, listed_s, b.pga_estimate_g.median,
              b.pga_estimate_g.ci95_low ? fmt::format("{:.3f}", *b.pga_estimate_g.ci95_low).c_str() : "open",
              b.pga_estimate_g.ci95_high ? fmt::format("{:.3f}", *b.pga_estimate_g.ci95_high).c_str() : "open",
              b.freq_estimate_hz.median, counted_s, b.populations.front().posterior_predictive_fraction);
}

}  // namespace
}  // namespace topple
