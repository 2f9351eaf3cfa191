#pragma once
// Event location shared by the ODE-based solvers (rocking.cpp, slide_rock.cpp): the root of a signed event function
// on a step's dense output, by TOMS 748 (Alefeld, Potra & Shi 1995; Boost.Math toms748_solve), to a few ulps of the
// time. Internal to the library (not installed).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include <boost/math/tools/toms748_solve.hpp>

namespace topple::detail {

/// Cap on root-finder iterations per event: TOMS 748 converges in about 10 on smooth dense output, Newton in 3 to 5;
/// 200 means a broken bracket.
inline constexpr std::uintmax_t kMaxRootIterations = 200;

/// The time tolerance of event location: a few ulps of the time itself, with a floor of 1 s so that events near t = 0
/// converge too.
inline double time_tolerance(double t) {
  return 4.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t), 1.0);
}

/// Root of f on [a, b] with f(a), f(b) of opposite signs (or zero), by TOMS 748, to time_tolerance. NaN when the
/// iterations ran out (the caller reports it with the run's parameters).
template <class F>
double find_root(F f, double a, double b, double fa, double fb) {
  if (fa == 0.0) return a;
  if (fb == 0.0) return b;
  std::uintmax_t iterations = kMaxRootIterations;
  const auto tol = [](double lo, double hi) {
    return std::abs(hi - lo) <= time_tolerance(std::max(std::abs(lo), std::abs(hi)));
  };
  const auto r = boost::math::tools::toms748_solve(f, a, b, fa, fb, tol, iterations);
  if (iterations >= kMaxRootIterations) return std::numeric_limits<double>::quiet_NaN();
  return 0.5 * (r.first + r.second);
}

}  // namespace topple::detail
