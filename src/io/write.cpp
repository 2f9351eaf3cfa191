#include "topple/io/write.hpp"

#include <cmath>
#include <iterator>

#include <fmt/format.h>

#include "topple/error.hpp"
#include "topple/io/output_file.hpp"
#include "topple/units.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

}  // namespace

nlohmann::ordered_json sliding_summary_json(const SlidingSummary& s, const SlidingBlock& block) {
  nlohmann::ordered_json j;
  j["max_abs_displacement_m"] = s.max_abs_displacement_m;
  j["max_displacement_time_s"] = s.max_displacement_time_s;
  j["residual_displacement_m"] = s.residual_displacement_m;
  j["max_abs_velocity_m_s"] = s.max_abs_velocity_m_s;
  j["slip_episodes"] = s.slip_episodes;
  j["first_slip_time_s"] = optional_json(s.first_slip_time_s);
  j["total_slip_duration_s"] = s.total_slip_duration_s;
  j["end_time_s"] = s.end_time_s;
  j["at_rest_at_end"] = s.at_rest_at_end;
  j["contact_lost_time_s"] = optional_json(s.contact_lost_time_s);
  j["yield_down_g"] = block.yield_down_m_s2() / block.g_m_s2;
  const double up = block.yield_up_m_s2();
  j["yield_up_g"] = std::isfinite(up) ? nlohmann::ordered_json(up / block.g_m_s2) : nlohmann::ordered_json(nullptr);
  j["mu_static"] = block.mu_static;
  j["mu_kinetic"] = block.mu_kinetic;
  j["slope_deg"] = block.slope_rad * 180.0 / kPi;
  j["mode"] = block.mode == SlidingMode::one_way ? "one-way" : "two-way";
  j["g_m_s2"] = block.g_m_s2;
  j["sign_convention"] = "displacement positive in the direction a positive ground acceleration pushes the block "
                         "(down-slope on an incline)";
  return j;
}

nlohmann::ordered_json rocking_summary_json(const RockingSummary& s, const RockingBody& body,
                                            const RockingOptions& options) {
  nlohmann::ordered_json j;
  j["max_abs_rotation_rad"] = s.max_abs_rotation_rad;
  j["max_rotation_over_alpha"] = s.max_rotation_over_alpha;
  j["max_rotation_time_s"] = s.max_rotation_time_s;
  j["max_abs_theta_dot_rad_s"] = s.max_abs_theta_dot_rad_s;
  j["impacts"] = s.impacts;
  j["uplifts"] = s.uplifts;
  j["uplift_time_s"] = optional_json(s.uplift_time_s);
  j["exceeded_alpha_time_s"] = optional_json(s.exceeded_alpha_time_s);
  j["overturned"] = s.overturned;
  j["overturn_time_s"] = optional_json(s.overturn_time_s);
  j["end_state"] = rocking_state_name(s.end_state);
  j["end_time_s"] = s.end_time_s;
  j["still_rocking_at_end"] = s.still_rocking_at_end;
  j["energy_lost_j_per_kg"] = s.energy_lost_j_per_kg;
  j["alpha_rad"] = s.alpha_rad;
  j["alpha_deg"] = s.alpha_rad * 180.0 / kPi;
  j["R_m"] = s.R_m;
  j["p_rad_s"] = s.p_rad_s;
  j["e"] = s.e;
  j["e_mode"] = options.restitution == RestitutionMode::housner ? "housner" : "given";
  j["onset_mode"] = onset_mode_name(s.onset_mode);
  j["onset_accel_ratio"] = optional_json(s.onset_accel_ratio);
  j["critical_mu"] = optional_json(s.critical_mu);
  j["mu"] = optional_json(options.mu);
  j["g_m_s2"] = options.g_m_s2;
  j["warnings"] = s.warnings;
  nlohmann::ordered_json b;
  b["shape"] = shape_name(body.shape);
  if (body.shape == RockingBody::Shape::block) {
    b["width_m"] = 2.0 * body.a_m;
    b["height_m"] = 2.0 * body.h_m;
  } else if (body.shape == RockingBody::Shape::cylinder) {
    b["diameter_m"] = 2.0 * body.a_m;
    b["height_m"] = 2.0 * body.h_m;
  }
  b["a_m"] = body.a_m;
  b["h_m"] = body.h_m;
  b["D_m2"] = body.D_m2;
  j["body"] = b;
  nlohmann::ordered_json m;
  m["method"] = options.method == RockingMethod::rk4 ? "rk4" : "adaptive";
  m["rel_tol"] = options.rel_tol;
  m["rk4_substeps"] = options.rk4_substeps;
  m["rest_energy_fraction"] = options.rest_energy_fraction;
  m["max_run_out_s"] = options.max_run_out_s;
  m["steps"] = s.steps;
  j["solver"] = m;
  return j;
}

nlohmann::ordered_json run_input_json(const RunInput& input, const GroundMotion& horizontal, double g_m_s2) {
  nlohmann::ordered_json in;
  in["motion"] = input.motion;
  in["pga_g"] = horizontal.pga_m_s2() / g_m_s2;
  in["scale_factor"] = input.scale_factor;
  in["invert"] = input.inverted;
  in["vertical"] = input.vertical ? nlohmann::ordered_json(*input.vertical) : nlohmann::ordered_json(nullptr);
  in["npts"] = horizontal.size();
  in["dt_s"] = horizontal.dt_s();
  if (input.with_duration) in["duration_s"] = horizontal.duration_s();
  return in;
}

void write_sliding_history_csv(const std::filesystem::path& path, const SlidingHistory& h,
                               const GroundMotion& horizontal) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,ground_accel_m_s2,displacement_m,velocity_m_s,state\n";
  fmt::memory_buffer row;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    row.clear();
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.9g},{:.12g},{:.12g},{}\n", h.time_s[i],
                   horizontal.accel_at(h.time_s[i]), h.displacement_m[i], h.velocity_m_s[i],
                   static_cast<int>(h.state[i]));
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  file.commit();
}

void write_rocking_history_csv(const std::filesystem::path& path, const RockingHistory& h) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,theta_rad,theta_dot_rad_s,state\n";
  fmt::memory_buffer row;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    row.clear();
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.12g},{:.12g},{}\n", h.time_s[i], h.theta_rad[i],
                   h.theta_dot_rad_s[i], rocking_state_name(h.state[i]));
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  file.commit();
}

}  // namespace topple::io
