// Survey file reader (TOML, toml++). Every error names the file, the line when known, and the key path.
#include "topple/io/survey_file.hpp"

#include <cmath>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "topple/core/error.hpp"
#include "topple/bodies/body.hpp"
#include "topple/inversion/inversion.hpp"
#include "topple/io/mesh.hpp"
#include "topple/io/read.hpp"
#include "topple/region/geodesy.hpp"
#include "topple/solvers/flexible.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/survey/population.hpp"
#include "io/mesh_pose_keys.hpp"
#include "io/survey_csv.hpp"

namespace topple {

namespace io {
namespace {

/// Reads one table, remembering which keys were used so that unknown ones are refused (typos must not pass).
class Reader {
 public:
  Reader(const toml::table& table, std::string file, std::string path)
      : table_(table), file_(std::move(file)), path_(std::move(path)) {}

  [[nodiscard]] InputError error(std::string_view key, const std::string& problem, const toml::node* node = nullptr) const {
    std::optional<std::size_t> line;
    const toml::node* at = node != nullptr ? node : table_.get(key);
    if (at != nullptr && at->source().begin.line > 0) line = at->source().begin.line;
    else if (table_.source().begin.line > 0) line = table_.source().begin.line;
    return InputError(InputLocation{file_, line, key.empty() ? path_ : field(key)}, problem);
  }
  [[nodiscard]] std::string field(std::string_view key) const {
    return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
  }
  const toml::node* get(std::string_view key) {
    used_.insert(std::string(key));
    return table_.get(key);
  }
  bool has(std::string_view key) const { return table_.contains(key); }
  [[nodiscard]] const std::string& file() const { return file_; }

  std::optional<std::string> string(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) throw error(key, "expected a string", n);
    return n->as_string()->get();
  }
  std::optional<double> number(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    return as_number(key, *n);
  }
  double as_number(std::string_view key, const toml::node& n) const {
    double v = 0.0;
    if (n.is_floating_point()) v = n.as_floating_point()->get();
    else if (n.is_integer()) v = static_cast<double>(n.as_integer()->get());
    else throw error(key, "expected a number", &n);
    if (!std::isfinite(v)) throw error(key, "must be finite", &n);
    return v;
  }
  /// A value or a two-element range [low, high] (low <= high).
  std::optional<Interval> interval(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (const auto* arr = n->as_array()) {
      if (arr->size() != 2) throw error(key, "a range is [low, high]", n);
      const double lo = as_number(key, *arr->get(0));
      const double hi = as_number(key, *arr->get(1));
      if (lo > hi) throw error(key, fmt::format("range [{}, {}] has low > high", lo, hi), n);
      return Interval{lo, hi};
    }
    const double v = as_number(key, *n);
    return Interval{v, v};
  }
  /// A length string with a unit ("8cm").
  std::optional<double> length(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    if (!n->is_string()) {
      throw error(key, "a length needs its unit: write it as a string such as \"8cm\" or \"0.08m\"", n);
    }
    try {
      return parse_length_m(n->as_string()->get(), field(key));
    } catch (const InputError& e) {
      throw error(key, e.problem(), n);
    }
  }
  /// [min, max, count] of a log-spaced axis.
  std::optional<std::tuple<double, double, int>> axis(std::string_view key) {
    const toml::node* n = get(key);
    if (n == nullptr) return std::nullopt;
    const auto* arr = n->as_array();
    if (arr == nullptr || arr->size() != 3) throw error(key, "expected [min, max, count]", n);
    const double lo = as_number(key, *arr->get(0));
    const double hi = as_number(key, *arr->get(1));
    const double count = as_number(key, *arr->get(2));
    if (!(lo > 0.0) || !(hi > lo)) throw error(key, fmt::format("need 0 < min < max, got [{}, {}]", lo, hi), n);
    if (count < 2 || count > 1000 || count != std::floor(count)) {
      throw error(key, fmt::format("count must be a whole number from 2 to 1000, got {}", count), n);
    }
    return std::tuple{lo, hi, static_cast<int>(count)};
  }
  void refuse_unknown() const {
    for (const auto& [key, node] : table_) {
      if (!used_.contains(std::string(key.str()))) {
        throw error(key.str(), "unknown key (check its spelling in docs/survey.md)", &node);
      }
    }
  }

 private:
  const toml::table& table_;
  std::string file_;
  std::string path_;
  std::set<std::string> used_;
};

Outcome parse_outcome(Reader& r, std::string_view text) {
  for (Outcome o : {Outcome::overturned, Outcome::not_overturned, Outcome::rocked, Outcome::not_rocked, Outcome::slid,
                    Outcome::not_slid, Outcome::slid_stood, Outcome::slid_toppled, Outcome::walked}) {
    if (text == outcome_name(o)) return o;
  }
  // The words a field team writes for a fall (docs/survey.md): aliases of overturned, nothing else.
  if (text == "toppled" || text == "fell") return Outcome::overturned;
  throw r.error("outcome", fmt::format("unknown outcome '{}' (known: overturned (or toppled, fell), not_overturned, "
                                       "rocked, not_rocked, slid, not_slid, slid_stood, slid_toppled, walked)", text));
}

/// A flexible support `{freq_hz = value or [low, high], damping = value or [low, high], name = "..."}` (docs/survey.md):
/// both numbers required (no default damping is guessed), frequency > 0 Hz, damping in [0, 1).
SupportFilter parse_support_filter(const toml::table& t, const std::string& file, const std::string& path,
                                   std::string* name = nullptr) {
  Reader r(t, file, path);
  SupportFilter f;
  const auto freq = r.interval("freq_hz");
  if (!freq) throw r.error("freq_hz", "a flexible support needs its natural frequency freq_hz (Hz, a value or a range)");
  if (!(freq->low > 0.0)) throw r.error("freq_hz", fmt::format("must be positive, got {} Hz", freq->low));
  if (freq->high > SupportOscillator::kMaxFreqHz) {
    // The library's limit (flexible.hpp), said here with the survey's file and line before any record is read.
    throw r.error("freq_hz", fmt::format("{} Hz is above {:g} Hz, where no shelf or floor is: a support that stiff "
                                         "moves with the ground (give the support as text for a rigid one)",
                                         freq->high, SupportOscillator::kMaxFreqHz));
  }
  const auto damping = r.interval("damping");
  if (!damping) throw r.error("damping", "a flexible support needs its damping ratio (decimal: 0.05 is 5 %)");
  if (damping->low < 0.0 || damping->high >= 1.0) {
    throw r.error("damping", fmt::format("the damping ratio must lie in [0, 1), got [{}, {}]", damping->low, damping->high));
  }
  f.freq_hz = *freq;
  f.damping = *damping;
  if (const auto n = r.string("name"); n && name != nullptr) *name = *n;
  r.refuse_unknown();
  return f;
}

/// An object's or a site's `support`: free text (a rigid support, named for the report) or a flexible support table.
/// Returns the filter when it is a table; `label` receives the text (a table's `name`, else "flexible support").
std::optional<SupportFilter> parse_support(Reader& r, std::string& label) {
  const toml::node* n = r.get("support");
  if (n == nullptr) return std::nullopt;
  if (const auto* t = n->as_table()) {
    label = "flexible support";
    const SupportFilter f = parse_support_filter(*t, r.file(), r.field("support"), &label);
    const auto text = [](const Interval& iv) {
      return iv.is_value() ? fmt::format("{:g}", iv.low) : fmt::format("{:g}-{:g}", iv.low, iv.high);
    };
    label += fmt::format(" ({} Hz, damping {})", text(f.freq_hz), text(f.damping));
    return f;
  }
  if (!n->is_string()) {
    throw r.error("support", "expected free text (\"furniture\") or a flexible support {freq_hz = ..., damping = ...}", n);
  }
  label = n->as_string()->get();
  return std::nullopt;
}

/// A bearing (deg clockwise from north) in [0, 360).
double parse_bearing(Reader& r, std::string_view key, double value) {
  if (!(value >= 0.0 && value < 360.0)) {
    throw r.error(key, fmt::format("a bearing must lie in [0, 360) degrees clockwise from north, got {}", value));
  }
  return value;
}

/// The body of an object given as a mesh (docs/survey.md, "Asymmetric bodies and bodies from 3-D scans"): `mesh` (a
/// path relative to the survey file), `mesh_azimuth_deg` (the plane of shaking, as `topple body --azimuth`),
/// optional `mesh_unit` ("m", "cm", "mm"; default "m") and `mesh_density_kg_m3` (checked; it does not change a
/// rocking body), and the pose (bodies/pose.hpp; default: at rest on the stable hull face nearest the scan):
/// `mesh_pose` ("rest" or "as-scanned"), `mesh_up` [x, y, z], `mesh_rotation_wxyz` [w, x, y, z], `mesh_axis_angle_deg`
/// [x, y, z, degrees], `mesh_face` (a number of `topple body --list-faces`), `mesh_contact_tolerance` ("1mm"). The
/// planar body comes from the mesh pipeline (io::read_mesh_body, rocking_body); a refusal names the survey's line and
/// field and the mesh file.
/// The survey key of a BodyOptions option named by check_body_options.
std::string mesh_option_key(const std::string& option) {
  return io_detail::mesh_option_key(option, "mesh_contact_tolerance", "mesh_azimuth_deg");
}

/// The pose keys of a mesh object (checked later by check_body_options, by name).
void read_mesh_pose(Reader& named, BodyOptions& options) {
  if (const auto pose = named.string("mesh_pose")) {
    const auto method = io_detail::mesh_pose_method(*pose);
    if (!method) throw named.error("mesh_pose", io_detail::mesh_pose_problem(*pose));
    options.pose = *method;
  }
  const auto fixed = [&](std::string_view key, std::size_t count, const char* what) -> std::optional<std::vector<double>> {
    const toml::node* n = named.get(key);
    if (n == nullptr) return std::nullopt;
    const auto* arr = n->as_array();
    if (arr == nullptr || arr->size() != count) {
      throw named.error(key, fmt::format("expected {} numbers: {}", count, what), n);
    }
    std::vector<double> v;
    for (const auto& e : *arr) v.push_back(named.as_number(key, e));
    return v;
  };
  io_detail::read_mesh_orientation(options, fixed);
  if (const toml::node* n = named.get("mesh_face")) {
    options.face = io_detail::mesh_face_number(*n);
    if (!options.face) throw named.error("mesh_face", io_detail::kMeshFaceProblem, n);
  }
  if (const auto tol = named.length("mesh_contact_tolerance")) options.contact_tolerance_m = *tol;
}

RockingBody mesh_object_body(Reader& named, const std::filesystem::path& base_dir, ObservedObject& o) {
  for (const char* key : {"width", "height", "diameter", "a", "h", "D", "b1", "b2", "inertia"}) {
    if (named.has(key)) {
      throw named.error(key, "does not apply to a body from a mesh (the mesh gives b1, b2, h and the inertia)");
    }
  }
  const toml::node* mesh_node = named.get("mesh");
  const auto file = named.string("mesh");
  if (!file || file->empty()) throw named.error("mesh", "expected the mesh file's path (.obj, .stl or .ply)", mesh_node);
  const auto azimuth = named.number("mesh_azimuth_deg");
  if (!azimuth) {
    throw named.error("mesh_azimuth_deg", "a body from a mesh needs the azimuth of its plane of shaking, degrees "
                                          "clockwise from the mesh's north (+y)");
  }
  BodyOptions options;
  options.azimuth_deg = *azimuth;
  if (const auto density = named.number("mesh_density_kg_m3")) options.density_kg_m3 = *density;
  read_mesh_pose(named, options);
  double unit_m = 1.0;
  if (const auto unit = named.string("mesh_unit")) {
    try {
      unit_m = mesh_unit_m(*unit, named.field("mesh_unit"));
    } catch (const InputError& e) {
      throw named.error("mesh_unit", e.problem());
    }
  }
  try {
    check_body_options(options);
  } catch (const InputError& e) {
    throw named.error(mesh_option_key(e.where().field), e.problem());
  }
  std::filesystem::path path(*file);
  if (path.is_relative()) path = base_dir / path;
  o.mesh_file = path.string();
  o.mesh_azimuth_deg = options.azimuth_deg;
  try {
    const MeshBody mb = read_mesh_body(path.string(), unit_m, options);
    if (const toml::node* m = named.get("model"); m != nullptr && m->value_or(std::string()) == "3d") {
      // model = "3d": the mesh as posed in three dimensions, turned so that its direction mesh_azimuth_deg (clockwise
      // from its +y) is the body's +x axis: the bearing azimuth_deg then places that direction, as it places the
      // planar section's plane of shaking (the keys keep their meaning).
      o.body_3d = std::make_shared<const RigidBody3D>(
          RigidBody3D::from_mesh(mb).rotated_about_vertical(deg_to_rad(options.azimuth_deg - 90.0)));
    }
    o.mesh_pose = mb.pose.method == PoseMethod::as_scanned
                      ? std::string("as-scanned")
                      : fmt::format("rest on face {} (tilt {:.4g} deg from the scan)", mb.pose.face.value_or(0),
                                    mb.pose.tilt_deg);
    return rocking_body(mb);
  } catch (const InputError& e) {
    if (e.where().field == "--face") throw named.error("mesh_face", fmt::format("mesh '{}': {}", path.string(), e.problem()));
    throw named.error("mesh", fmt::format("mesh '{}' gives no body: {}", path.string(), e.what()), mesh_node);
  }
}

/// What the reader says besides the survey: notes (a documented rule changed a given value) and warnings (a value
/// accepted as given that the user should check), one "file:line: field: text" line each (Survey).
struct ReaderMessages {
  std::vector<std::string>& notes;
  std::vector<std::string>& warnings;
};

/// Calls `check`, a rule of the survey (survey.hpp) that throws parameter_error(field, problem): what it throws is
/// located at this object's key in the file.
template <class F>
auto at_object_keys(const Reader& named, F&& check) -> decltype(check()) {
  try {
    return check();
  } catch (const InputError& e) {
    throw named.error(e.where().field, e.problem());
  }
}

/// `model = "slide" | "rock" | "coupled"` and the rule's refusals (survey.hpp, object_model; docs/survey.md,
/// "Objects that slide and rock"). Needs the body, mu and the outcome.
void parse_object_model(Reader& named, ObservedObject& o, int components, std::vector<std::string>& warnings) {
  if (const auto m = named.string("model")) {
    if (*m == "slide") o.model = ObjectModel::slide;
    else if (*m == "rock") o.model = ObjectModel::rock;
    else if (*m == "coupled") o.model = ObjectModel::coupled;
    else if (*m == "3d") o.model = ObjectModel::three_d;
    else throw named.error("model", fmt::format("unknown model '{}' (known: slide, rock, coupled, 3d)", *m));
  }
  // friction_3d (model = "3d"): the engine's base slides with the object's mu (survey.hpp).
  if (const auto f = named.string("friction_3d")) {
    if (*f == "mu") o.friction_3d = true;
    else if (*f != "none") throw named.error("friction_3d", fmt::format("unknown value '{}' (known: none, mu)", *f));
    if (o.model != ObjectModel::three_d) throw named.error("friction_3d", "friction_3d goes with model = \"3d\"");
  }
  // The survey's rules for the model (survey.hpp, check_object_model), located at this object's keys.
  for (const ObjectCheck& w : at_object_keys(named, [&] { return check_object_model(o, components); })) {
    warnings.push_back(named.error(w.field, w.problem).what());
  }
  // model = "3d": a box's body in three dimensions (a mesh's was made with its body, mesh_object_body), its +x axis
  // (the width) along the bearing, as the oriented box's (oriented.hpp). A cylinder's is its planar body's solid
  // cylinder (inversion_3c.cpp: the rim engine, rigid3d_disc.hpp), with no body_3d.
  if (o.model == ObjectModel::three_d && !o.body_3d && o.body.shape == RockingBody::Shape::block) {
    o.body_3d = std::make_shared<const RigidBody3D>(
        at_object_keys(named, [&] { return RigidBody3D::box(*o.width_m, *o.depth_m, *o.height_m); }));
  }
}

/// The shape an object's keys give. A missing shape is a block (the documented default: old surveys rely on it),
/// unless the keys say otherwise: a diameter, or a/h/D, without a shape would be measured as a block's width only by
/// a dangerous guess. A body from a mesh (`mesh = "..."`) is a general body: its shape may be left out.
std::string object_shape(Reader& named, bool from_mesh) {
  const std::optional<std::string> given_shape = named.string("shape");
  if (!given_shape && !from_mesh) {
    if (named.has("diameter")) {
      throw named.error("shape", "no shape given, but a diameter is: write shape = \"cylinder\" (a missing shape "
                                 "means \"block\", which has a width)");
    }
    if (named.has("a") || named.has("h") || named.has("D")) {
      throw named.error("shape", "no shape given, but a/h/D are: write shape = \"general\" (a missing shape means "
                                 "\"block\", which has a width and a height)");
    }
    if (named.has("b1") || named.has("b2") || named.has("inertia")) {
      throw named.error("shape", "no shape given, but b1/b2/inertia are: write shape = \"general\" (a missing shape "
                                 "means \"block\", which has a width and a height)");
    }
  }
  const std::string shape = given_shape.value_or(from_mesh ? "general" : "block");
  if (!from_mesh) {
    for (const char* key : {"mesh_azimuth_deg", "mesh_unit", "mesh_density_kg_m3", "mesh_pose", "mesh_up",
                            "mesh_rotation_wxyz", "mesh_axis_angle_deg", "mesh_face", "mesh_contact_tolerance"}) {
      if (named.has(key)) throw named.error(key, "goes with mesh = \"file\" (a body from a 3-D scan)");
    }
  }
  return shape;
}

/// A general body's D = I/m: an area with its unit.
double parse_general_D_m2(Reader& named) {
  const toml::node* dn = named.get("D");
  if (dn == nullptr || !dn->is_string()) throw named.error("D", "a general body needs D = I/m with its unit, e.g. \"0.01m2\"");
  std::string dtext = dn->as_string()->get();
  // D is an area (m^2): accept "m2"/"cm2" by converting the length unit's square.
  double factor = 0.0;
  for (const auto& [suffix, f] : {std::pair{"cm2", 1e-4}, std::pair{"mm2", 1e-6}, std::pair{"m2", 1.0}}) {
    if (dtext.size() > std::string_view(suffix).size() &&
        dtext.compare(dtext.size() - std::string_view(suffix).size(), std::string::npos, suffix) == 0) {
      factor = f;
      dtext.resize(dtext.size() - std::string_view(suffix).size());
      break;
    }
  }
  double d = 0.0;
  std::istringstream ss(dtext);
  if (factor == 0.0 || !(ss >> d) || !(d > 0.0)) {
    throw named.error("D", fmt::format("'{}' is not a positive area with unit m2, cm2 or mm2", dn->as_string()->get()), dn);
  }
  return d * factor;
}

/// The object's body, of its shape: from a mesh, an asymmetric general body, a block, a cylinder or a general body.
void parse_object_body(Reader& named, const std::string& shape, bool from_mesh, const std::filesystem::path& base_dir,
                       ObservedObject& o) {
  const auto require = [&](std::string_view key) {
    auto v = named.length(key);
    if (!v) throw named.error(key, fmt::format("a {} needs its {} (a length with unit)", shape, key));
    if (!(*v > 0.0)) throw named.error(key, fmt::format("must be positive, got {} m", *v));
    return *v;
  };
  try {
    if (from_mesh) {
      if (shape != "general") {
        throw named.error("shape", fmt::format("a body from a mesh is a general body: leave shape out or write "
                                               "\"general\", not \"{}\"", shape));
      }
      o.body = mesh_object_body(named, base_dir, o);
    } else if (shape == "general" && (named.has("b1") || named.has("b2") || named.has("inertia"))) {
      // The asymmetric general body (rocking.hpp, general_asymmetric): b1 to the pivot O- (theta < 0), b2 to O+,
      // h, and inertia = I_cm / m, as `topple rock --shape general --b1 --b2 --h --inertia` takes them.
      BodyDimensions d;
      d.b1_m = require("b1");
      d.b2_m = require("b2");
      d.h_m = require("h");
      d.a_m = named.has("a") ? named.length("a") : std::nullopt;  // refused by make_rocking_body, by name
      if (named.has("D")) d.D_m2 = 0.0;                          // likewise
      const toml::node* in = named.get("inertia");
      if (in == nullptr || !in->is_string()) {
        throw named.error("inertia", "an asymmetric general body needs inertia = I_cm/m with its unit, e.g. "
                                     "\"0.004m2\"", in);
      }
      d.inertia_m2 = parse_area_m2(in->as_string()->get(), "inertia");  // located by the catch below
      o.body = make_rocking_body(RockingBody::Shape::general, d);
    } else if (shape == "block") {
      o.width_m = require("width");
      o.height_m = require("height");
      o.body = RockingBody::block(*o.width_m, *o.height_m);
    } else if (shape == "cylinder") {
      o.diameter_m = require("diameter");
      o.height_m = require("height");
      o.body = RockingBody::cylinder(*o.diameter_m, *o.height_m);
    } else if (shape == "general") {
      const double a = require("a");
      const double h = require("h");
      o.body = RockingBody::general(a, h, parse_general_D_m2(named));
    } else {
      throw named.error("shape", fmt::format("unknown shape '{}' (known: block, cylinder, general)", shape));
    }
  } catch (const InputError& e) {
    if (!e.where().file.empty()) throw;
    throw named.error(e.where().field.empty() ? "shape" : e.where().field, e.problem());
  }
}

/// mu (required) and e ("housner", the default, a value or a range).
void parse_friction_and_restitution(Reader& named, ObservedObject& o) {
  const auto mu = named.interval("mu");
  if (!mu) throw named.error("mu", "the friction coefficient is required (a value or a range [low, high])");
  if (mu->low < 0.0) throw named.error("mu", "must be >= 0");
  o.mu = *mu;
  if (const toml::node* e = named.get("e")) {
    if (e->is_string()) {
      if (e->as_string()->get() != "housner") throw named.error("e", "write \"housner\", a value or a range", e);
    } else {
      const auto iv = named.interval("e");
      if (!iv || iv->low < 0.0 || iv->high > 1.0) throw named.error("e", "restitution must lie in [0, 1]", e);
      o.e_housner = false;
      o.e = *iv;
    }
  }
}

/// The largest support amplification a survey may state (parse_object_placement).
constexpr double kMaxAmplification = 10.0;

/// Where the object stands: its support (its own, or the site's flexible one), amplification, orientation to the
/// shaking (one component) or bearing (three), and a box's depth.
void parse_object_placement(Reader& named, ObservedObject& o, const Site* site, int components) {
  if (named.has("support")) {
    o.support_filter = parse_support(named, o.support);
  } else if (site != nullptr && site->support_filter) {
    o.support_filter = site->support_filter;  // the site's default (docs/survey.md)
    o.support = fmt::format("the site's flexible support ({:g}-{:g} Hz)", site->support_filter->freq_hz.low,
                            site->support_filter->freq_hz.high);
  }
  if (const auto amp = named.interval("amplification")) {
    if (!(amp->low > 0.0)) throw named.error("amplification", "must be positive");
    // At most 10 (docs/survey.md, "Support amplification"): the largest tabulated case is an object on flexible
    // furniture at a building's roof, 3 (ASCE/SEI 7-16 Eq. 13.3-1) x 2.5 (a_p, Tables 13.5-1/13.6-1) = 7.5.
    if (amp->high > kMaxAmplification) {
      throw named.error("amplification", fmt::format("must lie in (0, {:g}] (a support amplifies the ground motion at "
                                                     "most 7.5 times: a roof's 3 x flexible furniture's 2.5), got {:g}",
                                                     kMaxAmplification, amp->high));
    }
    o.amplification = *amp;
  }
  if (const auto orient = named.number("orientation_deg")) {
    if (*orient < 0.0 || *orient > 90.0) throw named.error("orientation_deg", "must lie in [0, 90] degrees");
    o.orientation_deg = orient;
  }
  if (components == 3 && o.orientation_deg) {
    throw named.error("orientation_deg", "a three-component survey gives the object's bearing, azimuth_deg, instead "
                                         "(the angle to the shaking is then the inversion's to find)");
  }
  if (const auto az = named.number("azimuth_deg")) {
    if (components != 3) throw named.error("azimuth_deg", "an object's bearing needs [inversion] components = 3");
    at_object_keys(named, [&] { check_object_bearing(o); });
    o.azimuth_deg = parse_bearing(named, "azimuth_deg", *az);
  }
  if (named.has("depth")) {  // a box (oriented.hpp): both horizontal axes rock
    if (components != 3) {
      throw named.error("depth", "a box's depth needs [inversion] components = 3 (one component has one plane of "
                                 "rocking)");
    }
    o.depth_m = named.length("depth");
    if (!(std::isfinite(*o.depth_m) && *o.depth_m > 0.0)) {  // the words of schema.cpp's kDepthProblem, in metres
      throw named.error("depth", fmt::format("depth must be positive and finite, got {}", *o.depth_m));
    }
    try {
      (void)OrientedBody::make(o.body, o.depth_m);  // a block only; positive and finite
    } catch (const InputError& e) {
      throw named.error("depth", e.problem());
    }
  }
}

/// How far and which way the object slid, and which way it fell; the sliding distance's uncertainty floor said.
void parse_object_displacement(Reader& named, ObservedObject& o, int components, ReaderMessages& said) {
  o.slid_m = named.length("slid");
  if (const auto u = named.length("slid_uncertainty")) o.slid_uncertainty_m = *u;
  o.slid_at_least_m = named.length("slid_at_least");
  if ((o.slid_m || o.slid_at_least_m) && o.outcome != Outcome::slid && o.outcome != Outcome::slid_stood) {
    throw named.error(o.slid_m ? "slid" : "slid_at_least",
                      fmt::format("a sliding distance goes with outcome = \"slid\" or \"slid_stood\"{}",
                                  o.outcome == Outcome::walked || o.outcome == Outcome::slid_toppled
                                      ? fmt::format(" (\"{}\" takes none: docs/survey.md)", outcome_name(o.outcome))
                                      : std::string()));
  }
  if (o.slid_m && o.slid_at_least_m) throw named.error("slid_at_least", "give either slid or slid_at_least");
  if (const auto az = named.number("slid_azimuth_deg")) {
    if (components != 3) throw named.error("slid_azimuth_deg", "a sliding direction needs [inversion] components = 3");
    if (o.outcome != Outcome::slid) throw named.error("slid_azimuth_deg", "a sliding direction goes with outcome = \"slid\"");
    o.slid_azimuth_deg = parse_bearing(named, "slid_azimuth_deg", *az);
  }
  if (const auto az = named.number("toppled_azimuth_deg")) {
    if (components != 3) {
      throw named.error("toppled_azimuth_deg", "a fall direction needs [inversion] components = 3");
    }
    at_object_keys(named, [&] { check_object_fall_direction(o); });
    o.toppled_azimuth_deg = parse_bearing(named, "toppled_azimuth_deg", *az);
  }
  if (o.slid_m && !(*o.slid_m > 0.0)) throw named.error("slid", "must be positive");
  if (o.slid_uncertainty_m < 0.0) throw named.error("slid_uncertainty", "must be >= 0");
  if (o.slid_m && named.has("slid_uncertainty") && sliding_sigma_m(o) > o.slid_uncertainty_m) {
    // The documented floor (docs/survey.md): said, so that a given uncertainty is never raised silently.
    const bool given = true;
    said.notes.push_back(named
                        .error(given ? "slid_uncertainty" : "slid",
                               fmt::format("the sliding distance's uncertainty used is {:.3g} cm = max({}25 % of slid, "
                                           "2 mm), the floor stated in docs/survey.md",
                                           100.0 * sliding_sigma_m(o),
                                           given ? fmt::format("the given {:.3g} cm, ", 100.0 * o.slid_uncertainty_m)
                                                 : std::string()))
                        .what());
  }
}

/// `evidence`: how far the outcome of an object (or of a population's members) is to be trusted (survey.hpp, Evidence).
void parse_evidence(Reader& named, ObservedObject& o) {
  if (const auto ev = named.string("evidence")) {
    if (*ev == "certain") o.evidence = Evidence::certain;
    else if (*ev == "likely") o.evidence = Evidence::likely;
    else if (*ev == "reported") o.evidence = Evidence::reported;
    else throw named.error("evidence", fmt::format("unknown evidence '{}' (known: certain, likely, reported)", *ev));
  }
}

ObservedObject parse_object(const toml::table& t, const std::string& file, const std::string& path,
                            ReaderMessages& said, const std::filesystem::path& base_dir,
                            const Site* site = nullptr, int components = 1) {
  Reader r(t, file, path);
  ObservedObject o;
  o.id = r.string("id").value_or("");
  if (o.id.empty()) throw r.error("id", "every object needs an id");
  Reader named(t, file, path + "(" + o.id + ")");
  named.get("id");
  o.description = named.string("description").value_or("");
  const bool from_mesh = named.has("mesh");
  const std::string shape = object_shape(named, from_mesh);
  parse_object_body(named, shape, from_mesh, base_dir, o);
  parse_friction_and_restitution(named, o);
  parse_object_placement(named, o, site, components);
  const auto outcome = named.string("outcome");
  if (!outcome) throw named.error("outcome", "every object needs its observed outcome");
  o.outcome = parse_outcome(named, *outcome);
  parse_object_model(named, o, components, said.warnings);
  // Housner's restitution of a body that strikes (survey.hpp, check_object_restitution).
  at_object_keys(named, [&] { check_object_restitution(o); });
  parse_object_displacement(named, o, components, said);
  parse_evidence(named, o);
  named.refuse_unknown();
  return o;
}

std::vector<ObservedObject> parse_objects(const toml::node* node, const std::string& file, const std::string& key,
                                          ReaderMessages& said, const std::filesystem::path& base_dir,
                                          const Site* site = nullptr, int components = 1) {
  std::vector<ObservedObject> out;
  if (node == nullptr) return out;
  const auto* arr = node->as_array();
  if (arr == nullptr) throw InputError(InputLocation{file, node->source().begin.line, key}, "expected [[" + key + "]] tables");
  std::set<std::string> ids;
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto* t = arr->get(i)->as_table();
    if (t == nullptr) throw InputError(InputLocation{file, node->source().begin.line, key}, "expected a table");
    out.push_back(parse_object(*t, file, fmt::format("{}[{}]", key, i + 1), said, base_dir, site, components));
    if (!ids.insert(out.back().id).second) {
      throw InputError(InputLocation{file, t->source().begin.line, fmt::format("{}[{}].id", key, i + 1)},
                       fmt::format("duplicate object id '{}'", out.back().id));
    }
  }
  return out;
}

// ---- Populations (docs/survey.md, "Populations"; survey/population.hpp) ----

/// A whole, non-negative count (`count`, `overturned`, `rocked`, `slid`, `members`).
std::optional<int> population_count(Reader& named, std::string_view key) {
  const toml::node* n = named.get(key);
  if (n == nullptr) return std::nullopt;
  if (!n->is_integer()) throw named.error(key, "a count is a whole number", n);
  const std::int64_t v = n->as_integer()->get();
  if (v < 0) throw named.error(key, fmt::format("a count cannot be negative, got {}", v), n);
  if (v > 100000000) throw named.error(key, fmt::format("{} is more than topple counts (at most 1e8)", v), n);
  return static_cast<int>(v);
}

/// A length ("1.2m") or a range of two lengths (["0.8m", "1.2m"], low <= high), m.
std::optional<Interval> population_length_range(Reader& named, std::string_view key) {
  const toml::node* n = named.get(key);
  if (n == nullptr) return std::nullopt;
  const auto one = [&](const toml::node& x) {
    if (!x.is_string()) throw named.error(key, "a length needs its unit: write it as a string such as \"1.2m\"", &x);
    try {
      return parse_length_m(x.as_string()->get(), named.field(key));
    } catch (const InputError& e) {
      throw named.error(key, e.problem(), &x);
    }
  };
  if (const auto* arr = n->as_array()) {
    if (arr->size() != 2) throw named.error(key, "a range of sizes is [low, high], e.g. [\"0.8m\", \"1.2m\"]", n);
    const Interval r{one(*arr->get(0)), one(*arr->get(1))};
    if (r.low > r.high) throw named.error(key, fmt::format("range [{}, {}] m has low > high", r.low, r.high), n);
    return r;
  }
  const double v = one(*n);
  return Interval{v, v};
}

/// `sample = [{height = "1.0m", width = "0.45m"}, ...]`: the measured members (an empty list is refused).
std::vector<PopulationMember> population_sample(Reader& named, std::vector<const toml::node*>& nodes) {
  std::vector<PopulationMember> out;
  const toml::node* n = named.get("sample");
  if (n == nullptr) return out;
  const auto* arr = n->as_array();
  if (arr == nullptr) throw named.error("sample", "expected a list of members: [{height = \"...\", width = \"...\"}, ...]", n);
  if (arr->empty()) throw named.error("sample", "the measured sample is empty: give its members, or leave sample out "
                                                "and state the sizes as ranges", n);
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto* t = arr->get(i)->as_table();
    if (t == nullptr) throw named.error("sample", fmt::format("member {} is not a table {{height = ..., ...}}", i + 1), arr->get(i));
    Reader m(*t, named.file(), named.field(fmt::format("sample[{}]", i + 1)));
    PopulationMember member;
    member.width_m = m.length("width");
    member.height_m = m.length("height");
    member.diameter_m = m.length("diameter");
    m.refuse_unknown();
    out.push_back(member);
    nodes.push_back(arr->get(i));
  }
  return out;
}

Population parse_population(const toml::table& t, const std::string& file, const std::string& path, const Site* site,
                            int components) {
  Reader r(t, file, path);
  Population p;
  p.id = r.string("id").value_or("");
  if (p.id.empty()) throw r.error("id", "every population needs an id");
  Reader named(t, file, path + "(" + p.id + ")");
  named.get("id");
  p.line = t.source().begin.line;
  p.description = named.string("description").value_or("");
  p.shape = named.string("shape").value_or("block");
  const auto count = population_count(named, "count");
  if (!count) throw named.error("count", "a population needs its count (how many objects of the class were there)");
  p.count = *count;
  const auto overturned = population_count(named, "overturned");
  if (!overturned) throw named.error("overturned", "a population needs how many overturned (0 if none)");
  p.overturned = *overturned;
  p.rocked = population_count(named, "rocked");
  p.slid = population_count(named, "slid");
  if (const auto members = population_count(named, "members")) p.members = *members;
  if (const toml::node* az = named.get("fallen_azimuths_deg")) {
    const auto* arr = az->as_array();
    if (arr == nullptr) throw named.error("fallen_azimuths_deg", "expected a list of directions in degrees", az);
    for (std::size_t i = 0; i < arr->size(); ++i) p.fallen_azimuths_deg.push_back(named.as_number("fallen_azimuths_deg", *arr->get(i)));
  }
  p.width_m = population_length_range(named, "width");
  p.height_m = population_length_range(named, "height");
  p.diameter_m = population_length_range(named, "diameter");
  std::vector<const toml::node*> sample_nodes;
  p.sample = population_sample(named, sample_nodes);
  // Counts and sizes (survey/population.hpp, check_population), located at the key, or at the sample's member.
  try {
    check_population(p);
  } catch (const InputError& e) {
    const std::string& field = e.where().field;
    if (field.starts_with("sample[")) {
      const std::size_t i = std::stoul(field.substr(7)) - 1;
      throw named.error(field, e.problem(), i < sample_nodes.size() ? sample_nodes[i] : nullptr);
    }
    throw named.error(field, e.problem());
  }
  // The class' shared keys, read as an object's (mu, e, support, amplification, orientation_deg, evidence; with three
  // components the bearing azimuth_deg and a box's depth), on the class' middle member's body.
  ObservedObject& o = p.prototype;
  o.id = p.id;
  o.description = p.description;
  {
    const std::vector<ObservedObject> shape_members = population_members(p);
    o.body = shape_members[shape_members.size() / 2].body;
  }
  parse_friction_and_restitution(named, o);
  parse_object_placement(named, o, site, components);
  parse_evidence(named, o);
  named.refuse_unknown();
  if (components == 3) {
    // Three components (docs/survey.md, "[[population]]"): the counts of overturned and the fall directions; the
    // rocked and slid counts need the one-component models.
    if (p.rocked) throw named.error("rocked", "a population's rocked count needs [inversion] components = 1");
    if (p.slid) throw named.error("slid", "a population's slid count needs [inversion] components = 1");
    if (!p.fallen_azimuths_deg.empty()) {
      ObservedObject fell = o;
      fell.outcome = Outcome::overturned;
      try {
        check_object_fall_direction(fell);
      } catch (const InputError& e) {
        throw named.error("fallen_azimuths_deg", e.problem());
      }
    }
  } else if (!p.fallen_azimuths_deg.empty()) {
    throw named.error("fallen_azimuths_deg", "fall directions need [inversion] components = 3");
  }
  // The restitution check of every member's shape (Housner's e of a squat member).
  for (const ObservedObject& m : population_members(p)) at_object_keys(named, [&] { check_object_restitution(m); });
  return p;
}

std::vector<Population> parse_populations(const toml::node* node, const std::string& file, const std::string& key,
                                          const Site* site, int components) {
  std::vector<Population> out;
  if (node == nullptr) return out;
  const auto* arr = node->as_array();
  if (arr == nullptr) throw InputError(InputLocation{file, node->source().begin.line, key}, "expected [[" + key + "]] tables");
  std::set<std::string> ids;
  for (const ObservedObject& o : site->objects) ids.insert(o.id);
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const auto* t = arr->get(i)->as_table();
    if (t == nullptr) throw InputError(InputLocation{file, node->source().begin.line, key}, "expected a table");
    out.push_back(parse_population(*t, file, fmt::format("{}[{}]", key, i + 1), site, components));
    if (!ids.insert(out.back().id).second) {
      throw InputError(InputLocation{file, t->source().begin.line, fmt::format("{}[{}].id", key, i + 1)},
                       fmt::format("duplicate id '{}' (objects and populations share one list of ids)", out.back().id));
    }
  }
  return out;
}

/// A site's instrument (docs/survey.md, "Regional surveys"): `pga_g = value` (g, > 0) or `record = "file"` (checked
/// to exist here, read by load_survey_records), not both. A measured PGA is at most the records' limit (100 g,
/// GroundMotionLimits::max_record_accel_m_s2). In a three-component survey the PGA axis is RotD50, which one record
/// file (one component) cannot give: such a station gives its RotD50 as pga_g (docs/survey.md, "Regional surveys").
void parse_instrument(Reader& r, Site& site, const std::filesystem::path& base_dir, int components) {
  if (r.has("pga_g") && r.has("record")) throw r.error("record", "give either pga_g (measured) or record, not both");
  if (const auto pga = r.number("pga_g")) {
    if (!(*pga > 0.0)) throw r.error("pga_g", fmt::format("a measured PGA must be positive, got {} g", *pga));
    constexpr double kMaxG = GroundMotionLimits::max_record_accel_m_s2 / kStandardGravity;
    if (*pga > kMaxG) {
      throw r.error("pga_g", fmt::format("a measured PGA is at most {:g} g (the limit records have), got {} g{}", kMaxG,
                                         *pga, site.name.empty() ? "" : fmt::format(" at site '{}'", site.name)));
    }
    site.instrument_pga_g = pga;
  }
  if (components == 3 && r.has("record")) {
    throw r.error("record", fmt::format("{}a station record is one component, and components = 3 estimates RotD50 "
                                        "(the median over rotation angles of the two horizontal components): its "
                                        "peak is not RotD50; give the station's RotD50 as pga_g instead",
                                        site.name.empty() ? "" : fmt::format("site '{}': ", site.name)));
  }
  if (const auto rec = r.string("record")) {
    std::filesystem::path p(*rec);
    if (p.is_relative()) p = base_dir / p;
    if (!std::filesystem::exists(p)) throw r.error("record", fmt::format("no such record file '{}'", p.string()));
    site.instrument_record = p.string();
  }
}

/// A site's macroseismic intensity (docs/survey.md, "Macroseismic intensity"; issue 30): `intensity` (1-12),
/// `intensity_scale` ("MMI" or "EMS-98"; default "MMI"), `intensity_reports` (an integer >= 1, the reports behind
/// it). The scale and the reports go with an intensity. JMA is refused by name: no sourced conversion to PGA.
void parse_intensity(Reader& r, Site& site) {
  const auto value = r.number("intensity");
  const auto scale = r.string("intensity_scale");
  const toml::node* reports = r.get("intensity_reports");
  if (!value) {
    if (scale) throw r.error("intensity_scale", "an intensity_scale goes with an intensity = value");
    if (reports != nullptr) throw r.error("intensity_reports", "intensity_reports go with an intensity = value");
    return;
  }
  if (!(*value >= 1.0 && *value <= 12.0)) {
    throw r.error("intensity", fmt::format("a macroseismic intensity lies in [1, 12], got {}", *value));
  }
  SiteIntensity in;
  in.value = *value;
  if (scale) {
    if (*scale == "MMI") in.scale = IntensityScale::mmi;
    else if (*scale == "EMS-98") in.scale = IntensityScale::ems98;
    else if (*scale == "JMA") {
      throw r.error("intensity_scale", "JMA intensities are not supported: topple has no sourced conversion from the "
                                       "JMA scale to PGA (known: MMI, EMS-98)");
    } else {
      throw r.error("intensity_scale", fmt::format("unknown intensity scale '{}' (known: MMI, EMS-98)", *scale));
    }
  }
  if (reports != nullptr) {
    const auto* i = reports->as_integer();
    if (i == nullptr) throw r.error("intensity_reports", "expected a whole number of reports", reports);
    // 10^8: more reports than any felt-report system holds for one place; bounds the int below.
    if (i->get() < 1 || i->get() > 100000000) {
      throw r.error("intensity_reports",
                    fmt::format("the number of reports must lie in [1, 100000000], got {}", i->get()), reports);
    }
    in.reports = static_cast<int>(i->get());
  }
  site.intensity = in;
}

void parse_site_fields(Reader& r, Site& site) {
  site.name = r.string("name").value_or("");
  site.lat_deg = r.number("lat");
  site.lon_deg = r.number("lon");
  site.notes = r.string("notes").value_or("");
  if (site.lat_deg && std::abs(*site.lat_deg) > 90.0) throw r.error("lat", "latitude must lie in [-90, 90]");
  if (site.lon_deg && std::abs(*site.lon_deg) > 180.0) throw r.error("lon", "longitude must lie in [-180, 180]");
  // The site's Vs30 for the earthquake prior (inversion/prior.hpp): given, or a NEHRP site class mapped to a stated
  // value (docs/survey.md): A 1500, B 1070, C 525, D 255 m/s (the geometric means of the class bounds 760-1500,
  // 360-760, 180-360), E 150 m/s.
  if (const auto v = r.number("vs30_m_s")) {
    if (!(*v >= 100.0 && *v <= 3000.0)) {
      throw r.error("vs30_m_s", fmt::format("must lie in [100, 3000] m/s, got {}", *v));
    }
    site.vs30_m_s = v;
  }
  if (const auto cls = r.string("site_class")) {
    if (site.vs30_m_s) throw r.error("site_class", "give either vs30_m_s or site_class, not both");
    static constexpr std::pair<std::string_view, double> kClasses[] = {
        {"A", 1500.0}, {"B", 1070.0}, {"C", 525.0}, {"D", 255.0}, {"E", 150.0}};
    for (const auto& [label, vs30] : kClasses) {
      if (*cls == label) site.vs30_m_s = vs30;
    }
    if (!site.vs30_m_s) {
      throw r.error("site_class", fmt::format("unknown site class '{}' (known: A, B, C, D, E)", *cls));
    }
  }
  // A site's support is a default for its objects: only a flexible support table makes sense there.
  if (const toml::node* n = r.get("support"); n != nullptr && !n->is_table()) {
    throw r.error("support", "a site's default support is a flexible support {freq_hz = ..., damping = ...}", n);
  }
  std::string label;
  site.support_filter = parse_support(r, label);
}

/// How the record files are read (records, and the sites' instrument records): record_format, record_units,
/// record_dt_s, record_columns (the --columns text, or [time, accel] with numbers or header names, "" for no time
/// column), record_separator, record_baseline. Each is checked here, at its line; the files are read by
/// load_survey_records.
void parse_record_options(Reader& r, InversionSettings& st) {
  const auto checked = [&](std::string_view key, auto parse) {
    const auto v = r.string(key);
    if (!v) return std::string();
    try {
      (void)parse(*v, "inversion." + std::string(key));
    } catch (const InputError& e) {
      throw r.error(key, e.problem());
    }
    return *v;
  };
  st.record_format = checked("record_format", [](const std::string& v, const std::string& f) {
    return parse_format_name(v, f);
  });
  st.record_units = checked("record_units", [](const std::string& v, const std::string& f) {
    return acceleration_unit_factor(v, f, kStandardGravity);
  });
  st.record_separator = checked("record_separator", [](const std::string& v, const std::string& f) {
    return parse_separator(v, f);
  });
  st.record_baseline = checked("record_baseline", [](const std::string& v, const std::string& f) {
    return parse_baseline(v, f);
  });
  if (const auto dt = r.number("record_dt_s")) {
    if (!(*dt > 0.0)) throw r.error("record_dt_s", fmt::format("must be positive, got {} s", *dt));
    st.record_dt_s = dt;
  }
  if (const toml::node* n = r.get("record_columns")) {
    std::string text;
    if (const auto* str = n->as_string()) {
      text = str->get();
    } else if (const auto* a = n->as_array(); a != nullptr && a->size() == 2) {
      for (std::size_t k = 0; k < 2; ++k) {
        const toml::node& e = *a->get(k);
        std::string part;
        if (const auto* i = e.as_integer()) {
          if (i->get() < 1 || i->get() > 100000) {
            throw r.error("record_columns", fmt::format("column numbers start at 1, got {}", i->get()), &e);
          }
          part = std::to_string(i->get());
        } else if (const auto* name = e.as_string(); name != nullptr && name->get().find('"') == std::string::npos) {
          if (!name->get().empty()) part = "\"" + name->get() + "\"";
        } else {
          throw r.error("record_columns", "expected a column number or a header name (without double quotes)", &e);
        }
        text += (k == 0 ? "" : ",") + part;
      }
    } else {
      throw r.error("record_columns", "expected [time, acceleration] (\"\" for no time column) or \"TIME,ACCEL\"", n);
    }
    try {
      (void)parse_columns(text, "inversion.record_columns");
    } catch (const InputError& e) {
      throw r.error("record_columns", e.problem(), n);
    }
    st.record_columns = text;
  }
}

/// The [inversion] table: the motion family, its grid and the number of components, checked by the inversion's own
/// rule (validate_inversion_settings) and located here.
void parse_inversion_table(const toml::table& t, const std::string& name, const std::filesystem::path& base_dir,
                           InversionSettings& st) {
  Reader r(t, name, "inversion");
  if (const auto fam = r.string("family")) {
    if (*fam == "synthetic") st.family = MotionFamily::synthetic;
    else if (*fam == "records") st.family = MotionFamily::records;
    else if (*fam == "rezaeian2010") st.family = MotionFamily::rezaeian2010;
    else if (*fam == "boore2003") st.family = MotionFamily::boore2003;
    else if (*fam == "mixture") st.family = MotionFamily::mixture;
    else throw r.error("family", fmt::format("unknown family '{}' (known: synthetic, records, rezaeian2010, boore2003, "
                                             "mixture)",
                                             *fam));
  }
  if (const toml::node* rec = r.get("records")) {
    const auto* arr = rec->as_array();
    if (arr == nullptr) throw r.error("records", "expected a list of file paths", rec);
    for (const auto& item : *arr) {
      if (!item.is_string()) throw r.error("records", "expected file paths (strings)", &item);
      std::filesystem::path p(item.as_string()->get());
      if (p.is_relative()) p = base_dir / p;
      if (!std::filesystem::exists(p)) throw r.error("records", fmt::format("no such record file '{}'", p.string()), &item);
      st.records.push_back(p.string());  // loaded by load_survey_records (read_survey): parsing reads no file
    }
  }
  if (st.family == MotionFamily::records && st.records.empty()) {
    throw r.error("records", "family = \"records\" needs records = [\"file\", ...]");
  }
  parse_record_options(r, st);
  if (const auto ax = r.axis("pga_g")) std::tie(st.pga_min_g, st.pga_max_g, st.pga_count) = *ax;
  if (const auto ax = r.axis("freq_hz")) std::tie(st.freq_min_hz, st.freq_max_hz, st.freq_count) = *ax;
  if (const auto n = r.number("motions_per_cell")) {
    if (*n < 1 || *n > 100000 || *n != std::floor(*n)) throw r.error("motions_per_cell", "must be a whole number >= 1");
    st.motions_per_cell = static_cast<int>(*n);
  }
  if (const auto seed = r.number("seed")) {
    if (*seed < 0 || *seed != std::floor(*seed)) throw r.error("seed", "must be a whole number >= 0");
    st.seed = static_cast<std::uint64_t>(*seed);
  }
  if (const auto d = r.number("duration_s")) {
    if (!(*d > 0.0)) throw r.error("duration_s", "must be positive");
    st.duration_s = *d;
  }
  if (const auto g = r.number("g_m_s2")) {
    if (!(*g > 0.0)) throw r.error("g_m_s2", "must be positive");
    st.g_m_s2 = *g;
  }
  if (const auto c = r.number("components")) {
    if (*c != 1.0 && *c != 3.0) throw r.error("components", fmt::format("must be 1 or 3, got {}", *c));
    st.components = static_cast<int>(*c);
  }
  if (st.components == 3 && st.family != MotionFamily::synthetic) {
    throw r.error("components", fmt::format("components = 3 needs family = \"synthetic\" (got \"{}\")",
                                            motion_family_name(st.family)));
  }
  if (const auto rho = r.number("coherence")) {
    if (st.components != 3) throw r.error("coherence", "coherence needs components = 3");
    if (!(*rho >= 0.0 && *rho <= 0.95)) throw r.error("coherence", fmt::format("must lie in [0, 0.95], got {}", *rho));
    st.coherence = *rho;
  }
  if (const auto nd = r.number("directions")) {
    if (st.components != 3) throw r.error("directions", "directions needs components = 3");
    if (*nd < 4 || *nd > 72 || *nd != std::floor(*nd)) {
      throw r.error("directions", fmt::format("must be a whole number from 4 to 72, got {}", *nd));
    }
    st.directions = static_cast<int>(*nd);
  }
  if (const auto prior = r.string("prior")) {
    if (*prior == "log-uniform") st.prior = InversionPrior::log_uniform;
    else if (*prior == "earthquake") st.prior = InversionPrior::earthquake;
    else throw r.error("prior", fmt::format("unknown prior '{}' (known: log-uniform, earthquake)", *prior));
  }
  // The family must be able to make motions at both ends of the grid: said here, with the file and the line,
  // rather than by the synthesis after the survey is read.
  try {
    validate_inversion_settings(st);
  } catch (const InputError& e) {
    const std::string field = e.where().field;
    const std::string key = field.rfind("inversion.", 0) == 0 ? field.substr(10) : "freq_hz";
    throw r.error(key, e.problem(), r.has(key) ? t.get(key) : nullptr);
  }
  r.refuse_unknown();
}

/// The [event] table: the epicentre and its depth.
void parse_event_table(const toml::table& t, const std::string& name, Survey& s) {
  Reader r(t, name, "event");
  if (const toml::node* epi = r.get("epicentre")) {
    const auto* arr = epi->as_array();
    if (arr == nullptr || arr->size() != 2) throw r.error("epicentre", "expected [lat, lon]", epi);
    s.epicentre_lat_deg = r.as_number("epicentre", *arr->get(0));
    s.epicentre_lon_deg = r.as_number("epicentre", *arr->get(1));
    if (std::abs(*s.epicentre_lat_deg) > 90.0) throw r.error("epicentre", "latitude must lie in [-90, 90]", epi);
    if (std::abs(*s.epicentre_lon_deg) > 180.0) throw r.error("epicentre", "longitude must lie in [-180, 180]", epi);
  }
  if (const auto depth = r.number("depth_km")) {
    if (!s.epicentre_lat_deg) throw r.error("depth_km", "a depth goes with epicentre = [lat, lon]");
    if (*depth < 0.0 || *depth > 700.0) throw r.error("depth_km", fmt::format("must lie in [0, 700] km, got {}", *depth));
    s.epicentre_depth_km = depth;
  }
  // The magnitude, for the earthquake prior (inversion/prior.hpp): BSSA14 and the period model hold for shallow
  // crustal events of about M 3 to 8.5.
  if (const auto m = r.number("magnitude")) {
    if (!(*m >= 3.0 && *m <= 8.5)) {
      throw r.error("magnitude", fmt::format("must lie in [3, 8.5] (BSSA14's range), got {}", *m));
    }
    s.inversion.event = EventSource{*m, s.epicentre_depth_km.value_or(0.0)};
  }
  r.refuse_unknown();
}

/// The sites: one [site] with its [[object]] tables, or [[sites]] each with its own.
void parse_sites(Reader& top, const std::string& name, const std::filesystem::path& base_dir, Survey& s) {
  ReaderMessages said{s.notes, s.warnings};
  const bool single = top.has("site") || top.has("object") || top.has("population");
  if (single && top.has("sites")) throw top.error("sites", "use either [site] with [[object]] or [[sites]], not both");
  if (single) {
    Site site;
    if (const toml::node* st = top.get("site")) {
      const auto* t = st->as_table();
      if (t == nullptr) throw top.error("site", "expected a table");
      Reader r(*t, name, "site");
      parse_site_fields(r, site);
      parse_instrument(r, site, base_dir, s.inversion.components);
      parse_intensity(r, site);
      r.refuse_unknown();
    }
    site.objects =
        parse_objects(top.get("object"), name, "object", said, base_dir, &site, s.inversion.components);
    site.populations = parse_populations(top.get("population"), name, "population", &site, s.inversion.components);
    s.sites.push_back(std::move(site));
  } else if (const toml::node* sites = top.get("sites")) {
    const auto* arr = sites->as_array();
    if (arr == nullptr) throw top.error("sites", "expected [[sites]] tables");
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const auto* t = arr->get(i)->as_table();
      if (t == nullptr) throw top.error("sites", "expected a table");
      Reader r(*t, name, fmt::format("sites[{}]", i + 1));
      Site site;
      parse_site_fields(r, site);
      parse_instrument(r, site, base_dir, s.inversion.components);
      parse_intensity(r, site);
      site.objects = parse_objects(r.get("object"), name, fmt::format("sites[{}].object", i + 1), said, base_dir,
                                   &site, s.inversion.components);
      site.populations = parse_populations(r.get("population"), name, fmt::format("sites[{}].population", i + 1),
                                           &site, s.inversion.components);
      r.refuse_unknown();
      s.sites.push_back(std::move(site));
    }
  }
}

/// Every site has objects or is an instrument station (while some site has objects), and a name.
void check_sites(const std::string& name, Survey& s) {
  if (s.sites.empty()) throw InputError(InputLocation{name, {}, "object"}, "the survey has no site and no object");
  bool any_objects = false;
  for (const Site& site : s.sites) any_objects = any_objects || site.has_observations();
  for (std::size_t i = 0; i < s.sites.size(); ++i) {
    // An instrument station may have no objects (docs/survey.md), as long as some site has objects to invert.
    // So may an intensity site (issue 30): it too enters the regional fit only.
    const bool evidence = s.sites[i].is_station() || s.sites[i].intensity.has_value();
    if (!s.sites[i].has_observations() && !(evidence && any_objects)) {
      throw InputError(InputLocation{name, {}, s.sites.size() == 1 ? "object" : fmt::format("sites[{}].object", i + 1)},
                       evidence ? "the survey has no site with observed objects to invert"
                                : "a site needs at least one observed object (or an instrument: pga_g or record; or "
                                  "a macroseismic intensity)");
    }
    // The documented default (docs/survey.md): a site without a name is "site N", N its position in the file.
    if (s.sites[i].name.empty()) s.sites[i].name = fmt::format("site {}", i + 1);
  }
}

Survey parse_toml_survey(std::string_view text, const std::string& name, const std::filesystem::path& base_dir) {
  toml::table root;
  try {
    root = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    throw InputError(InputLocation{name, static_cast<std::size_t>(e.source().begin.line), {}},
                     std::string(e.description()));
  }
  Survey s;
  s.source_file = name;
  Reader top(root, name, "");
  if (const toml::node* inv = top.get("inversion")) {
    const auto* t = inv->as_table();
    if (t == nullptr) throw top.error("inversion", "expected a table");
    parse_inversion_table(*t, name, base_dir, s.inversion);
  }
  if (const toml::node* ev = top.get("event")) {
    const auto* t = ev->as_table();
    if (t == nullptr) throw top.error("event", "expected a table");
    parse_event_table(*t, name, s);
  }
  parse_sites(top, name, base_dir, s);
  top.refuse_unknown();
  check_sites(name, s);
  // Each site's epicentral distance (the earthquake prior's R_JB for a point source), where both ends are known.
  if (s.epicentre_lat_deg && s.epicentre_lon_deg) {
    for (Site& site : s.sites) {
      if (site.lat_deg && site.lon_deg) {
        site.epicentral_distance_km =
            geodesic_distance_km(*s.epicentre_lat_deg, *s.epicentre_lon_deg, *site.lat_deg, *site.lon_deg);
      }
    }
  }
  return s;
}

}  // namespace

Survey parse_survey(std::string_view text, const std::string& name, const std::filesystem::path& base_dir) {
  if (!detail::is_csv_survey(text, name)) return parse_toml_survey(text, name, base_dir);
  // A CSV survey is read as the TOML survey it stands for (one reader, one set of rules), its errors and notes
  // placed back at the CSV's line and column.
  const detail::CsvSurveyText csv = detail::csv_survey_to_toml(text, name);
  Survey s;
  try {
    s = parse_toml_survey(csv.toml, name, base_dir);
  } catch (const InputError& e) {
    throw detail::relocate_csv_error(e, csv, name);
  }
  for (std::string& note : s.notes) note = detail::relocate_csv_note(note, csv, name);
  for (std::string& warning : s.warnings) warning = detail::relocate_csv_note(warning, csv, name);
  return s;
}

namespace {

/// The ReadOptions the [inversion] record_* keys give (checked when parsed; empty keys: the reader's defaults).
ReadOptions survey_read_options(const InversionSettings& st) {
  ReadOptions o;
  if (!st.record_format.empty()) o.format = parse_format_name(st.record_format, "inversion.record_format");
  o.units = st.record_units;
  o.dt_s = st.record_dt_s;
  if (!st.record_columns.empty()) o.columns = parse_columns(st.record_columns, "inversion.record_columns");
  if (!st.record_separator.empty()) o.separator = parse_separator(st.record_separator, "inversion.record_separator");
  if (!st.record_baseline.empty()) o.baseline = parse_baseline(st.record_baseline, "inversion.record_baseline");
  return o;
}

/// read_motion, the reader's option names (--columns, ...) given as the survey's keys, the record's file and line kept.
GroundMotion read_survey_record(const std::string& path, const ReadOptions& o) {
  try {
    return read_motion(path, o);
  } catch (const InputError& e) {
    static const std::pair<const char*, const char*> names[] = {
        {"--format", "inversion.record_format"},       {"--units", "inversion.record_units"},
        {"--dt", "inversion.record_dt_s"},             {"--columns", "inversion.record_columns"},
        {"--separator", "inversion.record_separator"}, {"--baseline", "inversion.record_baseline"}};
    for (const auto& [option, key] : names) {
      if (e.where().field == option) {
        InputLocation at = e.where();
        at.field = key;
        throw InputError(std::move(at), e.problem());
      }
    }
    throw;
  }
}

/// Where a record is named in the survey: `inversion.records` (item `item`) or a site's `record` (site `site`).
struct RecordKey {
  std::optional<std::size_t> site;  ///< index into survey.sites; none: inversion.records
  std::size_t item = 0;             ///< index into inversion.records
};

/// The survey field that names the record ("sites[2].record", "site.record", "inversion.records") and its line in
/// `text` (the survey's own text; a CSV survey's line through its TOML rewrite). Only on the error path: the text is
/// parsed again; no line when it is not at hand.
std::pair<std::string, std::optional<std::size_t>> record_key_location(std::optional<std::string_view> text,
                                                                       const std::string& name, const RecordKey& key) {
  std::string field = key.site ? "site.record" : "inversion.records";
  if (!text) return {field, std::nullopt};
  try {
    const bool csv = detail::is_csv_survey(*text, name);
    std::optional<detail::CsvSurveyText> rewritten;
    if (csv) rewritten = detail::csv_survey_to_toml(*text, name);
    const toml::table root = toml::parse(csv ? std::string_view(rewritten->toml) : *text, name);
    const toml::node* node = nullptr;
    if (!key.site) {
      node = root.at_path("inversion.records").node();
      if (const auto* arr = node ? node->as_array() : nullptr; arr != nullptr && key.item < arr->size()) {
        node = arr->get(key.item);
      }
    } else if (const auto* sites = root.get_as<toml::array>("sites")) {
      field = fmt::format("sites[{}].record", *key.site + 1);
      if (const auto* t = *key.site < sites->size() ? sites->get(*key.site)->as_table() : nullptr) node = t->get("record");
    } else {
      node = root.at_path("site.record").node();
    }
    if (node == nullptr || node->source().begin.line == 0) return {field, std::nullopt};
    std::size_t line = node->source().begin.line;
    if (csv) {
      if (line > rewritten->origins.size()) return {field, std::nullopt};
      line = rewritten->origins[line - 1].line;
    }
    return {field, line};
  } catch (const std::exception&) {  // the text parsed once already: no line rather than a second error
    return {field, std::nullopt};
  }
}

/// Loads the records; a record that does not read is named where the survey names it: the survey file, the line, the
/// field (`sites[N].record`, `inversion.records`), the site, then the record reader's own message (its file, line and
/// field).
void load_records(Survey& survey, std::optional<std::string_view> text) {
  InversionSettings& st = survey.inversion;
  const ReadOptions options = survey_read_options(st);
  const auto read = [&](const std::string& path, const RecordKey& key) {
    try {
      return read_survey_record(path, options);
    } catch (const InputError& e) {
      const auto survey_keys = [](std::string said) {  // the reader's advice names its CLI option: the survey's key
        for (std::size_t at = said.find("--columns"); at != std::string::npos; at = said.find("--columns", at)) {
          said.replace(at, 9, "[inversion] record_columns");
        }
        return said;
      };
      // An [inversion] record_* key that does not fit the record already names the key to change (at the record's
      // line, or the survey's): kept where it is.
      if (e.where().field.starts_with("inversion.record_")) throw InputError(e.where(), survey_keys(e.problem()));
      auto [field, line] = record_key_location(text, survey.source_file, key);
      const std::string site = key.site ? fmt::format("site '{}': ", survey.sites[*key.site].name) : std::string();
      const std::string said = survey_keys(e.what());
      throw InputError(InputLocation{survey.source_file, line, std::move(field)},
                       fmt::format("{}the record '{}' cannot be used: {}", site, path, said));
    }
  };
  st.record_motions.clear();
  for (std::size_t j = 0; j < st.records.size(); ++j) {
    st.record_motions.push_back(std::make_shared<const GroundMotion>(read(st.records[j], RecordKey{std::nullopt, j})));
  }
  // An instrument station's record gives its measured PGA (the record's peak |a|, in g).
  for (std::size_t i = 0; i < survey.sites.size(); ++i) {
    Site& site = survey.sites[i];
    if (site.instrument_record.empty()) continue;
    site.instrument_pga_g = read(site.instrument_record, RecordKey{i, 0}).pga_m_s2() / st.g_m_s2;
  }
}

}  // namespace

void load_survey_records(Survey& survey) { load_records(survey, std::nullopt); }

Survey read_survey(const std::filesystem::path& path) {
  const std::string text = read_input_file(path, "survey");
  Survey survey = parse_survey(text, path.string(), path.parent_path());
  load_records(survey, text);
  return survey;
}

}  // namespace io
}  // namespace topple
