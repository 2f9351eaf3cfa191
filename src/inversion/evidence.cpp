// The objects' own evidence, the ridge and what to look for next (evidence.hpp; docs/method.md has the equations).
#include "topple/inversion/evidence.hpp"

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "topple/inversion/matching.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple {

std::vector<double> marginal_over_pga(const std::vector<double>& cells, std::size_t np, std::size_t nf) {
  std::vector<double> m(np, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) m[i] += cells[i * nf + j];
  }
  return m;
}

std::vector<double> marginal_over_freq(const std::vector<double>& cells, std::size_t np, std::size_t nf) {
  std::vector<double> m(nf, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) m[j] += cells[i * nf + j];
  }
  return m;
}

namespace {

/// exp(log_values - max) normalised to sum 1 (the max first: no overflow, no underflow of the largest).
std::vector<double> normalised_exp(const std::vector<double>& log_values) {
  const double top = *std::max_element(log_values.begin(), log_values.end());
  std::vector<double> p(log_values.size());
  double z = 0.0;
  for (std::size_t c = 0; c < p.size(); ++c) z += p[c] = std::exp(log_values[c] - top);
  for (double& v : p) v /= z;
  return p;
}

std::size_t argmax(const std::vector<double>& v) {
  return static_cast<std::size_t>(std::max_element(v.begin(), v.end()) - v.begin());
}

/// Shannon entropy (bits) of a distribution that sums to `total` (> 0), normalised by it.
double entropy_bits(const std::vector<double>& p, double total) {
  double h = 0.0;
  for (const double v : p) {
    if (v > 0.0) {
      const double q = v / total;
      h -= q * std::log2(q);
    }
  }
  return h;
}

}  // namespace

std::vector<double> prior_cells(const InversionResult& r) {
  const std::size_t cells = r.pga_g.size() * r.freq_hz.size();
  if (r.log_prior.empty()) return std::vector<double>(cells, 1.0 / static_cast<double>(cells));
  if (r.log_prior.size() != cells) throw std::invalid_argument("prior_cells: log_prior has not one value per cell");
  return normalised_exp(r.log_prior);
}

std::vector<PgaGivenFreq> ridge_pga_given_freq(const std::vector<double>& ll, const std::vector<double>& pga_g,
                                               const std::vector<double>& freq_hz) {
  const std::size_t np = pga_g.size(), nf = freq_hz.size();
  if (ll.size() != np * nf) throw std::invalid_argument("ridge_pga_given_freq: the log-likelihood is not np x nf");
  const double top = *std::max_element(ll.begin(), ll.end());
  std::vector<double> mass(nf, 0.0);
  std::vector<std::vector<double>> column(nf, std::vector<double>(np, 0.0));
  for (std::size_t j = 0; j < nf; ++j) {
    for (std::size_t i = 0; i < np; ++i) mass[j] += column[j][i] = std::exp(ll[i * nf + j] - top);
  }
  const double largest = *std::max_element(mass.begin(), mass.end());
  std::vector<PgaGivenFreq> out(nf);
  for (std::size_t j = 0; j < nf; ++j) {
    out[j].freq_hz = freq_hz[j];
    out[j].likelihood_share = mass[j] / largest;
    if (out[j].likelihood_share < kRidgeNegligibleShare) continue;
    for (double& v : column[j]) v /= mass[j];  // L(i | j): the column's likelihood over PGA, summing to 1
    out[j].pga_g = detail::marginal_estimate(pga_g, column[j], pga_g[argmax(column[j])]);
  }
  return out;
}

void fill_likelihood_estimates(InversionResult& r) {
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const std::vector<double> lik = normalised_exp(r.log_likelihood);  // the posterior under the log-uniform prior
  r.marginal_pga_likelihood = marginal_over_pga(lik, np, nf);
  r.marginal_freq_likelihood = marginal_over_freq(lik, np, nf);
  const std::size_t best = argmax(r.log_likelihood);
  r.pga_likelihood_g = detail::marginal_estimate(r.pga_g, r.marginal_pga_likelihood, r.pga_g[best / nf]);
  r.freq_likelihood_hz = detail::marginal_estimate(r.freq_hz, r.marginal_freq_likelihood, r.freq_hz[best % nf]);
  r.pga_given_freq = ridge_pga_given_freq(r.log_likelihood, r.pga_g, r.freq_hz);
}

InformationGain expected_information_gain(const std::vector<double>& posterior, std::size_t np, std::size_t nf,
                                          const std::vector<std::vector<double>>& outcome_probability) {
  if (posterior.size() != np * nf) throw std::invalid_argument("expected_information_gain: posterior is not np x nf");
  for (const auto& py : outcome_probability) {
    if (py.size() != posterior.size()) {
      throw std::invalid_argument("expected_information_gain: an outcome's table is not one value per cell");
    }
  }
  const double total = std::accumulate(posterior.begin(), posterior.end(), 0.0);
  const double h_pga = entropy_bits(marginal_over_pga(posterior, np, nf), total);
  const double h_freq = entropy_bits(marginal_over_freq(posterior, np, nf), total);
  // EIG = H(p_axis) - sum_y P(y) H(p_axis | y) (Lindley 1956): the mutual information of the outcome and the axis.
  double expected_h_pga = 0.0, expected_h_freq = 0.0;
  std::vector<double> joint(posterior.size());
  for (const auto& py : outcome_probability) {
    double p_y = 0.0;
    for (std::size_t c = 0; c < joint.size(); ++c) p_y += joint[c] = posterior[c] * py[c];
    if (!(p_y > 0.0)) continue;  // an outcome that cannot happen adds nothing
    expected_h_pga += p_y / total * entropy_bits(marginal_over_pga(joint, np, nf), p_y);
    expected_h_freq += p_y / total * entropy_bits(marginal_over_freq(joint, np, nf), p_y);
  }
  // Mutual information is never negative; what rounding leaves below zero is zero.
  return {std::max(0.0, h_pga - expected_h_pga), std::max(0.0, h_freq - expected_h_freq)};
}

std::size_t catalogue_outcome_count(const ObservedObject& object) {
  return object_model(object) == ObjectModel::slide ? 2 : 3;
}

std::size_t catalogue_outcome(const ObservedObject& object, const DrawnParameters& p, const GroundMotion& motion,
                              double g) {
  if (object_model(object) == ObjectModel::slide) {
    // As observation_match: the response to amp * a with mu is amp times the response to a with mu / amp.
    const double amp = p.amplification;
    const SlidingSummary s =
        slide_summary(motion, SlidingBlock::make(p.mu / amp, p.mu / amp, 0.0, SlidingMode::two_way, g));
    return amp * s.max_abs_displacement_m >= kVisibleSlipM ? 0 : 1;
  }
  const double factor = rocking_plane_factor(object, p);
  const RockingOptions options = inversion_rocking_options(object, p, g);
  if (object_model(object) == ObjectModel::three_d) {
    // model = "3d" (a box, a mesh or a cylinder): the three-dimensional engine, not the planar one, with the motion
    // along the body's +x axis (its bearing); friction_3d: mu_s = the drawn mu. The same categories (kVisibleRockingRad
    // on the tilt).
    Rigid3DOptions o = rigid3d_options(options);
    if (object.friction_3d) o.mu_s = p.mu;
    const GroundMotion m = motion.scaled(factor);
    const Rigid3DSummary s =
        object.body_3d ? rock3d(m, nullptr, nullptr, *object.body_3d, o).summary
                       : rock3d_cylinder(m, nullptr, nullptr,
                                         CylinderBody3D::solid(2.0 * object.body.a_m, 2.0 * object.body.h_m), o)
                             .summary;
    if (s.overturned) return 0;
    return s.max_tilt_rad >= kVisibleRockingRad ? 1 : 2;
  }
  const RockingSummary s = factor == 1.0 ? rock_summary(motion, object.body, options)
                                         : rock_summary(motion.scaled(factor), object.body, options);
  if (s.overturned) return 0;
  return s.max_abs_rotation_rad >= kVisibleRockingRad ? 1 : 2;
}

namespace {

bool same_body(const RockingBody& a, const RockingBody& b) {
  const bool pivots = a.negative_pivot.has_value() == b.negative_pivot.has_value() &&
                      (!a.negative_pivot || (a.negative_pivot->b_m == b.negative_pivot->b_m &&
                                             a.negative_pivot->D_m2 == b.negative_pivot->D_m2));
  return a.shape == b.shape && a.a_m == b.a_m && a.h_m == b.h_m && a.D_m2 == b.D_m2 && pivots;
}

}  // namespace

bool detail::same_rocking_run(const ObservedObject& a, const DrawnParameters& pa, const ObservedObject& b,
                              const DrawnParameters& pb, double g) {
  // observation_match and catalogue_outcome both call rock_summary(motion, body, inversion_rocking_options(...))
  // when the model is rock, there is no support filter and the plane factor is 1: the same call when the bodies
  // and the options (restitution; the rest is fixed) agree.
  if (object_model(a) != ObjectModel::rock || object_model(b) != ObjectModel::rock) return false;
  if (a.support_filter || b.support_filter) return false;
  if (rocking_plane_factor(a, pa) != 1.0 || rocking_plane_factor(b, pb) != 1.0) return false;
  if (!same_body(a.body, b.body)) return false;
  const RockingOptions oa = inversion_rocking_options(a, pa, g);
  const RockingOptions ob = inversion_rocking_options(b, pb, g);
  return oa.restitution == ob.restitution && oa.e == ob.e && oa.g_m_s2 == ob.g_m_s2 &&
         oa.max_run_out_s == ob.max_run_out_s && oa.rel_tol == ob.rel_tol && oa.abs_tol == ob.abs_tol;
}

std::vector<NextObject> suggest_next_objects(const InversionResult& r, const InversionSettings& st,
                                             const FamilyGrid& family, const InversionOptions& options) {
  return detail::suggest_next_objects(r, st, family, options, nullptr);
}

std::vector<NextObject> detail::suggest_next_objects(const InversionResult& r, const InversionSettings& st,
                                                     const FamilyGrid& family, const InversionOptions& options,
                                                     const CatalogueShare* share) {
  const std::size_t np = r.pga_g.size(), nf = r.freq_hz.size();
  const std::size_t n = family.motions_per_column();
  if (r.posterior.size() != np * nf || family.motions.size() != nf || n == 0) {
    throw std::invalid_argument("suggest_next_objects: the result and the family disagree");
  }
  // The cells holding 99.9 % of the posterior, by decreasing posterior: the rest cannot move the expectation by more
  // than their 0.1 % (the EIG is taken over this truncated, renormalised posterior: docs/method.md).
  std::vector<std::size_t> order(r.posterior.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&r](std::size_t a, std::size_t b) { return r.posterior[a] > r.posterior[b]; });
  std::vector<std::size_t> cells;
  double mass = 0.0;
  for (const std::size_t c : order) {
    if (mass >= 0.999) break;
    cells.push_back(c);
    mass += r.posterior[c];
  }
  std::vector<double> truncated(r.posterior.size(), 0.0);
  for (const std::size_t c : cells) truncated[c] = r.posterior[c] / mass;

  const std::vector<CatalogueObject>& catalogue = household_catalogue();
  const std::size_t nx = catalogue.size();
  // The first kCatalogueMotions motions of each cell (common random numbers: the same ones in every cell), pooled over
  // the 3 x 3 neighbourhood below: with all N the ranking nearly doubled the example's time (13.2 s -> 24.3 s CPU).
  const std::size_t nk = std::min<std::size_t>(n, kCatalogueMotions);
  // counts[(x * cells + s) * 3 + y]: runs of catalogue object x in the s-th cell with outcome y.
  std::vector<unsigned> counts(nx * cells.size() * 3, 0);
  const bool shared = share != nullptr && share->cells == r.posterior.size() && share->nk == nk;
  // The parameters of motion k drawn as for the survey's objects with object indices after any survey's (1000 + x).
  std::vector<DrawnParameters> drawn(nx * nk);
  for (std::size_t x = 0; x < nx; ++x) {
    for (std::size_t k = 0; k < nk; ++k) drawn[x * nk + k] = draw_parameters(catalogue[x].object, st.seed, k, 1000 + x);
  }
  // One task per (cell, motion): the scaled motion is made once for all the catalogue objects that need a run, and
  // not at all when the survey's runs gave every outcome (CatalogueShare).
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, cells.size() * nk, [&](std::size_t task) {
      const std::size_t s = task / nk;
      const std::size_t k = task % nk;
      const std::size_t c = cells[s];
      std::optional<GroundMotion> motion;  // the family's motion k of the cell's column at the cell's PGA
      for (std::size_t x = 0; x < nx; ++x) {
        const std::uint8_t known = shared ? share->at(x, c, k) : detail::CatalogueShare::kNotRecorded;
        std::size_t y = known;
        if (known == detail::CatalogueShare::kNotRecorded) {
          // (Family motions have PGA 1 m/s^2.)
          if (!motion) motion = family.motions[c % nf][k]->scaled(r.pga_g[c / nf] * st.g_m_s2);
          y = catalogue_outcome(catalogue[x].object, drawn[x * nk + k], *motion, st.g_m_s2);
        }
        // Distinct (x, s) slots of one task; tasks of one cell (several k) meet on the same slot: atomic.
        std::atomic_ref<unsigned>(counts[(x * cells.size() + s) * 3 + y]).fetch_add(1, std::memory_order_relaxed);
      }
    });
  });

  // Where each grid cell sits in `cells` (none: not run).
  std::vector<std::ptrdiff_t> slot(r.posterior.size(), -1);
  for (std::size_t s = 0; s < cells.size(); ++s) slot[cells[s]] = static_cast<std::ptrdiff_t>(s);
  std::vector<NextObject> out;
  const double nn = static_cast<double>(nk);
  for (std::size_t x = 0; x < nx; ++x) {
    const ObservedObject& object = catalogue[x].object;
    const std::size_t ny = catalogue_outcome_count(object);
    const double kk = static_cast<double>(ny);
    // P(y | c): the share of outcome y over the runs of the cell's 3 x 3 neighbourhood (weights 4/2/1, as the
    // likelihood pools; neighbours that were not run are left out), smoothed (share N + 1/2) / (N + K/2): a share of 0
    // or 1 is not certainty, and certainty would overstate the information. Outside the run cells (posterior 0 here):
    // uniform.
    std::vector<std::vector<double>> py(ny, std::vector<double>(r.posterior.size(), 1.0 / kk));
    for (std::size_t s = 0; s < cells.size(); ++s) {
      std::vector<double> pooled(ny, 0.0);
      double weight = 0.0;
      for (const auto& [c2, w] : detail::neighbourhood(cells[s], np, nf)) {
        if (slot[c2] < 0) continue;
        const std::size_t s2 = static_cast<std::size_t>(slot[c2]);
        for (std::size_t y = 0; y < ny; ++y) pooled[y] += w * static_cast<double>(counts[(x * cells.size() + s2) * 3 + y]);
        weight += w;
      }
      for (std::size_t y = 0; y < ny; ++y) py[y][cells[s]] = (pooled[y] / weight + 0.5) / (nn + 0.5 * kk);
    }
    const InformationGain gain = expected_information_gain(truncated, np, nf, py);
    NextObject next;
    next.object = catalogue[x].name;
    next.description = catalogue[x].description;
    next.look_for = ny == 3 ? "whether it fell, rocked or stood still" : "whether it slid";
    next.bits_pga = gain.bits_pga;
    next.bits_freq = gain.bits_freq;
    out.push_back(std::move(next));
  }
  std::stable_sort(out.begin(), out.end(), [](const NextObject& a, const NextObject& b) {
    return a.bits_pga + a.bits_freq > b.bits_pga + b.bits_freq;
  });
  return out;
}

namespace {

std::string two(double v) { return fmt::format("{:.2g}", v); }

/// "about 0.55 g (68 %: 0.4-0.7 g)", open ends said as below/above the grid.
std::string estimate_words(const Estimate& e, const char* unit) {
  std::string s = e.median_edge < 0   ? std::string("below the grid")
                  : e.median_edge > 0 ? std::string("above the grid")
                                      : fmt::format("about {} {}", two(e.median), unit);
  const std::string lo = e.ci68_low ? two(*e.ci68_low) : std::string("below the grid");
  const std::string hi = e.ci68_high ? two(*e.ci68_high) : std::string("above the grid");
  return s + fmt::format(" (68 %: {} to {} {})", lo, hi, unit);
}

/// The median and 68 % ends as the summary writes them (two digits): equal words, no clause.
bool same_words(const Estimate& a, const Estimate& b) {
  const auto end = [](const std::optional<double>& v) { return v ? two(*v) : std::string("-"); };
  return a.median_edge == b.median_edge && two(a.median) == two(b.median) && end(a.ci68_low) == end(b.ci68_low) &&
         end(a.ci68_high) == end(b.ci68_high);
}

}  // namespace

std::string likelihood_summary_clause(const InversionResult& r) {
  if (r.marginal_pga_likelihood.empty()) return {};
  if (same_words(r.pga_likelihood_g, r.pga_estimate_g) && same_words(r.freq_likelihood_hz, r.freq_estimate_hz)) {
    return {};
  }
  return fmt::format("; the objects alone (the likelihood, without the {} prior) give a PGA {} and a frequency {}",
                     r.prior, estimate_words(r.pga_likelihood_g, "g"), estimate_words(r.freq_likelihood_hz, "Hz"));
}

std::string next_objects_summary_clause(const InversionResult& r) {
  if (r.next_objects.empty()) return {};
  // By reference into the list: the same object best on both axes is named once.
  const auto best = [&r](bool freq) -> const NextObject& {
    return *std::max_element(r.next_objects.begin(), r.next_objects.end(), [freq](const NextObject& a, const NextObject& b) {
      return freq ? a.bits_freq < b.bits_freq : a.bits_pga < b.bits_pga;
    });
  };
  const NextObject& f = best(true);
  const NextObject& p = best(false);
  constexpr double kWorthSaying = 0.05;  // bits: a twentieth of a yes/no answer
  const auto words = [](const NextObject& o, double bits) {
    return fmt::format("a {} ({}) and {} ({:.2f} bit)", o.object, o.description, o.look_for, bits);
  };
  std::vector<std::string> parts;
  if (&f == &p && f.bits_freq >= kWorthSaying && p.bits_pga >= kWorthSaying) {
    parts.push_back(fmt::format("to narrow both the frequency ({:.2f} bit) and the PGA ({:.2f} bit), look for a {} ({}) "
                                "and {}",
                                f.bits_freq, p.bits_pga, f.object, f.description, f.look_for));
  } else {
    if (f.bits_freq >= kWorthSaying) parts.push_back("to narrow the frequency, look for " + words(f, f.bits_freq));
    if (p.bits_pga >= kWorthSaying) parts.push_back("to narrow the PGA, look for " + words(p, p.bits_pga));
  }
  if (parts.empty()) return {};
  std::string s = parts.front();
  if (parts.size() > 1) s += "; " + parts[1];
  s[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  return " " + s + ".";
}

}  // namespace topple
