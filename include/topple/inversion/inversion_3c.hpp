#pragma once
// The main job in three components ([inversion] components = 3): two horizontal components and a vertical, objects
// at bearings, bidirectional sliding, and the direction of strongest shaking. docs/method.md, "Inversion in three
// components", has the equations; this header states the model.
//
// 1. Family. Motion k of column j is synthesize_set (synthesis.hpp) of the one-component family's spec (same seed
//    mix(seed, k + 1), same envelope and filter), with the survey's coherence rho and the synthesis' V/H model
//    (PGA_v = 2/3 RotD50, f_v = 1.5 f_h, capped at the synthesis' 20 Hz); its step is 1 / (20 f_v) (at most 0.01 s)
//    so that the vertical too has 20 samples a period. The pair is rotated onto its major axis: the principal axis of
//    the horizontal acceleration, the direction psi maximising sum_i (a_E,i sin psi + a_N,i cos psi)^2,
//    tan 2 theta = 2 S_EN / (S_EE - S_NN), theta from east (Penzien & Watabe 1975, EESD 3(4)). The three components
//    are then time-scaled together so that the major-axis component's measured predominant frequency (spectra.hpp)
//    is the column's: the frequency axis is that of the strongest direction. The realisation is kept in that frame
//    (major, minor = major + 90 deg clockwise, vertical) and scaled so that the pair's RotD50 PGA is 1 m/s^2: the
//    PGA axis of the grid is RotD50 (Boore 2010).
// 2. Orientation. The direction of strongest shaking Psi (the azimuth of the actual motion's major axis, mod 180) is
//    a parameter on a grid of `directions` bins of width w = 180 / directions, centres 0, w, 2w, ... In bin b,
//    realisation k's major axis points at Psi_b + delta_k, delta_k uniform in [-w/2, w/2) (PortableRandom, seeded
//    by the survey's seed and k: common random numbers across cells and bins), so that summed over the bins the
//    realisation's orientation is uniformly random. Rotating a realisation by 180 deg flips the sign of both
//    horizontals: a symmetric rocking body's outcome and the sliding distance are unchanged and the sliding
//    direction reverses, so each bin is an axis.
// 3. Objects. A rocking object of bearing beta feels the projection of the horizontal pair on beta (motion_set.hpp
//    eq. M1) at the angle gamma = beta - Psi_b - delta_k from the major axis, with the vertical (the planar rocking
//    model, rocking.hpp, g -> g + a_v): one run per bin. Unknown bearing: gamma uniform in [0, 180) per (motion k,
//    object), the same in every cell and bin (a Monte Carlo marginal, as mu's range): one run. A block with a `depth`
//    is a box (oriented.hpp, "Box"): it rocks along gamma and gamma + 90 (half-width depth / 2), and the governing
//    axis' response is scored (two runs where a block has one). A cylinder rocks in
//    the realisation's RotD100 direction (its worst: the largest peak), an approximation of three-dimensional
//    rocking. A sliding object runs the bidirectional solver (sliding2d.hpp) on the pair and the vertical once; its
//    residual distance does not depend on the orientation (isotropic friction) and its direction is the solver's
//    azimuth (from the major axis) + Psi_b + delta_k. Where the vertical lifts a rocking body off (g + a_v <= 0
//    somewhere; at a RotD50 PGA >= about 1.2 g with V/H = 2/3), the planar model does not hold: the run scores as
//    overturned. Amplification multiplies all three components; a flexible support filters the two horizontals
//    (flexible.hpp: support_motion) and passes the vertical unchanged.
// 4. Likelihood. As the one-component model (inversion.hpp, item 2) with the match m(c, k, o, b) per bin: L(c, b) is
//    the 3 x 3-pooled average over motions of the product over objects of eps + (1 - 2 eps) m. A measured sliding
//    distance scores the Gaussian kernel of inversion.hpp; a sliding direction theta_obs scores
//      m_dir = 1/2 [v(theta - theta_obs) + v(theta + 180 - theta_obs)],   v(x) = exp(kappa (cos x - 1)),
//    kappa = kSlidDirectionKappa (a von Mises error of the direction read from marks, circular standard deviation
//    about 21 deg), the two terms the two senses of the axis; the distance's and the direction's kernels multiply.
//    A block that never moved has no direction: m_dir is then the kernel's mean over a uniform direction,
//    exp(-kappa) I_0(kappa). An observed fall direction (toppled_azimuth_deg: a cylinder or a box that overturned)
//    multiplies the match of a run that overturned by the same kernel of the model's fall axis, turned by
//    Psi_b + delta_k: a box's governing axis (bearing or bearing + 90); a cylinder's governing direction on
//    oriented.hpp's 15-degree grid (such a cylinder is run there, 12 runs, rather than in the RotD100 direction: the
//    direction it falls first, not the one of the largest peak); a run lifted off by the vertical has none (the
//    kernel's mean). The realisation's RotD100 direction lies within about 15 deg of its major axis, its residual
//    sliding direction within about 40: a toppled column tells the direction more sharply than a slid block
//    (docs/method.md).
//    A block without depth falls along its bearing by the planar model: its fall direction adds nothing (the survey
//    refuses it).
// 5. Posterior. Uniform over log PGA x log frequency x direction bins; the PGA and frequency marginals sum over the
//    bins (InversionResult's log_likelihood is log of the bins' mean), the direction's over the cells.
//    Direction: mode, axial circular mean, and the shortest arcs holding the 68 % and 95 % highest-posterior bins.
//    Unconstrained: the 95 % arc spans more than kUnconstrainedArcDeg.
// 6. Static thresholds (docs/method.md, "Static thresholds in three components"). Uplift and slip depend on the
//    horizontal acceleration vector a(t) and the vertical: uplift about the edges of bearing beta needs
//    |a(t) . e_beta| > (g + a_v(t)) tan alpha, slip needs |a(t)| > mu (g + a_v(t)). Every projection's peak is at most
//    A = max_t |a(t)|, which is RotD100 PGA (the peak over all directions), and the family's vertical peak is at most
//    rho RotD50 <= rho A (rho: the family's largest PGA_v / RotD50, 2/3 nominally). So an object that rocked or
//    overturned (s = tan alpha; a box: its smaller one) or slid (s = mu) on a support of gain H (amplification, and a
//    flexible support's peak gain) with vertical gain V gives the hard threshold
//      RotD100 > s / (H + V rho s)                                                                     (S3a)
//    whatever its bearing; and, as RotD50 >= kRotD50FloorOfRotD100 RotD100 for every pair (the 1-degree grid's
//    median of |cos|), the hard but weaker
//      RotD50 > c s / (H + c V rho s),   c = kRotD50FloorOfRotD100.                                      (S3b)
//    An object that did not slide visibly gives RotD100 <= mu / (A_lo (1 - rho mu)) (soft, as in one component; it
//    bounds RotD50 <= RotD100 by the same number), and so does a box that did not rock (s = hypot of its two
//    tan alpha: both projections bounded bound the vector) and a cylinder (every direction: s = tan alpha). A planar
//    block that did not rock bounds only the projection on its bearing, which bounds no direction-free measure: no
//    threshold. InversionResult::rotd100_bounds holds (S3a), InversionResult::bounds (S3b), the PGA axis of the
//    estimates.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "topple/inversion/direction.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// Von Mises concentration of the error of an observed sliding direction (dimensionless; circular standard deviation
/// sqrt(-2 ln(I_1(8) / I_0(8))) = 0.36 rad = 21 deg).
inline constexpr double kSlidDirectionKappa = 8.0;
/// The direction of strongest shaking is reported as unconstrained when its 95 % arc spans more than this, deg (two
/// thirds of the half circle: the bearings rule out less than a third of the directions).
inline constexpr double kUnconstrainedArcDeg = 120.0;

/// The smallest RotD50 / RotD100 of any horizontal pair on rotd.hpp's angles 0, 1, ..., 179 deg (dimensionless):
/// (cos 45 deg + cos 45.5 deg) / 2. At the sample of the vector peak A, Y(theta) >= A |cos(theta - phi)|; at least 90
/// of the 180 angles lie within 45 deg of phi and 91 within 45.5 deg, so the 90th and 91st largest Y, whose mean is
/// RotD50, are at least A cos 45 and A cos 45.5 deg; and RotD100 <= A. (1 / sqrt 2 on continuous angles.)
inline constexpr double kRotD50FloorOfRotD100 = 0.7040080227431993;

/// The static thresholds of a three-component site (header, item 6): on RotD100 PGA (S3a), where they hold, and their
/// consequence on RotD50 PGA (S3b), per object in the same order in both. `vertical_ratio` is rho (>= 0; 0: no
/// vertical). Reasons name the axis.
struct ThreeComponentBounds {
  StaticBounds rotd100;
  StaticBounds rotd50;
};
[[nodiscard]] ThreeComponentBounds static_bounds_3c(const Site& site, double vertical_ratio);

/// One realisation of the three-component family in its major-axis frame (header, item 1). RotD50 PGA 1 m/s^2.
struct Realisation3c {
  std::shared_ptr<const GroundMotion> major;     ///< along the major axis (azimuth 0 of the frame), m/s^2
  std::shared_ptr<const GroundMotion> minor;     ///< 90 deg clockwise from it, m/s^2
  std::shared_ptr<const GroundMotion> vertical;  ///< positive up, m/s^2
  double rotd100_angle_deg = 0.0;     ///< direction of the largest peak, deg clockwise from the major axis, [0, 180)
  double larger_component_ratio = 1.0;  ///< max(PGA_E, PGA_N) of the synthesised pair / RotD50 (dimensionless)
  double rotd100_ratio = 1.0;           ///< RotD100 / RotD50 (dimensionless)
  double measured_freq_hz = 0.0;        ///< the major-axis component's measured predominant frequency, Hz
};

/// Realisation k of the column at freq_hz (header, item 1), the same bits for the same settings everywhere the
/// synthesis is.
[[nodiscard]] Realisation3c family_realisation_3c(const InversionSettings& settings, double freq_hz, int k);

struct FamilyGrid3c {
  std::vector<std::vector<Realisation3c>> motions;  ///< [column j][motion k]
  std::vector<double> freq_hz;                      ///< Hz
  std::vector<double> measured_freq_hz;             ///< per column, mean of the realisations', Hz
};
[[nodiscard]] FamilyGrid3c build_family_3c(const InversionSettings& settings, const std::vector<double>& freq_hz,
                                           const InversionOptions& options = {});

/// The direction bins' centres, deg: 0, w, 2w, ... (w = 180 / settings.directions).
[[nodiscard]] std::vector<double> direction_bins_deg(const InversionSettings& settings);
/// delta_k (header, item 2), deg in [-w/2, w/2).
[[nodiscard]] double direction_jitter_deg(const InversionSettings& settings, std::size_t k);
/// The angle from the major axis of an object of unknown bearing under motion k (header, item 3), deg in [0, 180).
[[nodiscard]] double unknown_bearing_angle_deg(std::uint64_t seed, std::size_t k, std::size_t o);

/// The matches of one run at every bin (header, items 3-4): `major`, `minor`, `vertical` are the realisation at the
/// cell's PGA; `major_azimuth_deg[b]` = Psi_b + delta_k; `unknown_angle_deg` the draw for an object without bearing.
/// Writes one match per bin into `out` (its size is the number of bins).
void observation_match_3c(const ObservedObject& object, const DrawnParameters& parameters, const GroundMotion& major,
                          const GroundMotion& minor, const GroundMotion& vertical, double rotd100_angle_deg,
                          std::span<const double> major_azimuth_deg, double unknown_angle_deg, double g_m_s2,
                          std::span<double> out);

/// The direction estimate from a posterior over the bins (header, item 5).
[[nodiscard]] DirectionEstimate direction_estimate(const std::vector<double>& bins_deg,
                                                   const std::vector<double>& posterior);

/// The three-component inversion of one site on a built family: the one pipeline of invert_sites (inversion.hpp)
/// with this family's runs, one match table per direction bin (what invert_site does for components = 3).
[[nodiscard]] InversionResult invert_site_3c(const Site& site, const InversionSettings& settings,
                                             const FamilyGrid3c& family, const InversionOptions& options = {});

/// The sentence the summary adds for a three-component result: the PGA axis (RotD50, with the larger-component
/// median) and the direction of strongest shaking or that it is unconstrained.
[[nodiscard]] std::string three_component_summary(const InversionResult& result);

}  // namespace topple
