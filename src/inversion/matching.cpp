// Matching an observed object to its solver (matching.hpp): parameters, the motion it feels, options, and the match of
// a run with the observation.
#include "topple/inversion/matching.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

#include "topple/core/units.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/solvers/sliding.hpp"
#include "inversion/inversion_detail.hpp"

namespace topple {

DrawnParameters draw_parameters(const ObservedObject& object, std::uint64_t seed, std::size_t k, std::size_t o) {
  PortableRandom rng(detail::mix(detail::mix(seed, k + 1), o + 1));
  const auto draw = [&](const Interval& iv) { return iv.is_value() ? iv.low : iv.low + (iv.high - iv.low) * rng.uniform(); };
  DrawnParameters p;
  p.mu = draw(object.mu);
  p.e = object.e_housner ? housner_restitution(object.body) : draw(object.e);
  p.amplification = draw(object.amplification);
  // Drawn last, and only for a flexible support: the draws above, and with them a survey without one, are unchanged.
  if (object.support_filter) {
    p.support_freq_hz = draw(object.support_filter->freq_hz);
    p.support_damping = draw(object.support_filter->damping);
  }
  return p;
}

DrawnParameters nominal_parameters(const ObservedObject& object) {
  DrawnParameters p;
  p.mu = object.mu.mid();
  p.e = object.e_housner ? housner_restitution(object.body) : object.e.mid();
  p.amplification = object.amplification.mid();
  if (object.support_filter) {
    p.support_freq_hz = object.support_filter->freq_hz.mid();
    p.support_damping = object.support_filter->damping.mid();
  }
  return p;
}

namespace {
/// The motion on the object's flexible support (its absolute acceleration, decoupled), or none for a rigid support
/// (which spares a copy of the ground's).
std::optional<GroundMotion> on_flexible_support(const ObservedObject& object, const DrawnParameters& p,
                                                const GroundMotion& ground) {
  if (!object.support_filter) return std::nullopt;
  return support_motion(ground, SupportOscillator::make(p.support_freq_hz, p.support_damping));
}
}  // namespace

GroundMotion object_motion(const ObservedObject& object, const DrawnParameters& p, const GroundMotion& ground) {
  std::optional<GroundMotion> filtered = on_flexible_support(object, p, ground);
  return filtered ? std::move(*filtered) : ground;
}

GroundMotion nominal_object_motion(const ObservedObject& object, const GroundMotion& ground) {
  return object_motion(object, nominal_parameters(object), ground);
}

double rocking_plane_factor(const ObservedObject& object, const DrawnParameters& p) {
  double factor = p.amplification;
  if (object.orientation_deg) factor *= std::cos(deg_to_rad(*object.orientation_deg));
  return factor;
}

RockingOptions inversion_rocking_options(const ObservedObject& object, const DrawnParameters& p, double g) {
  RockingOptions options;
  options.g_m_s2 = g;
  if (!object.e_housner) {
    options.restitution = RestitutionMode::given;
    options.e = p.e;
  }
  options.max_run_out_s = 20.0;
  options.rel_tol = 1e-6;  // outcomes (fell or not, rocked visibly or not) do not need the 1e-8 default
  return options;
}

SlideRockOptions inversion_slide_rock_options(const ObservedObject& object, const DrawnParameters& p, double g) {
  // The rocking runs' choices (inversion_rocking_options): restitution as the object gives it, 20 s run-out,
  // rel_tol 1e-6 (outcomes, not histories).
  return slide_rock_options(inversion_rocking_options(object, p, g));
}

double sliding_sigma_m(const ObservedObject& object) {
  const double d = object.slid_m.value_or(0.0);
  return std::max({object.slid_uncertainty_m, 0.25 * d, kVisibleSlipM});
}

double sliding_match(const ObservedObject& object, double max_displacement_m, double residual_m) {
  if (object.outcome == Outcome::not_slid) return max_displacement_m < kVisibleSlipM ? 1.0 : 0.0;
  if (object.slid_m) {
    const double z = (residual_m - *object.slid_m) / sliding_sigma_m(object);
    return std::exp(-0.5 * z * z);
  }
  if (object.slid_at_least_m) return residual_m >= *object.slid_at_least_m ? 1.0 : 0.0;
  return max_displacement_m >= kVisibleSlipM ? 1.0 : 0.0;
}

double rocking_match(Outcome outcome, bool overturned, double max_rotation_rad) {
  switch (outcome) {
    case Outcome::overturned: return overturned ? 1.0 : 0.0;
    case Outcome::not_overturned: return overturned ? 0.0 : 1.0;
    case Outcome::rocked: return !overturned && max_rotation_rad >= kVisibleRockingRad ? 1.0 : 0.0;
    case Outcome::not_rocked: return !overturned && max_rotation_rad < kVisibleRockingRad ? 1.0 : 0.0;
    default: return 0.0;
  }
}

double coupled_match(const ObservedObject& object, const SlideRockSummary& s) {
  // The one mapping from the coupled solver's results to the outcomes (docs/survey.md, "Objects that slide and
  // rock"). The offset a surveyor measures is the net one, u at the end (at rest theta = 0, so the base's offset).
  const double max_rotation = std::max(s.max_rotation_positive_rad, s.max_rotation_negative_rad);
  const double residual = std::abs(s.residual_slide_m);
  const bool visibly_slid = s.max_abs_slide_m >= kVisibleSlipM;
  switch (object.outcome) {
    case Outcome::slid:
    case Outcome::not_slid:
      return sliding_match(object, s.max_abs_slide_m, residual);
    case Outcome::overturned:
    case Outcome::not_overturned:
    case Outcome::rocked:
    case Outcome::not_rocked:
      return rocking_match(object.outcome, s.overturned, max_rotation);
    case Outcome::slid_stood:  // stood, and slid as observed (a distance, at least a distance, or visibly)
      return s.overturned ? 0.0 : sliding_match(object, s.max_abs_slide_m, residual);
    case Outcome::slid_toppled:  // fell, and its base had slid visibly
      return s.overturned && visibly_slid ? 1.0 : 0.0;
    case Outcome::walked: {  // stood, rocked visibly with impacts, offset, never slid flat on its base
      const bool never_slid_flat = s.mode_entries[static_cast<std::size_t>(SlideRockMode::slide)] == 0;
      return !s.overturned && max_rotation >= kVisibleRockingRad && s.impacts > 0 && residual >= kVisibleSlipM &&
                     never_slid_flat
                 ? 1.0
                 : 0.0;
    }
  }
  return 0.0;
}

double observation_match(const ObservedObject& object, const DrawnParameters& p, const GroundMotion& ground,
                         double g) {
  const std::optional<GroundMotion> filtered = on_flexible_support(object, p, ground);
  const GroundMotion& motion = filtered ? *filtered : ground;
  const ObjectModel model = object_model(object);  // survey.hpp: the rule
  if (model == ObjectModel::slide) {
    // Level ground, no vertical input: the response to amp * a with mu is amp times the response to a with
    // mu / amp (divide the equation of motion by amp), which spares a copy of the motion.
    const double amp = p.amplification;
    const SlidingSummary s = slide_summary(motion, SlidingBlock::make(p.mu / amp, p.mu / amp, 0.0, SlidingMode::two_way, g));
    const double max_d = amp * s.max_abs_displacement_m;
    const double residual = amp * std::abs(s.residual_displacement_m);
    return sliding_match(object, max_d, residual);
  }
  const double factor = rocking_plane_factor(object, p);
  if (model == ObjectModel::coupled) {
    // The coupled body in the object's rocking plane (the plane the orientation refers to), mu_s = mu_k = mu.
    const SlideRockOptions options = inversion_slide_rock_options(object, p, g);
    const SlideRockBody body = SlideRockBody::from_rocking(object.body, p.mu);
    const SlideRockSummary s = factor == 1.0 ? slide_rock(motion, body, options).summary
                                             : slide_rock(motion.scaled(factor), body, options).summary;
    return coupled_match(object, s);
  }
  const RockingOptions options = inversion_rocking_options(object, p, g);
  const RockingSummary s = factor == 1.0 ? rock_summary(motion, object.body, options)
                                         : rock_summary(motion.scaled(factor), object.body, options);
  return rocking_match(object.outcome, s.overturned, s.max_abs_rotation_rad);
}

}  // namespace topple
