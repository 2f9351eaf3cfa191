#pragma once
// The JSON of a flexible-support run (`topple slide --support-freq|--height --json`, Python's slide_flexible): the
// rigid block's summary fields (sliding_summary_json) plus a "support" object, one table for every front end.
#include <filesystem>

#include <nlohmann/json.hpp>

#include "topple/solvers/flexible.hpp"

namespace topple::io {

/// sliding_summary_json(summary.sliding, block) with "support": {analysis, kind "oscillator", freq_hz, damping_ratio,
/// mass_ratio, mode_freq_hz, mode_damping_ratio, kmax}.
[[nodiscard]] nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                                           const SupportOscillator& support, FlexibleAnalysis analysis);

/// The same for SLAMMER's sliding mass: "support": {analysis, kind "sliding_mass", height_m, vs_slope_m_s, vs_base_m_s,
/// damping_ratio, reference_strain (null when linear), vs_final_m_s, equivalent_linear_iterations, mode_freq_hz,
/// mode_damping_ratio, kmax}; `block` is the rigid block with mu = k_y that the summary's yield fields describe.
[[nodiscard]] nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                                           const SlidingMassColumn& column, FlexibleAnalysis analysis);

/// The history of a flexible-support run as CSV (`topple slide --support-freq|--height --out`):
/// time_s,ground_accel_m_s2,support_accel_m_s2,displacement_m,velocity_m_s,state -- displacement and velocity of the
/// body relative to the surface it slides on, state -1/0/1 as the rigid history (sliding.hpp SlipState). Written
/// through OutputFile (temporary name + rename).
void write_flexible_history_csv(const std::filesystem::path& path, const FlexibleHistory& history,
                                const GroundMotion& ground);

}  // namespace topple::io
