// Several ground-motion components on one time grid, jumps kept. See input_grid.hpp for the rules.
#include "topple/motion/input_grid.hpp"

#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <limits>

namespace topple {
namespace {

/// All present components on the primary's uniform grid: nothing to merge.
bool same_uniform_grid(std::span<const GroundMotion* const> components) {
  const GroundMotion& p = *components.front();
  if (!p.is_uniform()) return false;
  return std::all_of(components.begin(), components.end(), [&](const GroundMotion* m) {
    return m == nullptr || (m->is_uniform() && m->size() == p.size() && m->dt_s() == p.dt_s() &&
                            m->start_time_s() == p.start_time_s());
  });
}

/// Whether sample time t (>= T: T is the earliest sample not yet taken) is the instant T. Two records' sample times
/// that are the same instant computed two ways (i dt / s on a support's finer grid against j dt: flexible.hpp's
/// demand motion) differ by round-off, a few ulp of T; kept apart they would make two samples 1e-17 s apart, which
/// GroundMotion refuses (Limits::min_dt_s, 1e-6 s). 1e-12 of max(|T|, 1 s) is far above round-off and far below any
/// spacing a record may have, so no distinct samples are joined.
bool same_instant(double t, double T) { return t - T <= 1e-12 * std::max(std::abs(T), 1.0); }

/// Values of component m at instant T (see the header), with k its first sample not yet taken; advances k past the
/// samples at T.
void values_at(const GroundMotion& m, double T, double t_start, double t_end, std::size_t& k,
               std::vector<double>& out) {
  out.clear();
  const std::size_t n = m.size();
  const auto a = m.accel_m_s2();
  if (k < n && same_instant(m.time_s(k), T)) {
    const bool first = k == 0;
    while (k < n && same_instant(m.time_s(k), T)) out.push_back(a[k++]);
    if (first && T > t_start && out.front() != 0.0) out.insert(out.begin(), 0.0);  // from the still ground
    if (k == n && T < t_end && out.back() != 0.0) out.push_back(0.0);             // back to the still ground
    return;
  }
  if (k == 0 || k == n) {  // before its record or after it
    out.push_back(0.0);
    return;
  }
  // Strictly between samples k-1 and k, which are then at distinct times: the linear interpolant.
  const double ta = m.time_s(k - 1);
  const double tb = m.time_s(k);
  out.push_back(a[k - 1] + (T - ta) / (tb - ta) * (a[k] - a[k - 1]));
}

}  // namespace

InputGrid::InputGrid(const GroundMotion& horizontal, const GroundMotion* vertical)
    : InputGrid(std::array<const GroundMotion*, 2>{&horizontal, vertical}) {}

InputGrid::InputGrid(std::span<const GroundMotion* const> components) {
  assert(!components.empty() && components.front() != nullptr);
  const GroundMotion& primary = *components.front();
  dt_ = primary.dt_s();
  accel_.resize(components.size());
  const bool alone =
      std::all_of(components.begin() + 1, components.end(), [](const GroundMotion* m) { return m == nullptr; });
  if (alone || same_uniform_grid(components)) {
    size_ = primary.size();
    t0_ = primary.start_time_s();
    if (!primary.is_uniform()) times_ = primary.times_s();
    for (std::size_t c = 0; c < components.size(); ++c) {
      if (components[c] != nullptr) accel_[c] = components[c]->accel_m_s2();
    }
    return;
  }

  double t_start = std::numeric_limits<double>::infinity();
  double t_end = -std::numeric_limits<double>::infinity();
  std::size_t total = 0;
  for (const GroundMotion* m : components) {
    if (m == nullptr) continue;
    t_start = std::min(t_start, m->start_time_s());
    t_end = std::max(t_end, m->end_time_s());
    total += m->size();
  }
  store_.resize(components.size());
  for (std::size_t c = 0; c < components.size(); ++c) {
    if (components[c] != nullptr) store_[c].reserve(total + 4);
  }
  times_.reserve(total + 4);
  std::vector<std::size_t> next(components.size(), 0);
  std::vector<std::vector<double>> values(components.size());
  for (;;) {
    // The next instant: the earliest sample not yet taken of any component.
    double T = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < components.size(); ++c) {
      const GroundMotion* m = components[c];
      if (m != nullptr && next[c] < m->size()) T = std::min(T, m->time_s(next[c]));
    }
    if (T == std::numeric_limits<double>::infinity()) break;
    std::size_t points = 1;
    for (std::size_t c = 0; c < components.size(); ++c) {
      if (components[c] == nullptr) continue;
      values_at(*components[c], T, t_start, t_end, next[c], values[c]);
      points = std::max(points, values[c].size());
    }
    for (std::size_t j = 0; j < points; ++j) {
      times_.push_back(T);
      for (std::size_t c = 0; c < components.size(); ++c) {
        if (components[c] == nullptr) continue;
        const auto& v = values[c];
        store_[c].push_back(v[std::min(j, v.size() - 1)]);
      }
    }
  }
  size_ = times_.size();
  t0_ = times_.front();
  for (std::size_t c = 0; c < components.size(); ++c) {
    if (components[c] != nullptr) accel_[c] = store_[c];
  }
}

std::vector<double> effective_gravity(const InputGrid& grid, std::size_t vertical, double g_m_s2) {
  std::vector<double> ge;
  if (!grid.has(vertical)) return ge;
  const auto av = grid.accel_m_s2(vertical);
  ge.resize(av.size());
  for (std::size_t i = 0; i < av.size(); ++i) ge[i] = g_m_s2 + av[i];
  return ge;
}

}  // namespace topple
