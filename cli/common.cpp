#include "common.hpp"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "topple/output/plot.hpp"
#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {

void add_record_layout_options(CLI::App& cmd, MotionOptions& o) {
  cmd.add_option("--columns", o.columns, "Plain files: the time and acceleration columns TIME,ACCEL, each a number "
                                         "from 1 or a header name (e.g. 1,2 or \"Time (s)\",\"Table Acc (g)\"); "
                                         ",ACCEL or accel=ACCEL for no time column (then --dt); other columns "
                                         "are ignored");
  cmd.add_option("--separator", o.separator, "Plain files: field separator: auto (header and data each judged from "
                                             "their first line: tab, else semicolon, else comma, else blanks), "
                                             "whitespace, tab, comma, semicolon")
      ->capture_default_str();
  cmd.add_option("--baseline", o.baseline, "Offset removal of the record as read: none, mean (the record's mean), "
                                           "pre-event:T (mean of the first T seconds), poly:N (least-squares "
                                           "polynomial of degree N = 0..3)")
      ->capture_default_str();
}

void add_motion_options(CLI::App& cmd, MotionOptions& o) {
  cmd.add_option("--format", o.format, "Record format: auto (detect from content), peer-at2, cosmos-v2, csmip-v2, "
                                       "knet, usgs-smc, esm, plain")
      ->capture_default_str();
  cmd.add_option("--channel", o.channel, "Channel of a multi-channel file (CSMIP V2), 1-based");
  cmd.add_option("--units", o.units, "Unit of the values (g, m/s2, cm/s2, gal) of a plain file that does not name it; "
                                     "for a file that states its unit, it must agree");
  cmd.add_option("--dt", o.dt_s, "Time step of a one-column plain file, s; for a file that states its dt, it must "
                                 "agree");
  add_record_layout_options(cmd, o);
  cmd.add_option("--scale-pga", o.scale_pga, "Scale the record to this PGA, with a unit (e.g. 0.5g, 3m/s2)");
  cmd.add_option("--scale", o.scale, "Multiply the record by this factor");
  cmd.add_flag("--invert", o.invert, "Flip the polarity of the record");
  cmd.add_option("--g", o.g_m_s2, "Gravitational acceleration, m/s2")->capture_default_str();
}

io::ReadOptions read_options(const MotionOptions& o) {
  io::ReadOptions r;
  r.format = io::parse_format_name(o.format);
  r.channel = o.channel;
  r.units = o.units;
  r.dt_s = o.dt_s;
  r.g_m_s2 = o.g_m_s2;
  if (!o.columns.empty()) r.columns = io::parse_columns(o.columns, "--columns");
  r.separator = io::parse_separator(o.separator, "--separator");
  r.baseline = parse_baseline(o.baseline, "--baseline");
  return r;
}

GroundMotion transform_motion(GroundMotion motion, const MotionOptions& o) {
  if (!o.scale_pga.empty() && o.scale) throw parameter_error("--scale-pga", "give either --scale-pga or --scale");
  // The library names its parameter ("scale", "pga"); the user typed an option, about this file.
  const auto naming = [&](const char* option, const auto& f) {
    try {
      return f();
    } catch (const InputError& e) {
      if (!e.where().file.empty()) throw;
      throw InputError(InputLocation{.file = o.file, .line = {}, .field = option}, e.problem());
    }
  };
  // A record the user scales stays a record: at most 100 g (README "Limits"), checked before scaling.
  if (!o.scale_pga.empty()) {
    const double pga = parse_acceleration_m_s2(o.scale_pga, "--scale-pga", o.g_m_s2);
    motion = naming("--scale-pga", [&] {
      require_record_acceleration(pga, "--scale-pga");
      return motion.scaled_to_pga(pga);
    });
  }
  if (o.scale) {
    motion = naming("--scale", [&] {
      require_record_acceleration(std::abs(*o.scale) * motion.pga_m_s2(), "--scale");
      return motion.scaled(*o.scale);
    });
  }
  if (o.invert) motion = motion.inverted();
  return motion;
}

void check_g(double g_m_s2) {
  if (!(g_m_s2 > 0.0) || !std::isfinite(g_m_s2)) {
    throw parameter_error("--g", fmt::format("g must be positive and finite, got {}", g_m_s2));
  }
}

GroundMotion load_motion(const MotionOptions& o) {
  check_g(o.g_m_s2);
  return transform_motion(io::read_motion(o.file, read_options(o)), o);
}

RunMotion load_run_motion(const MotionOptions& motion, const PulseOptions& pulse, const std::string& vertical_path) {
  check_g(motion.g_m_s2);
  const bool from_pulse = !pulse.kind.empty();
  if (from_pulse == !motion.file.empty()) throw parameter_error("FILE", "give either a record file or --pulse");
  const GroundMotion raw =
      from_pulse ? make_pulse_motion(pulse, motion.g_m_s2) : io::read_motion(motion.file, read_options(motion));
  RunMotion run{transform_motion(raw, motion), std::nullopt, {}, {}};
  run.input.motion = from_pulse ? run.horizontal.metadata().event : motion.file;
  run.input.scale_factor = amplitude_factor(raw, run.horizontal);
  run.input.inverted = motion.invert;
  run.title = from_pulse ? run.input.motion : plot::file_label(motion.file);
  if (!motion.scale_pga.empty()) run.title += " scaled to PGA " + motion.scale_pga;
  if (motion.scale) run.title += fmt::format(" x {:g}", *motion.scale);
  if (motion.invert) run.title += ", inverted";
  if (!vertical_path.empty()) {
    run.vertical = io::read_motion(vertical_path, read_options(motion)).scaled(run.input.scale_factor);
    run.input.vertical = vertical_path;
  }
  return run;
}

void add_pulse_options(CLI::App& cmd, PulseOptions& o) {
  cmd.add_option("--pulse", o.kind, "Use an analytic pulse instead of a file: rect, tri, double-tri, sine, cosine, "
                                    "ricker, tri-train, trap-train (thesis Figs 3.5, 3.6; --cycles), mp "
                                    "(Mavroeidis-Papageorgiou near-fault pulse; --vel-amp, --gamma, --nu-deg)");
  cmd.add_option("--amp-g", o.amp_g, "Pulse amplitude, in g (all pulses but mp)");
  cmd.add_option("--duration", o.duration, "Pulse duration (rect/tri width, sine/cosine/train period, Ricker "
                                           "1/f_peak, mp 1/f_p), s (a bare number) or with a unit, e.g. 100ms");
  cmd.add_option("--tail", o.tail, "Still ground after the pulse, s (default: 5 pulse durations)");
  cmd.add_option("--pulse-dt", o.dt, "Sampling step of smooth pulses, s (default: duration/2000)");
  cmd.add_option("--cycles", o.cycles, "tri-train, trap-train: number of full cycles (default 1)");
  cmd.add_option("--ramp-fraction", o.ramp_fraction, "trap-train: rise (and fall) time as a fraction of the half "
                                                     "period, in (0, 0.5] (default 1/3; 0.5 is the tri-train)");
  cmd.add_option("--vel-amp", o.vel_amp_m_s, "mp: velocity amplitude A, m/s (scale to a PGA with --scale-pga)");
  cmd.add_option("--gamma", o.gamma, "mp: oscillatory character gamma > 1, half cycles under the envelope "
                                     "(default 2)");
  cmd.add_option("--nu-deg", o.nu_deg, "mp: phase nu, degrees (default 0: symmetric velocity pulse)");
}

double parse_seconds(const std::string& text, const std::string& option) {
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec == std::errc{} && ptr == text.data() + text.size()) {
    if (!std::isfinite(value)) throw parameter_error(option, fmt::format("'{}' is not finite", text));
    return value;
  }
  return parse_duration_s(text, option);
}

namespace {

/// The library names its fields; the user typed options.
template <class F>
GroundMotion naming_pulse_options(F f) {
  try {
    return f();
  } catch (const InputError& e) {
    static const std::pair<const char*, const char*> names[] = {
        {"amplitude", "--amp-g"},     {"duration", "--duration"},   {"tail", "--tail"},
        {"dt", "--pulse-dt"},         {"cycles", "--cycles"},       {"trapezoid_ramp_fraction", "--ramp-fraction"},
        {"velocity_amplitude_m_s", "--vel-amp"}, {"frequency_hz", "--duration"}, {"phase_rad", "--nu-deg"},
        {"gamma", "--gamma"}};
    for (const auto& [field, option] : names) {
      if (e.where().field == field && e.where().file.empty()) throw parameter_error(option, e.problem());
    }
    throw;
  }
}

}  // namespace

GroundMotion make_pulse_motion(const PulseOptions& o, double g_m_s2) {
  if (o.duration.empty()) throw parameter_error("--duration", "a pulse needs its duration (--duration)");
  const double duration = parse_seconds(o.duration, "--duration");
  const double tail = o.tail.empty() ? 5.0 * duration : parse_seconds(o.tail, "--tail");
  // 0 is the library's "default step" (duration / 2000): a user who types 0 gets an error, not the default.
  const double dt = o.dt.empty() ? 0.0 : parse_seconds(o.dt, "--pulse-dt");
  if (!o.dt.empty() && !(dt > 0.0)) throw parameter_error("--pulse-dt", fmt::format("must be positive, got {} s", dt));
  const bool mp = o.kind == "mp" || o.kind == "mavroeidis-papageorgiou";
  const PulseKind kind = [&] {
    if (mp) return PulseKind::sine;  // unused
    try {
      return parse_pulse_kind(o.kind, "--pulse");
    } catch (const InputError&) {
      throw parameter_error("--pulse", fmt::format("unknown pulse '{}' (known: rect, tri, double-tri, sine, cosine, "
                                                   "ricker, tri-train, trap-train, mp)", o.kind));
    }
  }();
  const bool train = !mp && (kind == PulseKind::triangular_train || kind == PulseKind::trapezoidal_train);
  const auto refuse = [&](bool given, const char* option, const char* applies_to) {
    if (given) throw parameter_error(option, fmt::format("{} applies to --pulse {} only", option, applies_to));
  };
  refuse(o.cycles.has_value() && !train, "--cycles", "tri-train and trap-train");
  refuse(o.ramp_fraction.has_value() && (mp || kind != PulseKind::trapezoidal_train), "--ramp-fraction", "trap-train");
  refuse(o.vel_amp_m_s.has_value() && !mp, "--vel-amp", "mp (the others take --amp-g)");
  refuse(o.gamma.has_value() && !mp, "--gamma", "mp");
  refuse(o.nu_deg.has_value() && !mp, "--nu-deg", "mp");
  if (mp) {
    if (o.amp_g) {
      throw parameter_error("--amp-g", "the mp pulse is given by its velocity amplitude (--vel-amp, m/s); scale it "
                                       "to a PGA with --scale-pga");
    }
    if (!o.vel_amp_m_s) {
      throw parameter_error("--vel-amp", "the mp pulse needs its velocity amplitude (--vel-amp, m/s)");
    }
    if (!(duration > 0.0)) throw parameter_error("--duration", fmt::format("must be positive, got {} s", duration));
    MavroeidisPapageorgiouPulse pulse;
    pulse.velocity_amplitude_m_s = *o.vel_amp_m_s;
    pulse.frequency_hz = 1.0 / duration;
    pulse.gamma = o.gamma.value_or(2.0);
    pulse.phase_rad = deg_to_rad(o.nu_deg.value_or(0.0));
    return naming_pulse_options([&] { return make_mavroeidis_papageorgiou_pulse(pulse, dt, tail); });
  }
  if (!o.amp_g) throw parameter_error("--amp-g", "a pulse needs its amplitude (--amp-g, in g)");
  PulseSpec spec;
  spec.kind = kind;
  spec.amplitude_m_s2 = *o.amp_g * g_m_s2;
  spec.duration_s = duration;
  spec.tail_s = tail;
  spec.dt_s = dt;
  if (o.cycles) spec.cycles = *o.cycles;
  if (o.ramp_fraction) spec.trapezoid_ramp_fraction = *o.ramp_fraction;
  return naming_pulse_options([&] { return make_pulse(spec); });
}

void check_output_path(const std::string& path) {
  if (path.empty()) return;
  // Opening (and dropping) the temporary file the result will go through: an unwritable place fails now, with its
  // path and exit status 4, and not after the computation.
  const io::OutputFile probe{std::filesystem::path(path)};
}

void check_plot_path(const std::string& path) {
  if (path.empty()) return;
  const auto dot = path.rfind('.');
  const std::string ext = dot == std::string::npos ? std::string() : path.substr(dot);
  if (ext != ".svg" && ext != ".png") {
    throw parameter_error("--plot", fmt::format("'{}': figures are written as .svg or .png", path));
  }
  check_output_path(path);
}

void require_finite(std::initializer_list<std::pair<std::string_view, double>> values) {
  for (const auto& [name, value] : values) {
    if (!std::isfinite(value)) {
      throw std::logic_error(fmt::format("{} came out as {} from finite input within the limits of a ground motion",
                                         name, value));
    }
  }
}

std::string format_seconds_or_none(const std::optional<double>& t) {
  return t ? fmt::format("{:.6f} s", *t) : std::string("none");
}

}  // namespace topple::cli
