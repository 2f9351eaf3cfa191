#pragma once
// topple rock --model 3d: the three-dimensional rocking and pivoting engine (rigid3d.hpp) for a block with a depth.
// Translation only.
#include <optional>
#include <string>

#include "common.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple::cli {

/// What `topple rock --model 3d` parsed, besides the motion.
struct Rigid3DRequest {
  double width_m = 0.0, depth_m = 0.0, height_m = 0.0;  ///< the block: x, y, z in its own frame
  Rigid3DOptions options;
  bool json = false;
  /// With a second horizontal component: the azimuth (degrees clockwise from north) of the block's +x axis; the
  /// motion set acts along east and north. Without one: the record acts along the block's +x axis, and the reported
  /// azimuths take that direction as 90 degrees (east).
  std::optional<double> bearing_deg;
  std::string h2;
  const MotionSet* set = nullptr;  ///< with --h2
};

/// Runs rock3d and prints the text summary or, with `json`, one JSON object (model "3d": the summary's keys, the
/// modes, the body, then "input").
void run_3d(const RunMotion& run, const Rigid3DRequest& request);

}  // namespace topple::cli
