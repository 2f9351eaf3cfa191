#pragma once
// Internal: the cylinder's engine with a slipping rim point and free flight (rigid3d_disc_contact.cpp), friction
// given; rock3d_cylinder (rigid3d_disc.cpp) hands a run to it where the rolling contact fails.
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "rigid3d_math.hpp"

namespace topple::detail {

/// The state the contact engine starts from: position_m is the centre of mass (r3d::EngineStart, rigid3d_math.hpp),
/// and the rim point in contact (its direction from the base's centre; used where the base is flat).
struct DiscStart : r3d::EngineStart {
  Vec3 contact_direction{1.0, 0.0, 0.0};
  /// the base flat on the ground, at rest (rock3d_cylinder's Shenton case, mu_s h < R, where g + a_z reaches 0: the
  /// flat slide model excludes flight, this engine does not); else the body on its rim, the rolling contact just failed
  bool at_rest = false;
};

/// From `start` (the body on its rim, the rolling contact just failed) to the end of the run; friction given and the
/// options checked by the caller. Its summary covers the run from start.time_s (counters from zero).
[[nodiscard]] Rigid3DResult rock3d_disc_contact(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                                const CylinderBody3D& body, const Rigid3DOptions& options,
                                                const DiscStart& start);

}  // namespace topple::detail
