#pragma once
// Three-dimensional rocking and pivoting of a rigid body with a convex polygonal base on a rigid level base (or an
// inclined one: "Inclined base" below) under three ground components, without sliding (issue 29, the foundation;
// docs/method.md, "Rocking in three dimensions").
//
// Frames. The ground frame G moves with the ground: x east, y north, z up (the ground's acceleration enters as the
// inertial force -a_g per unit mass, gravity as -g z). The body frame B: the base plane is z = 0, the base polygon's
// vertices v_i = (x_i, y_i, 0) are counter-clockwise seen from above, the centre of mass is c = (c_x, c_y, h), h > 0,
// strictly inside the polygon in plan, J = I_cm / m the inertia tensor about c per unit mass (B axes). Orientation:
// the unit quaternion q with R(q) mapping B to G. Everything is per unit mass (the mass drops out).
//
// Friction (Rigid3DOptions::mu_s, mu_k; rigid3d_slide.cpp; docs/method.md "Sliding in three dimensions"): absent,
// no contact point slides (the modes below). Given, the flat base sticks while |a_h| <= mu_s (g + a_z) and otherwise
// slides flat without spin as sliding2d.hpp's block (exact: no friction torque about c's vertical); it lifts where the
// centre of pressure c + h F_t / N leaves the base. From sticking the no-slip modes below take over, and their answer
// is kept where no contact needs more than mu_s N, the body never slides after coming back to rest and g + a_z > 0;
// otherwise (and from slipping: slide-rock) the run is rigid3d_contact.cpp's (docs/method.md, "Slide-rock and flight in
// three dimensions"): a free rigid body with an active set of base vertices, each sticking or slipping, the modes
// slide_rock (a contact vertex slipping while the base is not flat) and flight (no contact), impacts with a Coulomb
// impulse, Painleve's paradox resolved as slide_rock.hpp does. A run with friction never stops early.
//
// Contact modes (friction large enough that no contact point slides):
//   rest    the base lies flat on the ground;
//   rocking the body turns about a base edge (v_i, v_i+1) lying on the ground: one degree of freedom, the tilt theta
//           about the edge's axis e (unit, from v_i to v_i+1); the outward normal of the edge n = e x z. With
//           b = distance of c's plan from the edge (> 0) and G_v = g + a_z, f_n = -a_g . n (Konstantinidis & Makris
//           2007, eq 1, for a block; here any edge of a polygon):
//             J_e theta'' = (b sin theta + h cos theta) f_n - G_v (b cos theta - h sin theta),
//             J_e = e . J e + b^2 + h^2   (the moment of inertia about the edge, parallel axes).
//           This is the planar engine's equation (rocking.hpp) with alpha = atan(b / h), D = J_e, a_h = a_g . n.
//   pivot   the body turns about a base vertex p fixed on the ground: three rotational degrees of freedom, Euler's
//           equations about the fixed point in the body frame with r = c - p, J_p = J + |r|^2 1 - r r^T:
//             J_p w' = r x f_B - w x (J_p w),   q' = q (0, w) / 2,   f_B = R^T (-a_x, -a_y, -(g + a_z)).
//   flight  without friction not modelled (a stated limit): when the vertical contact force vanishes (a body thrown
//           up by a strong vertical input, or one falling fast near the ground) the first instant is reported
//           (Rigid3DSummary::flight_time_s, a warning) and the contact is kept, as the planar engine keeps it. With
//           friction given flight is modelled (ballistic c, torque-free rotation, landing an impact:
//           rigid3d_contact.cpp).
//
// Transitions (contact forces and moment balance):
//   rest -> the centre of pressure p(t) = c_plan - h a_h(t) / (g + a_z(t)) (where the resultant of gravity and the
//           ground's inertial force meets the base) leaves the polygon: across the interior of edge e (the static
//           threshold -a_h . n_e > (g + a_z) b_e / h) the body rocks about e; exactly through a vertex V (two
//           adjacent edges at once, e.g. a box under a component along its diagonal: |a_h| / (g + a_z) = |V - c| / h
//           with a_h pointing from V to c) it pivots on V.
//   rocking -> pivot: the vertical contact force at one end of the edge vanishes (the centre of pressure reaches the
//           end): the body pivots on the other end with the same angular velocity (no impact).
//   rocking -> impact: theta returns to 0 (the base lands flat). pivot -> impact: another vertex touches down (an
//           adjacent one: the impact law below picks the new corner, the edge or rest) or the base lands flat (a
//           third vertex within simultaneous_contact of the ground).
//   rocking/pivot -> fallen: the tilt (the angle between the body's z axis and the vertical) reaches 90 degrees.
//
// Impact law (docs/method.md, "Impact law"): perfectly plastic and sticking (Newton's e = 0, no contact slides), a
// small linear complementarity problem over the vertices down at the instant (Moreau 1988; Glocker & Pfeiffer 1995),
// solved by enumerating its sets: a vertex p alone (the impulse at p only, so the angular momentum about p is
// conserved, J_p' w+ = J w- + r' x v_c-: Housner 1963 generalised), an edge (impulses at both ends, the momentum about
// its axis conserved, J_e' theta'+ = e' . (J w- + r' x v_c-)), or the flat base at rest; the solution is the set
// whose vertical impulses are >= 0 and whose other contacts move up or stay (none: the impact would make a contact
// slide, which the model excludes; the set that moves no contact into the ground and pulls least is taken, and a
// warning says so once). A corner landing next to the pivot thus pivots on the new corner, the old one lifting
// (Housner's impulse at the new contact only), unless the motion would push the old one down; a block landing on its
// opposite edge is Housner's e = 1 - 2 a^2 / D (the planar law).
// Pivot swaps between the two ends of an edge whose kinetic energy off the edge's axis falls below 1e-8 of the whole
// take their (Zeno) limit, rocking about the edge. Vertices within simultaneous_contact times the body's size of the
// ground at a touch-down join it (a base that close to flat lands as one impact). A given e (RestitutionMode::given)
// keeps that direction of the motion after the impact and sets the ratio of kinetic energies to e^2 (the planar
// engine's theta'+ = e theta'- for a block on its opposite edge).
//
// Inclined base (Rigid3DOptions::base_incline_deg = beta > 0, downhill azimuth A; docs/method.md, "An inclined base").
// The base is a rigid plane through the ground's origin with normal n = cos(beta) z + sin(beta) e_d, e_d = (sin A,
// cos A, 0) the downhill direction; it moves with the ground (the record's accelerations, given in the horizontal and
// vertical frame of the record, are the base's). The engines above run unchanged in the base's frame P: the rotation
// Q by beta about the horizontal axis z x e_d (across the slope) maps the record frame's axes onto P's (z onto n, e_d
// onto the downhill line of the plane, the across-slope axis onto itself). Per unit mass the load in P is
// Q^T (a_x, a_y, g + a_z): the "horizontal" components a_P = (a_x', a_y') carry gravity's slope component
// -g sin(beta) e_d, the "vertical" one g cos(beta) + ... (linear in t between samples, so the engines' exactness is
// kept), and still ground (after the record) is Q^T (0, 0, g). Every output is in P: the tilt is the angle between the
// body's z axis and the base normal (the natural tilt of a body resting on the plane; fallen: 90 degrees from the
// normal), the azimuths (of the fall, of the tilt) are directions in the plane measured clockwise from P's y axis
// (north carried onto the plane by Q: on the fall line and across it they are the compass azimuths), the residual
// slide (east, north) is the displacement along the plane, its components on P's x and y axes (the downhill in-plane
// axis carried on e_d, as sliding2d.hpp's slope), the history in P, its energy with the potential of gravity in P.
// Without friction the base sticks (no contact slides, however steep: stated); with mu_s the flat phases are
// sliding2d.hpp's incline (eq S11; a body with tan(beta) > mu_s slides from the start, at g (sin beta - mu_k cos beta)
// down the plane on still ground).
//
// Rest rule: as the planar engine's (rocking.hpp): after a flat landing, kinetic energy below rest_energy_fraction times
// the energy to lift the centre of mass over the new contact (g (|c - contact| - h)) puts the body at rest.
//
// Method: Dormand-Prince 5(4) with its 4th-order dense output (as rocking_steppers.hpp), steps ending on every
// sample; events are roots of the dense output by TOMS 748 (event_root.hpp): while rocking on the pieces between
// turning points of theta, while pivoting on 4 equal parts of each step (a vertex that left the ground inside a part
// is located by its highest point, then the root after it). The quaternion is normalised at each mode change; R is
// formed from q / |q| (the exact flow keeps |q| = 1; the drift is of the order of the tolerance). Approximations
// (docs/method.md): a sign change that begins and ends inside one part is missed; the max tilt over the static limit
// (and, while pivoting, the first time it passes 1) is evaluated at the located tilt maxima and step ends.
#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "topple/bodies/body.hpp"
#include "topple/core/units.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding2d.hpp"

namespace topple {

/// A rigid body with a convex polygonal base, for the three-dimensional engine (frames in the header).
struct RigidBody3D {
  std::vector<std::array<double, 2>> base_xy_m;  ///< base polygon in the body frame (z = 0), counter-clockwise
  Vec3 centre_of_mass_m{};                       ///< c in the body frame; c_z = h > 0
  std::array<Vec3, 3> inertia_cm_m2{};           ///< J = I_cm / m about c, body axes, m^2 (symmetric)

  /// A uniform box: width along x, depth along y, height (m, > 0, <= kMaxBodyDimension_m), base centred at the
  /// origin. Throws InputError naming "width", "depth" or "height".
  [[nodiscard]] static RigidBody3D box(double width_m, double depth_m, double height_m);
  /// Any body: checks the polygon (>= 3 vertices, finite, convex, counter-clockwise, no repeated vertex), c inside it
  /// in plan (strictly) with h > 0, J symmetric and positive definite with the triangle inequalities of principal
  /// moments. Throws InputError naming "base", "centre_of_mass" or "inertia".
  [[nodiscard]] static RigidBody3D polygon(std::vector<std::array<double, 2>> base_xy_m, Vec3 centre_of_mass_m,
                                           std::array<Vec3, 3> inertia_cm_m2);
  /// The body of a mesh as posed (bodies/body.hpp): its support polygon, its centre of mass above the support plane,
  /// its inertia per unit mass. The body frame is the mesh's frame shifted down to the support plane.
  [[nodiscard]] static RigidBody3D from_mesh(const MeshBody& body);
  /// This body turned by angle_rad about the vertical through the body frame's origin (a test of frame
  /// independence).
  [[nodiscard]] RigidBody3D rotated_about_vertical(double angle_rad) const;

  [[nodiscard]] double height_m() const noexcept { return centre_of_mass_m[2]; }
  /// The static tilt limit toward plan direction azimuth (clockwise from north) atan(b / h), b = the base's extent
  /// beyond c in that direction (its support function): the tilt at which c passes over the base's edge or vertex.
  [[nodiscard]] double static_tilt_limit_rad(double azimuth_deg) const;
};

struct Rigid3DOptions {
  double g_m_s2 = kStandardGravity;
  RestitutionMode restitution = RestitutionMode::housner;
  double e = 1.0;                        ///< given: the kinetic-energy ratio at an impact is e^2, e in [0, 1]
  double rel_tol = 1e-8;                 ///< Dormand-Prince relative tolerance per step
  double abs_tol = 1e-12;                ///< absolute, on the state scaled by alpha and p alpha (as rocking.hpp)
  double rest_energy_fraction = 1e-8;    ///< rest rule (header), in (0, 1)
  /// Impact law (header): at a touch-down, vertices within this fraction of the body's size (its largest distance
  /// from c to a vertex) of the ground join the impact, in [0, 0.01]; 1e-5: a base within about 1e-5 rad of flat
  /// lands flat (one impact, as Moreau-Jean time stepping resolves it); 0: strictly successive impacts
  double simultaneous_contact = 1e-5;
  double max_run_out_s = 60.0;           ///< after the record, still ground, until rest, fall or this long, s
  std::size_t max_steps = 100'000'000;   ///< integrator steps (accepted and rejected); StepLimitError past it
  bool record_history = false;           ///< fill Rigid3DResult::history
  /// Coulomb friction in the base plane (docs/method.md, "Sliding in three dimensions"). Absent (the default): no
  /// contact point slides (friction large enough), today's engine bit for bit. Given: the body at rest sticks while
  /// |a_h| <= mu_s (g + a_z) and slides otherwise, flat and without spin, as sliding2d.hpp's block (stated below).
  std::optional<double> mu_s;
  std::optional<double> mu_k;            ///< kinetic friction, 0 <= mu_k <= mu_s; absent: mu_s (needs mu_s)
  Sliding2dOptions sliding{};            ///< tolerances of the sliding phases (sliding2d.hpp's defaults)
  /// An inclined base (docs/method.md, "An inclined base"): the plane's inclination beta, degrees in [0, 90); 0 (the
  /// default): level, today's engine bit for bit. The engines work in the base's frame (below).
  double base_incline_deg = 0.0;
  /// The plane's downhill direction seen from above (its fall line), degrees clockwise from north; finite; unused
  /// when base_incline_deg = 0.
  double base_incline_azimuth_deg = 0.0;
};

/// sliding: the base flat on the ground, slipping; slide_rock: on one or two base vertices of which at least one
/// slips; flight: no contact (these three only with friction given, Rigid3DOptions::mu_s).
enum class Rigid3DMode : std::uint8_t { rest, rocking, pivot, fallen, sliding, slide_rock, flight };
/// "rest", "rocking", "pivot", "fallen", "sliding", "slide_rock", "flight"
[[nodiscard]] std::string_view rigid3d_mode_name(Rigid3DMode mode);

/// A mode entered at time_s, with its contact: rocking: the edge (vertex_a, vertex_b = vertex_a + 1, indices into
/// base_xy_m); pivot: the vertex vertex_a (vertex_b = -1); others -1, -1.
struct Rigid3DModeChange {
  double time_s = 0.0;
  Rigid3DMode mode = Rigid3DMode::rest;
  int vertex_a = -1;
  int vertex_b = -1;
};

struct Rigid3DSummary {
  bool overturned = false;
  std::optional<double> overturn_time_s;
  double overturn_azimuth_deg = 0.0;     ///< the direction the top fell toward, clockwise from north
  double max_tilt_rad = 0.0;             ///< largest angle between the body's z axis and the vertical
  double max_tilt_azimuth_deg = 0.0;     ///< the direction of that tilt (toward which the top leans)
  double max_tilt_time_s = 0.0;
  /// max over time of tilt / static limit atan(b(u) / h) toward u, the body's plan direction that tips toward the
  /// tilt's direction d (R u = d cos(tilt) - z sin(tilt)); an edge: tilt / alpha_e (the planar theta / alpha)
  double max_tilt_over_limit = 0.0;
  /// first time the tilt passed the static limit of its direction (rocking: located, theta = alpha_e; pivoting:
  /// at the located tilt maxima and step ends)
  std::optional<double> exceeded_limit_time_s;
  std::size_t impacts = 0;
  std::size_t uplifts = 0;               ///< departures from rest
  std::optional<double> uplift_time_s;
  double energy_lost_j_per_kg = 0.0;     ///< to impacts and the rest rule
  /// first instant the vertical contact force vanished: without friction the contact is kept (a limit); with friction
  /// given (Rigid3DOptions::mu_s) the first instant of a modelled flight
  std::optional<double> flight_time_s;
  std::vector<Rigid3DModeChange> modes;  ///< every mode entered, in order (the first: rest at the start)
  // Sliding (zero unless Rigid3DOptions::mu_s is given):
  double residual_slide_east_m = 0.0;    ///< the base's displacement on the ground at the end, east
  double residual_slide_north_m = 0.0;   ///< same, north
  /// the largest horizontal distance of the base from where it started over the run (the excursion a sliding
  /// observation's "slid" / "not_slid" is scored on, as sliding2d.hpp's max |u|): while the base is flat, of its
  /// reference point (the body frame's origin, whose end position is the residual slide); while the body stands on one
  /// or two base vertices, of those contact vertices (the planar coupled model's u, the pivot corner's slide,
  /// slide_rock.hpp: tilting about a contact that sticks adds nothing); not updated in flight. Taken at the sliding
  /// solver's rows (its max |u| where the base never lifts) and the contact engine's step ends and events.
  double max_slide_m = 0.0;
  double max_slide_speed_m_s = 0.0;      ///< largest sliding speed |w| of the base on the ground
  double slide_path_length_m = 0.0;      ///< length of the base's track on the ground
  double friction_energy_j_per_kg = 0.0; ///< dissipated by kinetic friction (not in energy_lost_j_per_kg)
  int slip_episodes = 0;                 ///< slip starts from sticking
  std::optional<double> first_slip_time_s;
  /// the first time slide-rock began: a contact vertex slipping while the base is not flat (modelled, rigid3d_contact.cpp;
  /// the run goes on)
  std::optional<double> slide_rock_time_s;
  double slide_rock_duration_s = 0.0;    ///< time spent in slide-rock (friction given)
  std::size_t flights = 0;               ///< entries into flight (friction given)
  double flight_duration_s = 0.0;        ///< time spent in flight (friction given)
  /// the body's rotation about the vertical at the end, degrees counter-clockwise seen from above (the heading of its
  /// x axis; friction given: twist happens while a contact slips)
  double residual_yaw_deg = 0.0;
  /// contact modes with no or several consistent solutions (Painleve's paradox, docs/method.md): resolved by a
  /// tangential impact or a held contact
  std::size_t painleve_events = 0;
  double end_time_s = 0.0;
  Rigid3DMode end_mode = Rigid3DMode::rest;
  std::size_t steps = 0;
  std::vector<std::string> warnings;
};

/// On the record's samples and at every event (the state after it).
struct Rigid3DHistory {
  std::vector<double> time_s;
  std::vector<Vec3> position_m;          ///< the body frame's origin in the ground frame
  std::vector<Quaternion> orientation;   ///< q (w, x, y, z): body -> ground
  std::vector<Vec3> angular_velocity_rad_s;  ///< in the ground frame
  std::vector<double> energy_j_per_kg;   ///< kinetic (relative to the ground) + g (z_c - h)
  std::vector<Rigid3DMode> mode;
};

struct Rigid3DResult {
  Rigid3DSummary summary;
  Rigid3DHistory history;
};

/// The three-dimensional engine's options from a planar rocking body's (the settings the two share: g, restitution
/// and e, rel_tol, max_run_out_s, max_steps; no friction), as `topple rock --model 3d` copies them: how sweeps,
/// fragility and the three-component survey run a `model = "3d"` object with its planar options.
[[nodiscard]] Rigid3DOptions rigid3d_options(const RockingOptions& rocking);

/// The response to ground accelerations along x (east; required), y (north) and z (up) (m/s^2; null: absent). The
/// components may have different grids (the union is used, input_grid.hpp). Throws InputError for a bad option or
/// g + a_z <= 0 ("vertical").
[[nodiscard]] Rigid3DResult rock3d(const GroundMotion& x, const GroundMotion* y, const GroundMotion* z,
                                   const RigidBody3D& body, const Rigid3DOptions& options = {});

}  // namespace topple
