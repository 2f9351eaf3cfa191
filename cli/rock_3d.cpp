// topple rock --model 3d: see rock_3d.hpp. Parsing was done by cmd_rock.cpp; this prints, writes the history and
// draws the figure.
#include "rock_3d.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "topple/core/output_file.hpp"
#include "topple/core/units.hpp"
#include "topple/output/plot.hpp"
#include "topple/output/rigid3d_json.hpp"
#include "topple/output/write.hpp"

namespace topple::cli {
namespace {

/// The tilt (angle between the body's z axis and the vertical) of a unit quaternion (w, x, y, z): the z component of
/// R e_z is 1 - 2 (x^2 + y^2).
double tilt_of(const Quaternion& q) {
  const double n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  return std::acos(std::clamp(1.0 - 2.0 * (q[1] * q[1] + q[2] * q[2]) / n2, -1.0, 1.0));
}

/// --out: one row per history entry (every sample of the record and every event, the state after it).
void write_history_csv(const std::string& path, const Rigid3DHistory& h) {
  io::OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,x_m,y_m,z_m,qw,qx,qy,qz,wx_rad_s,wy_rad_s,wz_rad_s,tilt_rad,energy_j_per_kg,mode\n";
  fmt::memory_buffer row;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    row.clear();
    const Vec3& p = h.position_m[i];
    const Quaternion& q = h.orientation[i];
    const Vec3& w = h.angular_velocity_rad_s[i];
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},"
                   "{:.12g},{:.12g},{:.12g},{:.12g},{}\n", h.time_s[i], p[0], p[1], p[2], q[0], q[1], q[2], q[3],
                   w[0], w[1], w[2], tilt_of(q), h.energy_j_per_kg[i], rigid3d_mode_name(h.mode[i]));
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  file.commit();
}

plot::Series ground_series(const GroundMotion& m, double g, const std::string& label, const std::string& color) {
  plot::Series s{label, m.times_s(), {}, "lines", color, 1.2};
  for (const double a : m.accel_m_s2()) s.y.push_back(a / g);
  return s;
}

/// --plot: the ground components, the tilt with the smallest static limit, the tilt's direction, the angular
/// velocity; mode changes marked. Plotting computes no physics: the engine's history as it is.
void draw(const Rigid3DRequest& request, const RunMotion& run, const GroundMotion& x, const GroundMotion* y,
          const GroundMotion* z, const RigidBody3D* body, const Rigid3DResult& r) {
  const double g = request.options.g_m_s2;
  const Rigid3DHistory& h = r.history;
  plot::Panel accel{"ground acceleration (g)", {}, {}, {}, false, false};
  accel.series.push_back(ground_series(x, g, y != nullptr ? "east" : "along the body's +x", "#34495e"));
  if (y != nullptr) accel.series.push_back(ground_series(*y, g, "north", "#e67e22"));
  if (z != nullptr) accel.series.push_back(ground_series(*z, g, "vertical", "#27ae60"));
  // The smallest static limit over all directions (the support function's minimum over 1-degree steps; a cylinder's
  // is the same in every direction).
  double limit = INFINITY;
  if (request.cylinder) {
    limit = request.cylinder->static_tilt_limit_rad();
  } else {
    for (int a = 0; a < 360; ++a) limit = std::min(limit, body->static_tilt_limit_rad(a));
  }
  plot::Panel tilt{"tilt (deg)", {{"tilt", h.time_s, {}, "lines", "#c0392b", 1.8}},
                   {{rad_to_deg(limit), fmt::format("smallest static limit {:.3g} deg", rad_to_deg(limit))}}, {},
                   false, false};
  plot::Panel azimuth{"tilt toward (deg from north)", {{"azimuth", {}, {}, "points", "#8e44ad", 1.0}}, {}, {}, false,
                      false};
  plot::Panel rate{"angular velocity (rad/s)",
                   {{"ω_x", h.time_s, {}, "lines", "#2171b5", 1.3}, {"ω_y", h.time_s, {}, "lines", "#e67e22", 1.3},
                    {"ω_z", h.time_s, {}, "lines", "#27ae60", 1.3}},
                   {}, {}, false, false};
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const Quaternion& q = h.orientation[i];
    const double t = tilt_of(q);
    tilt.series[0].y.push_back(rad_to_deg(t));
    if (t > 1e-6) {  // the direction of the body's z axis in plan (R e_z's x, y: 2(xz + wy), 2(yz - wx))
      const double ex = 2.0 * (q[1] * q[3] + q[0] * q[2]);
      const double ey = 2.0 * (q[2] * q[3] - q[0] * q[1]);
      double az = rad_to_deg(std::atan2(ex, ey));
      if (az < 0.0) az += 360.0;
      azimuth.series[0].x.push_back(h.time_s[i]);
      azimuth.series[0].y.push_back(az);
    }
    for (std::size_t k = 0; k < 3; ++k) rate.series[k].y.push_back(h.angular_velocity_rad_s[i][k]);
  }
  std::vector<double> marks;
  for (std::size_t i = 1; i < r.summary.modes.size(); ++i) marks.push_back(r.summary.modes[i].time_s);
  tilt.marks_x = marks;
  rate.marks_x = marks;
  const std::string body_text =
      request.cylinder        ? fmt::format("cylinder {:.3g} x {:.3g} m", request.width_m, request.height_m)
      : request.mesh_file.empty()
          ? fmt::format("block {:.3g} x {:.3g} x {:.3g} m", request.width_m, request.depth_m, request.height_m)
          : plot::file_label(request.mesh_file);
  plot::Figure figure{fmt::format("{} in 3-D, {}{}{}: {}{}",
                                  request.cylinder ? "Rocking and rolling on the rim" : "Rocking and pivoting",
                                  body_text,
                                  request.bearing_deg ? fmt::format(", +x at {:g}°", *request.bearing_deg) : "",
                                  request.vertical_label.empty()
                                      ? std::string()
                                      : ", with vertical " + plot::file_label(request.vertical_label),
                                  run.title, r.summary.overturned ? fmt::format(" (overturned at {:.3f} s)",
                                                                                r.summary.overturn_time_s.value_or(0))
                                                                  : ""),
                      "time (s)", {accel, tilt, azimuth, rate}, 1000, 260, {}};
  if (azimuth.series[0].x.empty()) figure.panels.erase(figure.panels.begin() + 2);
  plot::render(figure, request.plot);
}

}  // namespace

void run_3d(const RunMotion& run, const Rigid3DRequest& request) {
  const double g = request.options.g_m_s2;
  const GroundMotion* reference = &run.horizontal;
  Rigid3DOptions options = request.options;
  options.record_history = !request.out.empty() || !request.plot.empty();
  Rigid3DResult result;
  if (request.cylinder) {
    // Axisymmetric: the pair along east (x) and north (y) (eq. M1) as it is; one record along x (azimuth 90).
    std::optional<GroundMotion> east, north;
    if (request.set != nullptr) {
      east = request.set->projected(90.0);
      north = request.set->projected(0.0);
    }
    const GroundMotion& x = east ? *east : run.horizontal;
    const GroundMotion* y = north ? &*north : nullptr;
    const GroundMotion* z = request.set != nullptr ? request.set->vertical_ptr() : run.vertical_ptr();
    result = rock3d_cylinder(x, y, z, *request.cylinder, options);
    if (!request.out.empty()) write_history_csv(request.out, result.history);
    if (!request.plot.empty()) draw(request, run, x, y, z, nullptr, result);
  } else if (request.set != nullptr) {
    // The pair along east (x) and north (y) (eq. M1), the body turned so that its +x axis points to the bearing:
    // a rotation by 90 - bearing degrees counter-clockwise seen from above.
    const GroundMotion east = request.set->projected(90.0);
    const GroundMotion north = request.set->projected(0.0);
    const RigidBody3D turned = request.body.rotated_about_vertical(deg_to_rad(90.0 - *request.bearing_deg));
    result = rock3d(east, &north, request.set->vertical_ptr(), turned, options);
    if (!request.out.empty()) write_history_csv(request.out, result.history);
    if (!request.plot.empty()) draw(request, run, east, &north, request.set->vertical_ptr(), &turned, result);
  } else {
    result = rock3d(run.horizontal, nullptr, run.vertical_ptr(), request.body, options);
    if (!request.out.empty()) write_history_csv(request.out, result.history);
    if (!request.plot.empty()) draw(request, run, run.horizontal, nullptr, run.vertical_ptr(), &request.body, result);
  }
  const Rigid3DSummary& s = result.summary;
  for (const auto& w : s.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
  require_finite({{"max tilt", s.max_tilt_rad}, {"max tilt / limit", s.max_tilt_over_limit},
                  {"energy lost", s.energy_lost_j_per_kg}, {"end time", s.end_time_s}});
  const auto opt = [](const std::optional<double>& v) { return v ? nlohmann::ordered_json(*v) : nullptr; };
  if (request.json) {
    nlohmann::ordered_json j = io::rigid3d_summary_json(s);
    if (request.cylinder) {
      j["body"] = {{"shape", "cylinder"},
                   {"diameter_m", request.width_m},
                   {"height_m", request.height_m},
                   {"bearing_deg", nullptr}};
    } else if (request.mesh_file.empty()) {
      j["body"] = {{"shape", "block"},
                   {"width_m", request.width_m},
                   {"depth_m", request.depth_m},
                   {"height_m", request.height_m},
                   {"bearing_deg", opt(request.bearing_deg)}};
    } else {
      // The mesh as posed, in its own frame shifted down to the support plane (rigid3d.hpp, from_mesh).
      nlohmann::ordered_json base = nlohmann::ordered_json::array();
      for (const auto& v : request.body.base_xy_m) base.push_back({v[0], v[1]});
      const Vec3& c = request.body.centre_of_mass_m;
      j["body"] = {{"shape", "mesh"},
                   {"file", plot::file_label(request.mesh_file)},
                   {"base_xy_m", base},
                   {"centre_of_mass_m", {c[0], c[1], c[2]}},
                   {"bearing_deg", opt(request.bearing_deg)}};
    }
    j["solver"] = io::rigid3d_solver_json(request.options, static_cast<bool>(request.cylinder));
    j["input"] = io::run_input_json(run.input, *reference, g);
    if (request.set != nullptr) j["input"]["h2"] = request.h2;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  const bool friction = request.options.mu_s.has_value();
  if (request.cylinder) {
    fmt::print("three-dimensional rocking and rolling on the rim ({}): cylinder {:.6g} x {:.6g} m (diameter x "
               "height){}\n",
               friction ? fmt::format("friction mu_s = {:.6g}, mu_k = {:.6g}", *request.options.mu_s,
                                      request.options.mu_k.value_or(*request.options.mu_s))
                        : std::string("no sliding"),
               request.width_m, request.height_m,
               request.set != nullptr ? std::string(", the pair along east and north")
                                      : std::string(", the record along +x (azimuth 90)"));
  } else {
    fmt::print("three-dimensional rocking and pivoting ({}): {}{}\n",
               friction ? fmt::format("sliding flat, mu_s = {:.6g}, mu_k = {:.6g}", *request.options.mu_s,
                                      request.options.mu_k.value_or(*request.options.mu_s))
                        : std::string("no sliding"),
               request.mesh_file.empty()
                   ? fmt::format("block {:.6g} x {:.6g} x {:.6g} m (width x depth x height)", request.width_m,
                                 request.depth_m, request.height_m)
                   : fmt::format("mesh {} as posed, base of {} vertices, centre of mass {:.6g} m above it",
                                 plot::file_label(request.mesh_file), request.body.base_xy_m.size(),
                                 request.body.height_m()),
               request.bearing_deg ? fmt::format(", +x axis at {:g} deg", *request.bearing_deg)
                                   : std::string(", the record along +x (azimuth 90)"));
  }
  if (request.options.base_incline_deg != 0.0) {
    fmt::print("inclined base          {:.6g} deg, downhill toward {:.6g} deg; tilt from the base normal, azimuths and "
               "slide in the base's plane\n",
               request.options.base_incline_deg, request.options.base_incline_azimuth_deg);
  }
  fmt::print("max tilt               {:.6g} rad toward {:.2f} deg at {:.4f} s, {:.6g} x the static limit\n",
             s.max_tilt_rad, s.max_tilt_azimuth_deg, s.max_tilt_time_s, s.max_tilt_over_limit);
  fmt::print("first uplift           {}\n", format_seconds_or_none(s.uplift_time_s));
  fmt::print("uplifts, impacts       {}, {}\n", s.uplifts, s.impacts);
  std::size_t pivots = 0;
  for (const auto& m : s.modes) pivots += m.mode == Rigid3DMode::pivot ? 1 : 0;
  if (!request.cylinder) fmt::print("pivots on a corner     {}\n", pivots);
  fmt::print("overturned             {}\n",
             s.overturned ? fmt::format("yes, at {} toward {:.2f} deg", format_seconds_or_none(s.overturn_time_s),
                                        s.overturn_azimuth_deg)
                          : std::string("no"));
  fmt::print("end                    {} at {:.4f} s\n", rigid3d_mode_name(s.end_mode), s.end_time_s);
  fmt::print("energy lost            {:.6g} J/kg\n", s.energy_lost_j_per_kg);
  if (friction) {
    fmt::print("residual slide         {:.6g} m east, {:.6g} m north ({} slip episodes, first {})\n",
               s.residual_slide_east_m, s.residual_slide_north_m, s.slip_episodes,
               format_seconds_or_none(s.first_slip_time_s));
    fmt::print("max slide speed        {:.6g} m/s, path {:.6g} m, friction energy {:.6g} J/kg\n", s.max_slide_speed_m_s,
               s.slide_path_length_m, s.friction_energy_j_per_kg);
  }
  if (!request.out.empty()) fmt::print("history written to {}\n", request.out);
  if (!request.plot.empty()) fmt::print("figure written to {}\n", request.plot);
}

}  // namespace topple::cli
