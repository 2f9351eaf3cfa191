#pragma once
// The field table of a body from a mesh (topple/bodies/body.hpp): what `topple body --json` prints, one entry per key, in
// order (name with unit, accessor), as summary_fields.hpp does for the solvers' results. The keys are a stable
// interface: add a field here, once.
//
// Unlike the solvers' tables (topple/core/field.hpp), an accessor returns JSON: the centre of mass and the pivots are
// vectors, the inertia a 3x3 matrix, the support polygon a list of points and the symmetric equivalent an object,
// which FieldValue (also the sweep's cell type) does not hold.
#include <array>
#include <cstddef>
#include <string>

#include <nlohmann/json.hpp>

#include <vector>

#include "topple/bodies/body.hpp"
#include "topple/bodies/pose.hpp"

namespace topple::io {

/// A mesh's body with what is reported beside it.
struct MeshBodyOutcome {
  const MeshBody& body;
  const std::string& file;  ///< the mesh file as given
  double unit_m = 1.0;      ///< the length of one unit of the file's coordinates, m
  std::size_t vertices = 0;
  std::size_t triangles = 0;
  double g_m_s2 = 9.80665;  ///< the gravity p1, p2 were computed with (BodyOptions::g_m_s2)
};

struct BodyField {
  const char* name;  ///< the JSON key, with its unit
  nlohmann::ordered_json (*get)(const MeshBodyOutcome& outcome);
};

/// file, unit_m, vertices, triangles, density_kg_m3, volume_m3, mass_kg, centre_of_mass_m, inertia_cm_kg_m2,
/// support_z_m, support_tolerance_m, support_contact_vertices, support_polygon_xy_m, azimuth_deg, g_m_s2, h_m, b1_m,
/// b2_m, r1_m, r2_m, alpha1_rad, alpha2_rad, alpha1_deg, alpha2_deg, inertia_cm_plane_kg_m2, inertia_o1_kg_m2,
/// inertia_o2_kg_m2, d1_m2, d2_m2, p1_rad_s, p2_rad_s, pivot1_m, pivot2_m, symmetric {b_m, r_m, alpha_rad,
/// alpha_deg, d_m2, p_rad_s} (definitions in body.hpp), pose {method ("rest" or "as-scanned"), chosen_by, face
/// (null as scanned), tilt_deg, rotation_wxyz, contact_tolerance_m, faces, stable_faces, static_overturning {min_g,
/// min_azimuth_deg, toward_north_g, toward_east_g, toward_south_g, toward_west_g}} (bodies/pose.hpp).
extern const std::array<BodyField, 35> kMeshBodyFields;

/// The text of a pose method: "rest", "as-scanned".
[[nodiscard]] const char* pose_method_name(PoseMethod method);

/// The static overturning accelerations as an object {min_g, min_azimuth_deg, toward_north_g, toward_east_g,
/// toward_south_g, toward_west_g}.
[[nodiscard]] nlohmann::ordered_json static_overturning_json(const StaticOverturning& s);

/// The faces of `topple body --list-faces --json`: one object each {face, tilt_deg, stable, area_m2, margin_m, h_m,
/// contact_vertices, normal, support_polygon_xy_m, static_overturning (null when not stable)}.
[[nodiscard]] nlohmann::ordered_json resting_faces_json(const std::vector<RestingFace>& faces);

/// The body as one JSON object, keys in kMeshBodyFields' order (what `topple body --json` prints).
[[nodiscard]] nlohmann::ordered_json mesh_body_json(const MeshBodyOutcome& outcome);

}  // namespace topple::io
