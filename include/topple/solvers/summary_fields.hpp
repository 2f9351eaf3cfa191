#pragma once
// The field tables of the solvers' results (topple/core/field.hpp): one table per result type, read by the JSON writers
// (io::sliding_summary_json, io::rocking_summary_json), the result columns of a sweep (make_plan) and the Python
// properties of SlidingResult and RockingResult. A field is added, renamed or converted here, once.
//
// A result is read together with the inputs that some fields report (the yield accelerations need the block, the
// restitution mode the options), hence the small views below.
#include <array>

#include "topple/core/field.hpp"
#include "topple/motion/ground_motion.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/solvers/sliding2d.hpp"
#include "topple/solvers/slide_rock.hpp"

namespace topple {

/// A sliding run's summary with the block it was run for.
struct SlidingOutcome {
  const SlidingSummary& summary;
  const SlidingBlock& block;
};

/// A bidirectional sliding run's summary with its block.
struct Sliding2dOutcome {
  const Sliding2dSummary& summary;
  const SlidingBlock& block;
};

/// A rocking run's summary with its body and options.
struct RockingOutcome {
  const RockingSummary& summary;
  const RockingBody& body;
  const RockingOptions& options;
};

/// A motion's intensity measures (intensity_measures) with the motion and the gravity its values in g use.
struct IntensityOutcome {
  const GroundMotion& motion;
  const IntensityMeasures& measures;
  double g_m_s2;
};

/// Sliding: the 12 results (max_abs_displacement_m ... yield_up_g, the sweep's result columns in this order), then
/// the block as run (mu_static, mu_kinetic, slope_deg, mode, g_m_s2). Optional times are null when they never
/// happened; yield_up_g is null for a one-way block (which never slips up-slope).
extern const std::array<Field<SlidingOutcome>, 17> kSlidingFields;

/// Bidirectional sliding (sliding2d.hpp): the results in the order of `topple slide --h2 --json`, then the block
/// (mu_static, mu_kinetic, g_m_s2). The first 14 (residual_displacement_m ... contact_lost_time_s, sweep_column 0-13)
/// are a sweep's result columns for sliding objects under [[motions.set]]; the works and integrator_steps are not
/// (the step count is the integrator's, not the physics'). residual_azimuth_deg is null when the block never moved;
/// optional times are null when they never happened.
extern const std::array<Field<Sliding2dOutcome>, 20> kSliding2dFields;

/// Rocking: in the order of `topple rock --json` (max_abs_rotation_rad ... g_m_s2); 19 of them are the sweep's
/// result columns (in their sweep_column order), the others (alpha_deg, R_m, e_mode, onset_accel_ratio, mu, g_m_s2)
/// only JSON and Python. Not fields: warnings (a list), body and solver (nested objects in the JSON).
extern const std::array<Field<RockingOutcome>, 25> kRockingFields;

/// Rocking, per side (theta > 0: about O+, the +x edge, b2; theta < 0: about O-, b1): alpha_negative_rad,
/// max_rotation_positive_rad, max_rotation_negative_rad, max_rotation_over_alpha_positive,
/// max_rotation_over_alpha_negative, e_onto_negative, exceeded_alpha_side and overturned_side ("positive",
/// "negative", or null when it never happened; the words of `topple rock --json`'s "sides"). A sweep's result
/// columns after kRockingFields' (sweep_column 0-7 among these), present only when the sweep has an asymmetric body,
/// so that a sweep without one keeps its columns.
extern const std::array<Field<RockingOutcome>, 8> kRockingSideFields;

/// A motion's intensity measures, as `topple info --json` prints them for each component (after the record's
/// metadata) and `topple.intensity` returns them: npts, uniform, dt_s, start_time_s, duration_s, pga_g, pga_m_s2,
/// pga_time_s, pgv_m_s, pgd_m, arias_m_s, d5_95_s, d5_time_s, d95_time_s, cav_m_s, tp_s, tm_s,
/// predominant_frequency_hz, g_m_s2; null where a measure is undefined (a zero record has no D5-95 or Tp).
extern const std::array<Field<IntensityOutcome>, 19> kIntensityFields;

/// A coupled slide-rock run's summary with its body and options (slide_rock.hpp).
struct SlideRockOutcome {
  const SlideRockSummary& summary;
  const SlideRockBody& body;
  const SlideRockOptions& options;
};

/// Coupled slide-rock: in the order of `topple rock --model coupled --json` (overturned ... g_m_s2). Not a sweep's result
/// (sweep_column -1). Optional times are null when they never happened; overturned_side is "positive", "negative" or null (as kRockingSideFields).
/// Not fields: modes (per mode: entries and first time; a nested object in the JSON), warnings, body.
extern const std::array<Field<SlideRockOutcome>, 30> kSlideRockFields;

}  // namespace topple
