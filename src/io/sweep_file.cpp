// Sweep files (TOML, toml++) into an ensemble::SweepSpec. See sweep_file.hpp and docs/sweeps.md.
#include "topple/io/sweep_file.hpp"

#include <glob.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <oneapi/tbb/parallel_for.h>
#include <toml++/toml.h>

#include "topple/bodies/body.hpp"
#include "topple/core/error.hpp"
#include "topple/io/mesh.hpp"
#include "topple/io/read.hpp"
#include "topple/motion/motion_set.hpp"
#include "topple/solvers/oriented.hpp"
#include "topple/solvers/rigid3d.hpp"
#include "topple/solvers/rigid3d_disc.hpp"
#include "topple/motion/pulses.hpp"
#include "topple/core/units.hpp"
#include "io/mesh_pose_keys.hpp"
#include "io/toml_reader.hpp"

namespace topple::io {
namespace fs = std::filesystem;
namespace {

using Parser = std::function<double(std::string_view text, const std::string& field)>;

using io_detail::toml_type_name;

std::optional<double> number_of(const toml::node& n) {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) return f->get();
  return std::nullopt;
}

/// Reads one sweep file; every error names the file, the line and the key (io_detail::TomlReader); what only a
/// sweep file reads: values as one, a list or a range, quantities with units, record file patterns.
class Reader : public io_detail::TomlReader {
 public:
  using TomlReader::TomlReader;

  /// Numbers: a number, a list of numbers or a range table. Empty when the key is absent.
  [[nodiscard]] std::optional<std::vector<double>> numbers(const toml::table& t, std::string_view key,
                                                           const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    if (const auto x = number_of(*n)) return std::vector<double>{*x};
    if (const auto* a = n->as_array()) {
      if (a->empty()) fail(n, field, "empty list: give at least one value");
      std::vector<double> out;
      for (const auto& e : *a) {
        const auto x = number_of(e);
        if (!x) fail(&e, field, fmt::format("expected numbers in the list, got {}", toml_type_name(e)));
        out.push_back(*x);
      }
      return out;
    }
    if (const auto* r = n->as_table()) {
      return range(*r, field, [&](const toml::node& e, const std::string& f) -> double {
        const auto x = number_of(e);
        if (!x) fail(&e, f, fmt::format("expected a number, got {}", toml_type_name(e)));
        return *x;
      });
    }
    fail(n, field, fmt::format("expected a number, a list of numbers or a range table {{from, to, count}}, got {}",
                               toml_type_name(*n)));
  }

  /// A dimensional parameter: `unit_key` (e.g. "width_m") takes numbers in that unit, `plain_key` (e.g. "width")
  /// strings with a unit, converted by `parse` to the same unit. Empty when both are absent.
  [[nodiscard]] std::optional<std::vector<double>> quantities(const toml::table& t, std::string_view unit_key,
                                                              std::string_view plain_key, const std::string& prefix,
                                                              const Parser& parse, std::string_view example) const {
    const std::string unit_field = prefix + std::string(unit_key);
    const std::string plain_field = prefix + std::string(plain_key);
    const toml::node* plain = t.get(plain_key);
    if (plain != nullptr && t.get(unit_key) != nullptr) {
      fail(plain, plain_field, fmt::format("give either {} or {}, not both", plain_key, unit_key));
    }
    if (plain == nullptr) return numbers(t, unit_key, unit_field);
    const auto one = [&](const toml::node& e) -> double {
      if (const auto* s = e.as_string()) return located(&e, plain_field, [&] { return parse(s->get(), plain_field); });
      if (const auto x = number_of(e)) {
        fail(&e, plain_field, fmt::format("{} has no unit: write it as a string with one (e.g. \"{}\"), or use {} "
                                          "for a plain number", *x, example, unit_key));
      }
      fail(&e, plain_field, fmt::format("expected a string with a unit (e.g. \"{}\"), got {}", example, toml_type_name(e)));
    };
    if (const auto* a = plain->as_array()) {
      if (a->empty()) fail(plain, plain_field, "empty list: give at least one value");
      std::vector<double> out;
      for (const auto& e : *a) out.push_back(one(e));
      return out;
    }
    if (const auto* r = plain->as_table()) {
      return range(*r, plain_field, [&](const toml::node& e, const std::string&) { return one(e); });
    }
    return std::vector<double>{one(*plain)};
  }

  /// Strings: a string or a list of strings.
  [[nodiscard]] std::optional<std::vector<std::string>> strings(const toml::table& t, std::string_view key,
                                                                const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    if (const auto* s = n->as_string()) return std::vector<std::string>{s->get()};
    if (const auto* a = n->as_array()) {
      if (a->empty()) fail(n, field, "empty list: give at least one value");
      std::vector<std::string> out;
      for (const auto& e : *a) {
        const auto* s = e.as_string();
        if (s == nullptr) fail(&e, field, fmt::format("expected strings in the list, got {}", toml_type_name(e)));
        out.push_back(s->get());
      }
      return out;
    }
    fail(n, field, fmt::format("expected a string or a list of strings, got {}", toml_type_name(*n)));
  }

  [[nodiscard]] std::optional<std::int64_t> integer(const toml::table& t, std::string_view key,
                                                    const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const auto* i = n->as_integer();
    if (i == nullptr) fail(n, field, fmt::format("expected an integer, got {}", toml_type_name(*n)));
    return i->get();
  }

  [[nodiscard]] std::optional<bool> boolean(const toml::table& t, std::string_view key, const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const auto* b = n->as_boolean();
    if (b == nullptr) fail(n, field, fmt::format("expected true or false, got {}", toml_type_name(*n)));
    return b->get();
  }

  /// A single dimensional value (no list): unit key or plain key.
  [[nodiscard]] std::optional<double> quantity(const toml::table& t, std::string_view unit_key,
                                               std::string_view plain_key, const std::string& prefix,
                                               const Parser& parse, std::string_view example) const {
    const auto v = quantities(t, unit_key, plain_key, prefix, parse, example);
    if (!v) return std::nullopt;
    if (v->size() != 1) {
      const toml::node* n = t.get(plain_key) != nullptr ? t.get(plain_key) : t.get(unit_key);
      fail(n, prefix + std::string(t.get(plain_key) != nullptr ? plain_key : unit_key), "expected a single value");
    }
    return v->front();
  }

  /// A range table {from, to, count | step, spacing = "linear" | "log"}; `value` reads from, to and step.
  template <class V>
  std::vector<double> range(const toml::table& r, const std::string& field, V value) const {
    check_keys(r, field, {"from", "to", "count", "step", "spacing"});
    const toml::node* from_n = r.get("from");
    const toml::node* to_n = r.get("to");
    if (from_n == nullptr || to_n == nullptr) fail(&r, field, "a range needs 'from' and 'to'");
    const double from = value(*from_n, field);
    const double to = value(*to_n, field);
    const auto spacing = string(r, "spacing", field + ".spacing").value_or("linear");
    if (spacing != "linear" && spacing != "log") {
      fail(r.get("spacing"), field + ".spacing", fmt::format("unknown spacing '{}' (known: linear, log)", spacing));
    }
    const toml::node* step_n = r.get("step");
    const auto count = integer(r, "count", field + ".count");
    if ((step_n != nullptr) == count.has_value()) fail(&r, field, "a range needs exactly one of 'count' and 'step'");
    if (to < from) fail(&r, field, fmt::format("empty range: 'to' ({}) is below 'from' ({})", to, from));
    std::vector<double> out;
    if (count) {
      if (*count < 1) fail(r.get("count"), field, fmt::format("empty range: count = {}", *count));
      if (*count > 100'000'000) fail(r.get("count"), field, fmt::format("count = {} is too large", *count));
      const auto n = static_cast<std::size_t>(*count);
      if (n > 1 && to == from) fail(&r, field, "range with count > 1 but 'to' equal to 'from'");
      if (spacing == "log" && !(from > 0.0)) fail(&r, field, "a log range needs 'from' > 0");
      for (std::size_t i = 0; i < n; ++i) {
        const double f = n == 1 ? 0.0 : static_cast<double>(i) / static_cast<double>(n - 1);
        double x = spacing == "log" ? from * std::pow(to / from, f) : from + (to - from) * f;
        if (i == 0) x = from;
        if (n > 1 && i + 1 == n) x = to;
        out.push_back(x);
      }
    } else {
      if (spacing == "log") fail(step_n, field, "a log range takes 'count', not 'step'");
      const double step = value(*step_n, field);
      if (!(step > 0.0) || !std::isfinite(step)) fail(step_n, field, fmt::format("step must be > 0, got {}", step));
      // Points from + i step up to 'to', which counts when within 1e-9 steps of a point (round-off).
      const double span = (to - from) / step;
      if (span > 1e8) fail(step_n, field, fmt::format("{} values is too many", span));
      const auto n = static_cast<std::size_t>(std::floor(span + 1e-9)) + 1;
      for (std::size_t i = 0; i < n; ++i) out.push_back(from + static_cast<double>(i) * step);
    }
    return out;
  }

  /// Glob patterns (relative to the sweep file's directory) to files, in pattern order, each pattern's matches
  /// sorted by name (bytes), each file once.
  [[nodiscard]] std::vector<std::pair<std::string, fs::path>> files(const toml::table& motions) const {
    std::vector<std::pair<std::string, fs::path>> out;
    const toml::node* n = motions.get("files");
    if (n == nullptr) return out;
    const auto patterns = strings(motions, "files", "motions.files");
    std::set<std::string> seen;
    const auto* arr = n->as_array();
    for (std::size_t i = 0; i < patterns->size(); ++i) {
      const std::string& pattern = (*patterns)[i];
      const toml::node* where = arr != nullptr ? arr->get(i) : n;
      const std::string field = arr != nullptr ? fmt::format("motions.files[{}]", i + 1) : "motions.files";
      if (pattern.empty()) fail(where, field, "empty file pattern");
      const bool absolute = fs::path(pattern).is_absolute();
      std::string prefix;
      std::size_t plain_prefix_size = 0;  // the prefix without its escapes: what glob's matches start with
      if (!absolute && !dir().empty()) {
        plain_prefix_size = dir().string().size() + 1;
        for (const char c : dir().string()) {
          if (c == '*' || c == '?' || c == '[' || c == '\\' || c == '{') prefix += '\\';
          prefix += c;
        }
        prefix += '/';
      }
      const std::string full = prefix + pattern;
      glob_t g{};
      const int rc = ::glob(full.c_str(), GLOB_MARK | GLOB_NOSORT | GLOB_BRACE, nullptr, &g);
      std::vector<std::string> matches;
      if (rc == 0) {
        for (std::size_t k = 0; k < g.gl_pathc; ++k) matches.emplace_back(g.gl_pathv[k]);
      }
      globfree(&g);
      if (rc == GLOB_ABORTED) fail(where, field, fmt::format("cannot read a directory while matching '{}'", pattern));
      const bool literal = pattern.find_first_of("*?[{") == std::string::npos;
      if (rc == GLOB_NOMATCH || matches.empty()) {
        if (literal) fail(where, field, fmt::format("no such record file '{}' (looked for '{}')", pattern, full));
        fail(where, field, fmt::format("'{}' matches no file (looked for '{}')", pattern, full));
      }
      std::sort(matches.begin(), matches.end());
      std::size_t kept = 0;
      for (const auto& m : matches) {
        if (!m.empty() && m.back() == '/') continue;  // a directory the pattern also matched
        const std::string name = m.substr(plain_prefix_size);
        if (name.find_first_of("\r\n") != std::string::npos) fail(where, field, "a file name holds a line break");
        ++kept;
        if (!seen.insert(fs::path(m).lexically_normal().string()).second) continue;
        out.emplace_back(name, fs::path(m));
      }
      if (kept == 0) fail(where, field, fmt::format("'{}' matches only directories", pattern));
    }
    return out;
  }
};

Parser length_parser() { return [](std::string_view s, const std::string& f) { return parse_length_m(s, f); }; }
Parser duration_parser() { return [](std::string_view s, const std::string& f) { return parse_duration_s(s, f); }; }
Parser frequency_parser() { return [](std::string_view s, const std::string& f) { return parse_frequency_hz(s, f); }; }
Parser area_parser() { return [](std::string_view s, const std::string& f) { return parse_area_m2(s, f); }; }
Parser angle_deg_parser() {
  return [](std::string_view s, const std::string& f) { return rad_to_deg(parse_angle_rad(s, f)); };
}
Parser acceleration_parser(double g, double divide_by) {
  return [g, divide_by](std::string_view s, const std::string& f) { return parse_acceleration_m_s2(s, f, g) / divide_by; };
}

/// read_motion with the reader's option names (--columns, --separator, --baseline) given as this file's keys, the
/// record's file and line kept.
GroundMotion read_sweep_record(const fs::path& path, const ReadOptions& ro) {
  try {
    return read_motion(path, ro);
  } catch (const InputError& e) {
    for (const std::string_view key : {"columns", "separator", "baseline"}) {
      if (e.where().field == "--" + std::string(key)) {
        InputLocation at = e.where();
        at.field = "motions." + std::string(key);
        throw InputError(std::move(at), e.problem());
      }
    }
    throw;
  }
}

/// [[motions.set]] tables (a station's components, read together) and the objects' bearings under them.
void read_record_sets(const Reader& r, const toml::table& m, const ReadOptions& ro, SweepFile& out) {
  if (const auto b = r.quantities(m, "bearing_deg", "bearing", "motions.", angle_deg_parser(), "45deg")) {
    if (m.get("set") == nullptr) {
      r.fail(m.get("bearing") != nullptr ? m.get("bearing") : m.get("bearing_deg"), "motions.bearing_deg",
             "bearings apply to objects under [[motions.set]] (two horizontal components), and there is none");
    }
    out.spec.bearings_deg = *b;
  }
  if (const auto step = r.numbers(m, "direction_step_deg", "motions.direction_step_deg")) {
    if (step->size() != 1) r.fail(m.get("direction_step_deg"), "motions.direction_step_deg", "expected one value");
    out.spec.orientation.cylinder_step_deg = step->front();
    r.located(m.get("direction_step_deg"), "motions.direction_step_deg", [&] {
      return oriented_directions(OrientedBody::planar(RockingBody::cylinder(1.0, 1.0)), 0.0, out.spec.orientation);
    });
  }
  const toml::node* sn = m.get("set");
  if (sn == nullptr) return;
  const auto* arr = sn->as_array();
  if (arr == nullptr || !arr->is_array_of_tables()) r.fail(sn, "motions.set", "expected [[motions.set]] tables");
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table& t = *arr->get(i)->as_table();
    const std::string key = fmt::format("motions.set[{}]", i + 1);
    r.check_keys(t, key, {"h1", "h2", "vertical", "azimuths_deg"});
    const auto path_of = [&](std::string_view k, bool required) -> std::optional<std::string> {
      const auto p = r.string(t, k, key + "." + std::string(k));
      if (!p && required) r.fail(&t, key + "." + std::string(k), fmt::format("a record set needs {}", k));
      if (p && p->empty()) r.fail(t.get(k), key + "." + std::string(k), "empty path");
      return p;
    };
    const std::string h1 = *path_of("h1", true);
    const std::string h2 = *path_of("h2", true);
    const std::optional<std::string> vertical = path_of("vertical", false);
    const auto read = [&](const std::string& name) {
      const fs::path p(name);
      return read_sweep_record(p.is_absolute() || r.dir().empty() ? p : r.dir() / p, ro);
    };
    const GroundMotion first = read(h1);
    const GroundMotion second = read(h2);
    const std::optional<GroundMotion> up = vertical ? std::optional(read(*vertical)) : std::nullopt;
    std::optional<ComponentAzimuths> user;
    if (const auto az = r.numbers(t, "azimuths_deg", key + ".azimuths_deg")) {
      if (az->size() != 2) {
        r.fail(t.get("azimuths_deg"), key + ".azimuths_deg", "expected the two azimuths [A1, A2], degrees clockwise "
                                                             "from north");
      }
      user = ComponentAzimuths{(*az)[0], (*az)[1]};
    }
    const toml::node* where = t.get("azimuths_deg") != nullptr ? t.get("azimuths_deg") : &t;
    const ComponentAzimuths azimuths = r.located(where, key + ".azimuths_deg", [&] {
      return resolve_azimuths(first, second, user, out.warnings, key + ".azimuths_deg");
    });
    const auto set = r.located(&t, key, [&] {
      return std::make_shared<const MotionSet>(
          MotionSet::make(first, &second, azimuths, up ? &*up : nullptr));
    });
    std::string name = h1 + "+" + h2 + (vertical ? "+" + *vertical : std::string());
    if (name.find_first_of("\r\n") != std::string::npos) r.fail(&t, key, "a file name holds a line break");
    out.spec.record_sets.push_back({std::move(name), set});
  }
}

/// The options for reading the record files of [motions] (format, units, dt, channel, columns, separator, baseline).
ReadOptions read_record_options(const Reader& r, const toml::table& m, double g) {
  ReadOptions ro;
  ro.g_m_s2 = g;
  io_detail::read_record_format_and_units(r, m, "motions.", g, ro);
  ro.dt_s = r.quantity(m, "dt_s", "dt", "motions.", duration_parser(), "0.01s");
  if (ro.dt_s && !(*ro.dt_s > 0.0)) r.fail(m.get("dt") ? m.get("dt") : m.get("dt_s"), "motions.dt", "must be > 0");
  if (const auto c = r.integer(m, "channel", "motions.channel")) {
    if (*c < 1 || *c > 1000) r.fail(m.get("channel"), "motions.channel", fmt::format("must be >= 1, got {}", *c));
    ro.channel = static_cast<int>(*c);
  }
  // Plain records as recorded (docs/sweeps.md): columns = ["Time (s)", "Table Acc (g)"], [1, 2], ["", 3] (no time
  // column) or the --columns text "1,2"; separator = "tab"; baseline = "pre-event:2".
  if (const toml::node* n = m.get("columns")) {
    const std::string field = "motions.columns";
    std::string text;
    if (const auto* s = n->as_string()) {
      text = s->get();
    } else if (const auto* a = n->as_array()) {
      if (a->size() != 2) {
        r.fail(n, field, fmt::format("expected [time, acceleration] (2 columns; \"\" for no time column), got {} "
                                     "element{}",
                                     a->size(), a->size() == 1 ? "" : "s"));
      }
      for (std::size_t k = 0; k < 2; ++k) {
        const toml::node& e = *a->get(k);
        std::string part;
        if (const auto* i = e.as_integer()) {
          if (i->get() < 1 || i->get() > 100000) r.fail(&e, field, fmt::format("column numbers start at 1, got {}", i->get()));
          part = std::to_string(i->get());
        } else if (const auto* str = e.as_string()) {
          if (str->get().find('"') != std::string::npos) r.fail(&e, field, "a column name with a double quote");
          part = str->get().empty() ? std::string() : "\"" + str->get() + "\"";
        } else {
          r.fail(&e, field, fmt::format("expected a column number or a header name, got {}", toml_type_name(e)));
        }
        text += (k == 0 ? "" : ",") + part;
      }
    } else {
      r.fail(n, field, fmt::format("expected [time, acceleration] or a string \"TIME,ACCEL\", got {}", toml_type_name(*n)));
    }
    ro.columns = r.located(n, field, [&] { return parse_columns(text, field); });
  }
  if (const auto sep = r.string(m, "separator", "motions.separator")) {
    ro.separator = r.located(m.get("separator"), "motions.separator",
                             [&] { return parse_separator(*sep, "motions.separator"); });
  }
  if (const auto b = r.string(m, "baseline", "motions.baseline")) {
    ro.baseline = r.located(m.get("baseline"), "motions.baseline", [&] { return parse_baseline(*b, "motions.baseline"); });
  }
  return ro;
}

/// The record files of [motions] and its record sets. Returns whether there are record files.
bool read_records(const Reader& r, const toml::table& m, const ReadOptions& ro, SweepFile& out) {
  // Records: every glob match, read once (in parallel; the first failure in file order is reported).
  const auto files = r.files(m);
  std::vector<std::shared_ptr<const GroundMotion>> loaded(files.size());
  std::vector<std::exception_ptr> errors(files.size());
  tbb::parallel_for(std::size_t{0}, files.size(), [&](std::size_t i) {
    try {
      loaded[i] = std::make_shared<const GroundMotion>(read_sweep_record(files[i].second, ro));
    } catch (...) {
      errors[i] = std::current_exception();
    }
  });
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  for (std::size_t i = 0; i < files.size(); ++i) out.spec.records.push_back({files[i].first, loaded[i]});
  read_record_sets(r, m, ro, out);
  return !files.empty();
}

/// Scaling (records only) and polarity.
void read_scaling(const Reader& r, const toml::table& m, double g, bool any_files, SweepFile& out) {
  const toml::node* scale_n = m.get("scale");
  const toml::node* pga_n = m.get("scale_pga") != nullptr ? m.get("scale_pga") : m.get("scale_pga_g");
  if (scale_n != nullptr && pga_n != nullptr) {
    r.fail(scale_n, "motions.scale", "give either scale (factors) or scale_pga / scale_pga_g (target PGAs), not both");
  }
  if (const auto pgas = r.quantities(m, "scale_pga_g", "scale_pga", "motions.", acceleration_parser(g, 1.0), "0.2g")) {
    const bool in_g = m.get("scale_pga_g") != nullptr;
    out.spec.scales.clear();
    for (const double v : *pgas) {
      const double target = in_g ? v * g : v;
      if (!(target > 0.0)) r.fail(pga_n, in_g ? "motions.scale_pga_g" : "motions.scale_pga",
                                  fmt::format("target PGAs must be > 0, got {}", v));
      out.spec.scales.push_back({ensemble::ScaleSpec::Kind::pga, target});
    }
  }
  if (const auto factors = r.numbers(m, "scale", "motions.scale")) {
    out.spec.scales.clear();
    for (const double v : *factors) out.spec.scales.push_back({ensemble::ScaleSpec::Kind::factor, v});
  }
  if (const auto ts = r.numbers(m, "time_scale", "motions.time_scale")) {
    for (const double v : *ts) {
      if (!(v > 0.0)) r.fail(m.get("time_scale"), "motions.time_scale", fmt::format("factors must be > 0, got {}", v));
    }
    out.spec.time_scales = *ts;
  }
  if ((scale_n != nullptr || pga_n != nullptr || m.get("time_scale") != nullptr) && !any_files &&
      out.spec.record_sets.empty()) {
    r.fail(scale_n != nullptr ? scale_n : pga_n != nullptr ? pga_n : m.get("time_scale"), "motions",
           "scale, scale_pga and time_scale apply to record files, and there are none (pulses take their own "
           "amplitudes and frequencies)");
  }
  if (const auto pol = r.strings(m, "polarity", "motions.polarity")) {
    out.spec.inverse.clear();
    for (const auto& p : *pol) {
      if (p != "normal" && p != "inverse") {
        r.fail(m.get("polarity"), "motions.polarity", fmt::format("unknown polarity '{}' (known: normal, inverse)", p));
      }
      out.spec.inverse.push_back(p == "inverse");
    }
  }
}

/// [[motions.pulse]]: every combination of kind x amplitude x frequency (or duration).
void read_pulses(const Reader& r, const toml::table& m, double g, SweepFile& out) {
  if (const toml::node* pn = m.get("pulse")) {
    const auto* arr = pn->as_array();
    if (arr == nullptr || !arr->is_array_of_tables()) {
      r.fail(pn, "motions.pulse", "expected [[motions.pulse]] tables");
    }
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table& p = *arr->get(i)->as_table();
      const std::string key = fmt::format("motions.pulse[{}]", i + 1);
      const std::string prefix = key + ".";
      r.check_keys(p, key, {"kind", "amp_g", "amp", "freq_hz", "freq", "duration_s", "duration", "tail_s", "tail",
                            "dt_s", "dt"});
      const auto kinds = r.strings(p, "kind", prefix + "kind");
      if (!kinds) r.fail(&p, prefix + "kind", "a pulse needs its kind (rect, tri, double-tri, sine, cosine, ricker)");
      std::vector<PulseKind> kind_values;
      for (const auto& k : *kinds) {
        kind_values.push_back(r.located(p.get("kind"), prefix + "kind", [&] { return parse_pulse_kind(k, "kind"); }));
      }
      const auto amps = r.quantities(p, "amp_g", "amp", prefix, acceleration_parser(g, g), "0.3g");
      if (!amps) r.fail(&p, prefix + "amp_g", "a pulse needs its amplitude (amp_g, or amp with a unit)");
      const auto freqs = r.quantities(p, "freq_hz", "freq", prefix, frequency_parser(), "2Hz");
      const auto durations = r.quantities(p, "duration_s", "duration", prefix, duration_parser(), "0.1s");
      if (freqs.has_value() == durations.has_value()) {
        r.fail(&p, prefix + "freq_hz", "a pulse needs exactly one of freq_hz / freq and duration_s / duration");
      }
      const auto tail = r.quantity(p, "tail_s", "tail", prefix, duration_parser(), "1s");
      const auto dt = r.quantity(p, "dt_s", "dt", prefix, duration_parser(), "0.001s");
      if (tail && !(*tail >= 0.0)) r.fail(&p, prefix + "tail", "must be >= 0");
      if (dt && !(*dt > 0.0)) r.fail(&p, prefix + "dt", "must be > 0");
      for (const PulseKind kind : kind_values) {
        for (const double amp_g : *amps) {
          for (const double x : freqs ? *freqs : *durations) {
            if (!(x > 0.0)) r.fail(&p, prefix + (freqs ? "freq_hz" : "duration_s"), fmt::format("must be > 0, got {}", x));
            ensemble::PulseInput in;
            in.spec.kind = kind;
            in.spec.amplitude_m_s2 = amp_g * g;  // as `topple slide --amp-g` computes it
            in.spec.duration_s = freqs ? 1.0 / x : x;
            in.spec.tail_s = tail ? *tail : 5.0 * in.spec.duration_s;  // the CLI's default: 5 pulse durations
            in.spec.dt_s = dt.value_or(0.0);
            in.name = fmt::format("{} amp_g={} {}={}", pulse_kind_name(kind), amp_g, freqs ? "freq_hz" : "duration_s", x);
            r.located(&p, key, [&] { return make_pulse(in.spec).size(); });  // validate now, not at the first run
            out.spec.pulses.push_back(std::move(in));
          }
        }
      }
    }
  }
}

/// [motions]: records and pulses, scaling, polarity.
void read_motions(const Reader& r, const toml::table& t, SweepFile& out) {
  const toml::table* m = nullptr;
  if (const toml::node* n = t.get("motions")) {
    m = n->as_table();
    if (m == nullptr) r.fail(n, "motions", fmt::format("expected a table [motions], got {}", toml_type_name(*n)));
  } else {
    r.fail(&t, "motions", "the sweep has no [motions] table");
  }
  const double g = out.spec.g_m_s2;
  r.check_keys(*m, "motions", {"files", "format", "units", "dt", "dt_s", "channel", "columns", "separator",
                               "baseline", "scale", "scale_pga",
                               "scale_pga_g", "time_scale", "polarity", "pulse", "set", "bearing", "bearing_deg",
                               "direction_step_deg"});
  const ReadOptions ro = read_record_options(r, *m, g);
  const bool any_files = read_records(r, *m, ro, out);
  read_scaling(r, *m, g, any_files, out);
  read_pulses(r, *m, g, out);
  if (out.spec.records.empty() && out.spec.pulses.empty() && out.spec.record_sets.empty()) {
    r.fail(m, "motions", "no motion: give files = [...], [[motions.pulse]] and/or [[motions.set]] tables");
  }
}

SlidingMode parse_mode(const Reader& r, const toml::node* n, const std::string& field, const std::string& s) {
  if (s == "two-way") return SlidingMode::two_way;
  if (s == "one-way") return SlidingMode::one_way;
  r.fail(n, field, fmt::format("unknown mode '{}' (known: two-way, one-way)", s));
}

/// An object's flexible supports (docs/sweeps.md): `support_freq_hz` / `support_freq` and `support_damping` (decimal),
/// each one value, a list or a range; every (frequency, damping) pair is a support. Neither key: one rigid support
/// (the sweep's meaning before these keys existed). One without the other is refused (no damping is guessed).
std::vector<std::optional<SupportOscillator>> read_supports(const Reader& r, const toml::table& o,
                                                             const std::string& prefix) {
  const auto freqs = r.quantities(o, "support_freq_hz", "support_freq", prefix, frequency_parser(), "4Hz");
  const auto dampings = r.numbers(o, "support_damping", prefix + "support_damping");
  if (!freqs && !dampings) return {std::nullopt};
  if (!freqs) r.fail(o.get("support_damping"), prefix + "support_freq_hz", "a flexible support needs its frequency");
  if (!dampings) {
    const toml::node* n = o.get("support_freq") != nullptr ? o.get("support_freq") : o.get("support_freq_hz");
    r.fail(n, prefix + "support_damping", "a flexible support needs its damping ratio (decimal: 0.05 is 5 %)");
  }
  std::vector<std::optional<SupportOscillator>> out;
  for (const double f : *freqs) {
    for (const double z : *dampings) {
      try {
        out.emplace_back(SupportOscillator::make(f, z));
      } catch (const InputError& e) {
        const bool freq = e.where().field == "support_freq";
        const std::string key = freq ? (o.get("support_freq") != nullptr ? "support_freq" : "support_freq_hz")
                                     : "support_damping";
        r.fail(o.get(key), prefix + key, e.problem());
      }
    }
  }
  return out;
}

void read_slide(const Reader& r, const toml::table& o, const std::string& key, double g, SweepFile& out) {
  const std::string prefix = key + ".";
  r.check_keys(o, key, {"model", "mu", "mu_kinetic", "slope_deg", "slope", "mode", "support_freq_hz", "support_freq",
                        "support_damping"});
  const auto supports = read_supports(r, o, prefix);
  const auto mu = r.numbers(o, "mu", prefix + "mu");
  if (!mu) r.fail(&o, prefix + "mu", "a sliding object needs its friction coefficient mu");
  const auto mu_k = r.numbers(o, "mu_kinetic", prefix + "mu_kinetic");
  const auto slopes = r.quantities(o, "slope_deg", "slope", prefix, angle_deg_parser(), "10deg").value_or(
      std::vector<double>{0.0});
  std::vector<SlidingMode> modes{SlidingMode::two_way};
  if (const auto ms = r.strings(o, "mode", prefix + "mode")) {
    modes.clear();
    for (const auto& s : *ms) modes.push_back(parse_mode(r, o.get("mode"), prefix + "mode", s));
  }
  const auto field_of = [&](const std::string& f) {
    if (f == "slope") return prefix + (o.get("slope") != nullptr ? "slope" : "slope_deg");
    return prefix + f;
  };
  for (const SlidingMode mode : modes) {
    for (const double slope_deg : slopes) {
      for (const double m : *mu) {
        std::vector<std::optional<double>> kinetic{std::nullopt};  // none given: mu_kinetic = mu
        if (mu_k) kinetic.assign(mu_k->begin(), mu_k->end());
        for (const std::optional<double>& k : kinetic) {
          try {
            // slope_deg * pi / 180: the expression `topple slide --slope-deg` uses, so that rows match it exactly.
            const SlidingBlock b = SlidingBlock::make(m, k, deg_to_rad(slope_deg), mode, g);
            for (const auto& support : supports) out.spec.objects.emplace_back(ensemble::SlideObject{b, slope_deg, support});
          } catch (const InputError& e) {
            const std::string f = field_of(e.where().field);
            r.fail(o.get(f.substr(prefix.size())) != nullptr ? o.get(f.substr(prefix.size())) : &o, f, e.problem());
          }
        }
      }
    }
  }
}

/// One body of a rocking object's expansion, with the dimensions as given (the sweep's object columns).
struct BodyCase {
  RockingBody body;
  std::optional<double> width_m, height_m, diameter_m;
  std::optional<double> inertia_m2;  ///< asymmetric general body: I_cm / m
  std::string mesh;                  ///< a body from a mesh: the file as given, and its plane's azimuth
  std::optional<double> mesh_azimuth_deg;
  std::string mesh_pose;             ///< "rest" or "as-scanned"
  std::optional<RigidBody3D> body_3d;  ///< model = "3d", a body from a mesh: its three-dimensional body as posed
};

/// The sweep key of a BodyOptions option named by check_body_options or mesh_body.
std::string mesh_option_key(const std::string& option) {
  return io_detail::mesh_option_key(option, "mesh_contact_tolerance", "mesh_azimuth_deg");
}

/// The pose keys of a mesh object (bodies/pose.hpp; one value each, for every mesh of the object): `mesh_pose`
/// ("rest", the default, or "as-scanned"), `mesh_up` [x, y, z], `mesh_rotation_wxyz` [w, x, y, z],
/// `mesh_axis_angle_deg` [x, y, z, degrees], `mesh_face` (a number of `topple body --list-faces`),
/// `mesh_contact_tolerance` ("1mm") or `mesh_contact_tolerance_m`.
void read_mesh_pose(const Reader& r, const toml::table& o, const std::string& prefix, BodyOptions& options) {
  if (const auto pose = r.string(o, "mesh_pose", prefix + "mesh_pose")) {
    const auto method = io_detail::mesh_pose_method(*pose);
    if (!method) r.fail(o.get("mesh_pose"), prefix + "mesh_pose", io_detail::mesh_pose_problem(*pose));
    options.pose = *method;
  }
  const auto fixed = [&](std::string_view key, std::size_t count, const char* what) {
    auto v = r.numbers(o, key, prefix + std::string(key));
    if (v && (v->size() != count || o.get(key)->as_array() == nullptr)) {
      r.fail(o.get(key), prefix + std::string(key), fmt::format("expected a list of {} numbers: {}", count, what));
    }
    return v;
  };
  io_detail::read_mesh_orientation(options, fixed);
  if (const toml::node* n = o.get("mesh_face")) {
    options.face = io_detail::mesh_face_number(*n);
    if (!options.face) r.fail(n, prefix + "mesh_face", io_detail::kMeshFaceProblem);
  }
  if (const auto tol = r.quantities(o, "mesh_contact_tolerance_m", "mesh_contact_tolerance", prefix, length_parser(),
                                    "1mm")) {
    if (tol->size() != 1) {
      r.fail(o.get("mesh_contact_tolerance") != nullptr ? o.get("mesh_contact_tolerance")
                                                         : o.get("mesh_contact_tolerance_m"),
             prefix + "mesh_contact_tolerance", "expected a single value");
    }
    options.contact_tolerance_m = tol->front();
  }
}

/// The bodies of an object given as meshes (docs/sweeps.md): `mesh` (a path or a list, relative to the sweep file)
/// x `mesh_azimuth_deg` (one value, a list or a range), posed by the `mesh_pose` keys (read_mesh_pose), through the
/// mesh pipeline (io::read_mesh_body, rocking_body). A refusal names the sweep file, the line, the key and the mesh
/// file.
/// With `three_d` (model = "3d") the body is the mesh as posed in three dimensions (RigidBody3D::from_mesh), turned by
/// the sweep's bearings: mesh_azimuth_deg (a planar body's plane of shaking) is refused.
std::vector<BodyCase> mesh_bodies(const Reader& r, const toml::table& o, const std::string& prefix,
                                  bool three_d = false) {
  const auto files = r.strings(o, "mesh", prefix + "mesh");
  if (three_d && o.get("mesh_azimuth_deg") != nullptr) {
    r.fail(o.get("mesh_azimuth_deg"), prefix + "mesh_azimuth_deg",
           "a three-dimensional body (model = \"3d\") has no plane of shaking: it stands with the mesh's +x axis at "
           "the sweep's bearing_deg");
  }
  const auto azimuths = three_d ? std::optional(std::vector<double>{0.0})
                                : r.numbers(o, "mesh_azimuth_deg", prefix + "mesh_azimuth_deg");
  if (!azimuths) {
    r.fail(&o, prefix + "mesh_azimuth_deg", "a body from a mesh needs the azimuth of its plane of shaking, degrees "
                                            "clockwise from the mesh's north (+y)");
  }
  BodyOptions options;
  if (const auto density = r.numbers(o, "mesh_density_kg_m3", prefix + "mesh_density_kg_m3")) {
    if (density->size() != 1) r.fail(o.get("mesh_density_kg_m3"), prefix + "mesh_density_kg_m3", "expected a single value");
    options.density_kg_m3 = density->front();
  }
  read_mesh_pose(r, o, prefix, options);
  double unit_m = 1.0;
  if (const auto unit = r.string(o, "mesh_unit", prefix + "mesh_unit")) {
    unit_m = r.located(o.get("mesh_unit"), prefix + "mesh_unit", [&] { return mesh_unit_m(*unit, "mesh_unit"); });
  }
  std::vector<BodyCase> out;
  for (const std::string& file : *files) {
    if (file.empty()) r.fail(o.get("mesh"), prefix + "mesh", "empty mesh path");
    const fs::path path = fs::path(file).is_absolute() || r.dir().empty() ? fs::path(file) : r.dir() / file;
    for (const double azimuth : *azimuths) {
      options.azimuth_deg = azimuth;
      try {
        check_body_options(options);
      } catch (const InputError& e) {
        std::string key = mesh_option_key(e.where().field);
        if (key == "mesh_contact_tolerance" && o.get(key) == nullptr) key = "mesh_contact_tolerance_m";
        r.fail(o.get(key), prefix + key, e.problem());
      }
      BodyCase c;
      try {
        const MeshBody mb = read_mesh_body(path.string(), unit_m, options);
        if (three_d) {
          c.body_3d = RigidBody3D::from_mesh(mb);
          // The planar section at azimuth 0 stays the object's planar body (the b1, b2, h columns).
        }
        c.body = rocking_body(mb);
        c.inertia_m2 = mb.planar.inertia_cm_kg_m2 / mb.mass.mass_kg;
      } catch (const InputError& e) {
        if (e.where().field == "--face") {
          r.fail(o.get("mesh_face"), prefix + "mesh_face", fmt::format("mesh '{}': {}", path.string(), e.problem()));
        }
        r.fail(o.get("mesh"), prefix + "mesh", fmt::format("mesh '{}' gives no body: {}", path.string(), e.what()));
      }
      c.mesh = file;
      if (!three_d) c.mesh_azimuth_deg = azimuth;
      c.mesh_pose = options.pose == PoseMethod::as_scanned ? "as-scanned" : "rest";
      out.push_back(std::move(c));
    }
  }
  return out;
}

/// The dimensions of a rocking object's bodies, each a list of values (their product is the object's bodies).
struct BodyAxes {
  std::vector<double> first;        // width, diameter, a or b1 (m)
  std::vector<double> second;       // height or h (m)
  std::vector<double> third{0.0};   // D (m^2), general only
  std::vector<double> fourth{0.0};  // asymmetric general: b2 (m)
  std::vector<double> fifth{0.0};   // asymmetric general: inertia (m^2)
  std::string first_key;
  std::string second_key;
};

/// The keys a rocking object's shape needs, read; those it does not take refused.
BodyAxes read_body_axes(const Reader& r, const toml::table& o, const std::string& prefix, const std::string& shape,
                        bool from_mesh, bool asymmetric) {
  const auto refuse = [&](std::initializer_list<std::string_view> keys) {
    for (const auto k : keys) {
      if (const toml::node* n = o.get(k)) {
        r.fail(n, prefix + std::string(k), fmt::format("does not apply to shape = \"{}\"", shape));
      }
    }
  };
  const auto need = [&](const std::optional<std::vector<double>>& v, std::string_view name) {
    if (!v) r.fail(&o, prefix + std::string(name), fmt::format("shape = \"{}\" needs {}", shape, name));
    return *v;
  };
  BodyAxes x;
  if (!from_mesh) {
    refuse({"mesh_azimuth_deg", "mesh_unit", "mesh_density_kg_m3", "mesh_pose", "mesh_up", "mesh_rotation_wxyz",
            "mesh_axis_angle_deg", "mesh_face", "mesh_contact_tolerance", "mesh_contact_tolerance_m"});
  }
  if (from_mesh) {
    if (shape != "general") {
      r.fail(o.get("shape"), prefix + "shape", fmt::format("a body from a mesh is a general body: leave shape out or "
                                                           "write \"general\", not \"{}\"", shape));
    }
    for (const auto k : {"width", "width_m", "height", "height_m", "diameter", "diameter_m", "a", "a_m", "h", "h_m",
                         "D_m2", "b1", "b1_m", "b2", "b2_m", "inertia", "inertia_m2"}) {
      if (const toml::node* n = o.get(k)) {
        r.fail(n, prefix + std::string(k), "does not apply to a body from a mesh (the mesh gives b1, b2, h and the "
                                           "inertia)");
      }
    }
  } else if (shape == "block" || shape == "cylinder") {
    x.first_key = shape == "block" ? "width" : "diameter";
    x.second_key = "height";
    x.first = need(r.quantities(o, x.first_key + "_m", x.first_key, prefix, length_parser(), "4cm"), x.first_key);
    x.second = need(r.quantities(o, "height_m", "height", prefix, length_parser(), "20cm"), "height");
    if (shape == "block") refuse({"diameter", "diameter_m"});
    if (shape == "cylinder") refuse({"width", "width_m"});
    refuse({"a", "a_m", "h", "h_m", "D_m2", "b1", "b1_m", "b2", "b2_m", "inertia", "inertia_m2"});
  } else if (asymmetric) {
    x.first_key = "b1";
    x.second_key = "h";
    x.first = need(r.quantities(o, "b1_m", "b1", prefix, length_parser(), "5cm"), "b1");
    x.second = need(r.quantities(o, "h_m", "h", prefix, length_parser(), "10cm"), "h");
    x.fourth = need(r.quantities(o, "b2_m", "b2", prefix, length_parser(), "3cm"), "b2");
    x.fifth = need(r.quantities(o, "inertia_m2", "inertia", prefix, area_parser(), "0.004m2"), "inertia_m2");
    refuse({"width", "width_m", "height", "height_m", "diameter", "diameter_m", "a", "a_m", "D_m2"});
  } else if (shape == "general") {
    x.first_key = "a";
    x.second_key = "h";
    x.first = need(r.quantities(o, "a_m", "a", prefix, length_parser(), "2cm"), "a");
    x.second = need(r.quantities(o, "h_m", "h", prefix, length_parser(), "10cm"), "h");
    x.third = need(r.numbers(o, "D_m2", prefix + "D_m2"), "D_m2");
    refuse({"width", "width_m", "height", "height_m", "diameter", "diameter_m"});
  } else if (shape.empty()) {
    r.fail(&o, prefix + "shape", "a rocking object needs its shape: block, cylinder or general");
  } else {
    r.fail(o.get("shape"), prefix + "shape", fmt::format("unknown shape '{}' (known: block, cylinder, general)", shape));
  }
  return x;
}

/// e: "housner" (none), a number in [0, 1], or a list mixing them; "housner" when not given.
std::vector<std::optional<double>> read_restitutions(const Reader& r, const toml::table& o, const std::string& prefix) {
  std::vector<std::optional<double>> es;
  const toml::node* en = o.get("e");
  if (en == nullptr) {
    es.emplace_back(std::nullopt);
    return es;
  }
  const auto one = [&](const toml::node& e) -> std::optional<double> {
    if (const auto* s = e.as_string()) {
      if (s->get() == "housner") return std::nullopt;
      r.fail(&e, prefix + "e", fmt::format("'{}' is neither 'housner' nor a number in [0, 1]", s->get()));
    }
    const auto x = number_of(e);
    if (!x) r.fail(&e, prefix + "e", fmt::format("expected \"housner\" or a number in [0, 1], got {}", toml_type_name(e)));
    if (!(*x >= 0.0 && *x <= 1.0)) r.fail(&e, prefix + "e", fmt::format("must be in [0, 1], got {}", *x));
    return *x;
  };
  if (const auto* a = en->as_array()) {
    if (a->empty()) r.fail(en, prefix + "e", "empty list: give at least one value");
    for (const auto& e : *a) es.push_back(one(e));
  } else if (en->is_table()) {
    const std::vector<double> values = *r.numbers(o, "e", prefix + "e");
    for (const double x : values) {
      if (!(x >= 0.0 && x <= 1.0)) r.fail(en, prefix + "e", fmt::format("must be in [0, 1], got {}", x));
      es.emplace_back(x);
    }
  } else {
    es.push_back(one(*en));
  }
  return es;
}

/// The bodies of the product of the axes, each made (and refused at its key) by the body's own rules.
std::vector<BodyCase> axis_bodies(const Reader& r, const toml::table& o, const std::string& prefix,
                                  const std::string& shape, bool asymmetric, const BodyAxes& axes) {
  const auto key_of = [&](const std::string& base) {
    return o.get(base) != nullptr ? base : base + (base == "D" || base == "inertia" ? "_m2" : "_m");
  };
  std::vector<BodyCase> bodies;
  for (const double x1 : axes.first) {
    for (const double x2 : axes.second) {
      for (const double x3 : axes.third) {
        for (const double x4 : axes.fourth) {
          for (const double x5 : axes.fifth) {
            BodyCase c;
            try {
              c.body = shape == "block"      ? RockingBody::block(x1, x2)
                       : shape == "cylinder" ? RockingBody::cylinder(x1, x2)
                       : asymmetric          ? RockingBody::general_asymmetric(x1, x4, x2, x5)
                                             : RockingBody::general(x1, x2, x3);
            } catch (const InputError& e) {
              std::string f = e.where().field;
              if (f == "width" || f == "diameter" || f == "a" || f == "b1") f = key_of(axes.first_key);
              if (f == "height" || f == "h") f = key_of(axes.second_key);
              if (f == "b2") f = key_of("b2");
              if (f == "inertia") f = key_of("inertia");
              if (f == "D") f = "D_m2";
              r.fail(o.get(f) != nullptr ? o.get(f) : &o, prefix + f, e.problem());
            }
            if (shape == "block") c.width_m = x1;
            if (shape == "cylinder") c.diameter_m = x1;
            if (shape != "general") c.height_m = x2;
            if (asymmetric) c.inertia_m2 = x5;
            bodies.push_back(std::move(c));
          }
        }
      }
    }
  }
  return bodies;
}

/// Which model a rocking object's keys are read for.
enum class RockModel { rock, coupled, three_d };

/// The keys a three-dimensional object (model = "3d") refuses, with why: it is a box (a block with its depth), a
/// solid cylinder (the rim engine, rigid3d_disc.hpp; mu and mu_kinetic its Coulomb friction) or a body from a mesh,
/// which stands on the ground (rigid3d.hpp).
void refuse_for_3d(const Reader& r, const toml::table& o, const std::string& prefix, const std::string& shape,
                   bool from_mesh) {
  for (const char* k : {"support_freq_hz", "support_freq", "support_damping"}) {
    if (const toml::node* n = o.get(k)) {
      r.fail(n, prefix + k, "a three-dimensional object (model = \"3d\") stands on the ground: flexible supports are "
                            "not run under [[motions.set]]");
    }
  }
  if (from_mesh) return;
  if (shape == "general") {
    r.fail(o.get("shape") != nullptr ? o.get("shape") : &o, prefix + "shape",
           "model = \"3d\": a general body (a, h, D or b1, b2, h, inertia) is a section in one vertical plane, "
           "without a base in three dimensions; give a block with its depth, or a mesh");
  }
  if (shape == "block" && o.get("depth") == nullptr && o.get("depth_m") == nullptr) {
    r.fail(&o, prefix + "depth", "model = \"3d\" needs the block's depth (depth_m, or depth with a unit): its extent "
                                 "along its own y axis, along bearing + 90");
  }
}

/// A rocking object (model = "rock"), a coupled slide-rock object (model = "coupled": the same body keys, mu
/// required, mu_kinetic optional; slide_rock.hpp) or a three-dimensional one (model = "3d": a block with its depth or
/// a mesh, no mu, no support; rigid3d.hpp).
void read_rock(const Reader& r, const toml::table& o, const std::string& key, double g, SweepFile& out,
               RockModel model = RockModel::rock) {
  const bool coupled = model == RockModel::coupled;
  const bool three_d = model == RockModel::three_d;
  const std::string prefix = key + ".";
  // The body keys of every rocking object; a coupled one (model = "coupled") also takes mu_kinetic.
  std::vector<std::string_view> keys{"model", "shape", "width", "width_m", "height", "height_m", "diameter",
                                     "diameter_m", "a", "a_m", "h", "h_m", "D_m2", "b1", "b1_m", "b2", "b2_m",
                                     "inertia", "inertia_m2", "mesh", "mesh_azimuth_deg", "mesh_unit",
                                     "mesh_density_kg_m3", "mesh_pose", "mesh_up", "mesh_rotation_wxyz",
                                     "mesh_axis_angle_deg", "mesh_face", "mesh_contact_tolerance",
                                     "mesh_contact_tolerance_m", "e", "mu", "support_freq_hz", "support_freq",
                                     "support_damping", "depth", "depth_m"};
  if (coupled || three_d) keys.emplace_back("mu_kinetic");
  r.check_keys(o, key, keys);
  const bool from_mesh = o.get("mesh") != nullptr;
  // A body from a mesh is a general body: its shape may be left out.
  const std::string shape = r.string(o, "shape", prefix + "shape").value_or(from_mesh ? "general" : "");
  if (three_d) refuse_for_3d(r, o, prefix, shape, from_mesh);
  const auto supports = read_supports(r, o, prefix);
  // A block's depth (a box, oriented.hpp): under [[motions.set]] only (make_plan says so).
  std::vector<std::optional<double>> depths{std::nullopt};
  if (const auto d = r.quantities(o, "depth_m", "depth", prefix, length_parser(), "30cm")) {
    if (shape != "block") {
      r.fail(o.get("depth") != nullptr ? o.get("depth") : o.get("depth_m"), prefix + "depth",
             "a depth applies to shape = \"block\" (a box) only");
    }
    depths.assign(d->begin(), d->end());
  }
  // An asymmetric general body (rocking.hpp, general_asymmetric) is told by b1, b2 or the inertia.
  const bool asymmetric = shape == "general" && !from_mesh &&
                          (o.get("b1") != nullptr || o.get("b1_m") != nullptr || o.get("b2") != nullptr ||
                           o.get("b2_m") != nullptr || o.get("inertia") != nullptr || o.get("inertia_m2") != nullptr);
  const BodyAxes axes = read_body_axes(r, o, prefix, shape, from_mesh, asymmetric);
  const std::vector<std::optional<double>> es = read_restitutions(r, o, prefix);
  const auto mus = r.numbers(o, "mu", prefix + "mu");
  std::vector<std::optional<double>> mu_values;
  if (mus) {
    for (const double m : *mus) {
      if (!(m >= 0.0) || !std::isfinite(m)) r.fail(o.get("mu"), prefix + "mu", fmt::format("must be >= 0, got {}", m));
      mu_values.emplace_back(m);
    }
  } else {
    if (coupled) r.fail(&o, prefix + "mu", "a coupled object needs its friction coefficient mu (static)");
    mu_values.emplace_back(std::nullopt);
  }
  std::vector<std::optional<double>> mu_k_values{std::nullopt};
  if (coupled || three_d) {
    if (const auto ks = r.numbers(o, "mu_kinetic", prefix + "mu_kinetic")) mu_k_values.assign(ks->begin(), ks->end());
  }
  if (three_d && !mus && o.get("mu_kinetic") != nullptr) {
    r.fail(o.get("mu_kinetic"), prefix + "mu_kinetic", "a kinetic friction coefficient needs the static one (mu)");
  }
  std::vector<BodyCase> bodies;
  if (from_mesh) bodies = mesh_bodies(r, o, prefix, three_d);
  for (BodyCase& c : axis_bodies(r, o, prefix, shape, asymmetric, axes)) bodies.push_back(std::move(c));
  for (const BodyCase& c : bodies) {
    const RockingBody& body = c.body;
    for (const auto& e : es) {
      // The planar rule; the three-dimensional impact has none (a body that cannot lift about the new contact comes
      // to rest, rigid3d.hpp).
      if (!e && !three_d) r.located(o.get("e") != nullptr ? o.get("e") : &o, prefix + "e", [&] {
        ensemble::check_housner_restitution(body);  // the rocking model's rule (sweep.hpp)
      });
      for (const auto& m : mu_values) {
        for (const auto& mu_k : mu_k_values) {
          if (coupled) {  // the body with its friction (SlideRockBody::make's rules), placed at the key's line
            try {
              (void)SlideRockBody::from_rocking(body, *m, mu_k);
            } catch (const InputError& err) {
              const bool kinetic = err.where().field == "mu_k";
              r.fail(o.get(kinetic ? "mu_kinetic" : "mu"), prefix + (kinetic ? "mu_kinetic" : "mu"), err.problem());
            }
          }
          // model = "3d" with friction: Rigid3DOptions' rule 0 <= mu_k <= mu_s (rigid3d.hpp), at the key's line
          if (three_d && m && mu_k && (!std::isfinite(*mu_k) || *mu_k < 0.0 || *mu_k > *m)) {
            r.fail(o.get("mu_kinetic"), prefix + "mu_kinetic",
                   fmt::format("kinetic friction must be in [0, mu = {}], got {}", *m, *mu_k));
          }
          RockingOptions options;
          options.g_m_s2 = g;
          options.restitution = e ? RestitutionMode::given : RestitutionMode::housner;
          if (e) options.e = *e;
          options.mu = m;
          ensemble::RockObject ro{.body = body, .options = options, .width_m = c.width_m, .height_m = c.height_m,
                                  .diameter_m = c.diameter_m, .inertia_m2 = c.inertia_m2, .mesh = c.mesh,
                                  .mesh_azimuth_deg = c.mesh_azimuth_deg, .mesh_pose = c.mesh_pose};
          ro.coupled = coupled;
          ro.mu_kinetic = mu_k;
          for (const auto& depth : depths) {
            ro.depth_m = depth;
            if (depth) r.located(o.get("depth") != nullptr ? o.get("depth") : o.get("depth_m"), prefix + "depth",
                                 [&] { return OrientedBody::box(*c.width_m, *depth, *c.height_m); });
            if (three_d && shape == "cylinder" && !from_mesh) {
              // the planar cylinder's a = d / 2, h = H / 2 (rocking_body.hpp): the same solid cylinder on its rim
              ro.cylinder_3d = r.located(o.get("shape"), prefix + "shape", [&] {
                return CylinderBody3D::solid(2.0 * body.a_m, 2.0 * body.h_m);
              });
            } else if (three_d) {  // the box in three dimensions (width along +x, depth along +y), or the mesh's body
              ro.body_3d = c.body_3d ? c.body_3d
                                     : std::optional(r.located(o.get("depth") != nullptr ? o.get("depth")
                                                                                         : o.get("depth_m"),
                                                               prefix + "depth", [&] {
                                         return RigidBody3D::box(*c.width_m, *depth, *c.height_m);
                                       }));
            }
            for (const auto& support : supports) {
              ro.support = support;
              out.spec.objects.emplace_back(ro);
            }
          }
        }
      }
    }
  }
}

void read_objects(const Reader& r, const toml::table& t, SweepFile& out) {
  const toml::node* n = t.get("object");
  if (n == nullptr) r.fail(&t, "object", "the sweep has no [[object]] table");
  const auto* arr = n->as_array();
  if (arr == nullptr || !arr->is_array_of_tables() || arr->empty()) {
    r.fail(n, "object", "expected [[object]] tables (an array of tables: note the double brackets)");
  }
  for (std::size_t i = 0; i < arr->size(); ++i) {
    const toml::table& o = *arr->get(i)->as_table();
    const std::string key = fmt::format("object[{}]", i + 1);
    const auto model = r.string(o, "model", key + ".model");
    if (!model) r.fail(&o, key + ".model", "an object needs its model: \"slide\", \"rock\", \"coupled\" or \"3d\"");
    if (*model == "slide") {
      read_slide(r, o, key, out.spec.g_m_s2, out);
    } else if (*model == "rock") {
      read_rock(r, o, key, out.spec.g_m_s2, out);
    } else if (*model == "coupled") {
      read_rock(r, o, key, out.spec.g_m_s2, out, RockModel::coupled);
    } else if (*model == "3d") {
      read_rock(r, o, key, out.spec.g_m_s2, out, RockModel::three_d);
    } else {
      r.fail(o.get("model"), key + ".model", fmt::format("unknown model '{}' (known: slide, rock, coupled, 3d)", *model));
    }
  }
}

void read_output(const Reader& r, const toml::table& t, const fs::path& sweep_path, SweepFile& out) {
  fs::path csv = sweep_path.filename();
  csv.replace_extension(".csv");
  if (const toml::node* n = t.get("output")) {
    const auto* o = n->as_table();
    if (o == nullptr) r.fail(n, "output", fmt::format("expected a table [output], got {}", toml_type_name(*n)));
    r.check_keys(*o, "output", {"path", "jsonl", "chunk_runs"});
    if (const auto p = r.string(*o, "path", "output.path")) {
      if (p->empty()) r.fail(o->get("path"), "output.path", "empty path");
      csv = *p;
    }
    out.jsonl = r.boolean(*o, "jsonl", "output.jsonl").value_or(false);
    if (const auto c = r.integer(*o, "chunk_runs", "output.chunk_runs")) {
      if (*c < 1) r.fail(o->get("chunk_runs"), "output.chunk_runs", fmt::format("must be >= 1, got {}", *c));
      out.spec.chunk_runs = static_cast<std::size_t>(*c);
    }
  }
  out.output_csv = csv.is_absolute() ? csv : r.dir() / csv;
}

}  // namespace

fs::path jsonl_path_for(const fs::path& csv_path) {
  fs::path p = csv_path;
  p.replace_extension(".jsonl");
  if (p == csv_path) p += ".jsonl";
  return p;
}

SweepFile parse_sweep_file(std::string_view text, const fs::path& path) {
  const std::string file = path.string();
  toml::table t;
  try {
    t = toml::parse(text, file);
  } catch (const toml::parse_error& e) {
    std::optional<std::size_t> line;
    if (e.source().begin.line > 0) line = e.source().begin.line;
    throw InputError(InputLocation{file, line, ""}, fmt::format("not valid TOML: {}", e.description()));
  }
  const Reader r(file, path.parent_path());
  r.check_keys(t, "", {"description", "g", "g_m_s2", "motions", "object", "output"});
  SweepFile out;
  out.path = path;
  static_cast<void>(r.string(t, "description", "description"));  // free text, checked to be a string
  if (const auto g = r.quantity(t, "g_m_s2", "g", "", acceleration_parser(kStandardGravity, 1.0), "9.81m/s2")) {
    if (!(*g > 0.0)) r.fail(t.get("g") != nullptr ? t.get("g") : t.get("g_m_s2"), "g", "must be > 0");
    out.spec.g_m_s2 = *g;
  }
  read_output(r, t, path, out);
  read_objects(r, t, out);  // objects first: they are cheap to check, records are not
  read_motions(r, t, out);
  return out;
}

SweepFile read_sweep_file(const fs::path& path) {
  return parse_sweep_file(read_input_file(path, "sweep"), path);
}

}  // namespace topple::io
