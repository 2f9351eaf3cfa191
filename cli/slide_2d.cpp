// topple slide --h2: bidirectional sliding. Parsing and printing only; the physics is sliding2d.hpp.
#include "slide_2d.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "common.hpp"
#include "topple/core/error.hpp"
#include "topple/output/write.hpp"
#include "topple/output/plot.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {

ComponentAzimuths parse_azimuths(const std::string& text) {
  const auto comma = text.find(',');
  const auto number = [&](std::string_view part) {
    double v = 0.0;
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), v);
    if (ec != std::errc{} || ptr != part.data() + part.size() || !std::isfinite(v)) {
      throw parameter_error("--azimuths", fmt::format("expected two azimuths in degrees as A1,A2 (e.g. 90,0), got "
                                                      "'{}'", text));
    }
    return v;
  };
  if (comma == std::string::npos) {
    throw parameter_error("--azimuths", fmt::format("expected two azimuths in degrees as A1,A2 (e.g. 90,0), got '{}'",
                                                    text));
  }
  const std::string_view all(text);
  return ComponentAzimuths{number(all.substr(0, comma)), number(all.substr(comma + 1))};
}

void run_bidirectional_slide(const GroundMotion& first, const GroundMotion& second, const ComponentAzimuths& azimuths,
                             const SlidingBlock& block, const GroundMotion* vertical, bool json,
                             const std::string& motion_name, const std::string& second_name, double scale_factor,
                             const std::string& plot_path, const std::string& out_path) {
  // With --plot or --out the run keeps its history (slide_2d); its summary is the summary-only path's
  // (sliding2d.hpp).
  const bool keep_history = !plot_path.empty() || !out_path.empty();
  const Sliding2dResult r = [&] {
    try {
      if (keep_history) return slide_2d(first, second, azimuths, block, vertical);
      return Sliding2dResult{slide_2d_summary(first, second, azimuths, block, vertical), {}};
    } catch (const InputError& e) {
      // The library names its fields; the user typed options.
      if (!e.where().file.empty()) throw;
      const std::string& field = e.where().field;
      throw parameter_error(field == "slope" ? "--slope-deg" : field == "slope_azimuth" ? "--slope-azimuth-deg"
                            : field == "mode"  ? "--one-way" : "--azimuths",
                            e.problem());
    }
  }();
  const Sliding2dSummary& s = r.summary;
  require_finite({{"residual displacement", s.residual_displacement_m},
                  {"max |displacement|", s.max_abs_displacement_m},
                  {"path length", s.path_length_m},
                  {"max |velocity|", s.max_abs_velocity_m_s},
                  {"end time", s.end_time_s},
                  {"input work", s.input_work_J_kg},
                  {"friction work", s.friction_work_J_kg}});
  const double g = block.g_m_s2;
  if (!out_path.empty()) io::write_sliding_2d_history_csv(out_path, r.history, first, second, azimuths, vertical);
  if (!plot_path.empty()) {
    const std::string title =
        fmt::format("Bidirectional sliding, mu_s = {:g}: {} and {}{}; residual {:.3g} m", block.mu_static,
                    plot::file_label(motion_name), plot::file_label(second_name),
                    vertical != nullptr ? " with vertical" : "", s.residual_displacement_m);
    plot::render(plot::sliding_2d_figure(first, second, azimuths, vertical, r, block, title), plot_path);
  }
  if (json) {
    nlohmann::ordered_json j = io::sliding_2d_summary_json(s, block);
    io::RunInput in;
    in.motion = motion_name;
    in.scale_factor = scale_factor;
    if (vertical != nullptr) in.vertical = "";  // the 2-D "input" says only whether there is one
    j["input"] = io::sliding_2d_input_json(in, second_name, first, second, azimuths, block);
    fmt::print("{}\n", j.dump(2));
    return;
  }
  if (block.slope_rad != 0.0) {
    fmt::print("bidirectional sliding block on a slope of {} deg falling toward {} deg: mu_s = {}, mu_k = {}, g = {} "
               "m/s2 (displacements in the plane)\n", rad_to_deg(block.slope_rad), azimuths.slope_azimuth_deg,
               block.mu_static, block.mu_kinetic, g);
  } else {
    fmt::print("bidirectional sliding block (level ground): mu_s = {}, mu_k = {}, g = {} m/s2\n", block.mu_static,
               block.mu_kinetic, g);
  }
  fmt::print("motion: {} at {} deg and {} at {} deg (PGA {:.4f} g and {:.4f} g)\n", motion_name,
             azimuths.first_deg, second_name, azimuths.second_deg, first.pga_m_s2() / g, second.pga_m_s2() / g);
  fmt::print("residual displacement  {:.6g} m", s.residual_displacement_m);
  if (s.residual_azimuth_deg) fmt::print(" toward {:.2f} deg (clockwise from north)", *s.residual_azimuth_deg);
  fmt::print("\n  east, north          {:.6g} m, {:.6g} m (of the block relative to the ground)\n", s.residual_east_m,
             s.residual_north_m);
  fmt::print("max |displacement|     {:.6g} m at {:.4f} s\n", s.max_abs_displacement_m, s.max_displacement_time_s);
  fmt::print("path length            {:.6g} m\n", s.path_length_m);
  fmt::print("peak relative speed    {:.6g} m/s\n", s.max_abs_velocity_m_s);
  fmt::print("slip episodes          {}\n", s.slip_episodes);
  fmt::print("first slip             {}\n", format_seconds_or_none(s.first_slip_time_s));
  fmt::print("total slip duration    {:.4f} s\n", s.total_slip_duration_s);
  if (!s.at_rest_at_end) {
    fmt::print("warning: the block never comes to rest ({})\n",
               block.slope_rad != 0.0 ? "slope steeper than kinetic friction" : "no kinetic friction");
  }
  if (s.contact_lost_time_s) {
    fmt::print(stderr, "warning: {} vanishes at t = {:.4f} s: the block leaves the ground and the sliding model "
                       "is not valid after that\n", block.slope_rad != 0.0 ? "the normal force" : "g + a_v",
               *s.contact_lost_time_s);
  }
  if (!out_path.empty()) fmt::print("history written to {}\n", out_path);
  if (!plot_path.empty()) fmt::print("figure written to {}\n", plot_path);
}

}  // namespace topple::cli
