#pragma once
// Writers: solver results to the files and JSON objects users and scripts read. Column and key names carry units;
// the JSON keys are a stable interface shared by the CLI and the Python package.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "topple/ground_motion.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"

namespace topple::io {

/// Summary of a sliding run as JSON (keys: max_abs_displacement_m, residual_displacement_m, slip_episodes,
/// first_slip_time_s (null when none), ...). Never emits NaN: absent values are null.
[[nodiscard]] nlohmann::ordered_json sliding_summary_json(const SlidingSummary& summary, const SlidingBlock& block);

/// Summary of a rocking run as JSON, as `topple rock --json` prints it less its "input" object (keys:
/// max_abs_rotation_rad, max_rotation_over_alpha, overturned, overturn_time_s (null when none), ..., body {shape,
/// dimensions in m, a_m, h_m, D_m2}, solver {method, rel_tol, ...}). Never emits NaN: absent values are null.
[[nodiscard]] nlohmann::ordered_json rocking_summary_json(const RockingSummary& summary, const RockingBody& body,
                                                          const RockingOptions& options);

/// History as CSV: time_s,ground_accel_m_s2,displacement_m,velocity_m_s,state (state: -1 slipping up-slope /
/// negative, 0 stuck, 1 slipping down-slope / positive). Throws InputError when the file cannot be written.
void write_sliding_history_csv(const std::filesystem::path& path, const SlidingHistory& history,
                               const GroundMotion& horizontal);

}  // namespace topple::io
