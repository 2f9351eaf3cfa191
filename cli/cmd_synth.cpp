// topple synth: a synthetic ground motion (synthesis.hpp) written as a CSV that every topple command reads back.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "grids.hpp"
#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/plot.hpp"
#include "topple/motion/spectra.hpp"
#include "topple/motion/stochastic.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/motion/rotd.hpp"
#include "slide_2d.hpp"

namespace topple::cli {
namespace {

struct SynthOptions {
  bool quiet = false;
  std::string pga;
  std::string freq;
  std::string duration;
  std::string dt = "0.01s";
  std::string seed = "0";
  std::string model = "clough-penzien";
  std::string envelope = "saragoni-hart";
  double zeta_g = 0.3;
  double g_m_s2 = kStandardGravity;
  std::string out;
  std::string plot;
  bool json = false;
  int components = 1;        // 1; 2: a horizontal pair; 3: the pair and a vertical
  double coherence = 0.0;    // rho of the pair's white noises
  double vh_ratio = 2.0 / 3.0;
  double vh_freq_ratio = 1.5;
  std::string azimuths = "90,0";
  // The stochastic point-source method (stochastic.hpp) instead of filtered noise: --magnitude and --distance-km.
  std::optional<double> magnitude;
  std::optional<double> distance_km;
};

/// "motion.csv" -> "motion.h1.csv" (the suffix before the extension; appended when there is none).
std::string component_path(const std::string& path, const char* suffix) {
  const std::filesystem::path p(path);
  std::filesystem::path out = p;
  out.replace_filename(p.stem().string() + "." + suffix + p.extension().string());
  return out.string();
}

/// Decimals that print every multiple of dt exactly enough for the reader to see a uniform grid (dt = 0.01 -> 2);
/// nullopt when dt has no short decimal form.
std::optional<int> decimals_of(double dt) {
  double scale = 1.0;
  for (int p = 0; p <= 9; ++p, scale *= 10.0) {
    const double scaled = dt * scale;
    if (std::abs(scaled - std::round(scaled)) <= 1e-9 * scaled) return p;
  }
  return std::nullopt;
}

/// The rows "time_s,accel_g" of a motion sampled at dt_s (times printed exactly enough to read as a uniform grid).
std::string csv_rows(const GroundMotion& motion, double dt_s, double g) {
  const auto a = motion.accel_m_s2();
  const std::optional<int> decimals = decimals_of(dt_s);
  std::string buffer;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = static_cast<double>(i) * dt_s;
    buffer += decimals ? fmt::format("{:.{}f}", t, *decimals) : fmt::format("{}", t);
    buffer += fmt::format(",{}\n", a[i] / g);
  }
  return buffer;
}

void write_motion_csv(const std::string& path, const GroundMotion& motion, const SynthesisSpec& spec, double f_g,
                      double g, const std::string& component_line = {}) {
  io::OutputFile file(path);
  std::ostream& out = file.stream();
  out << "# topple synth: Kanai-Tajimi / Clough-Penzien filtered white noise under a time envelope (docs/method.md)\n";
  if (!component_line.empty()) out << "# " << component_line << "\n";
  out << fmt::format("# model={} envelope={} pga_g={} freq_hz={} duration_s={} dt_s={} seed={} zeta_g={} "
                     "f_g_hz={:.9g} g_m_s2={}\n",
                     filter_model_name(spec.model), envelope_kind_name(spec.envelope), spec.pga_m_s2 / g,
                     spec.predominant_frequency_hz, spec.duration_s, spec.dt_s, spec.seed, spec.ground_damping, f_g, g);
  out << "time_s,accel_g\n" << csv_rows(motion, spec.dt_s, g);
  file.commit();
}

/// --components 2 or 3: a horizontal pair (RotD50 PGA = --pga) and optionally a vertical, one CSV per component.
void run_synth_set(const SynthOptions& o, const SynthesisSpec& horizontal) {
  if (o.components != 2 && o.components != 3) {
    throw parameter_error("--components", fmt::format("1, 2 (a horizontal pair) or 3 (and a vertical), got {}",
                                                      o.components));
  }
  if (!o.plot.empty()) throw parameter_error("--plot", "draws one motion; not with --components 2 or 3");
  if (o.out.empty()) throw parameter_error("--out", "give the CSV file name; the components get .h1, .h2, .v");
  SynthesisSetSpec spec;
  spec.horizontal = horizontal;
  spec.coherence = o.coherence;
  spec.azimuths = parse_azimuths(o.azimuths);
  spec.vertical = o.components == 3;
  spec.vertical_pga_ratio = o.vh_ratio;
  spec.vertical_frequency_ratio = o.vh_freq_ratio;
  const SynthesizedSet set = [&] {
    try {
      return synthesize_set(spec);
    } catch (const InputError& e) {
      const std::string& field = e.where().field;
      throw parameter_error(field == "coherence" ? "--coherence" : field == "azimuths" ? "--azimuths"
                            : field == "vertical_pga_ratio" ? "--vh-ratio"
                            : field == "vertical_frequency_ratio" || field.starts_with("vertical ") ? "--vh-freq-ratio"
                                                                                                      : field,
                            e.problem());
    }
  }();
  const std::string p1 = component_path(o.out, "h1");
  const std::string p2 = component_path(o.out, "h2");
  const std::string pv = component_path(o.out, "v");
  for (const std::string& p : {p1, p2}) check_output_path(p);
  if (set.vertical) check_output_path(pv);
  const double g = o.g_m_s2;
  const double f_g = ground_frequency_for_request_hz(horizontal.predominant_frequency_hz, horizontal.ground_damping,
                                                     horizontal.model);
  const auto line = [&](const char* name, double az) {
    return fmt::format("component={} azimuth_deg={:g} (clockwise from north) coherence={:g}; the pair's RotD50 PGA is "
                       "pga_g", name, az, spec.coherence);
  };
  write_motion_csv(p1, set.first, horizontal, f_g, g, line("H1", spec.azimuths.first_deg));
  write_motion_csv(p2, set.second, horizontal, f_g, g, line("H2", spec.azimuths.second_deg));
  SynthesisSpec vspec = horizontal;
  if (set.vertical) {
    vspec.pga_m_s2 = spec.vertical_pga_ratio * horizontal.pga_m_s2;
    vspec.predominant_frequency_hz = spec.vertical_frequency_ratio * horizontal.predominant_frequency_hz;
    const double f_gv =
        ground_frequency_for_request_hz(vspec.predominant_frequency_hz, vspec.ground_damping, vspec.model);
    write_motion_csv(pv, *set.vertical, vspec, f_gv, g,
                     fmt::format("component=V vertical (positive up): V/H PGA ratio {:g} of the pair's RotD50 PGA, "
                                 "f_v/f_h {:g}, its own noise (seed stream 3)",
                                 spec.vertical_pga_ratio, spec.vertical_frequency_ratio));
  }
  const MotionSet ms = MotionSet::make(set.first, &set.second, spec.azimuths);
  const RotDMeasures r = rotd_measures(ms, {});
  if (o.json) {
    nlohmann::ordered_json j;
    j["out"] = set.vertical ? nlohmann::ordered_json({p1, p2, pv}) : nlohmann::ordered_json({p1, p2});
    j["model"] = filter_model_name(horizontal.model);
    j["envelope"] = envelope_kind_name(horizontal.envelope);
    j["seed"] = horizontal.seed;
    j["npts"] = set.first.size();
    j["dt_s"] = horizontal.dt_s;
    j["azimuths_deg"] = {spec.azimuths.first_deg, spec.azimuths.second_deg};
    j["coherence"] = spec.coherence;
    j["rotd50_pga_g"] = r.pga_m_s2.rotd50 / g;
    j["rotd100_pga_g"] = r.pga_m_s2.rotd100 / g;
    j["pga_g"] = {set.first.pga_m_s2() / g, set.second.pga_m_s2() / g};
    j["vertical_pga_g"] = set.vertical ? nlohmann::ordered_json(set.vertical->pga_m_s2() / g)
                                       : nlohmann::ordered_json(nullptr);
    j["vertical_frequency_hz"] = set.vertical ? nlohmann::ordered_json(vspec.predominant_frequency_hz)
                                              : nlohmann::ordered_json(nullptr);
    j["requested_frequency_hz"] = horizontal.predominant_frequency_hz;
    j["g_m_s2"] = g;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("wrote {} and {}{}: {} samples each, dt {} s, seed {}, coherence {:g}\n", p1, p2,
             set.vertical ? " and " + pv : "", set.first.size(), horizontal.dt_s, horizontal.seed, spec.coherence);
  fmt::print("pair: RotD50 PGA {:.5g} g (the --pga), RotD100 {:.5g} g; H1 ({:g} deg) PGA {:.5g} g, H2 ({:g} deg) "
             "PGA {:.5g} g\n",
             r.pga_m_s2.rotd50 / g, r.pga_m_s2.rotd100 / g, spec.azimuths.first_deg, set.first.pga_m_s2() / g,
             spec.azimuths.second_deg, set.second.pga_m_s2() / g);
  if (set.vertical) {
    fmt::print("vertical: PGA {:.5g} g (V/H {:g}), requested predominant frequency {:.4g} Hz (f_v/f_h {:g})\n",
               set.vertical->pga_m_s2() / g, spec.vertical_pga_ratio, vspec.predominant_frequency_hz,
               spec.vertical_frequency_ratio);
  }
}

/// --magnitude M --distance-km R: one motion of Boore's (2003) stochastic method (stochastic.hpp), its own PGA
/// unless --pga scales it; its length and frequency content follow from M and R.
void run_synth_stochastic(const SynthOptions& o) {
  if (!o.magnitude) throw parameter_error("--magnitude", "--distance-km needs --magnitude");
  if (!o.distance_km) throw parameter_error("--distance-km", "--magnitude needs --distance-km");
  if (!o.freq.empty() || !o.duration.empty()) {
    throw parameter_error(o.freq.empty() ? "--duration" : "--freq",
                          "the stochastic method's frequency content and duration follow from --magnitude and "
                          "--distance-km; give neither --freq nor --duration");
  }
  if (o.components != 1) throw parameter_error("--components", "the stochastic method makes one component");
  StochasticSpec spec;
  spec.magnitude = *o.magnitude;
  spec.distance_km = *o.distance_km;
  spec.dt_s = parse_seconds(o.dt, "--dt");
  spec.seed = parse_seed(o.seed, "--seed");
  try {
    validate(spec);
  } catch (const InputError& e) {
    const std::string& field = e.where().field;
    throw parameter_error(field == "magnitude" ? "--magnitude" : field == "distance_km" ? "--distance-km"
                          : field == "dt_s"    ? "--dt"
                                               : field,
                          e.problem());
  }
  GroundMotion motion = synthesize_stochastic(spec);
  if (!o.pga.empty()) motion = motion.scaled_to_pga(parse_acceleration_m_s2(o.pga, "--pga", o.g_m_s2));
  const double measured = predominant_frequency_hz(motion);
  const double fc = corner_frequency_hz(spec.magnitude, spec.model);
  const double t_gm = stochastic_duration_s(spec.magnitude, spec.distance_km, spec.model);
  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    std::ostream& out = file.stream();
    out << "# topple synth: stochastic point-source motion (Boore 2003; docs/method.md)\n";
    out << fmt::format("# magnitude={} distance_km={} stress_bar={} kappa0_s={} corner_hz={:.9g} duration_gm_s={:.9g} "
                       "dt_s={} seed={} g_m_s2={}\n",
                       spec.magnitude, spec.distance_km, spec.model.stress_drop_bar, spec.model.kappa0_s, fc, t_gm,
                       spec.dt_s, spec.seed, o.g_m_s2);
    out << "time_s,accel_g\n" << csv_rows(motion, spec.dt_s, o.g_m_s2);
    file.commit();
  }
  if (!o.plot.empty()) {
    const FourierSpectrum fas = fourier_amplitude_spectrum(motion, predominant_frequency_fft_length(motion.size()));
    const std::vector<double> centres = predominant_frequency_centres_hz(motion.dt_s());
    const std::vector<double> smooth = konno_ohmachi_smooth(fas, centres, 40.0);
    const double peak = fas_peak_frequency_hz(spec.magnitude, spec.distance_km, spec.model);
    const std::vector<plot::Mark> marks{{peak, fmt::format("model peak {:.3g} Hz", peak), "#e67e22"},
                                        {measured, fmt::format("measured f_p {:.3g} Hz", measured), "#c0392b"}};
    const std::string title = fmt::format("Stochastic point-source motion (Boore 2003): M {:.3g}, R {:.3g} km, PGA "
                                          "{:.3g} g, seed {}",
                                          spec.magnitude, spec.distance_km, motion.pga_m_s2() / o.g_m_s2, spec.seed);
    plot::render(plot::motion_spectrum_figure(motion, fas, centres, smooth, marks, o.g_m_s2, title), o.plot);
  }
  if (o.json) {
    nlohmann::ordered_json j;
    j["out"] = o.out.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.out);
    j["plot"] = o.plot.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.plot);
    j["model"] = "boore2003";
    j["magnitude"] = spec.magnitude;
    j["distance_km"] = spec.distance_km;
    j["stress_bar"] = spec.model.stress_drop_bar;
    j["kappa0_s"] = spec.model.kappa0_s;
    j["corner_frequency_hz"] = fc;
    j["duration_gm_s"] = t_gm;
    j["seed"] = spec.seed;
    j["npts"] = motion.size();
    j["dt_s"] = spec.dt_s;
    j["duration_s"] = motion.duration_s();
    j["pga_g"] = motion.pga_m_s2() / o.g_m_s2;
    j["predominant_frequency_hz"] = measured;
    j["g_m_s2"] = o.g_m_s2;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  if (!o.out.empty()) fmt::print("wrote {}: ", o.out);
  fmt::print("{} samples, dt {} s, stochastic point source M {} at {} km (corner {:.3g} Hz, T_gm {:.3g} s), seed {}\n",
             motion.size(), spec.dt_s, spec.magnitude, spec.distance_km, fc, t_gm, spec.seed);
  fmt::print("PGA {:.5g} g; predominant frequency measured {:.4g} Hz\n", motion.pga_m_s2() / o.g_m_s2, measured);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

void run_synth(const SynthOptions& o) {
  // Without the stochastic method's options, the filtered noise needs all three: CLI11's own error, first, as when
  // they were marked required.
  if (!o.magnitude && !o.distance_km) {
    for (const auto& [value, name] : {std::pair{&o.pga, "--pga"}, {&o.freq, "--freq"}, {&o.duration, "--duration"}}) {
      if (value->empty()) throw CLI::RequiredError(name);
    }
  }
  check_g(o.g_m_s2);
  if (o.out.empty() && o.plot.empty()) {
    throw parameter_error("--out",
                          "give the CSV file to write (--out motion.csv), a figure (--plot motion.svg), or both");
  }
  check_plot_path(o.plot);
  if (o.components == 1) check_output_path(o.out);
  if (o.magnitude || o.distance_km) {
    run_synth_stochastic(o);
    return;
  }
  SynthesisSpec spec;
  spec.pga_m_s2 = parse_acceleration_m_s2(o.pga, "--pga", o.g_m_s2);
  spec.predominant_frequency_hz = parse_frequency_hz(o.freq, "--freq");
  spec.duration_s = parse_seconds(o.duration, "--duration");
  spec.dt_s = parse_seconds(o.dt, "--dt");
  spec.seed = parse_seed(o.seed, "--seed");
  spec.model = parse_filter_model(o.model, "--model");
  spec.envelope = parse_envelope_kind(o.envelope, "--envelope");
  spec.ground_damping = o.zeta_g;
  try {
    validate(spec);
  } catch (const InputError& e) {
    // The library names its fields; the user typed options.
    const std::string& field = e.where().field;
    const std::string option = field == "pga" ? "--pga" : field == "freq" ? "--freq" : field == "duration" ? "--duration"
                               : field == "dt" ? "--dt" : field == "ground_damping" ? "--zeta-g" : field;
    throw parameter_error(option, e.problem());
  }
  if (o.components != 1) {
    run_synth_set(o, spec);
    return;
  }
  const GroundMotion motion = synthesize(spec);
  const double f_g = ground_frequency_for_request_hz(spec.predominant_frequency_hz, spec.ground_damping, spec.model);
  if (!o.out.empty()) write_motion_csv(o.out, motion, spec, f_g, o.g_m_s2);
  const double measured = predominant_frequency_hz(motion);
  if (!o.plot.empty()) {
    // The spectrum the predominant frequency is measured on (spectra.hpp): zero padded to the next power of two at
    // least twice the record, Konno-Ohmachi b = 40, 0.1 Hz to min(25 Hz, 0.8 f_Nyquist).
    const FourierSpectrum fas = fourier_amplitude_spectrum(motion, predominant_frequency_fft_length(motion.size()));
    const std::vector<double> centres = predominant_frequency_centres_hz(motion.dt_s());
    const std::vector<double> smooth = konno_ohmachi_smooth(fas, centres, 40.0);
    const std::vector<plot::Mark> marks{
        {spec.predominant_frequency_hz, fmt::format("requested {:.3g} Hz", spec.predominant_frequency_hz), "#e67e22"},
        {measured, fmt::format("measured f_p {:.3g} Hz", measured), "#c0392b"}};
    const std::string title =
        fmt::format("Synthetic motion ({}, {}): PGA {:.3g} g, seed {}", filter_model_name(spec.model),
                    envelope_kind_name(spec.envelope), motion.pga_m_s2() / o.g_m_s2, spec.seed);
    plot::render(plot::motion_spectrum_figure(motion, fas, centres, smooth, marks, o.g_m_s2, title), o.plot);
  }
  if (o.json) {
    nlohmann::ordered_json j;
    j["out"] = o.out.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.out);
    j["plot"] = o.plot.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.plot);
    j["model"] = filter_model_name(spec.model);
    j["envelope"] = envelope_kind_name(spec.envelope);
    j["seed"] = spec.seed;
    j["npts"] = motion.size();
    j["dt_s"] = spec.dt_s;
    j["duration_s"] = motion.duration_s();
    j["pga_g"] = motion.pga_m_s2() / o.g_m_s2;
    j["requested_frequency_hz"] = spec.predominant_frequency_hz;
    j["filter_frequency_hz"] = f_g;
    j["zeta_g"] = spec.ground_damping;
    j["predominant_frequency_hz"] = measured;
    j["g_m_s2"] = o.g_m_s2;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  if (!o.out.empty()) fmt::print("wrote {}: ", o.out);
  fmt::print("{} samples, dt {} s, {} / {} motion, seed {}\n", motion.size(), spec.dt_s,
             filter_model_name(spec.model), envelope_kind_name(spec.envelope), spec.seed);
  fmt::print("PGA {:.5g} g; predominant frequency requested {:.4g} Hz (filter f_g {:.4g} Hz), measured {:.4g} Hz\n",
             motion.pga_m_s2() / o.g_m_s2, spec.predominant_frequency_hz, f_g, measured);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

}  // namespace

void add_synth_command(CLI::App& app) {
  auto o = std::make_shared<SynthOptions>();
  CLI::App* cmd = app.add_subcommand("synth", "Synthetic ground motion: Kanai-Tajimi / Clough-Penzien filtered white "
                                              "noise under a time envelope, reproducible from its seed");
  // --pga, --freq and --duration are required unless --magnitude and --distance-km choose the stochastic method
  // (checked in run_synth, with CLI11's RequiredError as before).
  cmd->add_option("--pga", o->pga, "Peak ground acceleration, with a unit (0.3g, 3m/s2); required (with "
                                   "--magnitude: optional, scales the motion to it)");
  cmd->add_option("--freq", o->freq, "Predominant frequency of the motion as topple measures it, e.g. 3Hz (required "
                                     "without --magnitude)");
  cmd->add_option("--duration", o->duration, "Record length, s (a bare number) or with a unit, e.g. 20s (required "
                                             "without --magnitude)");
  cmd->add_option("--magnitude", o->magnitude, "Moment magnitude (2-9): a motion of Boore's (2003) stochastic "
                                               "point-source method instead of filtered noise (with --distance-km)");
  cmd->add_option("--distance-km", o->distance_km, "With --magnitude: the hypocentral distance, km (1-1000)");
  cmd->add_option("--dt", o->dt, "Sample interval")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed (any 64-bit integer): same parameters and seed, same motion")
      ->capture_default_str();
  cmd->add_option("--model", o->model, "Filter: kanai-tajimi or clough-penzien")->capture_default_str();
  cmd->add_option("--envelope", o->envelope, "Time envelope: saragoni-hart or jennings")->capture_default_str();
  cmd->add_option("--zeta-g", o->zeta_g, "Kanai-Tajimi ground damping, 0.1-0.5")->capture_default_str();
  cmd->add_option("--g", o->g_m_s2, "Gravitational acceleration, m/s2 (for values in g)")->capture_default_str();
  cmd->add_option("--out", o->out, "CSV file to write (time_s,accel_g); --out, --plot or both");
  cmd->add_option("--plot", o->plot, "Draw the motion and its smoothed Fourier spectrum with the requested and "
                                     "measured predominant frequency to this .svg or .png file (gnuplot)");
  cmd->add_flag("--json", o->json, "Print a JSON summary instead of text");
  cmd->add_option("--components", o->components, "1 (one motion), 2 (two horizontal components; --pga is their "
                                                 "RotD50 PGA) or 3 (and a vertical); one CSV per component: "
                                                 "OUT.h1.csv, OUT.h2.csv, OUT.v.csv")
      ->capture_default_str();
  cmd->add_option("--coherence", o->coherence, "With --components 2 or 3: correlation coefficient of the two "
                                               "horizontal components' white noises, -1..1 (0: independent)")
      ->capture_default_str();
  cmd->add_option("--azimuths", o->azimuths, "With --components 2 or 3: the components' azimuths A1,A2, degrees "
                                             "clockwise from north (written in the files)")
      ->capture_default_str();
  cmd->add_option("--vh-ratio", o->vh_ratio, "With --components 3: the vertical's PGA over the pair's RotD50 PGA")
      ->capture_default_str();
  cmd->add_option("--vh-freq-ratio", o->vh_freq_ratio, "With --components 3: the vertical's predominant frequency "
                                                       "over the horizontal's, 0.5-4")
      ->capture_default_str();
  add_quiet_flag(*cmd, o->quiet);  // one motion is quick: no bar
  cmd->callback([o] { run_synth(*o); });
}

}  // namespace topple::cli
