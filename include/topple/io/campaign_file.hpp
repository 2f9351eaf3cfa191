#pragma once
// Campaign files: a TOML description of a shake-table campaign (its tests: body, table records, outcome observed),
// read into ensemble::CampaignSettings and ensemble::CampaignTest (topple/ensemble/campaign.hpp). docs/campaign.md
// describes every key; examples/campaign/ holds an example.
//
// Validation happens here, before any run: unknown keys, wrong types, a body given twice or not at all, values out of
// range, a model that needs mu without it, record or mesh files that do not exist, repeated test ids: each throws
// InputError naming the campaign file, the line and the key ("test[3].x"; tests numbered from 1 in file order), and a
// missing file also the test's id. Records and meshes are read later, one test at a time (load_campaign_input),
// their errors naming the test's id and key as well as the record's own file and line.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/bodies/body.hpp"
#include "topple/ensemble/campaign.hpp"
#include "topple/io/read.hpp"

namespace topple::io {

/// How one test's files are read.
struct CampaignTestFiles {
  std::filesystem::path x, y, z;         ///< resolved against the campaign file's directory; y, z empty: absent
  ReadOptions read;                      ///< format, units, dt_s (the same for the test's components)
  double scale = 1.0;                    ///< every component is multiplied by it
  double mesh_unit_m = 1.0;              ///< one unit of the mesh's coordinates, m
  BodyOptions body;                      ///< the mesh's pose (the `mesh_*` keys)
  std::optional<std::size_t> line;       ///< of the test's [[test]] table
  std::optional<std::size_t> x_line, y_line, z_line, mesh_line;  ///< of those keys
};

struct CampaignFile {
  std::filesystem::path path;
  ensemble::CampaignSettings settings;
  std::vector<ensemble::CampaignTest> tests;  ///< mesh paths resolved against the campaign file's directory
  std::vector<CampaignTestFiles> files;       ///< one per test
};

/// Reads and validates a campaign file (records and meshes are not read; their existence is checked). Throws
/// InputError.
[[nodiscard]] CampaignFile read_campaign_file(const std::filesystem::path& path);

/// Same on text in memory; `path` names it in messages and its directory anchors relative paths. `check_files`:
/// refuse record and mesh files that do not exist (off for the fuzz target).
[[nodiscard]] CampaignFile parse_campaign_file(std::string_view text, const std::filesystem::path& path,
                                               bool check_files = true);

/// Test i's records (read, scaled) and, for a mesh, its body as posed (io::read_mesh_body). Throws InputError naming
/// the campaign file, the key's line, the key and the test's id, with the reader's own message (record file, line).
[[nodiscard]] ensemble::CampaignInput load_campaign_input(const CampaignFile& campaign, std::size_t i);

}  // namespace topple::io
