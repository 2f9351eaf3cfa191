// topple info FILE [FILE2 [FILE3]]: what a record is and how strong it is; for a pair (and a vertical), each
// component and the pair's RotD50 / RotD100 (rotd.hpp).
#include <charconv>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "slide_2d.hpp"
#include "topple/core/error.hpp"
#include "topple/motion/intensity.hpp"
#include "topple/output/record_fields.hpp"
#include "topple/output/write.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/output/plot.hpp"
#include "topple/motion/spectra.hpp"

namespace topple::cli {
namespace {

std::string text_value(const OptionalMeasure& m, const char* format_unit) {
  return m.value ? fmt::format(fmt::runtime(format_unit), *m.value) : "undefined (" + m.undefined_reason + ")";
}

struct InfoOptions {
  std::vector<std::string> files;
  std::string channels;  // "1,3,2": one channel per file (multi-channel files)
  std::string azimuths;  // "A1,A2"
  bool json = false;
  std::string plot;
  bool quiet = false;
};

/// The channel of each file from --channels ("1,3,2"), or --channel for all.
std::vector<std::optional<int>> channels_of(const InfoOptions& o, const MotionOptions& m) {
  std::vector<std::optional<int>> out(o.files.size(), m.channel);
  if (o.channels.empty()) return out;
  if (m.channel) throw parameter_error("--channels", "give either --channel or --channels");
  std::vector<std::optional<int>> list;
  std::string_view rest(o.channels);
  while (true) {
    const auto comma = rest.find(',');
    const std::string_view part = rest.substr(0, comma);
    int c = 0;
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), c);
    if (ec != std::errc{} || ptr != part.data() + part.size()) {
      throw parameter_error("--channels", fmt::format("expected one channel number per file, e.g. 1,3,2; got '{}'",
                                                      o.channels));
    }
    list.push_back(c);
    if (comma == std::string_view::npos) break;
    rest = rest.substr(comma + 1);
  }
  if (list.size() != o.files.size()) {
    throw parameter_error("--channels", fmt::format("{} channels for {} files", list.size(), o.files.size()));
  }
  return list;
}

/// One component as JSON (the object `topple info FILE --json` prints): the record's metadata (kRecordMetadataFields),
/// then its measures from the library's field table (kIntensityFields, which topple.intensity returns too).
nlohmann::ordered_json component_json(const GroundMotion& motion, const IntensityMeasures& all, const std::string& file,
                                      double g) {
  nlohmann::ordered_json out;
  out["file"] = file;  // the path as typed: it stands for the table's source_file
  for (const Field<RecordMetadata>& field : kRecordMetadataFields) {
    if (std::string_view(field.name) != "source_file") out[field.name] = io::field_json(field.get(motion.metadata()));
  }
  out.update(io::fields_json(kIntensityFields, IntensityOutcome{motion, all, g}));
  return out;
}

void check_finite(const GroundMotion& motion, const IntensityMeasures& all) {
  const BasicIntensity& im = all.basic;
  require_finite({{"dt", motion.dt_s()}, {"start time", motion.start_time_s()}, {"duration", motion.duration_s()},
                  {"PGA", im.pga_m_s2}, {"PGA time", im.pga_time_s}, {"PGV", im.pgv_m_s}, {"PGD", im.pgd_m},
                  {"Arias intensity", im.arias_m_s}, {"CAV", all.cav_m_s}, {"Tp", all.tp_s.value.value_or(0.0)},
                  {"Tm", all.tm_s.value.value_or(0.0)}, {"f_p", all.predominant_frequency_hz.value.value_or(0.0)}});
  if (all.d5_95) {
    require_finite({{"D5-95", all.d5_95->duration_s}, {"D5", all.d5_95->start_s}, {"D95", all.d5_95->end_s}});
  }
}

void print_component(const GroundMotion& motion, const IntensityMeasures& all, const std::string& file, double g) {
  const BasicIntensity& im = all.basic;
  const auto& meta = motion.metadata();
  const std::optional<SignificantDuration>& duration = all.d5_95;
  fmt::print("file        {}\n", file);
  fmt::print("format      {}\n", meta.format);
  if (!meta.event.empty()) fmt::print("event       {}\n", meta.event);
  if (!meta.station.empty()) fmt::print("station     {}\n", meta.station);
  if (!meta.component.empty()) fmt::print("component   {}\n", meta.component);
  if (meta.azimuth_deg) fmt::print("azimuth     {:g} deg (clockwise from north, from the header)\n", *meta.azimuth_deg);
  if (meta.vertical) fmt::print("vertical    yes (from the header)\n");
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
  fmt::print("CAV         {:.5g} m/s\n", all.cav_m_s);
  fmt::print("Tp          {}   (peak of the 5%-damped PSA)\n", text_value(all.tp_s, "{:.4f} s"));
  fmt::print("Tm          {}   (Rathje et al. 1998)\n", text_value(all.tm_s, "{:.4f} s"));
  fmt::print("f_p         {}   (peak of the Konno-Ohmachi b=40 smoothed FAS)\n",
             text_value(all.predominant_frequency_hz, "{:.4f} Hz"));
  fmt::print("g           {} m/s2\n", g);
}

nlohmann::ordered_json rotd_json(const RotDValue& v, double scale, const MotionSet& set, const char* unit) {
  nlohmann::ordered_json j;
  j[fmt::format("rotd50_{}", unit)] = v.rotd50 / scale;
  j[fmt::format("rotd100_{}", unit)] = v.rotd100 / scale;
  j["rotd100_angle_deg"] = v.rotd100_angle_deg;
  const auto az = rotd_azimuth_deg(set, v.rotd100_angle_deg);
  j["rotd100_azimuth_deg"] = az ? nlohmann::ordered_json(*az) : nlohmann::ordered_json(nullptr);
  return j;
}

/// Several files: each component, then the pair's RotD.
void run_info_set(const InfoOptions& o, const MotionOptions& base) {
  const double g = base.g_m_s2;
  const auto channels = channels_of(o, base);
  std::vector<GroundMotion> motions;
  double factor = 1.0;
  for (std::size_t k = 0; k < o.files.size(); ++k) {
    MotionOptions m = base;
    m.file = o.files[k];
    m.channel = channels[k];
    GroundMotion raw = io::read_motion(m.file, read_options(m));
    // Scaling options apply to the first component; the others get the same factor (one shaking, scaled as one).
    if (k == 0) {
      motions.push_back(transform_motion(raw, m));
      factor = amplitude_factor(raw, motions.front());
    } else {
      motions.push_back(raw.scaled(factor));
    }
  }
  std::vector<std::string> warnings;
  std::optional<ComponentAzimuths> azimuths;
  const std::optional<ComponentAzimuths> user =
      o.azimuths.empty() ? std::nullopt : std::optional(parse_azimuths(o.azimuths));
  const GroundMotion& h1 = motions[0];
  const GroundMotion& h2 = motions[1];
  if (user || (h1.metadata().azimuth_deg && h2.metadata().azimuth_deg)) {
    azimuths = resolve_azimuths(h1, h2, user, warnings, "--azimuths");
  }
  const MotionSet set = MotionSet::make(h1, &h2, azimuths, motions.size() == 3 ? &motions[2] : nullptr);
  const std::vector<double> periods = rotd_periods_s();
  const RotDMeasures rotd = rotd_measures(set, periods, kDefaultDampingRatio);
  std::vector<IntensityMeasures> measures;
  for (const GroundMotion& m : motions) {
    measures.push_back(intensity_measures(m, g));
    check_finite(m, measures.back());
  }
  require_finite({{"RotD50 PGA", rotd.pga_m_s2.rotd50}, {"RotD100 PGA", rotd.pga_m_s2.rotd100}});
  for (const RotDValue& v : rotd.psa_m_s2) require_finite({{"RotD50 PSA", v.rotd50}, {"RotD100 PSA", v.rotd100}});
  for (const std::string& w : warnings) fmt::print(stderr, "warning: {}\n", w);
  if (!o.plot.empty()) {
    // Every component on the set's grid, each with its ground velocity, displacement and PSA on Tp's periods
    // (spectra.hpp), and the pair's RotD50 / RotD100 PSA on the same periods.
    const std::vector<double> plot_periods = tp_periods_s();
    const RotDMeasures plot_rotd = rotd_measures(set, plot_periods, kDefaultDampingRatio);
    std::vector<plot::ComponentRecord> components;
    const auto add = [&](std::string label, const GroundMotion& m) {
      components.push_back({std::move(label), &m, integrate_ground(m), response_spectrum(m, plot_periods, kDefaultDampingRatio)});
    };
    add(azimuths ? fmt::format("H1 ({:g} deg)", azimuths->first_deg) : "H1", set.first());
    add(azimuths ? fmt::format("H2 ({:g} deg)", azimuths->second_deg) : "H2", set.second());
    if (set.has_vertical()) add("V (up)", set.vertical());
    const auto& meta = h1.metadata();
    const std::string name = !meta.event.empty() ? meta.event + (meta.station.empty() ? "" : ", " + meta.station)
                                                 : plot::file_label(o.files[0]);
    const std::string title = fmt::format("{}: RotD50 PGA {:.3g} g, RotD100 {:.3g} g", name,
                                          rotd.pga_m_s2.rotd50 / g, rotd.pga_m_s2.rotd100 / g);
    plot::render(plot::record_set_figure(components, &plot_rotd, g, title), o.plot);
  }
  if (o.json) {
    nlohmann::ordered_json out;
    out["components"] = nlohmann::ordered_json::array();
    for (std::size_t k = 0; k < motions.size(); ++k) {
      out["components"].push_back(component_json(motions[k], measures[k], o.files[k], g));
    }
    out["azimuths_deg"] = azimuths ? nlohmann::ordered_json({azimuths->first_deg, azimuths->second_deg})
                                   : nlohmann::ordered_json(nullptr);
    nlohmann::ordered_json r;
    r["definition"] = "Boore 2010: rotation angles 0..179 deg from the first component toward the second; RotD50 the "
                      "median, RotD100 the largest";
    r["merged_npts"] = set.size();
    r["pga"] = rotd_json(rotd.pga_m_s2, g, set, "g");
    r["damping"] = rotd.damping;
    r["psa"] = nlohmann::ordered_json::array();
    for (std::size_t p = 0; p < periods.size(); ++p) {
      nlohmann::ordered_json row;
      row["period_s"] = periods[p];
      row.update(rotd_json(rotd.psa_m_s2[p], g, set, "g"));
      r["psa"].push_back(row);
    }
    out["rotd"] = r;
    out["warnings"] = warnings;
    out["g_m_s2"] = g;
    fmt::print("{}\n", out.dump(2));
    return;
  }
  const char* names[] = {"first horizontal component (H1)", "second horizontal component (H2)", "vertical component"};
  for (std::size_t k = 0; k < motions.size(); ++k) {
    fmt::print("== {}\n", names[k]);
    print_component(motions[k], measures[k], o.files[k], g);
    fmt::print("\n");
  }
  fmt::print("== the horizontal pair: RotD50 / RotD100 (Boore 2010; angles 0..179 deg, {} merged samples)\n",
             set.size());
  if (azimuths) {
    fmt::print("azimuths    H1 {:g} deg, H2 {:g} deg (clockwise from north)\n", azimuths->first_deg,
               azimuths->second_deg);
  } else {
    fmt::print("azimuths    unknown (give --azimuths A1,A2): directions are angles from H1 toward H2\n");
  }
  const auto direction = [&](double angle) {
    const auto az = rotd_azimuth_deg(set, angle);
    return az ? fmt::format("azimuth {:.0f} deg", *az) : fmt::format("{:.0f} deg from H1", angle);
  };
  fmt::print("PGA         RotD50 {:.5f} g, RotD100 {:.5f} g ({})\n", rotd.pga_m_s2.rotd50 / g,
             rotd.pga_m_s2.rotd100 / g, direction(rotd.pga_m_s2.rotd100_angle_deg));
  fmt::print("PSA, 5 % damping:\n  period_s  RotD50_g   RotD100_g  RotD100 direction\n");
  for (std::size_t p = 0; p < periods.size(); ++p) {
    fmt::print("  {:<8g}  {:<9.5f}  {:<9.5f}  {}\n", periods[p], rotd.psa_m_s2[p].rotd50 / g,
               rotd.psa_m_s2[p].rotd100 / g, direction(rotd.psa_m_s2[p].rotd100_angle_deg));
  }
  if (!o.plot.empty()) fmt::print("figure      {}\n", o.plot);
}

}  // namespace

void add_info_command(CLI::App& app) {
  auto options = std::make_shared<MotionOptions>();
  auto info = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand("info", "Describe a ground-motion record: format, station, npts, dt, PGA, PGV, "
                                             "PGD, Arias intensity, D5-95, CAV, Tp, Tm, predominant frequency; for two horizontal "
                                             "components (and a vertical), each of them and the pair's RotD50 and "
                                             "RotD100 of PGA and 5%-damped PSA");
  cmd->add_option("files", info->files, "Record file (format detected from content); or H1 H2 [V]: two horizontal "
                                        "components and a vertical of one station")
      ->required()
      ->expected(1, 3);
  add_motion_options(*cmd, *options);
  cmd->add_option("--channels", info->channels, "With several files: the channel of each (multi-channel files such as "
                                                "CSMIP V2), e.g. 1,3,2");
  cmd->add_option("--azimuths", info->azimuths, "With two horizontal components: their azimuths A1,A2 in degrees "
                                                "clockwise from north (default: the files' headers; a value given "
                                                "here wins over a header, with a warning)");
  cmd->add_flag("--json", info->json, "Print one JSON object instead of text");
  add_quiet_flag(*cmd, info->quiet);  // no bar: info is quick; accepted so that every command takes --quiet
  cmd->add_option("--plot", info->plot, "Draw acceleration, velocity, displacement and the 5%-damped PSA spectrum "
                                        "with Tp marked to this .svg or .png file (gnuplot); with H1 H2 [V], every "
                                        "component and the pair's RotD50 / RotD100 PSA");
  cmd->callback([options, info] {
    check_plot_path(info->plot);
    check_g(options->g_m_s2);
    if (info->files.size() > 1) {
      run_info_set(*info, *options);
      return;
    }
    if (!info->channels.empty()) throw parameter_error("--channels", "is for several files; use --channel");
    if (!info->azimuths.empty()) throw parameter_error("--azimuths", "needs two horizontal components (H1 H2)");
    const auto plot_path = &info->plot;
    const auto json = &info->json;
    options->file = info->files.front();
    const GroundMotion motion = load_motion(*options);
    const IntensityMeasures all = intensity_measures(motion, options->g_m_s2);
    const BasicIntensity& im = all.basic;
    const auto& meta = motion.metadata();
    const double g = options->g_m_s2;
    const OptionalMeasure& tp = all.tp_s;
    check_finite(motion, all);
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
      plot::render(plot::record_figure(motion, integrate_ground(motion), response_spectrum(motion, periods, kDefaultDampingRatio),
                                       marks, g, title),
                   *plot_path);
    }
    if (*json) {
      fmt::print("{}\n", component_json(motion, all, options->file, g).dump(2));
      return;
    }
    print_component(motion, all, options->file, g);
    if (!plot_path->empty()) fmt::print("figure      {}\n", *plot_path);
  });
}

}  // namespace topple::cli
