// topple info FILE: what a record is and how strong it is.
#include <cstdio>
#include <memory>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "topple/intensity.hpp"

namespace topple::cli {

void add_info_command(CLI::App& app) {
  auto options = std::make_shared<MotionOptions>();
  auto json = std::make_shared<bool>(false);
  CLI::App* cmd = app.add_subcommand("info", "Describe a ground-motion record: format, station, npts, dt, PGA, PGV, "
                                             "PGD, Arias intensity");
  cmd->add_option("file", options->file, "Record file (format detected from content)")->required();
  add_motion_options(*cmd, *options);
  cmd->add_flag("--json", *json, "Print one JSON object instead of text");
  cmd->callback([options, json] {
    const GroundMotion motion = load_motion(*options);
    const BasicIntensity im = basic_intensity(motion, options->g_m_s2);
    const auto& meta = motion.metadata();
    const double g = options->g_m_s2;
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
    fmt::print("g           {} m/s2\n", g);
  });
}

}  // namespace topple::cli
