#pragma once
// The options that place a mesh body (bodies/pose.hpp): one registration for every command that reads a mesh
// (`topple body`, `topple fragility --mesh`), so that they take the same options with the same meaning.
#include <cstddef>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "topple/bodies/body.hpp"

namespace topple::cli {

/// The pose options as typed; apply_pose_options turns them into BodyOptions.
struct PoseOptionsText {
  std::string pose = "rest";
  std::string up, rotation, axis_angle, contact_tolerance;
  std::optional<std::size_t> face;
};

/// Registers --pose, --up, --rotation, --axis-angle, --face, --contact-tolerance and --base-tolerance on `cmd`;
/// `with` starts each help text ("" for a command about a mesh, "With --mesh: " where the mesh is one choice).
void add_pose_options(CLI::App& cmd, PoseOptionsText& text, BodyOptions& body, const std::string& with = "");

/// After parsing: the rule that keeps old command lines meaning what they meant (--base-tolerance without --pose is
/// the as-scanned pose; with --pose rest it is refused, as --contact-tolerance is with as-scanned), then the options
/// into `body` (checked later by check_body_options). Throws a parameter error naming the option.
void apply_pose_options(const CLI::App& cmd, PoseOptionsText& text, BodyOptions& body);

}  // namespace topple::cli
