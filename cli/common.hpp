#pragma once
// Shared pieces of the `topple` command line: how a motion is named and loaded, unit-bearing option values, and
// printing. No physics here.
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>

#include <CLI/CLI.hpp>

#include "topple/motion/ground_motion.hpp"
#include "topple/io/read.hpp"
#include "topple/output/write.hpp"

namespace topple::cli {

/// Options every command that reads a ground motion shares: the file and how to read and transform it.
struct MotionOptions {
  std::string file;
  std::string format = "auto";
  std::optional<int> channel;
  std::string units;             // plain files: unit of the values
  std::optional<double> dt_s;    // plain one-column files
  std::string columns;           // plain files: "TIME,ACCEL" (io::parse_columns); empty: one or two columns
  std::string separator = "auto";  // plain files: auto, whitespace, tab, comma, semicolon
  std::string baseline = "none";   // offset removal: none, mean, pre-event:T, poly:N (motion/baseline.hpp)
  std::string scale_pga;         // "0.5g": scale to this PGA
  std::optional<double> scale;   // plain factor
  bool invert = false;
  double g_m_s2 = 9.80665;
};

/// Adds --format, --channel, --units, --dt, --columns, --separator, --baseline, --scale-pga, --scale, --invert, --g
/// to `cmd` (the file positional is
/// added by each command, since some take pulses instead).
void add_motion_options(CLI::App& cmd, MotionOptions& options);

/// Adds --columns, --separator, --baseline (how a plain record is laid out, and its offset removal): part of
/// add_motion_options, for a command that adds its own read options (fragility).
void add_record_layout_options(CLI::App& cmd, MotionOptions& options);

/// Reads and transforms the motion as the options say. Throws InputError.
[[nodiscard]] GroundMotion load_motion(const MotionOptions& options);

/// The io::ReadOptions the CLI options imply.
[[nodiscard]] io::ReadOptions read_options(const MotionOptions& options);

/// Applies --scale-pga / --scale / --invert to a motion.
[[nodiscard]] GroundMotion transform_motion(GroundMotion motion, const MotionOptions& options);

/// An analytic pulse instead of a record file (--pulse KIND --amp-g A --duration T [--tail T] [--pulse-dt T]; trains
/// take --cycles N [--ramp-fraction r]; the Mavroeidis-Papageorgiou pulse --vel-amp A --duration 1/f_p [--gamma]
/// [--nu-deg] instead of --amp-g).
struct PulseOptions {
  std::string kind;            // empty: no pulse
  std::optional<double> amp_g;
  std::string duration = "";   // "0.1" (s) or with a unit ("100ms")
  std::string tail = "";       // still ground after the pulse; default: 5 pulse durations
  std::string dt = "";         // sampling of smooth pulses; default duration/2000
  std::optional<int> cycles;             // tri-train, trap-train: number of cycles (default 1)
  std::optional<double> ramp_fraction;   // trap-train: ramp length / half period, (0, 0.5] (default 1/3)
  std::optional<double> vel_amp_m_s;     // mp: velocity amplitude A, m/s
  std::optional<double> gamma;           // mp: oscillatory character, > 1 (default 2)
  std::optional<double> nu_deg;          // mp: phase, degrees (default 0)
};

/// Adds --pulse, --amp-g, --duration, --tail, --pulse-dt, --cycles, --ramp-fraction, --vel-amp, --gamma, --nu-deg.
void add_pulse_options(CLI::App& cmd, PulseOptions& options);

/// The pulse as a motion (g from `g_m_s2`). Throws InputError naming the option.
[[nodiscard]] GroundMotion make_pulse_motion(const PulseOptions& options, double g_m_s2);

/// The motion of a single-run command (slide, rock, spectrum): a record file or --pulse, transformed by the motion
/// options, with its vertical component (scaled by the horizontal's amplitude_factor) and what the JSON "input"
/// object reports. Throws InputError naming the option.
struct RunMotion {
  GroundMotion horizontal;
  std::optional<GroundMotion> vertical;
  io::RunInput input;
  /// How figure titles name the motion: the record's file name (no directories) or the pulse, and its scaling
  /// ("ELC180.AT2 scaled to PGA 0.4g", "x 2", "inverted").
  std::string title;
  [[nodiscard]] const GroundMotion* vertical_ptr() const noexcept { return vertical ? &*vertical : nullptr; }
};
[[nodiscard]] RunMotion load_run_motion(const MotionOptions& motion, const PulseOptions& pulse,
                                        const std::string& vertical_path = {});

/// Checks --g (positive and finite) before any work; InputError naming --g.
void check_g(double g_m_s2);

/// A duration option: a bare number is seconds, or a value with a unit ("100ms").
[[nodiscard]] double parse_seconds(const std::string& text, const std::string& option);

/// Checks a --plot file name before any work is done: .svg or .png, else InputError naming --plot (exit 2); then
/// as check_output_path.
void check_plot_path(const std::string& path);

/// Checks before any work that a result file can be created where `path` says (empty: none asked): OutputError
/// naming the path (exit 4) otherwise. Nothing is left behind.
void check_output_path(const std::string& path);
/// Every number a command prints must be finite. Within GroundMotionLimits all derived quantities are (README
/// "Limits"), so a non-finite one is a bug: it is reported as an internal error (exit 1) naming the quantity, never
/// printed. Call before printing anything.
void require_finite(std::initializer_list<std::pair<std::string_view, double>> values);

/// JSON-friendly number: NaN/Inf never reach output (callers pass optionals for "none").
[[nodiscard]] std::string format_seconds_or_none(const std::optional<double>& t);

}  // namespace topple::cli
