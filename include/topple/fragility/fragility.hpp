#pragma once
// Fragility curves: the probability that an object overturns, or slides more than a distance, against an intensity
// measure (IM) of the shaking, from an ensemble of motions scaled to a grid of IM levels (a multiple-stripe analysis,
// Baker 2015, "Efficient analytical fragility function fitting using dynamic structural analysis", Earthquake
// Spectra 31(1)).
//
// Model. P(failure | IM = x) = Phi( ln(x / theta) / beta ): the lognormal fragility with median theta (in the IM's
// unit) and logarithmic standard deviation beta. At level x_j, n_j motions are run and z_j fail; the z_j are taken
// as independent binomial draws, so the log-likelihood is (Baker 2015, eq 11)
//   ln L(theta, beta) = sum_j [ z_j ln p_j + (n_j - z_j) ln(1 - p_j) ] + const,   p_j = Phi( ln(x_j / theta) / beta ).
// The fit maximises it over (mu = ln theta, beta) by Nelder-Mead on (mu, ln beta) (Nelder & Mead 1965, standard
// coefficients 1, 2, 1/2, 1/2), started from the probit least-squares line through the levels whose fraction lies
// strictly between 0 and 1 (or the geometric middle of the IM range with beta = 0.4 when none does), then polished
// by Newton steps on the analytic gradient with a finite-difference Hessian. ln p and ln(1 - p) are evaluated as
// ln Phi(u) and ln Phi(-u) (Boost.Math normal CDF and its complement), so far tails lose no precision.
//
// Confidence band (delta method). The observed information I = -Hessian of ln L at the optimum (central differences
// of the analytic gradient) gives the asymptotic covariance C = I^-1 of (mu, beta). At IM x the probit
// u(x) = (ln x - mu) / beta has gradient (-1/beta, -u/beta), so var u = g^T C g, and the band at confidence level c
// is Phi(u -/+ z sqrt(var u)) with z = Phi^-1((1 + c) / 2). Working on the probit scale keeps the band inside (0, 1).
// The standard errors of mu and beta are sqrt(C_11), sqrt(C_22); theta's interval is exp(mu -/+ z se_mu).
//
// Degenerate data. With no failure, or failures only, there is no finite maximum: InputError. With perfectly
// separated data (every level either all-fail or none-fail) the maximum lies at beta -> 0: beta is bounded below by
// kMinimumBeta and `beta_at_bound` says so (the band is then not meaningful and is reported as the curve itself).
//
// Ensemble. fragility_analysis scales every motion so that its IM equals each level (the IMs offered are all
// proportional to the amplitude: factor = level / IM(motion)), runs the objects on the ensemble engine (all cores),
// and counts the failures per level.
//
// Pairs (two horizontal components with their azimuths, and optionally a vertical). The ensemble may instead be of
// motion sets (FragilitySpec::motion_sets). The IM is then the pair's RotD50 PGA (Boore 2010, rotd.hpp: the
// orientation-independent PGA that ground-motion models predict and `synth --components 2 --pga` scales to); each
// set is scaled as a whole (both horizontals and the vertical by one factor) so that its RotD50 PGA equals each level.
// A sliding block slides in two dimensions (sliding2d.hpp: slide_2d_summary, two-way on level ground; failure when
// max |u| > threshold). A rocking body stands at a bearing (oriented.hpp: rock_oriented_summary, the planar model
// under the projection of the pair on the bearing, with the vertical; a cylinder in its worst direction): the given
// bearing for every motion or, when none is given, a bearing drawn uniformly on [0, 360) deg for each motion
// (PortableRandom(bearing_seed), the i-th draw for the i-th motion, the same at every level: common random numbers
// across levels), i.e. objects standing at unknown, uniformly distributed orientations. A body in three dimensions
// (OverturnFailure::body_3d, `topple fragility --model 3d`: a box or a mesh's body) is instead run by the
// three-dimensional engine (rigid3d.hpp) on the pair along east and north and the vertical, its +x axis at the bearing
// (as `topple rock --model 3d --h2 --bearing-deg`): it rocks about any base edge and pivots on a corner under both
// components at once.
#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "topple/core/progress.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple {

/// Intensity measures proportional to the motion's amplitude (intensity.hpp).
enum class IntensityMeasure : std::uint8_t {
  pga,  ///< peak ground acceleration, m/s^2 (shown in g)
  pgv,  ///< peak ground velocity, m/s
  pgd,  ///< peak ground displacement, m
  cav,  ///< cumulative absolute velocity, m/s
};
/// "pga", "pgv", "pgd", "cav"; throws InputError naming `field`.
[[nodiscard]] IntensityMeasure parse_intensity_measure(std::string_view name, const std::string& field = "--im");
[[nodiscard]] std::string_view intensity_measure_name(IntensityMeasure im);
/// The measure of a motion, SI (m/s^2, m/s, m, m/s).
[[nodiscard]] double intensity_measure_si(const GroundMotion& motion, IntensityMeasure im);
/// The unit the measure is shown in ("g" for PGA, else SI: "m/s", "m", "m/s") and the factor from SI to it.
[[nodiscard]] std::string_view intensity_measure_unit(IntensityMeasure im);
[[nodiscard]] double intensity_measure_display_factor(IntensityMeasure im, double g_m_s2 = kStandardGravity);
/// The IM's column and key name with its unit: im_pga_g, im_pgv_m_s, im_pgd_m, im_cav_m_s.
[[nodiscard]] std::string_view intensity_measure_column(IntensityMeasure im);

inline constexpr double kMinimumBeta = 0.01;  ///< lower bound of beta in the fit (see the header)

/// Counts at each IM level.
struct FragilityData {
  std::vector<double> im;          ///< levels (> 0, any unit: theta comes out in the same unit)
  std::vector<int> trials;         ///< n_j >= 1
  std::vector<int> failures;       ///< 0 <= z_j <= n_j
};

struct LognormalFragilityFit {
  double theta = 0.0;              ///< median, in the IM's unit
  double beta = 0.0;               ///< logarithmic standard deviation
  double log_likelihood = 0.0;     ///< ln L at the optimum (binomial coefficients omitted)
  double se_ln_theta = 0.0;        ///< standard error of ln theta (observed information)
  double se_beta = 0.0;
  double cov_ln_theta_beta = 0.0;  ///< covariance of ln theta and beta
  int iterations = 0;
  bool beta_at_bound = false;      ///< separated data: beta = kMinimumBeta (see the header)

  /// Phi(ln(x / theta) / beta).
  [[nodiscard]] double probability(double im) const;
  /// Delta-method band at confidence `level` (e.g. 0.95): {lower, upper} probability at x.
  [[nodiscard]] std::pair<double, double> band(double im, double level = 0.95) const;
};

/// Maximum-likelihood lognormal fit (see the header). Throws InputError naming "im", "trials" or "failures" for
/// inconsistent data, and "failures" when there is no failure or only failures.
[[nodiscard]] LognormalFragilityFit fit_lognormal_fragility(const FragilityData& data);

/// Binomial log-likelihood of the data under (theta, beta), without binomial coefficients.
[[nodiscard]] double fragility_log_likelihood(const FragilityData& data, double theta, double beta);

// ---- Ensemble analysis ----

/// What fails: a friction block sliding more than a distance, or a rocking body overturning.
struct SlidingFailure {
  SlidingBlock block;
  double threshold_m = 0.0;  ///< failure when max |d| > threshold (m, >= 0)
};
struct OverturnFailure {
  RockingBody body;
  RockingOptions options;
  /// The coupled slide-rock model (slide_rock.hpp) instead of Housner's rocking: the body with its friction
  /// (SlideRockBody::from_rocking(body, mu, mu_k)), run with slide_rock_options(options); failure when it falls.
  /// Single-component ensembles only (the pairs' oriented model is the rocking one).
  std::optional<SlideRockBody> coupled;
  /// The three-dimensional engine (rigid3d.hpp: rocking about any base edge, pivoting on a corner, no sliding)
  /// instead of the planar oriented model (header, "Pairs"): a box or a mesh's body with its +x axis at the bearing,
  /// run by rock3d under the pair projected on east and north and the vertical, with options' g, restitution, e,
  /// rel_tol, max_run_out_s and max_steps; failure when it falls. Pairs only. `body` stays the planar body (along +x).
  std::optional<RigidBody3D> body_3d;
  /// The same for a solid cylinder: the rim engine (rigid3d_disc.hpp, rock3d_cylinder) under the pair along east and
  /// north and the vertical; axisymmetric, so no bearing. Pairs only. `body` stays the planar cylinder.
  std::optional<CylinderBody3D> cylinder_3d;
  /// A three-dimensional body (body_3d or cylinder_3d).
  [[nodiscard]] bool three_d() const noexcept { return body_3d.has_value() || cylinder_3d.has_value(); }
  /// Coulomb friction at the base of body_3d or cylinder_3d (Rigid3DOptions::mu_s, mu_k: the base slides flat,
  /// slide-rocks and flies as rigid3d.hpp and rigid3d_disc.hpp state; docs/method.md, "Slide-rock and flight in three
  /// dimensions", "A circular base with friction"). Absent: no contact slides (the no-slip engines, as before).
  std::optional<double> mu_3d;
  std::optional<double> mu_k_3d;  ///< kinetic, 0 <= mu_k <= mu; absent: mu
};

struct FragilitySpec {
  std::vector<std::shared_ptr<const GroundMotion>> motions;  ///< the ensemble (records or synthetic)
  IntensityMeasure im = IntensityMeasure::pga;
  std::vector<double> levels_si;  ///< IM levels, SI (> 0)
  std::optional<SlidingFailure> sliding;
  std::optional<OverturnFailure> overturning;
  /// An ensemble of pairs instead of `motions` (header, "Pairs"): each with two horizontal components and known
  /// azimuths; `im` must be pga (the RotD50 PGA).
  std::vector<std::shared_ptr<const MotionSet>> motion_sets;
  /// Under pairs: the rocking body's bearing, degrees clockwise from north (not for a cylinder); none: uniformly
  /// random per motion, from bearing_seed.
  std::optional<double> bearing_deg;
  std::uint64_t bearing_seed = 1;
  int threads = 0;  ///< 0: every core
  ProgressCallback progress{};  ///< runs done / to do (progress.hpp); empty: none
};

struct FragilityCurve {
  std::string name;  ///< "slide" or "overturn"
  FragilityData data;  ///< im in SI
  std::optional<LognormalFragilityFit> fit;  ///< theta in SI; none when the data cannot be fitted (see fit_note)
  std::string fit_note;  ///< why there is no fit (no failure, or failures only, on the grid)
};

struct FragilityResult {
  IntensityMeasure im = IntensityMeasure::pga;
  bool rotd50 = false;               ///< an ensemble of pairs: the IM is the RotD50 PGA
  std::vector<double> bearings_deg;  ///< under pairs: each motion's bearing (given or drawn), degrees
  std::vector<FragilityCurve> curves;  ///< slide first, then overturn, as asked
  std::size_t runs = 0;
};

// ---- As recorded: a fragility surface in PGA and PGV/PGA ----
//
// Precariously-balanced-rock studies report the overturning probability of a body as a function of two measures of
// the shaking, PGA and PGV/PGA, with the body's slenderness alpha fixed (Purvance, Anooshehpoor & Brune 2008,
// "Freestanding block overturning fragilities: numerical simulation and experimental validation", Earthquake Engng
// Struct. Dyn. 37, 791-808: overturning needs PGA above the static threshold g tan(alpha) and becomes likelier as
// the pulse lengthens, i.e. as PGV/PGA grows). topple fits, to the binary outcomes (record i, failed y_i) of records
// run as recorded (no rescaling), the probit surface
//   P(fail | PGA, PGV/PGA) = Phi( (ln PGA - ln theta(v)) / beta ),   ln theta(v) = ln theta_ref + gamma ln(v / v_ref),
// v = PGV/PGA (s): a lognormal fragility in PGA (as the scaled curve) whose median moves as a power of PGV/PGA
// (gamma < 0: longer pulses topple at lower PGA), with one dispersion beta. v_ref is the geometric mean of the
// records' v (it centres the regressor, so ln theta_ref and gamma are nearly uncorrelated). The form is a probit GLM
// P = Phi(a0 + a1 ln PGA + a2 ln(v / v_ref)), fitted by maximum likelihood (Newton-Raphson on the exact Hessian of
// the Bernoulli log-likelihood, sum_i y_i ln Phi(u_i) + (1 - y_i) ln Phi(-u_i)), and mapped back by beta = 1/a1,
// ln theta_ref = -a0/a1, gamma = -a2/a1; their covariance is the delta method on the inverse observed information.
// Degenerate data are refused (InputError naming "outcomes"): no failure or failures only, fewer than 3 records of
// either outcome, PGV/PGA that does not vary (then the surface is a curve: run the scaled fragility), and separated
// outcomes (a line in (ln PGA, ln v) splits them: the maximum likelihood lies at beta -> 0, no finite estimate).

/// One record's outcome: its PGA (m/s^2), its PGV (m/s), and whether the object failed.
struct SurfaceOutcome {
  double pga_m_s2 = 0.0;
  double pgv_m_s = 0.0;
  bool failed = false;
};

struct FragilitySurfaceFit {
  double ln_theta_ref = 0.0;  ///< ln of the median PGA (m/s^2) at v = v_ref
  double gamma = 0.0;         ///< d ln theta / d ln(PGV/PGA)
  double beta = 0.0;          ///< logarithmic standard deviation in PGA
  double v_ref_s = 0.0;       ///< geometric mean of the records' PGV/PGA, s
  double se_ln_theta_ref = 0.0;
  double se_gamma = 0.0;
  double se_beta = 0.0;
  std::array<std::array<double, 3>, 3> covariance{};  ///< of (ln theta_ref, gamma, beta)
  double log_likelihood = 0.0;
  int iterations = 0;
  std::size_t records = 0;
  std::size_t failures = 0;

  /// theta(v) = theta_ref (v / v_ref)^gamma, m/s^2.
  [[nodiscard]] double median_pga_m_s2(double pgv_over_pga_s) const;
  /// Phi((ln PGA - ln theta(v)) / beta).
  [[nodiscard]] double probability(double pga_m_s2, double pgv_over_pga_s) const;
};

/// Maximum-likelihood fit of the surface (see above). Throws InputError naming "outcomes" for degenerate data and for
/// a PGA or PGV that is not positive and finite.
[[nodiscard]] FragilitySurfaceFit fit_fragility_surface(std::span<const SurfaceOutcome> outcomes);

struct AsRecordedCurve {
  std::string name;                          ///< "slide" or "overturn"
  std::vector<bool> failed;                  ///< per record
  std::optional<FragilitySurfaceFit> fit;    ///< none when the outcomes cannot be fitted (fit_note says why)
  std::string fit_note;
};

struct AsRecordedResult {
  std::vector<double> pga_m_s2;  ///< per record
  std::vector<double> pgv_m_s;   ///< per record
  std::vector<AsRecordedCurve> curves;  ///< slide first, then overturn, as asked
  std::size_t runs = 0;
};

/// Runs every motion of spec.motions once, as recorded (no scaling; spec.levels_si and spec.im unused), on each
/// object, and fits each curve's surface. Throws InputError naming "motions" (none, pairs, a motion with zero PGA or
/// PGV), "object" or "threshold".
[[nodiscard]] AsRecordedResult as_recorded_analysis(const FragilitySpec& spec);

/// Runs every motion scaled to every level on each object and fits each curve (a curve with no failure or only
/// failures on the grid keeps its counts and gets no fit). Throws InputError naming "motions", "levels", "object"
/// (neither failure mode given) or "threshold"; under pairs also "motions" (both kinds given, a set without a second
/// component or azimuths, a zero pair), "im" (not pga), "mode" / "slope" (a one-way or inclined block) and "bearing"
/// (not finite, or given for a cylinder); "model" for a coupled body under pairs, or a three-dimensional body (body_3d,
/// cylinder_3d) with single components or with the coupled model.
[[nodiscard]] FragilityResult fragility_analysis(const FragilitySpec& spec);

}  // namespace topple
