#pragma once
// Survey files (TOML): documented, with a commented example, in examples/survey.toml and docs/survey.md.
//
// Shape (one site):
//   [site]            name, lat, lon, notes
//   [inversion]       family, records, pga_g = [min, max, count], freq_hz = [min, max, count], motions_per_cell,
//                     seed, duration_s, g_m_s2
//   [[object]]        id, description, shape (block | cylinder | general), width/height | diameter/height | a/h/D
//                     (strings with units), mu (value or [low, high]), e ("housner", value or range), support,
//                     amplification (value or range), orientation_deg, outcome, slid / slid_uncertainty /
//                     slid_at_least (lengths with units), evidence (certain | likely | reported)
// Several sites: [[sites]] tables, each with name/lat/lon and its own [[sites.object]] list; optional [event] with
// epicentre = [lat, lon].
#include <filesystem>
#include <string_view>

#include "topple/survey.hpp"

namespace topple::io {

/// Reads and validates a survey. Throws InputError naming the file, the object (by id or index) and the field for
/// unknown keys, unknown shapes or outcomes, missing dimensions, missing units, non-positive sizes, bad ranges.
[[nodiscard]] Survey read_survey(const std::filesystem::path& path);

/// Same from text (name used in messages; relative record paths resolve against `base_dir`).
[[nodiscard]] Survey parse_survey(std::string_view text, const std::string& name,
                                  const std::filesystem::path& base_dir = {});

}  // namespace topple::io
