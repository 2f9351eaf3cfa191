// topple slide: sliding response of a friction block to a record or a pulse.
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "motion_set_options.hpp"
#include "slide_2d.hpp"
#include "topple/motion/motion_set.hpp"
#include "slide_flexible.hpp"
#include "topple/core/error.hpp"
#include "topple/output/write.hpp"
#include "topple/output/plot.hpp"
#include "topple/solvers/sliding.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

struct SlideOptions {
  MotionOptions motion;
  PulseOptions pulse;
  std::optional<double> mu;
  std::optional<double> mu_kinetic;
  double slope_deg = 0.0;
  bool one_way = false;
  std::string vertical;
  std::string h2;        // second horizontal component: bidirectional sliding (slide_2d.hpp)
  std::string azimuths;  // "A1,A2", degrees clockwise from north
  std::optional<double> slope_azimuth_deg;  // with --h2 on a slope: the downslope direction, clockwise from north
  std::string out;
  std::string plot;
  bool json = false;
  bool quiet = false;
  FlexibleOptions flexible;
};

/// The analysis a sliding figure shows: friction (static and kinetic), slope, one-way, the vertical, the motion.
std::string sliding_title(const SlidingBlock& block, const SlideOptions& o, const std::string& motion) {
  std::string t = fmt::format("Sliding block, μ = {:g}", block.mu_static);
  if (o.mu_kinetic) t += fmt::format(", μ_k = {:g}", *o.mu_kinetic);
  if (o.slope_deg != 0.0) t += fmt::format(", slope {:g}°", o.slope_deg);
  t += o.one_way ? ", one-way" : ", two-way";
  if (!o.vertical.empty()) t += ", with vertical " + plot::file_label(o.vertical);
  return t + ": " + motion;
}

void run_slide(const SlideOptions& o) {
  const double g = o.motion.g_m_s2;
  check_g(g);
  if (!o.mu) throw parameter_error("--mu", "the friction coefficient is required");
  check_flexible_options(o.flexible);
  check_plot_path(o.plot);
  check_output_path(o.out);
  const SlidingBlock block = [&] {
    try {
      return SlidingBlock::make(*o.mu, o.mu_kinetic, deg_to_rad(o.slope_deg),
                                o.one_way ? SlidingMode::one_way : SlidingMode::two_way, g);
    } catch (const InputError& e) {
      // The library names its fields; the user typed options.
      const std::string& field = e.where().field;
      if (!e.where().file.empty()) throw;
      throw parameter_error(field == "mu_kinetic" ? "--mu-kinetic" : field == "slope" ? "--slope-deg"
                            : field == "g"        ? "--g" : "--mu", e.problem());
    }
  }();
  const RunMotion run = load_run_motion(o.motion, o.pulse, o.vertical);
  const GroundMotion& horizontal = run.horizontal;
  const GroundMotion* vertical_ptr = run.vertical_ptr();
  if (!o.h2.empty()) {
    if (o.flexible.active()) {
      throw parameter_error("--h2", "flexible supports are not available with two components");
    }
    // The second component is scaled with the first (the shaking is scaled as a whole), as the vertical is; the
    // azimuths from --azimuths or the files' headers (motion_set_options.hpp).
    const MotionSet set = load_motion_set(run, o.motion, o.h2, o.azimuths);
    ComponentAzimuths azimuths = *set.azimuths();
    if (o.slope_deg != 0.0 && !o.slope_azimuth_deg) {
      throw parameter_error("--slope-azimuth-deg", "required with --h2 and --slope-deg: the azimuth of the downslope "
                                                   "direction, degrees clockwise from north");
    }
    if (o.slope_azimuth_deg) {
      if (o.slope_deg == 0.0) throw parameter_error("--slope-azimuth-deg", "needs --slope-deg (a slope)");
      azimuths.slope_azimuth_deg = *o.slope_azimuth_deg;
    }
    run_bidirectional_slide(set.first(), set.second(), azimuths, block, set.vertical_ptr(), o.json, run.input.motion,
                            o.h2, run.input.scale_factor, o.plot, o.out);
    return;
  }
  refuse_without_h2(o.azimuths);
  if (o.slope_azimuth_deg) {
    throw parameter_error("--slope-azimuth-deg", "needs --h2 (with one component the motion is along the fall line)");
  }
  if (o.flexible.active()) {
    run_flexible_slide(horizontal, block, o.flexible, o.json,
                       o.pulse.kind.empty() ? o.motion.file : horizontal.metadata().event, vertical_ptr, o.out, o.plot,
                       o.pulse.kind);
    return;
  }

  SlidingSummary summary;
  if (!o.out.empty() || !o.plot.empty()) {
    const SlidingResult result = slide(horizontal, block, vertical_ptr);
    if (!o.out.empty()) io::write_sliding_history_csv(o.out, result.history, horizontal);
    if (!o.plot.empty()) {
      plot::render(plot::sliding_figure(horizontal, result, block,
                                        sliding_title(block, o, run.title)),
                   o.plot);
    }
    summary = result.summary;
  } else {
    summary = slide_summary(horizontal, block, vertical_ptr);
  }

  require_finite({{"PGA", horizontal.pga_m_s2()}, {"max |displacement|", summary.max_abs_displacement_m},
                  {"time of max |displacement|", summary.max_displacement_time_s},
                  {"residual displacement", summary.residual_displacement_m},
                  {"max |velocity|", summary.max_abs_velocity_m_s}, {"end time", summary.end_time_s},
                  {"first slip", summary.first_slip_time_s.value_or(0.0)},
                  {"total slip duration", summary.total_slip_duration_s},
                  {"contact lost", summary.contact_lost_time_s.value_or(0.0)}});
  if (o.json) {
    nlohmann::ordered_json j = io::sliding_summary_json(summary, block);
    j["input"] = io::run_input_json(run.input, horizontal, g);
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("sliding block: mu_s = {}, mu_k = {}, slope = {} deg, {}, g = {} m/s2\n", block.mu_static,
             block.mu_kinetic, o.slope_deg, o.one_way ? "one-way (down-slope only)" : "two-way", g);
  fmt::print("motion: {} (PGA {:.4f} g, {} samples)\n", run.input.motion, horizontal.pga_m_s2() / g,
             horizontal.size());
  fmt::print("yield acceleration: {:.4f} g down-slope", block.yield_down_m_s2() / g);
  if (!o.one_way) fmt::print(", {:.4f} g up-slope", block.yield_up_m_s2() / g);
  fmt::print("\n");
  fmt::print("max |displacement|     {:.6g} m at {:.4f} s\n", summary.max_abs_displacement_m,
             summary.max_displacement_time_s);
  fmt::print("residual displacement  {:.6g} m (positive: direction of positive ground acceleration's push)\n",
             summary.residual_displacement_m);
  fmt::print("slip episodes          {}\n", summary.slip_episodes);
  fmt::print("first slip             {}\n", format_seconds_or_none(summary.first_slip_time_s));
  fmt::print("total slip duration    {:.4f} s\n", summary.total_slip_duration_s);
  if (!summary.at_rest_at_end) fmt::print("warning: the block never comes to rest (slope steeper than friction)\n");
  if (summary.contact_lost_time_s) {
    fmt::print(stderr, "warning: the normal force vanishes at t = {:.4f} s: the block leaves the plane and the "
                       "sliding model is not valid after that\n", *summary.contact_lost_time_s);
  }
  if (!o.out.empty()) fmt::print("history written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

}  // namespace

void add_slide_command(CLI::App& app) {
  auto o = std::make_shared<SlideOptions>();
  CLI::App* cmd = app.add_subcommand("slide", "Sliding of a rigid block on a friction surface (exact for "
                                              "piecewise-linear input)");
  cmd->add_option("file", o->motion.file, "Record file (format detected from content)");
  add_motion_options(*cmd, o->motion);
  add_pulse_options(*cmd, o->pulse);
  cmd->add_option("--mu", o->mu, "Friction coefficient (static; also kinetic unless --mu-kinetic)");
  cmd->add_option("--mu-kinetic", o->mu_kinetic, "Kinetic friction coefficient (<= --mu)");
  cmd->add_option("--slope-deg", o->slope_deg, "Inclination of the plane, degrees (positive displacement is "
                                               "down-slope)")->capture_default_str();
  cmd->add_flag("--one-way", o->one_way, "Down-slope sliding only (SLAMMER rigid-block convention)");
  add_motion_set_options(*cmd, o->vertical, o->h2, o->azimuths,
                         "bidirectional sliding, friction against the 2-D relative velocity in the plane");
  cmd->add_option("--slope-azimuth-deg", o->slope_azimuth_deg, "With --h2 and --slope-deg: azimuth of the downslope "
                                                               "direction, degrees clockwise from north");
  cmd->add_option("--out", o->out, "Write the time history to this CSV file (with --h2: east and north "
                                    "components of the ground, displacement and velocity)");
  cmd->add_option("--plot", o->plot, "Draw record, thresholds and response to this .svg or .png file (gnuplot); with "
                                     "--h2, both components (and the vertical) and the east and north response");
  cmd->add_flag("--json", o->json, "Print the summary as one JSON object");
  add_flexible_options(*cmd, o->flexible);
  add_quiet_flag(*cmd, o->quiet);  // a single run is quick: no bar; warnings are still printed
  cmd->callback([o] { run_slide(*o); });
}

}  // namespace topple::cli
