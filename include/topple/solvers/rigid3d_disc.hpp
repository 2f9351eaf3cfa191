#pragma once
// Three-dimensional rocking and rolling of a rigid body with a CIRCULAR base (a cylinder: columns, vases, bottles,
// tanks) on a rigid level base under three ground components, without slip (issue 29; docs/method.md, "Rocking in
// three dimensions", "A circular base: rolling on the rim"). Frames, units and outputs as rigid3d.hpp.
//
// Friction (Rigid3DOptions::mu_s, mu_k; docs/method.md, "A circular base with friction"): absent, the engine below
// bit for bit. Given: with mu_s h < R the base never lifts (Shenton 1996) and the run is slide_2d's block exactly;
// otherwise the rolling engine below runs with its contact force F = a_c - f checked on the dense output (N > 0,
// |F_t| <= mu_s N), and where it fails (or g + a_z reaches 0 at rest) the run goes on in rigid3d_disc_contact.cpp: a
// free rigid body on the lowest point of its rim, sticking (rolling), slipping (Coulomb, N from the normal
// constraint) or in flight, flat on the ground at rest or sliding, with plastic Coulomb impacts; modes sliding,
// slide_rock, flight and the sliding fields of Rigid3DSummary as the polygon engine fills them.
//
// Body. Base circle of radius R in the body plane z = 0, centred at the body frame's origin; centre of mass on the
// axis at c = (0, 0, h); inertia per unit mass about c: J_a about the axis, J_t about any transverse axis (an
// axisymmetric body). In the ground frame: a = R(q) e_z the axis, J_G w = J_t w + (J_a - J_t)(a . w) a.
//
// Modes: rest (the base flat on the ground); rim (Rigid3DMode::rocking: the body stands on the lowest point of its
// tilted base circle and rolls on it without slip: the classical rolling disk, O'Reilly 1996, with the centre of mass
// above the base's centre); fallen (the tilt reaches 90 degrees).
//
// Rim contact. The tilt theta: cos(theta) = a . z. The contact point is the lowest point of the base circle,
// p = o + R u, o = c - h a the base's centre, u = -z_perp / |z_perp|, z_perp = z - (a . z) a (|z_perp| = sin(theta)).
// With r = c - p = h a - R u, no slip (the material point at p has the ground's velocity): v_c = w x r, and the
// angular momentum balance about the moving contact (per unit mass; f = (-a_x, -a_y, -(g + a_z)) the gravity and
// the ground's inertial force):
//   M_p w' = r x f - w x (J_G w) - r x (w x r'),   M_p = J_G + |r|^2 1 - r r^T,   r' = h (w x a) - R u',
//   q' = (0, w) q / 2 (w in the ground frame),   x_c' = w x r.
// (Newton: a_c = F + f, a_c = d(w x r)/dt; Euler about c: d(J_G w)/dt = -r x F; eliminating the contact force F.)
// u' follows from a' = w x a: z_perp' = -(z . a') a - (z . a) a', u' = -(z_perp' - u (u . z_perp')) / sin(theta);
// at the upright (sin(theta) < 1e-12: the first stage after an uplift or an impact) u is the contact chosen there and
// u' = w x u (the rim point fixed in the body: the rocking limit).
// Under one horizontal component with no spin the motion stays in the vertical plane through the axis and this is
// the planar engine's cylinder (rocking.hpp) with a = R, D = J_t + R^2 + h^2.
//
// Transitions. rest -> rim: the static threshold |a_h| > (g + a_z) R / h (the resultant of gravity and the ground's
// inertial force leaves the base), located in each sample interval by TOMS 748 on |a_h|^2 - ((g + a_z) R / h)^2; the
// contact is the rim point toward -a_h (the body tips away from the ground's acceleration, as the planar engine's
// "a_h < 0 drives theta > 0"); with no vertical component the test at rest is one comparison per sample (|a_h|^2 is
// convex on a linear piece). rim -> landing: the base lands flat when s(t) = -z_perp(t) . u0 (sin(theta) cos(theta)
// cos(the contact's turn since the step's start u0)) falls to 0; in planar rocking this is theta = 0 exactly. Within a
// step the rim equations are continued past the upright on the step's side (u = -d where the lowest point d has
// passed to the far side, d . u0 < 0: in one plane the rim point fixed in the body that was the contact, as the planar
// engine continues its pivot's equation past theta = 0), so a step may end past the landing, which is the first root
// of s on the dense output: where s ends below 0, or at a minimum of s inside the step (ds/dt from < 0 to > 0) at or
// below 0. A step from flat (after an uplift or an impact; s = 0 there) looks for the body up (s > 0) at 16 points of
// the step; none: the step is taken again 16 times shorter, and below 1e-7 / p (p = sqrt(g / sqrt(R^2 + h^2))) the
// lift did not happen and the body is at rest at the step's end (time advances). A body
// with a sideways rate (w . u != 0) near the upright does not land on the ideal rim: its contact runs round the rim
// (u' ~ rate / theta) and it rolls over onto the other side (the rolling disk); a tilt minimum below 1e-3 alpha with a
// sideways rate counts as a flat landing at the minimum (a stated approximation: the whole base is then within
// 2 R sin(1e-3 alpha) of the ground).
// rim -> fallen: theta = 90 degrees (the azimuth of the fall: the axis' horizontal direction).
//
// Impact (Housner 1963 generalised, as rigid3d.hpp): the base lands flat; the new contact p' is the rim point with
// the largest downward velocity; the impulse acts at p' and the base's vertical impulses stop a rotation about the
// diameter through p' (which would push half the base into the ground): after the impact w+ = w_t t' + w_z z,
// t' = z x u', with the angular momentum about p' conserved along t' and z (a vertical impulse has no moment about
// the vertical; Housner's law about the rocking axis):  [t' z]^T M_p' [t' z] (w_t, w_z) = [t' z]^T (J w- + r' x v_c-).
// In one vertical plane this is the planar cylinder's e = 1 - 2 R^2 / D = 1 - 24 a^2 / (15 a^2 + 16 h^2) (rocking.hpp).
// w_t <= 0 (no lift about p') or the rest rule (rigid3d.hpp's, with the lift energy g (sqrt(R^2 + h^2) - h)) puts the
// body at rest. RestitutionMode::given keeps that direction and sets the kinetic-energy ratio to e^2.
//
// Method: Dormand-Prince 5(4) with its dense output (numerics/dp5.hpp) on the state (q, w, x_c), steps ending on
// every sample (after the record, on still ground, steps of any length; history rows from the dense output on the
// record's spacing); events are roots of the dense output by TOMS 748 (numerics/event_root.hpp) inside each step where
// their function changes sign at the step's ends or at one turning point (a double crossing inside one step between
// two turning points is missed: stated). Without friction the contact force is not checked (no slip, no flight; with
// friction: above). Not modelled: rolling resistance.
#include <optional>

#include "topple/bodies/body.hpp"
#include "topple/solvers/rigid3d.hpp"

namespace topple {

/// An axisymmetric body on a circular base (header).
struct CylinderBody3D {
  double radius_m = 0.0;            ///< R, base radius
  double centre_height_m = 0.0;     ///< h, centre of mass above the base's centre on the axis
  double inertia_axial_m2 = 0.0;    ///< J_a = I_axis / m about the centre of mass
  double inertia_transverse_m2 = 0.0;  ///< J_t = I_transverse / m about the centre of mass

  /// A uniform solid cylinder: diameter d, height H: R = d/2, h = H/2, J_a = R^2/2, J_t = (3 R^2 + H^2)/12 (the
  /// planar engine's cylinder, rocking_body.hpp). Throws InputError naming "diameter" or "height".
  [[nodiscard]] static CylinderBody3D solid(double diameter_m, double height_m);
  /// Any axisymmetric body; throws InputError naming "radius", "height" or "inertia" (J_a, J_t > 0, J_a <= 2 J_t).
  [[nodiscard]] static CylinderBody3D general(double radius_m, double centre_height_m, double inertia_axial_m2,
                                              double inertia_transverse_m2);
  /// The static tilt limit atan(R / h), the same toward every azimuth.
  [[nodiscard]] double static_tilt_limit_rad() const;
};

/// A state on the rim to start from (tests, free rolling): the orientation (body -> ground, unit) and the angular
/// velocity in the ground frame. The tilt must be in (0, 90) degrees.
struct CylinderInitialState {
  Quaternion orientation = kIdentityQuaternion;
  Vec3 angular_velocity_rad_s{};
};

/// The response of a cylinder to ground accelerations along x (east; required), y (north) and z (up) (m/s^2; null:
/// absent). Rigid3DSummary: modes rest / rocking (on the rim; vertex_a = vertex_b = -1) / fallen, and with friction
/// sliding / slide_rock / flight. Throws InputError for a bad option, bad friction ("mu_s", "mu_k"), or g + a_z <= 0
/// ("vertical") without friction or with mu_s h < R.
[[nodiscard]] Rigid3DResult rock3d_cylinder(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                            const CylinderBody3D& body, const Rigid3DOptions& options = {},
                                            const std::optional<CylinderInitialState>& initial = std::nullopt);

}  // namespace topple
