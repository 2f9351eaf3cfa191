// numerics/dp5.hpp: the one Dormand-Prince 5(4) tableau of the library. The rocking engine writes its step out with
// these coefficients (src/solvers/rocking_steppers.hpp); the slide-rock and 2-D sliding engines step with
// Boost.Odeint's runge_kutta_dopri5. These tests hold the two to one method: a step, its error estimate and its dense
// output written with this tableau equal Odeint's, and the step has the method's order.
#include <array>
#include <cmath>

#include <boost/numeric/odeint/stepper/runge_kutta_dopri5.hpp>
#include <gtest/gtest.h>

#include "topple/numerics/dp5.hpp"

namespace topple {
namespace {

namespace dp5 = detail::dp5;
using State = std::array<double, 2>;

/// A forced, damped oscillator: smooth, time-dependent, both components coupled (omega = 3 rad/s, zeta = 0.05).
void forced_oscillator(const State& x, State& dxdt, double t) {
  dxdt[0] = x[1];
  dxdt[1] = -9.0 * x[0] - 0.3 * x[1] + std::sin(2.0 * t);
}

State axpy(const State& x, double h, std::initializer_list<std::pair<double, const State*>> terms) {
  State r = x;
  for (std::size_t i = 0; i < 2; ++i) {
    double s = 0.0;
    for (const auto& [c, k] : terms) s += c * (*k)[i];
    r[i] += h * s;
  }
  return r;
}

/// One step written out from the tableau: the stages, the 5th-order result, the error estimate and the stages kept
/// for the dense output (k1, k3, k4, k5, k6, k7).
struct TableauStep {
  State x1{}, err{};
  std::array<State, 6> k{};
};

TableauStep tableau_step(const State& x0, double t0, double h) {
  State k1, k2, k3, k4, k5, k6, k7;
  forced_oscillator(x0, k1, t0);
  forced_oscillator(axpy(x0, h, {{dp5::b21, &k1}}), k2, t0 + dp5::a2 * h);
  forced_oscillator(axpy(x0, h, {{dp5::b31, &k1}, {dp5::b32, &k2}}), k3, t0 + dp5::a3 * h);
  forced_oscillator(axpy(x0, h, {{dp5::b41, &k1}, {dp5::b42, &k2}, {dp5::b43, &k3}}), k4, t0 + dp5::a4 * h);
  forced_oscillator(axpy(x0, h, {{dp5::b51, &k1}, {dp5::b52, &k2}, {dp5::b53, &k3}, {dp5::b54, &k4}}), k5,
                    t0 + dp5::a5 * h);
  forced_oscillator(
      axpy(x0, h, {{dp5::b61, &k1}, {dp5::b62, &k2}, {dp5::b63, &k3}, {dp5::b64, &k4}, {dp5::b65, &k5}}), k6, t0 + h);
  TableauStep s;
  s.x1 = axpy(x0, h, {{dp5::c1, &k1}, {dp5::c3, &k3}, {dp5::c4, &k4}, {dp5::c5, &k5}, {dp5::c6, &k6}});
  forced_oscillator(s.x1, k7, t0 + h);
  s.err = axpy(State{}, h, {{dp5::dc1, &k1}, {dp5::dc3, &k3}, {dp5::dc4, &k4}, {dp5::dc5, &k5}, {dp5::dc6, &k6},
                            {dp5::dc7, &k7}});
  s.k = {k1, k3, k4, k5, k6, k7};
  return s;
}

State dense(const State& x0, double h, const TableauStep& s, double frac) {
  State r = x0;
  for (std::size_t i = 0; i < 2; ++i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < 6; ++j) {
      double b = 0.0;  // b_j(frac) by Horner, as the rocking stepper evaluates it
      for (std::size_t m = 6; m-- > 0;) b = b * frac + dp5::kDense[j].c[m];
      sum += b * s.k[j][i];
    }
    r[i] += h * sum;
  }
  return r;
}

// The two implementations differ only in the order of their floating-point operations (Odeint sums the stages in
// its algebra's order and evaluates the dense weights factored, the tableau step as above): agreement to a few
// units in the last place of the state's scale, 1e-14, says they are one method; a wrong coefficient shows at 1e-6.
constexpr double kSameMethod = 1e-14;

TEST(Dp5, AStepFromTheTableauIsOdeintsStep) {
  boost::numeric::odeint::runge_kutta_dopri5<State> odeint_dp5;
  const State x0{0.3, -0.7};
  for (const double h : {0.01, 0.05, 0.2}) {
    const double t0 = 1.25;
    State dxdt0, x1, dxdt1, err;
    forced_oscillator(x0, dxdt0, t0);
    odeint_dp5.do_step(forced_oscillator, x0, dxdt0, t0, x1, dxdt1, h, err);
    const TableauStep s = tableau_step(x0, t0, h);
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_NEAR(s.x1[i], x1[i], kSameMethod) << "h = " << h << ", component " << i;
      // The error estimate is a difference of two 5th/4th-order sums: compared on the state's scale too.
      EXPECT_NEAR(s.err[i], err[i], kSameMethod) << "h = " << h << ", component " << i;
    }
    // The dense output at the ends is the step's own ends, and inside it is Odeint's calc_state.
    for (const double frac : {0.0, 0.25, 0.5, 0.9, 1.0}) {
      State odeint_x;
      odeint_dp5.calc_state(t0 + frac * h, odeint_x, x0, dxdt0, t0, x1, dxdt1, t0 + h);
      const State mine = dense(x0, h, s, frac);
      for (std::size_t i = 0; i < 2; ++i) EXPECT_NEAR(mine[i], odeint_x[i], kSameMethod) << "s = " << frac;
    }
    for (std::size_t i = 0; i < 2; ++i) {
      EXPECT_NEAR(dense(x0, h, s, 1.0)[i], s.x1[i], kSameMethod);
      EXPECT_EQ(dense(x0, h, s, 0.0)[i], x0[i]);  // b_j(0) = 0 exactly
    }
  }
}

TEST(Dp5, TheStepIsFifthOrder) {
  // y' = -y from y(0) = 1 (as a 2-vector with a zero second component): the local error of one step is C h^6, so
  // halving h divides it by 2^6 = 64; the measured ratios lie within 10 % of it over these steps (the next term of
  // the error, O(h^7), moves the ratio by a few per cent at h = 0.2).
  const auto decay = [](const State& x, State& dxdt, double) {
    dxdt[0] = -x[0];
    dxdt[1] = 0.0;
  };
  // A fresh stepper for each step: Odeint's DP5 keeps the last derivative (first same as last) between calls.
  using Dopri = boost::numeric::odeint::runge_kutta_dopri5<State>;
  double previous = 0.0;
  for (const double h : {0.2, 0.1, 0.05, 0.025}) {
    State x{1.0, 0.0};
    Dopri().do_step(decay, x, 0.0, h);
    const double error = std::abs(x[0] - std::exp(-h));
    if (previous > 0.0) {
      EXPECT_NEAR(previous / error, 64.0, 6.4) << "h = " << h;
    }
    previous = error;
  }
  // A polynomial solution of degree <= 5 is integrated exactly: y' = 5 t^4 from 0 gives t^5 (to round-off).
  const auto quintic = [](const State&, State& dxdt, double t) {
    dxdt[0] = 5.0 * t * t * t * t;
    dxdt[1] = 0.0;
  };
  State x{0.0, 0.0};
  Dopri().do_step(quintic, x, 0.0, 0.5);
  EXPECT_NEAR(x[0], std::pow(0.5, 5), 1e-16);
}

}  // namespace
}  // namespace topple
