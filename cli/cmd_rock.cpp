// topple rock: rocking and overturning of a rigid block, cylinder or general body under a record or a pulse.
// Parsing and printing only; the response is topple::rock / topple::rock_summary.
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common.hpp"
#include "topple/error.hpp"
#include "topple/io/write.hpp"
#include "topple/plot.hpp"
#include "topple/rocking.hpp"
#include "topple/units.hpp"

namespace topple::cli {
namespace {

struct RockOptions {
  MotionOptions motion;
  PulseOptions pulse;
  std::string shape;
  std::string width;
  std::string height;
  std::string diameter;
  std::string a;
  std::string h;
  std::string D;
  std::string e = "housner";
  std::optional<double> mu;
  std::string vertical;
  std::string method = "adaptive";
  std::optional<double> rtol;
  std::optional<int> rk4_substeps;
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
      {"g", "--g"},           {"rel_tol", "--rtol"},  {"rk4_substeps", "--rk4-substeps"},
      {"max_run_out_s", "--run-out"}, {"vertical", "--vertical"}};
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

/// An area such as "0.011m2", "110cm2", "0.011 m^2" (the pivot moment of inertia per unit mass D). A bare number is
/// refused, as for lengths.
double parse_area_m2(const std::string& text, const std::string& option) {
  std::string s = text;
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  double value = 0.0;
  const char* first = s.data();
  const char* last = s.data() + s.size();
  const auto [ptr, ec] = std::from_chars(first, last, value);
  if (ec != std::errc{} || ptr == first) {
    throw parameter_error(option, fmt::format("'{}' is not an area (expected a number and a unit, e.g. 0.011m2)", text));
  }
  if (!std::isfinite(value)) throw parameter_error(option, fmt::format("'{}' is not finite", text));
  std::string unit(ptr, last);
  unit.erase(0, unit.find_first_not_of(' '));
  if (unit.empty()) throw parameter_error(option, fmt::format("'{}' has no unit; write it with one, e.g. '{}m2'", text, value));
  static const std::map<std::string, double> units{{"m2", 1.0},    {"m^2", 1.0},    {"cm2", 1e-4},
                                                   {"cm^2", 1e-4}, {"mm2", 1e-6},   {"mm^2", 1e-6}};
  const auto it = units.find(unit);
  if (it == units.end()) {
    throw parameter_error(option, fmt::format("unknown area unit '{}' in '{}' (known: m2, cm2, mm2)", unit, text));
  }
  return value * it->second;
}

RockingBody make_body(const RockOptions& o) {
  const auto need = [](const std::string& value, const char* option, const std::string& shape) {
    if (value.empty()) throw parameter_error(option, fmt::format("--shape {} needs {}", shape, option));
  };
  const auto refuse = [](const std::string& value, const char* option, const std::string& shape) {
    if (!value.empty()) throw parameter_error(option, fmt::format("{} does not apply to --shape {}", option, shape));
  };
  if (o.shape == "block") {
    need(o.width, "--width", o.shape);
    need(o.height, "--height", o.shape);
    for (const auto& [v, name] : {std::pair{o.diameter, "--diameter"}, std::pair{o.a, "--a"}, std::pair{o.h, "--h"},
                                  std::pair{o.D, "--D"}}) {
      refuse(v, name, o.shape);
    }
    return naming_options([&] {
      return RockingBody::block(parse_length_m(o.width, "--width"), parse_length_m(o.height, "--height"));
    });
  }
  if (o.shape == "cylinder") {
    need(o.diameter, "--diameter", o.shape);
    need(o.height, "--height", o.shape);
    for (const auto& [v, name] : {std::pair{o.width, "--width"}, std::pair{o.a, "--a"}, std::pair{o.h, "--h"},
                                  std::pair{o.D, "--D"}}) {
      refuse(v, name, o.shape);
    }
    return naming_options([&] {
      return RockingBody::cylinder(parse_length_m(o.diameter, "--diameter"), parse_length_m(o.height, "--height"));
    });
  }
  if (o.shape == "general") {
    need(o.a, "--a", o.shape);
    need(o.h, "--h", o.shape);
    need(o.D, "--D", o.shape);
    for (const auto& [v, name] : {std::pair{o.width, "--width"}, std::pair{o.height, "--height"},
                                  std::pair{o.diameter, "--diameter"}}) {
      refuse(v, name, o.shape);
    }
    return naming_options([&] {
      return RockingBody::general(parse_length_m(o.a, "--a"), parse_length_m(o.h, "--h"), parse_area_m2(o.D, "--D"));
    });
  }
  if (o.shape.empty()) throw parameter_error("--shape", "the body's shape is required: block, cylinder or general");
  throw parameter_error("--shape", fmt::format("unknown shape '{}' (known: block, cylinder, general)", o.shape));
}

RockingOptions make_options(const RockOptions& o) {
  RockingOptions r;
  r.g_m_s2 = o.motion.g_m_s2;
  if (o.e == "housner") {
    r.restitution = RestitutionMode::housner;
  } else {
    double e = 0.0;
    const auto [ptr, ec] = std::from_chars(o.e.data(), o.e.data() + o.e.size(), e);
    if (ec != std::errc{} || ptr != o.e.data() + o.e.size()) {
      throw parameter_error("--e", fmt::format("'{}' is neither a number in [0, 1] nor 'housner'", o.e));
    }
    r.restitution = RestitutionMode::given;
    r.e = e;
  }
  r.mu = o.mu;
  if (o.method == "adaptive") {
    r.method = RockingMethod::adaptive;
  } else if (o.method == "rk4") {
    r.method = RockingMethod::rk4;
  } else {
    throw parameter_error("--method", fmt::format("unknown method '{}' (known: adaptive, rk4)", o.method));
  }
  if (o.rtol) r.rel_tol = *o.rtol;
  if (o.rk4_substeps) r.rk4_substeps = *o.rk4_substeps;
  if (!o.run_out.empty()) r.max_run_out_s = parse_seconds(o.run_out, "--run-out");
  return r;
}

void write_history_csv(const std::string& path, const RockingHistory& h) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw parameter_error("--out", fmt::format("cannot write '{}'", path));
  out << "time_s,theta_rad,theta_dot_rad_s,state\n";
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    out << fmt::format("{:.9g},{:.12g},{:.12g},{}\n", h.time_s[i], h.theta_rad[i], h.theta_dot_rad_s[i],
                       rocking_state_name(h.state[i]));
  }
  if (!out) throw parameter_error("--out", fmt::format("error while writing '{}'", path));
}

void run_rock(const RockOptions& o) {
  const double g = o.motion.g_m_s2;
  if (!(g > 0.0) || !std::isfinite(g)) throw parameter_error("--g", fmt::format("g must be positive and finite, got {}", g));
  check_plot_path(o.plot);
  const RockingBody body = make_body(o);
  const RockingOptions options = make_options(o);
  const bool from_pulse = !o.pulse.kind.empty();
  if (from_pulse == !o.motion.file.empty()) throw parameter_error("FILE", "give either a record file or --pulse");
  const GroundMotion raw =
      from_pulse ? make_pulse_motion(o.pulse, g) : io::read_motion(o.motion.file, read_options(o.motion));
  const double raw_pga = raw.pga_m_s2();
  const GroundMotion horizontal = transform_motion(raw, o.motion);
  const double factor = raw_pga > 0.0 ? horizontal.pga_m_s2() / raw_pga : 1.0;
  // The vertical component gets the same amplitude factor as the horizontal (scaling scales the whole shaking);
  // --invert flips the horizontal polarity only.
  std::optional<GroundMotion> vertical;
  if (!o.vertical.empty()) vertical = io::read_motion(o.vertical, read_options(o.motion)).scaled(factor);
  const GroundMotion* vertical_ptr = vertical ? &*vertical : nullptr;

  const std::string motion_name = from_pulse ? horizontal.metadata().event : o.motion.file;
  RockingSummary s;
  if (!o.out.empty() || !o.plot.empty()) {
    const RockingResult result = naming_options([&] { return rock(horizontal, body, options, vertical_ptr); });
    if (!o.out.empty()) write_history_csv(o.out, result.history);
    if (!o.plot.empty()) {
      const std::string title = fmt::format("Rocking {}, a = {:.3g} m, h = {:.3g} m, α = {:.3g} rad, e = {:.3g}: {}",
                                            shape_name(body.shape), body.a_m, body.h_m, result.summary.alpha_rad,
                                            result.summary.e, motion_name);
      plot::render(plot::rocking_figure(horizontal, result, body, title, vertical_ptr), o.plot);
    }
    s = result.summary;
  } else {
    s = naming_options([&] { return rock_summary(horizontal, body, options, vertical_ptr); });
  }
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
    nlohmann::ordered_json in;
    in["motion"] = motion_name;
    in["pga_g"] = horizontal.pga_m_s2() / g;
    in["scale_factor"] = factor;
    in["invert"] = o.motion.invert;
    in["vertical"] = o.vertical.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(o.vertical);
    in["npts"] = horizontal.size();
    in["dt_s"] = horizontal.dt_s();
    in["duration_s"] = horizontal.duration_s();
    j["input"] = in;
    fmt::print("{}\n", j.dump(2));
    return;
  }
  fmt::print("rocking body: {} a = {:.6g} m, h = {:.6g} m, D = {:.6g} m2\n", shape_name(body.shape), body.a_m,
             body.h_m, body.D_m2);
  fmt::print("  alpha = {:.6g} rad ({:.4f} deg), R = {:.6g} m, p = {:.6g} rad/s, e = {:.6g} ({}), g = {} m/s2\n",
             s.alpha_rad, s.alpha_rad * 180.0 / kPi, s.R_m, s.p_rad_s, s.e,
             options.restitution == RestitutionMode::housner ? "Housner" : "given", g);
  fmt::print("  uplift threshold {:.5f} g (a/h)\n", body.a_m / body.h_m);
  fmt::print("motion: {} (PGA {:.4f} g, {} samples)\n", motion_name, horizontal.pga_m_s2() / g, horizontal.size());
  fmt::print("max |theta|            {:.6g} rad = {:.6g} alpha at {:.4f} s\n", s.max_abs_rotation_rad,
             s.max_rotation_over_alpha, s.max_rotation_time_s);
  fmt::print("first uplift           {}\n", format_seconds_or_none(s.uplift_time_s));
  fmt::print("uplifts, impacts       {}, {}\n", s.uplifts, s.impacts);
  fmt::print("|theta| > alpha first  {}\n", format_seconds_or_none(s.exceeded_alpha_time_s));
  fmt::print("overturned             {}{}\n", s.overturned ? "yes, at " : "no",
             s.overturned ? format_seconds_or_none(s.overturn_time_s) : std::string());
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
                                       "(--a, --h, --D)");
  cmd->add_option("--width", o->width, "Block width, with a unit (e.g. 4cm)");
  cmd->add_option("--height", o->height, "Block or cylinder height, with a unit (e.g. 0.20m)");
  cmd->add_option("--diameter", o->diameter, "Cylinder diameter, with a unit");
  cmd->add_option("--a", o->a, "General body: horizontal distance from the centre of mass to the pivot edge");
  cmd->add_option("--h", o->h, "General body: height of the centre of mass above the base");
  cmd->add_option("--D", o->D, "General body: pivot moment of inertia per unit mass, with a unit (e.g. 0.011m2)");
  cmd->add_option("--e", o->e, "Coefficient of restitution (angular-velocity ratio at impact) in [0, 1], or "
                               "'housner' (1 - 2a^2/D, from angular momentum)")->capture_default_str();
  cmd->add_option("--mu", o->mu, "Friction coefficient: check Shenton's slide/rock/slide-rock onset criterion");
  cmd->add_option("--vertical", o->vertical, "Vertical acceleration record (positive up), scaled with the horizontal");
  cmd->add_option("--method", o->method, "adaptive (Dormand-Prince with event location) or rk4 (fixed step dt/n, "
                                         "as in the thesis)")->capture_default_str();
  cmd->add_option("--rtol", o->rtol, "Relative tolerance of the adaptive method (default 1e-8)");
  cmd->add_option("--rk4-substeps", o->rk4_substeps, "RK4 steps per sample interval (default 10)");
  cmd->add_option("--run-out", o->run_out, "Longest integration after the record on still ground, s (default 60)");
  cmd->add_option("--out", o->out, "Write the time history to this CSV file (time_s,theta_rad,theta_dot_rad_s,state)");
  cmd->add_option("--plot", o->plot, "Draw record with the uplift levels, theta/alpha with the overturning limits, "
                                     "theta', impacts and the fall, to this .svg or .png file (gnuplot)");
  cmd->add_flag("--json", o->json, "Print the summary as one JSON object");
  cmd->callback([o] { run_rock(*o); });
}

}  // namespace topple::cli
