// The body that `topple body --json` writes, read back (io/body_file.hpp).
#include "topple/io/body_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "topple/core/error.hpp"

namespace topple::io {
namespace {

constexpr std::uintmax_t kMaxBodyFileBytes = std::uintmax_t{64} << 20;

InputError body_error(const std::string& file, const std::string& field, const std::string& problem) {
  return InputError(InputLocation{file, std::nullopt, field}, problem);
}

const char* kind_of(const nlohmann::json& v) { return v.type_name(); }

/// A required number field: present, a number, finite; `positive` also refuses <= 0 (zero allowed when not).
double number(const nlohmann::json& j, const char* field, const std::string& file, bool positive) {
  const auto it = j.find(field);
  if (it == j.end()) {
    throw body_error(file, field, fmt::format("missing: a body file is what `topple body MESH --json` writes, with "
                                              "b1_m, b2_m, h_m, inertia_cm_plane_kg_m2 and mass_kg"));
  }
  if (!it->is_number()) throw body_error(file, field, fmt::format("must be a number, got {}", kind_of(*it)));
  const double v = it->get<double>();
  if (!std::isfinite(v) || (positive ? !(v > 0.0) : v < 0.0)) {
    throw body_error(file, field, fmt::format("must be {} and finite, got {}", positive ? "positive" : ">= 0", v));
  }
  return v;
}

}  // namespace

RockingBody BodyFile::rocking_body() const { return RockingBody::general_asymmetric(b1_m, b2_m, h_m, inertia_m2); }

BodyFile parse_body_file(std::string_view content, const std::string& name) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(content.begin(), content.end());
  } catch (const nlohmann::json::parse_error& e) {
    // e.byte is the 1-based offset of the error: turn it into a line for the message.
    const std::size_t upto = std::min<std::size_t>(e.byte, content.size());
    const auto end = content.begin() + static_cast<std::ptrdiff_t>(upto);
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(content.begin(), end, '\n'));
    throw InputError(InputLocation{name, line, ""}, fmt::format("not JSON ({}): a body file is what `topple body MESH "
                                                                "--json` writes", e.what()));
  } catch (const nlohmann::json::exception& e) {
    // The parser's other refusals, e.g. out_of_range 406 for a number beyond double's range (1e400): found by
    // fuzz_body_file, which ended on them before this.
    throw InputError(InputLocation{name, std::nullopt, ""},
                     fmt::format("not a body file ({}): a body file is what `topple body MESH --json` writes", e.what()));
  }
  if (!j.is_object()) {
    throw InputError(InputLocation{name, std::nullopt, ""},
                     fmt::format("a body file is one JSON object (what `topple body MESH --json` writes), got {}",
                                 kind_of(j)));
  }
  BodyFile b;
  b.b1_m = number(j, "b1_m", name, true);
  b.b2_m = number(j, "b2_m", name, true);
  b.h_m = number(j, "h_m", name, true);
  const double mass_kg = number(j, "mass_kg", name, true);
  const double icm_kg_m2 = number(j, "inertia_cm_plane_kg_m2", name, false);
  b.inertia_m2 = icm_kg_m2 / mass_kg;  // k2 = I_cm / m, as rocking_body(MeshBody) forms it
  if (const auto it = j.find("azimuth_deg"); it != j.end() && it->is_number()) b.azimuth_deg = it->get<double>();
  if (const auto it = j.find("file"); it != j.end() && it->is_string()) b.mesh_file = it->get<std::string>();
  try {
    (void)b.rocking_body();
  } catch (const InputError& e) {
    throw body_error(name, e.where().field, e.problem());
  }
  return b;
}

BodyFile read_body_file(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(InputLocation{path, std::nullopt, ""}, fmt::format("cannot read: {}", ec.message()));
  if (size > kMaxBodyFileBytes) {
    throw InputError(InputLocation{path, std::nullopt, ""},
                     fmt::format("{} bytes: a body file is a small JSON object (at most 64 MiB read)", size));
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(InputLocation{path, std::nullopt, ""}, "cannot open");
  std::ostringstream s;
  s << in.rdbuf();
  return parse_body_file(s.str(), path);
}

}  // namespace topple::io
