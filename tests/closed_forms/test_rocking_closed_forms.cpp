// The closed forms of rocking (closed_forms/rocking.hpp) against the reference numbers of
// shared/references/rocking.md (R4-R8), moved from tests/solvers/test_rocking.cpp, which checks the rocking engine
// against these closed forms.
#include <cmath>

#include <gtest/gtest.h>

#include "support/rocking_references.hpp"
#include "topple/closed_forms/rocking.hpp"
#include "topple/core/error.hpp"
#include "topple/core/units.hpp"
#include "topple/solvers/rocking.hpp"

namespace topple {
namespace {

using test::block_alpha_p;
using test::kG;
using test::kPrinted6;
using test::r4_block;

TEST(RockingClosedForms, R4PeriodOfFreeRockingWithoutLoss) {
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  // Closed forms (library benchmarks) against rocking.md: T_lin = 3.080962 s (formula), T = 3.084580 s (quadrature).
  EXPECT_NEAR(linearized_free_rocking_period_s(b, theta0, kG), 3.080962, kPrinted6);
  EXPECT_NEAR(free_rocking_period_s(b, theta0, kG), 3.084580, kPrinted6);
}

TEST(RockingClosedForms, R5SpeedAtFirstImpact) {
  const auto b = r4_block();
  const double theta0 = 0.5 * b.alpha_rad();
  EXPECT_NEAR(free_rocking_impact_speed_rad_s(b, theta0, kG), 0.295529, kPrinted6);
}

TEST(RockingClosedForms, R6AmplitudeDecayFollowsTheExactRecursion) {
  const auto b = r4_block();
  const double alpha = b.alpha_rad();
  const double theta0 = 0.5 * alpha;
  const double e = housner_restitution(b);
  // rocking.md R6 nonlinear column, theta_n / alpha (6 decimals).
  const double table[] = {0.420356, 0.358023, 0.307494};
  for (int n = 1; n <= 3; ++n) {
    EXPECT_NEAR(free_rocking_amplitude_rad(b, theta0, e, n) / alpha, table[n - 1], kPrinted6) << n;
  }
}

TEST(RockingClosedForms, R7RectangularPulseLinearized) {
  const double p = 2.0;
  const double alpha = 0.2;
  const auto b = block_alpha_p(alpha, p);
  // Linearised closed form a / (g alpha) = 1 / (1 - exp(-p t1)) (rocking.md R7 table, 6 decimals).
  const double pt1[] = {0.25, 0.5, 1.0, 2.0, 4.0};
  const double lin[] = {4.520812, 2.541494, 1.581977, 1.156518, 1.018657};
  for (int i = 0; i < 5; ++i) {
    EXPECT_NEAR(rectangular_pulse_threshold_linearized_m_s2(b, pt1[i] / p, kG) / (kG * alpha), lin[i], kPrinted6);
  }
}

TEST(RockingClosedForms, R8VelocityImpulse) {
  // dv_crit = (g / (p cos alpha)) sqrt(2 (1 - cos alpha)), p = 2 (rocking.md R8 table, 6 decimals).
  const double alphas[] = {5, 10, 20};
  const double table[] = {0.429541, 0.868188, 1.812815};
  const double small[] = {0.428042, 0.856084, 1.712168};
  for (int i = 0; i < 3; ++i) {
    const auto b = block_alpha_p(deg_to_rad(alphas[i]), 2.0);
    EXPECT_NEAR(velocity_impulse_threshold_m_s(b, kG), table[i], kPrinted6);
    EXPECT_NEAR(kG * deg_to_rad(alphas[i]) / 2.0, small[i], kPrinted6);
  }
  const auto b = r4_block();
  const double dv = velocity_impulse_threshold_m_s(b, kG);
  EXPECT_NEAR(dv, 1.168890, kPrinted6);
}

TEST(RockingClosedForms, InvalidInputsNameTheField) {
  const auto b = r4_block();
  EXPECT_THROW((void)linearized_free_rocking_period_s(b, 0.0, kG), InputError);
  EXPECT_THROW((void)free_rocking_period_s(b, b.alpha_rad(), kG), InputError);
  EXPECT_THROW((void)free_rocking_impact_speed_rad_s(b, 0.1, 0.0), InputError);
  EXPECT_THROW((void)free_rocking_amplitude_rad(b, 0.1, 1.5, 1), InputError);
  EXPECT_THROW((void)free_rocking_amplitude_rad(b, 0.1, 0.9, -1), InputError);
  EXPECT_THROW((void)rectangular_pulse_threshold_linearized_m_s2(b, 0.0, kG), InputError);
  EXPECT_THROW((void)velocity_impulse_threshold_m_s(b, -1.0), InputError);
}

}  // namespace
}  // namespace topple
