// topple invert SURVEY: from observed objects to PGA and predominant-frequency bounds.
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>

#include <fmt/format.h>

#include "commands.hpp"
#include "progress.hpp"
#include "topple/core/error.hpp"
#include "topple/ensemble/ensemble.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/output/inversion_output.hpp"
#include "topple/output/provenance.hpp"
#include "topple/output/region_output.hpp"
#include "topple/output/region_report.hpp"
#include "topple/region/survey_inversion.hpp"
#include "topple/io/survey_file.hpp"

namespace topple::cli {
namespace {

struct InvertOptions {
  std::string survey;
  bool json = false;
  std::string grid;
  std::string map;
  std::string report;
  int threads = 0;
  bool quiet = false;
  bool no_next_objects = false;
};

/// The files and folder the command writes (io::write_survey_grids, write_survey_map, write_survey_report), in the
/// order of --help: each made ready before the runs (prepare_output_folder).
struct OutputOption {
  const char* name;
  std::string InvertOptions::*path;
  bool folder;  ///< a directory (--report), else a file
  const char* help;
};

constexpr std::array<OutputOption, 3> kOutputOptions{{
    {"--grid", &InvertOptions::grid, false, "Write the likelihood grid to this CSV file"},
    {"--map", &InvertOptions::map, false,
     "Write one GeoJSON point per site (and, with an epicentre, PGA vs distance CSV; with a regional fit, the region "
     "CSV and iso-acceleration contours)"},
    {"--report", &InvertOptions::report, true,
     "Write a self-contained HTML report (and its figures) into this directory"},
}};

std::string interval_text(const std::optional<double>& lo, const std::optional<double>& hi, const char* unit) {
  const auto end = [&](const std::optional<double>& v, const char* none) {
    return v ? fmt::format("{:.3g}", *v) : std::string(none);
  };
  return fmt::format("[{}, {}] {}", end(lo, "unconstrained"), end(hi, "unconstrained"), unit);
}

/// The exact command line of this process (Linux: /proc/self/cmdline), each argument quoted for a POSIX shell where
/// it needs it; "unknown" where it cannot be read.
std::string own_command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string raw((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (raw.empty()) return "unknown";
  std::string out;
  std::size_t start = 0;
  while (start < raw.size()) {
    std::size_t end = raw.find('\0', start);
    if (end == std::string::npos) end = raw.size();
    const std::string arg = raw.substr(start, end - start);
    const bool plain = !arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                             "0123456789_-./=:,+@%") == std::string::npos;
    std::string quoted = "'";
    for (char c : arg) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += (out.empty() ? "" : " ") + (plain ? arg : quoted + "'");
    start = end + 1;
  }
  return out;
}

void print_site(const Site& site, const InversionResult& r) {
  fmt::print("== {}\n", site.name);
  fmt::print("{}\n", inversion_summary(r));
  fmt::print("objects: {}   grid: {} PGA x {} frequencies, {} runs in {:.1f} s\n", site.objects.size(),
             r.pga_g.size(), r.freq_hz.size(), r.runs, r.seconds);
  // Three components: the thresholds hold on RotD100 (inversion_3c.hpp, item 6); listed there, with their
  // consequence on RotD50, the estimates' axis, on one line.
  const StaticBounds& listed = r.rotd100_bounds ? *r.rotd100_bounds : r.bounds;
  fmt::print("static thresholds on {}PGA: {} (hard: lower {}; soft ones a dynamic estimate may pass)\n",
             r.rotd100_bounds ? "RotD100 " : "", interval_text(listed.lower_g, listed.upper_g, "g"),
             listed.hard_lower_g ? fmt::format("{:.3g} g", *listed.hard_lower_g) : std::string("none"));
  for (const auto& b : listed.lower) {
    fmt::print("  lower {:.3g} g ({})  {}: {}\n", b.pga_g, b.hard ? "hard" : "soft", b.object_id, b.reason);
  }
  for (const auto& b : listed.upper) {
    fmt::print("  upper {:.3g} g ({})  {}: {}\n", b.pga_g, b.hard ? "hard" : "soft", b.object_id, b.reason);
  }
  if (r.rotd100_bounds) {
    fmt::print("  on RotD50 PGA (the estimates' axis): {} (hard: lower {})\n",
               interval_text(r.bounds.lower_g, r.bounds.upper_g, "g"),
               r.bounds.hard_lower_g ? fmt::format("{:.3g} g", *r.bounds.hard_lower_g) : std::string("none"));
  }
  const Estimate& pga = r.pga_estimate_g;
  const Estimate& freq = r.freq_estimate_hz;
  const auto edge = [](int at) { return at < 0 ? " (grid edge: below the grid)" : at > 0 ? " (grid edge: above the grid)" : ""; };
  fmt::print("PGA:       median {:.3g} g{}, 68 % {}, 95 % {}; maximum-likelihood cell {:.3g} g{}\n", pga.median,
             edge(pga.median_edge), interval_text(pga.ci68_low, pga.ci68_high, "g"),
             interval_text(pga.ci95_low, pga.ci95_high, "g"), pga.best, edge(pga.best_edge));
  fmt::print("frequency: median {:.3g} Hz{}, 68 % {}, 95 % {}; maximum-likelihood cell {:.3g} Hz{}\n", freq.median,
             edge(freq.median_edge), interval_text(freq.ci68_low, freq.ci68_high, "Hz"),
             interval_text(freq.ci95_low, freq.ci95_high, "Hz"), freq.best, edge(freq.best_edge));
  if (!r.marginal_pga_likelihood.empty() && !r.log_prior.empty()) {
    // The objects alone (evidence.hpp): only where a prior other than the log-uniform one makes them differ.
    const Estimate& lp = r.pga_likelihood_g;
    const Estimate& lf = r.freq_likelihood_hz;
    fmt::print("objects alone (likelihood, no {} prior): PGA median {:.3g} g{}, 68 % {}; frequency median {:.3g} Hz{}, "
               "68 % {}\n",
               r.prior, lp.median, edge(lp.median_edge), interval_text(lp.ci68_low, lp.ci68_high, "g"), lf.median,
               edge(lf.median_edge), interval_text(lf.ci68_low, lf.ci68_high, "Hz"));
  }
  fmt::print("objects: P(observation) posterior-predictive / at the maximum-likelihood cell, information (bits), "
             "misfit if P < {}:\n", kMisfitProbability);
  for (const auto& o : r.objects) {
    // With components = 3 the model each object ran with (slide: 2-D sliding block; rock: oriented rocking body)
    // follows its outcome; a one-component summary keeps its old lines.
    const std::string outcome = r.three_component ? fmt::format("{} ({})", outcome_name(o.outcome), object_model_name(o.model))
                                                  : std::string(outcome_name(o.outcome));
    fmt::print("  {:<16} {:<{}} {:.3f} / {:.2f}  {:.2f} bit{}\n", o.id, outcome, r.three_component ? 23 : 15,
               o.posterior_predictive,
               o.probability_at_best, o.constraint_bits, o.misfit ? "  MISFIT" : "");
  }
  if (!r.populations.empty()) {  // issue 30: populations (docs/survey.md, "[[population]]")
    fmt::print("populations: overturned observed / model at the estimate / posterior-predictive:\n");
    for (const PopulationReport& p : r.populations) {
      fmt::print("  {:<16} {} of {} = {:.3f} / {:.3f} / {:.3f}  ({})\n", p.id, p.overturned, p.count, p.observed_fraction,
                 p.model_fraction_at_estimate, p.posterior_predictive_fraction, p.member_rule);
    }
  }
  if (!r.next_objects.empty()) {
    fmt::print("what to look for next: expected information (bits) of one more object's outcome, on PGA / on frequency:\n");
    for (const NextObject& n : r.next_objects) {
      fmt::print("  {:<24} {:.2f} / {:.2f}  {}, {}\n", n.object, n.bits_pga, n.bits_freq, n.description, n.look_for);
    }
  }
  for (const auto& note : r.notes) fmt::print("note: {}\n", note);
}

std::string interval_text(const Interval95& v, const char* unit) {
  return fmt::format("{:.3g} {} (68 % [{:.3g}, {:.3g}], 95 % [{:.3g}, {:.3g}])", v.median, unit, v.ci68_low, v.ci68_high,
                     v.ci95_low, v.ci95_high);
}

void print_region(const RegionalResult& fit, const std::vector<const InversionResult*>& per_site) {
  fmt::print("== Region: ln PGA = c0 - c1 ln sqrt(R^2 + c2^2) + delta, delta ~ N(0, tau^2) (PGA in g, R hypocentral km)\n");
  fmt::print("c0  = {}\nc1  = {}\nc2  = {:g} km (fixed)\ntau = {}\n", interval_text(fit.c0, ""), interval_text(fit.c1, ""),
             fit.c2_km, interval_text(fit.tau, ""));
  fmt::print("{:<28} {:>8} {:>10} {:>26} {:>26}\n", "site", "R km", "instrument", "independent median [95 %] g",
             "pooled median [95 %] g");
  for (const PooledSite& p : fit.sites) {
    const InversionResult* r = per_site[p.site_index];
    std::string own = "-";
    if (r != nullptr) {
      const Estimate& e = r->pga_estimate_g;
      own = fmt::format("{:.3g} {}", e.median, interval_text(e.ci95_low, e.ci95_high, ""));
    }
    std::string instrument = p.instrument_pga_g ? fmt::format("{:.3g}", *p.instrument_pga_g) : std::string("-");
    fmt::print("{:<28} {:>8.1f} {:>10} {:>26} {:>26}\n", p.name, p.distance_km, instrument, own,
               fmt::format("{:.3g} [{:.3g}, {:.3g}]", p.pga_g.median, p.pga_g.ci95_low, p.pga_g.ci95_high));
    if (r != nullptr && p.instrument_pga_g) {
      fmt::print("  calibration site: the objects {} the instrument ({:.3g} g {} their own 95 % interval)\n",
                 objects_agree_with_instrument(r->pga_estimate_g, *p.instrument_pga_g) ? "agree with" : "DISAGREE with",
                 *p.instrument_pga_g,
                 objects_agree_with_instrument(r->pga_estimate_g, *p.instrument_pga_g) ? "inside" : "outside");
    }
    if (p.intensity) {  // issue 30: the intensity's PGA through WGRW12, and whether the objects agree with it
      fmt::print("  intensity {} {:g} ({} reports): PGA {:.3g} g [{:.3g}, {:.3g}] through WGRW12{}\n",
                 intensity_scale_name(p.intensity->intensity.scale), p.intensity->intensity.value,
                 p.intensity->intensity.reports ? fmt::format("{}", *p.intensity->intensity.reports) : "unstated",
                 p.intensity->pga_g, p.intensity->ci95_low_g(), p.intensity->ci95_high_g(),
                 r == nullptr ? ""
                 : objects_agree_with_intensity(r->pga_estimate_g, *p.intensity)
                     ? "; the objects agree with it"
                     : "; the objects DISAGREE with it");
    }
  }
  for (const std::string& note : fit.notes) fmt::print("note: region: {}\n", note);
  if (!fit.frequency) return;
  const FrequencyRelation& f = *fit.frequency;
  fmt::print("== Frequency: ln f = d0 + d1 ln sqrt(R^2 + c2^2) + eps, eps ~ N(0, tau_f^2) (f in Hz), against a constant f\n");
  fmt::print("d0    = {}\nd1    = {}\ntau_f = {}\n", interval_text(f.d0, ""), interval_text(f.d1, ""),
             interval_text(f.tau, ""));
  fmt::print("constant model: f = {}\n", interval_text(f.constant_f_hz, "Hz"));
  fmt::print("Bayes factor relation/constant = {:.3g} (ln {:.2f}, {} sites with a frequency likelihood): {}\n",
             std::exp(f.ln_bayes_factor), f.ln_bayes_factor, f.sites_with_frequency,
             f.supported ? "the data support the relation; frequencies pooled through it"
                         : "not supported (B < 3): no pooled frequencies");
  if (f.supported) {
    fmt::print("{:<28} {:>8} {:>26} {:>26}\n", "site", "R km", "independent median [95 %] Hz", "pooled median [95 %] Hz");
    for (const PooledSite& p : fit.sites) {
      const InversionResult* r = per_site[p.site_index];
      const std::string own = r != nullptr ? fmt::format("{:.3g} {}", r->freq_estimate_hz.median,
                                                         interval_text(r->freq_estimate_hz.ci95_low,
                                                                       r->freq_estimate_hz.ci95_high, ""))
                                           : std::string("-");
      fmt::print("{:<28} {:>8.1f} {:>26} {:>26}\n", p.name, p.distance_km, own,
                 fmt::format("{:.3g} [{:.3g}, {:.3g}]", p.freq_hz->median, p.freq_hz->ci95_low, p.freq_hz->ci95_high));
    }
  }
  for (const std::string& note : f.notes) fmt::print("note: region frequency: {}\n", note);
}

/// Output files may name folders that do not exist yet (as --report does): made before the runs, so that a path
/// that cannot be written fails in a second instead of after the inversion.
void prepare_output_folder(const std::string& path, const char* option, bool is_folder = false) {
  std::error_code ec;
  if (!is_folder && std::filesystem::is_directory(path, ec)) {
    throw InputError(InputLocation{path, {}, option}, "is a directory; give a file name");
  }
  if (is_folder && std::filesystem::exists(path, ec) && !std::filesystem::is_directory(path, ec)) {
    throw InputError(InputLocation{path, {}, option}, "exists and is not a directory");
  }
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (parent.empty()) return;
  std::filesystem::create_directories(parent, ec);
  if (ec) throw InputError(InputLocation{parent.string(), {}, option}, "cannot create the folder: " + ec.message());
}

void run_invert(const InvertOptions& o) {
  // Every option is checked before any work (the survey is read in milliseconds; the runs take seconds).
  InversionOptions options;
  options.threads = o.threads;
  options.next_objects = !o.no_next_objects;
  validate_inversion_options(options);
  // Under mpirun/srun the sites are split across the ranks (inversion_distributed.hpp); rank 0 alone prints and
  // writes, the others return after the gather.
  std::unique_ptr<ensemble::Cluster> cluster = ensemble::join_cluster();
  const bool quiet = o.quiet || cluster->rank() != 0;
  ProgressBar bar(progress_wanted(quiet));
  options.progress = bar.callback();
  const Survey survey = io::read_survey(o.survey);
  const io::Provenance provenance = io::make_provenance(o.survey, own_command_line());
  for (const OutputOption& out : kOutputOptions) {
    if (!(o.*out.path).empty()) prepare_output_folder(o.*out.path, out.name, out.folder);
  }
  if (!quiet) {
    for (const std::string& note : survey.notes) fmt::print(stderr, "topple: note: {}\n", note);
  }
  if (cluster->rank() == 0) {  // warnings are said even with --quiet, as the sweep's are
    for (const std::string& w : survey.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
  }
  if (!quiet) {
    if (cluster->size() > 1) fmt::print(stderr, "topple: {} sites over {} MPI ranks\n", survey.sites.size(), cluster->size());
    for (const Site& site : survey.sites) {
      fmt::print(stderr, "topple: inverting {} ({} objects)...\n", site.name, site.objects.size());
    }
  }
  // The library's survey-level entry point (survey_inversion.hpp), as Python calls it: one family for every site, the
  // sites split across MPI ranks under mpirun, then the regional fit; the files as the library writes them.
  const RegionalSettings region_settings;
  const SurveyInversion inversion = invert_survey(survey, options, *cluster, region_settings);
  bar.finish();
  if (cluster->rank() != 0) return;  // rank 0 reports
  if (!o.grid.empty()) io::write_survey_grids(o.grid, survey, inversion);
  if (!o.map.empty()) io::write_survey_map(o.map, survey, inversion);
  if (!o.report.empty()) {
    const SurveyReport report = write_survey_report(o.report, survey, inversion, provenance, region_settings);
    for (const std::filesystem::path& page : report.site_pages) {
      if (!o.quiet) fmt::print(stderr, "topple: report written to {}\n", page.string());
    }
    for (const std::string& w : report.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
    if (report.region_page && !o.quiet) fmt::print(stderr, "topple: regional page written to {}\n", report.region_page->string());
  }
  if (o.json) {
    fmt::print("{}\n", io::survey_inversion_json(survey, inversion, provenance, region_settings).dump(2));
    return;
  }
  const std::vector<Site> sites = inversion.sites_with_objects(survey);
  for (std::size_t k = 0; k < inversion.results.size(); ++k) print_site(sites[k], inversion.results[k]);
  for (const std::string& note : inversion.region_notes) fmt::print("note: {}\n", note);
  if (inversion.region) print_region(*inversion.region, inversion.per_site(survey.sites.size()));
}

}  // namespace

void add_invert_command(CLI::App& app) {
  auto o = std::make_shared<InvertOptions>();
  CLI::App* cmd = app.add_subcommand("invert", "From observed objects (a survey file) to PGA and predominant-"
                                               "frequency bounds, a likelihood map and a report");
  cmd->add_option("survey", o->survey, "Survey file (TOML; see examples/survey.toml)")->required();
  cmd->add_flag("--json", o->json, "Print the result as one JSON object");
  for (const OutputOption& out : kOutputOptions) cmd->add_option(out.name, (*o).*out.path, out.help);
  cmd->add_option("--threads", o->threads, "Worker threads (default: all cores)");
  add_quiet_flag(*cmd, o->quiet, "no notes and no progress messages");
  cmd->add_flag("--no-next-objects", o->no_next_objects,
                "Skip ranking the household catalogue by what one more object would tell (saves its runs)");
  cmd->callback([o] { run_invert(*o); });
}

}  // namespace topple::cli
