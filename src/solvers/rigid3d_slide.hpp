#pragma once
// Internal: the two halves of rock3d (rigid3d.hpp). rigid3d.cpp holds the no-slip engine, rigid3d_slide.cpp the
// sliding phases with Coulomb friction (docs/method.md, "Sliding in three dimensions").
#include <optional>

#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "rigid3d_math.hpp"

namespace topple::detail {

/// The records in an inclined base's frame (rigid3d.hpp, "Inclined base"; rigid3d_slide.cpp): on the union grid of
/// x, y and z (input_grid.hpp), the components of Q^T (a_x, a_y, g + a_z): x' and y' along the base's x and y axes and
/// z' = (the load normal to the base) - g, so that the engines' g + a_z is that load. All three are given (zero
/// where the load is), so that the engines never take the x-alone path. Between samples linear as the records are.
struct BaseRecords {
  std::optional<GroundMotion> x, y, z;
};
[[nodiscard]] BaseRecords base_records(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                       const Rigid3DOptions& options);

/// The no-slip engine (rigid3d.cpp), the body at rest at start_time_s (before the record: from its start). Options
/// checked by the caller; mu_s and mu_k are not read.
[[nodiscard]] Rigid3DResult rock3d_rigid(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                         const RigidBody3D& body, const Rigid3DOptions& options, double start_time_s);

/// rock3d with friction given (rigid3d_slide.cpp): sliding phases by slide_2d, the onset of rocking from the centre of
/// pressure, then the no-slip engine.
[[nodiscard]] Rigid3DResult rock3d_friction(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                            const RigidBody3D& body, const Rigid3DOptions& options);

/// The friction options' checks (rock3d_friction's): mu_s given, finite and >= 0, 0 <= mu_k <= mu_s, the sliding
/// tolerances. Throws InputError naming "mu_s" or "mu_k".
void check_friction(const Rigid3DOptions& options);

/// A body that can never lift (Shenton 1996: mu_s h below the least distance from c's plan to the base's edge):
/// slide_2d's answer whole, as rock3d_friction returns it for such a body (modes rest / sliding; history rows with the
/// identity orientation). Friction given and checked by the caller.
[[nodiscard]] Rigid3DResult rock3d_flat_slide(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                              const Rigid3DOptions& options);

/// The state the contact engine starts from (rigid3d_contact.cpp): position_m is the body frame's origin in the
/// ground frame (r3d::EngineStart, rigid3d_math.hpp).
struct ContactStart : r3d::EngineStart {};

/// The engine with slipping contacts and flight (rigid3d_contact.cpp), friction given (checked by the caller), from
/// `start` (a flat base: at rest or sliding) to the end of the run. Its summary covers the run from start.time_s.
[[nodiscard]] Rigid3DResult rock3d_contact(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                           const RigidBody3D& body, const Rigid3DOptions& options,
                                           const ContactStart& start);

}  // namespace topple::detail
