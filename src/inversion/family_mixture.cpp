// family = "mixture": Bayesian model averaging over the Clough-Penzien family ("synthetic") and the stochastic
// point-source family ("boore2003") (docs/method.md, "A mixture of the two families").
//
// With prior weights w_f, the model-averaged likelihood of a cell is L(c) = sum_f w_f L_f(c) (Hoeting, Madigan,
// Raftery & Volinsky 1999, "Bayesian model averaging: a tutorial", Statist. Sci. 14, eq. 1 applied to the data's
// probability), and the posterior weight of a family is P(f | data) = w_f Z_f / sum_g w_g Z_g with
// Z_f = sum_c prior(c) L_f(c) (ibid., eq. 2). L_f(c) is the mean over family f's motions of the product over objects
// (inversion.hpp, item 2). With w_f = 1/2 and N/2 motions of each family in a cell of N, the plain mean over the
// cell's N motions, which reduce_likelihood takes, is exactly (1/2) mean_synthetic + (1/2) mean_boore2003: the
// mixture costs what one family of N motions costs, and nothing downstream of the family needs to know of it.
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/numerics/statistics.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple::detail {

namespace {

/// The members in the order their motions alternate in a column (motion k from member k % 2).
constexpr std::array<MotionFamily, 2> kMembers{MotionFamily::synthetic, MotionFamily::boore2003};

/// The member's settings: the mixture's, with its family and half the motions.
InversionSettings member_settings(const InversionSettings& st, MotionFamily f) {
  InversionSettings sub = st;
  sub.family = f;
  sub.motions_per_cell = st.motions_per_cell / 2;
  return sub;
}

}  // namespace

double mixture_prior_weight(MotionFamily) { return 1.0 / static_cast<double>(kMembers.size()); }

void validate_mixture_settings(const InversionSettings& st) {
  // Equal prior weights need equal numbers of motions per member (see the header): an even N.
  if (st.motions_per_cell < 2 || st.motions_per_cell % 2 != 0) {
    throw parameter_error("inversion.motions_per_cell",
                          fmt::format("family = \"mixture\" takes half of each cell's motions from each of its two "
                                      "families (synthetic, boore2003): need an even number >= 2, got {}",
                                      st.motions_per_cell));
  }
  // The grid must suit both members (each member's own rule names the field and the family).
  for (const MotionFamily f : kMembers) validate_inversion_settings(member_settings(st, f));
}

std::vector<GroundMotion> mixture_family_motions(const InversionSettings& st, double freq_hz) {
  // Each member's motions are those it makes alone with N/2 motions (the same seeds), alternated: motion k of the
  // column is motion k / 2 of member k % 2 (so that any prefix of the column, e.g. the catalogue's first
  // kCatalogueMotions in evidence.cpp, holds both members alike).
  std::array<std::vector<GroundMotion>, kMembers.size()> per;
  for (std::size_t f = 0; f < kMembers.size(); ++f) per[f] = family_motions(member_settings(st, kMembers[f]), freq_hz);
  std::vector<GroundMotion> out;
  out.reserve(static_cast<std::size_t>(st.motions_per_cell));
  for (std::size_t k = 0; k < per.front().size(); ++k) {
    for (auto& motions : per) out.push_back(std::move(motions[k]));
  }
  return out;
}

void label_mixture_members(FamilyGrid& family) {
  const std::size_t n = family.motions_per_column();
  family.member.resize(n);
  family.draw_index.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    family.member[k] = kMembers[k % kMembers.size()];
    family.draw_index[k] = k / kMembers.size();  // the member's own motion index: its parameters as it draws them alone
  }
}

std::vector<FamilyWeight> mixture_family_weights(const MatchTable& m, const std::vector<MotionFamily>& member,
                                                 const std::vector<double>& error_rates,
                                                 const double* population_run_log,
                                                 const std::vector<double>& log_prior) {
  const std::size_t cells = m.cells();
  if (member.size() != m.motions) throw std::invalid_argument("mixture_family_weights: one member per motion needed");
  // The prior over the cells, normalised (log): uniform when log_prior is empty.
  std::vector<double> lp(cells, -std::log(static_cast<double>(cells)));
  if (!log_prior.empty()) {
    const double z = log_sum_exp(log_prior);
    for (std::size_t c = 0; c < cells; ++c) lp[c] = log_prior[c] - z;
  }
  std::vector<FamilyWeight> out;
  std::vector<double> log_wz;  // log(w_f Z_f)
  for (const MotionFamily f : kMembers) {
    // Member f's own match table (its motions, in order) and population factors: its likelihood L_f as it would be
    // alone (the same motions, the same parameter draws: FamilyGrid::draw_index).
    std::vector<std::size_t> ks;
    for (std::size_t k = 0; k < m.motions; ++k) {
      if (member[k] == f) ks.push_back(k);
    }
    MatchTable sub;
    sub.pga_count = m.pga_count;
    sub.freq_count = m.freq_count;
    sub.motions = ks.size();
    sub.objects = m.objects;
    sub.match.reserve(cells * ks.size() * m.objects);
    std::vector<double> pop;
    if (population_run_log != nullptr) pop.reserve(cells * ks.size());
    for (std::size_t c = 0; c < cells; ++c) {
      for (const std::size_t k : ks) {
        for (std::size_t o = 0; o < m.objects; ++o) sub.match.push_back(m.at(c, k, o));
        if (population_run_log != nullptr) pop.push_back(population_run_log[c * m.motions + k]);
      }
    }
    const std::vector<double> ll =
        reduce_likelihood(sub, error_rates, population_run_log != nullptr ? pop.data() : nullptr).log_likelihood;
    std::vector<double> terms(cells);
    for (std::size_t c = 0; c < cells; ++c) terms[c] = ll[c] + lp[c];
    const double w = mixture_prior_weight(f);
    log_wz.push_back(std::log(w) + log_sum_exp(terms));
    out.push_back({std::string(motion_family_name(f)), w, 0.0});
  }
  const double z = log_sum_exp(log_wz);
  for (std::size_t f = 0; f < out.size(); ++f) out[f].posterior_weight = std::exp(log_wz[f] - z);
  return out;
}

std::string mixture_note(const std::vector<FamilyWeight>& weights) {
  std::string s = "The motions: a model-averaged mixture (Bayesian model averaging), half of each cell's motions from "
                  "each family, prior weights";
  for (const FamilyWeight& w : weights) s += fmt::format(" {} {:.2f}", w.family, w.prior_weight);
  s += "; the objects give them posterior weights";
  for (const FamilyWeight& w : weights) s += fmt::format(" {} {:.2f}", w.family, w.posterior_weight);
  return s + ".";
}

}  // namespace topple::detail
