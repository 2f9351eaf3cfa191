#pragma once
// Numpy-style docstrings of topple._core (what `help(topple.X)` shows), kept apart from the bindings so that
// module.cpp stays readable. Every parameter and returned value names its unit; python/tests/test_docstrings.py
// checks that each public name has Parameters / Returns sections and that unit-suffixed names (_m, _s, _g, _hz ...)
// are documented with their unit. The stubs (python/topple/__init__.pyi) carry each docstring's first line.
// The rocking solver's options, shared by rock, overturning_map and fragility (adjacent literals concatenate).
#define TOPPLE_DOC_ROCKING_SOLVER                                                  \
  "g : float\n    Gravity, m/s^2.\n"                                              \
  "method : {\"adaptive\", \"rk4\"}\n    Integrator of the rocking motion between events.\n" \
  "rel_tol : float\n    Relative tolerance of the adaptive integrator (dimensionless).\n" \
  "rk4_substeps : int\n    RK4 steps per record interval.\n"                       \
  "max_run_out_s : float\n    Longest time the body is followed after the record ends, s.\n"

namespace topple::python::doc {

inline constexpr const char* input_error = R"(Bad caller input (file, parameter, array value).

str() is the message the CLI prints after "topple: error: ". A missing file raises the subclass
topple.MissingFileError, which is also a FileNotFoundError.

Attributes
----------
file : str or None
    Path as given, when the problem is in a file.
line : int or None
    1-based line in that file.
field : str or None
    Parameter, key or column name ("mu", "dt_s", "NPTS", "width").
problem : str
    The message without its location.
)";

inline constexpr const char* missing_file_error = R"(A file that does not exist (or cannot be opened).

Both a topple.InputError (the CLI's message) and a FileNotFoundError.

Attributes
----------
file : str
    Path as given.
line : int or None
    1-based line, when known (usually None).
field : str or None
    The parameter or key that named the file, when known.
problem : str
    The message without its location.
errno : int
    errno.ENOENT.
filename : str
    Path as given (as FileNotFoundError has it).
)";

inline constexpr const char* ground_motion =
    R"(One component of ground acceleration, piecewise linear between samples (SI).

GroundMotion(accel, dt=None, units="g", *, time=None, start_time_s=0.0, g=9.80665)

Parameters
----------
accel : numpy.ndarray of float64 or sequence of float
    Acceleration samples, 1-D, in `units`. Another dtype raises TypeError (convert explicitly); a strided array is
    copied. NaN or Inf raise topple.InputError.
dt : float, optional
    Sample interval, s, for uniform samples (> 0). Give either dt or time.
units : str
    Unit of `accel`: "g" (of `g` below), "m/s2", "cm/s2", "gal" or "mm/s2".
time : numpy.ndarray of float64 or sequence of float, optional
    Sample times, s, non-decreasing, for irregular samples (a repeated time is a jump).
start_time_s : float
    Time of the first sample, s, for uniform samples.
g : float
    Gravity, m/s^2, for units="g", and the g of accel_g / pga_g (default standard gravity 9.80665 m/s^2).

Attributes
----------
npts : int
    Number of samples.
is_uniform : bool
    True when the samples are equally spaced.
dt_s : float
    Sample interval, s (mean interval of an irregular record).
start_time_s, end_time_s, duration_s : float
    First and last sample times and their difference, s.
accel_m_s2 : numpy.ndarray
    Acceleration, m/s^2: a read-only view on the C++ data (no copy).
accel_g : numpy.ndarray
    Acceleration in the motion's own g (g_m_s2), a new array.
time_s : numpy.ndarray
    Sample times, s (a new array).
pga_m_s2 : float
    Peak ground acceleration max |a|, m/s^2.
pga_g : float
    Peak ground acceleration in the motion's own g (g_m_s2), g.
g_m_s2 : float
    The g the motion was built or read with, m/s^2; operations (scaled, inverted ...) keep it.
pga_time_s : float
    Time of the peak, s.
metadata : dict
    format, source_file, event, station, component (str), azimuth_deg (float, None when the file does not state
    it), vertical (bool), units_as_read (str): the fields of ``topple info --json``.
name : str
    The source file as given, else the event description (synthetic and pulse motions).
)";

inline constexpr const char* accel_at = R"(Acceleration at a time, by linear interpolation.

Parameters
----------
t_s : float
    Time, s (0 outside the record).

Returns
-------
float
    Acceleration, m/s^2.
)";

inline constexpr const char* scaled = R"(The motion with every acceleration multiplied by a factor.

Parameters
----------
factor : float
    Dimensionless factor (finite).

Returns
-------
GroundMotion
    The scaled motion (same times and g).
)";

inline constexpr const char* scaled_to_pga = R"(The motion scaled so that its PGA is `pga_g`.

Parameters
----------
pga_g : float
    Target peak ground acceleration, g (> 0).
g : float, optional
    Gravity, m/s^2, that `pga_g` is in (default: the motion's own g_m_s2).

Returns
-------
GroundMotion
    The scaled motion.
)";

inline constexpr const char* inverted = R"(The motion with its sign reversed (the other polarity).

Returns
-------
GroundMotion
    -a(t), same times.
)";

inline constexpr const char* time_scaled =
    R"(The motion compressed or stretched in time (frequencies multiplied by 1 / factor).

Parameters
----------
factor : float
    Dimensionless time factor (> 0): every time t becomes factor * t.

Returns
-------
GroundMotion
    The time-scaled motion (same accelerations).
)";

inline constexpr const char* trimmed = R"(The part of the motion between two times (interpolated at the ends).

Parameters
----------
t_begin_s : float
    Start time, s.
t_end_s : float
    End time, s (> t_begin_s).

Returns
-------
GroundMotion
    The trimmed motion.
)";

inline constexpr const char* resampled =
    R"(The motion resampled at a uniform interval (linear interpolation: exact for this motion).

Parameters
----------
dt_s : float
    New sample interval, s (> 0).

Returns
-------
GroundMotion
    The resampled motion.
)";

inline constexpr const char* baseline_corrected = R"(The motion with a least-squares polynomial baseline removed.

Parameters
----------
order : int
    Polynomial order (0: mean, 1: linear trend, ...).

Returns
-------
GroundMotion
    The corrected motion.
)";

inline constexpr const char* read = R"(Read a strong-motion record.

Formats: PEER .AT2, COSMOS V2, CSMIP V2, USGS SMC, K-NET, ESM and plain text, detected from content.

Parameters
----------
path : str
    The record file. A missing file raises topple.MissingFileError (a FileNotFoundError).
format : str, optional
    "auto" (default) or one of "peer-at2", "cosmos-v2", "csmip-v2", "knet", "usgs-smc", "esm", "plain".
units : str, optional
    Unit of a plain file's values ("g", "m/s2", "cm/s2", "gal", "mm/s2").
dt : float, optional
    Sample interval of a one-column plain file, s.
channel : int, optional
    1-based channel of a multi-channel file.
g : float
    Gravity, m/s^2, for values in g and for the motion's accel_g / pga_g (default 9.80665 m/s^2).
columns : str or (time, accel), optional
    Plain files: the time and acceleration columns, as `topple --columns` ('1,2', 'Time (s),Table Acc (g)',
    ',3' for no time column) or a pair of 1-based numbers or header names ((1, 2), ('Time (s)', 'Table Acc (g)'),
    ('', 3) for no time column). Other columns are ignored. See docs/formats.md.
separator : str
    Plain files: "auto" (default), "whitespace", "tab", "comma" or "semicolon".
baseline : str
    Offset removal of the record as read: "none" (default), "mean", "pre-event:T" (mean of the first T seconds),
    "poly:N" (least-squares polynomial of degree N = 0..3). See docs/method.md, "Baseline removal".

Returns
-------
GroundMotion
    The record, in m/s^2 inside.
)";

inline constexpr const char* sliding_result = R"(Sliding response of a rigid block (the result of topple.slide).

Summary attributes have the names and units of `topple slide --json`; json() returns that object. Histories are
empty when run with history=False.

Attributes
----------
max_abs_displacement_m : float
    Maximum |relative displacement|, m.
max_displacement_time_s : float
    Time of that maximum, s.
residual_displacement_m : float
    Relative displacement at the end, m (signed: + down-slope / positive direction).
max_abs_velocity_m_s : float
    Maximum |relative velocity|, m/s.
slip_episodes : int
    Number of slip episodes.
first_slip_time_s : float or None
    Time the block first slips, s (None: it never slips).
total_slip_duration_s : float
    Total time spent slipping, s.
end_time_s : float
    Time the run ended, s (the record end, or later when still sliding).
at_rest_at_end : bool
    True when the block is stuck at the end.
contact_lost_time_s : float or None
    Time the vertical acceleration lifts the block off the plane, s (None: never).
yield_down_g : float
    Down-slope (positive) yield acceleration, g.
yield_up_g : float or None
    Up-slope (negative) yield acceleration, g (None in one-way mode).
mu_static, mu_kinetic : float
    Friction coefficients (dimensionless).
slope_deg : float
    Plane inclination, deg.
mode : str
    "two-way" or "one-way".
g_m_s2 : float
    Gravity used, m/s^2.
time_s : numpy.ndarray
    History times, s (read-only view).
displacement_m : numpy.ndarray
    Relative displacement history, m (read-only view).
velocity_m_s : numpy.ndarray
    Relative velocity history, m/s (read-only view).
state : numpy.ndarray of int8
    -1 slipping up-slope / negative, 0 stuck, 1 slipping down-slope / positive.
)";

inline constexpr const char* sliding_json = R"(The summary as `topple slide --json` writes it.

Returns
-------
dict
    The JSON object (keys with units, e.g. residual_displacement_m in m) with its "input".
)";

inline constexpr const char* slide =
    R"(Exact sliding of a rigid block with Coulomb friction on a level or inclined plane.

Parameters
----------
motion : GroundMotion
    Horizontal ground acceleration (along the slope's fall line when inclined).
mu : float
    Static friction coefficient (dimensionless, >= 0).
mu_kinetic : float, optional
    Kinetic friction coefficient, <= mu (default: mu).
mode : {"two-way", "one-way"}
    "one-way": down-slope slip only (SLAMMER's rigid block).
slope_deg : float
    Plane inclination, deg (0: level).
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up, m/s^2 inside.
g : float
    Gravity, m/s^2 (default 9.80665 m/s^2).
history : bool
    False: summary only (faster; histories empty).

Returns
-------
SlidingResult
    Summary (displacements in m, times in s, yield accelerations in g) and histories.
)";

inline constexpr const char* sliding_2d_result =
    R"(Bidirectional sliding response of a rigid block (the result of topple.slide_2d).

Summary attributes have the names and units of `topple slide --h2 --json`; json() returns that object. Frame: x east,
y north; displacements are of the block relative to the ground (on a slope: in the plane, the downslope axis carried
on the slope's azimuth). Histories are empty unless run with history=True.

Attributes
----------
residual_displacement_m : float
    |u| when the block has come to rest after the record, m.
residual_azimuth_deg : float or None
    Direction of that residual displacement, deg clockwise from north in [0, 360) (None: the block never moved).
residual_east_m, residual_north_m : float
    East and north components of the residual displacement, m.
max_abs_displacement_m : float
    Maximum |u| over the response, m.
max_displacement_time_s : float
    First time |u| reaches that maximum, s.
path_length_m : float
    Length of the block's track on the ground (integral of the relative speed), m.
max_abs_velocity_m_s : float
    Peak relative speed, m/s.
slip_episodes : int
    Number of slip starts from relative rest.
first_slip_time_s : float or None
    Time the block first slips, s (None: it never slips).
total_slip_duration_s : float
    Total time spent slipping, s.
end_time_s : float
    Time the block came to rest, s (the record end, or later when it slid past it).
at_rest_at_end : bool
    False only when the block never comes to rest (mu_kinetic = 0, or a slope steeper than kinetic friction).
contact_lost_time_s : float or None
    First time the normal force vanishes (g + a_v <= 0 on level ground), s: the block leaves the ground and the model
    is not valid after it (None: never).
input_work_J_kg : float
    Work of the inertial load on the block per unit mass, J/kg (on a slope gravity's included).
friction_work_J_kg : float
    Energy dissipated by friction per unit mass, J/kg.
integrator_steps : int
    Dormand-Prince steps taken in the slip phases, rejected ones included.
mu_static, mu_kinetic : float
    Friction coefficients (dimensionless).
g_m_s2 : float
    Gravity used, m/s^2.
time_s : numpy.ndarray
    History times, s (read-only view): the merged grid's points plus every slip start and stop.
east_m, north_m : numpy.ndarray
    Relative displacement history, east and north components, m (read-only views).
east_m_s, north_m_s : numpy.ndarray
    Relative velocity history, east and north components, m/s (read-only views).
slipping : numpy.ndarray of uint8
    1 while slipping, 0 stuck.
)";

inline constexpr const char* sliding_2d_json = R"(The summary as `topple slide --h2 --json` writes it.

Returns
-------
dict
    The JSON object (keys with units, e.g. residual_displacement_m in m, residual_azimuth_deg in deg) with its
    "input".
)";

inline constexpr const char* slide_2d =
    R"(Bidirectional sliding of a rigid block with isotropic Coulomb friction on level or inclined ground.

Both horizontal components (and the vertical, when given) act together: friction opposes the two-dimensional
relative velocity with magnitude mu_kinetic (g + a_v) (topple/solvers/sliding2d.hpp, docs/method.md "Bidirectional
sliding"). On one axis this is topple.slide's two-way block.

Parameters
----------
first, second : GroundMotion
    The two horizontal components, positive toward their azimuths, m/s^2 inside; any sampling (merged exactly).
mu : float
    Static friction coefficient (dimensionless, >= 0).
mu_kinetic : float, optional
    Kinetic friction coefficient, <= mu (default: mu).
azimuths_deg : sequence of two float
    The components' azimuths, deg clockwise from north (default (90, 0): east, north); perpendicular.
slope_deg : float
    Plane inclination, deg (0: level).
slope_azimuth_deg : float, optional
    On a slope (required there, refused on level ground): the azimuth of the downslope direction, deg clockwise
    from north.
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up, m/s^2 inside.
g : float
    Gravity, m/s^2 (default 9.80665 m/s^2).
history : bool
    True: also store the history (time_s, east_m, north_m, east_m_s, north_m_s, slipping); False: summary only.

Returns
-------
Sliding2dResult
    Summary (residual displacement in m with its azimuth in deg, max |u| in m, path length in m, slip episodes, peak
    relative speed in m/s) and, with history=True, the histories.
)";

inline constexpr const char* slide_spectrum =
    R"(Sliding displacement spectrum: one block per friction coefficient (topple/fragility/object_spectra.hpp).

Blocks have mu static = kinetic, on a plane at slope_deg. Draw it with topple.plot.sliding_spectrum.

Parameters
----------
motion : GroundMotion
    Ground acceleration.
mu : numpy.ndarray of float64 or sequence of float
    Friction coefficients (dimensionless, >= 0, atan(mu) + slope < 90 deg).
slope_deg : float
    Plane inclination, deg.
mode : {"two-way", "one-way"}
    Sliding mode.
g : float
    Gravity, m/s^2.

Returns
-------
dict
    Arrays, one value per mu in the given order: mu, max_abs_displacement_m (m), residual_displacement_m (m,
    signed), yield_accel_g (down-slope yield k_y = tan(atan(mu) - slope), g), yield_over_pga (k_y g / PGA),
    slip_episodes (int64), total_slip_duration_s (s), at_rest_at_end (bool); scalars pga_g (g), slope_deg (deg),
    mode, g_m_s2 (m/s^2), motion (the record's name).
)";

inline constexpr const char* slide_spectrum_2d =
    R"(Bidirectional sliding spectrum: one 2-D block per friction coefficient under a pair (topple/fragility/object_spectra.hpp).

For each mu (static = kinetic, level ground, two-way) the block slides under both horizontal components together,
with the vertical when given: topple.slide_2d with that mu, bit for bit. The abscissa k_y g / PGA uses the pair's
RotD50 PGA (Boore 2010; topple.rotd). Beside each point, each horizontal component run alone by the 1-D solver with
the same block and vertical (topple.slide). The dict is `topple spectrum slide H1 --h2 H2 --json`'s.

Parameters
----------
first, second : GroundMotion
    The two horizontal components, positive toward their azimuths, m/s^2 inside; any sampling (merged exactly).
mu : numpy.ndarray of float64 or sequence of float
    Friction coefficients (dimensionless, finite, >= 0).
azimuths_deg : sequence of two float
    The components' azimuths, deg clockwise from north (default (90, 0): east, north); perpendicular.
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up, m/s^2 inside.
g : float
    Gravity, m/s^2 (default 9.80665 m/s^2).

Returns
-------
dict
    The CLI's keys: motion and second (the components' names), vertical (bool), azimuths_deg (deg), pga_axis,
    rotd50_pga_g (g), h1_pga_g and h2_pga_g (each component's PGA, g), g_m_s2 (m/s^2), mode ("two-way"), slope_deg
    (0 deg), and points: per mu a dict of mu, yield_accel_g (g), ky_over_rotd50_pga, the 2-D run's summary
    (topple.Sliding2dResult.json()'s keys: residual_displacement_m in m, residual_azimuth_deg in deg or None,
    max_abs_displacement_m in m, path_length_m in m, ...) and h1_alone / h2_alone (max_abs_displacement_m in m,
    residual_displacement_m in m signed, slip_episodes). Also, as float64 arrays in the order of mu: mu,
    ky_over_rotd50_pga, max_abs_displacement_m (m), residual_displacement_m (m), h1_max_abs_displacement_m (m),
    h2_max_abs_displacement_m (m).
)";

inline constexpr const char* slide_flexible =
    R"(Sliding on a flexible support (topple/solvers/flexible.hpp), decoupled or coupled.

Either an object (friction mu) on a shelf or floor, given by support_freq_hz, support_damping and mass_ratio; or
SLAMMER's flexible sliding mass (mu is k_y), given by height_m, vs_slope_m_s, vs_base_m_s and damping.

Parameters
----------
motion : GroundMotion
    Ground acceleration at the base of the support.
mu : float
    Friction coefficient of the object (dimensionless), or the yield coefficient k_y of a sliding mass.
mode : {"two-way", "one-way"}
    Sliding mode.
support_freq_hz : float, optional
    Natural frequency of the support alone, Hz.
support_damping : float
    Damping ratio of the support (dimensionless).
mass_ratio : float
    Object mass / support modal mass (dimensionless; coupled analysis).
height_m : float, optional
    Height of the sliding mass, m (SLAMMER flexible analysis).
vs_slope_m_s : float, optional
    Shear-wave velocity of the sliding mass, m/s.
vs_base_m_s : float, optional
    Shear-wave velocity of the base, m/s.
damping : float, optional
    Material damping ratio of the sliding mass (dimensionless; the mode adds the base impedance damping).
reference_strain : float, optional
    Reference shear strain (decimal) for the equivalent-linear iteration.
coupled : bool
    True: coupled analysis (the sliding feeds back on the support).
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up (both analyses; coupled: normal force m (g + a_v)).
g : float
    Gravity, m/s^2.

Returns
-------
dict
    The dict of `topple slide --support-freq|--height --json`: the sliding summary fields (displacements in m,
    times in s) and "support" (mode_freq_hz in Hz, mode_damping_ratio, kmax in g, vs_final_m_s in m/s ...).
)";

inline constexpr const char* rocking_body =
    R"(A rigid body that rocks about its base edges (made by Block, Cylinder or General).

Attributes
----------
shape : str
    "block", "cylinder" or "general".
a_m : float
    Horizontal distance from the centre of mass to a pivot edge, m.
h_m : float
    Height of the centre of mass, m.
D_m2 : float
    Moment of inertia about a pivot per unit mass, m^2.
alpha_rad : float
    Slenderness angle atan(a / h), rad.
R_m : float
    Distance from the centre of mass to a pivot, m.
housner_e : float
    Housner's coefficient of restitution 1 - (3/2) sin^2(alpha) for a block (dimensionless; negative for squat bodies).
symmetric : bool
    True when both pivots are at the same distance b from the centre of mass (Block, Cylinder, General).
b1_m, b2_m : float
    Horizontal distance from the centre of mass to the pivot O- (rocking with theta < 0, the -x edge) and to O+
    (theta > 0), m; both a_m for a symmetric body (GeneralAsymmetric gives them apart).
D1_m2, D2_m2 : float
    Moment of inertia about O- and about O+ per unit mass, m^2 (both D_m2 for a symmetric body).
)";

inline constexpr const char* p_rad_s = R"(Frequency parameter p = sqrt(g R / D) of the body.

Parameters
----------
g : float
    Gravity, m/s^2.

Returns
-------
float
    p, rad/s.
)";

inline constexpr const char* block = R"(A rectangular block standing on its base.

Parameters
----------
width : float
    Full base width across the rocking direction (the narrow side), m.
height : float
    Full height, m.

Returns
-------
RockingBody
    The block (a_m = width / 2, h_m = height / 2).
)";

inline constexpr const char* cylinder = R"(A solid cylinder standing on its end.

Parameters
----------
diameter : float
    Diameter, m.
height : float
    Height, m.

Returns
-------
RockingBody
    The cylinder.
)";

inline constexpr const char* general = R"(Any rigid body, by its geometry about a pivot.

Parameters
----------
a : float
    Horizontal distance from the centre of mass to the pivot edge, m.
h : float
    Height of the centre of mass, m.
D : float
    Moment of inertia about the pivot per unit mass, m^2 (>= a^2 + h^2).

Returns
-------
RockingBody
    The body.
)";

inline constexpr const char* general_asymmetric =
    R"(An asymmetric rigid body: CM to the pivot O- (b1) and O+ (b2), CM height h (m), inertia = I_cm / m (m^2).

Rocking with theta < 0 turns about O- (the -x edge), with theta > 0 about O+; each side has its own slenderness
angle atan(b/h), uplift level g b/h and Housner restitution on landing (docs/method.md, "Asymmetric bodies").

Parameters
----------
b1 : float
    Horizontal distance from the centre of mass to the pivot O-, m (> 0).
b2 : float
    Horizontal distance from the centre of mass to the pivot O+, m (> 0).
h : float
    Height of the centre of mass above the base, m (> 0).
inertia : float
    Moment of inertia about the centre of mass (the rocking axis) per unit mass, m^2 (>= 0).

Returns
-------
RockingBody
    The body (b1_m, b2_m, D1_m2, D2_m2 give its two pivots).
)";

inline constexpr const char* rocking_result = R"(Rocking response of a rigid body (the result of topple.rock).

Summary attributes have the names and units of `topple rock --json`; json() returns that object. Histories and
events are empty when run with history=False.

Attributes
----------
max_abs_rotation_rad : float
    Maximum |theta|, rad.
max_rotation_over_alpha : float
    Maximum |theta| / alpha (1: the body passes its tipping angle).
max_rotation_time_s : float
    Time of that maximum, s.
max_rotation_positive_rad, max_rotation_negative_rad : float
    Maximum rotation on each side (theta > 0 about O+, theta < 0 about O-), rad, both >= 0.
max_rotation_over_alpha_positive, max_rotation_over_alpha_negative : float
    Each side's maximum rotation over that side's slenderness angle (an asymmetric body tips at a different angle on
    each side).
overturned_side : int
    +1: fell toward +x (about O+), -1: toward -x (about O-), 0: did not fall.
max_abs_theta_dot_rad_s : float
    Maximum |theta'|, rad/s.
impacts, uplifts : int
    Number of impacts and of uplifts.
uplift_time_s : float or None
    First uplift, s.
exceeded_alpha_time_s : float or None
    First time |theta| > alpha, s.
overturned : bool
    True when the body fell.
overturn_time_s : float or None
    Time of overturning, s.
end_state : str
    "rest", "rocking+", "rocking-" or "fallen".
end_time_s : float
    Time the run ended, s.
still_rocking_at_end : bool
    True when the body still rocks at end_time_s.
energy_lost_j_per_kg : float
    Energy lost in impacts per unit mass, J/kg.
alpha_rad, alpha_deg : float
    Slenderness angle, rad and deg.
R_m : float
    Centre of mass to pivot, m.
p_rad_s : float
    Frequency parameter, rad/s.
e : float
    Coefficient of restitution used (dimensionless).
e_mode : str
    "housner" (Housner's value of the body) or "given".
onset_mode : str
    Shenton's onset criterion: "unchecked" (no mu given), "rest", "rock", "slide" or "slide-rock".
onset_accel_ratio : float or None
    Onset acceleration / g tan(alpha) (dimensionless).
critical_mu : float or None
    Friction coefficient below which the body would slide before it rocks (dimensionless).
mu : float or None
    Friction coefficient checked (dimensionless).
g_m_s2 : float
    Gravity used, m/s^2.
warnings : list of str
    What the solver had to say (e.g. a run-out limit reached).
body : RockingBody
    The body.
time_s : numpy.ndarray
    History times, s (read-only view).
theta_rad : numpy.ndarray
    Rotation history, rad (read-only view).
theta_dot_rad_s : numpy.ndarray
    Angular velocity history, rad/s (read-only view).
state : numpy.ndarray of int8
    -1 rocking negative, 0 at rest, 1 rocking positive, 2 fallen.
events : list of dict
    kind, time_s (s), theta_rad (rad), theta_dot_before_rad_s and theta_dot_after_rad_s (rad/s).
)";

inline constexpr const char* rocking_json = R"(The summary as `topple rock --json` writes it.

Returns
-------
dict
    The JSON object (keys with units, e.g. max_rotation_time_s in s).
)";

inline constexpr const char* rock =
    R"(Housner rocking and overturning of a rigid body on a level base that does not slide.

Parameters
----------
motion : GroundMotion
    Horizontal ground acceleration.
shape : RockingBody
    The body (topple.Block, topple.Cylinder or topple.General; lengths in m).
e : float or "housner"
    Coefficient of restitution in [0, 1] (dimensionless), or "housner" for Housner's value of the body.
mu : float, optional
    Friction coefficient (dimensionless) for Shenton's slide/rock onset check.
)" TOPPLE_DOC_ROCKING_SOLVER R"(vertical : GroundMotion, optional
    Vertical ground acceleration, positive up.
history : bool
    False: summary only.

Returns
-------
RockingResult
    Summary (angles in rad, times in s) and histories.
)";

inline constexpr const char* slide_rock_result =
    R"(Coupled sliding and rocking of a rigid body with friction (the result of topple.slide_rock).

Summary attributes have the names and units of `topple rock --model coupled --json`; json() returns that object
(its "input" object included, as topple.rock's). theta > 0 is a rotation about O+ (the top moves toward +x); the slide is positive toward +x (sliding.hpp's
displacement, positive the way a positive acceleration pushes the block, is minus it). Histories and transitions are
empty when run with history=False.

Attributes
----------
overturned : bool
    The body fell.
overturned_side : str or None
    "positive" (toward +x, about O+), "negative", or None when it did not fall.
overturn_time_s : float or None
    Time of overturning, s.
max_rotation_over_alpha : float
    Maximum |theta| / alpha of its side (1: the body passes its tipping angle).
max_rotation_positive_rad : float
    Maximum theta over theta > 0, rad.
max_rotation_negative_rad : float
    Maximum -theta over theta < 0, rad.
max_rotation_over_alpha_positive : float
    max_rotation_positive_rad / alpha+ (dimensionless).
max_rotation_over_alpha_negative : float
    max_rotation_negative_rad / alpha- (dimensionless).
exceeded_alpha_time_s : float or None
    First time |theta| exceeded the tipping angle of its side, s.
residual_slide_m : float
    Slide at the end of the run, m, positive toward +x.
max_abs_slide_m : float
    Maximum |slide|, m.
slip_episodes : int
    Entries into sliding or slide-rock from a sticking state.
impacts : int
    Corner strikes (rocking impacts and landings from flight).
uplifts : int
    Lift-offs from full contact.
tangential_impacts : int
    Painleve's paradox: impacts without collision that stopped a slipping pivot (docs/method.md).
painleve_holds : int
    Painleve's paradox: holds of a sticking pivot whose every slip had no solution (docs/method.md).
max_tangential_impulse_ratio : float
    Largest |P_t| / P_n over the tangential impacts (<= mu_kinetic, Coulomb's cone).
onset_mode : str
    The first mode left rest for: "rest" (never moved), "slide", "rock", "slide-rock" or "flight".
end_mode : str
    The mode at the end: "rest", "slide", "rock", "slide-rock", "flight" or "fallen".
end_time_s : float
    End of the run, s.
moving_at_end : bool
    The run-out cap (max_run_out_s) ended a run still in motion.
friction_energy_j_per_kg : float
    Energy dissipated by kinetic friction, J/kg.
impact_energy_j_per_kg : float
    Energy lost in impacts and to the rest rule, J/kg.
alpha_positive_deg : float
    Tipping angle about O+, atan(b2 / h), deg.
alpha_negative_deg : float
    Tipping angle about O-, atan(b1 / h), deg.
mu_static : float
    Static friction coefficient (dimensionless).
mu_kinetic : float
    Kinetic friction coefficient (dimensionless).
e_mode : str
    "housner" or "given".
used_sliding_kernel : bool
    The body cannot lift (mu_static < b / h): the run was the exact sliding solver.
g_m_s2 : float
    Gravity, m/s^2.
warnings : list of str
    Solver warnings.
modes : dict
    Per mode name: {"entries": int, "first_time_s": float or None (s)}.
body : RockingBody
    The body as given.
time_s : numpy.ndarray
    History times, s (record samples, integrator step ends and events).
slide_m : numpy.ndarray
    Slide u of the pivot corner, m, positive toward +x.
slide_velocity_m_s : numpy.ndarray
    Slip velocity u', m/s.
theta_rad : numpy.ndarray
    Rotation, rad.
theta_dot_rad_s : numpy.ndarray
    Angular velocity, rad/s.
cm_height_m : numpy.ndarray
    Height of the centre of mass above the ground, m.
mode : numpy.ndarray
    Mode codes (int8): 0 rest, 1 slide, 2 rock, 3 slide-rock, 4 flight, 5 fallen.
transitions : list of dict
    Every change of mode: {"time_s": s, "mode": name}.
)";

inline constexpr const char* slide_rock_json = R"(The summary as `topple rock --model coupled --json` writes it.

Returns
-------
dict
    The JSON object (keys with units, e.g. residual_slide_m in m), with its "input" object.
)";

inline constexpr const char* slide_rock =
    R"(Coupled sliding and rocking of a rigid body with Coulomb friction on a level or inclined base (slide_rock.hpp).

As `topple rock --model coupled --mu MU [--mu-k MU_K]`: the body may rest, slide, rock, slide and rock, or fly,
whichever its contact forces allow. A body with mu < min(b1, b2) / h cannot lift and is run by the exact sliding
solver.

Parameters
----------
motion : GroundMotion
    Horizontal ground acceleration, positive toward +x.
body : RockingBody
    The body (topple.Block, topple.Cylinder, topple.General or topple.GeneralAsymmetric; lengths in m).
mu : float
    Static friction coefficient (dimensionless, >= 0). InputError (field "mu") when invalid.
mu_k : float, optional
    Kinetic friction coefficient (dimensionless, 0 <= mu_k <= mu); default mu. InputError (field "mu_k").
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up.
e : float or "housner"
    Coefficient of restitution in [0, 1] (dimensionless) on a sticking impact after pure rocking, or "housner".
g : float
    Gravity, m/s^2.
rel_tol : float
    Relative tolerance of the adaptive integrator (dimensionless).
max_run_out_s : float
    Longest time the body is followed after the record ends, s.
slope_deg : float
    Inclination of the base in the plane of shaking, degrees (0: level); down-slope is -x (the b1 corner), as
    `--slope-deg`. InputError (field "slope") when tan(slope) > mu or slope > alpha- (the body cannot stand on it).
history : bool
    False: summary only.

Returns
-------
SlideRockResult
    Summary (angles in rad or deg as named, slides in m, times in s, energies in J/kg) and histories.
)";

inline constexpr const char* motion_set =
    R"(One station's ground motion in up to three components on one time grid (motion_set.hpp).

MotionSet(first, second=None, *, vertical=None, azimuths_deg=None)

The components are merged exactly onto the union of their sample times (each piecewise linear between its own
samples, zero outside its record, jumps kept): different dt or lengths are not an error. Components whose time
spans overlap over less than half the longest span are refused (InputError, field "time span").

Parameters
----------
first : GroundMotion
    First horizontal component, positive toward its azimuth.
second : GroundMotion or None
    Second horizontal component, perpendicular to the first.
vertical : GroundMotion or None
    Vertical component, positive up.
azimuths_deg : (float, float) or None
    Azimuths of the first and second components, deg clockwise from north (east = 90), perpendicular
    (second = first +- 90); None when unknown (projection on an azimuth needs them; RotD does not).
    InputError (field "azimuths_deg") when not perpendicular to 1e-6 deg.

Attributes
----------
npts : int
    Number of samples of the merged grid.
first : GroundMotion
    The first horizontal component on the merged grid, acceleration in m/s^2.
second : GroundMotion or None
    The second horizontal component on the merged grid (None when absent).
vertical : GroundMotion or None
    The vertical component on the merged grid, positive up (None when absent).
azimuths_deg : (float, float) or None
    The horizontal components' azimuths, deg clockwise from north, or None when unknown.
)";

inline constexpr const char* projected =
    R"(The horizontal acceleration projected on a direction: a1 cos(az - az1) + a2 cos(az - az2).

Parameters
----------
azimuth_deg : float
    Direction, deg clockwise from north. With one horizontal component only its own azimuth or the opposite one.

Returns
-------
GroundMotion
    The projected acceleration on the set's grid, m/s^2 (equal to the first component at its own azimuth).
    InputError (field "azimuth_deg") when the azimuths are unknown.
)";

inline constexpr const char* rotated =
    R"(The horizontal pair rotated to azimuth_deg and azimuth_deg + 90 (clockwise).

Parameters
----------
azimuth_deg : float
    Azimuth of the first rotated component, deg clockwise from north.

Returns
-------
(GroundMotion, GroundMotion)
    The components toward azimuth_deg and azimuth_deg + 90, m/s^2. InputError when the azimuths are unknown.
)";

#define TOPPLE_DOC_ROTD_RETURNS                                                                                     \
  "Returns\n-------\ndict\n"                                                                                        \
  "    The numbers `topple info H1 H2 --json` prints under \"rotd\" (Boore 2010; angles 0..179 deg from the first\n" \
  "    component toward the second; RotD50 the median over the angles, RotD100 the largest):\n"                      \
  "    angles_deg (numpy array, deg), pga_rotd50_m_s2, pga_rotd100_m_s2 (float, m/s^2), pga_rotd50_g,\n"            \
  "    pga_rotd100_g (float, g), pga_rotd100_angle_deg (deg from the first component), pga_rotd100_azimuth_deg\n"    \
  "    (deg clockwise from north in [0, 180), None when the azimuths are unknown), pga_by_angle_m_s2 (180 values,\n" \
  "    m/s^2), period_s (s), damping, psa_rotd50_m_s2, psa_rotd100_m_s2 (m/s^2), psa_rotd50_g, psa_rotd100_g (g),\n" \
  "    psa_rotd100_angle_deg (deg), psa_rotd100_azimuth_deg (list of float or None), psa_by_angle_m_s2 (array\n"     \
  "    periods x 180, m/s^2), merged_npts, azimuths_deg, g_m_s2 (m/s^2).\n"

inline constexpr const char* motion_set_rotd =
    "RotD50 and RotD100 of the PGA and of the PSA of the horizontal pair (Boore 2010).\n\n"
    "Parameters\n----------\n"
    "periods_s : numpy.ndarray of float64, sequence of float or None\n"
    "    Oscillator periods, s (> 0); None: topple info's periods 0.1, 0.2, 0.3, 0.5, 0.75, 1, 1.5, 2, 3, 4 s.\n"
    "damping : float\n    Damping ratio of the oscillators (dimensionless fraction of critical), 0 <= damping < 1.\n"
    "g : float\n    Gravity, m/s^2, for the values in g.\n\n" TOPPLE_DOC_ROTD_RETURNS
    "    InputError (field \"second\") when the set has no second horizontal component.\n";

inline constexpr const char* rotd =
    "RotD50 and RotD100 of the PGA and of the 5 %-damped PSA of two horizontal components (Boore 2010).\n\n"
    "The same numbers as `topple info H1 H2 --json` (rotd.hpp; PGA exact on the merged grid, PSA by the exact\n"
    "Nigam-Jennings oscillator of each component combined at every angle).\n\n"
    "Parameters\n----------\n"
    "first : GroundMotion\n    First horizontal component (acceleration, m/s^2 inside).\n"
    "second : GroundMotion\n    Second horizontal component, perpendicular to the first; merged exactly with it.\n"
    "azimuths_deg : (float, float) or None\n"
    "    The components' azimuths, deg clockwise from north (perpendicular); only the RotD100 azimuths need them.\n"
    "periods_s : numpy.ndarray of float64, sequence of float or None\n"
    "    Oscillator periods, s (> 0); None: topple info's periods 0.1, 0.2, 0.3, 0.5, 0.75, 1, 1.5, 2, 3, 4 s.\n"
    "damping : float\n    Damping ratio of the oscillators (dimensionless fraction of critical), 0 <= damping < 1.\n"
    "g : float\n    Gravity, m/s^2, for the values in g.\n\n" TOPPLE_DOC_ROTD_RETURNS;

inline constexpr const char* rock3d =
    R"(A box or a solid cylinder rocking in three dimensions, as `topple rock --model 3d --json`.

The box rocks about an edge of its base or pivots on a corner under one or two horizontal components and the
vertical (topple/solvers/rigid3d.hpp, docs/method.md "Rocking in three dimensions"): impacts perfectly plastic and
sticking, the complementarity solution over the corners down (docs/method.md "Impact law": Housner's law where the
impulse acts at the new contact only), or a given e; no sliding, no flight (a warning names the first instant the
vertical contact force vanished). A solid cylinder (diameter_m instead of width_m and depth_m; the CLI's --shape
cylinder --diameter --height) rocks and rolls on the rim of its base (topple/solvers/rigid3d_disc.hpp, docs/method.md
"A circular base: rolling on the rim"); it is axisymmetric: no bearing_deg, the pair acts along east and north.

Parameters
----------
first : GroundMotion
    The horizontal component; alone, it acts along the box's +x axis (reported as azimuth 90 deg).
second : GroundMotion, optional
    The other horizontal component: the pair acts along east and north, the box's +x axis toward bearing_deg.
width_m, depth_m : float, optional
    A box: its extent along its x and y axes, m (> 0); both required unless diameter_m is given.
height_m : float
    The box's or the cylinder's height, m (> 0).
diameter_m : float, optional
    A solid cylinder: the diameter of its base, m (> 0); instead of width_m and depth_m.
azimuths_deg : sequence of two float
    With second: the components' azimuths, deg clockwise from north (default (90, 0): east, north); perpendicular.
bearing_deg : float, optional
    With second (required for a box; refused for a cylinder): the azimuth of the box's +x axis, deg clockwise from
    north.
vertical : GroundMotion, optional
    Vertical ground acceleration (up positive); g + a_z must stay positive.
e : "housner" or float
    Restitution: "housner" (angular momentum about the new contact) or the kinetic-energy ratio e^2 at an impact,
    e in [0, 1].
g : float
    Gravity, m/s^2.
rel_tol : float
    Relative tolerance of the Dormand-Prince steps (dimensionless).
simultaneous_contact : float, optional
    A box: at a touch-down, the base corners within this fraction of the body's size (its largest distance from the
    centre of mass to a corner; dimensionless) of the ground land with it as one impact, in [0, 0.01]; None: 1e-5
    (the CLI's --simultaneous-contact); 0: strictly successive impacts. Refused for a cylinder (its base lands flat).
mu : float, optional
    The static friction coefficient mu_s (>= 0; the CLI's --mu; docs/method.md "Sliding in three dimensions"): the
    base sticks while |a_h| <= mu_s (g + a_z) and slides flat otherwise. None (the default): no sliding, the engine as
    before. A cylinder (docs/method.md "A circular base with friction"): slides flat when mu_s h < R (it can never
    lift); otherwise rolls on its rim while the contact force is inside the friction cone, and slips on its rim and
    flies where it is not (summary "slide_rock_time_s", "flight_time_s", the sliding keys).
mu_k : float, optional
    The kinetic friction coefficient, 0 <= mu_k <= mu (the CLI's --mu-k); None: mu. Needs mu.
base_incline_deg : float
    A box: the base is a plane inclined at this angle, degrees in [0, 90) (the CLI's --base-incline-deg; docs/method.md
    "An inclined base"); 0 (the default): level. Without mu the box sticks to the plane; with mu it slides on it (from
    rest where tan(incline) > mu). The summary is in the base's frame: tilt from the base normal, azimuths and the
    residual slide in the plane (east and north carried onto it); "solver" says the incline. Refused for a cylinder.
base_incline_azimuth_deg : float
    The plane's downhill direction, degrees clockwise from north (the CLI's --base-incline-azimuth-deg); with one
    component (no second) the record acts along the box's +x, azimuth 90.
max_run_out_s : float
    Longest integration after the record on still ground, s.
history : bool
    Add "history": time_s (s), position_m (the body frame's origin, m), orientation_wxyz (unit quaternion, body to
    ground), angular_velocity_rad_s (rad/s, ground frame), energy_j_per_kg (J/kg), mode; a row per sample and event.

Returns
-------
dict
    The summary with the CLI's JSON keys less "input": overturned, overturn_time_s (s), overturn_azimuth_deg (deg),
    max_tilt_rad (rad), max_tilt_azimuth_deg (deg), max_tilt_time_s (s), max_tilt_over_limit, impacts, uplifts,
    energy_lost_j_per_kg (J/kg), modes, body, solver, ...)";

inline constexpr const char* rock_oriented =
    R"(Rocking of an oriented object under two horizontal components (and the vertical), as `topple rock --h2`.

The object rocks in the vertical plane of its bearing under the projection of both components on it (the planar
model, topple/solvers/oriented.hpp, docs/method.md "Oriented objects"). A block with depth_m is a box, also run along
bearing + 90 deg; a cylinder has no bearing and is taken in its worst direction over a grid of directions (an
approximation of three-dimensional rocking).

Parameters
----------
first, second : GroundMotion
    The two horizontal components, positive toward their azimuths; any sampling (merged exactly).
shape : RockingBody
    The body (topple.Block, topple.Cylinder or topple.General; lengths in m). Its +x side faces the bearing.
azimuths_deg : sequence of two float
    The components' azimuths, deg clockwise from north (default (90, 0): east, north); perpendicular.
bearing_deg : float, optional
    The direction across the object's narrow side, deg clockwise from north: required, but refused for a cylinder.
depth_m : float, optional
    A block's other horizontal dimension, m (along bearing + 90 deg): a box.
direction_step_deg : float, optional
    A cylinder's direction grid, deg (default 15; must divide 180).
vertical : GroundMotion, optional
    Vertical ground acceleration, positive up.
e : float or "housner"
    Coefficient of restitution in [0, 1] (dimensionless), or "housner".
mu : float, optional
    Friction coefficient (dimensionless) for Shenton's slide/rock onset check.
)" TOPPLE_DOC_ROCKING_SOLVER R"(
Returns
-------
dict
    The JSON of `topple rock --h2 --json` less "input": the governing direction's summary (angles in rad, times in
    s) and "orientation" (every direction's azimuth in deg, max rotation over alpha, fall; the governing one).
)";

inline constexpr const char* synth =
    R"(A synthetic ground motion, as `topple synth`: the same parameters and seed give the same bits everywhere.

Filtered white noise (Clough-Penzien or Kanai-Tajimi) under an envelope, scaled to the PGA.

Parameters
----------
pga_g : float
    Peak ground acceleration, g.
freq_hz : float
    Predominant frequency of the ground filter, Hz (0.2 to 20 Hz).
duration_s : float
    Duration, s.
seed : int
    Random seed.
dt_s : float
    Sample interval, s.
model : {"clough-penzien", "kanai-tajimi"}
    Ground filter.
envelope : {"saragoni-hart", "jennings"}
    Amplitude envelope.
zeta_g : float
    Damping ratio of the ground filter (dimensionless).
g : float
    Gravity, m/s^2, that pga_g is in.
components : {1, 2, 3}
    1: one motion (as before). 2: two horizontal components, the same process driven by white noises with
    correlation `coherence`; pga_g is then the pair's RotD50 PGA (Boore 2010), both components scaled by one
    factor. 3: and a vertical component, its own independent noise, PGA vh_ratio x the RotD50 PGA, predominant
    frequency vh_freq_ratio x freq_hz (synthesis.hpp, docs/method.md "Synthetic motion sets"). As
    `topple synth --components`.
coherence : float or None
    components 2 or 3: correlation coefficient of the two horizontal noises, -1..1 (dimensionless); None: 0
    (independent).
azimuths_deg : (float, float) or None
    components 2 or 3: the components' azimuths, deg clockwise from north, perpendicular; None: (90, 0).
vh_ratio : float or None
    components 3: vertical PGA over the pair's RotD50 PGA (dimensionless, (0, 2]); None: 2/3.
vh_freq_ratio : float or None
    components 3: vertical over horizontal predominant frequency (dimensionless, 0.5-4); None: 1.5.

Returns
-------
GroundMotion or MotionSet
    components=1: the motion (PGA exactly pga_g). 2 or 3: a MotionSet with the azimuths (and the vertical),
    the same bits as the CSV files `topple synth --components 2|3` writes.
    The set-only parameters are refused (InputError naming them) with components=1, vh_ratio and
    vh_freq_ratio with components=2.
)";

inline constexpr const char* intensity = R"(Intensity measures of a motion, as `topple info --json` names them.

Parameters
----------
motion : GroundMotion
    Ground acceleration.
g : float
    Gravity, m/s^2, for the values in g.

Returns
-------
dict
    npts, uniform (True for a constant step), dt_s (s), start_time_s (s), duration_s (s), pga_g (g), pga_m_s2
    (m/s^2), pga_time_s (s), pgv_m_s (m/s), pgd_m (m),
    arias_m_s (Arias intensity, m/s), d5_95_s (significant duration, s), d5_time_s, d95_time_s (s), cav_m_s (m/s),
    tp_s (predominant period, s), tm_s (mean period, s), predominant_frequency_hz (Hz), g_m_s2 (m/s^2); None where
    undefined.
)";

// Private workers of topple.invert (python/topple/__init__.py documents the parameters).
inline constexpr const char* invert_text =
    "topple.invert's worker for a survey given as TOML text (text, name for messages, base_dir for records).";
inline constexpr const char* invert_file = "topple.invert's worker for a survey file.";
inline constexpr const char* invert_region_text =
    "topple.invert_region's worker for a survey given as TOML text (text, name for messages, base_dir for records).";
inline constexpr const char* invert_region_file = "topple.invert_region's worker for a survey file.";

inline constexpr const char* response_spectrum =
    R"(Elastic response spectrum of linear oscillators, by the exact Nigam-Jennings recurrence.

x'' + 2 zeta w x' + w^2 x = -a_g from rest (topple/motion/spectra.hpp; maxima at the samples, over the record only). Draw
it with topple.plot.response_spectrum.

Parameters
----------
motion : GroundMotion
    Ground acceleration.
periods_s : numpy.ndarray of float64 or sequence of float, optional
    Oscillator periods, s (> 0; default: 100 per decade from 0.02 s to 5 s).
damping : float
    Damping ratio zeta in [0, 1) (dimensionless).
g : float
    Gravity, m/s^2, for psa_g.

Returns
-------
dict
    Arrays, one value per period: period_s (s), sd_m (max |x|, m), psv_m_s (w SD, m/s), psa_m_s2 (w^2 SD, m/s^2),
    psa_g (PSA / g), sv_m_s (max |x'|, m/s), sa_m_s2 (max absolute acceleration, m/s^2); scalars damping, g_m_s2
    (m/s^2), motion (name).
)";

inline constexpr const char* fourier_spectrum =
    R"(Fourier amplitude spectrum |A(f)| = dt |DFT| and its Konno-Ohmachi smoothing.

Irregular records are resampled at their smallest interval first. Draw it with topple.plot.fourier_spectrum.

Parameters
----------
motion : GroundMotion
    Ground acceleration.
smoothing_b : float or None
    Konno-Ohmachi bandwidth b (> 0, dimensionless); None: no smoothing.
centre_hz : numpy.ndarray of float64 or sequence of float, optional
    Centre frequencies of the smoothing, Hz (default: 200 per decade from 0.1 Hz to min(25 Hz, 0.8 f_Nyquist)).
fft_length : int, optional
    Zero-padded FFT length (>= npts; default: the next power of two >= 2 npts).

Returns
-------
dict
    freq_hz (Hz, k / (N dt)), amplitude_m_s (m/s), smoothed_freq_hz (Hz) and smoothed_amplitude_m_s (m/s; None
    without smoothing), dt_s (s), fft_length, smoothing_b, predominant_frequency_hz (Hz, as topple.intensity; None
    when undefined), motion (name).
)";

inline constexpr const char* overturning_map =
    R"(Overturning map: which bodies of one slenderness overturn at which PGA (topple/fragility/object_spectra.hpp).

Bodies of one shape and slenderness alpha_rad = atan(a / h), of the given full heights, under the motion scaled to
each PGA. Runs on `threads` cores with the GIL released. Draw it with topple.plot.overturning_map.

Parameters
----------
motion : GroundMotion
    Ground acceleration (scaled to each PGA).
alpha_rad : float
    Slenderness angle atan(a / h), rad.
heights_m : numpy.ndarray of float64 or sequence of float
    Full body heights, m.
pga_g : numpy.ndarray of float64 or sequence of float
    Peak ground accelerations, g.
shape : {"block", "cylinder"}
    Body shape.
e : float or "housner"
    Coefficient of restitution (dimensionless).
mu : float, optional
    Friction coefficient (dimensionless) for the onset check.
)" TOPPLE_DOC_ROCKING_SOLVER R"(threads : int
    Worker threads (0: all cores).

Returns
-------
dict
    pga_g (g, ascending) and pga_m_s2 (m/s^2); per size in the given order: height_m (m), width_m (full width or
    diameter, m), R_m (m), p_rad_s (rad/s), first_overturn_pga_g (g, NaN when none overturns), standing_above_first
    (bool), overturn_count (int64); overturned (bool) and max_rotation_over_alpha, 2-D [size, pga]; alpha_rad (rad),
    uplift_pga_g (tan(alpha), g), shape, g_m_s2 (m/s^2), motion (name).
)";

inline constexpr const char* fragility_fit_class =
    R"(Lognormal fragility P(failure | IM = x) = Phi(ln(x / theta) / beta).

Maximum-likelihood fit to binomial counts (Baker 2015; topple/fragility/fragility.hpp).

Attributes
----------
theta : float
    Median, in the unit of the IM levels it was fitted to (g for PGA).
beta : float
    Logarithmic standard deviation (dimensionless).
log_likelihood : float
    Log-likelihood at the maximum.
se_ln_theta, se_beta : float
    Standard errors of ln theta and beta (observed information).
cov_ln_theta_beta : float
    Their covariance.
iterations : int
    Newton iterations used.
beta_at_bound : bool
    True for separated data: beta is held at its lower bound 0.01 and the band is not meaningful.
)";

inline constexpr const char* fragility_probability = R"(Probability of failure at an intensity.

Parameters
----------
im : float or numpy.ndarray of float64
    Intensity measure, in the unit theta is in.

Returns
-------
float or numpy.ndarray
    Probability in [0, 1].
)";

inline constexpr const char* fragility_band = R"(Delta-method confidence band of the probability.

Parameters
----------
im : float or numpy.ndarray of float64
    Intensity measure, in the unit theta is in.
level : float
    Confidence level in (0, 1).

Returns
-------
tuple
    (lower, upper) probabilities, floats or arrays as `im`.
)";

inline constexpr const char* fragility_fit = R"(Fit a lognormal fragility to counts of failures.

Warns (RuntimeWarning) when the data are separated and beta sits at its lower bound.

Parameters
----------
im : numpy.ndarray of float64 or sequence of float
    Intensity levels (> 0, any unit: theta comes out in it).
trials : sequence of int
    Runs at each level.
failures : sequence of int
    Failures at each level. No failure at all, or failures only: topple.InputError.

Returns
-------
FragilityFit
    The fit.
)";

inline constexpr const char* fragility =
    R"(Fragility analysis: failure counts over scaled motions and their lognormal fits (topple/fragility/fragility.hpp).

Every motion is scaled so that its IM equals each level and run on a sliding block (failure: max |d| >
threshold_m) and/or a rocking body (failure: overturning). Warns (RuntimeWarning) for each curve whose fit has beta
at its lower bound. Runs on `threads` cores with the GIL released. Draw it with topple.plot.fragility.

An ensemble of pairs (a list of topple.MotionSet with two horizontal components and their azimuths, and optionally
a vertical; e.g. from topple.synth(components=2)) is `topple fragility --h2` / `--components 2|3`: the IM is each
pair's RotD50 PGA (im must be "pga"), every set is scaled as a whole, the block slides in two dimensions (level
ground, two-way) and the body rocks under the projection of the pair on its bearing (planar model; a cylinder in
its worst direction): bearing_deg for every motion or, when None, a bearing drawn uniformly in [0, 360) deg per
motion from bearing_seed (the same at every level).

Parameters
----------
motions : list of GroundMotion, or list of MotionSet
    The ensemble: records (one component each), or pairs (one kind per list).
levels : numpy.ndarray of float64 or sequence of float
    IM levels: g for pga (pairs: RotD50 PGA, g), m/s for pgv and cav, m for pgd.
im : {"pga", "pgv", "pgd", "cav"}
    Intensity measure.
mu : float, optional
    Friction coefficient of the sliding block (dimensionless; with threshold_m).
threshold_m : float, optional
    Sliding failure threshold on max |displacement|, m.
mu_kinetic : float, optional
    Kinetic friction coefficient (dimensionless).
mode : {"two-way", "one-way"}
    Sliding mode.
slope_deg : float
    Plane inclination, deg.
body : RockingBody, optional
    Rocking body (failure = overturning).
e : float or "housner"
    Coefficient of restitution (dimensionless).
rock_mu : float, optional
    Friction coefficient for the rocking onset check (dimensionless).
)" TOPPLE_DOC_ROCKING_SOLVER R"(threads : int
    Worker threads (0: all cores).
bearing_deg : float, optional
    Pairs only: the rocking body's bearing (across its narrow side), deg clockwise from north, for every motion (not
    for a cylinder); None: uniformly random per motion.
bearing_seed : int, optional
    Pairs only, without bearing_deg: seed of the random bearings (default 1, as `topple fragility`).

Returns
-------
dict
    im, im_unit, rotd50 (True for pairs: the IM is the RotD50 PGA), bearings_deg (pairs: each motion's bearing in
    deg, float64 array; None otherwise), runs, g_m_s2 (m/s^2), motions (count), mu, threshold_m (m) and body as
    given, and curves: a list (slide first, then overturn) of dicts name, im (levels, in im_unit), trials, failures
    (int64), fraction, fit (FragilityFit, theta in im_unit; None when the counts cannot be fitted) and fit_note.
)";

inline constexpr const char* sweep = R"(Run a sweep file in memory (used by topple.sweep).

Parameters
----------
path : str
    The sweep file.
threads : int
    Worker threads (0: all cores).

Returns
-------
dict
    Column name -> values.
)";

}  // namespace topple::python::doc

#undef TOPPLE_DOC_ROCKING_SOLVER
