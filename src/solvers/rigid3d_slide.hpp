#pragma once
// Internal: the two halves of rock3d (rigid3d.hpp). rigid3d.cpp holds the no-slip engine, rigid3d_slide.cpp the
// sliding phases with Coulomb friction (docs/method.md, "Sliding in three dimensions").
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple::detail {

/// The no-slip engine (rigid3d.cpp), the body at rest at start_time_s (before the record: from its start). Options
/// checked by the caller; mu_s and mu_k are not read.
[[nodiscard]] Rigid3DResult rock3d_rigid(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                         const RigidBody3D& body, const Rigid3DOptions& options, double start_time_s);

/// rock3d with friction given (rigid3d_slide.cpp): sliding phases by slide_2d, the onset of rocking from the centre of
/// pressure, then the no-slip engine.
[[nodiscard]] Rigid3DResult rock3d_friction(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                            const RigidBody3D& body, const Rigid3DOptions& options);

}  // namespace topple::detail
