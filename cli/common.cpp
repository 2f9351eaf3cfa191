#include "common.hpp"

#include <fmt/format.h>

#include <charconv>

#include "topple/error.hpp"
#include "topple/pulses.hpp"
#include "topple/units.hpp"

namespace topple::cli {

void add_motion_options(CLI::App& cmd, MotionOptions& o) {
  cmd.add_option("--format", o.format, "Record format: auto (detect from content), peer-at2, cosmos-v2, csmip-v2, "
                                       "knet, usgs-smc, esm, plain")
      ->capture_default_str();
  cmd.add_option("--channel", o.channel, "Channel of a multi-channel file (CSMIP V2), 1-based");
  cmd.add_option("--units", o.units, "Unit of the values of a plain file: g, m/s2, cm/s2, gal");
  cmd.add_option("--dt", o.dt_s, "Time step of a one-column plain file, s");
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
  return r;
}

GroundMotion transform_motion(GroundMotion motion, const MotionOptions& o) {
  if (!o.scale_pga.empty() && o.scale) throw parameter_error("--scale-pga", "give either --scale-pga or --scale");
  if (!o.scale_pga.empty()) motion = motion.scaled_to_pga(parse_acceleration_m_s2(o.scale_pga, "--scale-pga", o.g_m_s2));
  if (o.scale) motion = motion.scaled(*o.scale);
  if (o.invert) motion = motion.inverted();
  return motion;
}

GroundMotion load_motion(const MotionOptions& o) {
  if (!(o.g_m_s2 > 0.0) || !std::isfinite(o.g_m_s2)) {
    throw parameter_error("--g", fmt::format("g must be positive and finite, got {}", o.g_m_s2));
  }
  return transform_motion(io::read_motion(o.file, read_options(o)), o);
}

void add_pulse_options(CLI::App& cmd, PulseOptions& o) {
  cmd.add_option("--pulse", o.kind, "Use an analytic pulse instead of a file: rect, tri, double-tri, sine, cosine, "
                                    "ricker");
  cmd.add_option("--amp-g", o.amp_g, "Pulse amplitude, in g");
  cmd.add_option("--duration", o.duration, "Pulse duration (rect/tri width, sine/cosine period, Ricker 1/f_peak), "
                                           "s (a bare number) or with a unit, e.g. 100ms");
  cmd.add_option("--tail", o.tail, "Still ground after the pulse, s (default: 5 pulse durations)");
  cmd.add_option("--pulse-dt", o.dt, "Sampling step of smooth pulses, s (default: duration/2000)");
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

GroundMotion make_pulse_motion(const PulseOptions& o, double g_m_s2) {
  if (!o.amp_g) throw parameter_error("--amp-g", "a pulse needs its amplitude (--amp-g, in g)");
  if (o.duration.empty()) throw parameter_error("--duration", "a pulse needs its duration (--duration)");
  PulseSpec spec;
  spec.kind = parse_pulse_kind(o.kind, "--pulse");
  spec.amplitude_m_s2 = *o.amp_g * g_m_s2;
  spec.duration_s = parse_seconds(o.duration, "--duration");
  spec.tail_s = o.tail.empty() ? 5.0 * spec.duration_s : parse_seconds(o.tail, "--tail");
  spec.dt_s = o.dt.empty() ? 0.0 : parse_seconds(o.dt, "--pulse-dt");
  if (spec.dt_s < 0.0) throw parameter_error("--pulse-dt", "must be positive");
  return make_pulse(spec);
}

std::string format_seconds_or_none(const std::optional<double>& t) {
  return t ? fmt::format("{:.6f} s", *t) : std::string("none");
}

}  // namespace topple::cli
