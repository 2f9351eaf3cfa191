#pragma once
// Internals of the inversion shared by inversion.cpp (one component) and inversion_3c.cpp (three components).
#include <cstdint>
#include <vector>

#include "topple/inversion/inversion.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/solvers/slide_rock.hpp"
#include "topple/motion/synthesis.hpp"

namespace topple::detail {

/// A 64-bit hash of two numbers (SplitMix64 of a * golden + b): the seeds of motion k and object o.
[[nodiscard]] std::uint64_t mix(std::uint64_t a, std::uint64_t b);

/// The synthesis of motion k of a synthetic family's column (inversion.hpp): 20 samples per period of the column's
/// frequency (at most 0.01 s), at least 8 periods, seed mix(settings.seed, k + 1) in every column.
[[nodiscard]] SynthesisSpec family_spec(const InversionSettings& settings, double freq_hz, int k);

/// The three-component synthesis of motion k (inversion_3c.hpp, item 1): family_spec with a step of 1 / (20 f_v)
/// (at most 0.01 s), the survey's coherence, components called east (first) and north (second), a vertical.
[[nodiscard]] SynthesisSetSpec family_set_spec(const InversionSettings& settings, double freq_hz, int k);

/// The match of a sliding observation (inversion.hpp, item 2) from a run's max |displacement| and residual distance
/// (m): not_slid: max < 2 mm; a measured distance: its Gaussian kernel; slid_at_least: residual >= it; slid: max >= 2 mm.
[[nodiscard]] double sliding_match(const ObservedObject& object, double max_displacement_m, double residual_m);
/// The rocking options of the inversion's runs: restitution as the object gives it, 20 s run-out, rel_tol 1e-6.
[[nodiscard]] RockingOptions inversion_rocking_options(const ObservedObject& object, const DrawnParameters& parameters,
                                                      double g_m_s2);
/// The coupled runs' options: those of inversion_rocking_options (restitution, 20 s run-out, rel_tol 1e-6).
[[nodiscard]] SlideRockOptions inversion_slide_rock_options(const ObservedObject& object,
                                                           const DrawnParameters& parameters, double g_m_s2);
/// The match of any observation of an object simulated with the coupled model, from the run's summary: the one place
/// the coupled solver's results become outcomes (docs/survey.md, "Objects that slide and rock").
[[nodiscard]] double coupled_match(const ObservedObject& object, const SlideRockSummary& summary);
/// The match (0 or 1) of a rocking observation for a run that overturned or not, with its max |theta| (rad).
[[nodiscard]] double rocking_match(Outcome outcome, bool overturned, double max_rotation_rad);

/// tan(alpha) of a body's uplift threshold g tan(alpha) in a static threshold: an asymmetric body's smaller one for a
/// lower threshold (it rocked), its larger one for an upper threshold (it did not), the weaker claim.
[[nodiscard]] double uplift_tan_alpha(const RockingBody& body, bool lower);
/// Fills the aggregates of the per-object thresholds b.lower and b.upper: lower_g, upper_g, their hard ones, and the
/// contradictions (a lower threshold above an upper one).
void settle_static_bounds(StaticBounds& b);

/// The 3 x 3 neighbourhood of a cell with weights 4/2/1 (inversion.hpp, item 2).
[[nodiscard]] std::vector<std::pair<std::size_t, double>> neighbourhood(std::size_t c, std::size_t np,
                                                                        std::size_t nf);

}  // namespace topple::detail
