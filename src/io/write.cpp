#include "topple/io/write.hpp"

#include <cmath>
#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "topple/error.hpp"
#include "topple/units.hpp"

namespace topple::io {
namespace {

nlohmann::ordered_json optional_json(const std::optional<double>& value) {
  return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json(nullptr);
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

nlohmann::ordered_json sliding_summary_json(const SlidingSummary& s, const SlidingBlock& block) {
  nlohmann::ordered_json j;
  j["max_abs_displacement_m"] = s.max_abs_displacement_m;
  j["max_displacement_time_s"] = s.max_displacement_time_s;
  j["residual_displacement_m"] = s.residual_displacement_m;
  j["max_abs_velocity_m_s"] = s.max_abs_velocity_m_s;
  j["slip_episodes"] = s.slip_episodes;
  j["first_slip_time_s"] = optional_json(s.first_slip_time_s);
  j["total_slip_duration_s"] = s.total_slip_duration_s;
  j["end_time_s"] = s.end_time_s;
  j["at_rest_at_end"] = s.at_rest_at_end;
  j["contact_lost_time_s"] = optional_json(s.contact_lost_time_s);
  j["yield_down_g"] = block.yield_down_m_s2() / block.g_m_s2;
  const double up = block.yield_up_m_s2();
  j["yield_up_g"] = std::isfinite(up) ? nlohmann::ordered_json(up / block.g_m_s2) : nlohmann::ordered_json(nullptr);
  j["mu_static"] = block.mu_static;
  j["mu_kinetic"] = block.mu_kinetic;
  j["slope_deg"] = block.slope_rad * 180.0 / kPi;
  j["mode"] = block.mode == SlidingMode::one_way ? "one-way" : "two-way";
  j["g_m_s2"] = block.g_m_s2;
  j["sign_convention"] = "displacement positive in the direction a positive ground acceleration pushes the block "
                         "(down-slope on an incline)";
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
