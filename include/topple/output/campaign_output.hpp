#pragma once
// The outputs of `topple campaign` (docs/campaign.md): one CSV row per test and model, and the JSON summary per
// model (confusion, metrics, azimuth error, speed, the target), with "blind": true (the outcomes observed were read
// only to score).
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "topple/ensemble/campaign.hpp"

namespace topple::io {

/// Columns: id, model, predicted (overturned | standing), observed, max_tilt_over_limit, overturn_time_s,
/// overturn_azimuth_deg, observed_azimuth_deg, cpu_s, duration_s (empty cells: none). Written to a temporary name
/// and renamed (core/output_file.hpp); OutputError otherwise.
void write_campaign_csv(const std::filesystem::path& path, const std::vector<ensemble::CampaignRow>& rows);

/// {"campaign": name, "file": the campaign file, "blind": true, "tests": n, "frame": ..., "target": {...},
///  "models": [{"model", "tp", "fp", "tn", "fn", "accuracy", "recall", "precision", "f1" (null when undefined),
///  "azimuths_compared", "median_azimuth_error_deg", "cpu_s", "simulated_s", "times_real_time",
///  "meets_target": {"accuracy", "recall", "speed", "all"}}], "warnings": [...]}.
[[nodiscard]] nlohmann::ordered_json campaign_summary_json(const ensemble::CampaignSettings& settings,
                                                           const std::string& file, std::size_t tests,
                                                           const std::vector<ensemble::CampaignRow>& rows);

}  // namespace topple::io
