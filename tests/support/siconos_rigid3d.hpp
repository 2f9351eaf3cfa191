#pragma once
// Independent reference for topple's 3-D rigid-body engine (issue 29): a rectangular box on a rigid level plane,
// simulated with Siconos (INRIA; Debian's libsiconos-kernel-dev 4.x), TEST code only. Nothing here is topple's method:
// it is a second, unrelated discretisation used to check the event-driven engines.
//
// Model. Box of half-widths (a, b, c) along its body axes (x, y, z), mass m, principal inertia about the CM
// I = m/3 (b^2 + c^2, a^2 + c^2, a^2 + b^2). Frame: the ground's (x, y horizontal, z up; the plane z = 0), so the
// motion is relative to the ground and the ground acceleration a_g(t) = (a_x, a_y, a_z) enters as the inertial force
// -m a_g(t) at the CM, with gravity -m g e_z. Contacts: the 4 base corners (body z = -c), each a unilateral contact
// with the plane, Newton's impact law (normal restitution e) and isotropic Coulomb friction mu (Siconos
// NewtonImpactFrictionNSL, 3-D contact: normal + 2 tangential). Dynamics: Siconos NewtonEulerDS (position and unit
// quaternion, twist with the angular velocity in the body frame, gyroscopic term included).
//
// Method (Siconos' defaults): Moreau-Jean time stepping (Moreau 1988; Jean 1999, "The non-smooth contact dynamics
// method", Comput. Methods Appl. Mech. Engrg. 177) with theta = 1/2, an event-capturing scheme of first order: an
// impact or a stick-slip transition inside a step is resolved at the step's end, so positions carry O(h) errors at
// each such event and O(h^2) per step in smooth phases. Each step solves a 3-D frictional contact problem
// (FrictionContact, NSGS). The ground acceleration is piecewise linear (linear interpolation of the samples) and is
// applied as its mean over each step (the step's midpoint value for a linear ramp).
//
// Outputs per step: CM position, orientation quaternion, tilt (angle of the body's z axis from the vertical), the
// four corner heights. Overturned when the tilt reaches overturn_tilt_rad (default 80 deg: far past any box's static
// limit atan(sqrt(a^2 + b^2) / c), the top about to strike the ground, which this 4-corner model does not represent);
// the run then stops.
#include <array>
#include <optional>
#include <vector>

namespace topple::test {

struct SiconosBox {
  double half_x_m = 0.1;   ///< a: half-width along body x
  double half_y_m = 0.1;   ///< b: half-width along body y
  double half_z_m = 0.5;   ///< c: half-height (CM height at rest)
  double mass_kg = 1.0;
  double restitution = 0.0;  ///< Newton's e at the corners (normal)
  double mu = 10.0;          ///< Coulomb friction at the corners
};

struct SiconosOptions {
  double step_s = 1e-3;                     ///< Moreau-Jean step h
  double g_m_s2 = 9.80665;
  double duration_s = 1.0;                  ///< simulated time (input is zero after its last sample)
  double overturn_tilt_rad = 80.0 * 3.14159265358979323846 / 180.0;
  double solver_tolerance = 1e-10;          ///< NSGS tolerance on the contact problem
  int solver_max_iterations = 1000;
  std::array<double, 3> initial_position_m{0.0, 0.0, 0.0};  ///< CM offset from (0, 0, c); zero: at rest on its base
};

/// Ground acceleration history, m/s^2, on a uniform grid starting at t = 0 (missing components: zero). Linear between
/// samples, zero after the last one.
struct SiconosGroundMotion {
  double dt_s = 0.01;
  std::vector<double> ax_m_s2;
  std::vector<double> ay_m_s2;
  std::vector<double> az_m_s2;
};

struct SiconosHistory {
  std::vector<double> time_s;
  std::vector<std::array<double, 3>> position_m;   ///< CM, ground frame
  std::vector<std::array<double, 4>> quaternion;   ///< (w, x, y, z), body to ground
  std::vector<double> tilt_rad;                    ///< angle between the body z axis and the vertical
  std::vector<std::array<double, 4>> corner_z_m;   ///< heights of the base corners (+x+y, -x+y, -x-y, +x-y)
};

struct SiconosResult {
  SiconosHistory history;
  double max_tilt_rad = 0.0;
  double max_tilt_time_s = 0.0;
  std::array<double, 2> max_tilt_axis{0.0, 0.0};  ///< horizontal direction the top moved toward at max tilt (unit)
  bool overturned = false;
  std::optional<double> overturn_time_s;
  std::optional<double> cm_past_base_time_s;  ///< first time the CM's vertical leaves the base's footprint
  std::array<double, 4> max_corner_z_m{0.0, 0.0, 0.0, 0.0};  ///< max height reached by each base corner
  std::array<double, 2> final_displacement_m{0.0, 0.0};     ///< CM horizontal displacement at the end
  double final_yaw_rad = 0.0;                                ///< rotation about the vertical at the end
  /// Ends of the steps whose contact problem NSGS left above solver_tolerance (Siconos' info != 0); counted here
  /// instead of Siconos' default message on stderr.
  std::vector<double> unconverged_step_times_s;
};

/// Runs the Siconos simulation. Throws std::runtime_error when Siconos fails.
[[nodiscard]] SiconosResult simulate_siconos_box(const SiconosBox& box, const SiconosGroundMotion& ground,
                                                 const SiconosOptions& options = {});

}  // namespace topple::test
