// Onset of rocking, sliding or slide-rock from rest (Shenton 1996): see shenton.hpp for the criteria.
#include "topple/solvers/shenton.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "topple/core/enum_names.hpp"
#include "topple/core/error.hpp"

namespace topple {

constexpr std::array<EnumName<OnsetMode>, 5> kOnsetModeNames{{
    {OnsetMode::unchecked, "unchecked"},
    {OnsetMode::rest, "rest"},
    {OnsetMode::rock, "rock"},
    {OnsetMode::slide, "slide"},
    {OnsetMode::slide_rock, "slide-rock"},
}};

std::string_view onset_mode_name(OnsetMode mode) { return enum_name(kOnsetModeNames, mode); }

double shenton_critical_mu(const RockingBody& body, double accel_ratio) {
  if (!std::isfinite(accel_ratio) || accel_ratio < 0.0) {
    throw parameter_error("accel_ratio", fmt::format("|a_h|/(g + a_v) must be finite and >= 0, got {}", accel_ratio));
  }
  const double a = body.a_m;
  const double h = body.h_m;
  const double D = body.D_m2;
  return (accel_ratio * (D - h * h) + a * h) / ((D - a * a) + accel_ratio * a * h);
}

OnsetMode shenton_onset_mode(const RockingBody& body, double accel_ratio, double mu) {
  if (!std::isfinite(mu) || mu < 0.0) {
    throw parameter_error("mu", fmt::format("friction coefficient must be finite and >= 0, got {}", mu));
  }
  const double mu_crit = shenton_critical_mu(body, accel_ratio);  // validates accel_ratio
  const double beta = body.a_m / body.h_m;
  if (accel_ratio < std::min(mu, beta)) return OnsetMode::rest;
  if (mu < beta) return OnsetMode::slide;
  return mu >= mu_crit ? OnsetMode::rock : OnsetMode::slide_rock;
}

}  // namespace topple
