#pragma once
// The conventions of shared/references/rocking.md that the rocking engine's tests (tests/solvers/test_rocking.cpp)
// and the closed forms' tests (tests/closed_forms/test_rocking_closed_forms.cpp) both use: its g, the tolerance of
// its printed digits, and its two ways of giving a block.
#include <cmath>

#include "topple/bodies/rocking_body.hpp"

namespace topple::test {

/// rocking.md uses g = 9.81 m/s^2 unless a case says otherwise.
inline constexpr double kG = 9.81;

/// Half a unit in the last printed digit of a rocking.md number given with 6 decimals: the closed form may differ
/// from the printed value by that much and no more.
inline constexpr double kPrinted6 = 5e-7;

/// Rectangular block with slenderness alpha and frequency parameter p: R = 3 g / (4 p^2) (rocking.md section 0).
inline RockingBody block_alpha_p(double alpha, double p, double g = kG) {
  const double R = 3.0 * g / (4.0 * p * p);
  return RockingBody::block(2.0 * R * std::sin(alpha), 2.0 * R * std::cos(alpha));
}

/// The R4 geometry: full width B = 1 m, alpha = 0.2 rad, H = B / tan(alpha) (OpenSees RockingBC_example.tcl).
inline RockingBody r4_block() { return RockingBody::block(1.0, 1.0 / std::tan(0.2)); }

}  // namespace topple::test
