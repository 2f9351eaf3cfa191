// Inversion of field observations: static bounds and the likelihood over PGA x predominant frequency. See
// inversion.hpp and docs/method.md for the method.
#include "topple/inversion.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "topple/ensemble.hpp"
#include "topple/error.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"
#include "topple/spectra.hpp"
#include "topple/synthesis.hpp"
#include "topple/units.hpp"

namespace topple {
namespace {

bool is_sliding_outcome(Outcome o) { return o == Outcome::slid || o == Outcome::not_slid; }

std::string fmt_g(double v) { return fmt::format("{:.3g} g", v); }

/// Edges (in log) of the cells of a log-spaced axis: geometric midpoints, extended by half a step at each end.
std::vector<double> log_edges(const std::vector<double>& v) {
  const std::size_t n = v.size();
  std::vector<double> e(n + 1);
  for (std::size_t i = 1; i < n; ++i) e[i] = 0.5 * (std::log(v[i - 1]) + std::log(v[i]));
  e[0] = std::log(v[0]) - (n > 1 ? 0.5 * (std::log(v[1]) - std::log(v[0])) : 0.5);
  e[n] = std::log(v[n - 1]) + (n > 1 ? 0.5 * (std::log(v[n - 1]) - std::log(v[n - 2])) : 0.5);
  return e;
}

/// Quantile q of a marginal over a log axis; `cell` receives the cell it falls in.
double quantile(const std::vector<double>& values, const std::vector<double>& marginal, double q, std::size_t& cell) {
  const auto e = log_edges(values);
  double c = 0.0;
  for (std::size_t i = 0; i < marginal.size(); ++i) {
    if (c + marginal[i] >= q && marginal[i] > 0.0) {
      cell = i;
      return std::exp(e[i] + (q - c) / marginal[i] * (e[i + 1] - e[i]));
    }
    c += marginal[i];
  }
  cell = marginal.size() - 1;
  return std::exp(e.back());
}

Estimate estimate(const std::vector<double>& values, const std::vector<double>& marginal, double best) {
  Estimate est;
  est.best = best;
  std::size_t cell = 0;
  est.median = quantile(values, marginal, 0.5, cell);
  const std::size_t last = values.size() - 1;
  const auto lower = [&](double q) -> std::optional<double> {
    std::size_t at = 0;
    const double v = quantile(values, marginal, q, at);
    return at == 0 ? std::nullopt : std::optional<double>(v);
  };
  const auto upper = [&](double q) -> std::optional<double> {
    std::size_t at = 0;
    const double v = quantile(values, marginal, q, at);
    return at == last ? std::nullopt : std::optional<double>(v);
  };
  est.ci68_low = lower(0.16);
  est.ci68_high = upper(0.84);
  est.ci95_low = lower(0.025);
  est.ci95_high = upper(0.975);
  return est;
}

std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  SplitMix64 s(a * 0x9E3779B97F4A7C15ULL + b);
  return s.next();
}

}  // namespace

StaticBounds static_bounds(const Site& site) {
  StaticBounds b;
  for (const ObservedObject& o : site.objects) {
    const double amp_hi = o.amplification.high;
    const double amp_lo = o.amplification.low;
    const double tan_alpha = std::tan(o.body.alpha_rad());
    const std::string amp_text = o.amplification.is_value() && o.amplification.low == 1.0
                                     ? ""
                                     : fmt::format(" / amplification {:.3g}", o.amplification.is_value() ? amp_hi : amp_hi);
    switch (o.outcome) {
      case Outcome::slid:
        b.lower.push_back({o.mu.low / amp_hi, o.id, fmt::format("slid: PGA > mu g = {}{}", fmt_g(o.mu.low), amp_text)});
        break;
      case Outcome::not_slid:
        b.upper.push_back({o.mu.high / amp_lo, o.id,
                           fmt::format("did not slide: PGA <= mu g = {}{}", fmt_g(o.mu.high), amp_text)});
        break;
      case Outcome::overturned:
      case Outcome::rocked:
        b.lower.push_back({tan_alpha / amp_hi, o.id,
                           fmt::format("{}: PGA > g a/h = {}{}", outcome_name(o.outcome), fmt_g(tan_alpha), amp_text)});
        break;
      case Outcome::not_overturned:
        break;  // a body can rock without falling at any PGA above g a/h: no static bound
    }
  }
  for (const auto& l : b.lower) {
    if (!b.lower_g || l.pga_g > *b.lower_g) b.lower_g = l.pga_g;
  }
  for (const auto& u : b.upper) {
    if (!b.upper_g || u.pga_g < *b.upper_g) b.upper_g = u.pga_g;
  }
  for (const auto& l : b.lower) {
    for (const auto& u : b.upper) {
      if (l.pga_g > u.pga_g) {
        b.contradictions.push_back(fmt::format("{} ({}) vs {} ({})", l.object_id, l.reason, u.object_id, u.reason));
      }
    }
  }
  return b;
}

bool in_credible_region(const InversionResult& r, double pga_g, double freq_hz, double level) {
  const auto cell_of = [](const std::vector<double>& v, double x) -> std::optional<std::size_t> {
    const auto e = log_edges(v);
    const double lx = std::log(x);
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (lx >= e[i] && lx <= e[i + 1]) return i;
    }
    return std::nullopt;
  };
  const auto i = cell_of(r.pga_g, pga_g);
  const auto j = cell_of(r.freq_hz, freq_hz);
  if (!i || !j) return false;
  const std::size_t target = *i * r.freq_hz.size() + *j;
  std::vector<std::size_t> order(r.posterior.size());
  for (std::size_t c = 0; c < order.size(); ++c) order[c] = c;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return r.posterior[a] > r.posterior[b]; });
  double mass = 0.0;
  for (std::size_t c : order) {
    if (c == target) return true;
    mass += r.posterior[c];
    if (mass >= level) return false;
  }
  return false;
}

DrawnParameters draw_parameters(const ObservedObject& object, std::uint64_t seed, std::size_t k, std::size_t o) {
  PortableRandom rng(mix(mix(seed, k + 1), o + 1));
  const auto draw = [&](const Interval& iv) { return iv.is_value() ? iv.low : iv.low + (iv.high - iv.low) * rng.uniform(); };
  DrawnParameters p;
  p.mu = draw(object.mu);
  p.e = object.e_housner ? housner_restitution(object.body) : draw(object.e);
  p.amplification = draw(object.amplification);
  return p;
}

double sliding_sigma_m(const ObservedObject& object) {
  const double d = object.slid_m.value_or(0.0);
  return std::max({object.slid_uncertainty_m, 0.25 * d, kVisibleSlipM});
}

double observation_match(const ObservedObject& object, const DrawnParameters& p, const GroundMotion& motion,
                         double g) {
  if (is_sliding_outcome(object.outcome)) {
    // Level ground, no vertical input: the response to amp * a with mu is amp times the response to a with
    // mu / amp (divide the equation of motion by amp), which spares a copy of the motion.
    const double amp = p.amplification;
    const SlidingSummary s = slide_summary(motion, SlidingBlock::make(p.mu / amp, p.mu / amp, 0.0, SlidingMode::two_way, g));
    const double max_d = amp * s.max_abs_displacement_m;
    const double residual = amp * std::abs(s.residual_displacement_m);
    if (object.outcome == Outcome::not_slid) return max_d < kVisibleSlipM ? 1.0 : 0.0;
    if (object.slid_m) {
      const double z = (residual - *object.slid_m) / sliding_sigma_m(object);
      return std::exp(-0.5 * z * z);
    }
    if (object.slid_at_least_m) return residual >= *object.slid_at_least_m ? 1.0 : 0.0;
    return max_d >= kVisibleSlipM ? 1.0 : 0.0;
  }
  double factor = p.amplification;
  if (object.orientation_deg) factor *= std::cos(*object.orientation_deg * kPi / 180.0);
  RockingOptions options;
  options.g_m_s2 = g;
  if (!object.e_housner) {
    options.restitution = RestitutionMode::given;
    options.e = p.e;
  }
  options.max_run_out_s = 20.0;
  options.rel_tol = 1e-6;  // outcomes (fell or not, rocked visibly or not) do not need the 1e-8 default
  const RockingSummary s = factor == 1.0 ? rock_summary(motion, object.body, options)
                                         : rock_summary(motion.scaled(factor), object.body, options);
  switch (object.outcome) {
    case Outcome::overturned: return s.overturned ? 1.0 : 0.0;
    case Outcome::not_overturned: return s.overturned ? 0.0 : 1.0;
    case Outcome::rocked: return !s.overturned && s.max_abs_rotation_rad >= kVisibleRockingRad ? 1.0 : 0.0;
    default: return 0.0;
  }
}

namespace {

/// The synthesis of motion k of a synthetic family's column: 20 samples per period of the column's frequency (at most
/// 0.01 s) and at least 8 periods.
SynthesisSpec family_spec(const InversionSettings& st, double freq_hz, int k) {
  SynthesisSpec spec;
  spec.pga_m_s2 = 1.0;
  spec.predominant_frequency_hz = freq_hz;
  spec.duration_s = std::max(st.duration_s, 8.0 / freq_hz);
  spec.dt_s = std::min(0.01, 1.0 / (20.0 * freq_hz));
  spec.seed = mix(st.seed, static_cast<std::uint64_t>(k) + 1);  // the same seeds in every column
  return spec;
}

}  // namespace

void validate_inversion_settings(const InversionSettings& st) {
  const auto axis = [](const char* field, double lo, double hi, int count, const char* unit) {
    if (!(lo > 0.0) || !(hi > lo) || !std::isfinite(hi)) {
      throw parameter_error(field, fmt::format("need 0 < min < max, got [{}, {}] {}", lo, hi, unit));
    }
    if (count < 2 || count > 1000) throw parameter_error(field, fmt::format("count must be 2 to 1000, got {}", count));
  };
  axis("inversion.pga_g", st.pga_min_g, st.pga_max_g, st.pga_count, "g");
  axis("inversion.freq_hz", st.freq_min_hz, st.freq_max_hz, st.freq_count, "Hz");
  if (st.motions_per_cell < 1) {
    throw parameter_error("inversion.motions_per_cell", fmt::format("must be >= 1, got {}", st.motions_per_cell));
  }
  if (!(st.duration_s > 0.0) || !std::isfinite(st.duration_s)) {
    throw parameter_error("inversion.duration_s", fmt::format("must be positive, got {} s", st.duration_s));
  }
  if (!(st.g_m_s2 > 0.0) || !std::isfinite(st.g_m_s2)) {
    throw parameter_error("inversion.g_m_s2", fmt::format("must be positive, got {} m/s2", st.g_m_s2));
  }
  if (st.family == MotionFamily::records) {
    if (st.records.empty() && st.record_motions.empty()) {
      throw parameter_error("inversion.records", "family = \"records\" needs records = [\"file\", ...]");
    }
    return;
  }
  for (const double f : {st.freq_min_hz, st.freq_max_hz}) {
    try {
      validate(family_spec(st, f, 0));
    } catch (const InputError& e) {
      throw parameter_error("inversion.freq_hz",
                            fmt::format("the synthetic family cannot make motions with a predominant frequency of "
                                        "{} Hz (the grid is [{}, {}] Hz): {}: {}",
                                        f, st.freq_min_hz, st.freq_max_hz, e.where().field, e.problem()));
    }
  }
}

std::vector<GroundMotion> family_motions(const InversionSettings& st, double freq_hz) {
  std::vector<GroundMotion> out;
  if (st.family == MotionFamily::synthetic) {
    out.reserve(static_cast<std::size_t>(st.motions_per_cell));
    for (int k = 0; k < st.motions_per_cell; ++k) {
      GroundMotion m = synthesize(family_spec(st, freq_hz, k));
      // Put the motion's measured predominant frequency exactly on the column's: time scaling by c divides every
      // frequency by c.
      const double measured = predominant_frequency_hz(m);
      out.push_back(m.time_scaled(measured / freq_hz).scaled_to_pga(1.0));
    }
    return out;
  }
  if (st.record_motions.empty()) {
    throw parameter_error("inversion.records", "family = \"records\" needs the records loaded (io::read_survey does)");
  }
  out.reserve(2 * st.record_motions.size());
  for (const auto& rec : st.record_motions) {
    const double measured = predominant_frequency_hz(*rec);
    const GroundMotion m = rec->time_scaled(measured / freq_hz).scaled_to_pga(1.0);
    out.push_back(m);
    out.push_back(m.inverted());
  }
  return out;
}

void validate_inversion_options(const InversionOptions& options) {
  if (options.threads < 0) {
    throw parameter_error("--threads", fmt::format("must be >= 0 (0: all cores), got {}", options.threads));
  }
}

FamilyGrid build_family(const InversionSettings& st, const std::vector<double>& freq_hz,
                        const InversionOptions& options) {
  validate_inversion_options(options);
  const bool loaded = st.records.empty() ? !st.record_motions.empty() : st.record_motions.size() == st.records.size();
  if (st.family == MotionFamily::records && !loaded) {
    throw parameter_error("inversion.records", fmt::format("{} record(s) named but {} loaded: the inversion core reads "
                                                           "no file (io::read_survey loads them)",
                                                           st.records.size(), st.record_motions.size()));
  }
  const std::size_t nf = freq_hz.size();
  FamilyGrid family;
  family.freq_hz = freq_hz;
  family.motions.resize(nf);
  family.measured_freq_hz.resize(nf);
  // Columns in parallel, within the thread limit of `options` (the runs below obey it too).
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(std::size_t{0}, nf, [&](std::size_t j) {
      double sum = 0.0;
      for (GroundMotion& m : family_motions(st, freq_hz[j])) {
        sum += predominant_frequency_hz(m);
        family.motions[j].push_back(std::make_shared<const GroundMotion>(std::move(m)));
      }
      family.measured_freq_hz[j] = sum / static_cast<double>(family.motions[j].size());
    });
  });
  return family;
}

MatchTable simulate_matches(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                            const FamilyGrid& family, const InversionOptions& options) {
  validate_inversion_options(options);
  MatchTable table;
  table.pga_count = pga_g.size();
  table.freq_count = family.motions.size();
  table.motions = family.motions_per_column();
  table.objects = site.objects.size();
  const std::size_t np = table.pga_count;
  const std::size_t nf = table.freq_count;
  const std::size_t n = table.motions;
  const std::size_t no = table.objects;

  ensemble::Plan plan;
  plan.motion_columns = {"cell", "pga_g", "freq_hz", "motion"};
  plan.object_columns = {"object"};
  plan.result_columns = {"match"};
  plan.identity = "topple inversion v1";
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      for (std::size_t k = 0; k < n; ++k) {
        ensemble::MotionCase mc;
        mc.base = family.motions[j][k];
        mc.transform.target_pga_m_s2 = pga_g[i] * st.g_m_s2;
        mc.values = {ensemble::Value(static_cast<std::int64_t>(i * nf + j)), ensemble::Value(pga_g[i]),
                     ensemble::Value(family.freq_hz[j]), ensemble::Value(static_cast<std::int64_t>(k))};
        plan.motions.push_back(std::move(mc));
      }
    }
  }
  for (const ObservedObject& o : site.objects) plan.objects.push_back({{ensemble::Value(o.id)}});
  // Parameters drawn once per (motion k, object): the same draw in every cell.
  std::vector<DrawnParameters> drawn(n * no);
  for (std::size_t k = 0; k < n; ++k) {
    for (std::size_t o = 0; o < no; ++o) drawn[k * no + o] = draw_parameters(site.objects[o], st.seed, k, o);
  }
  const double g = st.g_m_s2;
  plan.run = [&site, &drawn, n, no, g](const GroundMotion& motion, std::size_t motion_index, std::size_t o0,
                                      std::size_t o1, std::span<ensemble::Value> results) {
    const std::size_t k = motion_index % n;
    for (std::size_t o = o0; o < o1; ++o) {
      results[o - o0] = ensemble::Value(observation_match(site.objects[o], drawn[k * no + o], motion, g));
    }
  };
  ensemble::ExecuteOptions exec;
  exec.threads = options.threads;
  exec.progress = options.progress;
  const ensemble::ResultTable rows = ensemble::run_in_memory(plan, exec);
  // Rows come in run order: row = (cell * N + k) * objects + o, the MatchTable's own indexing.
  const std::size_t match_col = rows.columns.size() - 1;
  table.match.resize(rows.rows.size());
  for (std::size_t row = 0; row < rows.rows.size(); ++row) {
    table.match[row] = std::get<double>(rows.rows[row][match_col]);
  }
  return table;
}

namespace {

/// The 3 x 3 neighbourhood of a cell in the log grid, weighted 4 (the cell), 2 (edge neighbours), 1 (corners): the
/// response varies smoothly over a cell's width, so pooling the neighbours' runs cuts the Monte Carlo noise of N runs
/// at the price of about one cell of blur.
std::vector<std::pair<std::size_t, double>> neighbourhood(std::size_t c, std::size_t np, std::size_t nf) {
  std::vector<std::pair<std::size_t, double>> out;
  const auto ci = static_cast<std::ptrdiff_t>(c / nf);
  const auto cj = static_cast<std::ptrdiff_t>(c % nf);
  for (int di = -1; di <= 1; ++di) {
    for (int dj = -1; dj <= 1; ++dj) {
      const auto i2 = ci + di;
      const auto j2 = cj + dj;
      if (i2 < 0 || j2 < 0 || i2 >= static_cast<std::ptrdiff_t>(np) || j2 >= static_cast<std::ptrdiff_t>(nf)) continue;
      out.emplace_back(static_cast<std::size_t>(i2) * nf + static_cast<std::size_t>(j2),
                       (di == 0 ? 2.0 : 1.0) * (dj == 0 ? 2.0 : 1.0));
    }
  }
  return out;
}

/// Matches summed over the motions of each (object, cell): index o * cells + c.
std::vector<double> match_counts(const MatchTable& m) {
  const std::size_t cells = m.cells();
  std::vector<double> counts(m.objects * cells, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    for (std::size_t k = 0; k < m.motions; ++k) {
      for (std::size_t o = 0; o < m.objects; ++o) counts[o * cells + c] += m.at(c, k, o);
    }
  }
  return counts;
}

}  // namespace

LikelihoodReduction reduce_likelihood(const MatchTable& m, const std::vector<double>& error_rates) {
  if (error_rates.size() != m.objects) {
    throw std::invalid_argument("reduce_likelihood: one error rate per object is needed");
  }
  const std::size_t np = m.pga_count;
  const std::size_t nf = m.freq_count;
  const std::size_t n = m.motions;
  const std::size_t no = m.objects;
  const std::size_t cells = m.cells();
  const double nn = static_cast<double>(n);
  std::vector<std::vector<std::pair<std::size_t, double>>> hoods(cells);
  for (std::size_t c = 0; c < cells; ++c) hoods[c] = neighbourhood(c, np, nf);
  const std::vector<double> counts = match_counts(m);

  LikelihoodReduction out;
  // Per-object probability of its observation (for the report and the contours): smoothed counts.
  out.probability.assign(no, std::vector<double>(cells, 0.0));
  out.max_probability.assign(no, 0.0);
  out.reproduced_anywhere.assign(no, false);
  for (std::size_t o = 0; o < no; ++o) {
    double total = 0.0;
    for (std::size_t c = 0; c < cells; ++c) {
      double sum = 0.0;
      double weight = 0.0;
      for (const auto& [c2, w] : hoods[c]) {
        sum += w * counts[o * cells + c2];
        weight += w;
      }
      total += counts[o * cells + c];
      out.probability[o][c] = (sum / weight + 0.5) / (nn + 1.0);
      out.max_probability[o] = std::max(out.max_probability[o], out.probability[o][c]);
    }
    out.reproduced_anywhere[o] = total > 0.0;
  }
  // Joint likelihood: all objects saw the same motion, so a cell's likelihood is the average over its motions k of
  // the product over objects of q = eps + (1 - 2 eps) m, where eps is the chance that the observation is wrong
  // (evidence_error_rate). Averaging products, not multiplying averages, keeps the correlation the shared motion
  // induces between objects (a strong realisation topples them all). Log-sum-exp keeps it finite for any number of
  // objects.
  std::vector<double> run_log(cells * n, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    for (std::size_t k = 0; k < n; ++k) {
      double lq = 0.0;
      for (std::size_t o = 0; o < no; ++o) {
        const double eps = error_rates[o];
        lq += std::log(eps + (1.0 - 2.0 * eps) * m.at(c, k, o));
      }
      run_log[c * n + k] = lq;
    }
  }
  out.log_likelihood.assign(cells, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    double top = -std::numeric_limits<double>::infinity();
    for (const auto& [c2, w] : hoods[c]) {
      for (std::size_t k = 0; k < n; ++k) top = std::max(top, run_log[c2 * n + k]);
    }
    double sum = 0.0;
    double weight = 0.0;
    for (const auto& [c2, w] : hoods[c]) {
      for (std::size_t k = 0; k < n; ++k) sum += w * std::exp(run_log[c2 * n + k] - top);
      weight += w * nn;
    }
    out.log_likelihood[c] = top + std::log(sum / weight);
  }
  return out;
}

void fill_posterior_and_estimates(InversionResult& r) {
  const std::size_t np = r.pga_g.size();
  const std::size_t nf = r.freq_hz.size();
  const std::size_t cells = np * nf;
  // Posterior with a prior uniform over the log grid.
  const double ll_max = *std::max_element(r.log_likelihood.begin(), r.log_likelihood.end());
  r.posterior.resize(cells);
  double z = 0.0;
  for (std::size_t c = 0; c < cells; ++c) z += r.posterior[c] = std::exp(r.log_likelihood[c] - ll_max);
  for (double& p : r.posterior) p /= z;
  r.best_cell = static_cast<std::size_t>(std::max_element(r.log_likelihood.begin(), r.log_likelihood.end()) -
                                         r.log_likelihood.begin());
  r.marginal_pga.assign(np, 0.0);
  r.marginal_freq.assign(nf, 0.0);
  for (std::size_t i = 0; i < np; ++i) {
    for (std::size_t j = 0; j < nf; ++j) {
      r.marginal_pga[i] += r.posterior[i * nf + j];
      r.marginal_freq[j] += r.posterior[i * nf + j];
    }
  }
  r.pga_estimate_g = estimate(r.pga_g, r.marginal_pga, r.pga_g[r.best_cell / nf]);
  r.freq_estimate_hz = estimate(r.freq_hz, r.marginal_freq, r.freq_hz[r.best_cell % nf]);
  for (ObjectReport& rep : r.objects) rep.probability_at_best = rep.probability[r.best_cell];
}

std::vector<std::string> inversion_notes(const InversionResult& r, const MatchTable& m) {
  std::vector<std::string> notes;
  if (!r.bounds.lower_g) {
    notes.push_back("No object moved: the observations give no static lower bound on PGA.");
  }
  if (!r.bounds.upper_g) {
    notes.push_back("No object stayed put on its friction surface: the observations give no static upper bound on "
                    "PGA.");
  }
  for (const std::string& c : r.bounds.contradictions) notes.push_back("Static contradiction: " + c + ".");
  const Estimate& pga = r.pga_estimate_g;
  if (!pga.ci95_low || !pga.ci95_high) {
    notes.push_back(fmt::format("The 95 % interval of PGA reaches the {} of the grid ({}): the observations do not "
                                "constrain it there.",
                                !pga.ci95_low && !pga.ci95_high ? "both ends"
                                                                : (!pga.ci95_low ? "lower end" : "upper end"),
                                !pga.ci95_low ? fmt_g(r.pga_g.front()) : fmt_g(r.pga_g.back())));
  }
  if (!r.freq_estimate_hz.ci95_low || !r.freq_estimate_hz.ci95_high) {
    notes.push_back("The predominant frequency is not constrained at one or both ends of the grid by these "
                    "observations.");
  }
  std::vector<std::string> never;
  for (const ObjectReport& rep : r.objects) {
    if (!rep.reproduced_anywhere) never.push_back(fmt::format("{} ({})", rep.id, outcome_name(rep.outcome)));
  }
  if (!never.empty()) {
    std::string list;
    for (const auto& s : never) list += (list.empty() ? "" : ", ") + s;
    notes.push_back(fmt::format("Not reproduced by any run in any cell: {}. Check these observations (or widen the "
                                "grid or the parameter ranges).", list));
  }
  // What the observations share: counts of matches per (object, cell).
  const std::size_t cells = m.cells();
  const std::size_t no = m.objects;
  const std::vector<double> counts = match_counts(m);
  bool every_cell_contradicted = true;
  for (std::size_t c = 0; c < cells && every_cell_contradicted; ++c) {
    bool all_reproduced = true;
    for (std::size_t o = 0; o < no; ++o) all_reproduced = all_reproduced && counts[o * cells + c] > 0.0;
    if (all_reproduced) every_cell_contradicted = false;
  }
  if (every_cell_contradicted && no > 1) {
    std::string list;
    for (std::size_t o = 0; o < no; ++o) {
      if (counts[o * cells + r.best_cell] == 0.0) list += (list.empty() ? "" : ", ") + r.objects[o].id;
    }
    notes.push_back(fmt::format("The observations contradict each other in every cell of the grid: no cell "
                                "reproduces them all. At the best cell, not reproduced: {}.", list));
  }
  return notes;
}

namespace {

/// Steps 2-5 on a built family (step 1). `started` is when the inversion began (for InversionResult::seconds).
InversionResult invert_on_family(const Site& site, const InversionSettings& st, const FamilyGrid& family,
                                 const InversionOptions& options, std::chrono::steady_clock::time_point started) {
  InversionResult r;
  r.site = site.name;
  r.pga_g = log_spaced(st.pga_min_g, st.pga_max_g, static_cast<std::size_t>(st.pga_count));
  r.freq_hz = family.freq_hz;
  r.bounds = static_bounds(site);
  r.measured_freq_hz = family.measured_freq_hz;
  const MatchTable matches = simulate_matches(site, st, r.pga_g, family, options);
  r.runs = matches.match.size();

  std::vector<double> error_rates;
  for (const ObservedObject& o : site.objects) error_rates.push_back(evidence_error_rate(o.evidence));
  LikelihoodReduction reduced = reduce_likelihood(matches, error_rates);
  r.log_likelihood = std::move(reduced.log_likelihood);
  r.objects.resize(site.objects.size());
  for (std::size_t o = 0; o < site.objects.size(); ++o) {
    ObjectReport& rep = r.objects[o];
    rep.id = site.objects[o].id;
    rep.outcome = site.objects[o].outcome;
    rep.probability = std::move(reduced.probability[o]);
    rep.max_probability = reduced.max_probability[o];
    rep.reproduced_anywhere = reduced.reproduced_anywhere[o];
  }
  fill_posterior_and_estimates(r);
  r.notes = inversion_notes(r, matches);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return r;
}

}  // namespace

InversionResult invert_site(const Site& site, const InversionSettings& st, const InversionOptions& options) {
  validate_inversion_options(options);
  validate_inversion_settings(st);
  const auto start = std::chrono::steady_clock::now();
  const FamilyGrid family =
      build_family(st, log_spaced(st.freq_min_hz, st.freq_max_hz, static_cast<std::size_t>(st.freq_count)), options);
  return invert_on_family(site, st, family, options, start);
}

std::vector<InversionResult> invert_sites(const std::vector<Site>& sites, const InversionSettings& st,
                                          const InversionOptions& options) {
  validate_inversion_options(options);
  validate_inversion_settings(st);
  std::vector<InversionResult> out;
  if (sites.empty()) return out;
  auto start = std::chrono::steady_clock::now();
  const FamilyGrid family =
      build_family(st, log_spaced(st.freq_min_hz, st.freq_max_hz, static_cast<std::size_t>(st.freq_count)), options);
  for (const Site& site : sites) {
    out.push_back(invert_on_family(site, st, family, options, start));
    start = std::chrono::steady_clock::now();  // the family's time is counted in the first site's
  }
  return out;
}

}  // namespace topple
