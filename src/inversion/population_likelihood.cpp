// Populations in the inversion (docs/method.md, "Populations of objects"): the K representative members of each
// population (survey/population.hpp) run under every motion of every cell, the category of each run (overturned,
// slid, rocked, stayed), and the multinomial log-likelihood of the counts per (cell, motion).
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/inversion/matching.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/survey/population.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple::detail {
namespace {

/// A population's members are simulated with the coupled model when it counts the ones that slid (the only model in
/// which a body both slides and rocks), else with the rocking model (docs/survey.md, "Populations").
bool coupled(const Population& p) { return p.slid.has_value(); }

/// The category of one member's run under `ground` (already scaled to the cell's PGA): overturned takes precedence,
/// then slid (base moved >= kVisibleSlipM, coupled model only), then rocked (max |theta| >= kVisibleRockingRad), else
/// stayed.
PopulationCategory run_category(const Population& p, const ObservedObject& member, const DrawnParameters& d,
                                const GroundMotion& ground, double g) {
  const GroundMotion motion = object_motion(member, d, ground);
  const double factor = rocking_plane_factor(member, d);
  if (coupled(p)) {
    const SlideRockOptions options = inversion_slide_rock_options(member, d, g);
    const SlideRockBody body = SlideRockBody::from_rocking(member.body, d.mu);
    const SlideRockSummary s = factor == 1.0 ? slide_rock(motion, body, options).summary
                                             : slide_rock(motion.scaled(factor), body, options).summary;
    if (s.overturned) return PopulationCategory::overturned;
    if (s.max_abs_slide_m >= kVisibleSlipM) return PopulationCategory::slid;
    if (std::max(s.max_rotation_positive_rad, s.max_rotation_negative_rad) >= kVisibleRockingRad) {
      return PopulationCategory::rocked;
    }
    return PopulationCategory::stayed;
  }
  const RockingOptions options = inversion_rocking_options(member, d, g);
  const RockingSummary s = factor == 1.0 ? rock_summary(motion, member.body, options)
                                         : rock_summary(motion.scaled(factor), member.body, options);
  if (s.overturned) return PopulationCategory::overturned;
  return s.max_abs_rotation_rad >= kVisibleRockingRad ? PopulationCategory::rocked : PopulationCategory::stayed;
}

/// The draws of the members come from object indices far above any object's, so that they never repeat an object's.
constexpr std::size_t kMemberDrawOffset = 1000000;

}  // namespace

PopulationRuns simulate_populations(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                                    const FamilyGrid& family, const InversionOptions& options) {
  PopulationRuns out;
  const std::size_t np = pga_g.size();
  const std::size_t nf = family.motions.size();
  const std::size_t n = family.motions_per_column();
  const std::size_t cells = np * nf;
  out.motions = n;
  out.run_log.assign(cells * n, 0.0);
  if (site.populations.empty()) return out;
  // Every member of every population, one "object" of the plan each; owner[m] its population.
  std::vector<ObservedObject> members;
  std::vector<std::size_t> owner;
  for (std::size_t p = 0; p < site.populations.size(); ++p) {
    std::vector<ObservedObject> m = population_members(site.populations[p]);
    out.members.push_back(m.size());
    for (ObservedObject& o : m) {
      members.push_back(std::move(o));
      owner.push_back(p);
    }
  }
  const std::size_t nm = members.size();
  ensemble::Plan plan;
  plan.motion_columns = {"cell", "motion"};
  plan.object_columns = {"member"};
  plan.result_columns = {"category"};
  plan.identity = "topple inversion populations v1";
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        ensemble::MotionCase mc;
        mc.base = family.motions[j][k];
        mc.transform.target_pga_m_s2 = pga_g[i] * st.g_m_s2;
        mc.values = {ensemble::Value(static_cast<std::int64_t>(i * nf + j)), ensemble::Value(static_cast<std::int64_t>(k))};
        plan.motions.push_back(std::move(mc));
      }
    }
  }
  for (const ObservedObject& o : members) plan.objects.push_back({{ensemble::Value(o.id)}});
  // Parameters drawn once per (motion k, member), the same in every cell (as the objects', simulate_matches).
  std::vector<DrawnParameters> drawn(n * nm);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t m = 0; m < nm; ++m) drawn[k * nm + m] = draw_parameters(members[m], st.seed, family.draw_of(k), kMemberDrawOffset + m);
  }
  const double g = st.g_m_s2;
  plan.run = [&](const GroundMotion& motion, std::size_t motion_index, std::size_t o0, std::size_t o1,
                 std::span<ensemble::Value> results) {
    const std::size_t k = motion_index % n;
    for (std::size_t m = o0; m < o1; ++m) {
      const PopulationCategory c = run_category(site.populations[owner[m]], members[m], drawn[k * nm + m], motion, g);
      results[m - o0] = ensemble::Value(static_cast<double>(static_cast<int>(c)));
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = options.threads;
  exec.progress = options.progress;
  const ensemble::ResultTable rows = ensemble::run_in_memory(plan, exec);
  out.runs = rows.rows.size();
  const std::size_t col = rows.columns.size() - 1;
  // Shares of each population's members in each category, per (cell, motion): index ((c * n + k) * 4 + category).
  out.shares.assign(site.populations.size(), std::vector<double>(cells * n * kPopulationCategories, 0.0));
  for (std::size_t row = 0; row < rows.rows.size(); ++row) {
    const std::size_t m = row % nm;
    const std::size_t ck = row / nm;  // c * n + k
    const auto cat = static_cast<std::size_t>(std::get<double>(rows.rows[row][col]));
    out.shares[owner[m]][ck * kPopulationCategories + cat] += 1.0 / static_cast<double>(out.members[owner[m]]);
  }
  for (std::size_t p = 0; p < site.populations.size(); ++p) {
    const Population& pop = site.populations[p];
    for (std::size_t ck = 0; ck < cells * n; ++ck) {
      out.run_log[ck] += population_log_likelihood(pop, std::span<const double>(out.shares[p]).subspan(
                                                            ck * kPopulationCategories, kPopulationCategories));
    }
  }
  return out;
}

std::vector<PopulationReport> population_reports(const Site& site, const PopulationRuns& runs, std::size_t cells) {
  std::vector<PopulationReport> out;
  const std::size_t n = runs.motions;
  for (std::size_t p = 0; p < site.populations.size(); ++p) {
    const Population& pop = site.populations[p];
    PopulationReport rep;
    rep.id = pop.id;
    rep.count = pop.count;
    rep.overturned = pop.overturned;
    rep.rocked = pop.rocked;
    rep.slid = pop.slid;
    rep.members = runs.members[p];
    rep.member_rule = population_member_rule(pop);
    rep.observed_fraction = static_cast<double>(pop.overturned) / static_cast<double>(pop.count);
    rep.model_fraction.assign(cells, 0.0);
    for (std::size_t c = 0; c < cells; ++c) {
      for (std::size_t k = 0; k < n; ++k) {
        rep.model_fraction[c] +=
            runs.shares[p][(c * n + k) * kPopulationCategories + static_cast<std::size_t>(PopulationCategory::overturned)] /
            static_cast<double>(n);
      }
    }
    out.push_back(std::move(rep));
  }
  return out;
}

void finish_population_reports(InversionResult& r) {
  if (r.populations.empty()) return;
  const std::size_t nf = r.freq_hz.size();
  const auto nearest = [](const std::vector<double>& axis, double x) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < axis.size(); ++i) {
      if (std::abs(std::log(axis[i] / x)) < std::abs(std::log(axis[best] / x))) best = i;
    }
    return best;
  };
  const std::size_t at = nearest(r.pga_g, r.pga_estimate_g.median) * nf + nearest(r.freq_hz, r.freq_estimate_hz.median);
  for (PopulationReport& rep : r.populations) {
    rep.model_fraction_at_estimate = rep.model_fraction[at];
    rep.posterior_predictive_fraction = 0.0;
    for (std::size_t c = 0; c < r.posterior.size(); ++c) rep.posterior_predictive_fraction += r.posterior[c] * rep.model_fraction[c];
  }
}

}  // namespace topple::detail
