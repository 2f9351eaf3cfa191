#pragma once
// Shared pieces of the `topple` command line: how a motion is named and loaded, unit-bearing option values, and
// printing. No physics here.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "topple/ground_motion.hpp"
#include "topple/io/read.hpp"

namespace topple::cli {

/// Options every command that reads a ground motion shares: the file and how to read and transform it.
struct MotionOptions {
  std::string file;
  std::string format = "auto";
  std::optional<int> channel;
  std::string units;             // plain files: unit of the values
  std::optional<double> dt_s;    // plain one-column files
  std::string scale_pga;         // "0.5g": scale to this PGA
  std::optional<double> scale;   // plain factor
  bool invert = false;
  double g_m_s2 = 9.80665;
};

/// Adds --format, --channel, --units, --dt, --scale-pga, --scale, --invert, --g to `cmd` (the file positional is
/// added by each command, since some take pulses instead).
void add_motion_options(CLI::App& cmd, MotionOptions& options);

/// Reads and transforms the motion as the options say. Throws InputError.
[[nodiscard]] GroundMotion load_motion(const MotionOptions& options);

/// The io::ReadOptions the CLI options imply.
[[nodiscard]] io::ReadOptions read_options(const MotionOptions& options);

/// Applies --scale-pga / --scale / --invert to a motion.
[[nodiscard]] GroundMotion transform_motion(GroundMotion motion, const MotionOptions& options);

/// JSON-friendly number: NaN/Inf never reach output (callers pass optionals for "none").
[[nodiscard]] std::string format_seconds_or_none(const std::optional<double>& t);

}  // namespace topple::cli
