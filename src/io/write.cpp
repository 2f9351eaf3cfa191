#include "topple/io/write.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <type_traits>
#include <variant>

#include <fmt/format.h>

#include "topple/error.hpp"
#include "topple/units.hpp"

namespace topple::io {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

nlohmann::ordered_json field_json(const FieldValue& value) {
  return std::visit(
      [](const auto& v) -> nlohmann::ordered_json {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, std::monostate>) {
          return nullptr;
        } else {
          return v;  // a non-finite double dumps as null (nlohmann::json): never NaN in the output
        }
      },
      value);
}

nlohmann::ordered_json sliding_summary_json(const SlidingSummary& s, const SlidingBlock& block) {
  nlohmann::ordered_json j = fields_json(kSlidingFields, SlidingOutcome{s, block});
  j["sign_convention"] = "displacement positive in the direction a positive ground acceleration pushes the block "
                         "(down-slope on an incline)";
  return j;
}

nlohmann::ordered_json rocking_summary_json(const RockingSummary& s, const RockingBody& body,
                                            const RockingOptions& options) {
  nlohmann::ordered_json j = fields_json(kRockingFields, RockingOutcome{s, body, options});
  j["warnings"] = s.warnings;
  nlohmann::ordered_json b;
  b["shape"] = shape_name(body.shape);
  if (body.shape == RockingBody::Shape::block) {
    b["width_m"] = 2.0 * body.a_m;
    b["height_m"] = 2.0 * body.h_m;
  } else if (body.shape == RockingBody::Shape::cylinder) {
    b["diameter_m"] = 2.0 * body.a_m;
    b["height_m"] = 2.0 * body.h_m;
  }
  b["a_m"] = body.a_m;
  b["h_m"] = body.h_m;
  b["D_m2"] = body.D_m2;
  j["body"] = b;
  nlohmann::ordered_json m;
  m["method"] = options.method == RockingMethod::rk4 ? "rk4" : "adaptive";
  m["rel_tol"] = options.rel_tol;
  m["rk4_substeps"] = options.rk4_substeps;
  m["rest_energy_fraction"] = options.rest_energy_fraction;
  m["max_run_out_s"] = options.max_run_out_s;
  m["steps"] = s.steps;
  j["solver"] = m;
  return j;
}

void write_sliding_history_csv(const std::filesystem::path& path, const SlidingHistory& h,
                               const GroundMotion& horizontal) {
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "w"));
  if (!f) throw InputError(InputLocation{path.string(), {}, "--out"}, "cannot open the file for writing");
  fmt::print(f.get(), "time_s,ground_accel_m_s2,displacement_m,velocity_m_s,state\n");
  for (std::size_t i = 0; i < h.time_s.size(); ++i) {
    fmt::print(f.get(), "{:.9g},{:.9g},{:.12g},{:.12g},{}\n", h.time_s[i], horizontal.accel_at(h.time_s[i]),
               h.displacement_m[i], h.velocity_m_s[i], static_cast<int>(h.state[i]));
  }
  if (std::ferror(f.get())) throw InputError(InputLocation{path.string(), {}, "--out"}, "write failed");
}

}  // namespace topple::io
