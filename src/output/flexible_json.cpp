#include "topple/output/flexible_json.hpp"

#include <array>
#include <iterator>
#include <variant>
#include <utility>

#include <fmt/format.h>

#include "topple/core/field.hpp"
#include "topple/core/output_file.hpp"
#include "topple/output/write.hpp"

namespace topple::io {
namespace {

/// The support object's first fields.
nlohmann::ordered_json support_head(FlexibleAnalysis a, const char* kind) {
  nlohmann::ordered_json s;
  s["analysis"] = a == FlexibleAnalysis::coupled ? "coupled" : "decoupled";
  s["kind"] = kind;
  return s;
}

/// The supports' own fields, in the JSON's order: one table per support type (core/field.hpp).
constexpr std::array<Field<SupportOscillator>, 3> kOscillatorFields{{
    {"freq_hz", [](const SupportOscillator& o) -> FieldValue { return o.freq_hz; }},
    {"damping_ratio", [](const SupportOscillator& o) -> FieldValue { return o.damping_ratio; }},
    {"mass_ratio", [](const SupportOscillator& o) -> FieldValue { return o.mass_ratio; }},
}};
constexpr std::array<Field<SlidingMassColumn>, 5> kSlidingMassFields{{
    {"height_m", [](const SlidingMassColumn& c) -> FieldValue { return c.height_m; }},
    {"vs_slope_m_s", [](const SlidingMassColumn& c) -> FieldValue { return c.vs_slope_m_s; }},
    {"vs_base_m_s", [](const SlidingMassColumn& c) -> FieldValue { return c.vs_base_m_s; }},
    {"damping_ratio", [](const SlidingMassColumn& c) -> FieldValue { return c.damping_ratio; }},
    {"reference_strain", [](const SlidingMassColumn& c) -> FieldValue {
       return c.reference_strain ? FieldValue(*c.reference_strain) : FieldValue(std::monostate{});
     }},
}};

/// The rigid block's summary with the support object, closed by the mode's fields.
nlohmann::ordered_json with_support(nlohmann::ordered_json support, const FlexibleSummary& s, const SlidingBlock& block) {
  support["mode_freq_hz"] = s.mode.omega_rad_s / (2.0 * kPi);
  support["mode_damping_ratio"] = s.mode.damping_ratio;
  support["kmax"] = s.kmax;
  nlohmann::ordered_json j = sliding_summary_json(s.sliding, block);
  j["support"] = std::move(support);
  return j;
}

}  // namespace

nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                             const SupportOscillator& support, FlexibleAnalysis analysis) {
  nlohmann::ordered_json s = support_head(analysis, "oscillator");
  s.update(fields_json(kOscillatorFields, support));
  return with_support(std::move(s), summary, block);
}

nlohmann::ordered_json flexible_summary_json(const FlexibleSummary& summary, const SlidingBlock& block,
                                             const SlidingMassColumn& column, FlexibleAnalysis analysis) {
  nlohmann::ordered_json s = support_head(analysis, "sliding_mass");
  s.update(fields_json(kSlidingMassFields, column));
  s["vs_final_m_s"] = summary.mode.vs_m_s;
  s["equivalent_linear_iterations"] = summary.mode.iterations;
  return with_support(std::move(s), summary, block);
}

void write_flexible_history_csv(const std::filesystem::path& path, const FlexibleHistory& h, const GroundMotion& ground) {
  OutputFile file(path);
  std::ostream& out = file.stream();
  out << "time_s,ground_accel_m_s2,support_accel_m_s2,displacement_m,velocity_m_s,state\n";
  fmt::memory_buffer row;
  const SlidingHistory& s = h.sliding;
  for (std::size_t i = 0; i < s.time_s.size(); ++i) {
    row.clear();
    // The digits of write_sliding_history_csv: times and accelerations to 9, displacement and velocity to 12.
    fmt::format_to(std::back_inserter(row), "{:.9g},{:.9g},{:.9g},{:.12g},{:.12g},{}\n", s.time_s[i],
                   ground.accel_at(s.time_s[i]), h.support_accel_m_s2[i], s.displacement_m[i], s.velocity_m_s[i],
                   static_cast<int>(s.state[i]));
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
  file.commit();
}

}  // namespace topple::io
