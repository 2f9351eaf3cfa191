// topple spectrum slide | rock: sliding displacement spectrum over mu, overturning map over PGA x size.
// Parsing and printing only; the computation is topple::sliding_spectrum / topple::overturning_map.
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "grids.hpp"
#include "motion_set_options.hpp"
#include "slide_flexible.hpp"
#include "topple/core/error.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/core/output_file.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/output/write.hpp"
#include "topple/output/plot.hpp"
#include "topple/motion/rotd.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

struct MotionInput {
  MotionOptions motion;
  PulseOptions pulse;
  std::string support_freq;     ///< objects on a shelf or floor: its frequency ("4Hz")
  std::string support_damping;  ///< and damping ("5%", default 5 %)
  std::string h2;                ///< spectrum rock: the second horizontal component (motion_set_options.hpp)
  std::string azimuths;          ///< "A1,A2"
  std::optional<double> bearing_deg;  ///< the family's bearing: it rocks under the projection on it
};

struct LoadedMotion {
  GroundMotion motion;  ///< what the objects stand on: the ground's motion, or their support's
  std::string name;
  std::optional<SupportOscillator> support;
  double ground_pga_m_s2 = 0.0;  ///< of the ground's motion as read (the support's differs)
  std::string title;  ///< RunMotion::title, and the support when there is one
};

/// The support is checked before the motion is read.
std::optional<SupportOscillator> support_of(const MotionInput& in) {
  if (in.support_freq.empty()) {
    if (!in.support_damping.empty()) throw parameter_error("--support-damping", "goes with --support-freq");
    return std::nullopt;
  }
  return support_from_options(in.support_freq, in.support_damping);
}

/// The motion the objects rock under: the record, or with --h2 the projection of the pair on --bearing-deg (the
/// planar model of oriented.hpp, eq. M1; the PGA axis is then the projected motion's PGA).
LoadedMotion load(const MotionInput& in) {
  const std::optional<SupportOscillator> support = support_of(in);
  RunMotion run = load_run_motion(in.motion, in.pulse);
  if (!in.h2.empty()) {
    if (!in.bearing_deg) {
      throw parameter_error("--bearing-deg", "required with --h2: the family's bearing (the direction across its "
                                             "narrow side, degrees clockwise from north)");
    }
    const MotionSet set = load_motion_set(run, in.motion, in.h2, in.azimuths);
    run.horizontal = set.projected(*in.bearing_deg);  // azimuths are known (load_motion_set)
    run.input.motion += fmt::format(" and {} along {:g} deg", in.h2, *in.bearing_deg);
    run.title += fmt::format(" and {} along {:g}°", plot::file_label(in.h2), *in.bearing_deg);
  } else {
    refuse_without_h2(in.azimuths, {{"--bearing-deg", in.bearing_deg.has_value()}});
  }
  if (support) {
    // Objects on a flexible support: the spectrum of what the support passes on (flexible.hpp, decoupled).
    if (!run.horizontal.is_uniform()) {
      throw parameter_error("--support-freq", "a flexible support needs a uniformly sampled motion (pulses are "
                                              "sampled at their jumps)");
    }
    const double ground_pga = run.horizontal.pga_m_s2();
    std::string title = run.title + fmt::format(", on a {:.3g} Hz support ({:.3g} % damping)", support->freq_hz,
                                                100.0 * support->damping_ratio);
    return {support_motion(run.horizontal, *support), std::move(run.input.motion), support, ground_pga,
            std::move(title)};
  }
  const double ground_pga = run.horizontal.pga_m_s2();
  return {std::move(run.horizontal), std::move(run.input.motion), std::nullopt, ground_pga, std::move(run.title)};
}

/// The support in the JSON: null on the ground.
nlohmann::ordered_json support_json(const LoadedMotion& lm, double g) {
  if (!lm.support) return nullptr;
  nlohmann::ordered_json j;
  j["freq_hz"] = lm.support->freq_hz;
  j["damping_ratio"] = lm.support->damping_ratio;
  j["ground_pga_g"] = lm.ground_pga_m_s2 / g;
  j["support_pga_g"] = lm.motion.pga_m_s2() / g;
  return j;
}

/// The text line that says the objects stand on a flexible support.
void print_support(const LoadedMotion& lm, double g) {
  if (!lm.support) return;
  fmt::print("on a flexible support: {:.4g} Hz, damping {:.4g}; its peak acceleration {:.4f} g (ground {:.4f} g): the "
             "PGA values here are the support's\n",
             lm.support->freq_hz, lm.support->damping_ratio, lm.motion.pga_m_s2() / g, lm.ground_pga_m_s2 / g);
}

/// Library fields -> the options that set them.
template <class F>
auto naming(const std::map<std::string, std::string>& names, F f) {
  try {
    return f();
  } catch (const InputError& e) {
    const auto it = names.find(e.where().field);
    if (it == names.end() || !e.where().file.empty()) throw;
    throw parameter_error(it->second, e.problem());
  }
}

// ---- spectrum slide ----

struct SlideSpectrumOptions {
  bool quiet = false;
  MotionInput input;
  std::string mu;
  std::string mu_range;
  std::string ky_range;
  double slope_deg = 0.0;
  bool one_way = false;
  std::string vertical;  ///< with --h2: the vertical component
  std::string out;
  std::string plot;
  bool json = false;
};

/// spectrum slide FILE --h2 H2 [--vertical V]: the bidirectional spectrum (object_spectra.hpp, sliding_spectrum_2d)
/// over `mu` or, with `ky_ratios`, over k_y / RotD50 PGA. The set is read as `slide --h2` reads it, so that each
/// point is that command's run.
void run_slide_spectrum_2d(const SlideSpectrumOptions& o, std::vector<double> mu, const std::vector<double>& ky_ratios) {
  const double g = o.input.motion.g_m_s2;
  for (const auto& [given, option] : {std::pair{o.slope_deg != 0.0, "--slope-deg"}, std::pair{o.one_way, "--one-way"},
                                      std::pair{!o.input.support_freq.empty(), "--support-freq"},
                                      std::pair{o.input.bearing_deg.has_value(), "--bearing-deg"},
                                      std::pair{!o.plot.empty(), "--plot"}}) {
    if (given) {
      throw parameter_error(option, "not with --h2: the bidirectional spectrum is of a two-way block on level ground "
                                    "(friction is isotropic: no bearing), without a support, and has no figure yet");
    }
  }
  const RunMotion run = load_run_motion(o.input.motion, o.input.pulse, o.vertical);
  const MotionSet set = load_motion_set(run, o.input.motion, o.input.h2, o.input.azimuths);
  if (!ky_ratios.empty()) {
    const double rotd50 = rotd_measures(set, {}).pga_m_s2.rotd50;
    for (double ratio : ky_ratios) {
      mu.push_back(naming({{"ky_over_pga", "--ky-ratio-range"}}, [&] { return mu_for_yield_ratio(ratio, rotd50, 0.0, g); }));
    }
  }
  const SlidingSpectrum2d sp = naming({{"mu", o.mu.empty() ? "--mu-range" : "--mu"}, {"g", "--g"}},
                                      [&] { return sliding_spectrum_2d(set, mu, g); });
  for (const auto& p : sp.points) {
    require_finite({{"residual displacement", p.bidirectional.residual_displacement_m},
                    {"max |displacement|", p.bidirectional.max_abs_displacement_m},
                    {"path length", p.bidirectional.path_length_m}});
  }
  const std::string& h1 = run.input.motion;
  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    std::ostream& out = file.stream();
    out << "mu,yield_accel_g,ky_over_rotd50_pga,max_abs_displacement_m,residual_displacement_m,residual_azimuth_deg,"
           "path_length_m,max_abs_velocity_m_s,slip_episodes,total_slip_duration_s,h1_max_abs_displacement_m,"
           "h1_residual_displacement_m,h2_max_abs_displacement_m,h2_residual_displacement_m\n";
    for (const auto& p : sp.points) {
      const Sliding2dSummary& b = p.bidirectional;
      out << fmt::format("{},{},{},{},{},{},{},{},{},{},{},{},{},{}\n", p.mu, p.yield_accel_g, p.yield_over_rotd50_pga,
                         b.max_abs_displacement_m, b.residual_displacement_m,
                         b.residual_azimuth_deg ? fmt::format("{}", *b.residual_azimuth_deg) : std::string(),
                         b.path_length_m, b.max_abs_velocity_m_s, b.slip_episodes, b.total_slip_duration_s,
                         p.first_alone.max_abs_displacement_m, p.first_alone.residual_displacement_m,
                         p.second_alone.max_abs_displacement_m, p.second_alone.residual_displacement_m);
    }
    file.commit();
  }
  if (o.json) {
    fmt::print("{}\n", io::sliding_spectrum_2d_json(sp, h1, o.input.h2).dump(2));
    return;
  }
  fmt::print("bidirectional sliding spectrum: {} at {:g} deg and {} at {:g} deg{} (RotD50 PGA {:.4f} g; components "
             "{:.4f} g, {:.4f} g), two-way, level ground, g = {} m/s2\n", h1, sp.azimuths.first_deg, o.input.h2,
             sp.azimuths.second_deg, sp.with_vertical ? " with the vertical" : "", sp.rotd50_pga_m_s2 / g,
             sp.first_pga_m_s2 / g, sp.second_pga_m_s2 / g, g);
  fmt::print("{:>10} {:>10} {:>14} {:>14} {:>9} {:>8} {:>14} {:>14}\n", "mu", "ky/RotD50", "max |u| (m)",
             "residual (m)", "toward", "slips", "H1 alone (m)", "H2 alone (m)");
  for (const auto& p : sp.points) {
    const Sliding2dSummary& b = p.bidirectional;
    fmt::print("{:>10.5g} {:>10.5g} {:>14.6g} {:>14.6g} {:>9} {:>8} {:>14.6g} {:>14.6g}\n", p.mu,
               p.yield_over_rotd50_pga, b.max_abs_displacement_m, b.residual_displacement_m,
               b.residual_azimuth_deg ? fmt::format("{:.1f}", *b.residual_azimuth_deg) : std::string("-"),
               b.slip_episodes, p.first_alone.max_abs_displacement_m, p.second_alone.max_abs_displacement_m);
  }
  fmt::print("(toward: the residual's azimuth, deg clockwise from north; H1/H2 alone: max |d| of each component run "
             "alone by the 1-D solver)\n");
  if (!o.out.empty()) fmt::print("table written to {}\n", o.out);
}

void run_slide_spectrum(const SlideSpectrumOptions& o) {
  check_plot_path(o.plot);
  const int given = int(!o.mu.empty()) + int(!o.mu_range.empty()) + int(!o.ky_range.empty());
  if (given != 1) throw parameter_error("--mu", "give exactly one of --mu LIST, --mu-range LO:HI:N, --ky-ratio-range LO:HI:N");
  check_output_path(o.out);
  const double g = o.input.motion.g_m_s2;
  check_g(g);
  const double slope = deg_to_rad(o.slope_deg);
  // Every option is checked before the motion is read: the grids first.
  std::vector<double> mu;
  if (!o.mu.empty()) mu = parse_list(o.mu, "--mu", parse_number);
  if (!o.mu_range.empty()) {
    const Range r = parse_range(o.mu_range, "--mu-range", parse_number);
    mu = linear_grid(r.lo, r.hi, r.n, "--mu-range");
  }
  std::vector<double> ky_ratios;
  if (!o.ky_range.empty()) {
    const Range r = parse_range(o.ky_range, "--ky-ratio-range", parse_number);
    ky_ratios = linear_grid(r.lo, r.hi, r.n, "--ky-ratio-range");
  }
  const SlidingMode mode = o.one_way ? SlidingMode::one_way : SlidingMode::two_way;
  for (double m : mu) {  // each block is valid (and the slope with it) before the motion is read
    (void)naming({{"mu", o.mu.empty() ? "--mu-range" : "--mu"}, {"mu_kinetic", "--mu"}, {"slope", "--slope-deg"},
                  {"g", "--g"}},
                 [&] { return SlidingBlock::make(m, std::nullopt, slope, mode, g); });
  }
  if (!o.input.h2.empty()) {
    run_slide_spectrum_2d(o, std::move(mu), ky_ratios);
    return;
  }
  if (!o.vertical.empty()) {
    throw parameter_error("--vertical", "needs --h2 (the one-component spectrum has no vertical input: "
                                        "topple slide FILE --vertical V runs one block with it)");
  }
  if (o.input.bearing_deg) {
    throw parameter_error("--bearing-deg", "a sliding block has no bearing (friction is isotropic)");
  }
  const LoadedMotion lm = load(o.input);
  if (!ky_ratios.empty()) {
    for (double ratio : ky_ratios) {
      mu.push_back(naming({{"ky_over_pga", "--ky-ratio-range"}},
                          [&] { return mu_for_yield_ratio(ratio, lm.motion.pga_m_s2(), slope, g); }));
    }
  }
  const std::string_view mode_name = sliding_mode_name(mode);
  const SlidingSpectrum sp = naming({{"mu", "--mu"}, {"slope", "--slope-deg"}, {"g", "--g"}},
                                    [&] { return sliding_spectrum(lm.motion, mu, slope, mode, g); });

  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    std::ostream& out = file.stream();
    out << "mu,yield_accel_g,ky_over_pga,max_abs_displacement_m,residual_displacement_m,slip_episodes,"
           "total_slip_duration_s\n";
    for (const auto& p : sp.points) {
      out << fmt::format("{},{},{},{},{},{},{}\n", p.mu, p.yield_accel_g, p.yield_over_pga, p.max_abs_displacement_m,
                         p.residual_displacement_m, p.slip_episodes, p.total_slip_duration_s);
    }
    file.commit();
  }
  if (!o.plot.empty()) {
    plot::render(plot::sliding_spectrum_figure(sp, !o.ky_range.empty(),
                                               fmt::format("Sliding displacement spectrum, {}, slope {:g}°: {}",
                                                           mode_name, o.slope_deg, lm.title)),
                 o.plot);
  }
  if (o.json) {
    nlohmann::ordered_json j;
    j["motion"] = lm.name;
    j["pga_g"] = sp.pga_m_s2 / g;
    j["npts"] = lm.motion.size();
    j["dt_s"] = lm.motion.dt_s();
    j["g_m_s2"] = g;
    j["mode"] = mode_name;
    j["slope_deg"] = o.slope_deg;
    if (lm.support) j["support"] = support_json(lm, g);
    auto& pts = j["points"] = nlohmann::ordered_json::array();
    for (const auto& p : sp.points) {
      pts.push_back({{"mu", p.mu},
                     {"yield_accel_g", p.yield_accel_g},
                     {"ky_over_pga", p.yield_over_pga},
                     {"max_abs_displacement_m", p.max_abs_displacement_m},
                     {"residual_displacement_m", p.residual_displacement_m},
                     {"slip_episodes", p.slip_episodes}});
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("sliding displacement spectrum: {} (PGA {:.4f} g), {}, slope {} deg, g = {} m/s2\n", lm.name,
             sp.pga_m_s2 / g, mode_name, o.slope_deg, g);
  print_support(lm, g);
  fmt::print("{:>10} {:>10} {:>14} {:>14} {:>8}\n", "mu", "ky/PGA", "max |d| (m)", "residual (m)", "slips");
  for (const auto& p : sp.points) {
    fmt::print("{:>10.5g} {:>10.5g} {:>14.6g} {:>14.6g} {:>8}\n", p.mu, p.yield_over_pga, p.max_abs_displacement_m,
               p.residual_displacement_m, p.slip_episodes);
  }
  if (!o.out.empty()) fmt::print("table written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

// ---- spectrum rock ----

struct RockSpectrumOptions {
  bool quiet = false;
  MotionInput input;
  std::string shape = "block";
  std::string alpha;
  std::optional<double> slenderness;
  std::string heights;
  std::string height_range;
  std::string pga;
  std::string pga_range;
  std::string e = "housner";
  int threads = 0;
  std::string out;
  std::string plot;
  bool json = false;
};

void run_rock_spectrum(const RockSpectrumOptions& o) {
  check_plot_path(o.plot);
  check_output_path(o.out);
  check_threads(o.threads);
  const double g = o.input.motion.g_m_s2;
  check_g(g);
  BodyFamily family;
  family.shape = parse_shape(o.shape, "--shape");
  if (family.shape == RockingBody::Shape::general) {
    throw parameter_error("--shape", fmt::format("unknown shape '{}' (known: block, cylinder)", o.shape));
  }
  if (o.alpha.empty() == !o.slenderness.has_value()) {
    throw parameter_error("--alpha", "give the slenderness as --alpha ANGLE (e.g. 0.2rad) or --slenderness b/h");
  }
  if (o.slenderness) {
    if (!(*o.slenderness > 0.0) || !std::isfinite(*o.slenderness)) {
      throw parameter_error("--slenderness", fmt::format("must be positive, got {}", *o.slenderness));
    }
    family.alpha_rad = std::atan(*o.slenderness);
  } else {
    family.alpha_rad = parse_angle_rad(o.alpha, "--alpha");
  }
  if (o.heights.empty() == o.height_range.empty()) {
    throw parameter_error("--heights", "give the sizes as --heights LIST or --height-range LO:HI:N (full heights)");
  }
  if (!o.heights.empty()) {
    family.heights_m = parse_list(o.heights, "--heights", [](const std::string& t, const std::string& opt) {
      return parse_length_m(t, opt);
    });
  } else {
    const Range r = parse_range(o.height_range, "--height-range", [](const std::string& t, const std::string& opt) {
      return parse_length_m(t, opt);
    });
    family.heights_m = log_grid(r.lo, r.hi, r.n, "--height-range");
  }
  if (o.pga.empty() == o.pga_range.empty()) {
    throw parameter_error("--pga", "give the amplitudes as --pga LIST or --pga-range LO:HI:N (e.g. 0.05g:1g:40)");
  }
  const ValueParser accel = [g](const std::string& t, const std::string& opt) {
    return parse_acceleration_m_s2(t, opt, g);
  };
  std::vector<double> pga;
  if (!o.pga.empty()) {
    pga = parse_list(o.pga, "--pga", accel);
  } else {
    const Range r = parse_range(o.pga_range, "--pga-range", accel);
    pga = linear_grid(r.lo, r.hi, r.n, "--pga-range");
  }
  // Each cell is one rocking run and one stored result: the product of the axes is capped too.
  constexpr std::size_t kMaxCells = 1'000'000;
  if (family.heights_m.size() * pga.size() > kMaxCells) {
    throw parameter_error(o.pga.empty() ? "--pga-range" : "--pga",
                          fmt::format("{} sizes x {} PGAs is more than {} runs", family.heights_m.size(), pga.size(),
                                      kMaxCells));
  }
  OverturningMapOptions mo;
  mo.rocking.g_m_s2 = g;
  mo.threads = o.threads;
  ProgressBar bar(progress_wanted(o.quiet));
  mo.progress = bar.callback();
  const RestitutionChoice e = parse_restitution(o.e, "--e");
  mo.rocking.restitution = e.mode;
  mo.rocking.e = e.e;
  if (!o.input.h2.empty() && family.shape == RockingBody::Shape::cylinder) {
    throw parameter_error("--h2", "a cylinder under two components is taken in its worst direction, which the map "
                                  "does not search: run blocks at a --bearing-deg, or `topple rock --h2` / a sweep "
                                  "with [[motions.set]] for cylinders");
  }
  const LoadedMotion lm = load(o.input);
  const std::string pga_option = o.pga.empty() ? "--pga-range" : "--pga";
  const std::string height_option = o.heights.empty() ? "--height-range" : "--heights";
  const OverturningMap map = naming(
      {{"alpha", o.slenderness ? "--slenderness" : "--alpha"}, {"height", height_option}, {"width", height_option},
       {"diameter", height_option}, {"pga", pga_option}, {"e", "--e"}, {"g", "--g"}},
      [&] { return overturning_map(lm.motion, family, pga, mo); });
  bar.finish();

  const std::size_t na = map.pga_m_s2.size();
  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    std::ostream& out = file.stream();
    out << fmt::format("height_m,{},R_m,p_rad_s,pga_g,overturned,max_rotation_over_alpha\n",
                       family.shape == RockingBody::Shape::cylinder ? "diameter_m" : "width_m");
    for (std::size_t s = 0; s < map.sizes.size(); ++s) {
      const auto& z = map.sizes[s];
      for (std::size_t k = 0; k < na; ++k) {
        out << fmt::format("{},{},{},{},{},{},{}\n", z.height_m, z.width_m, z.R_m, z.p_rad_s, map.pga_m_s2[k] / g,
                           map.at(s, k) ? "true" : "false", map.max_rotation_over_alpha[s * na + k]);
      }
    }
    file.commit();
  }
  if (!o.plot.empty()) {
    plot::render(plot::overturning_map_figure(map, fmt::format("Overturning map, {} α = {:.3g} rad, e = {}: {}", o.shape,
                                                               map.alpha_rad, o.e, lm.title)),
                 o.plot);
  }
  if (o.json) {
    nlohmann::ordered_json j;
    j["motion"] = lm.name;
    j["pga_g_as_read"] = lm.motion.pga_m_s2() / g;
    j["g_m_s2"] = g;
    j["shape"] = o.shape;
    j["alpha_rad"] = map.alpha_rad;
    if (lm.support) j["support"] = support_json(lm, g);
    j["uplift_pga_g"] = std::tan(map.alpha_rad);
    nlohmann::ordered_json grid = nlohmann::ordered_json::array();
    for (double a : map.pga_m_s2) grid.push_back(a / g);
    j["pga_g"] = grid;
    auto& sizes = j["sizes"] = nlohmann::ordered_json::array();
    for (const auto& z : map.sizes) {
      sizes.push_back({{"height_m", z.height_m},
                       {family.shape == RockingBody::Shape::cylinder ? "diameter_m" : "width_m", z.width_m},
                       {"R_m", z.R_m},
                       {"p_rad_s", z.p_rad_s},
                       {"first_overturn_pga_g", z.first_overturn_pga_m_s2
                                                    ? nlohmann::ordered_json(*z.first_overturn_pga_m_s2 / g)
                                                    : nlohmann::ordered_json(nullptr)},
                       {"standing_above_first", z.standing_above_first},
                       {"overturn_count", z.overturn_count}});
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("overturning map: {} ({} {} PGAs x {} sizes), {} alpha = {:.4g} rad, uplift at PGA > {:.4f} g\n", lm.name,
             na, "grid", map.sizes.size(), o.shape, map.alpha_rad, std::tan(map.alpha_rad));
  print_support(lm, g);
  fmt::print("{:>12} {:>10} {:>20} {:>22}\n", "height (m)", "p (rad/s)", "first overturn (g)", "standing above first");
  for (const auto& z : map.sizes) {
    fmt::print("{:>12.5g} {:>10.4g} {:>20} {:>22}\n", z.height_m, z.p_rad_s,
               z.first_overturn_pga_m_s2 ? fmt::format("{:.4f}", *z.first_overturn_pga_m_s2 / g) : std::string("none"),
               z.standing_above_first ? "yes" : "no");
  }
  if (!o.out.empty()) fmt::print("map written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

void add_motion_input(CLI::App& cmd, MotionInput& in) {
  cmd.add_option("file", in.motion.file, "Record file (format detected from content)");
  add_motion_options(cmd, in.motion);
  add_pulse_options(cmd, in.pulse);
  cmd.add_option("--support-freq", in.support_freq, "Objects on a shelf or floor: its natural frequency (e.g. 4Hz); "
                                                    "they see its absolute acceleration (decoupled)");
  cmd.add_option("--support-damping", in.support_damping, "Damping ratio of the support (5% or 0.05; default 5%)");
  cmd.add_option("--h2", in.h2, "Second horizontal component (record file). spectrum rock: the blocks rock under the "
                                "projection of the pair on --bearing-deg (planar model; PGA is the projection's); "
                                "spectrum slide: bidirectional sliding (PGA axis: the pair's RotD50)");
  cmd.add_option("--azimuths", in.azimuths, "With --h2: the components' azimuths A1,A2, degrees clockwise from north "
                                            "(default: the files' headers)");
  cmd.add_option("--bearing-deg", in.bearing_deg, "With --h2: the family's bearing (across the narrow side), degrees "
                                                  "clockwise from north");
}

}  // namespace

void add_spectrum_command(CLI::App& app) {
  CLI::App* spectrum = app.add_subcommand("spectrum", "Object spectra of one motion: sliding displacement vs friction, "
                                                      "overturning map over amplitude x size");
  spectrum->require_subcommand(1);

  auto s = std::make_shared<SlideSpectrumOptions>();
  CLI::App* slide = spectrum->add_subcommand("slide", "Max and residual sliding displacement vs mu (or k_y/PGA)");
  add_motion_input(*slide, s->input);
  slide->add_option("--mu", s->mu, "Friction coefficients, comma-separated (e.g. 0.05,0.1,0.2)");
  slide->add_option("--mu-range", s->mu_range, "Friction coefficients LO:HI:N, evenly spaced (e.g. 0.02:0.5:25)");
  slide->add_option("--ky-ratio-range", s->ky_range, "Yield acceleration over PGA, LO:HI:N, evenly spaced "
                                                     "(mu = tan(slope + atan(ratio PGA/g)))");
  slide->add_option("--slope-deg", s->slope_deg, "Inclination of the plane, degrees")->capture_default_str();
  slide->add_flag("--one-way", s->one_way, "Down-slope sliding only (SLAMMER rigid-block convention)");
  slide->add_option("--vertical", s->vertical, "With --h2: the vertical component (positive up), scaled with the "
                                               "horizontal ones");
  slide->add_option("--out", s->out, "Write the spectrum to this CSV file");
  slide->add_option("--plot", s->plot, "Draw the spectrum to this .svg or .png file (gnuplot)");
  slide->add_flag("--json", s->json, "Print the spectrum as one JSON object");
  add_quiet_flag(*slide, s->quiet);  // one pass over the motion per mu: quick, no bar
  slide->callback([s] { run_slide_spectrum(*s); });

  auto r = std::make_shared<RockSpectrumOptions>();
  CLI::App* rock = spectrum->add_subcommand("rock", "Overturning map over PGA x size for a family of fixed slenderness, "
                                                    "and each size's first-overturn PGA");
  add_motion_input(*rock, r->input);
  rock->add_option("--shape", r->shape, "block or cylinder")->capture_default_str();
  rock->add_option("--alpha", r->alpha, "Slenderness angle atan(b/h), with a unit (e.g. 0.2rad, 11deg)");
  rock->add_option("--slenderness", r->slenderness, "Slenderness b/h = width/height (= tan alpha)");
  rock->add_option("--heights", r->heights, "Full heights of the family, comma-separated with units (e.g. 20cm,1m)");
  rock->add_option("--height-range", r->height_range, "Full heights LO:HI:N, log spaced (e.g. 10cm:4m:50)");
  rock->add_option("--pga", r->pga, "PGAs the motion is scaled to, comma-separated with units (e.g. 0.2g,0.4g)");
  rock->add_option("--pga-range", r->pga_range, "PGAs LO:HI:N, evenly spaced (e.g. 0.05g:1g:50)");
  rock->add_option("--e", r->e, "Coefficient of restitution in [0, 1], or 'housner'")->capture_default_str();
  rock->add_option("--threads", r->threads, "Worker threads (0: every core)")->capture_default_str();
  rock->add_option("--out", r->out, "Write the map to this CSV file (one row per size and PGA)");
  rock->add_option("--plot", r->plot, "Draw the map with the first-overturn curve to this .svg or .png file");
  rock->add_flag("--json", r->json, "Print the first-overturn PGA of each size as one JSON object");
  add_quiet_flag(*rock, r->quiet);
  rock->callback([r] { run_rock_spectrum(*r); });
}

}  // namespace topple::cli
