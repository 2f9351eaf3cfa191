// The field tables of the sliding and rocking summaries (summary_fields.hpp).
#include "topple/solvers/summary_fields.hpp"

#include <cmath>
#include <cstdint>
#include <optional>
#include <string>

#include "topple/core/units.hpp"

namespace topple {
namespace {

FieldValue optional_value(const std::optional<double>& v) { return v ? FieldValue{*v} : FieldValue{}; }

FieldValue count(std::size_t n) { return static_cast<std::int64_t>(n); }

/// +1 / -1 / 0 as "positive" / "negative" / null (the sides of rocking.hpp).
FieldValue side_value(int side) {
  if (side == 0) return {};
  return std::string(side > 0 ? "positive" : "negative");
}

FieldValue optional_measure(const OptionalMeasure& m) { return optional_value(m.value); }

using S = SlidingOutcome;
using I = IntensityOutcome;
using S2 = Sliding2dOutcome;
using R = RockingOutcome;
using C = SlideRockOutcome;

}  // namespace

const std::array<Field<SlidingOutcome>, 17> kSlidingFields{{
    {"max_abs_displacement_m", [](const S& r) -> FieldValue { return r.summary.max_abs_displacement_m; }, 0},
    {"max_displacement_time_s", [](const S& r) -> FieldValue { return r.summary.max_displacement_time_s; }, 1},
    {"residual_displacement_m", [](const S& r) -> FieldValue { return r.summary.residual_displacement_m; }, 2},
    {"max_abs_velocity_m_s", [](const S& r) -> FieldValue { return r.summary.max_abs_velocity_m_s; }, 3},
    {"slip_episodes", [](const S& r) -> FieldValue { return std::int64_t{r.summary.slip_episodes}; }, 4},
    {"first_slip_time_s", [](const S& r) { return optional_value(r.summary.first_slip_time_s); }, 5},
    {"total_slip_duration_s", [](const S& r) -> FieldValue { return r.summary.total_slip_duration_s; }, 6},
    {"end_time_s", [](const S& r) -> FieldValue { return r.summary.end_time_s; }, 7},
    {"at_rest_at_end", [](const S& r) -> FieldValue { return r.summary.at_rest_at_end; }, 8},
    {"contact_lost_time_s", [](const S& r) { return optional_value(r.summary.contact_lost_time_s); }, 9},
    {"yield_down_g", [](const S& r) -> FieldValue { return r.block.yield_down_m_s2() / r.block.g_m_s2; }, 10},
    // A one-way block never slips up-slope: its up-slope yield acceleration is infinite, reported as null.
    {"yield_up_g",
     [](const S& r) -> FieldValue {
       const double up = r.block.yield_up_m_s2();
       return std::isfinite(up) ? FieldValue{up / r.block.g_m_s2} : FieldValue{};
     },
     11},
    {"mu_static", [](const S& r) -> FieldValue { return r.block.mu_static; }},
    {"mu_kinetic", [](const S& r) -> FieldValue { return r.block.mu_kinetic; }},
    {"slope_deg", [](const S& r) -> FieldValue { return rad_to_deg(r.block.slope_rad); }},
    {"mode",
     [](const S& r) -> FieldValue {
       return std::string(sliding_mode_name(r.block.mode));
     }},
    {"g_m_s2", [](const S& r) -> FieldValue { return r.block.g_m_s2; }},
}};

const std::array<Field<Sliding2dOutcome>, 20> kSliding2dFields{{
    {"residual_displacement_m", [](const S2& r) -> FieldValue { return r.summary.residual_displacement_m; }, 0},
    {"residual_azimuth_deg", [](const S2& r) { return optional_value(r.summary.residual_azimuth_deg); }, 1},
    {"residual_east_m", [](const S2& r) -> FieldValue { return r.summary.residual_east_m; }, 2},
    {"residual_north_m", [](const S2& r) -> FieldValue { return r.summary.residual_north_m; }, 3},
    {"max_abs_displacement_m", [](const S2& r) -> FieldValue { return r.summary.max_abs_displacement_m; }, 4},
    {"max_displacement_time_s", [](const S2& r) -> FieldValue { return r.summary.max_displacement_time_s; }, 5},
    {"path_length_m", [](const S2& r) -> FieldValue { return r.summary.path_length_m; }, 6},
    {"max_abs_velocity_m_s", [](const S2& r) -> FieldValue { return r.summary.max_abs_velocity_m_s; }, 7},
    {"slip_episodes", [](const S2& r) -> FieldValue { return std::int64_t{r.summary.slip_episodes}; }, 8},
    {"first_slip_time_s", [](const S2& r) { return optional_value(r.summary.first_slip_time_s); }, 9},
    {"total_slip_duration_s", [](const S2& r) -> FieldValue { return r.summary.total_slip_duration_s; }, 10},
    {"end_time_s", [](const S2& r) -> FieldValue { return r.summary.end_time_s; }, 11},
    {"at_rest_at_end", [](const S2& r) -> FieldValue { return r.summary.at_rest_at_end; }, 12},
    {"contact_lost_time_s", [](const S2& r) { return optional_value(r.summary.contact_lost_time_s); }, 13},
    {"input_work_J_kg", [](const S2& r) -> FieldValue { return r.summary.input_work_J_kg; }},
    {"friction_work_J_kg", [](const S2& r) -> FieldValue { return r.summary.friction_work_J_kg; }},
    {"integrator_steps", [](const S2& r) { return count(r.summary.integrator_steps); }},
    {"mu_static", [](const S2& r) -> FieldValue { return r.block.mu_static; }},
    {"mu_kinetic", [](const S2& r) -> FieldValue { return r.block.mu_kinetic; }},
    {"g_m_s2", [](const S2& r) -> FieldValue { return r.block.g_m_s2; }},
}};

const std::array<Field<RockingOutcome>, 25> kRockingFields{{
    {"max_abs_rotation_rad", [](const R& r) -> FieldValue { return r.summary.max_abs_rotation_rad; }, 0},
    {"max_rotation_over_alpha", [](const R& r) -> FieldValue { return r.summary.max_rotation_over_alpha; }, 1},
    {"max_rotation_time_s", [](const R& r) -> FieldValue { return r.summary.max_rotation_time_s; }, 2},
    {"max_abs_theta_dot_rad_s", [](const R& r) -> FieldValue { return r.summary.max_abs_theta_dot_rad_s; }, 3},
    {"impacts", [](const R& r) { return count(r.summary.impacts); }, 4},
    {"uplifts", [](const R& r) { return count(r.summary.uplifts); }, 5},
    {"uplift_time_s", [](const R& r) { return optional_value(r.summary.uplift_time_s); }, 6},
    {"exceeded_alpha_time_s", [](const R& r) { return optional_value(r.summary.exceeded_alpha_time_s); }, 7},
    {"overturned", [](const R& r) -> FieldValue { return r.summary.overturned; }, 8},
    {"overturn_time_s", [](const R& r) { return optional_value(r.summary.overturn_time_s); }, 9},
    {"end_state", [](const R& r) -> FieldValue { return std::string(rocking_state_name(r.summary.end_state)); }, 12},
    {"end_time_s", [](const R& r) -> FieldValue { return r.summary.end_time_s; }, 11},
    {"still_rocking_at_end", [](const R& r) -> FieldValue { return r.summary.still_rocking_at_end; }, 13},
    {"energy_lost_j_per_kg", [](const R& r) -> FieldValue { return r.summary.energy_lost_j_per_kg; }, 10},
    {"alpha_rad", [](const R& r) -> FieldValue { return r.summary.alpha_rad; }, 16},
    {"alpha_deg", [](const R& r) -> FieldValue { return rad_to_deg(r.summary.alpha_rad); }},
    {"R_m", [](const R& r) -> FieldValue { return r.summary.R_m; }},
    {"p_rad_s", [](const R& r) -> FieldValue { return r.summary.p_rad_s; }, 17},
    {"e", [](const R& r) -> FieldValue { return r.summary.e; }, 18},
    {"e_mode",
     [](const R& r) -> FieldValue {
       return std::string(restitution_mode_name(r.options.restitution));
     }},
    {"onset_mode", [](const R& r) -> FieldValue { return std::string(onset_mode_name(r.summary.onset_mode)); }, 14},
    {"onset_accel_ratio", [](const R& r) { return optional_value(r.summary.onset_accel_ratio); }},
    {"critical_mu", [](const R& r) { return optional_value(r.summary.critical_mu); }, 15},
    {"mu", [](const R& r) { return optional_value(r.options.mu); }},
    {"g_m_s2", [](const R& r) -> FieldValue { return r.options.g_m_s2; }},
}};

const std::array<Field<RockingOutcome>, 8> kRockingSideFields{{
    {"alpha_negative_rad", [](const R& r) -> FieldValue { return r.summary.alpha_negative_rad; }, 0},
    {"max_rotation_positive_rad", [](const R& r) -> FieldValue { return r.summary.max_rotation_positive_rad; }, 1},
    {"max_rotation_negative_rad", [](const R& r) -> FieldValue { return r.summary.max_rotation_negative_rad; }, 2},
    {"max_rotation_over_alpha_positive",
     [](const R& r) -> FieldValue { return r.summary.max_rotation_over_alpha_positive; }, 3},
    {"max_rotation_over_alpha_negative",
     [](const R& r) -> FieldValue { return r.summary.max_rotation_over_alpha_negative; }, 4},
    {"e_onto_negative", [](const R& r) -> FieldValue { return r.summary.e_onto_negative; }, 5},
    {"exceeded_alpha_side", [](const R& r) { return side_value(r.summary.exceeded_alpha_side); }, 6},
    {"overturned_side", [](const R& r) { return side_value(r.summary.overturned_side); }, 7},
}};

const std::array<Field<IntensityOutcome>, 19> kIntensityFields{{
    {"npts", [](const I& r) { return count(r.motion.size()); }},
    {"uniform", [](const I& r) -> FieldValue { return r.motion.is_uniform(); }},
    {"dt_s", [](const I& r) -> FieldValue { return r.motion.dt_s(); }},
    {"start_time_s", [](const I& r) -> FieldValue { return r.motion.start_time_s(); }},
    {"duration_s", [](const I& r) -> FieldValue { return r.motion.duration_s(); }},
    {"pga_g", [](const I& r) -> FieldValue { return r.measures.basic.pga_m_s2 / r.g_m_s2; }},
    {"pga_m_s2", [](const I& r) -> FieldValue { return r.measures.basic.pga_m_s2; }},
    {"pga_time_s", [](const I& r) -> FieldValue { return r.measures.basic.pga_time_s; }},
    {"pgv_m_s", [](const I& r) -> FieldValue { return r.measures.basic.pgv_m_s; }},
    {"pgd_m", [](const I& r) -> FieldValue { return r.measures.basic.pgd_m; }},
    {"arias_m_s", [](const I& r) -> FieldValue { return r.measures.basic.arias_m_s; }},
    {"d5_95_s",
     [](const I& r) { return r.measures.d5_95 ? FieldValue{r.measures.d5_95->duration_s} : FieldValue{}; }},
    {"d5_time_s", [](const I& r) { return r.measures.d5_95 ? FieldValue{r.measures.d5_95->start_s} : FieldValue{}; }},
    {"d95_time_s", [](const I& r) { return r.measures.d5_95 ? FieldValue{r.measures.d5_95->end_s} : FieldValue{}; }},
    {"cav_m_s", [](const I& r) -> FieldValue { return r.measures.cav_m_s; }},
    {"tp_s", [](const I& r) { return optional_measure(r.measures.tp_s); }},
    {"tm_s", [](const I& r) { return optional_measure(r.measures.tm_s); }},
    {"predominant_frequency_hz", [](const I& r) { return optional_measure(r.measures.predominant_frequency_hz); }},
    {"g_m_s2", [](const I& r) -> FieldValue { return r.g_m_s2; }},
}};

const std::array<Field<SlideRockOutcome>, 30> kSlideRockFields{{
    {"overturned", [](const C& r) -> FieldValue { return r.summary.overturned; }},
    {"overturned_side", [](const C& r) { return side_value(r.summary.overturned_side); }},
    {"overturn_time_s", [](const C& r) { return optional_value(r.summary.overturn_time_s); }},
    {"max_rotation_over_alpha", [](const C& r) -> FieldValue { return r.summary.max_rotation_over_alpha; }},
    {"max_rotation_positive_rad", [](const C& r) -> FieldValue { return r.summary.max_rotation_positive_rad; }},
    {"max_rotation_negative_rad", [](const C& r) -> FieldValue { return r.summary.max_rotation_negative_rad; }},
    {"max_rotation_over_alpha_positive",
     [](const C& r) -> FieldValue { return r.summary.max_rotation_over_alpha_positive; }},
    {"max_rotation_over_alpha_negative",
     [](const C& r) -> FieldValue { return r.summary.max_rotation_over_alpha_negative; }},
    {"exceeded_alpha_time_s", [](const C& r) { return optional_value(r.summary.exceeded_alpha_time_s); }},
    {"residual_slide_m", [](const C& r) -> FieldValue { return r.summary.residual_slide_m; }},
    {"max_abs_slide_m", [](const C& r) -> FieldValue { return r.summary.max_abs_slide_m; }},
    {"slip_episodes", [](const C& r) -> FieldValue { return std::int64_t{r.summary.slip_episodes}; }},
    {"impacts", [](const C& r) { return count(r.summary.impacts); }},
    {"uplifts", [](const C& r) { return count(r.summary.uplifts); }},
    {"tangential_impacts", [](const C& r) { return count(r.summary.tangential_impacts); }},
    {"painleve_holds", [](const C& r) { return count(r.summary.painleve_holds); }},
    {"max_tangential_impulse_ratio",
     [](const C& r) -> FieldValue { return r.summary.max_tangential_impulse_ratio; }},
    {"onset_mode", [](const C& r) -> FieldValue { return std::string(slide_rock_mode_name(r.summary.onset_mode)); }},
    {"end_mode", [](const C& r) -> FieldValue { return std::string(slide_rock_mode_name(r.summary.end_mode)); }},
    {"end_time_s", [](const C& r) -> FieldValue { return r.summary.end_time_s; }},
    {"moving_at_end", [](const C& r) -> FieldValue { return r.summary.moving_at_end; }},
    {"friction_energy_j_per_kg", [](const C& r) -> FieldValue { return r.summary.friction_energy_j_per_kg; }},
    {"impact_energy_j_per_kg", [](const C& r) -> FieldValue { return r.summary.impact_energy_j_per_kg; }},
    {"alpha_positive_deg", [](const C& r) -> FieldValue { return rad_to_deg(r.summary.alpha_positive_rad); }},
    {"alpha_negative_deg", [](const C& r) -> FieldValue { return rad_to_deg(r.summary.alpha_negative_rad); }},
    {"mu_static", [](const C& r) -> FieldValue { return r.body.mu_static; }},
    {"mu_kinetic", [](const C& r) -> FieldValue { return r.body.mu_kinetic; }},
    {"e_mode", [](const C& r) -> FieldValue { return std::string(restitution_mode_name(r.options.restitution)); }},
    {"used_sliding_kernel", [](const C& r) -> FieldValue { return r.summary.used_sliding_kernel; }},
    {"g_m_s2", [](const C& r) -> FieldValue { return r.options.g_m_s2; }},
}};

}  // namespace topple
