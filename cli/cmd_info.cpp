// topple info FILE: what a record is and how strong it is.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "topple/error.hpp"
#include "topple/intensity.hpp"
#include "topple/plot.hpp"
#include "topple/spectra.hpp"

namespace topple::cli {
namespace {

nlohmann::ordered_json json_value(const OptionalMeasure& m) {
  return m.value ? nlohmann::ordered_json(*m.value) : nlohmann::ordered_json(nullptr);
}

std::string text_value(const OptionalMeasure& m, const char* format_unit) {
  return m.value ? fmt::format(fmt::runtime(format_unit), *m.value) : "undefined (" + m.undefined_reason + ")";
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto options = std::make_shared<MotionOptions>();
  auto json = std::make_shared<bool>(false);
  auto plot_path = std::make_shared<std::string>();
  auto quiet = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("info", "Describe a ground-motion record: format, station, npts, dt, PGA, PGV, "
                                             "PGD, Arias intensity, D5-95, CAV, Tp, Tm, predominant frequency");
  cmd->add_option("file", options->file, "Record file (format detected from content)")->required();
  add_motion_options(*cmd, *options);
  cmd->add_flag("--json", *json, "Print one JSON object instead of text");
  add_quiet_flag(*cmd, *quiet);  // no bar: info is quick; accepted so that every command takes --quiet
  cmd->add_option("--plot", *plot_path, "Draw acceleration, velocity, displacement and the 5%-damped PSA spectrum "
                                        "with Tp marked to this .svg or .png file (gnuplot)");
  cmd->callback([options, json, plot_path] {
    check_plot_path(*plot_path);
    const GroundMotion motion = load_motion(*options);
    const IntensityMeasures all = intensity_measures(motion, options->g_m_s2);
    const BasicIntensity& im = all.basic;
    const auto& meta = motion.metadata();
    const double g = options->g_m_s2;
    const std::optional<SignificantDuration>& duration = all.d5_95;
    const double cav = all.cav_m_s;
    const OptionalMeasure& tp = all.tp_s;
    const OptionalMeasure& tm = all.tm_s;
    const OptionalMeasure& fp = all.predominant_frequency_hz;
    require_finite({{"dt", motion.dt_s()}, {"start time", motion.start_time_s()}, {"duration", motion.duration_s()},
                    {"PGA", im.pga_m_s2}, {"PGA time", im.pga_time_s}, {"PGV", im.pgv_m_s}, {"PGD", im.pgd_m},
                    {"Arias intensity", im.arias_m_s}, {"CAV", cav}, {"Tp", tp.value.value_or(0.0)},
                    {"Tm", tm.value.value_or(0.0)}, {"f_p", fp.value.value_or(0.0)}});
    if (duration) require_finite({{"D5-95", duration->duration_s}, {"D5", duration->start_s}, {"D95", duration->end_s}});
    if (!plot_path->empty()) {
      // Tp's own spectrum (spectra.hpp): 5 % damping on Tp's periods.
      const auto periods = tp_periods_s();
      std::vector<plot::Mark> marks;
      if (tp.value) marks.push_back({*tp.value, fmt::format("Tp = {:.3f} s", *tp.value), "#e67e22"});
      const std::string name = !meta.event.empty() ? meta.event + (meta.station.empty() ? "" : ", " + meta.station)
                                                   : plot::file_label(options->file);
      const std::string title = fmt::format("{}{}: PGA {:.3g} g, PGV {:.3g} m/s, PGD {:.3g} m", name,
                                            meta.component.empty() ? "" : " " + meta.component, im.pga_m_s2 / g,
                                            im.pgv_m_s, im.pgd_m);
      plot::render(plot::record_figure(motion, integrate_ground(motion), response_spectrum(motion, periods, 0.05),
                                       marks, g, title),
                   *plot_path);
    }
    if (*json) {
      nlohmann::ordered_json out;
      out["file"] = options->file;
      out["format"] = meta.format;
      out["event"] = meta.event;
      out["station"] = meta.station;
      out["component"] = meta.component;
      out["units_as_read"] = meta.units_as_read;
      out["npts"] = motion.size();
      out["uniform"] = motion.is_uniform();
      out["dt_s"] = motion.dt_s();
      out["start_time_s"] = motion.start_time_s();
      out["duration_s"] = motion.duration_s();
      out["pga_g"] = im.pga_m_s2 / g;
      out["pga_m_s2"] = im.pga_m_s2;
      out["pga_time_s"] = im.pga_time_s;
      out["pgv_m_s"] = im.pgv_m_s;
      out["pgd_m"] = im.pgd_m;
      out["arias_m_s"] = im.arias_m_s;
      out["d5_95_s"] = duration ? nlohmann::ordered_json(duration->duration_s) : nlohmann::ordered_json(nullptr);
      out["d5_time_s"] = duration ? nlohmann::ordered_json(duration->start_s) : nlohmann::ordered_json(nullptr);
      out["d95_time_s"] = duration ? nlohmann::ordered_json(duration->end_s) : nlohmann::ordered_json(nullptr);
      out["cav_m_s"] = cav;
      out["tp_s"] = json_value(tp);
      out["tm_s"] = json_value(tm);
      out["predominant_frequency_hz"] = json_value(fp);
      out["g_m_s2"] = g;
      fmt::print("{}\n", out.dump(2));
      return;
    }
    fmt::print("file        {}\n", options->file);
    fmt::print("format      {}\n", meta.format);
    if (!meta.event.empty()) fmt::print("event       {}\n", meta.event);
    if (!meta.station.empty()) fmt::print("station     {}\n", meta.station);
    if (!meta.component.empty()) fmt::print("component   {}\n", meta.component);
    if (!meta.units_as_read.empty()) fmt::print("units read  {}\n", meta.units_as_read);
    fmt::print("npts        {}\n", motion.size());
    fmt::print("dt          {:.6g} s{}\n", motion.dt_s(), motion.is_uniform() ? "" : " (mean; irregular sampling)");
    fmt::print("duration    {:.4f} s\n", motion.duration_s());
    fmt::print("PGA         {:.5f} g ({:.5g} m/s2) at {:.4f} s\n", im.pga_m_s2 / g, im.pga_m_s2, im.pga_time_s);
    fmt::print("PGV         {:.5g} m/s\n", im.pgv_m_s);
    fmt::print("PGD         {:.5g} m   (no baseline correction)\n", im.pgd_m);
    fmt::print("Arias       {:.5g} m/s\n", im.arias_m_s);
    if (duration) {
      fmt::print("D5-95       {:.4f} s (from {:.4f} s to {:.4f} s)\n", duration->duration_s, duration->start_s,
                 duration->end_s);
    } else {
      fmt::print("D5-95       undefined (the record is identically zero)\n");
    }
    fmt::print("CAV         {:.5g} m/s\n", cav);
    fmt::print("Tp          {}   (peak of the 5%-damped PSA)\n", text_value(tp, "{:.4f} s"));
    fmt::print("Tm          {}   (Rathje et al. 1998)\n", text_value(tm, "{:.4f} s"));
    fmt::print("f_p         {}   (peak of the Konno-Ohmachi b=40 smoothed FAS)\n", text_value(fp, "{:.4f} Hz"));
    fmt::print("g           {} m/s2\n", g);
    if (!plot_path->empty()) fmt::print("figure      {}\n", *plot_path);
  });
}

}  // namespace topple::cli
