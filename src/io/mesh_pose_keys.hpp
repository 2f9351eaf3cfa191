#pragma once
// The pose keys of a body given as a mesh, as every TOML file names them (sweep, survey and campaign files;
// docs/sweeps.md, docs/survey.md, docs/campaign.md): `mesh_pose` ("rest" or "as-scanned"), `mesh_up` [x, y, z],
// `mesh_rotation_wxyz` [w, x, y, z], `mesh_axis_angle_deg` [x, y, z, degrees], `mesh_face` (a number of `topple body
// --list-faces`) and the contact tolerance (each file its own spelling). One meaning and one set of words for the
// three readers; each reads the values with its own reader, so that errors keep its file, line and key.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "topple/bodies/body.hpp"

namespace topple::io_detail {

/// mesh_pose's value as a pose method; nullopt for another word (the caller refuses it with mesh_pose_problem).
[[nodiscard]] inline std::optional<PoseMethod> mesh_pose_method(std::string_view value) {
  if (value == "rest") return PoseMethod::rest;
  if (value == "as-scanned") return PoseMethod::as_scanned;
  return std::nullopt;
}
[[nodiscard]] inline std::string mesh_pose_problem(std::string_view value) {
  return fmt::format("'{}' is not a pose: \"rest\" or \"as-scanned\"", value);
}

inline constexpr const char* kMeshFaceProblem =
    "expected a face number (an integer from 1; see topple body --list-faces)";
/// mesh_face's value: a face number from 1, or nullopt (refused with kMeshFaceProblem).
[[nodiscard]] inline std::optional<std::size_t> mesh_face_number(const toml::node& n) {
  const auto* i = n.as_integer();
  if (i == nullptr || i->get() < 1) return std::nullopt;
  return static_cast<std::size_t>(i->get());
}

/// The three orientation keys into options. fixed(key, count, what) reads the key as a list of `count` numbers
/// (nullopt when absent; its reader's own error otherwise), `what` saying what the list is.
template <class Fixed>
void read_mesh_orientation(BodyOptions& options, Fixed&& fixed) {
  if (const std::optional<std::vector<double>> v = fixed("mesh_up", 3, "[x, y, z], the mesh's direction that becomes up")) {
    options.up = Vec3{(*v)[0], (*v)[1], (*v)[2]};
  }
  if (const std::optional<std::vector<double>> v = fixed("mesh_rotation_wxyz", 4, "[w, x, y, z], a unit quaternion")) {
    options.rotation_wxyz = Quaternion{(*v)[0], (*v)[1], (*v)[2], (*v)[3]};
  }
  if (const std::optional<std::vector<double>> v =
          fixed("mesh_axis_angle_deg", 4, "[x, y, z, degrees], an axis and an angle")) {
    options.axis_angle_deg = std::array<double, 4>{(*v)[0], (*v)[1], (*v)[2], (*v)[3]};
  }
}

/// The file's key for an option check_body_options (or the mesh pipeline) names: tolerance_key is the file's
/// spelling of the contact tolerance, other the key for an option without one of its own.
[[nodiscard]] inline std::string mesh_option_key(std::string_view option, std::string_view tolerance_key,
                                                 std::string_view other) {
  if (option == "--density") return "mesh_density_kg_m3";
  if (option == "--pose") return "mesh_pose";
  if (option == "--up") return "mesh_up";
  if (option == "--rotation") return "mesh_rotation_wxyz";
  if (option == "--axis-angle") return "mesh_axis_angle_deg";
  if (option == "--face") return "mesh_face";
  if (option == "--contact-tolerance") return std::string(tolerance_key);
  return std::string(other);
}

}  // namespace topple::io_detail
