// topple slide --support-freq ... | --height ...: parsing and printing only (physics in topple/solvers/flexible.hpp).
#include "slide_flexible.hpp"

#include <charconv>
#include <cmath>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "topple/core/error.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/output/flexible_json.hpp"
#include "topple/output/plot.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

/// "5%" -> 0.05, "0.05" -> 0.05.
double parse_ratio(const std::string& text, const std::string& field) {
  std::string body = text;
  double factor = 1.0;
  if (!body.empty() && body.back() == '%') {
    body.pop_back();
    factor = 0.01;
  }
  double value = 0.0;
  const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), value);
  if (ec != std::errc() || end != body.data() + body.size() || body.empty() || !std::isfinite(value)) {
    throw parameter_error(field, fmt::format("expected a ratio such as 0.05 or 5%, got '{}'", text));
  }
  return value * factor;
}

/// The library names its fields (SupportOscillator::make, SlidingMassColumn::make, the analyses); the user typed
/// options. `mu_option` is the option the library's "mu_kinetic" refusal is about (--mu-kinetic or --slope-deg).
template <class F>
auto naming_flexible_options(F f, const char* mu_option = "--mu-kinetic") -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    const std::pair<const char*, const char*> names[] = {
        {"support_freq", "--support-freq"}, {"support_damping", "--support-damping"}, {"mass_ratio", "--mass-ratio"},
        {"height", "--height"},             {"vs_slope", "--vs-slope"},               {"vs_base", "--vs-base"},
        {"damping", "--damping"},           {"reference_strain", "--ref-strain"},     {"ky", "--mu"},
        {"mu_kinetic", mu_option}};
    for (const auto& [field, option] : names) {
      if (e.where().field == field) throw parameter_error(option, e.problem());
    }
    throw;
  }
}

}  // namespace

void check_flexible_options(const FlexibleOptions& o) {
  const bool shelf = !o.support_freq.empty(), column = !o.height.empty();
  if (shelf && column) {
    throw parameter_error("--height", "give either --support-freq (shelf, floor) or --height (sliding mass)");
  }
  // Options that describe one of the two supports mean nothing without it: refused, never ignored.
  const std::pair<bool, const char*> column_options[] = {{o.vs_slope_m_s.has_value(), "--vs-slope"},
                                                         {o.vs_base_m_s.has_value(), "--vs-base"},
                                                         {!o.damping.empty(), "--damping"},
                                                         {!o.reference_strain.empty(), "--ref-strain"}};
  const std::pair<bool, const char*> shelf_options[] = {{!o.support_damping.empty(), "--support-damping"},
                                                        {o.mass_ratio.has_value(), "--mass-ratio"}};
  for (const auto& [given, option] : column_options) {
    if (!given) continue;
    if (shelf) {
      throw parameter_error("--support-freq", "--height, --vs-slope, --vs-base, --damping and --ref-strain describe "
                                              "a sliding mass, not a shelf or floor");
    }
    if (!column) throw parameter_error(option, fmt::format("{} needs --height (a flexible sliding mass)", option));
  }
  for (const auto& [given, option] : shelf_options) {
    if (!given) continue;
    if (column) throw parameter_error("--height", "--support-damping and --mass-ratio describe a shelf or floor");
    if (!shelf) throw parameter_error(option, fmt::format("{} needs --support-freq (a shelf or floor)", option));
  }
  if (o.coupled && !shelf && !column) {
    throw parameter_error("--coupled", "--coupled needs --support-freq (a shelf or floor) or --height (a sliding "
                                       "mass): a rigid support has no coupling");
  }
  if (o.mass_ratio && !o.coupled) {
    throw parameter_error("--mass-ratio", "--mass-ratio needs --coupled (the decoupled analysis leaves the support "
                                          "unloaded by the object)");
  }
}

SupportOscillator support_from_options(const std::string& support_freq, const std::string& support_damping,
                                       double mass_ratio) {
  const double freq_hz = parse_frequency_hz(support_freq, "--support-freq");
  const double damping = support_damping.empty() ? kDefaultDampingRatio : parse_ratio(support_damping, "--support-damping");
  return naming_flexible_options([&] { return SupportOscillator::make(freq_hz, damping, mass_ratio); });
}

void add_flexible_options(CLI::App& cmd, FlexibleOptions& o) {
  cmd.add_option("--support-freq", o.support_freq, "Object on a shelf or floor: the support's natural frequency "
                                                   "(e.g. 4Hz or 0.25s)");
  cmd.add_option("--support-damping", o.support_damping, "Damping ratio of the support (5% or 0.05; default 5%)");
  cmd.add_option("--mass-ratio", o.mass_ratio, "Object mass / support mass (coupled analysis; default 0)");
  cmd.add_option("--height", o.height, "SLAMMER flexible sliding mass: its height (e.g. 50m); --mu is then k_y");
  cmd.add_option("--vs-slope", o.vs_slope_m_s, "Shear-wave velocity of the sliding mass, m/s");
  cmd.add_option("--vs-base", o.vs_base_m_s, "Shear-wave velocity below the sliding surface, m/s");
  cmd.add_option("--damping", o.damping, "Material damping ratio of the sliding mass (5% or 0.05)");
  cmd.add_option("--ref-strain", o.reference_strain, "Equivalent-linear analysis with this reference shear strain "
                                                     "(0.05% or 0.0005); linear elastic without it");
  cmd.add_flag("--coupled", o.coupled, "Coupled analysis (the slip feeds back on the support); decoupled without it");
}

void run_flexible_slide(const GroundMotion& horizontal, const SlidingBlock& block, const FlexibleOptions& o, bool json,
                        const std::string& motion_name, const GroundMotion* vertical, const std::string& out,
                        const std::string& plot, const std::string& pulse_kind) {
  const bool with_history = !out.empty() || !plot.empty();
  FlexibleHistory history;
  check_flexible_options(o);
  // The support's response is exact for uniformly sampled input (flexible.hpp); analytic pulses keep their jumps
  // and the end of their last cycle exactly, on an irregular grid. Said about what the user gave, a pulse or a file.
  if (!horizontal.is_uniform()) {
    if (!pulse_kind.empty()) {
      throw parameter_error("--pulse", fmt::format("the {} pulse is sampled irregularly (at its jumps and the end of "
                                                   "its cycles): flexible supports run on uniformly sampled records "
                                                   "only (write the pulse to a record file at a uniform step)",
                                                   pulse_kind));
    }
    throw InputError(InputLocation{.file = motion_name, .line = {}, .field = {}},
                     "the record is irregularly sampled: flexible-support analyses need a uniformly sampled record "
                     "(resample it first)");
  }
  const FlexibleAnalysis analysis = o.coupled ? FlexibleAnalysis::coupled : FlexibleAnalysis::decoupled;
  const double g = block.g_m_s2;
  FlexibleSummary r;
  nlohmann::ordered_json j;
  const char* mu_option = block.mu_kinetic != block.mu_static ? "--mu-kinetic" : "--slope-deg";
  if (!o.support_freq.empty()) {
    const SupportOscillator s = support_from_options(o.support_freq, o.support_damping, o.mass_ratio.value_or(0.0));
    naming_flexible_options([&] {
      if (with_history) {
        FlexibleResult full = slide_flexible_history(horizontal, s, block, analysis, vertical);
        r = full.summary;
        history = std::move(full.history);
      } else {
        r = slide_flexible(horizontal, s, block, analysis, vertical);
      }
    }, mu_option);
    j = io::flexible_summary_json(r, block, s, analysis);
  } else {
    if (!o.vs_slope_m_s || !o.vs_base_m_s || o.damping.empty()) {
      throw parameter_error("--height", "a sliding mass needs --vs-slope, --vs-base and --damping");
    }
    if (block.slope_rad != 0.0 || block.mu_kinetic != block.mu_static) {
      throw parameter_error("--height", "the sliding mass is described by k_y (--mu) alone: no --slope-deg or --mu-kinetic");
    }
    std::optional<double> ref;
    if (!o.reference_strain.empty()) ref = parse_ratio(o.reference_strain, "--ref-strain");
    const double damping = parse_ratio(o.damping, "--damping");
    // The library accepts a negative material damping while the total with the impedance damping stays in [0, 1)
    // (SLAMMER's published suite enters -5 % against its 20 % impedance damping, flexible.hpp); a user's
    // --damping -5% is a typing slip far more often than that: refused, the range stated.
    if (!(damping >= 0.0 && damping < 1.0)) {
      throw parameter_error("--damping", fmt::format("the material damping ratio must be in [0, 1) (0.05 or 5%), "
                                                     "got '{}'", o.damping));
    }
    const SlidingMassColumn col = naming_flexible_options([&] {
      return SlidingMassColumn::make(parse_length_m(o.height, "--height"), *o.vs_slope_m_s, *o.vs_base_m_s, damping,
                                     ref);
    });
    naming_flexible_options([&] {
      if (with_history) {
        FlexibleResult full = slide_flexible_history(horizontal, col, block.mu_static, analysis, block.mode, g, vertical);
        r = full.summary;
        history = std::move(full.history);
      } else {
        r = slide_flexible(horizontal, col, block.mu_static, analysis, block.mode, g, vertical);
      }
    });
    j = io::flexible_summary_json(r, block, col, analysis);
  }
  if (!out.empty()) io::write_flexible_history_csv(out, history, horizontal);
  if (!plot.empty()) {
    // The rigid run's figure (record, yield levels, slip starts, relative velocity and displacement) with the
    // sliding surface's own acceleration drawn over the ground's.
    plot::Figure f = plot::sliding_figure(
        horizontal, SlidingResult{r.sliding, history.sliding}, block,
        fmt::format("{} sliding on a {}, yield {:.3g} g: {}", j["support"]["analysis"].get<std::string>(),
                    o.support_freq.empty() ? "flexible sliding mass" : "flexible support", block.mu_static,
                    motion_name));
    std::vector<double> support_g(history.support_accel_m_s2.size());
    for (std::size_t i = 0; i < support_g.size(); ++i) support_g[i] = history.support_accel_m_s2[i] / g;
    f.panels.front().series.push_back({"support", history.sliding.time_s, std::move(support_g), "lines", "#27ae60", 1.2});
    plot::render(f, plot);
  }
  if (json) {
    nlohmann::ordered_json input;
    input["motion"] = motion_name;
    input["pga_g"] = horizontal.pga_m_s2() / g;
    input["vertical"] = vertical != nullptr;
    input["npts"] = horizontal.size();
    input["dt_s"] = horizontal.dt_s();
    j["input"] = input;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("{} analysis on a {}: mode {:.4g} Hz, damping {:.4g}, k_max {:.4f}\n", j["support"]["analysis"].get<std::string>(),
             o.support_freq.empty() ? "flexible sliding mass" : "shelf/floor oscillator",
             r.mode.omega_rad_s / (2.0 * kPi), r.mode.damping_ratio, r.kmax);
  if (o.support_freq.empty()) fmt::print("final V_s {:.4g} m/s after {} equivalent-linear iterations\n", r.mode.vs_m_s, r.mode.iterations);
  fmt::print("motion: {} (PGA {:.4f} g, {} samples), yield {:.4f} g, {}\n", motion_name, horizontal.pga_m_s2() / g,
             horizontal.size(), block.mu_static, block.mode == SlidingMode::one_way ? "one-way" : "two-way");
  fmt::print("max |displacement|     {:.6g} m at {:.4f} s\n", r.sliding.max_abs_displacement_m,
             r.sliding.max_displacement_time_s);
  fmt::print("residual displacement  {:.6g} m\n", r.sliding.residual_displacement_m);
  fmt::print("slip episodes          {}\n", r.sliding.slip_episodes);
  if (!out.empty()) fmt::print("history written to {}\n", out);
  if (!plot.empty()) fmt::print("figure written to {}\n", plot);
}

}  // namespace topple::cli
