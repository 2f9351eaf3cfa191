#pragma once
// A field survey: what was seen at one or more sites after an earthquake (thesis section 1.1).
//
// At each site, a field engineer notes household objects that slid (and how far), rocked, toppled or stayed put,
// with their sizes, the surfaces they stood on and how sure the observation is. Read from a TOML file by
// io::read_survey (topple/io/survey_file.hpp); inverted by topple/inversion/inversion.hpp.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "topple/motion/ground_motion.hpp"
#include "topple/bodies/rocking_body.hpp"

namespace topple {

struct RigidBody3D;  // solvers/rigid3d.hpp: a body with a convex polygonal base in three dimensions

/// A quantity known as a value (low == high) or a range [low, high], sampled uniformly in the inversion. The ends are
/// in the unit of the field that holds the interval (all of them dimensionless today: mu, e, amplification).
struct Interval {
  double low = 0.0;   ///< in the holder's unit
  double high = 0.0;  ///< in the holder's unit
  [[nodiscard]] bool is_value() const noexcept { return low == high; }
  [[nodiscard]] double mid() const noexcept { return 0.5 * (low + high); }
};

enum class Outcome {
  overturned,      ///< toppled: |theta| reached pi/2
  not_overturned,  ///< stood (it may have rocked)
  rocked,          ///< visibly rocked (max |theta| >= kVisibleRockingRad) but stood
  slid,            ///< slid: a distance (value +- uncertainty), at least a distance, or just "slid" (>= kVisibleSlipM)
  not_slid,        ///< did not slide (max |d| < kVisibleSlipM)
  not_rocked,      ///< stood and did not visibly rock (max |theta| < kVisibleRockingRad)
  // Outcomes of an object that can both slide and rock, simulated with the coupled model (slide_rock.hpp; the rule:
  // object_model below; the definitions from the solver's results: docs/survey.md and inversion.hpp, coupled_match).
  slid_stood,      ///< stood, and its base moved (max |u| >= kVisibleSlipM): "slid 3 cm and stood" (distance as slid)
  slid_toppled,    ///< toppled, and its base had slid visibly before it fell
  walked,          ///< stood, rocked visibly with impacts, and is offset (|residual u| >= kVisibleSlipM) without ever
                   ///< sliding flat on its base: the offset came from slips while rocking (slide-rock, impacts)
};

/// What "visibly" means (stated once, used for the outcomes above and in docs/method.md).
inline constexpr double kVisibleRockingRad = 0.01;  ///< 0.57 degrees of tilt at the peak
inline constexpr double kVisibleSlipM = 0.002;      ///< 2 mm

[[nodiscard]] std::string_view outcome_name(Outcome outcome);  ///< "overturned", "not_overturned", ...
/// True for slid_stood, slid_toppled, walked: observations of both motions, which only the coupled model makes.
[[nodiscard]] bool is_coupled_outcome(Outcome outcome) noexcept;

/// The model an object is simulated with in the inversion (docs/survey.md, "Objects that slide and rock").
///   slide:   the exact sliding block (sliding.hpp), two-way, level ground
///   rock:    Housner's rocking body on a base that does not slide (rocking.hpp)
///   coupled: the coupled slide-rock body (slide_rock.hpp) with mu_s = mu_k = the object's mu
///   three_d: the three-dimensional engine (rigid3d.hpp: rocking about any base edge, pivoting on a corner; with
///            friction_3d sliding and slide-rock too, and then the sliding and coupled outcomes) on the pair and the
///            vertical at the object's bearing; three-component surveys only, a box (a block with its depth), a
///            cylinder or a body from a mesh, `model = "3d"` only (never by the rule: docs/survey.md)
enum class ObjectModel { slide, rock, coupled, three_d };
[[nodiscard]] std::string_view object_model_name(ObjectModel model);  ///< "slide", "rock", "coupled", "3d"

enum class Evidence { certain, likely, reported };
[[nodiscard]] std::string_view evidence_name(Evidence evidence);
/// The chance that an observation is wrong (misreported, misremembered): certain 0.02, likely 0.10, reported 0.25.
/// The inversion scores a run that reproduces the observation 1 - eps, one that does not eps.
[[nodiscard]] double evidence_error_rate(Evidence evidence) noexcept;

/// A flexible support under an object (a shelf, an upper floor): a one-mode oscillator whose absolute acceleration
/// the object feels (flexible.hpp: support_motion, the decoupled analysis). Frequency and damping are values or
/// ranges, drawn per (motion k, object) as mu is, after mu, e and the amplification (docs/survey.md).
struct SupportFilter {
  Interval freq_hz;   ///< natural frequency of the support, Hz (> 0)
  Interval damping;   ///< its viscous damping ratio, decimal, in [0, 1)
};

struct ObservedObject {
  std::string id;
  std::string description;
  RockingBody body;            ///< nominal geometry (shape, a, h, D; asymmetric general: both pivots)
  std::optional<double> width_m, height_m, diameter_m;  ///< dimensions as given (for reports)
  /// A body from a 3-D scan (`mesh = "..."`): the mesh file (resolved against the survey file) and the azimuth of
  /// the plane of shaking in the mesh's frame (degrees clockwise from +y). Empty / none: the body was given by its
  /// dimensions. The body itself (general, asymmetric: b1, b2, h, inertia) is in `body`.
  std::string mesh_file;
  std::optional<double> mesh_azimuth_deg;
  /// A body from a 3-D scan: the pose it was given (bodies/pose.hpp), as the invert JSON and the report say it:
  /// "rest on face N (tilt T deg from the scan)" or "as-scanned" (`mesh_pose = "as-scanned"`, the earlier answer).
  std::string mesh_pose;
  Interval mu;                 ///< friction coefficient, dimensionless (value or range)
  bool e_housner = true;       ///< restitution from Housner's formula for the shape
  Interval e;                  ///< given restitution, dimensionless (value or range) when !e_housner
  std::string support = "ground";  ///< "ground", "furniture", "upper floor" (free text)
  Interval amplification{1.0, 1.0};  ///< support motion / ground motion, dimensionless (>= 1 for furniture, floors)
  /// The support's filter when it is flexible (`support = {freq_hz = ..., damping = ...}`, the object's own or its
  /// site's default); the amplification, if any, multiplies the filtered motion. None: a rigid support.
  std::optional<SupportFilter> support_filter;
  std::optional<double> orientation_deg;  ///< angle between the object's rocking plane and the shaking direction;
                                          ///< the rocking model sees cos(angle) of the motion (0 when unknown)
  /// Three-component surveys ([inversion] components = 3; docs/survey.md): the bearing across the object's narrow
  /// side, degrees clockwise from north, in [0, 360) (its rocking plane; a direction, so 10 and 190 are one bearing
  /// for a symmetric body). None: unknown, uniformly random (inversion_3c.hpp).
  std::optional<double> azimuth_deg;
  /// Outcome slid, three-component surveys: the direction the object moved (marks on the floor), degrees clockwise
  /// from north, in [0, 360). None: not seen.
  std::optional<double> slid_azimuth_deg;
  /// Three-component surveys, shape = "block": the block's other horizontal dimension (along bearing + 90), m. Given,
  /// the object is a box rocked about both pairs of base edges (oriented.hpp, OrientedBody::make). None: the block
  /// rocks along its bearing only, as before.
  std::optional<double> depth_m;
  /// Outcome overturned, three-component surveys, a cylinder or a box: the direction the object fell (a tombstone's,
  /// a column's), degrees clockwise from north, in [0, 360). None: not seen. (A block without depth falls along its
  /// bearing by the planar model: its fall direction says nothing more.)
  std::optional<double> toppled_azimuth_deg;
  Outcome outcome = Outcome::not_overturned;
  /// `model = "slide" | "rock" | "coupled" | "3d"` as the survey forces it; none: the rule (object_model).
  std::optional<ObjectModel> model;
  /// model = "3d": the body in three dimensions (the box of width, depth and height, or the mesh as posed, its +x
  /// axis along azimuth_deg), set by the reader. None for the other models.
  std::shared_ptr<const RigidBody3D> body_3d;
  /// model = "3d", a box or a mesh (`friction_3d = "mu"`): the engine's base may slide with Coulomb friction, mu_s =
  /// mu_k = the drawn mu (Rigid3DOptions::mu_s; as the coupled model takes mu). False (the default, `"none"`): the
  /// no-slip engine, as before the key. Needed for the sliding and coupled outcomes with model = "3d" (scored on the
  /// engine's run, inversion_3c.cpp; docs/survey.md).
  bool friction_3d = false;
  std::optional<double> slid_m;              ///< observed sliding distance (outcome slid or slid_stood)
  double slid_uncertainty_m = 0.0;           ///< its one-sigma uncertainty
  std::optional<double> slid_at_least_m;     ///< or: it slid at least this far
  Evidence evidence = Evidence::certain;
};

/// The model the inversion simulates `object` with. The rule (docs/survey.md, "Objects that slide and rock"):
/// the survey's `model` when given; otherwise the coupled model for an observation of both motions (slid_stood,
/// slid_toppled, walked), and for an observation of one motion the model that motion is about (slid, not_slid: the
/// sliding block; the others: the rocking body), as before the coupled model existed, so that a survey keeps its
/// meaning. io::read_survey refuses the combinations that make no sense (a coupled outcome with model = "slide" or
/// "rock", a rocking outcome with "slide", a sliding one with "rock"; slid_toppled or walked on a body that can never
/// lift: mu_s < min(b1, b2) / h over its whole range, Shenton 1996).
[[nodiscard]] ObjectModel object_model(const ObservedObject& object) noexcept;

/// What the survey's physics checks say of an object: the field it concerns ("model", "outcome", "mu") and why.
struct ObjectCheck {
  std::string field;
  std::string problem;
};

/// The survey's rules for the model of `object` in a survey of `components` (1 or 3) components, with the object's
/// model, outcome, body and mu already read: throws parameter_error(field, problem) for a combination that makes no
/// sense (object_model above; a coupled object in a three-component survey; model = "3d" outside a three-component
/// survey, or on a sliding or coupled outcome without friction_3d (field "model"), on a general body ("shape") or a
/// block without its depth ("depth"), friction_3d on a cylinder; slid_toppled or walked on a body that
/// slides before it can lift over its whole mu range, Shenton 1996, for the coupled model and model = "3d" alike) and
/// returns the warnings, kept values that the
/// user should know of (mu at or above the body's Painleve limit, slide_rock.hpp, painleve_friction_limit).
[[nodiscard]] std::vector<ObjectCheck> check_object_model(const ObservedObject& object, int components);

/// Housner's restitution of an object that strikes (the rocking model always, the coupled one when it can lift), with
/// the model, body, mu, e and depth already read: with e = "housner", 1 - 2a^2/D must not be negative (a body too
/// squat to rock onto its other edge, rocking.hpp, kSquatBodyAdvice), nor across a box (oriented.hpp: the other axis
/// is a block of width `depth`). Throws parameter_error("e" or "depth", problem).
void check_object_restitution(const ObservedObject& object);

/// An object given a bearing (azimuth_deg, three-component surveys), with its body read: a cylinder has no narrow
/// side and takes none. Throws parameter_error("azimuth_deg", problem).
void check_object_bearing(const ObservedObject& object);

/// An object given the direction it fell (toppled_azimuth_deg), with its body, depth and outcome read: only an
/// overturned cylinder, box or model = "3d" body tells the direction of the shaking by the way it fell (the planar
/// model of a block without depth falls along its bearing). Throws parameter_error("toppled_azimuth_deg", problem).
void check_object_fall_direction(const ObservedObject& object);

/// The macroseismic scales a site's intensity may be given on (docs/survey.md, "Macroseismic intensity"): MMI
/// (Modified Mercalli, as in USGS "Did You Feel It?") and EMS-98, taken as equal to MMI (Musson, Grunthal & Stucchi
/// 2010; region/intensity.hpp). JMA is not accepted: no sourced JMA-to-PGA conversion is implemented.
enum class IntensityScale { mmi, ems98 };

/// A macroseismic intensity observed at a site (issue 30): `intensity = 7.5`, `intensity_scale = "MMI"`,
/// `intensity_reports = 12`. It is evidence on the site's PGA through a ground-motion-to-intensity conversion
/// (region/intensity.hpp: Worden et al. 2012) with its sigma, widened for few reports as ShakeMap does.
struct SiteIntensity {
  double value = 0.0;                       ///< intensity on `scale`, in [1, 12] (decimals: an average of reports)
  IntensityScale scale = IntensityScale::mmi;
  std::optional<int> reports;               ///< the number of reports behind it (>= 1); none: not stated (taken as 1)
};

/// One measured member of a population's sample (docs/survey.md, "Populations"): its dimensions, m (a block: width and
/// height; a cylinder: diameter and height).
struct PopulationMember {
  std::optional<double> width_m, height_m, diameter_m;
};

/// A population (docs/survey.md, "Populations"; docs/method.md, "Populations of objects"): a class of similar objects
/// counted, not listed ("71 of 212 gravestones toppled; 20 of them measured"). Everything an object has but its size
/// and outcome is the class' (`prototype`: shape, mu, e, support, amplification, orientation, model, evidence); the
/// sizes are a stated range per dimension (uniform in it) or a measured sample; the outcomes are counts.
struct Population {
  std::string id;
  std::string description;
  std::string shape = "block";        ///< "block" or "cylinder"
  ObservedObject prototype;           ///< the class' shared keys; its body is the class' middle member's
  int count = 0;                      ///< objects in the class (>= 1)
  int overturned = 0;                 ///< of them, toppled
  std::optional<int> rocked;          ///< stood and visibly rocked (given: a category of the multinomial)
  std::optional<int> slid;            ///< stood and visibly slid (given: a category; the coupled model is used)
  std::vector<double> fallen_azimuths_deg;  ///< directions the toppled ones fell, deg clockwise from north
  std::optional<Interval> width_m, height_m, diameter_m;  ///< stated ranges, m (uniform in each)
  std::vector<PopulationMember> sample;                   ///< measured members (used instead of the ranges)
  int members = 16;                   ///< K, the representative members simulated (`members` key, 1 to 200)
  std::size_t line = 0;               ///< where the population starts in the survey file (for messages)
};

struct Site {
  std::string name;
  std::optional<double> lat_deg, lon_deg;
  std::string notes;
  /// The site's default flexible support (`support = {...}` in [site] / [[sites]]): objects without a `support` key
  /// of their own stand on it (io::read_survey copies it into their support_filter).
  std::optional<SupportFilter> support_filter;
  std::vector<ObservedObject> objects;
  /// Populations of similar objects counted, not listed (Population); inverted with the objects.
  std::vector<Population> populations;
  /// Objects or populations: something observed to invert.
  [[nodiscard]] bool has_observations() const noexcept { return !objects.empty() || !populations.empty(); }
  /// An instrument station (docs/survey.md, "Regional surveys"): the PGA an accelerograph measured here, in g, given
  /// as `pga_g = ...` or read from `record = "file"` (the record's peak |a| over g_m_s2, set by
  /// io::load_survey_records). Such a site may have no objects; if it has some, they are inverted alone and checked
  /// against it (a calibration site). None: no instrument.
  std::optional<double> instrument_pga_g;
  std::string instrument_record;  ///< the record's path (resolved against the survey file), empty when none
  /// [site] vs30_m_s, or site_class "A".."E" mapped to a stated Vs30 (survey_file.cpp, docs/survey.md), m/s: the
  /// site's time-averaged shear-wave velocity of the top 30 m, used by the earthquake prior's ground-motion model
  /// (inversion/prior.hpp). None: not given.
  std::optional<double> vs30_m_s;
  /// The epicentral distance from [event] epicentre to the site's lat/lon (geodesic, WGS84), km; set by the reader
  /// when both are given. None: unknown.
  std::optional<double> epicentral_distance_km;
  /// A macroseismic intensity observed here (SiteIntensity). Such a site may have no objects (it enters the regional
  /// fit only, as a station does); with objects, the report says whether the two agree. None: no intensity.
  std::optional<SiteIntensity> intensity;
  [[nodiscard]] bool is_station() const noexcept { return instrument_pga_g.has_value() || !instrument_record.empty(); }
};

/// The motions the inversion explores. synthetic: Clough-Penzien filtered noise (synthesis.hpp), the default;
/// rezaeian2010: the record-like family of Rezaeian & Der Kiureghian (2010) (synthesis.hpp, docs/method.md);
/// records: the survey's own records; boore2003: the stochastic point-source method of Boore (2003), motions from an
/// earthquake's magnitude and distance (stochastic.hpp, docs/method.md); mixture: Bayesian model averaging over
/// synthetic and boore2003 with prior weights 1/2 each, half of each cell's motions from each (inversion.hpp,
/// FamilyGrid; docs/method.md, "A mixture of the two families").
enum class MotionFamily { synthetic, records, rezaeian2010, boore2003, mixture };
/// "synthetic", "records", "rezaeian2010", "boore2003", "mixture": the names a survey's `family` key takes.
[[nodiscard]] std::string_view motion_family_name(MotionFamily family);

/// The prior on (PGA, predominant frequency) (docs/method.md, "Priors"; inversion/prior.hpp). log_uniform: uniform
/// in log PGA and log frequency over the grid (the default; old surveys keep their answer bit for bit). earthquake:
/// from a ground-motion model (BSSA14) and a mean-period model (Bray & Rathje 1998), over weak priors on M and R,
/// or at the event's M and each site's distance when [event] magnitude is given.
enum class InversionPrior { log_uniform, earthquake };
/// "log-uniform", "earthquake": the names the survey's [inversion] prior key takes and the JSON's "prior" says.
[[nodiscard]] std::string_view inversion_prior_name(InversionPrior prior);

/// The earthquake, as the prior sees it ([event] magnitude, depth_km): set by the reader when a magnitude is given.
struct EventSource {
  double magnitude = 0.0;  ///< moment magnitude M
  double depth_km = 0.0;   ///< hypocentre depth, km (0 when not given)
};

/// How the inversion explores the shaking (defaults as documented in docs/method.md).
struct InversionSettings {
  MotionFamily family = MotionFamily::synthetic;
  std::vector<std::string> records;      ///< family = records: paths (relative to the survey file, resolved)
  /// family = records: the records themselves, in the order of `records`, loaded at the edge (io::read_survey); the
  /// inversion core reads no file.
  std::vector<std::shared_ptr<const GroundMotion>> record_motions;
  double pga_min_g = 0.02, pga_max_g = 2.0;
  int pga_count = 30;
  double freq_min_hz = 0.3, freq_max_hz = 20.0;
  int freq_count = 25;
  int motions_per_cell = 40;             ///< synthetic family: N motions per cell (records: 2 per record)
  std::uint64_t seed = 1;
  double duration_s = 20.0;              ///< synthetic motions' length
  double g_m_s2 = kStandardGravity;
  /// 1: today's one-component model (the default; old surveys keep their meaning bit for bit). 3: two horizontal
  /// components and a vertical, oriented objects, bidirectional sliding and the direction of strongest shaking
  /// (inversion_3c.hpp, docs/method.md "Inversion in three components"). Only the synthetic family.
  int components = 1;
  /// components = 3: the correlation coefficient of the two horizontal white noises (synthesis.hpp,
  /// SynthesisSetSpec::coherence), in [0, 0.95]: 0 independent components, larger values a motion polarised along
  /// its major axis (major/minor r.m.s. ratio sqrt((1 + rho) / (1 - rho))).
  double coherence = 0.0;
  /// components = 3: the number of bins of the direction of strongest shaking over [0, 180) deg (4 to 72; 12 is
  /// 15 deg bins).
  int directions = 12;
  /// How the survey's record files (`records`, and the sites' instrument `record`s) are read: [inversion]
  /// record_format, record_units, record_dt_s, record_columns, record_separator, record_baseline (docs/survey.md),
  /// as the CLI's --format, --units, --dt, --columns, --separator, --baseline; checked when the survey is parsed,
  /// applied by io::load_survey_records. Empty: the reader's default.
  std::string record_format, record_units, record_columns, record_separator, record_baseline;
  std::optional<double> record_dt_s;
  /// [inversion] prior (see InversionPrior).
  InversionPrior prior = InversionPrior::log_uniform;
  /// [event] magnitude (and depth_km), copied here by the reader for the earthquake prior; none: unknown event.
  std::optional<EventSource> event;
};

struct Survey {
  std::string source_file;
  std::vector<Site> sites;
  InversionSettings inversion;
  std::optional<double> epicentre_lat_deg, epicentre_lon_deg;
  std::optional<double> epicentre_depth_km;  ///< [event] depth_km: the hypocentre's depth, km (>= 0); none: 0 is used
  /// What the reader applied by a documented rule that changes a given value (the sliding-uncertainty floor), one
  /// "file:line: field: text" line each, for the front ends to show.
  std::vector<std::string> notes;
  /// Values accepted as given that the user should check (a coupled object's friction at or above its Painleve limit,
  /// slide_rock.hpp), one "file:line: field: text" line each; the CLI prints them and adds them to its JSON.
  std::vector<std::string> warnings;
};

}  // namespace topple
