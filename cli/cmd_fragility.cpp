// topple fragility: P(overturn) and P(slide > d) against an intensity measure over an ensemble of records or
// synthetic motions, with the lognormal maximum-likelihood fit and its band. Parsing and printing only.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "progress.hpp"
#include "common.hpp"
#include "grids.hpp"
#include "motion_set_options.hpp"
#include "pose_options.hpp"
#include "topple/core/error.hpp"
#include "topple/core/output_file.hpp"
#include "topple/fragility/fragility.hpp"
#include "topple/fragility/object_spectra.hpp"
#include "topple/io/body_file.hpp"
#include "topple/io/mesh.hpp"
#include "topple/output/fragility_output.hpp"
#include "topple/output/plot.hpp"
#include "topple/motion/synthesis.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

struct FragilityOptions {
  std::vector<std::string> files;
  MotionOptions motion;  // read options and --g (scaling options do not apply: every motion is scaled to the levels)
  std::optional<int> synth;
  std::string freq = "2Hz";
  std::string duration = "20s";
  std::string synth_dt = "0.01";
  std::string seed = "1";
  std::string im = "pga";
  std::string im_range;
  std::optional<double> mu;
  double slope_deg = 0.0;
  bool one_way = false;
  std::string threshold;
  std::string shape;
  std::string width;
  std::string height;
  std::string diameter;
  std::string b1;          // general (asymmetric) body: --shape general --b1 --b2 --h --inertia
  std::string b2;
  std::string h;
  std::string inertia;
  std::string body_file;   // --body: what `topple body --json` writes
  std::string mesh;        // --mesh FILE: a scanned body, at --azimuth (BodyOptions: every option of the mesh body)
  std::string mesh_unit = "m";
  BodyOptions mesh_options;
  PoseOptionsText mesh_pose;  // --pose, --up, --rotation, --axis-angle, --face, --contact-tolerance, --base-tolerance
  std::string model = "rocking";  // or "coupled": the slide-rock model (slide_rock.hpp); or "3d" (rigid3d.hpp, pairs)
  std::string depth;              // --model 3d, a block: its depth (along its +y axis, bearing + 90)
  std::optional<double> rock_mu;
  std::optional<double> rock_mu_k;
  bool as_recorded = false;
  std::string e = "housner";
  double band = 0.95;
  int threads = 0;
  bool quiet = false;
  std::string out;
  std::string plot;
  bool json = false;
  int components = 1;                 // --synth: 2 = horizontal pairs, 3 = pairs with a vertical
  std::vector<std::string> h2;        // record pairs: each file's second horizontal component, in order
  std::vector<std::string> vertical;  // and (optional) vertical
  std::string azimuths;               // "A1,A2" for every pair (default: the files' headers)
  std::optional<double> bearing_deg;  // rocking body's bearing under pairs (none: uniformly random per motion)
  std::string bearing_seed = "1";
};

/// The most synthetic motions (each is held in memory; 1e4 motions of 20 s at 0.01 s: 320 MB) and IM levels.
constexpr int kMaxSynthMotions = 10'000;
constexpr std::size_t kMaxLevels = 1'000;

/// The analysis a fragility figure shows: the ensemble, and each failure with its parameters (the sliding threshold d,
/// mu, slope, one-way; the body and e).
std::string fragility_title(const FragilityOptions& o, std::size_t motions) {
  std::string t = o.synth ? fmt::format("Fragility over {} synthetic motions (f_p {}, seeds from {})", motions, o.freq,
                                        o.seed)
                          : fmt::format("Fragility over {} records", motions);
  if (o.files.size() == 1) t += " (" + plot::file_label(o.files.front()) + ")";
  if (o.mu) {
    t += fmt::format(", slide > d = {} at μ = {:g}", o.threshold, *o.mu);
    if (o.slope_deg != 0.0) t += fmt::format(", slope {:g}°", o.slope_deg);
    t += o.one_way ? ", one-way" : ", two-way";
  }
  if (!o.body_file.empty()) {
    t += ", overturn of the body in " + plot::file_label(o.body_file);
  } else if (!o.mesh.empty()) {
    t += fmt::format(", overturn of {} at azimuth {:g}°", plot::file_label(o.mesh), o.mesh_options.azimuth_deg);
  } else if (o.shape == "general") {
    t += fmt::format(", overturn of a body b1 {}, b2 {}, h {}", o.b1, o.b2, o.h);
  } else if (!o.shape.empty()) {
    t += o.shape == "cylinder" ? fmt::format(", overturn of a cylinder {} x {}", o.diameter, o.height)
                               : fmt::format(", overturn of a {} {} x {}", o.shape, o.width, o.height);
  }
  if (!o.shape.empty() || !o.body_file.empty() || !o.mesh.empty()) {
    t += ", e = " + o.e;
    if (o.model == "3d") t += fmt::format(", in 3-D{}", o.depth.empty() ? "" : " with depth " + o.depth);
    if (o.model == "coupled" || (o.model == "3d" && o.rock_mu)) {
      t += fmt::format(", {} (μ = {:g}{})", o.model == "3d" ? "with friction" : "coupled slide-rock", o.rock_mu.value_or(0.0),
                       o.rock_mu_k ? fmt::format(", μ_k = {:g}", *o.rock_mu_k) : std::string());
    }
  }
  return t;
}

/// The ensemble's options: pairs (synthetic: --synth N --components 2|3; records: FILES --h2 FILES2 [--vertical
/// FILES3]) or single components, and the options that apply to pairs only. True for pairs.
bool check_ensemble_options(const FragilityOptions& o) {
  if (o.components < 1 || o.components > 3) {
    throw parameter_error("--components", fmt::format("1, 2 (horizontal pairs) or 3 (pairs and a vertical), got {}",
                                                      o.components));
  }
  if (o.components != 1 && !o.synth) throw parameter_error("--components", "applies to --synth (records: --h2)");
  if (!o.h2.empty() && o.synth) throw parameter_error("--h2", "record pairs are files; with --synth use --components 2");
  if (!o.h2.empty() && o.h2.size() != o.files.size()) {
    throw parameter_error("--h2", fmt::format("one second component per record file: {} files, {} given", o.files.size(),
                                              o.h2.size()));
  }
  if (!o.vertical.empty() && o.vertical.size() != o.h2.size()) {
    throw parameter_error("--vertical", o.h2.empty() ? std::string("needs --h2 (pairs)")
                                                     : fmt::format("one vertical per pair: {} pairs, {} given",
                                                                   o.h2.size(), o.vertical.size()));
  }
  const bool pairs = o.components > 1 || !o.h2.empty();
  if (!pairs) {
    for (const auto& [option, given] : {std::pair{"--azimuths", !o.azimuths.empty()},
                                        std::pair{"--bearing-deg", o.bearing_deg.has_value()},
                                        std::pair{"--bearing-seed", o.bearing_seed != "1"}}) {
      if (given) throw parameter_error(option, "applies to pairs: --h2 with record files, or --synth N --components 2");
    }
  }
  if (!o.azimuths.empty() && o.synth) {
    throw parameter_error("--azimuths", "synthetic pairs are at 90,0 (east, north); --azimuths names record pairs");
  }
  if (!o.motion.scale_pga.empty() || o.motion.scale || o.motion.invert) {
    throw parameter_error("--scale-pga", "fragility scales every motion to each IM level itself: --scale-pga, --scale "
                                         "and --invert do not apply");
  }
  return pairs;
}

/// The rocking body: --body FILE (what `topple body --json` writes), --mesh FILE at --azimuth (io::read_mesh_body
/// with the whole BodyOptions), or --shape block / cylinder / general (--b1 --b2 --h --inertia, asymmetric).
RockingBody make_fragility_body(const FragilityOptions& o, double g) {
  if (!o.body_file.empty()) return io::read_body_file(o.body_file).rocking_body();
  if (!o.mesh.empty()) {
    BodyOptions b = o.mesh_options;
    b.g_m_s2 = g;
    const double unit_m = io::mesh_unit_m(o.mesh_unit, "--mesh-unit");
    const MeshBody body = with_field_names({{"--unit", "--mesh-unit"}}, [&] { return io::read_mesh_body(o.mesh, unit_m, b); });
    return rocking_body(body);
  }
  const RockingBody::Shape shape = parse_shape(o.shape, "--shape");
  BodyDimensions d;
  const auto length = [](const std::string& text, const char* option) -> std::optional<double> {
    if (text.empty()) return std::nullopt;
    return parse_length_m(text, option);
  };
  if (shape == RockingBody::Shape::general) {
    for (const auto& [option, given] : {std::pair{"--width", !o.width.empty()}, std::pair{"--height", !o.height.empty()},
                                        std::pair{"--diameter", !o.diameter.empty()}}) {
      if (given) throw parameter_error(option, "a general body is given by --b1, --b2, --h and --inertia");
    }
    d.b1_m = length(o.b1, "--b1");
    d.b2_m = length(o.b2, "--b2");
    d.h_m = length(o.h, "--h");
    if (!o.inertia.empty()) d.inertia_m2 = parse_area_m2(o.inertia, "--inertia");
    for (const auto& [option, given] : {std::pair{"--b1", d.b1_m.has_value()}, std::pair{"--b2", d.b2_m.has_value()},
                                        std::pair{"--h", d.h_m.has_value()},
                                        std::pair{"--inertia", d.inertia_m2.has_value()}}) {
      if (!given) throw parameter_error(option, "a general body needs --b1, --b2, --h and --inertia");
    }
  } else {
    for (const auto& [option, given] : {std::pair{"--b1", !o.b1.empty()}, std::pair{"--b2", !o.b2.empty()},
                                        std::pair{"--h", !o.h.empty()}, std::pair{"--inertia", !o.inertia.empty()}}) {
      if (given) throw parameter_error(option, "applies to --shape general");
    }
    if (o.height.empty()) throw parameter_error("--height", "the rocking body needs --height");
    d.height_m = parse_length_m(o.height, "--height");
    d.width_m = length(o.width, "--width");
    d.diameter_m = length(o.diameter, "--diameter");
  }
  try {
    return make_rocking_body(shape, d);
  } catch (const InputError& err) {
    const std::string& field = err.where().field;
    for (const char* known : {"width", "height", "diameter", "b1", "b2", "h", "inertia"}) {
      if (field == known) throw parameter_error("--" + field, err.problem());
    }
    throw;
  }
}

/// --model 3d: the body in three dimensions (rigid3d.hpp): a block with --depth (width along +x, depth along +y), or
/// the mesh as posed turned so that its direction --azimuth (clockwise from its +y) is the body's +x axis, the one
/// the bearing places (as the survey's mesh objects, docs/survey.md). A general body and --body are refused (no base
/// in three dimensions); a cylinder is add_failures' (the rim engine, rigid3d_disc.hpp).
RigidBody3D make_fragility_body_3d(const FragilityOptions& o, double g) {
  if (!o.body_file.empty()) {
    throw parameter_error("--body", "--model 3d needs the body in three dimensions: a body file holds its section in "
                                    "one plane; give the mesh (--mesh FILE) or a block (--shape block --depth)");
  }
  if (!o.mesh.empty()) {
    if (!o.depth.empty()) throw parameter_error("--depth", "is a block's: a mesh has its own shape");
    BodyOptions b = o.mesh_options;
    b.g_m_s2 = g;
    const double unit_m = io::mesh_unit_m(o.mesh_unit, "--mesh-unit");
    const MeshBody body =
        with_field_names({{"--unit", "--mesh-unit"}}, [&] { return io::read_mesh_body(o.mesh, unit_m, b); });
    return RigidBody3D::from_mesh(body).rotated_about_vertical(deg_to_rad(o.mesh_options.azimuth_deg - 90.0));
  }
  if (o.shape != "block") {
    throw parameter_error("--shape", "--model 3d: a general body is a section in one vertical plane, without a base "
                                     "in three dimensions; give a block (--shape block --width --depth --height) or a "
                                     "mesh (--mesh FILE)");
  }
  if (o.depth.empty()) {
    throw parameter_error("--depth", "--model 3d needs the block's depth, with a unit (its extent along bearing + 90)");
  }
  const double width = parse_length_m(o.width, "--width");
  const double depth = parse_length_m(o.depth, "--depth");
  const double height = parse_length_m(o.height, "--height");
  return with_field_names({{"width", "--width"}, {"depth", "--depth"}, {"height", "--height"}},
                          [&] { return RigidBody3D::box(width, depth, height); });
}

/// The failure modes asked for: a sliding block past its threshold and/or an overturning rocking body.
void add_failures(const FragilityOptions& o, double g, FragilitySpec& spec) {
  if (o.mu) {
    if (o.threshold.empty()) throw parameter_error("--threshold", "a sliding block needs its displacement threshold, e.g. 5cm");
    SlidingFailure f;
    try {
      f.block = SlidingBlock::make(*o.mu, std::nullopt, deg_to_rad(o.slope_deg),
                                   o.one_way ? SlidingMode::one_way : SlidingMode::two_way, g);
    } catch (const InputError& e) {
      throw parameter_error(e.where().field == "slope" ? "--slope-deg" : "--mu", e.problem());
    }
    f.threshold_m = parse_length_m(o.threshold, "--threshold");
    spec.sliding = f;
  } else if (!o.threshold.empty()) {
    throw parameter_error("--mu", "--threshold applies to a sliding block: give its friction coefficient --mu");
  }
  if (!o.shape.empty() || !o.body_file.empty() || !o.mesh.empty()) {
    OverturnFailure f;
    f.options.g_m_s2 = g;
    const RestitutionChoice e = parse_restitution(o.e, "--e");
    f.options.restitution = e.mode;
    f.options.e = e.e;
    f.body = make_fragility_body(o, g);
    if (o.model == "coupled") {
      if (!o.rock_mu) {
        throw parameter_error("--rock-mu", "the coupled model needs the rocking body's friction coefficient");
      }
      f.coupled = with_field_names({{"mu", "--rock-mu"}, {"mu_k", "--rock-mu-k"}},
                                   [&] { return SlideRockBody::from_rocking(f.body, *o.rock_mu, o.rock_mu_k); });
    } else if (o.model == "3d") {
      if (o.rock_mu_k && !o.rock_mu) throw parameter_error("--rock-mu-k", "needs --rock-mu");
      f.mu_3d = o.rock_mu;  // absent: no contact slides (the no-slip engine)
      f.mu_k_3d = o.rock_mu_k;
      if (o.shape == "cylinder" && o.mesh.empty() && o.body_file.empty()) {
        // the rim engine's solid cylinder of the planar cylinder's a = d / 2, h = H / 2 (rocking_body.hpp)
        if (!o.depth.empty()) {
          throw parameter_error("--depth", "is a block's: a cylinder is given by --diameter and --height");
        }
        f.cylinder_3d = CylinderBody3D::solid(2.0 * f.body.a_m, 2.0 * f.body.h_m);
      } else {
        f.body_3d = make_fragility_body_3d(o, g);
      }
    } else if (o.model != "rocking") {
      throw parameter_error("--model", fmt::format("'rocking', 'coupled' or '3d', got '{}'", o.model));
    } else if (o.rock_mu || o.rock_mu_k) {
      throw parameter_error(o.rock_mu ? "--rock-mu" : "--rock-mu-k", "needs --model coupled (the rocking model does "
                                                                     "not slide)");
    }
    spec.overturning = f;
  } else if (o.model != "rocking" || o.rock_mu || o.rock_mu_k) {
    throw parameter_error(o.model != "rocking" ? "--model" : "--rock-mu",
                          "applies to a rocking body (--shape, --body or --mesh)");
  }
  if (!o.depth.empty() && o.model != "3d") {
    throw parameter_error("--depth", "a block's depth applies to --model 3d (the planar models rock in one plane)");
  }
  if (!spec.sliding && !spec.overturning) {
    throw parameter_error("--mu", "give a sliding block (--mu, --threshold) and/or a rocking body (--shape ..., "
                                  "--body FILE or --mesh FILE)");
  }

}

/// The ensemble (synthetic motions or pairs, record files or pairs of files) into spec; returns the motions' names.
std::vector<std::string> add_motions(const FragilityOptions& o, bool pairs, double g, FragilitySpec& spec) {
  std::vector<std::string> names;
  if (o.synth.has_value() == !o.files.empty()) throw parameter_error("FILES", "give record files or --synth N");
  if (o.synth) {
    if (*o.synth < 1 || *o.synth > kMaxSynthMotions) {
      throw parameter_error("--synth", fmt::format("needs 1 to {} motions, got {}", kMaxSynthMotions, *o.synth));
    }
    const std::uint64_t first_seed = parse_seed(o.seed, "--seed");
    const auto count = static_cast<std::uint64_t>(*o.synth);
    if (first_seed > std::numeric_limits<std::uint64_t>::max() - (count - 1)) {
      throw parameter_error("--seed", fmt::format("seeds {} + 0 .. {} pass 2^64 - 1", first_seed, count - 1));
    }
    SynthesisSpec s;
    s.pga_m_s2 = 0.1 * g;  // rescaled to every level anyway
    s.predominant_frequency_hz = parse_frequency_hz(o.freq, "--freq");
    s.duration_s = parse_seconds(o.duration, "--duration");
    s.dt_s = parse_seconds(o.synth_dt, "--synth-dt");
    const auto synth_option = [](const InputError& e) {
      const std::string& field = e.where().field;
      return field == "freq" || field == "predominant_frequency_hz" ? "--freq"
             : field == "duration" || field == "duration_s"         ? "--duration"
             : field == "dt" || field == "dt_s"                     ? "--synth-dt"
                                                                    : "--synth";
    };
    try {
      validate(s);  // before the first motion is made
    } catch (const InputError& e) {
      throw parameter_error(synth_option(e), e.problem());
    }
    for (std::uint64_t i = 0; i < count; ++i) {
      s.seed = first_seed + i;
      try {
        if (pairs) {
          // synthesis.hpp's pair: pga_m_s2 is its RotD50 PGA; independent components at 90,0; the vertical (V/H 2/3).
          SynthesisSetSpec ss;
          ss.horizontal = s;
          ss.vertical = o.components == 3;
          const SynthesizedSet syn = synthesize_set(ss);
          spec.motion_sets.push_back(std::make_shared<const MotionSet>(
              MotionSet::make(syn.first, &syn.second, ss.azimuths, syn.vertical ? &*syn.vertical : nullptr)));
        } else {
          spec.motions.push_back(std::make_shared<const GroundMotion>(synthesize(s)));
        }
      } catch (const InputError& e) {
        throw parameter_error(synth_option(e), e.problem());
      }
      names.push_back(fmt::format("synthetic {}seed {}", pairs ? "pair " : "", s.seed));
    }
  } else if (pairs) {
    // Each pair read as `slide FILE --h2 H2 [--vertical V]` reads it (motion_set_options.hpp).
    for (std::size_t k = 0; k < o.files.size(); ++k) {
      MotionOptions mo = o.motion;
      mo.file = o.files[k];
      const std::string v = o.vertical.empty() ? std::string() : o.vertical[k];
      const RunMotion run = load_run_motion(mo, PulseOptions{}, v);
      spec.motion_sets.push_back(std::make_shared<const MotionSet>(load_motion_set(run, mo, o.h2[k], o.azimuths)));
      names.push_back(o.files[k] + "+" + o.h2[k] + (v.empty() ? "" : "+" + v));
    }
  } else {
    for (const std::string& f : o.files) {
      spec.motions.push_back(std::make_shared<const GroundMotion>(io::read_motion(f, read_options(o.motion))));
      names.push_back(f);
    }
  }
  return names;
}

/// The fits and counts as text.
void print_fragility(const FragilityOptions& o, const FragilityResult& res, std::size_t motions, std::size_t levels,
                     const std::string& bearing_rule) {
  const double k = intensity_measure_display_factor(res.im, o.motion.g_m_s2);
  const std::string unit(intensity_measure_unit(res.im));
  fmt::print("fragility over {} motions x {} {} levels ({} runs), g = {} m/s2\n", motions,
             levels, res.rotd50 ? "RotD50 PGA" : o.im, res.runs, o.motion.g_m_s2);
  if (res.rotd50) {
    fmt::print("pairs: IM = each pair's RotD50 PGA (Boore 2010), both components scaled together; sliding in two "
               "dimensions; rocking bodies at a bearing of {}\n", bearing_rule);
  }
  for (const auto& c : res.curves) {
    fmt::print("{}:", c.name == "overturn" ? "P(overturn)" : "P(slide > threshold)");
    if (c.fit) {
      fmt::print(" median theta = {:.4g} {} (ln theta +- {:.3g}), beta = {:.3f} +- {:.3f}{}\n", c.fit->theta * k, unit,
                 c.fit->se_ln_theta, c.fit->beta, c.fit->se_beta,
                 c.fit->beta_at_bound ? " (separated data: beta at its lower bound)" : "");
    } else {
      fmt::print(" no fit: {}\n", c.fit_note);
    }
    for (std::size_t i = 0; i < c.data.im.size(); ++i) {
      fmt::print("  {} = {:<10.4g} {:>4}/{:<4}\n", res.rotd50 ? "RotD50 PGA" : o.im, c.data.im[i] * k,
                 c.data.failures[i], c.data.trials[i]);
    }
  }
}

/// --as-recorded: every record run once as recorded; per record its PGA, PGV, PGV/PGA and outcome, and the fragility
/// surface in PGA and PGV/PGA (fragility.hpp, "As recorded").
void run_as_recorded(const FragilityOptions& o, bool pairs) {
  const double g = o.motion.g_m_s2;
  if (pairs) throw parameter_error("--as-recorded", "runs single components (pairs are scaled by their RotD50 PGA)");
  if (o.synth) throw parameter_error("--synth", "--as-recorded runs record files as they are (synthetic motions have "
                                                "no PGA of their own here: use the scaled fragility)");
  if (!o.im_range.empty()) throw parameter_error("--im-range", "--as-recorded does not scale the records to levels");
  if (o.im != "pga") throw parameter_error("--im", "--as-recorded fits a surface in PGA and PGV/PGA");
  FragilitySpec spec;
  spec.threads = o.threads;
  add_failures(o, g, spec);
  const std::vector<std::string> names = add_motions(o, false, g, spec);
  ProgressBar bar(progress_wanted(o.quiet));
  spec.progress = bar.callback();
  const AsRecordedResult res = with_field_names({{"mode", "--one-way"}, {"slope", "--slope-deg"}, {"model", "--model"}},
                                                [&] { return as_recorded_analysis(spec); });
  bar.finish();
  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    io::write_as_recorded_csv(file.stream(), res, names, g);
    file.commit();
  }
  if (!o.plot.empty()) {
    // The overturning surface when there is a rocking body (the last curve), else the sliding one.
    const std::size_t curve = res.curves.size() - 1;
    plot::render(io::fragility_surface_figure(res, curve, g, fragility_title(o, names.size()) + ", as recorded"),
                 o.plot);
  }
  for (const auto& c : res.curves) {
    if (c.fit) require_finite({{"theta_ref", c.fit->ln_theta_ref}, {"gamma", c.fit->gamma}, {"beta", c.fit->beta}});
  }
  if (o.json) {
    fmt::print("{}\n", io::as_recorded_json(res, names, g).dump(2));
    return;
  }
  fmt::print("fragility over {} records as recorded (no rescaling), g = {} m/s2\n", names.size(), g);
  fmt::print("surface: {}\n", io::kFragilitySurfaceForm);
  for (const auto& c : res.curves) {
    const auto failures = std::count(c.failed.begin(), c.failed.end(), true);
    fmt::print("{}: {} of {} records\n", c.name == "overturn" ? "P(overturn)" : "P(slide > threshold)", failures,
               c.failed.size());
    if (c.fit) {
      const FragilitySurfaceFit& f = *c.fit;
      fmt::print("  median PGA at PGV/PGA = {:.4g} s: {:.4g} g (ln theta_ref +- {:.3g}); gamma = {:.3f} +- {:.3f}; "
                 "beta = {:.3f} +- {:.3f}\n",
                 f.v_ref_s, std::exp(f.ln_theta_ref) / g, f.se_ln_theta_ref, f.gamma, f.se_gamma, f.beta, f.se_beta);
    } else {
      fmt::print("  no surface: {}\n", c.fit_note);
    }
  }
  fmt::print("{:<40} {:>9} {:>9} {:>9}", "record", "PGA (g)", "PGV (m/s)", "PGV/PGA");
  for (const auto& c : res.curves) fmt::print(" {:>9}", c.name);
  fmt::print("\n");
  for (std::size_t i = 0; i < names.size(); ++i) {
    fmt::print("{:<40} {:>9.4f} {:>9.4f} {:>9.4f}", plot::file_label(names[i]), res.pga_m_s2[i] / g, res.pgv_m_s[i],
               res.pgv_m_s[i] / res.pga_m_s2[i]);
    for (const auto& c : res.curves) fmt::print(" {:>9}", c.failed[i] ? "yes" : "no");
    fmt::print("\n");
  }
  if (!o.out.empty()) fmt::print("table written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

void run_fragility(const FragilityOptions& o) {
  check_plot_path(o.plot);
  check_output_path(o.out);
  check_threads(o.threads);
  const double g = o.motion.g_m_s2;
  check_g(g);
  const bool pairs = check_ensemble_options(o);
  if (!(o.band > 0.0 && o.band < 1.0)) throw parameter_error("--band", fmt::format("must be in (0, 1), got {}", o.band));
  if (o.as_recorded) {
    run_as_recorded(o, pairs);
    return;
  }
  FragilitySpec spec;
  spec.im = parse_intensity_measure(o.im, "--im");
  if (pairs && spec.im != IntensityMeasure::pga) {
    throw parameter_error("--im", fmt::format("an ensemble of pairs is scaled by its RotD50 PGA: --im must be pga, got "
                                              "'{}'", o.im));
  }
  spec.bearing_deg = o.bearing_deg;
  spec.bearing_seed = parse_seed(o.bearing_seed, "--bearing-seed");
  spec.threads = o.threads;
  if (o.im_range.empty()) throw parameter_error("--im-range", "the IM levels are required, e.g. --im-range 0.05:2:12 "
                                                              "(in g for PGA, SI for the others)");
  const Range r = parse_range(o.im_range, "--im-range", parse_number, kMaxLevels);
  const double to_si = 1.0 / intensity_measure_display_factor(spec.im, g);
  for (double x : log_grid(r.lo, r.hi, r.n, "--im-range")) spec.levels_si.push_back(x * to_si);

  add_failures(o, g, spec);

  const std::vector<std::string> names = add_motions(o, pairs, g, spec);
  ProgressBar bar(progress_wanted(o.quiet));
  spec.progress = bar.callback();
  // The library names its fields; the user typed options.
  const FragilityResult res =
      with_field_names({{"mode", "--one-way"}, {"slope", "--slope-deg"}, {"bearing", "--bearing-deg"},
                        {"levels", "--im-range"}, {"model", "--model"}},
                       [&] { return fragility_analysis(spec); });
  bar.finish();
  const std::string bearing_rule =
      o.bearing_deg ? fmt::format("{:g} deg for every motion", *o.bearing_deg)
                    : fmt::format("uniformly random on [0, 360) deg per motion (PortableRandom seed {})",
                                  spec.bearing_seed);

  if (!o.out.empty()) {
    io::OutputFile file(o.out);
    io::write_fragility_csv(file.stream(), res, g, o.band);
    file.commit();
  }
  if (!o.plot.empty()) {
    plot::render(plot::fragility_figure(res, g, o.band,
                                        fragility_title(o, names.size()) + (res.rotd50 ? " (RotD50 PGA of pairs)" : "")),
                 o.plot);
  }
  if (o.json) {
    const nlohmann::ordered_json j = io::fragility_json(res, {o.im, g, names, o.band, bearing_rule});
    fmt::print("{}\n", j.dump(2));
    return;
  }
  print_fragility(o, res, names.size(), spec.levels_si.size(), bearing_rule);
  if (!o.out.empty()) fmt::print("table written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

}  // namespace

void add_fragility_command(CLI::App& app) {
  auto o = std::make_shared<FragilityOptions>();
  CLI::App* cmd = app.add_subcommand("fragility", "P(overturn) and P(slide > d) vs an intensity measure over an "
                                                  "ensemble of motions, lognormal MLE fit with its band");
  cmd->add_option("files", o->files, "Record files of the ensemble");
  cmd->add_option("--format", o->motion.format, "Record format (default: detect)")->capture_default_str();
  cmd->add_option("--units", o->motion.units, "Unit of the values of plain files: g, m/s2, cm/s2, gal");
  cmd->add_option("--dt", o->motion.dt_s, "Time step of one-column plain files, s");
  add_record_layout_options(*cmd, o->motion);
  cmd->add_option("--g", o->motion.g_m_s2, "Gravitational acceleration, m/s2")->capture_default_str();
  cmd->add_option("--synth", o->synth, "Use N synthetic motions instead of files (seeds SEED .. SEED+N-1)");
  cmd->add_option("--freq", o->freq, "Synthetic: predominant frequency, with a unit")->capture_default_str();
  cmd->add_option("--duration", o->duration, "Synthetic: duration, s or with a unit")->capture_default_str();
  cmd->add_option("--synth-dt", o->synth_dt, "Synthetic: sample interval, s")->capture_default_str();
  cmd->add_option("--seed", o->seed, "Synthetic: first seed")->capture_default_str();
  cmd->add_option("--im", o->im, "Intensity measure: pga (g), pgv (m/s), pgd (m), cav (m/s)")->capture_default_str();
  cmd->add_option("--im-range", o->im_range, "IM levels LO:HI:N, log spaced, in the IM's unit (e.g. 0.05:2:12)");
  cmd->add_option("--mu", o->mu, "Sliding block: friction coefficient");
  cmd->add_option("--slope-deg", o->slope_deg, "Sliding block: inclination, degrees")->capture_default_str();
  cmd->add_flag("--one-way", o->one_way, "Sliding block: down-slope sliding only");
  cmd->add_option("--threshold", o->threshold, "Sliding block: failure when max |d| exceeds this, with a unit (5cm)");
  cmd->add_option("--shape", o->shape, "Rocking body: block (--width, --height), cylinder (--diameter, --height) or "
                                       "general (--b1, --b2, --h, --inertia)");
  cmd->add_option("--width", o->width, "Block width, with a unit");
  cmd->add_option("--height", o->height, "Block or cylinder height, with a unit");
  cmd->add_option("--diameter", o->diameter, "Cylinder diameter, with a unit");
  cmd->add_option("--b1", o->b1, "General body (--shape general): CM to the pivot on the -x side, with a unit");
  cmd->add_option("--b2", o->b2, "General body: CM to the pivot on the +x side, with a unit");
  cmd->add_option("--h", o->h, "General body: height of the CM above the base, with a unit");
  cmd->add_option("--inertia", o->inertia, "General body: I_cm / m about the rocking axis, with a unit (e.g. 0.02m2)");
  CLI::Option* body_option =
      cmd->add_option("--body", o->body_file, "Rocking body: the JSON `topple body MESH --json` wrote (instead of "
                                              "--shape)");
  CLI::Option* mesh_option =
      cmd->add_option("--mesh", o->mesh, "Rocking body: a mesh file (.obj, .stl, .ply), rocking in the plane of "
                                         "--azimuth (as `topple body`)");
  cmd->add_option("--azimuth", o->mesh_options.azimuth_deg, "With --mesh: the plane of shaking, degrees clockwise "
                                                            "from north")->capture_default_str();
  cmd->add_option("--mesh-unit", o->mesh_unit, "With --mesh: unit of its coordinates (m, cm, mm)")
      ->capture_default_str();
  cmd->add_option("--density", o->mesh_options.density_kg_m3, "With --mesh: uniform density, kg/m^3")
      ->capture_default_str();
  add_pose_options(*cmd, o->mesh_pose, o->mesh_options, "With --mesh: ");
  for (const char* name : {"--shape", "--width", "--height", "--diameter", "--b1", "--b2", "--h", "--inertia"}) {
    body_option->excludes(cmd->get_option(name));
    mesh_option->excludes(cmd->get_option(name));
  }
  body_option->excludes(mesh_option);
  cmd->add_option("--model", o->model, "Rocking body: rocking (Housner), coupled (sliding and rocking at once, "
                                       "slide_rock.hpp; needs --rock-mu) or 3d (pairs: a block with --depth or a "
                                       "mesh, rocking and pivoting in three dimensions, rigid3d.hpp; a cylinder "
                                       "rocking and rolling on its rim, rigid3d_disc.hpp)")
      ->capture_default_str();
  cmd->add_option("--depth", o->depth, "--model 3d, a block: its depth (along bearing + 90), with a unit");
  cmd->add_option("--rock-mu", o->rock_mu, "--model coupled, or 3d (a block or mesh; absent: no sliding): the "
                                           "rocking body's static friction coefficient");
  cmd->add_option("--rock-mu-k", o->rock_mu_k, "--model coupled or 3d: its kinetic friction coefficient (default: "
                                               "--rock-mu)");
  cmd->add_flag("--as-recorded", o->as_recorded, "Run each record once as recorded (no rescaling; no --im-range): "
                                                 "per record PGA, PGV, PGV/PGA and outcome, and the fragility surface "
                                                 "in PGA and PGV/PGA (--out: the table; --plot: the surface)");
  cmd->add_option("--e", o->e, "Coefficient of restitution in [0, 1], or 'housner'")->capture_default_str();
  cmd->add_option("--band", o->band, "Confidence level of the band")->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads (0: every core)")->capture_default_str();
  cmd->add_option("--out", o->out, "Write the counts, fitted probabilities and band per level to this CSV file");
  cmd->add_option("--plot", o->plot, "Draw the curves with their data points and band to this .svg or .png file");
  cmd->add_flag("--json", o->json, "Print the fits as one JSON object");
  cmd->add_option("--components", o->components, "Synthetic: 1, or 2 for horizontal pairs (IM: their RotD50 PGA), 3 "
                                                 "for pairs with a vertical")->capture_default_str();
  cmd->add_option("--h2", o->h2, "Record pairs: the second horizontal component of each record file, in order (IM: "
                                 "the pair's RotD50 PGA; 2-D sliding, oriented rocking)");
  cmd->add_option("--vertical", o->vertical, "Record pairs: the vertical of each pair, in order (optional)");
  cmd->add_option("--azimuths", o->azimuths, "Record pairs: the components' azimuths A1,A2, degrees clockwise from "
                                             "north (default: the files' headers)");
  cmd->add_option("--bearing-deg", o->bearing_deg, "Pairs: the rocking body's bearing (across its narrow side), "
                                                   "degrees clockwise from north; default: uniformly random per motion");
  cmd->add_option("--bearing-seed", o->bearing_seed, "Pairs without --bearing-deg: seed of the random bearings")
      ->capture_default_str();
  add_quiet_flag(*cmd, o->quiet);
  cmd->callback([o, cmd] {
    if (!o->mesh.empty()) {
      apply_pose_options(*cmd, o->mesh_pose, o->mesh_options);
    } else {
      for (const char* name : {"--pose", "--up", "--rotation", "--axis-angle", "--face", "--contact-tolerance",
                               "--base-tolerance"}) {
        if (cmd->count(name) > 0) throw parameter_error(name, "places a mesh body: it applies with --mesh only");
      }
    }
    run_fragility(*o);
  });
}

}  // namespace topple::cli
