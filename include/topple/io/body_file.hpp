#pragma once
// Reading the body that `topple body --json` writes (output/body_json.hpp, kMeshBodyFields): the asymmetric rocking
// body of a mesh in the vertical plane of its azimuth, for `rock --body` and `fragility --body`.
//
// Only the fields needed are read: b1_m, b2_m, h_m (m), inertia_cm_plane_kg_m2 and mass_kg (I_cm / m = the first over
// the second, the k2 of RockingBody::general_asymmetric, as rocking_body(MeshBody) forms it), and, for the report,
// azimuth_deg and file when present. Unknown fields are ignored (the JSON grows: pose fields, ...). A file that is not
// a JSON object, or lacks one of the needed fields, or holds one that is not a positive finite number, is refused with
// an InputError naming the file and the field.
#include <optional>
#include <string>
#include <string_view>

#include "topple/bodies/rocking_body.hpp"

namespace topple::io {

struct BodyFile {
  double b1_m = 0.0;        ///< CM to the pivot O- (the rear, -x), m
  double b2_m = 0.0;        ///< CM to the pivot O+ (the front, +x), m
  double h_m = 0.0;         ///< CM height above the support plane, m
  double inertia_m2 = 0.0;  ///< I_cm / m about the rocking axis through the CM, m^2
  std::optional<double> azimuth_deg;  ///< the plane's azimuth, when the file gives it
  std::string mesh_file;              ///< the mesh it came from, when the file gives it
  /// RockingBody::general_asymmetric(b1, b2, h, inertia): the body `topple body` prints as a rock command.
  [[nodiscard]] RockingBody rocking_body() const;
};

/// Reads `path` (at most 64 MiB). Throws InputError naming `path` and the field.
[[nodiscard]] BodyFile read_body_file(const std::string& path);

/// The same on content already in memory; `name` is used in messages.
[[nodiscard]] BodyFile parse_body_file(std::string_view content, const std::string& name);

}  // namespace topple::io
