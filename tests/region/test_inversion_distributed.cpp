// Sites split across MPI ranks (inversion_distributed.hpp): the payload's round trip, the assignment rule, and the
// 2-rank `topple invert` against the 1-rank one (under mpirun, when topple is built with MPI).
#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/regional_scenario.hpp"
#include "support/shared_data.hpp"
#include "topple/region/inversion_distributed.hpp"
#include "topple/output/inversion_output.hpp"

namespace topple {
namespace {

/// The first `count` sites of the regional scenario (objects whose outcomes the solvers computed).
std::vector<Site> scenario_sites(std::size_t count, const InversionSettings& st) {
  const std::vector<Site> all = testing::make_regional_scenario(5, testing::RegionalTruth{}, st).survey.sites;
  return {all.begin(), all.begin() + static_cast<std::ptrdiff_t>(count)};
}

/// The JSON without what may differ between runs: wall times and the provenance (date, command line).
nlohmann::json comparable(nlohmann::json j) {
  if (j.is_object()) {
    j.erase("seconds");
    j.erase("provenance");
    for (auto& [key, value] : j.items()) value = comparable(value);
  } else if (j.is_array()) {
    for (auto& value : j) value = comparable(value);
  }
  return j;
}

// The prior (issue 32) travels too: a site inverted on another rank keeps its log prior and says which prior it was.
TEST(InversionDistributed, ThePriorTravels) {
  InversionSettings st = testing::small_grid(0.02, 8, 2.0, 4.5, 2, 3);
  st.prior = InversionPrior::earthquake;
  const std::vector<Site> sites = scenario_sites(1, st);
  const std::vector<InversionResult> results = invert_sites(sites, st);
  ASSERT_FALSE(results.front().log_prior.empty());
  const std::vector<InversionResult> back = unpack_inversion_results(pack_inversion_results(results));
  EXPECT_EQ(back.front().log_prior, results.front().log_prior);
  EXPECT_EQ(back.front().prior, "earthquake");
}

// A population's report (issue 30) travels with its site's result.
TEST(InversionDistributed, ThePopulationsTravel) {
  const InversionSettings st = testing::small_grid(0.02, 8, 2.0, 4.5, 2, 3);
  std::vector<Site> sites = scenario_sites(1, st);
  Population p;
  p.id = "stones";
  p.count = 30;
  p.overturned = 7;
  p.rocked = 5;
  p.width_m = Interval{0.2, 0.4};
  p.height_m = Interval{0.8, 1.2};
  p.prototype.mu = {0.6, 0.6};
  p.members = 3;
  sites.front().populations.push_back(p);
  const std::vector<InversionResult> results = invert_sites(sites, st);
  ASSERT_EQ(results.front().populations.size(), 1u);
  const std::vector<InversionResult> back = unpack_inversion_results(pack_inversion_results(results));
  ASSERT_EQ(back.front().populations.size(), 1u);
  EXPECT_EQ(io::inversion_json(back.front(), sites.front()).dump(), io::inversion_json(results.front(), sites.front()).dump());
  EXPECT_EQ(back.front().populations.front().rocked, std::optional<int>(5));
}

// Every field survives the trip: the JSON of each result (all of its fields, numbers printed to round-trip precision)
// is the same string before and after, and the wall time (not in every JSON) bit for bit.
TEST(InversionDistributed, PackedResultsUnpackExactly) {
  const InversionSettings st = testing::small_grid(0.02, 8, 2.0, 4.5, 2, 3);
  const std::vector<Site> sites = scenario_sites(3, st);
  ASSERT_EQ(sites.size(), 3u);
  const std::vector<InversionResult> results = invert_sites(sites, st);
  const std::vector<InversionResult> back = unpack_inversion_results(pack_inversion_results(results));
  ASSERT_EQ(back.size(), results.size());
  for (std::size_t s = 0; s < results.size(); ++s) {
    EXPECT_EQ(io::inversion_json(back[s], sites[s]).dump(), io::inversion_json(results[s], sites[s]).dump()) << s;
    EXPECT_EQ(back[s].seconds, results[s].seconds);
    EXPECT_EQ(back[s].bounds.lower.size(), results[s].bounds.lower.size());
  }
  // Three components: the direction of strongest shaking and the RotD100 thresholds travel too (the map and the
  // JSON of a site inverted on another rank need them).
  InversionSettings st3 = testing::small_grid(0.05, 6, 0.5, 8.0, 3, 2);
  st3.components = 3;
  st3.directions = 4;
  st3.duration_s = 6.0;
  Site site3 = sites.front();
  site3.objects.resize(2);
  site3.objects[0].azimuth_deg = 30.0;
  const std::vector<InversionResult> three = invert_sites({site3}, st3);
  ASSERT_TRUE(three.front().three_component && three.front().rotd100_bounds);
  const std::vector<InversionResult> three_back = unpack_inversion_results(pack_inversion_results(three));
  ASSERT_TRUE(three_back.front().three_component && three_back.front().rotd100_bounds);
  EXPECT_EQ(io::inversion_json(three_back.front(), site3).dump(), io::inversion_json(three.front(), site3).dump());
  EXPECT_EQ(three_back.front().three_component->direction.posterior, three.front().three_component->direction.posterior);
  // A payload cut short is refused, not read past its end.
  std::vector<std::uint64_t> words = pack_inversion_results(results);
  words.resize(words.size() / 2);
  EXPECT_THROW((void)unpack_inversion_results(words), std::runtime_error);
}

// Longest processing time first on the object counts {5, 1, 3, 3, 2} over 2 ranks: 5 -> r0; 3 -> r1; 3 -> r1 (3 < 5);
// 2 -> r0 (5 < 6); 1 -> r1 (6 < 7): loads 7 and 7.
TEST(InversionDistributed, SitesDealtByLongestProcessingTime) {
  std::vector<Site> sites(5);
  const int counts[5] = {5, 1, 3, 3, 2};
  for (std::size_t s = 0; s < 5; ++s) sites[s].objects.resize(static_cast<std::size_t>(counts[s]));
  EXPECT_EQ(assign_sites_to_ranks(sites, 2), (std::vector<int>{0, 1, 1, 1, 0}));
  EXPECT_EQ(assign_sites_to_ranks(sites, 1), (std::vector<int>{0, 0, 0, 0, 0}));
  EXPECT_EQ(assign_sites_to_ranks(sites, 8), (std::vector<int>{0, 4, 1, 2, 3}));  // more ranks than sites: one each
  EXPECT_THROW((void)assign_sites_to_ranks(sites, 0), std::invalid_argument);
}

// One process: the distributed call is invert_sites (the same JSON but for the wall time).
TEST(InversionDistributed, OneProcessIsInvertSites) {
  const InversionSettings st = testing::small_grid(0.02, 8, 2.0, 4.5, 2, 3);
  const std::vector<Site> sites = scenario_sites(2, st);
  ensemble::SingleProcess one;
  const auto a = invert_sites_distributed(sites, st, {}, one);
  const auto b = invert_sites(sites, st);
  ASSERT_EQ(a.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    EXPECT_EQ(comparable(nlohmann::json(io::inversion_json(a[s], sites[s]))),
              comparable(nlohmann::json(io::inversion_json(b[s], sites[s]))));
  }
}

// examples/regional_survey.toml on 2 ranks (sites split, results gathered to rank 0) gives the 1-rank JSON exactly:
// every site's inversion, the regional fit, the frequency relation and the pooled estimates (doubles compared as
// printed to round-trip precision: equal bits).
TEST(InversionDistributed, TwoRanksGiveTheOneRankResult) {
  if (!test::mpi_tests_enabled()) GTEST_SKIP() << "mpirun absent, topple built without MPI, or a sanitizer build";
  test::TempDir dir;
  const std::string survey = (std::filesystem::path(TOPPLE_SOURCE_DIR) / "examples/regional_survey.toml").string();
  const auto one = test::run_cli("invert '" + survey + "' --json --quiet --threads 1");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const std::string out = (dir.path() / "two.json").string();
  const std::string cmd = fmt::format(
      "mpirun -n 2 --oversubscribe --allow-run-as-root --mca btl self,vader '{}' invert '{}' --json --quiet --threads 1 "
      ">'{}' 2>'{}.log'",
      TOPPLE_CLI_PATH, survey, out, out);
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << cmd << "\n" << test::slurp(out + ".log");
  const auto a = nlohmann::json::parse(one.out);
  const auto b = nlohmann::json::parse(test::slurp(out));
  ASSERT_EQ(b.at("sites").size(), 12u);  // every site of the example has objects
  EXPECT_EQ(comparable(a), comparable(b));
  EXPECT_TRUE(b.at("region").at("frequency_relation").is_object());
}

}  // namespace
}  // namespace topple
