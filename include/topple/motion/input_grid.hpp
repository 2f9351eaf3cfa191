#pragma once
// InputGrid: several ground-motion components (horizontal, vertical, a second horizontal ...) on one time grid, for
// the solvers.
//
// Model. Each component is piecewise linear between its samples and zero outside its own record (GroundMotion: the
// ground is still before and after), and may jump: two samples at one instant mean a jump (a rectangular pulse).
// The solvers integrate exactly, or with steps that end on samples, only if every component is linear over every
// step of the grid, so the grid is the union of all the components' sample times, and a jump of any component is
// two grid points at the same instant:
//   - a time where every component is continuous is one grid point, with each component's value there (its own
//     sample where it has one, else its linear interpolant: exact, since it is linear between its samples);
//   - a time where some component has k samples (a jump when k >= 2) gives max k points at that instant; a component
//     with fewer values there repeats its last one (the instant has no duration, so only the values before and
//     after it matter);
//   - a component whose record starts after the grid's start (or ends before its end) jumps there from (to) the
//     still ground: a point with 0 and one with its first (last) sample, unless that sample is 0.
// The grid spans all the components, from the earliest start to the latest end: the ground moves as long as any
// component does. The first component (the primary, a horizontal record) is never absent.
//
// Cost. When every component is on the primary's uniform grid (or the primary is alone), nothing is copied: the grid
// refers to the motions' samples, which must outlive it. Otherwise a merge in one pass over all samples.
#include <cstddef>
#include <span>
#include <vector>

#include "topple/motion/ground_motion.hpp"

namespace topple {

class InputGrid {
 public:
  /// components[0] is the primary (not null); a null entry is an absent component, zero everywhere.
  explicit InputGrid(std::span<const GroundMotion* const> components);
  /// The common case: a horizontal record and an optional vertical one (components 0 and 1).
  InputGrid(const GroundMotion& horizontal, const GroundMotion* vertical);

  // The views below point into this object's own storage or into the motions: copying would leave them pointing into
  // the original, so the grid moves (vectors keep their buffers on move) but does not copy.
  InputGrid(const InputGrid&) = delete;
  InputGrid& operator=(const InputGrid&) = delete;
  InputGrid(InputGrid&&) noexcept = default;
  InputGrid& operator=(InputGrid&&) noexcept = default;
  ~InputGrid() = default;

  /// Number of grid points (at least 2).
  [[nodiscard]] std::size_t size() const noexcept { return size_; }
  /// Number of components given (absent ones included).
  [[nodiscard]] std::size_t components() const noexcept { return accel_.size(); }
  /// True when the points are t0 + i dt (times_s() is then empty).
  [[nodiscard]] bool is_uniform() const noexcept { return times_.empty(); }
  /// Time of point i, s. Repeated times are jumps.
  [[nodiscard]] double time_s(std::size_t i) const noexcept {
    return times_.empty() ? t0_ + static_cast<double>(i) * dt_ : times_[i];
  }
  /// All point times, s (empty for a uniform grid).
  [[nodiscard]] std::span<const double> times_s() const noexcept { return times_; }
  /// First point's time, s.
  [[nodiscard]] double start_time_s() const noexcept { return t0_; }
  /// Step of a uniform grid, s; for an irregular grid, the primary's dt_s() (its mean interval): the solvers' scale
  /// for a first step or a run-out grid.
  [[nodiscard]] double dt_s() const noexcept { return dt_; }
  /// Acceleration of component c at each point, m/s^2; empty for an absent component (zero everywhere).
  [[nodiscard]] std::span<const double> accel_m_s2(std::size_t c) const noexcept { return accel_[c]; }
  /// Whether component c was given.
  [[nodiscard]] bool has(std::size_t c) const noexcept { return !accel_[c].empty(); }

 private:
  std::size_t size_ = 0;
  double t0_ = 0.0;
  double dt_ = 0.0;
  std::vector<double> times_;
  std::vector<std::vector<double>> store_;         // merged values, when a merge was needed
  std::vector<std::span<const double>> accel_;     // per component: into store_ or into the motion
};

/// Effective gravity g + a_v at each grid point, m/s^2, with a_v component `vertical` (positive up); empty when that
/// component is absent (g everywhere).
[[nodiscard]] std::vector<double> effective_gravity(const InputGrid& grid, std::size_t vertical, double g_m_s2);

}  // namespace topple
