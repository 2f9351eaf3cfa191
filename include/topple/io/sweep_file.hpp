#pragma once
// Sweep files: a TOML description of an ensemble (motions x objects x parameters), read into an ensemble::SweepSpec (topple/ensemble/sweep.hpp).
// docs/sweeps.md describes every key; examples/sweep/ holds commented examples.
//
// Validation happens here, before any run: unknown keys, wrong types, empty lists or ranges, dimensional values
// without a unit, globs that match nothing, missing or unreadable records, parameter combinations the models refuse
// (kinetic friction above static, a slope steeper than the friction angle allows, a body too squat for Housner's
// restitution) all throw InputError naming the sweep file, the line and the key (e.g. "object[2].width"); object
// and pulse tables are numbered from 1 in the order they appear. Every record is read here, once.
//
// Values. Every parameter key takes one value, a list, or a range table:
//   mu = 0.2          mu = [0.05, 0.1, 0.2]          mu = { from = 0.05, to = 0.5, count = 10 }
//   mu = { from = 0.05, to = 0.5, step = 0.05 }      mu = { from = 0.01, to = 1, count = 9, spacing = "log" }
// A dimensional key has two spellings: with its unit in the name it takes numbers in that unit (width_m = 0.04,
// slope_deg = 10, amp_g = 0.3, freq_hz = 2), without it takes strings with a unit (width = "4cm", slope = "10deg",
// amp = "3m/s2", freq = "2Hz"); a bare number there is refused.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "topple/ensemble/sweep.hpp"

namespace topple::io {

struct SweepFile {
  std::filesystem::path path;       ///< the sweep file as given
  ensemble::SweepSpec spec;         ///< motions (records read) and objects, expanded
  std::filesystem::path output_csv; ///< [output] path, relative to the sweep file's directory (default: the sweep
                                    ///< file's name with .csv)
  bool jsonl = false;               ///< [output] jsonl
  /// What the reader accepted but the user should see: an azimuth given in a [[motions.set]] that overrides a
  /// record header's (resolve_azimuths).
  std::vector<std::string> warnings;
};

/// Reads, validates and expands a sweep file, reading every record it names. Throws InputError.
[[nodiscard]] SweepFile read_sweep_file(const std::filesystem::path& path);

/// Same on text in memory; `path` names it in messages and its directory anchors relative globs and the output.
[[nodiscard]] SweepFile parse_sweep_file(std::string_view text, const std::filesystem::path& path);

/// Where the JSON lines go for a CSV output: the same name with the extension .jsonl ("out/r.csv" -> "out/r.jsonl").
[[nodiscard]] std::filesystem::path jsonl_path_for(const std::filesystem::path& csv_path);

}  // namespace topple::io
