// topple rock --model 3d: see rock_3d.hpp. Parsing was done by cmd_rock.cpp; this prints.
#include "rock_3d.hpp"

#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "topple/core/units.hpp"
#include "topple/output/write.hpp"

namespace topple::cli {

void run_3d(const RunMotion& run, const Rigid3DRequest& request) {
  const RigidBody3D box = RigidBody3D::box(request.width_m, request.depth_m, request.height_m);
  const double g = request.options.g_m_s2;
  Rigid3DSummary s;
  const GroundMotion* reference = &run.horizontal;
  if (request.set != nullptr) {
    // The pair along east (x) and north (y) (eq. M1), the block turned so that its +x axis points to the bearing:
    // a rotation by 90 - bearing degrees counter-clockwise seen from above.
    const GroundMotion east = request.set->projected(90.0);
    const GroundMotion north = request.set->projected(0.0);
    const RigidBody3D turned = box.rotated_about_vertical(deg_to_rad(90.0 - *request.bearing_deg));
    s = rock3d(east, &north, request.set->vertical_ptr(), turned, request.options).summary;
  } else {
    s = rock3d(run.horizontal, nullptr, run.vertical_ptr(), box, request.options).summary;
  }
  for (const auto& w : s.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
  require_finite({{"max tilt", s.max_tilt_rad}, {"max tilt / limit", s.max_tilt_over_limit},
                  {"energy lost", s.energy_lost_j_per_kg}, {"end time", s.end_time_s}});
  const auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; };
  if (request.json) {
    nlohmann::ordered_json j;
    j["model"] = "3d";
    j["overturned"] = s.overturned;
    j["overturn_time_s"] = opt(s.overturn_time_s);
    j["overturn_azimuth_deg"] = s.overturned ? nlohmann::ordered_json(s.overturn_azimuth_deg) : nullptr;
    j["max_tilt_rad"] = s.max_tilt_rad;
    j["max_tilt_azimuth_deg"] = s.max_tilt_azimuth_deg;
    j["max_tilt_time_s"] = s.max_tilt_time_s;
    j["max_tilt_over_limit"] = s.max_tilt_over_limit;
    j["exceeded_limit_time_s"] = opt(s.exceeded_limit_time_s);
    j["impacts"] = s.impacts;
    j["uplifts"] = s.uplifts;
    j["uplift_time_s"] = opt(s.uplift_time_s);
    j["energy_lost_j_per_kg"] = s.energy_lost_j_per_kg;
    j["flight_time_s"] = opt(s.flight_time_s);
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
    j["steps"] = s.steps;
    j["warnings"] = s.warnings;
    j["body"] = {{"shape", "block"},
                 {"width_m", request.width_m},
                 {"depth_m", request.depth_m},
                 {"height_m", request.height_m},
                 {"bearing_deg", opt(request.bearing_deg)}};
    j["solver"] = {{"model", "3d"},
                   {"restitution", restitution_mode_name(request.options.restitution)},
                   {"e", request.options.restitution == RestitutionMode::given
                             ? nlohmann::ordered_json(request.options.e)
                             : nullptr},
                   {"rel_tol", request.options.rel_tol},
                   {"g_m_s2", g}};
    j["input"] = io::run_input_json(run.input, *reference, g);
    if (request.set != nullptr) j["input"]["h2"] = request.h2;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("three-dimensional rocking and pivoting (no sliding): block {:.6g} x {:.6g} x {:.6g} m (width x depth "
             "x height){}\n",
             request.width_m, request.depth_m, request.height_m,
             request.bearing_deg ? fmt::format(", +x axis at {:g} deg", *request.bearing_deg)
                                 : std::string(", the record along +x (azimuth 90)"));
  fmt::print("max tilt               {:.6g} rad toward {:.2f} deg at {:.4f} s, {:.6g} x the static limit\n",
             s.max_tilt_rad, s.max_tilt_azimuth_deg, s.max_tilt_time_s, s.max_tilt_over_limit);
  fmt::print("first uplift           {}\n", format_seconds_or_none(s.uplift_time_s));
  fmt::print("uplifts, impacts       {}, {}\n", s.uplifts, s.impacts);
  std::size_t pivots = 0;
  for (const auto& m : s.modes) pivots += m.mode == Rigid3DMode::pivot ? 1 : 0;
  fmt::print("pivots on a corner     {}\n", pivots);
  fmt::print("overturned             {}\n",
             s.overturned ? fmt::format("yes, at {} toward {:.2f} deg", format_seconds_or_none(s.overturn_time_s),
                                        s.overturn_azimuth_deg)
                          : std::string("no"));
  fmt::print("end                    {} at {:.4f} s\n", rigid3d_mode_name(s.end_mode), s.end_time_s);
  fmt::print("energy lost            {:.6g} J/kg\n", s.energy_lost_j_per_kg);
}

}  // namespace topple::cli
