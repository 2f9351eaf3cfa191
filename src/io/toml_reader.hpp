#pragma once
// What the sweep and campaign readers (sweep_file.cpp, campaign_file.cpp) read alike: the TOML type of a value as
// their errors name it, a reader that locates every error at the file, the line and the key (and rethrows a library
// check's InputError there), and the record keys `format` and `units` as both files name them (docs/sweeps.md,
// docs/campaign.md). One reading and one set of words for the two files; each file's reader derives from TomlReader
// and adds what only it reads (sweep values as lists and ranges, campaign numbers and file names).
#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/io/read.hpp"

namespace topple::io_detail {

/// A TOML value's type, as an error message names what it got ("expected a number, got a string").
[[nodiscard]] inline std::string toml_type_name(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::string: return "a string";
    case toml::node_type::integer: return "an integer";
    case toml::node_type::floating_point: return "a number";
    case toml::node_type::boolean: return "a boolean";
    case toml::node_type::date: return "a date";
    case toml::node_type::time: return "a time";
    case toml::node_type::date_time: return "a date-time";
    case toml::node_type::array: return "a list";
    case toml::node_type::table: return "a table";
    default: return "nothing";
  }
}

/// A TOML node's line in its file (1-based), or nullopt where toml++ knows none.
[[nodiscard]] inline std::optional<std::size_t> toml_line(const toml::node* n) {
  if (n != nullptr && n->source().begin.line > 0) return n->source().begin.line;
  return std::nullopt;
}

/// Reads one TOML file (`file` as errors name it, `dir` the folder its relative paths start from); every error
/// names the file, the line and the key.
class TomlReader {
 public:
  TomlReader(std::string file, std::filesystem::path dir) : file_(std::move(file)), dir_(std::move(dir)) {}

  [[noreturn]] void fail(const toml::node* node, const std::string& key, const std::string& problem) const {
    throw InputError(InputLocation{file_, toml_line(node), key}, problem);
  }

  /// Rethrows an InputError of a library check (a units helper, a model factory) with this file's location and the
  /// user's key.
  template <class F>
  auto located(const toml::node* node, const std::string& key, F f) const {
    try {
      return f();
    } catch (const InputError& e) {
      fail(node, key, e.problem());
    }
  }

  /// Refuses a key of `t` (the table `where`) that is not in `allowed`, listing those that are.
  void check_keys(const toml::table& t, const std::string& where,
                  std::initializer_list<std::string_view> allowed) const {
    check_keys(t, where, std::vector<std::string_view>(allowed));
  }
  void check_keys(const toml::table& t, const std::string& where, const std::vector<std::string_view>& allowed) const {
    for (auto&& [k, v] : t) {
      const std::string_view name = k.str();
      if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
      std::string known;
      for (const auto& a : allowed) known += (known.empty() ? "" : ", ") + std::string(a);
      fail(&v, where.empty() ? std::string(name) : where + "." + std::string(name),
           fmt::format("unknown key '{}' (known here: {})", name, known));
    }
  }

  /// A string value; nullopt when the key is absent.
  [[nodiscard]] std::optional<std::string> string(const toml::table& t, std::string_view key,
                                                  const std::string& field) const {
    const toml::node* n = t.get(key);
    if (n == nullptr) return std::nullopt;
    const auto* s = n->as_string();
    if (s == nullptr) fail(n, field, fmt::format("expected a string, got {}", toml_type_name(*n)));
    return s->get();
  }

  [[nodiscard]] const std::string& file_name() const { return file_; }
  [[nodiscard]] const std::filesystem::path& dir() const { return dir_; }

 private:
  std::string file_;
  std::filesystem::path dir_;
};

/// The record keys `format` (a format name, as --format) and `units` (the unit of a plain file's values, as --units;
/// checked against `g`) of table `t`, into `ro`; `prefix` is the table's path in error keys ("motions.",
/// "campaign.", "test[2].").
inline void read_record_format_and_units(const TomlReader& r, const toml::table& t, const std::string& prefix,
                                         double g, io::ReadOptions& ro) {
  if (const auto f = r.string(t, "format", prefix + "format")) {
    ro.format =
        r.located(t.get("format"), prefix + "format", [&] { return io::parse_format_name(*f, prefix + "format"); });
  }
  if (const auto u = r.string(t, "units", prefix + "units")) {
    r.located(t.get("units"), prefix + "units", [&] { return acceleration_unit_factor(*u, prefix + "units", g); });
    ro.units = *u;
  }
}

}  // namespace topple::io_detail
