// Inversion of field observations: static bounds and the likelihood over PGA x predominant frequency. See
// inversion.hpp and docs/method.md for the method.
#include "topple/inversion/inversion.hpp"
#include "topple/inversion/prior.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "topple/ensemble/ensemble.hpp"
#include "topple/core/error.hpp"
#include "topple/inversion/evidence.hpp"
#include "topple/survey/population.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/inversion/inversion_3c.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/stochastic.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"
#include "topple/numerics/statistics.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple {
namespace {

std::string fmt_g(double v) { return fmt::format("{:.3g} g", v); }

/// Quantile q of a marginal over a log axis; `cell` receives the cell it falls in.
double quantile(const std::vector<double>& values, const std::vector<double>& marginal, double q, std::size_t& cell) {
  const auto e = log_cell_edges(values);
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
  const auto edge = [last](std::size_t at) { return at == 0 ? -1 : (at == last ? 1 : 0); };
  est.median_edge = edge(cell);
  est.best_edge = edge(static_cast<std::size_t>(
      std::min_element(values.begin(), values.end(),
                       [best](double a, double b) { return std::abs(a - best) < std::abs(b - best); }) -
      values.begin()));
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

}  // namespace

Estimate detail::marginal_estimate(const std::vector<double>& values, const std::vector<double>& marginal, double best) {
  return estimate(values, marginal, best);
}

namespace detail {
std::uint64_t mix(std::uint64_t a, std::uint64_t b) {
  SplitMix64 s(a * 0x9E3779B97F4A7C15ULL + b);
  return s.next();
}
}  // namespace detail
using detail::mix;

/// tan(alpha) of the uplift threshold g tan(alpha) that a static bound uses. A symmetric body has one. An asymmetric
/// one (b1 != b2) uplifts about either pivot, at g b1/h or g b2/h by the direction of the peak, which the survey does
/// not know: a lower bound (it rocked) takes the smaller, an upper one (it did not) the larger, the weaker claim.
double detail::uplift_tan_alpha(const RockingBody& body, bool lower) {
  const double plus = std::tan(body.alpha_rad());
  if (body.symmetric()) return plus;
  const double minus = std::tan(body.side_body(-1).alpha_rad());
  return lower ? std::min(plus, minus) : std::max(plus, minus);
}

namespace {
using detail::uplift_tan_alpha;
/// The hard lower threshold tan (g) of an object simulated with the coupled model whose base moved (slid, slid_stood,
/// slid_toppled, walked) and the words for it; none for the other objects. The body leaves rest only when |a| passes
/// g min(mu_s, b/h) (slide_rock.hpp: the rest region, Shenton 1996): so a slip needs PGA > g min(mu, b/h) (a body
/// with mu > b/h may slip while it rocks, below mu g), and an outcome that needs rocking (slid_toppled, walked)
/// needs uplift, PGA > g b/h.
std::optional<std::pair<double, std::string>> coupled_moved_threshold(const ObservedObject& o) {
  if (object_model(o) != ObjectModel::coupled) return std::nullopt;
  const double tan_alpha = uplift_tan_alpha(o.body, true);
  switch (o.outcome) {
    case Outcome::slid:
    case Outcome::slid_stood: {
      const double t = std::min(o.mu.low, tan_alpha);
      return std::pair{t, fmt::format("{} (coupled): PGA > g min(mu, a/h) = {}", outcome_name(o.outcome), fmt_g(t))};
    }
    case Outcome::slid_toppled:
    case Outcome::walked:
      return std::pair{tan_alpha, fmt::format("{} (coupled): PGA > g a/h = {}", outcome_name(o.outcome),
                                              fmt_g(tan_alpha))};
    default: return std::nullopt;
  }
}

/// An object on a flexible support: its support's peak is at most max_peak_amplification(zeta_low) times the ground's
/// (any motion), so an object that slid, rocked or overturned still bounds the ground's PGA from below (weakly). The
/// support may also attenuate the ground's peak without limit (well above its frequency): no upper bound.
void flexible_support_bound(const ObservedObject& o, StaticBounds& b) {
  const double amp_max = o.amplification.high * max_peak_amplification(o.support_filter->damping.low);
  if (!std::isfinite(amp_max)) return;  // undamped support: no bound
  const auto text = [&](double threshold_g) {
    return fmt::format("PGA > {} / {:.3g}, the most its flexible support can amplify a peak", fmt_g(threshold_g),
                       amp_max);
  };
  if (const auto moved = coupled_moved_threshold(o)) {
    b.lower.push_back({moved->first / amp_max, o.id, moved->second + ": " + text(moved->first), true});
    return;
  }
  switch (o.outcome) {
    case Outcome::slid:
      b.lower.push_back({o.mu.low / amp_max, o.id, "slid: " + text(o.mu.low), true});  // hard, as on rigid ground
      break;
    case Outcome::overturned:
    case Outcome::rocked: {
      const double tan_alpha = uplift_tan_alpha(o.body, true);
      b.lower.push_back(
          {tan_alpha / amp_max, o.id, fmt::format("{}: {}", outcome_name(o.outcome), text(tan_alpha)), true});
      break;
    }
    default: break;
  }
}
}  // namespace

StaticBounds static_bounds(const Site& site) {
  StaticBounds b;
  for (const ObservedObject& o : site.objects) {
    if (o.support_filter) {
      flexible_support_bound(o, b);
      continue;
    }
    // A lower threshold divides by the largest amplification, an upper one by the smallest (the weakest claim); the
    // text shows the amplification actually used and the result.
    const auto divided = [](double amp, double value_g) {
      return amp == 1.0 ? std::string()
                 : fmt::format(" / amplification {:.3g} = {}", amp, fmt_g(value_g / amp));
    };
    const double amp_hi = o.amplification.high;
    const double amp_lo = o.amplification.low;
    const double tan_alpha = uplift_tan_alpha(o.body, o.outcome != Outcome::not_rocked);
    if (const auto moved = coupled_moved_threshold(o)) {  // hard, like every threshold of a body leaving rest
      b.lower.push_back({moved->first / amp_hi, o.id, moved->second + divided(amp_hi, moved->first), true});
      continue;
    }
    switch (o.outcome) {
      case Outcome::slid:  // hard: no slip at all while |a| <= mu g (Coulomb, level ground)
        b.lower.push_back({o.mu.low / amp_hi, o.id,
                           fmt::format("slid: PGA > mu g = {}{}", fmt_g(o.mu.low), divided(amp_hi, o.mu.low)), true});
        break;
      case Outcome::not_slid:  // soft: a brief excursion above mu g may slip it less than the visible 2 mm
        b.upper.push_back({o.mu.high / amp_lo, o.id,
                           fmt::format("did not slide visibly: PGA <= mu g = {}{}", fmt_g(o.mu.high),
                                       divided(amp_lo, o.mu.high)),
                           false});
        break;
      case Outcome::overturned:
      case Outcome::rocked:  // hard: no uplift while |a| <= g a/h (Housner)
        b.lower.push_back({tan_alpha / amp_hi, o.id,
                           fmt::format("{}: PGA > g a/h = {}{}", outcome_name(o.outcome), fmt_g(tan_alpha),
                                       divided(amp_hi, tan_alpha)),
                           true});
        break;
      case Outcome::not_rocked:  // soft: a brief excursion above g a/h may uplift it less than the visible tilt
        b.upper.push_back({tan_alpha / amp_lo, o.id,
                           fmt::format("did not rock visibly: PGA <= g a/h = {}{}", fmt_g(tan_alpha),
                                       divided(amp_lo, tan_alpha)),
                           false});
        break;
      case Outcome::not_overturned:
        break;  // a body can rock without falling at any PGA above g a/h: no static threshold
      case Outcome::slid_stood:
      case Outcome::slid_toppled:
      case Outcome::walked:
        break;  // coupled outcomes: coupled_moved_threshold above
    }
  }
  // A population some of whose members overturned, rocked or slid (docs/method.md, "Populations of objects"): at
  // least one member left rest, so PGA exceeded the lowest threshold in the class, g min(b/h) (and for a slip,
  // g min(mu, b/h), Shenton 1996), over the largest amplification; hard, as for an object. None on a flexible support.
  for (const Population& p : site.populations) {
    if (p.prototype.support_filter) continue;
    const bool lifted = p.overturned > 0 || p.rocked.value_or(0) > 0;
    const bool slipped = p.slid.value_or(0) > 0;
    if (!lifted && !slipped) continue;
    const double b_h = population_min_slenderness(p);
    const double t = lifted ? b_h : std::min(b_h, p.prototype.mu.low);
    const double amp = p.prototype.amplification.high;
    b.lower.push_back({t / amp, p.id,
                       fmt::format("population: {} of {} {}: PGA > g {} = {}{}", lifted ? p.overturned + p.rocked.value_or(0) : *p.slid,
                                   p.count, lifted ? "overturned or rocked" : "slid",
                                   lifted ? "min(b/h)" : "min(mu, b/h)", fmt_g(t),
                                   amp == 1.0 ? std::string() : fmt::format(" / amplification {:.3g}", amp)),
                       true});
  }
  detail::settle_static_bounds(b);
  return b;
}

void detail::settle_static_bounds(StaticBounds& b) {
  for (const auto& l : b.lower) {
    if (l.hard && (!b.hard_lower_g || l.pga_g > *b.hard_lower_g)) b.hard_lower_g = l.pga_g;
  }
  for (const auto& u : b.upper) {
    if (u.hard && (!b.hard_upper_g || u.pga_g < *b.hard_upper_g)) b.hard_upper_g = u.pga_g;
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
}

bool in_credible_region(const InversionResult& r, double pga_g, double freq_hz, double level) {
  const auto cell_of = [](const std::vector<double>& v, double x) -> std::optional<std::size_t> {
    const auto e = log_cell_edges(v);
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

namespace detail {

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

}  // namespace detail
using detail::family_spec;

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
  if (st.components != 1 && st.components != 3) {
    throw parameter_error("inversion.components", fmt::format("must be 1 or 3, got {}", st.components));
  }
  if (st.components == 3) {
    if (st.family != MotionFamily::synthetic) {
      throw parameter_error("inversion.components", "components = 3 needs family = \"synthetic\"");
    }
    if (!(st.coherence >= 0.0 && st.coherence <= 0.95)) {
      throw parameter_error("inversion.coherence", fmt::format("must lie in [0, 0.95], got {}", st.coherence));
    }
    if (st.directions < 4 || st.directions > 72) {
      throw parameter_error("inversion.directions", fmt::format("must be 4 to 72, got {}", st.directions));
    }
    for (const double f : {st.freq_min_hz, st.freq_max_hz}) {
      try {
        validate(detail::family_set_spec(st, f, 0));
      } catch (const InputError& e) {
        throw parameter_error("inversion.freq_hz",
                              fmt::format("the three-component family cannot make motions with a predominant "
                                          "frequency of {} Hz (the grid is [{}, {}] Hz): {}: {}",
                                          f, st.freq_min_hz, st.freq_max_hz, e.where().field, e.problem()));
      }
    }
  }
  if (st.family == MotionFamily::mixture) {  // family_mixture.cpp: an even N, a grid both members accept
    detail::validate_mixture_settings(st);
    return;
  }
  if (st.family == MotionFamily::records) {
    if (st.records.empty() && st.record_motions.empty()) {
      throw parameter_error("inversion.records", "family = \"records\" needs records = [\"file\", ...]");
    }
    return;
  }
  if (st.family == MotionFamily::rezaeian2010 || st.family == MotionFamily::boore2003) {
    // The record-like family makes any frequency whose step (1 / (20 f_max), synthesis.hpp) the readers accept; the
    // frequency axis is kept to the band predominant_frequency_hz measures (0.1 Hz up), and 25 Hz at the top. The
    // stochastic family (stochastic.hpp) samples at the same step and is kept to the same band.
    if (st.freq_min_hz < 0.1 || st.freq_max_hz > 25.0) {
      throw parameter_error("inversion.freq_hz", fmt::format("the {} family makes predominant frequencies "
                                                             "of 0.1 to 25 Hz; the grid is [{}, {}] Hz",
                                                             motion_family_name(st.family), st.freq_min_hz,
                                                             st.freq_max_hz));
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

namespace {

/// Motion k of a drawn family's column (synthetic, rezaeian2010, boore2003): each motion depends on (settings,
/// column, k) alone, so build_family can make them on any thread in any order.
GroundMotion drawn_family_motion(const InversionSettings& st, double freq_hz, int k) {
  if (st.family == MotionFamily::synthetic) {
    GroundMotion m = synthesize(family_spec(st, freq_hz, k));
    // Put the motion's measured predominant frequency exactly on the column's: time scaling by c divides every
    // frequency by c.
    const double measured = predominant_frequency_hz(m);
    return m.time_scaled(measured / freq_hz).scaled_to_pga(1.0);
  }
  if (st.family == MotionFamily::rezaeian2010) {
    // Parameters of motion k drawn once (the same in every column: common random numbers), f_mid at the column.
    const std::uint64_t seed = mix(st.seed, static_cast<std::uint64_t>(k) + 1);
    RezaeianSpec spec = draw_rezaeian(seed, freq_hz);
    GroundMotion m = synthesize_rezaeian(spec);
    double measured = predominant_frequency_hz(m);
    // The measured peak may sit well off f_mid (a broad filter, a strong drift): aim f_mid once more, so that the
    // time scaling below stays within a factor 1.25 or so and keeps the drawn durations.
    if (measured > 1.25 * freq_hz || measured < 0.8 * freq_hz) {
      spec = draw_rezaeian(seed, freq_hz * freq_hz / measured);
      m = synthesize_rezaeian(spec);
      measured = predominant_frequency_hz(m);
    }
    return m.time_scaled(measured / freq_hz).scaled_to_pga(1.0);
  }
  // boore2003. Motion k: scenarios (M, R, kappa0) drawn for a spectral peak at the column and kept when the motion's
  // measured predominant frequency lies within a factor 1.15 of it (stochastic.hpp, draw_boore2003); the same seeds
  // in every column. The time scaling then puts it exactly on the column.
  const BooreDraw d = draw_boore2003(mix(st.seed, static_cast<std::uint64_t>(k) + 1), freq_hz);
  return d.motion.time_scaled(d.measured_hz / freq_hz).scaled_to_pga(1.0);
}

bool drawn_family(const InversionSettings& st) {
  return st.family == MotionFamily::synthetic || st.family == MotionFamily::rezaeian2010 ||
         st.family == MotionFamily::boore2003;
}

}  // namespace

std::vector<GroundMotion> family_motions(const InversionSettings& st, double freq_hz) {
  if (st.family == MotionFamily::mixture) return detail::mixture_family_motions(st, freq_hz);  // family_mixture.cpp
  std::vector<GroundMotion> out;
  if (drawn_family(st)) {
    out.reserve(static_cast<std::size_t>(st.motions_per_cell));
    for (int k = 0; k < st.motions_per_cell; ++k) out.push_back(drawn_family_motion(st, freq_hz, k));
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
  // Within the thread limit of `options` (the runs below obey it too).
  tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
  if (drawn_family(st)) {
    // Every (column, motion) on its own task, not one column per task: the high-frequency columns' motions are up to
    // 4x longer, and a thread left with the last of them would run it alone while the other waits (issue 32). The
    // same motions and, summed in k order, the same measured frequencies as family_motions column by column.
    const auto n = static_cast<std::size_t>(st.motions_per_cell);
    std::vector<std::shared_ptr<const GroundMotion>> motions(nf * n);
    std::vector<double> measured(nf * n);
    arena.execute([&] {
      tbb::parallel_for(std::size_t{0}, nf * n, [&](std::size_t task) {
        // High-frequency (costly) columns first: fewer left at the end.
        const std::size_t j = nf - 1 - task / n;
        const std::size_t k = task % n;
        auto m = std::make_shared<const GroundMotion>(drawn_family_motion(st, freq_hz[j], static_cast<int>(k)));
        measured[j * n + k] = predominant_frequency_hz(*m);
        motions[j * n + k] = std::move(m);
      });
    });
    for (std::size_t j = 0; j < nf; ++j) {
      double sum = 0.0;
      for (std::size_t k = 0; k < n; ++k) {
        sum += measured[j * n + k];
        family.motions[j].push_back(std::move(motions[j * n + k]));
      }
      family.measured_freq_hz[j] = sum / static_cast<double>(n);
    }
    return family;
  }
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
  if (st.family == MotionFamily::mixture) detail::label_mixture_members(family);  // each motion's member and draw
  return family;
}

MatchTable simulate_matches(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                            const FamilyGrid& family, const InversionOptions& options) {
  return detail::simulate_matches(site, st, pga_g, family, options, nullptr);
}

MatchTable detail::simulate_matches(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                                    const FamilyGrid& family, const InversionOptions& options,
                                    CatalogueShare* share) {
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
    for (std::size_t o = 0; o < no; ++o) drawn[k * no + o] = draw_parameters(site.objects[o], st.seed, family.draw_of(k), o);
  }
  const double g = st.g_m_s2;
  // What to look for next (evidence.hpp) runs catalogue objects under the first kCatalogueMotions motions of the cells;
  // a survey object whose rocking run is the same computation as a catalogue object's (same_rocking_run for each of
  // those motions) records its outcome category for the ranking, which then need not run it again. Only where the
  // motions are bit-identical: the engine's motion is base.scaled_to_pga(target), a multiplication of each sample by
  // target / peak, the ranking's base.scaled(target), one by target; equal when target / peak == target.
  std::vector<std::ptrdiff_t> share_of(no, -1);  // survey object o -> its block in share->outcome
  std::vector<std::uint8_t> motion_shared;       // per (cell, k < nk): the two motions are bit-identical
  const std::size_t nk = std::min<std::size_t>(n, kCatalogueMotions);
  if (share != nullptr) {
    const std::vector<CatalogueObject>& catalogue = household_catalogue();
    *share = CatalogueShare{};
    share->cells = np * nf;
    share->nk = nk;
    share->block.assign(catalogue.size(), -1);
    std::ptrdiff_t blocks = 0;
    for (std::size_t x = 0; x < catalogue.size(); ++x) {
      for (std::size_t o = 0; o < no && share->block[x] < 0; ++o) {
        if (share_of[o] >= 0) continue;
        bool same = nk > 0;
        for (std::size_t k = 0; k < nk && same; ++k) {
          same = same_rocking_run(site.objects[o], drawn[k * no + o], catalogue[x].object,
                                  draw_parameters(catalogue[x].object, st.seed, k, 1000 + x), g);
        }
        if (same) share->block[x] = share_of[o] = blocks++;
      }
    }
    share->outcome.assign(static_cast<std::size_t>(blocks) * share->cells * nk, CatalogueShare::kNotRecorded);
    if (blocks > 0) {
      motion_shared.assign(share->cells * nk, 0);
      for (std::size_t i = 0; i < np; ++i) {
        const double target = pga_g[i] * g;  // as the plan's transform and the ranking form it
        for (std::size_t j = 0; j < nf; ++j) {
          for (std::size_t k = 0; k < nk; ++k) {
            motion_shared[(i * nf + j) * nk + k] = target / family.motions[j][k]->pga_m_s2() == target ? 1 : 0;
          }
        }
      }
    }
  }
  plan.run = [&site, &drawn, &share_of, &motion_shared, share, n, nk, no, g](
                 const GroundMotion& motion, std::size_t motion_index, std::size_t o0, std::size_t o1,
                 std::span<ensemble::Value> results) {
    const std::size_t k = motion_index % n;
    const std::size_t cell = motion_index / n;
    for (std::size_t o = o0; o < o1; ++o) {
      const ObservedObject& object = site.objects[o];
      const DrawnParameters& p = drawn[k * no + o];
      if (share_of[o] >= 0 && k < nk && motion_shared[cell * nk + k] != 0) {
        // observation_match's rocking path for a rigid support and factor 1 (same_rocking_run), with the summary kept.
        const RockingSummary s = rock_summary(motion, object.body, inversion_rocking_options(object, p, g));
        share->outcome[(static_cast<std::size_t>(share_of[o]) * share->cells + cell) * nk + k] =
            s.overturned ? 0 : (s.max_abs_rotation_rad >= kVisibleRockingRad ? 1 : 2);
        results[o - o0] = ensemble::Value(rocking_match(object.outcome, s.overturned, s.max_abs_rotation_rad));
        continue;
      }
      results[o - o0] = ensemble::Value(observation_match(object, p, motion, g));
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

namespace detail {

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

}  // namespace detail
using detail::neighbourhood;

namespace {

/// The neighbourhood of every cell of an np x nf grid.
std::vector<std::vector<std::pair<std::size_t, double>>> neighbourhoods(std::size_t np, std::size_t nf) {
  std::vector<std::vector<std::pair<std::size_t, double>>> hoods(np * nf);
  for (std::size_t c = 0; c < hoods.size(); ++c) hoods[c] = neighbourhood(c, np, nf);
  return hoods;
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

/// The joint log-likelihood of every cell (reduce_likelihood, header item 2) from the match table, one error rate per
/// object and each cell's neighbourhood. An error rate of 1/2 makes an object's factor the constant 1/2: the
/// likelihood without that object (assess_objects), up to a constant.
std::vector<double> joint_log_likelihood(const MatchTable& m, const std::vector<double>& error_rates,
                                         const std::vector<std::vector<std::pair<std::size_t, double>>>& hoods,
                                         const double* population_run_log = nullptr) {
  const std::size_t n = m.motions;
  const std::size_t no = m.objects;
  const std::size_t cells = m.cells();
  const double nn = static_cast<double>(n);
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
      // The populations' multinomials under the same motion (eq. P1, docs/method.md): one more factor of the run.
      if (population_run_log != nullptr) lq += population_run_log[c * n + k];
      run_log[c * n + k] = lq;
    }
  }
  std::vector<double> log_likelihood(cells, 0.0);
  std::vector<double> x, w;  // the neighbourhood's runs and their weights
  for (std::size_t c = 0; c < cells; ++c) {
    x.clear();
    w.clear();
    double weight = 0.0;
    for (const auto& [c2, wc] : hoods[c]) {
      for (std::size_t k = 0; k < n; ++k) {
        x.push_back(run_log[c2 * n + k]);
        w.push_back(wc);
      }
      weight += wc * nn;
    }
    log_likelihood[c] = log_sum_exp(x, w, weight);  // log of the weighted mean of the runs' products
  }
  return log_likelihood;
}

}  // namespace

LikelihoodReduction reduce_likelihood(const MatchTable& m, const std::vector<double>& error_rates) {
  return detail::reduce_likelihood(m, error_rates, nullptr);
}

LikelihoodReduction detail::reduce_likelihood(const MatchTable& m, const std::vector<double>& error_rates,
                                              const double* population_run_log) {
  if (error_rates.size() != m.objects) {
    throw std::invalid_argument("reduce_likelihood: one error rate per object is needed");
  }
  const std::size_t np = m.pga_count;
  const std::size_t nf = m.freq_count;
  const std::size_t n = m.motions;
  const std::size_t no = m.objects;
  const std::size_t cells = m.cells();
  const double nn = static_cast<double>(n);
  const std::vector<std::vector<std::pair<std::size_t, double>>> hoods = neighbourhoods(np, nf);
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
  out.log_likelihood = joint_log_likelihood(m, error_rates, hoods, population_run_log);
  return out;
}

void fill_posterior_and_estimates(InversionResult& r) {
  const std::size_t np = r.pga_g.size();
  const std::size_t nf = r.freq_hz.size();
  const std::size_t cells = np * nf;
  // Posterior = likelihood x prior: the prior uniform over the log grid when log_prior is empty (then the sum below is
  // the likelihood's alone, bit for bit), else log_prior per cell.
  if (!r.log_prior.empty() && r.log_prior.size() != cells) {
    throw std::invalid_argument("fill_posterior_and_estimates: log_prior has not one value per cell");
  }
  std::vector<double> log_post = r.log_likelihood;
  if (!r.log_prior.empty()) {
    for (std::size_t c = 0; c < cells; ++c) log_post[c] += r.log_prior[c];
  }
  const double ll_max = *std::max_element(log_post.begin(), log_post.end());
  r.posterior.resize(cells);
  double z = 0.0;
  for (std::size_t c = 0; c < cells; ++c) z += r.posterior[c] = std::exp(log_post[c] - ll_max);
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
  fill_likelihood_estimates(r);  // the objects' own evidence and the ridge (evidence.hpp)
}

void detail::assess_objects(InversionResult& r, const std::vector<MatchTable>& bins,
                            const std::vector<double>& error_rates, const std::vector<double>& ll_joint,
                            const std::vector<double>& posterior_joint, const std::vector<double>* population_run_log) {
  const std::size_t nb = bins.size();
  const std::size_t cells = bins.front().cells();
  const std::size_t no = bins.front().objects;
  const std::vector<std::vector<std::pair<std::size_t, double>>> hoods =
      neighbourhoods(bins.front().pga_count, bins.front().freq_count);
  const double z_all = log_sum_exp(ll_joint);  // log posterior = ll - z_all
  const std::vector<double> counts = nb == 1 ? match_counts(bins.front()) : std::vector<double>{};  // see below
  const double nn = static_cast<double>(bins.front().motions);
  for (std::size_t o = 0; o < no; ++o) {
    ObjectReport& rep = r.objects[o];
    // The plain share of each cell's runs (not the smoothed probability, whose +1/2 floors it at 1/(2N + 2): with
    // few motions per cell that floor alone would pass the misfit level).
    // Summed in the order each model used before they were one pipeline, which keeps both to the bit: one bin by the
    // cells' counts, several bins run by run (by the cells' counts, three components' P moves by about 4e-14,
    // relative).
    rep.posterior_predictive = 0.0;
    if (nb == 1) {
      for (std::size_t c = 0; c < cells; ++c) rep.posterior_predictive += posterior_joint[c] * counts[o * cells + c] / nn;
    } else {
      for (std::size_t c = 0; c < cells; ++c) {
        for (std::size_t k = 0; k < bins.front().motions; ++k) {
          for (std::size_t b = 0; b < nb; ++b) {
            rep.posterior_predictive += posterior_joint[c * nb + b] * bins[b].at(c, k, o) / nn;
          }
        }
      }
    }
    rep.misfit = rep.posterior_predictive < kMisfitProbability;
    // Without object o: eps = 1/2 turns its factor into the constant 1/2, which the normalisation removes.
    std::vector<double> rates = error_rates;
    rates[o] = 0.5;
    std::vector<double> ll_without(cells * nb);
    for (std::size_t b = 0; b < nb; ++b) {
      // The populations' factor of bin b (SiteRuns::population_run_log: bin-major blocks of cells x motions).
      const double* pop = population_run_log == nullptr || population_run_log->empty()
                              ? nullptr
                              : population_run_log->data() + b * cells * bins[b].motions;
      const std::vector<double> ll = joint_log_likelihood(bins[b], rates, hoods, pop);
      // With a prior, ll_joint carries it (infer_site) and so must the posterior without object o.
      const double* lp = r.log_prior.empty() ? nullptr : r.log_prior.data();
      for (std::size_t c = 0; c < cells; ++c) ll_without[c * nb + b] = lp == nullptr ? ll[c] : ll[c] + lp[c];
    }
    const double z_without = log_sum_exp(ll_without);
    double kl_nats = 0.0;  // sum_i p(i) (log p(i) - log p_without(i)), in log space: no 0/0 where p underflows
    for (std::size_t i = 0; i < ll_joint.size(); ++i) {
      if (posterior_joint[i] > 0.0) {
        kl_nats += posterior_joint[i] * ((ll_joint[i] - z_all) - (ll_without[i] - z_without));
      }
    }
    rep.constraint_bits = std::max(0.0, kl_nats / std::log(2.0));
  }
}

void assess_objects(InversionResult& r, const MatchTable& m, const std::vector<double>& error_rates) {
  if (r.objects.size() != m.objects || error_rates.size() != m.objects || r.posterior.size() != m.cells()) {
    throw std::invalid_argument("assess_objects: the result, the match table and the error rates disagree");
  }
  if (r.log_prior.empty()) {
    detail::assess_objects(r, {m}, error_rates, r.log_likelihood, r.posterior);  // one direction bin
    return;
  }
  std::vector<double> lp(r.log_likelihood.size());  // the log posterior up to a constant: likelihood x prior
  for (std::size_t c = 0; c < lp.size(); ++c) lp[c] = r.log_likelihood[c] + r.log_prior[c];
  detail::assess_objects(r, {m}, error_rates, lp, r.posterior);
}

std::vector<std::size_t> most_constraining_objects(const InversionResult& r) {
  std::vector<std::size_t> order;
  for (std::size_t o = 0; o < r.objects.size(); ++o) {
    if (r.objects[o].constraint_bits >= 0.1) order.push_back(o);
  }
  std::stable_sort(order.begin(), order.end(), [&r](std::size_t a, std::size_t b) {
    return r.objects[a].constraint_bits > r.objects[b].constraint_bits;
  });
  if (order.size() > 3) order.resize(3);
  return order;
}

namespace {

std::string two_digits(double v) { return fmt::format("{:.2g}", v); }

std::string list_text(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    out += (i == 0 ? "" : (i + 1 == items.size() ? " and " : ", ")) + items[i];
  }
  return out;
}

/// "68 %: 0.45-0.78 g", with an open end said as below/above the grid (never the grid's edge as a number).
std::string interval_words(const char* level, const std::optional<double>& lo, const std::optional<double>& hi,
                           const char* unit) {
  if (lo && hi) return fmt::format("{}: {}\u2013{} {}", level, two_digits(*lo), two_digits(*hi), unit);
  if (hi) return fmt::format("{}: from below the grid to {} {}", level, two_digits(*hi), unit);
  if (lo) return fmt::format("{}: from {} {} to above the grid", level, two_digits(*lo), unit);
  return fmt::format("{}: anywhere on the grid", level);
}

/// "about 0.55 g", or "below the grid (under 0.02 g)" when the median lies in the grid's first cell.
std::string median_words(const Estimate& e, const std::vector<double>& axis, const char* unit) {
  if (e.median_edge < 0) return fmt::format("below the grid (at most about {} {})", two_digits(axis.front()), unit);
  if (e.median_edge > 0) return fmt::format("above the grid (at least about {} {})", two_digits(axis.back()), unit);
  return fmt::format("of about {} {}", two_digits(e.median), unit);
}

}  // namespace

std::string inversion_summary(const InversionResult& r) {
  const Estimate& pga = r.pga_estimate_g;
  const Estimate& f = r.freq_estimate_hz;
  std::string s = fmt::format(
      "The shaking at {} most likely had a PGA {} (median; {}, {}) and a predominant frequency {} (median; {}, "
      "{})",
      r.site.empty() ? std::string("the site") : r.site, median_words(pga, r.pga_g, "g"),
      interval_words("68 %", pga.ci68_low, pga.ci68_high, "g"), interval_words("95 %", pga.ci95_low, pga.ci95_high, "g"),
      median_words(f, r.freq_hz, "Hz"), interval_words("68 %", f.ci68_low, f.ci68_high, "Hz"),
      interval_words("95 %", f.ci95_low, f.ci95_high, "Hz"));
  const std::vector<std::size_t> top = most_constraining_objects(r);
  std::vector<std::string> names;
  for (std::size_t o : top) names.push_back(r.objects[o].id);
  if (names.empty() && r.objects.empty() && !r.populations.empty()) {
    // Populations only (issue 30): say what the counts were.
    std::vector<std::string> counts;
    for (const PopulationReport& p : r.populations) {
      counts.push_back(fmt::format("{} ({} of {} overturned)", p.id, p.overturned, p.count));
    }
    s += "; the evidence is the count" + std::string(counts.size() == 1 ? " of " : "s of ") + list_text(counts);
  } else if (names.empty()) {
    s += "; no single object constrains it much (each changes the posterior by less than 0.1 bit)";
  } else {
    s += fmt::format("; the {} that constrain{} it most {} {}", names.size() == 1 ? "object" : "objects",
                     names.size() == 1 ? "s" : "", names.size() == 1 ? "is" : "are", list_text(names));
  }
  std::vector<std::string> misfits;
  for (const ObjectReport& o : r.objects) {
    if (o.misfit) {
      misfits.push_back(fmt::format("{} ({}, P = {:.2f})", o.id, outcome_name(o.outcome), o.posterior_predictive));
    }
  }
  if (!misfits.empty()) {
    s += fmt::format("; not explained by this answer (posterior-predictive P below {}): {}", kMisfitProbability,
                     list_text(misfits));
  }
  // evidence.hpp: the objects alone when they differ from the posterior; what to look for next.
  return s + likelihood_summary_clause(r) + "." + three_component_summary(r) + next_objects_summary_clause(r);
}

std::vector<std::string> inversion_notes(const InversionResult& r, const MatchTable& m) {
  std::vector<std::string> notes;
  if (!r.bounds.lower_g) {
    notes.push_back("No object moved: the observations give no static lower bound on PGA.");
  }
  if (!r.bounds.upper_g) {
    notes.push_back("No object stayed put on its friction surface: the observations give no static upper threshold "
                    "on PGA.");
  }
  for (const std::string& c : r.bounds.contradictions) notes.push_back("Static contradiction: " + c + ".");
  const Estimate& pga = r.pga_estimate_g;
  if (!pga.ci95_low || !pga.ci95_high) {
    const std::string where =
        !pga.ci95_low && !pga.ci95_high
            ? fmt::format("both ends of the grid ({} and {})", fmt_g(r.pga_g.front()), fmt_g(r.pga_g.back()))
            : fmt::format("the {} end of the grid ({})", !pga.ci95_low ? "lower" : "upper",
                          !pga.ci95_low ? fmt_g(r.pga_g.front()) : fmt_g(r.pga_g.back()));
    notes.push_back(fmt::format("The 95 % interval of PGA reaches {}: the observations do not constrain it there.",
                                where));
  }
  if (!r.freq_estimate_hz.ci95_low || !r.freq_estimate_hz.ci95_high) {
    notes.push_back("The predominant frequency is not constrained at one or both ends of the grid by these "
                    "observations.");
    if (!r.pga_given_freq.empty()) {
      notes.push_back("If the predominant frequency is known from elsewhere (a nearby record's spectrum, the event's "
                      "size), read the PGA the objects need at it off pga_given_freq (JSON) or the ridge in the "
                      "report's Figure 1.");
    }
  }
  std::vector<std::string> misfits;
  for (const ObjectReport& rep : r.objects) {
    if (rep.misfit) {
      misfits.push_back(fmt::format("{} ({}, P = {:.3f})", rep.id, outcome_name(rep.outcome), rep.posterior_predictive));
    }
  }
  if (!misfits.empty()) {
    std::string list;
    for (const auto& s : misfits) list += (list.empty() ? "" : ", ") + s;
    notes.push_back(fmt::format("Misfit: the answer gives these observations a posterior-predictive probability below "
                                "{}: {}. Check them (object, outcome, friction, support) before trusting the estimate.",
                                kMisfitProbability, list));
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

std::vector<double> detail::pga_axis(const InversionSettings& st) {
  return log_spaced(st.pga_min_g, st.pga_max_g, static_cast<std::size_t>(st.pga_count));
}

std::vector<double> detail::freq_axis(const InversionSettings& st) {
  return log_spaced(st.freq_min_hz, st.freq_max_hz, static_cast<std::size_t>(st.freq_count));
}

std::vector<double> detail::evidence_error_rates(const Site& site) {
  std::vector<double> rates;
  for (const ObservedObject& o : site.objects) rates.push_back(evidence_error_rate(o.evidence));
  return rates;
}

detail::SiteRuns detail::simulate_site(const Site& site, const InversionSettings& st, const std::vector<double>& pga_g,
                                       const FamilyGrid& family, const InversionOptions& options) {
  SiteRuns runs;
  runs.bounds = static_bounds(site);
  if (site.objects.empty()) {  // populations only: an empty table of the grid's shape
    MatchTable empty;
    empty.pga_count = pga_g.size();
    empty.freq_count = family.motions.size();
    empty.motions = family.motions_per_column();
    runs.bins.push_back(std::move(empty));
  } else {
    // One component: one direction bin; the catalogue outcomes it can share are recorded for the ranking.
    runs.bins.push_back(detail::simulate_matches(site, st, pga_g, family, options,
                                                 options.next_objects ? &runs.catalogue_share : nullptr));
  }
  runs.runs = runs.bins.front().match.size();
  if (!site.populations.empty()) {  // population_likelihood.cpp
    PopulationRuns pop = simulate_populations(site, st, pga_g, family, options);
    runs.runs += pop.runs;
    runs.populations = population_reports(site, pop, pga_g.size() * family.motions.size());
    runs.population_run_log = std::move(pop.run_log);
  }
  for (const ObservedObject& o : site.objects) runs.models.push_back(object_model(o));
  runs.member = family.member;  // family = "mixture": the weights of its members (infer_site)
  runs.log_prior = log_prior_for(pga_g, family.freq_hz, site, st);  // the prior (prior.hpp)
  runs.prior = std::string(inversion_prior_name(st.prior));
  if (st.prior != InversionPrior::log_uniform) runs.notes.push_back("The prior: " + prior_description(site, st) + ".");
  return runs;
}

namespace {

/// The bins' mean match (for the notes, which ask whether some run matched); the table itself for one bin.
MatchTable mean_over_bins(const std::vector<MatchTable>& bins) {
  MatchTable t = bins.front();
  if (bins.size() == 1) return t;
  const double nb = static_cast<double>(bins.size());
  for (std::size_t i = 0; i < t.match.size(); ++i) {
    t.match[i] = 0.0;
    for (const MatchTable& b : bins) t.match[i] += b.match[i] / nb;
  }
  return t;
}

/// The direction axis' estimate (inversion_3c.hpp, item 5) from the joint posterior over (cell, bin), and what the
/// three-component result says in larger-component PGA.
void estimate_direction(InversionResult& r, const detail::SiteRuns& runs, const std::vector<double>& posterior_joint) {
  ThreeComponentResult tc = *runs.three_component;
  const std::size_t nb = runs.bins.size();
  std::vector<double> post_dir(nb, 0.0);
  for (std::size_t c = 0; c < r.posterior.size(); ++c) {
    for (std::size_t b = 0; b < nb; ++b) post_dir[b] += posterior_joint[c * nb + b];
  }
  tc.direction = direction_estimate(runs.direction_bins_deg, post_dir);
  tc.larger_component_median_g = r.pga_estimate_g.median * tc.larger_component_ratio;
  if (r.pga_estimate_g.ci95_low) tc.larger_component_ci95_low_g = *r.pga_estimate_g.ci95_low * tc.larger_component_ratio;
  if (r.pga_estimate_g.ci95_high) tc.larger_component_ci95_high_g = *r.pga_estimate_g.ci95_high * tc.larger_component_ratio;
  r.three_component = tc;
}

}  // namespace

InversionResult detail::infer_site(const Site& site, const std::vector<double>& pga_g,
                                   const std::vector<double>& freq_hz, const std::vector<double>& measured_freq_hz,
                                   SiteRuns runs) {
  InversionResult r;
  r.site = site.name;
  r.pga_g = pga_g;
  r.freq_hz = freq_hz;
  r.measured_freq_hz = measured_freq_hz;
  r.bounds = std::move(runs.bounds);
  r.rotd100_bounds = std::move(runs.rotd100_bounds);
  r.runs = runs.runs;
  const std::vector<double> error_rates = evidence_error_rates(site);
  const std::size_t nb = runs.bins.size();
  const std::size_t cells = runs.bins.front().cells();
  const std::size_t no = site.objects.size();

  // Step 3 per direction bin (inversion.hpp, item 2); the joint log-likelihood over (cell, bin), index c * nb + b,
  // and the cell's, log of the bins' mean (inversion_3c.hpp, item 5; with one bin, the bin's to the bit).
  std::vector<LikelihoodReduction> per_bin;
  const std::vector<double>* population_run_log = runs.population_run_log.empty() ? nullptr : &runs.population_run_log;
  for (std::size_t b = 0; b < runs.bins.size(); ++b) {
    const MatchTable& m = runs.bins[b];
    const double* pop = population_run_log == nullptr ? nullptr : population_run_log->data() + b * m.cells() * m.motions;
    per_bin.push_back(detail::reduce_likelihood(m, error_rates, pop));
  }
  std::vector<double> ll_joint(cells * nb);
  for (std::size_t c = 0; c < cells; ++c) {
    for (std::size_t b = 0; b < nb; ++b) ll_joint[c * nb + b] = per_bin[b].log_likelihood[c];
  }
  r.log_likelihood.assign(cells, 0.0);
  for (std::size_t c = 0; c < cells; ++c) {
    r.log_likelihood[c] = log_sum_exp(std::span<const double>(ll_joint).subspan(c * nb, nb)) -
                          std::log(static_cast<double>(nb));
  }
  r.objects.resize(no);
  for (std::size_t o = 0; o < no; ++o) {
    ObjectReport& rep = r.objects[o];
    rep.id = site.objects[o].id;
    rep.outcome = site.objects[o].outcome;
    rep.model = runs.models[o];
    rep.probability.assign(cells, 0.0);
    rep.reproduced_anywhere = false;
    for (std::size_t b = 0; b < nb; ++b) {
      for (std::size_t c = 0; c < cells; ++c) rep.probability[c] += per_bin[b].probability[o][c] / static_cast<double>(nb);
      rep.reproduced_anywhere = rep.reproduced_anywhere || per_bin[b].reproduced_anywhere[o];
    }
    rep.max_probability = *std::max_element(rep.probability.begin(), rep.probability.end());
  }
  // Step 4, and 4b over the joint posterior. With one bin it is the cell posterior, normalised as
  // fill_posterior_and_estimates does (which keeps one component's numbers to the bit). A prior (prior.hpp) multiplies
  // every bin of a cell alike: the joint log posterior is ll_joint + log_prior of the cell.
  r.log_prior = std::move(runs.log_prior);
  r.prior = runs.prior;
  fill_posterior_and_estimates(r);
  if (!runs.member.empty()) {  // family = "mixture": P(f | data) of its members (family_mixture.cpp), one bin
    r.family_weights = mixture_family_weights(runs.bins.front(), runs.member, error_rates,
                                              population_run_log == nullptr ? nullptr : population_run_log->data(),
                                              r.log_prior);
    runs.notes.push_back(mixture_note(r.family_weights));
  }
  if (!r.log_prior.empty()) {
    for (std::size_t c = 0; c < cells; ++c) {
      for (std::size_t b = 0; b < nb; ++b) ll_joint[c * nb + b] += r.log_prior[c];
    }
  }
  std::vector<double> posterior_joint = r.posterior;
  if (nb > 1) {
    const double z_joint = log_sum_exp(ll_joint);
    posterior_joint.resize(ll_joint.size());
    for (std::size_t i = 0; i < ll_joint.size(); ++i) posterior_joint[i] = std::exp(ll_joint[i] - z_joint);
  }
  assess_objects(r, runs.bins, error_rates, ll_joint, posterior_joint, population_run_log);
  r.populations = std::move(runs.populations);
  finish_population_reports(r);
  // Step 5, the notes: the common ones, then the motion family's own.
  r.notes = inversion_notes(r, mean_over_bins(runs.bins));
  for (std::string& note : runs.notes) r.notes.push_back(std::move(note));
  if (runs.three_component) {
    estimate_direction(r, runs, posterior_joint);
    const DirectionEstimate& d = r.three_component->direction;
    if (!d.constrained) {
      r.notes.push_back(fmt::format("The direction of strongest shaking is unconstrained: its 95 % arc spans {:.0f} "
                                    "deg (more than {:.0f} deg). Bearings of objects that rocked, overturned or stood, "
                                    "and sliding directions, constrain it.",
                                    d.ci95.width_deg, kUnconstrainedArcDeg));
    }
  }
  return r;
}

InversionResult invert_site(const Site& site, const InversionSettings& st, const InversionOptions& options) {
  return invert_sites({site}, st, options).front();
}

std::vector<InversionResult> invert_sites(const std::vector<Site>& sites, const InversionSettings& st,
                                          const InversionOptions& options) {
  validate_inversion_options(options);
  validate_inversion_settings(st);
  std::vector<InversionResult> out;
  if (sites.empty()) return out;
  auto start = std::chrono::steady_clock::now();
  // Step 1, the family, built once for every site (the same motions for each): one component, a ground motion per
  // run; three components (inversion_3c.hpp), a realisation of the motion set and a direction axis.
  const std::vector<double> pga_g = detail::pga_axis(st);
  const std::vector<double> freq_hz = detail::freq_axis(st);
  std::optional<FamilyGrid> one;
  std::optional<FamilyGrid3c> three;
  if (st.components == 3) {
    three = build_family_3c(st, freq_hz, options);
  } else {
    one = build_family(st, freq_hz, options);
  }
  const std::vector<double>& measured = three ? three->measured_freq_hz : one->measured_freq_hz;
  for (const Site& site : sites) {
    detail::SiteRuns runs = three ? detail::simulate_site_3c(site, st, pga_g, *three, options)
                                  : detail::simulate_site(site, st, pga_g, *one, options);
    const detail::CatalogueShare share = std::move(runs.catalogue_share);
    out.push_back(detail::infer_site(site, pga_g, freq_hz, measured, std::move(runs)));
    out.back().family = std::string(motion_family_name(st.family));
    // What to look for next (evidence.hpp): one component only (the catalogue is run on the family's motions).
    if (one && options.next_objects && !site.objects.empty()) {
      out.back().next_objects = detail::suggest_next_objects(out.back(), st, *one, options, &share);
    }
    const auto now = std::chrono::steady_clock::now();
    out.back().seconds = std::chrono::duration<double>(now - start).count();
    start = now;  // the family's time is counted in the first site's
  }
  return out;
}

}  // namespace topple
