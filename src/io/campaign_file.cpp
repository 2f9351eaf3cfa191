// Campaign files (TOML, toml++) into ensemble::CampaignSettings and CampaignTests. See campaign_file.hpp and
// docs/campaign.md.
#include "topple/io/campaign_file.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/io/mesh.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "io/mesh_pose_keys.hpp"
#include "io/toml_reader.hpp"

namespace topple::io {
namespace {

namespace fs = std::filesystem;

using io_detail::toml_type_name;

/// Reads one campaign file; every error names the file, the line and the key (io_detail::TomlReader); what only a
/// campaign file reads: numbers, positive numbers, file names.
class Reader : public io_detail::TomlReader {
 public:
  using TomlReader::TomlReader;

  [[nodiscard]] std::optional<double> number(const toml::table& t, std::string_view key, const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    double v = 0.0;
    if (const auto* i = n->as_integer()) {
      v = static_cast<double>(i->get());
    } else if (const auto* f = n->as_floating_point()) {
      v = f->get();
    } else {
      fail(n, field, fmt::format("expected a number, got {}", toml_type_name(*n)));
    }
    if (!std::isfinite(v)) fail(n, field, fmt::format("must be finite, got {}", v));
    return v;
  }

  [[nodiscard]] double positive(const toml::table& t, std::string_view key, const std::string& field) const {
    const auto v = number(t, key, field);
    if (!v) fail(&t, field, fmt::format("missing: the {} is required", key));
    if (!(*v > 0.0)) fail(t.get(key), field, fmt::format("must be > 0, got {}", *v));
    return *v;
  }

  /// A file named by `key`, relative to the campaign file's directory.
  [[nodiscard]] std::optional<fs::path> file(const toml::table& t, std::string_view key, const std::string& field,
                                             const std::string& id, bool check) const {
    const auto name = string(t, key, field);
    if (!name) return std::nullopt;
    if (name->empty()) fail(t.get(key), field, fmt::format("test '{}': the file name is empty", id));
    if (name->find_first_of("\r\n") != std::string::npos) fail(t.get(key), field, "a file name holds a line break");
    const fs::path p = fs::path(*name).is_absolute() ? fs::path(*name) : dir() / *name;
    std::error_code ec;
    if (check && !fs::is_regular_file(p, ec)) {
      fail(t.get(key), field, fmt::format("test '{}': file '{}' not found{}", id, p.string(),
                                          fs::exists(p, ec) ? " (not a regular file)" : ""));
    }
    return p;
  }
};

/// format, units, dt_s: in [campaign] (every test's default) or in a test.
void read_record_keys(const Reader& r, const toml::table& t, const std::string& prefix, double g, ReadOptions& ro) {
  io_detail::read_record_format_and_units(r, t, prefix, g, ro);
  if (const auto dt = r.number(t, "dt_s", prefix + "dt_s")) {
    if (!(*dt > 0.0)) r.fail(t.get("dt_s"), prefix + "dt_s", fmt::format("must be > 0, got {}", *dt));
    ro.dt_s = dt;
  }
}

/// The mesh pose keys (the sweep file's names: docs/sweeps.md): mesh_pose, mesh_up, mesh_rotation_wxyz,
/// mesh_axis_angle_deg, mesh_face, mesh_contact_tolerance_m.
void read_mesh_pose(const Reader& r, const toml::table& t, const std::string& prefix, BodyOptions& options) {
  if (const auto pose = r.string(t, "mesh_pose", prefix + "mesh_pose")) {
    const auto method = io_detail::mesh_pose_method(*pose);
    if (!method) r.fail(t.get("mesh_pose"), prefix + "mesh_pose", io_detail::mesh_pose_problem(*pose));
    options.pose = *method;
  }
  const auto fixed = [&](std::string_view key, std::size_t count, const char* what) -> std::optional<std::vector<double>> {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const auto* a = n->as_array();
    if (a == nullptr || a->size() != count) {
      r.fail(n, prefix + std::string(key), fmt::format("expected a list of {} numbers: {}", count, what));
    }
    std::vector<double> v;
    for (std::size_t k = 0; k < count; ++k) {
      const toml::node& e = *a->get(k);
      if (const auto* i = e.as_integer()) v.push_back(static_cast<double>(i->get()));
      else if (const auto* f = e.as_floating_point()) v.push_back(f->get());
      else r.fail(&e, prefix + std::string(key), fmt::format("expected a number, got {}", toml_type_name(e)));
    }
    return v;
  };
  io_detail::read_mesh_orientation(options, fixed);
  if (const toml::node* n = t.get("mesh_face")) {
    options.face = io_detail::mesh_face_number(*n);
    if (!options.face) r.fail(n, prefix + "mesh_face", io_detail::kMeshFaceProblem);
  }
  if (const auto tol = r.number(t, "mesh_contact_tolerance_m", prefix + "mesh_contact_tolerance_m")) {
    options.contact_tolerance_m = *tol;
  }
  // check_body_options names its option (--up, --face, ...): the key of this file instead.
  try {
    check_body_options(options);
  } catch (const InputError& e) {
    const std::string key = io_detail::mesh_option_key(e.where().field, "mesh_contact_tolerance_m", "mesh");
    r.fail(t.get(key) != nullptr ? t.get(key) : &t, prefix + key, e.problem());
  }
}

void read_settings(const Reader& r, const toml::table& root, CampaignFile& out, ReadOptions& defaults,
                   double& default_mesh_unit_m) {
  ensemble::CampaignSettings& s = out.settings;
  s.name = out.path.stem().string();
  const toml::node* cn = root.get("campaign");
  if (cn == nullptr) return;
  const toml::table* c = cn->as_table();
  if (c == nullptr) r.fail(cn, "campaign", fmt::format("expected a table [campaign], got {}", toml_type_name(*cn)));
  r.check_keys(*c, "campaign", {"name", "description", "models", "mu", "mu_k", "restitution", "g_m_s2", "format",
                                "units", "dt_s", "mesh_unit"});
  if (const auto name = r.string(*c, "name", "campaign.name")) s.name = *name;
  static_cast<void>(r.string(*c, "description", "campaign.description"));
  if (const toml::node* mn = c->get("models")) {
    const auto* a = mn->as_array();
    if (a == nullptr || a->empty()) r.fail(mn, "campaign.models", "expected a non-empty list such as [\"planar\", \"3d\"]");
    s.models.clear();
    for (std::size_t k = 0; k < a->size(); ++k) {
      const toml::node& e = *a->get(k);
      const auto* str = e.as_string();
      if (str == nullptr) r.fail(&e, "campaign.models", fmt::format("expected a model name, got {}", toml_type_name(e)));
      const auto m = r.located(&e, "campaign.models", [&] { return ensemble::parse_campaign_model(str->get()); });
      if (std::find(s.models.begin(), s.models.end(), m) != s.models.end()) {
        r.fail(&e, "campaign.models", fmt::format("model '{}' listed twice", str->get()));
      }
      s.models.push_back(m);
    }
  }
  s.mu = r.number(*c, "mu", "campaign.mu");
  if (s.mu && *s.mu < 0.0) r.fail(c->get("mu"), "campaign.mu", fmt::format("must be >= 0, got {}", *s.mu));
  s.mu_k = r.number(*c, "mu_k", "campaign.mu_k");
  if (s.mu_k) {
    if (!s.mu) r.fail(c->get("mu_k"), "campaign.mu_k", "needs mu (the static friction coefficient)");
    if (*s.mu_k < 0.0 || *s.mu_k > *s.mu) {
      r.fail(c->get("mu_k"), "campaign.mu_k", fmt::format("must be in [0, mu = {}], got {}", *s.mu, *s.mu_k));
    }
  }
  const bool coupled = std::find(s.models.begin(), s.models.end(), ensemble::CampaignModel::coupled) != s.models.end();
  if (coupled && !s.mu) r.fail(c->get("models"), "campaign.models", "the model 'coupled' needs mu (add mu = ...)");
  if (const toml::node* en = c->get("restitution")) {
    if (const auto* str = en->as_string()) {
      if (str->get() != "housner") {
        r.fail(en, "campaign.restitution", fmt::format("expected \"housner\" or a number in [0, 1], got '{}'", str->get()));
      }
    } else {
      const auto e = r.number(*c, "restitution", "campaign.restitution");
      if (*e < 0.0 || *e > 1.0) r.fail(en, "campaign.restitution", fmt::format("must be in [0, 1], got {}", *e));
      s.restitution = RestitutionMode::given;
      s.e = *e;
    }
  }
  if (const auto g = r.number(*c, "g_m_s2", "campaign.g_m_s2")) {
    if (!(*g > 0.0)) r.fail(c->get("g_m_s2"), "campaign.g_m_s2", fmt::format("must be > 0, got {}", *g));
    s.g_m_s2 = *g;
  }
  defaults.g_m_s2 = s.g_m_s2;
  read_record_keys(r, *c, "campaign.", s.g_m_s2, defaults);
  if (const auto u = r.string(*c, "mesh_unit", "campaign.mesh_unit")) {
    default_mesh_unit_m =
        r.located(c->get("mesh_unit"), "campaign.mesh_unit", [&] { return mesh_unit_m(*u, "mesh_unit"); });
  }
}

void read_test(const Reader& r, const toml::table& t, std::size_t number, bool check, const ReadOptions& defaults,
               double default_mesh_unit_m, CampaignFile& out) {
  const std::string prefix = fmt::format("test[{}].", number);
  r.check_keys(t, fmt::format("test[{}]", number),
               {"id", "mesh", "mesh_unit", "mesh_pose", "mesh_up", "mesh_rotation_wxyz", "mesh_axis_angle_deg",
                "mesh_face", "mesh_contact_tolerance_m", "block", "cylinder", "x", "y", "z", "format", "units", "dt_s",
                "scale", "bearing_deg", "observed", "observed_azimuth_deg"});
  ensemble::CampaignTest test;
  CampaignTestFiles files;
  files.line = io_detail::toml_line(&t);
  const auto id = r.string(t, "id", prefix + "id");
  if (!id || id->empty()) r.fail(id ? t.get("id") : &t, prefix + "id", "every test needs a non-empty id");
  if (id->find_first_of("\r\n,\"") != std::string::npos) {
    r.fail(t.get("id"), prefix + "id", "an id holds a line break, a comma or a double quote (it is a CSV field)");
  }
  test.id = *id;
  // The body: exactly one of mesh, block, cylinder.
  const int bodies = (t.get("mesh") ? 1 : 0) + (t.get("block") ? 1 : 0) + (t.get("cylinder") ? 1 : 0);
  if (bodies != 1) {
    r.fail(&t, prefix + "body", fmt::format("test '{}': give exactly one body: mesh = \"file\", block = {{width_m, "
                                            "depth_m, height_m}} or cylinder = {{diameter_m, height_m}} (got {})",
                                            test.id, bodies));
  }
  const bool mesh = t.get("mesh") != nullptr;
  for (const char* key : {"mesh_unit", "mesh_pose", "mesh_up", "mesh_rotation_wxyz", "mesh_axis_angle_deg",
                          "mesh_face", "mesh_contact_tolerance_m"}) {
    if (!mesh && t.get(key) != nullptr) r.fail(t.get(key), prefix + key, "applies to a mesh body only");
  }
  if (mesh) {
    files.mesh_line = io_detail::toml_line(t.get("mesh"));
    test.body = ensemble::CampaignMesh{r.file(t, "mesh", prefix + "mesh", test.id, check)->string()};
    files.mesh_unit_m = default_mesh_unit_m;
    if (const auto u = r.string(t, "mesh_unit", prefix + "mesh_unit")) {
      files.mesh_unit_m = r.located(t.get("mesh_unit"), prefix + "mesh_unit", [&] { return mesh_unit_m(*u, "mesh_unit"); });
    }
    read_mesh_pose(r, t, prefix, files.body);
  } else {
    const bool block = t.get("block") != nullptr;
    const std::string key = block ? "block" : "cylinder";
    const toml::node* bn = t.get(key);
    const toml::table* b = bn->as_table();
    if (b == nullptr) r.fail(bn, prefix + key, fmt::format("expected an inline table, got {}", toml_type_name(*bn)));
    const std::string p = prefix + key + ".";
    if (block) {
      r.check_keys(*b, prefix + key, {"width_m", "depth_m", "height_m"});
      ensemble::CampaignBlock k{r.positive(*b, "width_m", p + "width_m"), r.positive(*b, "depth_m", p + "depth_m"),
                                r.positive(*b, "height_m", p + "height_m")};
      // The 3-D engine's own limits (dimensions at most kMaxBodyDimension_m), named by its field.
      try {
        static_cast<void>(RigidBody3D::box(k.width_m, k.depth_m, k.height_m));
      } catch (const InputError& e) {
        const std::string f = e.where().field + "_m";
        r.fail(b->get(f) != nullptr ? b->get(f) : bn, p + f, e.problem());
      }
      test.body = k;
    } else {
      r.check_keys(*b, prefix + key, {"diameter_m", "height_m"});
      ensemble::CampaignCylinder k{r.positive(*b, "diameter_m", p + "diameter_m"),
                                   r.positive(*b, "height_m", p + "height_m")};
      try {
        static_cast<void>(CylinderBody3D::solid(k.diameter_m, k.height_m));
      } catch (const InputError& e) {
        const std::string f = e.where().field + "_m";
        r.fail(b->get(f) != nullptr ? b->get(f) : bn, p + f, e.problem());
      }
      test.body = k;
    }
  }
  // The table's motion.
  const auto x = r.file(t, "x", prefix + "x", test.id, check);
  if (!x) r.fail(&t, prefix + "x", fmt::format("test '{}': the table's x record is required (x = \"file\")", test.id));
  files.x = *x;
  files.x_line = io_detail::toml_line(t.get("x"));
  if (const auto y = r.file(t, "y", prefix + "y", test.id, check)) {
    files.y = *y;
    files.y_line = io_detail::toml_line(t.get("y"));
  }
  if (const auto z = r.file(t, "z", prefix + "z", test.id, check)) {
    files.z = *z;
    files.z_line = io_detail::toml_line(t.get("z"));
  }
  files.read = defaults;
  read_record_keys(r, t, prefix, defaults.g_m_s2, files.read);
  if (const auto s = r.number(t, "scale", prefix + "scale")) {
    if (!(*s > 0.0)) r.fail(t.get("scale"), prefix + "scale", fmt::format("must be > 0, got {}", *s));
    files.scale = *s;
  }
  if (const auto b = r.number(t, "bearing_deg", prefix + "bearing_deg")) test.bearing_deg = *b;
  // The outcome observed: read here, used only to score (campaign.hpp).
  const auto observed = r.string(t, "observed", prefix + "observed");
  if (!observed) {
    r.fail(&t, prefix + "observed", fmt::format("test '{}': the outcome observed is required: observed = "
                                                "\"overturned\" or \"standing\"", test.id));
  }
  if (*observed == "overturned") {
    test.observed_overturned = true;
  } else if (*observed != "standing") {
    r.fail(t.get("observed"), prefix + "observed",
           fmt::format("expected \"overturned\" or \"standing\", got '{}'", *observed));
  }
  if (const auto a = r.number(t, "observed_azimuth_deg", prefix + "observed_azimuth_deg")) {
    if (!test.observed_overturned) {
      r.fail(t.get("observed_azimuth_deg"), prefix + "observed_azimuth_deg",
             "is the direction of an observed fall: the test is observed standing");
    }
    test.observed_azimuth_deg = a;
  }
  out.tests.push_back(std::move(test));
  out.files.push_back(std::move(files));
}

}  // namespace

CampaignFile parse_campaign_file(std::string_view text, const fs::path& path, bool check_files) {
  const std::string file = path.string();
  check_input_text(text, file);
  toml::table root;
  try {
    root = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::optional<std::size_t> line;
    if (e.source().begin.line > 0) line = e.source().begin.line;
    throw InputError(InputLocation{file, line, ""}, fmt::format("not valid TOML: {}", e.description()));
  }
  const Reader r(file, path.parent_path());
  r.check_keys(root, "", {"campaign", "test"});
  CampaignFile out;
  out.path = path;
  ReadOptions defaults;
  double mesh_unit = 1.0;
  read_settings(r, root, out, defaults, mesh_unit);
  const toml::node* tn = root.get("test");
  const toml::array* tests = tn != nullptr ? tn->as_array() : nullptr;
  if (tn != nullptr && (tests == nullptr || !tests->is_array_of_tables())) {
    r.fail(tn, "test", "expected [[test]] tables");
  }
  if (tests == nullptr || tests->empty()) r.fail(nullptr, "test", "the campaign has no [[test]]");
  std::map<std::string, std::size_t> ids;
  for (std::size_t i = 0; i < tests->size(); ++i) {
    const toml::table& t = *tests->get(i)->as_table();
    read_test(r, t, i + 1, check_files, defaults, mesh_unit, out);
    const auto [it, fresh] = ids.emplace(out.tests.back().id, i + 1);
    if (!fresh) {
      r.fail(t.get("id"), fmt::format("test[{}].id", i + 1),
             fmt::format("id '{}' is already test[{}]'s", out.tests.back().id, it->second));
    }
  }
  return out;
}

CampaignFile read_campaign_file(const fs::path& path) {
  return parse_campaign_file(read_input_file(path, "campaign"), path);
}

ensemble::CampaignInput load_campaign_input(const CampaignFile& campaign, std::size_t i) {
  const ensemble::CampaignTest& test = campaign.tests.at(i);
  const CampaignTestFiles& f = campaign.files.at(i);
  const std::string file = campaign.path.string();
  const auto located = [&](const char* key, const std::optional<std::size_t>& line, auto fn) {
    try {
      return fn();
    } catch (const InputError& e) {
      throw InputError(InputLocation{file, line, fmt::format("test[{}].{}", i + 1, key)},
                       fmt::format("test '{}': {}", test.id, e.what()));
    }
  };
  const auto record = [&](const fs::path& p, const char* key, const std::optional<std::size_t>& line) {
    return located(key, line, [&] {
      GroundMotion m = read_motion(p, f.read);
      return f.scale == 1.0 ? m : m.scaled(f.scale);
    });
  };
  ensemble::CampaignInput in{record(f.x, "x", f.x_line), std::nullopt, std::nullopt, std::nullopt};
  if (!f.y.empty()) in.y = record(f.y, "y", f.y_line);
  if (!f.z.empty()) in.z = record(f.z, "z", f.z_line);
  if (const auto* m = std::get_if<ensemble::CampaignMesh>(&test.body)) {
    BodyOptions options = f.body;
    options.g_m_s2 = campaign.settings.g_m_s2;
    in.mesh = located("mesh", f.mesh_line, [&] { return read_mesh_body(m->path, f.mesh_unit_m, options); });
  }
  return in;
}

}  // namespace topple::io
