#pragma once
// topple rock --model 3d: the three-dimensional rocking and pivoting engine (rigid3d.hpp) for a block with a depth or
// a mesh as posed (`topple body`'s pose options). Translation only.
#include <optional>
#include <string>

#include "common.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"

namespace topple::cli {

/// What `topple rock --model 3d` parsed, besides the motion.
struct Rigid3DRequest {
  RigidBody3D body;  ///< in its own frame (the block's, or the posed mesh's shifted down to its support plane)
  /// A solid cylinder (--shape cylinder): the rim engine (rigid3d_disc.hpp) instead of `body`; width_m is its
  /// diameter, height_m its height. Axisymmetric: no bearing (with --h2 the pair acts along east and north).
  std::optional<CylinderBody3D> cylinder;
  /// The block's dimensions (x, y, z in its own frame); zero for a mesh.
  double width_m = 0.0, depth_m = 0.0, height_m = 0.0;
  std::string mesh_file;  ///< --mesh: the file (the body is the mesh's); empty for a block
  Rigid3DOptions options;
  bool json = false;
  /// With a second horizontal component: the azimuth (degrees clockwise from north) of the body's +x axis; the
  /// motion set acts along east and north. Without one: the record acts along the body's +x axis, and the reported
  /// azimuths take that direction as 90 degrees (east).
  std::optional<double> bearing_deg;
  std::string h2;
  const MotionSet* set = nullptr;  ///< with --h2
  std::string out;   ///< --out: the history as CSV (time, position, quaternion, angular velocity, tilt, energy, mode)
  std::string plot;  ///< --plot: the figure (.svg or .png, gnuplot)
  std::string vertical_label;  ///< the --vertical file, for the figure's title
};

/// Runs rock3d and prints the text summary or, with `json`, one JSON object (model "3d": the summary's keys, the
/// modes, the body, then "input"); writes the history and the figure when asked.
void run_3d(const RunMotion& run, const Rigid3DRequest& request);

}  // namespace topple::cli
