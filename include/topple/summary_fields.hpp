#pragma once
// The field tables of the solvers' results (topple/field.hpp): one table per result type, read by the JSON writers
// (io::sliding_summary_json, io::rocking_summary_json), the result columns of a sweep (make_plan) and the Python
// properties of SlidingResult and RockingResult. A field is added, renamed or converted here, once.
//
// A result is read together with the inputs that some fields report (the yield accelerations need the block, the
// restitution mode the options), hence the small views below.
#include <array>

#include "topple/field.hpp"
#include "topple/rocking.hpp"
#include "topple/sliding.hpp"
#include "topple/sliding2d.hpp"
#include "topple/slide_rock.hpp"

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

/// Sliding: the 12 results (max_abs_displacement_m ... yield_up_g, the sweep's result columns in this order), then
/// the block as run (mu_static, mu_kinetic, slope_deg, mode, g_m_s2). Optional times are null when they never
/// happened; yield_up_g is null for a one-way block (which never slips up-slope).
extern const std::array<Field<SlidingOutcome>, 17> kSlidingFields;

/// Bidirectional sliding (sliding2d.hpp): the results in the order of `topple slide --h2 --json`, then the block
/// (mu_static, mu_kinetic, g_m_s2). Not a sweep's result (sweep_column -1). residual_azimuth_deg is null when the
/// block never moved; optional times are null when they never happened.
extern const std::array<Field<Sliding2dOutcome>, 20> kSliding2dFields;

/// Rocking: in the order of `topple rock --json` (max_abs_rotation_rad ... g_m_s2); 19 of them are the sweep's
/// result columns (in their sweep_column order), the others (alpha_deg, R_m, e_mode, onset_accel_ratio, mu, g_m_s2)
/// only JSON and Python. Not fields: warnings (a list), body and solver (nested objects in the JSON).
extern const std::array<Field<RockingOutcome>, 25> kRockingFields;

/// A coupled slide-rock run's summary with its body and options (slide_rock.hpp).
struct SlideRockOutcome {
  const SlideRockSummary& summary;
  const SlideRockBody& body;
  const SlideRockOptions& options;
};

/// Coupled slide-rock: in the order of `topple sliderock --json` (overturned ... g_m_s2). Not a sweep's result
/// (sweep_column -1). Optional times are null when they never happened; overturned_side is 0 when it did not fall.
/// Not fields: modes (per mode: entries and first time; a nested object in the JSON), warnings, body.
extern const std::array<Field<SlideRockOutcome>, 27> kSlideRockFields;

}  // namespace topple
