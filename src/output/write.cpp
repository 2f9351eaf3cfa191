#include "topple/output/write.hpp"

#include <cmath>
#include <iterator>
#include <type_traits>
#include <variant>

#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/core/units.hpp"

namespace topple::io {

nlohmann::ordered_json field_json(const FieldValue& value) {
  return std::visit(
      [](const auto& v) -> nlohmann::ordered_json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return nullptr;
        } else {
          return v;  // a non-finite double dumps as null (nlohmann::json): never NaN in the output
        }
      },
      value);
}

nlohmann::ordered_json sliding_summary_json(const SlidingSummary& s, const SlidingBlock& block) {
  nlohmann::ordered_json j = fields_json(kSlidingFields, SlidingOutcome{s, block});
  j["sign_convention"] = "displacement positive in the direction a positive ground acceleration pushes the block "
                         "(down-slope on an incline)";
  return j;
}

nlohmann::ordered_json sliding_2d_summary_json(const Sliding2dSummary& s, const SlidingBlock& block) {
  nlohmann::ordered_json j = fields_json(kSliding2dFields, Sliding2dOutcome{s, block});
  j["sign_convention"] = "displacement of the block relative to the ground; x east, y north; azimuth in degrees "
                         "clockwise from north";
  return j;
}

nlohmann::ordered_json sliding_spectrum_2d_json(const SlidingSpectrum2d& sp, const std::string& first_name,
                                                const std::string& second_name) {
  const double g = sp.g_m_s2;
  nlohmann::ordered_json j;
  j["motion"] = first_name;
  j["second"] = second_name;
  j["vertical"] = sp.with_vertical;
  j["azimuths_deg"] = {sp.azimuths.first_deg, sp.azimuths.second_deg};
  j["pga_axis"] = "RotD50 of the pair (Boore 2010)";
  j["rotd50_pga_g"] = sp.rotd50_pga_m_s2 / g;
  j["h1_pga_g"] = sp.first_pga_m_s2 / g;
  j["h2_pga_g"] = sp.second_pga_m_s2 / g;
  j["g_m_s2"] = g;
  j["mode"] = sliding_mode_name(SlidingMode::two_way);
  j["slope_deg"] = 0.0;
  auto& pts = j["points"] = nlohmann::ordered_json::array();
  const auto alone = [](const SlidingSummary& s) {
    return nlohmann::ordered_json{{"max_abs_displacement_m", s.max_abs_displacement_m},
                                  {"residual_displacement_m", s.residual_displacement_m},
                                  {"slip_episodes", s.slip_episodes}};
  };
  for (const SlidingSpectrum2dPoint& p : sp.points) {
    nlohmann::ordered_json x;
    x["mu"] = p.mu;
    x["yield_accel_g"] = p.yield_accel_g;
    x["ky_over_rotd50_pga"] = p.yield_over_rotd50_pga;
    // The 2-D run's fields, as `slide --h2 --json` prints them (the spectrum's block: level, two-way, mu_s = mu_k).
    const SlidingBlock block = SlidingBlock::make(p.mu, std::nullopt, 0.0, SlidingMode::two_way, g);
    x.update(sliding_2d_summary_json(p.bidirectional, block));
    x["h1_alone"] = alone(p.first_alone);
    x["h2_alone"] = alone(p.second_alone);
    pts.push_back(std::move(x));
  }
  return j;
}

nlohmann::ordered_json oriented_rocking_json(const OrientedRockingSummary& summary, const OrientedBody& body,
                                             std::optional<double> bearing_deg, const ComponentAzimuths& azimuths,
                                             const OrientationOptions& orientation) {
  nlohmann::ordered_json j;
  j["model"] = "planar rocking under the projection of the two horizontal components on each direction (eq. M1), "
               "with the vertical when there is one";
  j["bearing_deg"] = bearing_deg ? nlohmann::ordered_json(*bearing_deg) : nlohmann::ordered_json(nullptr);
  j["azimuths_deg"] = {azimuths.first_deg, azimuths.second_deg};
  if (body.axisymmetric()) j["direction_step_deg"] = orientation.cylinder_step_deg;
  if (body.across) j["depth_m"] = 2.0 * body.across->a_m;
  const DirectionResponse& g = summary.governing_response();
  j["governing_azimuth_deg"] = g.azimuth_deg;
  j["governing_axis"] = std::string(oriented_axis_name(g.axis));
  j["directions"] = nlohmann::ordered_json::array();
  for (const DirectionResponse& d : summary.directions) {
    nlohmann::ordered_json row;
    row["azimuth_deg"] = d.azimuth_deg;
    row["axis"] = std::string(oriented_axis_name(d.axis));
    row["max_rotation_over_alpha"] = d.summary.max_rotation_over_alpha;
    row["overturned"] = d.summary.overturned;
    row["overturn_time_s"] =
        d.summary.overturn_time_s ? nlohmann::ordered_json(*d.summary.overturn_time_s) : nlohmann::ordered_json(nullptr);
    j["directions"].push_back(row);
  }
  return j;
}

nlohmann::ordered_json rocking_summary_json(const RockingSummary& s, const RockingBody& body,
                                            const RockingOptions& options) {
  nlohmann::ordered_json j = fields_json(kRockingFields, RockingOutcome{s, body, options});
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
  if (body.negative_pivot) {  // asymmetric: both pivots (b1: O-, theta < 0; b2: O+, theta > 0)
    b["b1_m"] = body.negative_pivot->b_m;
    b["b2_m"] = body.a_m;
    b["h_m"] = body.h_m;
    b["inertia_m2"] = body.D_m2 - body.a_m * body.a_m - body.h_m * body.h_m;
    b["D1_m2"] = body.negative_pivot->D_m2;
    b["D2_m2"] = body.D_m2;
  } else {
    b["a_m"] = body.a_m;
    b["h_m"] = body.h_m;
    b["D_m2"] = body.D_m2;
  }
  j["body"] = b;
  if (body.negative_pivot) {
    // Per side (only for asymmetric bodies, so that symmetric summaries keep their keys): "negative" is theta < 0,
    // about O- (b1), "positive" theta > 0, about O+ (b2).
    const auto side = [](double alpha, double max_rad, double ratio, double e_onto) {
      nlohmann::ordered_json x;
      x["alpha_rad"] = alpha;
      x["max_rotation_rad"] = max_rad;
      x["max_rotation_over_alpha"] = ratio;
      x["e_onto"] = e_onto;
      return x;
    };
    nlohmann::ordered_json sides;
    sides["negative"] = side(s.alpha_negative_rad, s.max_rotation_negative_rad, s.max_rotation_over_alpha_negative,
                             s.e_onto_negative);
    sides["positive"] =
        side(s.alpha_rad, s.max_rotation_positive_rad, s.max_rotation_over_alpha_positive, s.e);
    const auto side_name = [](int x) { return x > 0 ? "positive" : x < 0 ? "negative" : nullptr; };
    sides["exceeded_alpha_side"] = s.exceeded_alpha_side != 0 ? nlohmann::ordered_json(side_name(s.exceeded_alpha_side))
                                                              : nlohmann::ordered_json(nullptr);
    sides["overturned_side"] = s.overturned_side != 0 ? nlohmann::ordered_json(side_name(s.overturned_side))
                                                      : nlohmann::ordered_json(nullptr);
    j["sides"] = sides;
  }
  nlohmann::ordered_json m;
  m["method"] = rocking_method_name(options.method);
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

nlohmann::ordered_json sliding_2d_input_json(const RunInput& input, const std::string& second_name,
                                             const GroundMotion& first, const GroundMotion& second,
                                             const ComponentAzimuths& azimuths, const SlidingBlock& block) {
  nlohmann::ordered_json in;
  in["motion"] = input.motion;
  in["h2"] = second_name;
  in["azimuths_deg"] = {azimuths.first_deg, azimuths.second_deg};
  if (block.slope_rad != 0.0) {
    in["slope_deg"] = rad_to_deg(block.slope_rad);
    in["slope_azimuth_deg"] = azimuths.slope_azimuth_deg;
  }
  in["scale_factor"] = input.scale_factor;
  in["vertical"] = input.vertical ? nlohmann::ordered_json(true) : nlohmann::ordered_json(nullptr);
  in["pga_g"] = {first.pga_m_s2() / block.g_m_s2, second.pga_m_s2() / block.g_m_s2};
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

void write_sliding_2d_history_csv(const std::filesystem::path& path, const Sliding2dHistory& h,
                                  const GroundMotion& first, const GroundMotion& second,
                                  const ComponentAzimuths& azimuths, const GroundMotion* vertical) {
  // Unit vectors (east, north) of the components' azimuths, clockwise from north (sliding2d.hpp's frame).
  const double r1 = deg_to_rad(azimuths.first_deg);
  const double r2 = deg_to_rad(azimuths.second_deg);
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,ground_east_m_s2,ground_north_m_s2,ground_up_m_s2,displacement_east_m,displacement_north_m,"
         "velocity_east_m_s,velocity_north_m_s,slipping\n";
  fmt::memory_buffer row;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    const double t = h.time_s[i];
    const double a1 = first.accel_at(t);
    const double a2 = second.accel_at(t);
    row.clear();
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.9g},{:.9g},{:.9g},{:.12g},{:.12g},{:.12g},{:.12g},{}\n", t,
                   a1 * std::sin(r1) + a2 * std::sin(r2), a1 * std::cos(r1) + a2 * std::cos(r2),
                   vertical != nullptr ? vertical->accel_at(t) : 0.0, h.east_m[i], h.north_m[i], h.east_m_s[i],
                   h.north_m_s[i], static_cast<int>(h.slipping[i]));
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

nlohmann::ordered_json slide_rock_summary_json(const SlideRockSummary& s, const SlideRockBody& body,
                                               const SlideRockOptions& options) {
  nlohmann::ordered_json j = fields_json(kSlideRockFields, SlideRockOutcome{s, body, options});
  nlohmann::ordered_json modes = nlohmann::ordered_json::object();
  for (std::size_t m = 0; m < kSlideRockModes; ++m) {
    nlohmann::ordered_json x;
    x["entries"] = s.mode_entries[m];
    x["first_time_s"] = s.mode_first_time_s[m] ? nlohmann::ordered_json(*s.mode_first_time_s[m]) : nullptr;
    modes[std::string(slide_rock_mode_name(static_cast<SlideRockMode>(m)))] = x;
  }
  j["modes"] = modes;
  j["warnings"] = s.warnings;
  nlohmann::ordered_json b;
  b["b1_m"] = body.b1_m;
  b["b2_m"] = body.b2_m;
  b["h_m"] = body.h_m;
  b["inertia_m2"] = body.inertia_m2;
  j["body"] = b;
  j["sign_convention"] = "theta > 0 and slide > 0 toward +x; sliding.hpp's d is -slide";
  if (options.slope_rad != 0.0) {  // an inclined base (slide_rock.hpp); a level one keeps the level output
    j["slope"] = {{"slope_deg", rad_to_deg(options.slope_rad)}, {"down_slope", "-x"}};
  }
  return j;
}

void write_slide_rock_history_csv(const std::filesystem::path& path, const SlideRockHistory& h) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,slide_m,slide_velocity_m_s,theta_rad,theta_dot_rad_s,cm_height_m,mode\n";
  fmt::memory_buffer row;
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    row.clear();
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.12g},{:.12g},{:.12g},{:.12g},{:.12g},{}\n", h.time_s[i],
                   h.slide_m[i], h.slide_velocity_m_s[i], h.theta_rad[i], h.theta_dot_rad_s[i], h.cm_height_m[i],
                   slide_rock_mode_name(h.mode[i]));
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  file.commit();
}

}  // namespace topple::io
