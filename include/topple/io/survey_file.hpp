#pragma once
// Survey files (TOML, or CSV from a spreadsheet): documented, with examples, in examples/survey.toml,
// examples/survey.csv and docs/survey.md.
//
// CSV (docs/survey.md, "CSV surveys"): `site.KEY,value` / `inversion.KEY,value` / `event.KEY,value` rows, then a
// header row of object keys (a length column may carry its unit: width_cm), then one object per row. It is read as
// the TOML survey it stands for, so every rule below applies; errors name the CSV's line and column. A name ending in
// .csv is CSV, .toml is TOML, anything else is told by content.
//
// Shape (one site):
//   [site]            name, lat, lon, notes
//   [inversion]       family, records, pga_g = [min, max, count], freq_hz = [min, max, count], motions_per_cell,
//                     seed, duration_s, g_m_s2
//   [[object]]        id, description, shape (block | cylinder | general), width/height | diameter/height | a/h/D
//                     | b1/b2/h/inertia (asymmetric general; strings with units) | mesh + mesh_azimuth_deg
//                     [+ mesh_unit, mesh_density_kg_m3] (a body from a 3-D scan, the path relative to the file), mu (value or [low, high]), e ("housner", value or range), support,
//                     amplification (value or range), orientation_deg, outcome, model (slide | rock | coupled;
//                     docs/survey.md "Objects that slide and rock"), slid / slid_uncertainty /
//                     slid_at_least (lengths with units), evidence (certain | likely | reported)
// Several sites: [[sites]] tables, each with name/lat/lon and its own [[sites.object]] list; optional [event] with
// epicentre = [lat, lon].
#include <filesystem>
#include <string_view>

#include "topple/survey/survey.hpp"

namespace topple::io {

/// Reads and validates a survey, and loads its records (load_survey_records). Throws InputError naming the file, the
/// object (by id or index) and the field for unknown keys, unknown shapes or outcomes, missing dimensions, missing
/// units, non-positive sizes, bad ranges, a frequency axis the motion family cannot make; and for a directory.
[[nodiscard]] Survey read_survey(const std::filesystem::path& path);

/// Same from text, TOML or CSV (told by `name`'s extension, else by content; name used in messages; relative record
/// and mesh paths resolve against `base_dir`). Reads no record: the records of a records family are only checked
/// to exist (load_survey_records loads them). It does read the meshes objects name (`mesh = "..."`, through
/// io::read_mesh_body, bounded by kMaxMeshFileBytes), since the body is needed to check the object.
[[nodiscard]] Survey parse_survey(std::string_view text, const std::string& name,
                                  const std::filesystem::path& base_dir = {});

/// Loads the records named by survey.inversion.records into survey.inversion.record_motions (the inversion core reads
/// no file; read_survey calls this). Throws InputError naming the record file that does not read.
void load_survey_records(Survey& survey);

}  // namespace topple::io
