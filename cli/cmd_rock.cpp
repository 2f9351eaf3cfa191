// topple rock: rocking and overturning of a rigid block, cylinder or general body under a record or a pulse.
// Parsing and printing only; the response is topple::rock / topple::rock_summary.
#include <cmath>
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
#include "motion_set_options.hpp"
#include "pose_options.hpp"
#include "rock_3d.hpp"
#include "rock_coupled.hpp"
#include "topple/core/error.hpp"
#include "topple/io/body_file.hpp"
#include "topple/io/mesh.hpp"
#include "topple/output/write.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/output/plot.hpp"
#include "topple/solvers/rocking.hpp"
#include "topple/core/units.hpp"

namespace topple::cli {
namespace {

struct RockOptions {
  bool quiet = false;
  MotionOptions motion;
  PulseOptions pulse;
  std::string shape;
  std::string width;
  std::string height;
  std::string diameter;
  std::string a;
  std::string h;
  std::string D;
  std::string b1;
  std::string b2;
  std::string inertia;
  std::string body_file;  // --body: what `topple body --json` writes (io/body_file.hpp)
  std::string mesh;       // --mesh FILE (--model 3d): the mesh as posed (BodyOptions, the pose options)
  std::string mesh_unit = "m";
  BodyOptions mesh_options;
  PoseOptionsText mesh_pose;
  std::string e = "housner";
  std::optional<double> mu;
  std::optional<double> mu_k;
  std::optional<double> slope_deg;  // --model coupled: inclined base
  std::string model = "rocking";
  std::string vertical;
  std::string h2;        // second horizontal component: an oriented object (oriented.hpp)
  std::string azimuths;  // "A1,A2", degrees clockwise from north
  std::optional<double> bearing_deg;
  std::string depth;     // a block's other horizontal dimension: a box
  std::optional<double> direction_step_deg;  // cylinder: spacing of the directions tried
  std::string method = "adaptive";
  std::optional<double> rtol;
  std::optional<double> simultaneous_contact;  // --model 3d, a polygon base: fraction of the body's size (rigid3d.hpp)
  std::optional<double> base_incline_deg;          // --model 3d, a polygon base: an inclined base (rigid3d.hpp)
  std::optional<double> base_incline_azimuth_deg;  // its downhill azimuth
  std::optional<int> rk4_substeps;
  std::optional<std::size_t> max_steps;
  std::string run_out;
  std::string out;
  std::string plot;
  bool json = false;
};

/// Library field names -> the options that set them, so that errors name what the user typed.
const std::map<std::string, std::string>& option_names() {
  static const std::map<std::string, std::string> names{
      {"width", "--width"},   {"height", "--height"}, {"diameter", "--diameter"},     {"a", "--a"},
      {"h", "--h"},           {"D", "--D"},           {"e", "--e"},                   {"mu", "--mu"},
      {"b1", "--b1"},         {"b2", "--b2"},         {"inertia", "--inertia"},
      {"g", "--g"},           {"rel_tol", "--rtol"},  {"rk4_substeps", "--rk4-substeps"},
      {"max_steps", "--max-steps"},
      {"max_run_out_s", "--run-out"}, {"vertical", "--vertical"}, {"mu_k", "--mu-k"}, {"slope", "--slope-deg"},
      {"mu_s", "--mu"},
      {"depth", "--depth"},   {"bearing", "--bearing-deg"}, {"cylinder_step", "--direction-step-deg"},
      {"azimuth", "--azimuths"}, {"simultaneous_contact", "--simultaneous-contact"},
      {"base_incline_deg", "--base-incline-deg"}, {"base_incline_azimuth_deg", "--base-incline-azimuth-deg"}};
  return names;
}

template <class F>
auto naming_options(F f) {
  try {
    return f();
  } catch (const InputError& err) {
    const auto& names = option_names();
    const auto it = names.find(err.where().field);
    if (it == names.end() || !err.where().file.empty()) throw;
    throw parameter_error(it->second, err.problem());
  }
}

RockingBody make_body(const RockOptions& o) {
  if (!o.body_file.empty()) return io::read_body_file(o.body_file).rocking_body();  // errors name the file and field
  const RockingBody::Shape shape = naming_options([&] { return parse_shape(o.shape, "--shape"); });
  const auto length = [](const std::string& text, const char* option) -> std::optional<double> {
    if (text.empty()) return std::nullopt;
    return parse_length_m(text, option);
  };
  BodyDimensions d;
  d.width_m = length(o.width, "--width");
  d.height_m = length(o.height, "--height");
  d.diameter_m = length(o.diameter, "--diameter");
  d.a_m = length(o.a, "--a");
  d.h_m = length(o.h, "--h");
  if (!o.D.empty()) d.D_m2 = parse_area_m2(o.D, "--D");
  d.b1_m = length(o.b1, "--b1");
  d.b2_m = length(o.b2, "--b2");
  if (!o.inertia.empty()) d.inertia_m2 = parse_area_m2(o.inertia, "--inertia");
  return naming_options([&] { return make_rocking_body(shape, d); });
}

RockingOptions make_options(const RockOptions& o) {
  RockingOptions r;
  r.g_m_s2 = o.motion.g_m_s2;
  const RestitutionChoice e = parse_restitution(o.e, "--e");
  r.restitution = e.mode;
  r.e = e.e;
  r.mu = o.mu;
  r.method = parse_rocking_method(o.method, "--method");
  if (o.rtol) r.rel_tol = *o.rtol;
  if (o.rk4_substeps) r.rk4_substeps = *o.rk4_substeps;
  if (o.max_steps) r.max_steps = *o.max_steps;
  if (!o.run_out.empty()) r.max_run_out_s = parse_seconds(o.run_out, "--run-out");
  return r;
}

/// The --out history and --plot figure of a full run on `horizontal` (the record, or an oriented object's governing
/// direction).
void write_outputs(const RockOptions& o, const RunMotion& run, const GroundMotion& horizontal,
                   const GroundMotion* vertical_ptr, const RockingBody& body, const RockingOptions& options,
                   const RockingResult& result, const std::string& direction) {
  if (!o.out.empty()) io::write_rocking_history_csv(o.out, result.history);
  if (!o.plot.empty()) {
    const std::string title =
        fmt::format("Rocking {}, a = {:.3g} m, h = {:.3g} m, α = {:.3g} rad, e = {:.3g}{}{}{}: {}",
                    shape_name(body.shape), body.a_m, body.h_m, result.summary.alpha_rad, result.summary.e,
                    options.restitution == RestitutionMode::housner ? " (Housner)" : "",
                    o.vertical.empty() ? "" : ", with vertical " + plot::file_label(o.vertical), direction, run.title);
    plot::render(plot::rocking_figure(horizontal, result, body, title, vertical_ptr), o.plot);
  }
}

/// What an oriented run adds to the report.
struct OrientationReport {
  const OrientedRockingSummary& summary;
  const OrientedBody& body;
  std::optional<double> bearing_deg;
  ComponentAzimuths azimuths;
  OrientationOptions orientation;
};

void report(const RockOptions& o, const RunMotion& run, const GroundMotion& horizontal, const RockingBody& body,
            const RockingOptions& options, const RockingSummary& s, const OrientationReport* orientation);

/// --h2: an oriented object under the motion set (oriented.hpp), reported by its governing direction.
void run_oriented(const RockOptions& o, const RunMotion& run, const RockingBody& body, const RockingOptions& options) {
  const std::optional<double> depth =
      o.depth.empty() ? std::nullopt : std::optional(parse_length_m(o.depth, "--depth"));
  const OrientedBody oriented = naming_options([&] { return OrientedBody::make(body, depth); });
  naming_options([&] { check_orientation(oriented, o.bearing_deg, o.direction_step_deg.has_value()); });
  OrientationOptions orientation;
  if (o.direction_step_deg) orientation.cylinder_step_deg = *o.direction_step_deg;
  const MotionSet set = load_motion_set(run, o.motion, o.h2, o.azimuths);
  const double bearing = o.bearing_deg.value_or(0.0);
  OrientedRockingSummary oriented_summary;
  std::optional<RockingResult> full;
  if (!o.out.empty() || !o.plot.empty()) {
    OrientedRockingResult r = naming_options([&] { return rock_oriented(set, oriented, bearing, options, orientation); });
    oriented_summary = std::move(r.orientation);
    full = std::move(r.governing);
  } else {
    oriented_summary = naming_options([&] { return rock_oriented_summary(set, oriented, bearing, options, orientation); });
  }
  const DirectionResponse& gov = oriented_summary.governing_response();
  const RockingBody& planar = planar_body_of(oriented, gov.axis);
  const GroundMotion horizontal = set.projected(gov.azimuth_deg);
  if (full) {
    write_outputs(o, run, horizontal, set.vertical_ptr(), planar, options, *full,
                  fmt::format(", along {:g}°", gov.azimuth_deg));
  }
  for (const DirectionResponse& d : oriented_summary.directions) {
    require_finite({{"max |theta| / alpha", d.summary.max_rotation_over_alpha}});
  }
  const OrientationReport report_of{oriented_summary, oriented, o.bearing_deg, *set.azimuths(), orientation};
  report(o, run, horizontal, planar, options, gov.summary, &report_of);
}

/// --model 3d: the three-dimensional engine (rigid3d.hpp) for a block with a depth or a mesh as posed, or the rim
/// engine (rigid3d_disc.hpp) for a solid cylinder (rock_3d.hpp). `body` is the planar body of the options (none with
/// --mesh); run_rock refused --body already.
void run_model_3d(const RockOptions& o, RunMotion& run, const std::optional<RockingBody>& body,
                  const RockingOptions& options) {
  const bool cylinder = body && body->shape == RockingBody::Shape::cylinder;
  if (cylinder && !o.depth.empty()) {
    throw parameter_error("--depth", "is a block's: a cylinder is given by --diameter and --height");
  }
  if (cylinder && o.bearing_deg) {
    throw parameter_error("--bearing-deg", "a cylinder is the same body turned about its axis: it has no bearing "
                                           "(the components act along their --azimuths)");
  }
  if (body && !cylinder && body->shape != RockingBody::Shape::block) {
    throw parameter_error("--shape", "--model 3d: a general body (--a/--h/--D or --b1/--b2/--h/--inertia) is a "
                                     "section in one vertical plane, without a base in three dimensions; give a block "
                                     "(--shape block --width --depth --height) or a mesh (--mesh FILE)");
  }
  if (body && !cylinder && o.depth.empty()) {
    throw parameter_error("--depth", "--model 3d needs the block's depth, with a unit (its extent along its own y "
                                     "axis: along bearing + 90 with --h2)");
  }
  if (!body && !o.depth.empty()) throw parameter_error("--depth", "is a block's: a mesh has its own shape");
  if (o.slope_deg) {
    throw parameter_error("--slope-deg", "is the coupled model's; --model 3d takes an inclined base as "
                                         "--base-incline-deg and --base-incline-azimuth-deg");
  }
  if (o.direction_step_deg) throw parameter_error("--direction-step-deg", "is for a cylinder of the rocking model");
  if (options.method != RockingMethod::adaptive) throw parameter_error("--method", "--model 3d is adaptive only");
  Rigid3DRequest request;
  if (cylinder) {
    // the planar cylinder's a = d / 2 and h = H / 2 (rocking_body.hpp): the same solid cylinder in three dimensions
    request.width_m = 2.0 * body->a_m;
    request.height_m = 2.0 * body->h_m;
    request.cylinder = naming_options([&] { return CylinderBody3D::solid(request.width_m, request.height_m); });
  } else if (body) {
    request.width_m = 2.0 * body->a_m;
    request.height_m = 2.0 * body->h_m;
    request.depth_m = parse_length_m(o.depth, "--depth");
    request.body = naming_options([&] {  // "depth" -> --depth
      return RigidBody3D::box(request.width_m, request.depth_m, request.height_m);
    });
  } else {
    BodyOptions b = o.mesh_options;
    b.g_m_s2 = options.g_m_s2;
    const double unit_m = io::mesh_unit_m(o.mesh_unit, "--mesh-unit");
    const MeshBody mesh =
        with_field_names({{"--unit", "--mesh-unit"}}, [&] { return io::read_mesh_body(o.mesh, unit_m, b); });
    request.body = RigidBody3D::from_mesh(mesh);
    request.mesh_file = o.mesh;
  }
  request.out = o.out;
  request.plot = o.plot;
  request.vertical_label = o.vertical;
  request.options = rigid3d_options(options);  // rigid3d.hpp: the settings the planar options share
  if (o.simultaneous_contact) {
    if (cylinder) {
      throw parameter_error("--simultaneous-contact", "is the polygon engine's (a block's or a mesh's corners landing "
                                                      "together): a cylinder's base lands flat on its rim");
    }
    // rock3d checks the same range (field "simultaneous_contact", which option_names maps to this option); here the
    // refusal also says what the number is.
    if (!std::isfinite(*o.simultaneous_contact) || *o.simultaneous_contact < 0.0 || *o.simultaneous_contact > 0.01) {
      throw parameter_error("--simultaneous-contact", fmt::format("must be in [0, 0.01] (a fraction of the body's "
                                                                  "size), got {}", *o.simultaneous_contact));
    }
    request.options.simultaneous_contact = *o.simultaneous_contact;
  }
  if (o.base_incline_deg || o.base_incline_azimuth_deg) {
    if (cylinder) {
      throw parameter_error(o.base_incline_deg ? "--base-incline-deg" : "--base-incline-azimuth-deg",
                            "the cylinder's rim engine (rigid3d_disc.hpp) has a level base: an inclined base is a "
                            "block's or a mesh's");
    }
    if (!o.base_incline_deg) {
      throw parameter_error("--base-incline-azimuth-deg", "needs --base-incline-deg (the base's inclination)");
    }
    // checked by rock3d: [0, 90) degrees, a finite azimuth (fields named as these options)
    request.options.base_incline_deg = *o.base_incline_deg;
    request.options.base_incline_azimuth_deg = o.base_incline_azimuth_deg.value_or(0.0);
  }
  // absent: no sliding (rigid3d.hpp; a cylinder: rigid3d_disc.hpp's friction); checked by rock3d ("mu_s" -> --mu)
  request.options.mu_s = o.mu;
  request.options.mu_k = o.mu_k;
  request.json = o.json;
  std::optional<MotionSet> set;
  if (!o.h2.empty()) {
    if (!cylinder && !o.bearing_deg) {
      throw parameter_error("--bearing-deg", "required with --model 3d and --h2: the azimuth of the body's +x axis "
                                             "(a block: across its width), degrees clockwise from north");
    }
    if (o.bearing_deg && !std::isfinite(*o.bearing_deg)) {
      throw parameter_error("--bearing-deg", fmt::format("must be finite, got {}", *o.bearing_deg));
    }
    set = load_motion_set(run, o.motion, o.h2, o.azimuths);
    request.set = &*set;
    request.bearing_deg = o.bearing_deg;
    request.h2 = o.h2;
  } else {
    refuse_without_h2(o.azimuths, {{"--bearing-deg", o.bearing_deg.has_value()}});
  }
  naming_options([&] { run_3d(run, request); });
}

void run_rock(const RockOptions& o) {
  const double g = o.motion.g_m_s2;
  check_g(g);
  check_plot_path(o.plot);
  check_output_path(o.out);
  if (!o.mesh.empty() && o.model != "3d") {
    throw parameter_error("--mesh", "needs --model 3d (for the planar models: `topple body MESH --json > body.json`, "
                                    "then --body body.json)");
  }
  if ((o.base_incline_deg || o.base_incline_azimuth_deg) && o.model != "3d") {
    throw parameter_error(o.base_incline_deg ? "--base-incline-deg" : "--base-incline-azimuth-deg",
                          "applies with --model 3d only (the coupled model's inclined base is --slope-deg)");
  }
  if (o.simultaneous_contact && o.model != "3d") {
    throw parameter_error("--simultaneous-contact", "applies with --model 3d only (the planar models land on one edge)");
  }
  if (!o.body_file.empty() && o.model == "3d") {
    throw parameter_error("--body", "--model 3d needs the body in three dimensions: a body file holds its section in "
                                    "one vertical plane only; give the mesh it came from (--mesh FILE, with the same "
                                    "pose options as `topple body`)");
  }
  const std::optional<RockingBody> body3d = o.mesh.empty() ? std::optional(make_body(o)) : std::nullopt;
  const RockingOptions options = make_options(o);
  RunMotion run = load_run_motion(o.motion, o.pulse, o.vertical);
  run.input.with_duration = true;
  if (o.model == "3d") {
    run_model_3d(o, run, body3d, options);
    return;
  }
  const RockingBody& body = *body3d;
  if (o.model == "coupled") {  // the coupled slide-rock model (rock_coupled.hpp)
    if (!o.mu) throw parameter_error("--mu", "the coupled model needs the friction coefficient (--mu)");
    if (!o.depth.empty()) {
      throw parameter_error("--depth", "the coupled model runs in one vertical plane: give the axis to check with "
                                       "--bearing-deg (a box: run each axis)");
    }
    if (o.direction_step_deg) {
      throw parameter_error("--direction-step-deg", "the coupled model runs in one vertical plane, the one "
                                                    "--bearing-deg gives; the worst direction is searched by the "
                                                    "rocking model only");
    }
    if (options.method != RockingMethod::adaptive) {
      throw parameter_error("--method", "the coupled model is adaptive only");
    }
    CoupledRequest request;
    request.options = slide_rock_options(options);
    if (o.slope_deg) request.options.slope_rad = deg_to_rad(*o.slope_deg);  // validated by slide_rock ("slope")
    request.out = o.out;
    request.plot = o.plot;
    request.json = o.json;
    if (!o.h2.empty()) {
      // Oriented (oriented.hpp): the planar model in the vertical plane of the bearing, under the pair's projection
      // on it (eq. M1) with the vertical; out-of-plane motion neglected, as for the rocking model.
      if (!o.bearing_deg) {
        throw parameter_error("--bearing-deg", "required with --model coupled and --h2: the bearing of the body's +x "
                                               "side (the b2 edge), degrees clockwise from north, whose vertical "
                                               "plane the coupled model runs in");
      }
      if (!std::isfinite(*o.bearing_deg)) {
        throw parameter_error("--bearing-deg", fmt::format("must be finite, got {}", *o.bearing_deg));
      }
      const MotionSet set = load_motion_set(run, o.motion, o.h2, o.azimuths);
      run.horizontal = set.projected(*o.bearing_deg);  // azimuths are known (load_motion_set)
      if (set.vertical_ptr() != nullptr) run.vertical = *set.vertical_ptr();
      run.input.motion += fmt::format(" and {} along {:g} deg", o.h2, *o.bearing_deg);
      run.title += fmt::format(" and {} along {:g}°", plot::file_label(o.h2), *o.bearing_deg);
      request.bearing_deg = o.bearing_deg;
      request.h2 = o.h2;
      request.azimuths = set.azimuths();
    } else {
      refuse_without_h2(o.azimuths, {{"--bearing-deg", o.bearing_deg.has_value()}});
    }
    const SlideRockBody coupled = naming_options([&] { return SlideRockBody::from_rocking(body, *o.mu, o.mu_k); });
    naming_options([&] { run_coupled(run, coupled, request); });
    return;
  }
  if (o.model != "rocking") {
    throw parameter_error("--model", fmt::format("'rocking', 'coupled' or '3d', got '{}'", o.model));
  }
  if (o.mu_k) throw parameter_error("--mu-k", "needs --model coupled or 3d (the rocking model does not slide)");
  if (o.slope_deg) throw parameter_error("--slope-deg", "needs --model coupled (the rocking model has a level base)");
  if (!o.h2.empty()) {
    run_oriented(o, run, body, options);
    return;
  }
  refuse_without_h2(o.azimuths, {{"--bearing-deg", o.bearing_deg.has_value()},
                                 {"--depth", !o.depth.empty()},
                                 {"--direction-step-deg", o.direction_step_deg.has_value()}});
  const GroundMotion& horizontal = run.horizontal;
  const GroundMotion* vertical_ptr = run.vertical_ptr();
  RockingSummary s;
  if (!o.out.empty() || !o.plot.empty()) {
    const RockingResult result = naming_options([&] { return rock(horizontal, body, options, vertical_ptr); });
    write_outputs(o, run, horizontal, vertical_ptr, body, options, result, "");
    s = result.summary;
  } else {
    s = naming_options([&] { return rock_summary(horizontal, body, options, vertical_ptr); });
  }
  report(o, run, horizontal, body, options, s, nullptr);
}

void report(const RockOptions& o, const RunMotion& run, const GroundMotion& horizontal, const RockingBody& body,
            const RockingOptions& options, const RockingSummary& s, const OrientationReport* orientation) {
  const double g = o.motion.g_m_s2;
  const std::string& motion_name = run.input.motion;
  for (const auto& w : s.warnings) fmt::print(stderr, "topple: warning: {}\n", w);
  require_finite({{"PGA", horizontal.pga_m_s2()}, {"max |theta|", s.max_abs_rotation_rad},
                  {"max |theta| / alpha", s.max_rotation_over_alpha}, {"time of max |theta|", s.max_rotation_time_s},
                  {"first uplift", s.uplift_time_s.value_or(0.0)}, {"|theta| > alpha", s.exceeded_alpha_time_s.value_or(0.0)},
                  {"overturning time", s.overturn_time_s.value_or(0.0)}, {"end time", s.end_time_s},
                  {"energy lost", s.energy_lost_j_per_kg}, {"max |theta dot|", s.max_abs_theta_dot_rad_s},
                  {"onset ratio", s.onset_accel_ratio.value_or(0.0)}, {"critical mu", s.critical_mu.value_or(0.0)},
                  {"alpha", s.alpha_rad}, {"R", s.R_m}, {"p", s.p_rad_s}, {"e", s.e}});

  if (o.json) {
    nlohmann::ordered_json j = io::rocking_summary_json(s, body, options);
    j["input"] = io::run_input_json(run.input, horizontal, g);
    if (orientation != nullptr) {
      j["input"]["h2"] = o.h2;
      j["orientation"] = io::oriented_rocking_json(orientation->summary, orientation->body, orientation->bearing_deg,
                                                   orientation->azimuths, orientation->orientation);
    }
    fmt::print("{}\n", j.dump(2));
    return;
  }
  if (orientation != nullptr) {
    const OrientationReport& x = *orientation;
    fmt::print("oriented object: planar rocking under the projection of the two horizontal components on each "
               "direction (eq. M1), with the vertical when there is one\n");
    fmt::print("  components at {:g} and {:g} deg (clockwise from north); {}\n", x.azimuths.first_deg,
               x.azimuths.second_deg,
               x.bearing_deg ? fmt::format("bearing {:g} deg", *x.bearing_deg)
                             : fmt::format("cylinder: worst of every {:g} deg over 180 (an approximation of "
                                           "three-dimensional rocking)", x.orientation.cylinder_step_deg));
    for (const DirectionResponse& d : x.summary.directions) {
      fmt::print("  along {:>6g} deg ({:<7}) max |theta| / alpha {:.6g}{}\n", d.azimuth_deg, oriented_axis_name(d.axis),
                 d.summary.max_rotation_over_alpha,
                 d.summary.overturned ? fmt::format(", overturned at {:.4f} s", *d.summary.overturn_time_s)
                                      : std::string());
    }
    fmt::print("governing direction: {:g} deg ({}); below, its planar run\n",
               x.summary.governing_response().azimuth_deg, oriented_axis_name(x.summary.governing_response().axis));
  }
  if (body.negative_pivot) {
    fmt::print("rocking body: {} b1 = {:.6g} m (pivot O-, theta < 0), b2 = {:.6g} m (O+, theta > 0), h = {:.6g} m, "
               "D1 = {:.6g} m2, D2 = {:.6g} m2\n",
               shape_name(body.shape), body.negative_pivot->b_m, body.a_m, body.h_m, body.negative_pivot->D_m2,
               body.D_m2);
    fmt::print("  O-: alpha = {:.6g} rad ({:.4f} deg), e onto O- = {:.6g}, uplift threshold {:.5f} g (b1/h)\n",
               s.alpha_negative_rad, rad_to_deg(s.alpha_negative_rad), s.e_onto_negative,
               body.negative_pivot->b_m / body.h_m);
    fmt::print("  O+ (below: alpha, R, p, e of O+)\n");
  } else {
    fmt::print("rocking body: {} a = {:.6g} m, h = {:.6g} m, D = {:.6g} m2\n", shape_name(body.shape), body.a_m,
               body.h_m, body.D_m2);
  }
  fmt::print("  alpha = {:.6g} rad ({:.4f} deg), R = {:.6g} m, p = {:.6g} rad/s, e = {:.6g} ({}), g = {} m/s2\n",
             s.alpha_rad, rad_to_deg(s.alpha_rad), s.R_m, s.p_rad_s, s.e,
             options.restitution == RestitutionMode::housner ? "Housner" : restitution_mode_name(options.restitution), g);
  fmt::print("  uplift threshold {:.5f} g ({})\n", body.a_m / body.h_m, body.negative_pivot ? "b2/h" : "a/h");
  fmt::print("motion: {}{} (PGA {:.4f} g, {} samples)\n", motion_name,
             orientation != nullptr ? fmt::format(" and {}, projected on {:g} deg", o.h2,
                                                  orientation->summary.governing_response().azimuth_deg)
                                    : std::string(),
             horizontal.pga_m_s2() / g, horizontal.size());
  fmt::print("max |theta|            {:.6g} rad = {:.6g} alpha at {:.4f} s\n", s.max_abs_rotation_rad,
             s.max_rotation_over_alpha, s.max_rotation_time_s);
  if (body.negative_pivot) {
    fmt::print("max theta > 0 (O+)     {:.6g} rad = {:.6g} alpha+\n", s.max_rotation_positive_rad,
               s.max_rotation_over_alpha_positive);
    fmt::print("max -theta (O-)        {:.6g} rad = {:.6g} alpha-\n", s.max_rotation_negative_rad,
               s.max_rotation_over_alpha_negative);
  }
  fmt::print("first uplift           {}\n", format_seconds_or_none(s.uplift_time_s));
  fmt::print("uplifts, impacts       {}, {}\n", s.uplifts, s.impacts);
  fmt::print("|theta| > alpha first  {}\n", format_seconds_or_none(s.exceeded_alpha_time_s));
  fmt::print("overturned             {}{}{}\n", s.overturned ? "yes, at " : "no",
             s.overturned ? format_seconds_or_none(s.overturn_time_s) : std::string(),
             s.overturned && body.negative_pivot ? (s.overturned_side > 0 ? " toward +x (about O+)"
                                                                          : " toward -x (about O-)")
                                                 : "");
  fmt::print("end                    {} at {:.4f} s\n", rocking_state_name(s.end_state), s.end_time_s);
  fmt::print("energy lost            {:.6g} J/kg\n", s.energy_lost_j_per_kg);
  fmt::print("onset mode             {}{}\n", onset_mode_name(s.onset_mode),
             o.mu ? fmt::format(" (mu = {})", *o.mu) : std::string(" (give --mu to check)"));
  if (!o.out.empty()) fmt::print("history written to {}\n", o.out);
  if (!o.plot.empty()) fmt::print("figure written to {}\n", o.plot);
}

}  // namespace

void add_rock_command(CLI::App& app) {
  auto o = std::make_shared<RockOptions>();
  CLI::App* cmd = app.add_subcommand(
      "rock", "Rocking and overturning of a rigid body on a level base (Housner's model; no sliding)");
  cmd->add_option("file", o->motion.file, "Record file (format detected from content)");
  add_motion_options(*cmd, o->motion);
  add_pulse_options(*cmd, o->pulse);
  cmd->add_option("--shape", o->shape, "block (--width, --height), cylinder (--diameter, --height) or general "
                                       "(--a, --h, --D; asymmetric: --b1, --b2, --h, --inertia)");
  cmd->add_option("--width", o->width, "Block width, with a unit (e.g. 4cm)");
  cmd->add_option("--height", o->height, "Block or cylinder height, with a unit (e.g. 0.20m)");
  cmd->add_option("--diameter", o->diameter, "Cylinder diameter, with a unit");
  cmd->add_option("--a", o->a, "General body: horizontal distance from the centre of mass to the pivot edge");
  cmd->add_option("--h", o->h, "General body: height of the centre of mass above the base");
  cmd->add_option("--D", o->D, "General body: pivot moment of inertia per unit mass, with a unit (e.g. 0.011m2)");
  cmd->add_option("--b1", o->b1, "Asymmetric general body: horizontal distance from the centre of mass to the pivot "
                                 "edge on the -x side (rocking with theta < 0), with a unit");
  cmd->add_option("--b2", o->b2, "Asymmetric general body: the same to the +x edge (theta > 0; a ground "
                                 "acceleration toward -x lifts the body about it), with a unit");
  cmd->add_option("--inertia", o->inertia, "Asymmetric general body: moment of inertia about the centre of mass "
                                           "per unit mass I_cm/m, with a unit (e.g. 0.004m2)");
  CLI::Option* body_option =
      cmd->add_option("--body", o->body_file, "The body `topple body MESH --json` wrote (its b1_m, b2_m, h_m, "
                                              "inertia_cm_plane_kg_m2, mass_kg): the mesh's asymmetric general body "
                                              "at its azimuth; instead of --shape and the dimensions");
  CLI::Option* mesh_option =
      cmd->add_option("--mesh", o->mesh, "--model 3d: the body of a mesh file (.obj, .stl, .ply) as `topple body` "
                                         "poses it (its support polygon, centre of mass and inertia); instead of "
                                         "--shape and the dimensions");
  cmd->add_option("--mesh-unit", o->mesh_unit, "With --mesh: unit of its coordinates (m, cm, mm)")
      ->capture_default_str();
  cmd->add_option("--density", o->mesh_options.density_kg_m3, "With --mesh: uniform density, kg/m^3")
      ->capture_default_str();
  add_pose_options(*cmd, o->mesh_pose, o->mesh_options, "With --mesh: ");
  for (const char* name : {"--shape", "--width", "--height", "--diameter", "--a", "--h", "--D", "--b1", "--b2",
                           "--inertia"}) {
    body_option->excludes(cmd->get_option(name));
    mesh_option->excludes(cmd->get_option(name));
  }
  body_option->excludes(mesh_option);
  cmd->add_option("--e", o->e, "Coefficient of restitution (angular-velocity ratio at impact) in [0, 1], or "
                               "'housner' (1 - 2a^2/D, from angular momentum)")->capture_default_str();
  cmd->add_option("--mu", o->mu, "Friction coefficient: check Shenton's slide/rock/slide-rock onset criterion; with "
                                 "--model coupled or 3d the static friction coefficient (3d without it: no sliding)");
  cmd->add_option("--model", o->model, "rocking (Housner; no sliding), coupled (sliding and rocking at once, "
                                       "Coulomb friction --mu/--mu-k: slide_rock.hpp) or 3d (a block with --depth, "
                                       "or a mesh (--mesh), rocking and pivoting on its base in three dimensions, "
                                       "sliding flat with --mu/--mu-k: rigid3d.hpp)")->capture_default_str();
  cmd->add_option("--mu-k", o->mu_k, "--model coupled or 3d: kinetic friction coefficient (default: --mu)");
  cmd->add_option("--slope-deg", o->slope_deg, "--model coupled: inclination of the base, degrees, down-slope toward "
                                               "-x (the b1 corner); needs tan(slope) <= --mu and slope <= alpha-");
  add_motion_set_options(*cmd, o->vertical, o->h2, o->azimuths,
                         "an oriented object rocking under the projection of both components on its directions "
                         "(planar model)");
  cmd->add_option("--bearing-deg", o->bearing_deg, "With --h2: the direction across the object's narrow side "
                                                   "(its +x side), degrees clockwise from north; not for a cylinder");
  cmd->add_option("--depth", o->depth, "With --h2, a block: its other horizontal dimension (along bearing + 90), "
                                       "with a unit: a box, checked about both axes");
  cmd->add_option("--direction-step-deg", o->direction_step_deg, "With --h2, a cylinder: spacing of the directions "
                                                                 "tried over 180 deg (default 15; must divide 180)");
  cmd->add_option("--method", o->method, "adaptive (Dormand-Prince with event location) or rk4 (fixed step dt/n, "
                                         "as in the thesis)")->capture_default_str();
  cmd->add_option("--rtol", o->rtol, "Relative tolerance of the adaptive method (default 1e-8)");
  cmd->add_option("--simultaneous-contact", o->simultaneous_contact,
                  "--model 3d, a block or a mesh: at a touch-down, base vertices within this fraction of the body's "
                  "size (its largest distance from the centre of mass to a vertex; dimensionless) of the ground land "
                  "with it as one impact, in [0, 0.01] (default 1e-5; 0: strictly successive impacts)");
  cmd->add_option("--base-incline-deg", o->base_incline_deg,
                  "--model 3d, a block or a mesh: the base is a plane inclined at this angle, degrees in [0, 90) "
                  "(default 0, level); the body sticks to it without --mu, slides on it with --mu; the outputs are in "
                  "the base's frame (tilt from the base normal, slide along the plane)");
  cmd->add_option("--base-incline-azimuth-deg", o->base_incline_azimuth_deg,
                  "--model 3d with --base-incline-deg: the plane's downhill direction, degrees clockwise from north "
                  "(default 0; without --h2 the record runs along the body's +x, azimuth 90)");
  cmd->add_option("--rk4-substeps", o->rk4_substeps, "RK4 steps per sample interval (default 10)");
  cmd->add_option("--max-steps", o->max_steps, "Cap on integrator steps; past it the run stops with exit status 3 "
                                               "(default 100000000)");
  cmd->add_option("--run-out", o->run_out, "Longest integration after the record on still ground, s (default 60)");
  cmd->add_option("--out", o->out, "Write the time history to this CSV file (time_s,theta_rad,theta_dot_rad_s,state; "
                                   "--model 3d: time_s, x_m, y_m, z_m, qw..qz, wx..wz_rad_s, tilt_rad, "
                                   "energy_j_per_kg, mode)");
  cmd->add_option("--plot", o->plot, "Draw record with the uplift levels, theta/alpha with the overturning limits, "
                                     "theta', impacts and the fall, to this .svg or .png file (gnuplot)");
  cmd->add_flag("--json", o->json, "Print the summary as one JSON object");
  add_quiet_flag(*cmd, o->quiet);  // a single run is quick: no bar; warnings are still printed
  cmd->callback([o, cmd] {
    if (!o->mesh.empty()) {
      apply_pose_options(*cmd, o->mesh_pose, o->mesh_options);
    } else {
      for (const char* name : {"--pose", "--up", "--rotation", "--axis-angle", "--face", "--contact-tolerance",
                               "--base-tolerance", "--mesh-unit", "--density"}) {
        if (cmd->count(name) > 0) throw parameter_error(name, "places a mesh body: it applies with --mesh only");
      }
    }
    run_rock(*o);
  });
}

}  // namespace topple::cli
