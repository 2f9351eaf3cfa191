// topple rock --model coupled: the coupled slide-rock model (slide_rock.hpp). Parsing and printing only.
#include "rock_coupled.hpp"

#include <cstddef>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "topple/output/write.hpp"
#include "topple/output/plot.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {

void run_coupled(const RunMotion& run, const SlideRockBody& body, const CoupledRequest& request) {
  SlideRockOptions options = request.options;
  options.record_history = !request.out.empty() || !request.plot.empty();
  const SlideRockResult result = slide_rock(run.horizontal, body, options, run.vertical_ptr());
  const SlideRockSummary& s = result.summary;
  if (!request.out.empty()) io::write_slide_rock_history_csv(request.out, result.history);
  if (!request.plot.empty()) {
    const std::string title = fmt::format(
        "Coupled slide-rock, b1 = {:.3g} m, b2 = {:.3g} m, h = {:.3g} m, mu_s = {:.3g}, mu_k = {:.3g}{}: {}", body.b1_m,
        body.b2_m, body.h_m, body.mu_static, body.mu_kinetic,
        options.slope_rad != 0.0 ? fmt::format(", slope {:g}°", rad_to_deg(options.slope_rad)) : std::string(),
        run.title);
    plot::render(plot::slide_rock_figure(run.horizontal, result, body, title, run.vertical_ptr(), options.g_m_s2,
                                         options.slope_rad),
                 request.plot);
  }
  for (const auto& w : s.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
  require_finite({{"residual slide", s.residual_slide_m}, {"max |slide|", s.max_abs_slide_m},
                  {"max theta / alpha", s.max_rotation_over_alpha}, {"end time", s.end_time_s},
                  {"friction energy", s.friction_energy_j_per_kg}, {"impact energy", s.impact_energy_j_per_kg},
                  {"overturning time", s.overturn_time_s.value_or(0.0)}});
  const double g = options.g_m_s2;
  if (request.json) {
    nlohmann::ordered_json j = io::slide_rock_summary_json(s, body, options);
    j["input"] = io::run_input_json(run.input, run.horizontal, g);
    if (request.bearing_deg && request.azimuths) {
      j["input"]["h2"] = request.h2;
      j["orientation"] = {{"bearing_deg", *request.bearing_deg},
                          {"azimuths_deg", {request.azimuths->first_deg, request.azimuths->second_deg}},
                          {"model", "planar: the projection of the pair on the bearing, with the vertical"}};
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("coupled slide-rock body: b1 = {:.6g} m (O-, theta < 0), b2 = {:.6g} m (O+, theta > 0), h = {:.6g} m, "
             "I_cm/m = {:.6g} m2, mu_s = {:.6g}, mu_k = {:.6g}\n",
             body.b1_m, body.b2_m, body.h_m, body.inertia_m2, body.mu_static, body.mu_kinetic);
  fmt::print("  alpha+ = {:.4f} deg, alpha- = {:.4f} deg{}\n", rad_to_deg(s.alpha_positive_rad),
             rad_to_deg(s.alpha_negative_rad),
             s.used_sliding_kernel ? " (cannot lift: mu_s < b/h; exact sliding solver)" : "");
  if (options.slope_rad != 0.0) {
    fmt::print("base: inclined at {:g} deg, down-slope toward -x (slide > 0 is up-slope)\n",
               rad_to_deg(options.slope_rad));
  }
  if (request.bearing_deg) {
    fmt::print("plane of shaking: bearing {:g} deg (+x side), the pair's projection on it (planar model)\n",
               *request.bearing_deg);
  }
  fmt::print("motion: {} (PGA {:.4f} g, {} samples)\n", run.input.motion, run.horizontal.pga_m_s2() / g,
             run.horizontal.size());
  fmt::print("onset mode             {}\n", slide_rock_mode_name(s.onset_mode));
  fmt::print("max theta / alpha      {:.6g} (+x side {:.6g}, -x side {:.6g})\n", s.max_rotation_over_alpha,
             s.max_rotation_over_alpha_positive, s.max_rotation_over_alpha_negative);
  fmt::print("residual slide         {:.6g} m (toward +x)\n", s.residual_slide_m);
  fmt::print("max |slide|            {:.6g} m\n", s.max_abs_slide_m);
  fmt::print("slip episodes, impacts {}, {}\n", s.slip_episodes, s.impacts);
  fmt::print("overturned             {}\n",
             s.overturned ? fmt::format("yes, at {} toward {}x", format_seconds_or_none(s.overturn_time_s),
                                        s.overturned_side > 0 ? '+' : '-')
                          : std::string("no"));
  fmt::print("modes visited         ");
  for (std::size_t m = 0; m < kSlideRockModes; ++m) {
    if (s.mode_entries[m] == 0) continue;
    fmt::print(" {} x{} (first {:.4f} s)", slide_rock_mode_name(static_cast<SlideRockMode>(m)), s.mode_entries[m],
               *s.mode_first_time_s[m]);
  }
  fmt::print("\n");
  fmt::print("energy dissipated      friction {:.6g} J/kg, impacts {:.6g} J/kg\n", s.friction_energy_j_per_kg,
             s.impact_energy_j_per_kg);
  fmt::print("end                    {} at {:.4f} s\n", slide_rock_mode_name(s.end_mode), s.end_time_s);
  if (!request.out.empty()) fmt::print("history written to {}\n", request.out);
  if (!request.plot.empty()) fmt::print("figure written to {}\n", request.plot);
}

}  // namespace topple::cli
