#pragma once
// The standard sweep: records and pulses against sliding blocks and rocking bodies (what `topple sweep` runs).
//
// A SweepSpec (built in code, or read from a sweep file by topple/io/sweep_file.hpp) says which motions and which
// objects; make_plan turns it into the runs of a generic ensemble plan (topple/ensemble/ensemble.hpp), whose run function
// calls the solvers. This is where physics meets the engine: the engine itself knows only runs, chunks and stores.
// The types stay in namespace topple::ensemble, where callers have always found them.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "topple/ensemble/ensemble.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple::ensemble {

/// A record read from a file (or built in code).
struct RecordInput {
  std::string name;                          ///< the "motion" column, e.g. the path as the sweep file matched it
  std::shared_ptr<const GroundMotion> motion;
};

/// One station's components read together (motion_set.hpp): two horizontal components with known azimuths and an
/// optional vertical, merged on one grid. Rocking objects run on it as oriented objects (oriented.hpp) at each of
/// SweepSpec::bearings_deg; sliding objects as bidirectional sliders (sliding2d.hpp; two-way, level ground), the
/// same run at every bearing (friction is isotropic). Scaling applies to the set as a whole: the factor that scales the first component
/// (to a target PGA, or a plain factor) scales every component, as `topple rock H1 --h2 H2 --scale-pga` does;
/// time scaling applies to all; polarity "inverse" flips the horizontal components (the vertical keeps its sign).
struct RecordSetInput {
  std::string name;                       ///< the "motion" column: "H1+H2" or "H1+H2+V", the paths as given
  std::shared_ptr<const MotionSet> set;   ///< with its second component and azimuths
};

/// An analytic pulse (pulses.hpp). Its amplitude and duration are its own, so sweep scaling (scales, time_scales)
/// does not apply to it; polarity does.
struct PulseInput {
  std::string name;  ///< the "motion" column, e.g. "sine amp_g=0.2 freq_hz=1"
  PulseSpec spec;
};

/// How records are scaled: each record is run once per ScaleSpec.
struct ScaleSpec {
  enum class Kind : std::uint8_t { none, factor, pga };
  Kind kind = Kind::none;
  double value = 1.0;  ///< factor (dimensionless) or target PGA (m/s^2)
};

/// A friction block (sliding.hpp). `slope_deg` is the inclination as given, for the slope_deg column
/// (block.slope_rad = slope_deg * pi / 180, as `topple slide --slope-deg` computes it).
struct SlideObject {
  SlidingBlock block;
  double slope_deg = 0.0;
  /// A flexible support under the object (shelf, floor): the object runs on the support's absolute acceleration
  /// (flexible.hpp: support_motion, the decoupled analysis; the mass ratio is not used). None: rigid, as before.
  std::optional<SupportOscillator> support = std::nullopt;
};

/// A rocking body (rocking.hpp). The dimension columns hold what was given: width and height for a block, diameter
/// and height for a cylinder; an asymmetric general body's b1, b2, h come from `body`, its inertia is kept as given.
struct RockObject {
  RockingBody body;
  RockingOptions options;
  std::optional<double> width_m;
  std::optional<double> height_m;
  std::optional<double> diameter_m;
  std::optional<double> inertia_m2 = std::nullopt;  ///< asymmetric general body: I_cm / m as given (or from the mesh), m^2
  std::string mesh = {};             ///< a body from a mesh: the file as the sweep file names it (empty: none)
  std::optional<double> mesh_azimuth_deg = std::nullopt;  ///< and the azimuth of its plane of shaking, degrees
  std::string mesh_pose = {};        ///< and the pose it was given: "rest" or "as-scanned" (bodies/pose.hpp)
  std::optional<SupportOscillator> support = std::nullopt;  ///< as SlideObject::support
  /// A block's other horizontal dimension, m: a box checked about both axes (oriented.hpp). Record sets only.
  std::optional<double> depth_m = std::nullopt;
  /// The coupled slide-rock model (slide_rock.hpp) instead of Housner's rocking (model = "coupled" in a sweep file):
  /// SlideRockBody::from_rocking(body, *options.mu, mu_kinetic), run with slide_rock_options(options). options.mu
  /// (the static friction coefficient) is then required. Single records and pulses only.
  bool coupled = false;
  std::optional<double> mu_kinetic = std::nullopt;  ///< coupled: kinetic friction (none: options.mu)
  /// The three-dimensional engine (rigid3d.hpp: rocking about base edges and pivoting on corners) instead of the
  /// planar models (model = "3d" in a sweep file): a box (a block with depth_m) or a body from a mesh as posed, run
  /// by rock3d under each record set with its +x axis at the bearing (as `topple rock --model 3d --h2
  /// --bearing-deg`), with options.g_m_s2, restitution, e, rel_tol, max_run_out_s and max_steps. `body` stays the
  /// planar body (its columns). Record sets only; no support. Friction: options.mu (Rigid3DOptions::mu_s) and
  /// mu_kinetic (mu_k), absent: the no-slip engine (rigid3d.hpp).
  std::optional<RigidBody3D> body_3d = std::nullopt;
  /// model = "3d" for a solid cylinder: the rim engine (rigid3d_disc.hpp, rock3d_cylinder) under the pair along east
  /// and north and the vertical. Axisymmetric: the bearing does not enter (each bearing's row is the same run).
  /// Friction as body_3d's (options.mu, mu_kinetic; rigid3d_disc.hpp's friction); absent: rolling without slip.
  std::optional<CylinderBody3D> cylinder_3d = std::nullopt;
  /// A three-dimensional object (model = "3d"): body_3d or cylinder_3d.
  [[nodiscard]] bool three_d() const noexcept { return body_3d.has_value() || cylinder_3d.has_value(); }
};

using ObjectSpec = std::variant<SlideObject, RockObject>;

struct SweepSpec {
  std::vector<RecordInput> records;
  std::vector<PulseInput> pulses;
  std::vector<double> time_scales{1.0};  ///< records only
  std::vector<ScaleSpec> scales{ScaleSpec{}};  ///< records only
  std::vector<bool> inverse{false};     ///< polarities, records and pulses: false = "normal", true = "inverse"
  std::vector<ObjectSpec> objects;
  std::vector<RecordSetInput> record_sets;  ///< stations of two or three components
  /// The objects' bearings (degrees clockwise from north) under the record sets: each set is run at each bearing.
  /// Required with record sets unless every object is a cylinder (taken in its worst direction, oriented.hpp) or a
  /// sliding object.
  std::vector<double> bearings_deg;
  OrientationOptions orientation;       ///< the cylinder's direction grid under record sets
  double g_m_s2 = kStandardGravity;     ///< for the *_g columns and amplitudes in g
  std::size_t chunk_runs = 0;           ///< 0 = default
};

/// Expands the spec (motions: records x time scales x scales x polarities, then pulses x polarities, then record
/// sets x bearings x time scales x scales x polarities; objects in the given order) into a plan whose run function
/// calls slide_summary / slide_summaries and rock_summary, and under a record set rock_oriented_summary and
/// slide_2d_summary.
///
/// Columns, present when some run uses them:
///   motion: motion, [pulse_kind, pulse_amp_g, pulse_duration_s], time_scale, scale_factor, pga_g, polarity,
///           [bearing_deg] (only with record sets: a sweep without one has the columns it always had; pga_g of a
///           set is its first component's)
///   object: model, g_m_s2, [mu, mu_kinetic, slope_deg, mode], [shape, width_m, height_m, diameter_m, (a_m, h_m,
///           D_m2), (b1_m, b2_m, h_m, inertia_m2: asymmetric bodies), (mesh, mesh_azimuth_deg, mesh_pose: bodies from meshes),
///           restitution],
///           [support_freq_hz, support_damping] (only when some object has a flexible support: a sweep without one
///           has the columns it always had; a rigid object's cells there are empty), [depth_m] (only when some
///           object is a box)
///           (mu also holds the friction coefficient a rocking body's onset check uses)
///   results: sliding: max_abs_displacement_m, max_displacement_time_s, residual_displacement_m,
///            max_abs_velocity_m_s, slip_episodes, first_slip_time_s, total_slip_duration_s, end_time_s,
///            at_rest_at_end, contact_lost_time_s, yield_down_g, yield_up_g (present when sliding objects run under
///            single records or pulses);
///            bidirectional sliding under a record set (kSliding2dFields' sweep fields, as `topple slide --h2 --json`
///            names them): residual_displacement_m (|u|), residual_azimuth_deg, residual_east_m, residual_north_m,
///            max_abs_displacement_m (max |u|), max_displacement_time_s, path_length_m, max_abs_velocity_m_s (peak
///            |w|), slip_episodes ... contact_lost_time_s; the names 1-D rows have are the same columns, the others
///            are added only when sliding objects run under a set (a 2-D row leaves yield_down_g, yield_up_g empty,
///            a 1-D row the 2-D-only cells);
///            rocking: max_abs_rotation_rad, max_rotation_over_alpha, max_rotation_time_s, max_abs_theta_dot_rad_s,
///            impacts, uplifts, uplift_time_s, exceeded_alpha_time_s, overturned, overturn_time_s,
///            energy_lost_j_per_kg, end_time_s, end_state, still_rocking_at_end, onset_mode, critical_mu,
///            alpha_rad, p_rad_s, e; under a record set they are the governing direction's, and
///            [governing_azimuth_deg, governing_axis] (only with record sets) say which it was; then, only when some
///            body is asymmetric, the per-side results (kRockingSideFields: alpha_negative_rad ... overturned_side)
///            coupled slide-rock objects (model "coupled"; only when some object is one): kSlideRockFields in their
///            order (overturned ... used_sliding_kernel), less mu_static, mu_kinetic, g_m_s2 and e_mode, which are
///            object columns (mu, mu_kinetic, g_m_s2, restitution); a name a rocking column has is that column;
///            three-dimensional objects (model "3d"; only when some object is one): kRigid3DFields in their order
///            (overturned, overturn_time_s, overturn_azimuth_deg, max_tilt_rad, max_tilt_azimuth_deg,
///            max_tilt_time_s, max_tilt_over_limit, exceeded_limit_time_s, impacts, uplifts, uplift_time_s,
///            energy_lost_j_per_kg, flight_time_s, end_time_s, end_mode); a name a rocking column has is that column
///            (a 3-D row leaves the planar-only cells empty, a planar row the 3-D-only ones); then, only when some
///            3-D object has friction (mu), residual_slide_east_m, residual_slide_north_m, max_slide_speed_m_s,
///            slide_path_length_m, friction_energy_j_per_kg, slip_episodes, first_slip_time_s, slide_rock_time_s
///            (a name a sliding column has is that column)
/// Throws InputError for an empty spec (no motion or no object), a motion that cannot be scaled (zero record), a
/// one-way or inclined sliding object under a record set (fields "object[k].mode", "object[k].slope_deg"), a flexible
/// support under a record set, a box (depth) under a single record or pulse, a coupled object without mu or under a
/// record set ("object[k].model"), a three-dimensional object under a single record or pulse ("object[k].model"),
/// or with friction out of range, or on a cylinder, or mu_kinetic without mu ("object[k].mu", "object[k].mu_kinetic"),
/// record sets with rocking objects other than cylinders and
/// without bearings (field "bearing"), or a bearing without record sets.
[[nodiscard]] Plan make_plan(const SweepSpec& spec);

/// A rocking object of a sweep with Housner's restitution (e = "housner"): 1 - 2a^2/D must not be negative (a body
/// too squat to rock onto its other edge, rocking.hpp, kSquatBodyAdvice). Throws parameter_error("e", problem); the
/// sweep reader calls it for each body and places the error at the file's line.
void check_housner_restitution(const RockingBody& body);

/// A record set under a motion case's transform: `first` is the engine's transform of set.first() (the case's base
/// motion); the second component gets the same transform, the vertical the same without the inversion (it keeps its
/// sign: polarity flips the horizontal shaking). The sweep's set cases and the fragility of pairs use it.
[[nodiscard]] MotionSet transformed_set(const MotionSet& set, const MotionTransform& transform,
                                        const GroundMotion& first);

}  // namespace topple::ensemble
