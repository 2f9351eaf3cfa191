// The ensemble plan: chunk sizes, motion transforms and the plan's consistency checks (ensemble.hpp).
#include <algorithm>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

#include "ensemble/ensemble_detail.hpp"
#include "topple/ensemble/ensemble.hpp"

namespace topple::ensemble {

GroundMotion MotionTransform::apply(const GroundMotion& base) const {
  // Each transform reads the previous one's motion and makes a new one; the base itself is copied only when no
  // transform applies (the inversion's 30,000 motions per survey are scaled_to_pga alone: one copy, not two).
  std::optional<GroundMotion> m;
  const auto current = [&]() -> const GroundMotion& { return m ? *m : base; };
  if (time_scale != 1.0) m = base.time_scaled(time_scale);
  if (target_pga_m_s2) m = current().scaled_to_pga(*target_pga_m_s2);
  if (factor) m = current().scaled(*factor);
  if (invert) m = current().inverted();
  return m ? std::move(*m) : base;
}

std::size_t default_chunk_runs(std::size_t runs) noexcept {
  const std::size_t target = (runs + 4095) / 4096;
  return std::clamp<std::size_t>(target, 1024, 100'000);
}

std::size_t Plan::chunk_size() const noexcept { return chunk_runs > 0 ? chunk_runs : default_chunk_runs(runs()); }

std::size_t Plan::chunks() const noexcept {
  const std::size_t c = chunk_size();
  return (runs() + c - 1) / c;
}

std::vector<std::string> Plan::columns() const {
  std::vector<std::string> all{"run"};
  all.insert(all.end(), motion_columns.begin(), motion_columns.end());
  all.insert(all.end(), object_columns.begin(), object_columns.end());
  all.insert(all.end(), result_columns.begin(), result_columns.end());
  return all;
}

namespace detail {

bool has_line_break(const Value& v) {
  const auto* s = std::get_if<std::string>(&v);
  return s != nullptr && s->find_first_of("\r\n") != std::string::npos;
}

}  // namespace detail

void check_plan(const Plan& plan) {
  if (!plan.run) throw std::invalid_argument("ensemble plan: no run function");
  std::set<std::string> seen;
  for (const auto& c : plan.columns()) {
    if (c.empty()) throw std::invalid_argument("ensemble plan: empty column name");
    if (!seen.insert(c).second) throw std::invalid_argument("ensemble plan: duplicated column '" + c + "'");
  }
  for (std::size_t m = 0; m < plan.motions.size(); ++m) {
    const auto& mc = plan.motions[m];
    if (!mc.base) throw std::invalid_argument(fmt::format("ensemble plan: motion {} has no base motion", m));
    if (mc.values.size() != plan.motion_columns.size()) {
      throw std::invalid_argument(fmt::format("ensemble plan: motion {} has {} values for {} columns", m,
                                              mc.values.size(), plan.motion_columns.size()));
    }
    if (std::any_of(mc.values.begin(), mc.values.end(), detail::has_line_break)) {
      throw std::invalid_argument(fmt::format("ensemble plan: motion {} has a line break in a value", m));
    }
  }
  for (std::size_t o = 0; o < plan.objects.size(); ++o) {
    const auto& oc = plan.objects[o];
    if (oc.values.size() != plan.object_columns.size()) {
      throw std::invalid_argument(fmt::format("ensemble plan: object {} has {} values for {} columns", o,
                                              oc.values.size(), plan.object_columns.size()));
    }
    if (std::any_of(oc.values.begin(), oc.values.end(), detail::has_line_break)) {
      throw std::invalid_argument(fmt::format("ensemble plan: object {} has a line break in a value", o));
    }
  }
}

}  // namespace topple::ensemble
