#include "topple/output/rigid3d_json.hpp"

#include <optional>

namespace topple::io {

namespace {

nlohmann::ordered_json or_null(const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; }

}  // namespace

nlohmann::ordered_json rigid3d_summary_json(const Rigid3DSummary& s) {
  nlohmann::ordered_json j;
  j["model"] = "3d";
  j["overturned"] = s.overturned;
  j["overturn_time_s"] = or_null(s.overturn_time_s);
  j["overturn_azimuth_deg"] = s.overturned ? nlohmann::ordered_json(s.overturn_azimuth_deg) : nullptr;
  j["max_tilt_rad"] = s.max_tilt_rad;
  j["max_tilt_azimuth_deg"] = s.max_tilt_azimuth_deg;
  j["max_tilt_time_s"] = s.max_tilt_time_s;
  j["max_tilt_over_limit"] = s.max_tilt_over_limit;
  j["exceeded_limit_time_s"] = or_null(s.exceeded_limit_time_s);
  j["impacts"] = s.impacts;
  j["uplifts"] = s.uplifts;
  j["uplift_time_s"] = or_null(s.uplift_time_s);
  j["energy_lost_j_per_kg"] = s.energy_lost_j_per_kg;
  j["flight_time_s"] = or_null(s.flight_time_s);
  j["end_time_s"] = s.end_time_s;
  j["end_mode"] = rigid3d_mode_name(s.end_mode);
  nlohmann::ordered_json modes = nlohmann::ordered_json::array();
  for (const Rigid3DModeChange& m : s.modes) {
    modes.push_back({{"time_s", m.time_s},
                     {"mode", rigid3d_mode_name(m.mode)},
                     {"vertex_a", m.vertex_a >= 0 ? nlohmann::ordered_json(m.vertex_a) : nullptr},
                     {"vertex_b", m.vertex_b >= 0 ? nlohmann::ordered_json(m.vertex_b) : nullptr}});
  }
  j["modes"] = modes;
  // sliding (rigid3d.hpp, Rigid3DOptions::mu_s; zero without friction)
  j["residual_slide_east_m"] = s.residual_slide_east_m;
  j["residual_slide_north_m"] = s.residual_slide_north_m;
  j["max_slide_m"] = s.max_slide_m;  // the base's largest excursion from its start (rigid3d.hpp)
  j["max_slide_speed_m_s"] = s.max_slide_speed_m_s;
  j["slide_path_length_m"] = s.slide_path_length_m;
  j["friction_energy_j_per_kg"] = s.friction_energy_j_per_kg;
  j["slip_episodes"] = s.slip_episodes;
  j["first_slip_time_s"] = or_null(s.first_slip_time_s);
  j["slide_rock_time_s"] = or_null(s.slide_rock_time_s);
  // slide-rock and flight (rigid3d_contact.cpp; with friction given, modelled; zero without)
  j["slide_rock_duration_s"] = s.slide_rock_duration_s;
  j["flights"] = s.flights;
  j["flight_duration_s"] = s.flight_duration_s;
  j["residual_yaw_deg"] = s.residual_yaw_deg;
  j["painleve_events"] = s.painleve_events;
  j["steps"] = s.steps;
  j["warnings"] = s.warnings;
  return j;
}

nlohmann::ordered_json rigid3d_solver_json(const Rigid3DOptions& options, bool circular_base) {
  return {{"model", "3d"},
          {"restitution", restitution_mode_name(options.restitution)},
          {"e", options.restitution == RestitutionMode::given ? nlohmann::ordered_json(options.e) : nullptr},
          // the impact law (rigid3d.hpp): the complementarity solution over the contacts down at the instant, those
          // within simultaneous_contact of the body's size joining one impact (before issue 29's fix: one contact
          // chosen, an edge kept down after a corner landing next to the pivot)
          // A circular base lands flat and strikes at one rim point: Housner's angular-momentum balance about that
          // point, generalised to 3-D (docs/method.md, "A circular base: rolling on the rim", impact law).
          {"impact_law", circular_base ? "housner_rim_point" : "complementarity"},
          {"simultaneous_contact",
           circular_base ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(options.simultaneous_contact)},
          {"rel_tol", options.rel_tol},
          {"mu_s", or_null(options.mu_s)},
          {"mu_k", options.mu_s ? nlohmann::ordered_json(options.mu_k.value_or(*options.mu_s)) : nullptr},
          {"g_m_s2", options.g_m_s2},
          // the base (rigid3d.hpp, "Inclined base"): level (0) or inclined; the summary's tilt, azimuths and slide are
          // in the base's frame ("base"; on a level base the same as the ground's)
          {"base_incline_deg", options.base_incline_deg},
          {"base_incline_azimuth_deg",
           options.base_incline_deg != 0.0 ? nlohmann::ordered_json(options.base_incline_azimuth_deg) : nullptr},
          {"output_frame", options.base_incline_deg != 0.0 ? "base" : "ground"}};
}

}  // namespace topple::io
