#pragma once
// Matching an observed object to its solver, in one place: the parameters it is run with, the motion it feels (its
// amplification, its flexible support, its orientation), the solver and the solver's options its model calls for,
// and how a run's result becomes a match m in [0, 1] with the observation (inversion.hpp, item 2). The inversion's
// runs (observation_match) and the report's replay of the best cell (report.hpp) both go through these functions, so
// that the report draws what the inversion ran.
#include <cstddef>
#include <cstdint>

#include "topple/motion/ground_motion.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/survey/survey.hpp"

namespace topple {

/// The parameters of one run of an object, drawn from the survey's ranges (draw_parameters) or at their middles
/// (nominal_parameters).
struct DrawnParameters {
  double mu = 0.0;              ///< friction coefficient (dimensionless)
  double e = 0.0;               ///< restitution (dimensionless), used when !object.e_housner
  double amplification = 1.0;   ///< support motion / ground motion (dimensionless)
  double support_freq_hz = 0.0;  ///< the flexible support's frequency (Hz), when the object has a support_filter
  double support_damping = 0.0;  ///< its damping ratio (decimal), likewise
};

/// The drawn parameters of object o for motion k (deterministic in seed, k, o; uniform in each range).
[[nodiscard]] DrawnParameters draw_parameters(const ObservedObject& object, std::uint64_t seed, std::size_t k,
                                              std::size_t o);

/// The parameters at the middle of each range (restitution: Housner's where the object says so): the report's
/// replay of one motion.
[[nodiscard]] DrawnParameters nominal_parameters(const ObservedObject& object);

/// The motion an object feels on its support before amplification: the ground's, or, on a flexible support
/// (survey.hpp: SupportFilter), the support's absolute acceleration (flexible.hpp: support_motion) with the
/// parameters' frequency and damping.
[[nodiscard]] GroundMotion object_motion(const ObservedObject& object, const DrawnParameters& parameters,
                                         const GroundMotion& ground);

/// object_motion at the nominal parameters (for the report's replay).
[[nodiscard]] GroundMotion nominal_object_motion(const ObservedObject& object, const GroundMotion& ground);

/// The factor on the support's motion that a rocking or coupled body feels in its rocking plane: the amplification
/// times cos(orientation) (the object's orientation_deg from the motion's direction, when given). A sliding block
/// feels the amplification alone (level ground, isotropic friction).
[[nodiscard]] double rocking_plane_factor(const ObservedObject& object, const DrawnParameters& parameters);

/// The rocking runs' options: restitution as the object gives it, 20 s run-out, rel_tol 1e-6 (outcomes, fell or not,
/// rocked visibly or not, do not need the 1e-8 default).
[[nodiscard]] RockingOptions inversion_rocking_options(const ObservedObject& object, const DrawnParameters& parameters,
                                                      double g_m_s2);
/// The coupled runs' options: those of inversion_rocking_options (slide_rock_options, slide_rock.hpp).
[[nodiscard]] SlideRockOptions inversion_slide_rock_options(const ObservedObject& object,
                                                           const DrawnParameters& parameters, double g_m_s2);

/// The one-sigma width (m) of the Gaussian kernel that scores a measured sliding distance: the larger of the given
/// slid_uncertainty, 25 % of slid (a distance read off marks is rarely better than that) and kVisibleSlipM (2 mm).
/// docs/survey.md states this floor; the survey keeps the given value, the report shows the one used.
[[nodiscard]] double sliding_sigma_m(const ObservedObject& object);

/// The match of a sliding observation (inversion.hpp, item 2) from a run's max |displacement| and residual distance
/// (m): not_slid: max < 2 mm; a measured distance: its Gaussian kernel; slid_at_least: residual >= it; slid: max >= 2 mm.
[[nodiscard]] double sliding_match(const ObservedObject& object, double max_displacement_m, double residual_m);
/// The match (0 or 1) of a rocking observation for a run that overturned or not, with its max |theta| (rad).
[[nodiscard]] double rocking_match(Outcome outcome, bool overturned, double max_rotation_rad);
/// The match of any observation of an object simulated with the coupled model, from the run's summary: the one place
/// the coupled solver's results become outcomes (docs/survey.md, "Objects that slide and rock").
[[nodiscard]] double coupled_match(const ObservedObject& object, const SlideRockSummary& summary);

/// Per-run match of an object's observation: simulate `object` with the given parameters under `motion` (already
/// scaled to the cell's PGA; filtered here through the object's flexible support, if it has one) with the solver of
/// its model (survey.hpp, object_model) and compare with the observation.
[[nodiscard]] double observation_match(const ObservedObject& object, const DrawnParameters& parameters,
                                       const GroundMotion& motion, double g_m_s2);

}  // namespace topple
