#pragma once
// Dormand-Prince 5(4) (Dormand & Prince 1980, J. Comput. Appl. Math. 6(1), 19-26): the tableau, the embedded error
// estimate and the 4th-order dense output of Hairer, Norsett & Wanner 1993, II.5 and II.6, as Boost.Odeint's
// runge_kutta_dopri5 has them. One tableau for the library's DP5 integrators: the rocking engine's stepper
// (src/solvers/rocking_steppers.hpp) writes the step out for its two components with these coefficients; the
// slide-rock and 2-D sliding engines step with Boost.Odeint's runge_kutta_dopri5, the same method (docs/method.md).
// Internal to the library (not installed).
#include <array>
#include <cstddef>

namespace topple::detail::dp5 {
constexpr double a2 = 1.0 / 5.0, a3 = 3.0 / 10.0, a4 = 4.0 / 5.0, a5 = 8.0 / 9.0;
constexpr double b21 = 1.0 / 5.0;
constexpr double b31 = 3.0 / 40.0, b32 = 9.0 / 40.0;
constexpr double b41 = 44.0 / 45.0, b42 = -56.0 / 15.0, b43 = 32.0 / 9.0;
constexpr double b51 = 19372.0 / 6561.0, b52 = -25360.0 / 2187.0, b53 = 64448.0 / 6561.0, b54 = -212.0 / 729.0;
constexpr double b61 = 9017.0 / 3168.0, b62 = -355.0 / 33.0, b63 = 46732.0 / 5247.0, b64 = 49.0 / 176.0,
                 b65 = -5103.0 / 18656.0;
// 5th-order weights (the FSAL row: also stage 7's coefficients)
constexpr double c1 = 35.0 / 384.0, c3 = 500.0 / 1113.0, c4 = 125.0 / 192.0, c5 = -2187.0 / 6784.0, c6 = 11.0 / 84.0;
// 5th-order minus 4th-order weights: the error estimate
constexpr double dc1 = c1 - 5179.0 / 57600.0, dc3 = c3 - 7571.0 / 16695.0, dc4 = c4 - 393.0 / 640.0,
                 dc5 = c5 - -92097.0 / 339200.0, dc6 = c6 - 187.0 / 2100.0, dc7 = -1.0 / 40.0;

/// Polynomial in the step fraction s, coefficients of s^0 .. s^5.
struct Poly {
  std::array<double, 6> c{};
  constexpr Poly operator+(const Poly& o) const {
    Poly r;
    for (std::size_t i = 0; i < 6; ++i) r.c[i] = c[i] + o.c[i];
    return r;
  }
  constexpr Poly operator*(double k) const {
    Poly r;
    for (std::size_t i = 0; i < 6; ++i) r.c[i] = c[i] * k;
    return r;
  }
  constexpr Poly operator*(const Poly& o) const {  // the products used here stay within degree 5
    Poly r;
    for (std::size_t i = 0; i < 6; ++i) {
      for (std::size_t j = 0; i + j < 6; ++j) r.c[i + j] += c[i] * o.c[j];
    }
    return r;
  }
};

/// The dense-output weights b_j(s) of Hairer, Norsett & Wanner (II.6; odeint's calc_state), as polynomials:
/// x(t0 + s h) = x0 + h sum_j b_j(s) k_j, j = 1, 3, 4, 5, 6, 7.
constexpr std::array<Poly, 6> dense_weights() {
  const Poly s{{0, 1, 0, 0, 0, 0}};
  const Poly one{{1, 0, 0, 0, 0, 0}};
  const Poly sm1 = s + one * -1.0;
  const Poly A = s * s * (one * 3.0 + s * -2.0);
  const Poly B = s * s * sm1;
  const Poly C = s * s * sm1 * sm1;
  const Poly D = s * sm1 * sm1;
  const auto X = [&](double k, double a, double b, double d) { return (one * a + s * -b) * (k / d); };
  const Poly X1 = X(5.0, 2558722523.0, 31403016.0, 11282082432.0);
  const Poly X3 = X(100.0, 882725551.0, 15701508.0, 32700410799.0);
  const Poly X4 = X(25.0, 443332067.0, 31403016.0, 1880347072.0);
  const Poly X5 = X(32805.0, 23143187.0, 3489224.0, 199316789632.0);
  const Poly X6 = X(55.0, 29972135.0, 7076736.0, 822651844.0);
  const Poly X7 = X(10.0, 7414447.0, 829305.0, 29380423.0);
  return {A * c1 + C * X1 * -1.0 + D, A * c3 + C * X3, A * c4 + C * X4 * -1.0,
          A * c5 + C * X5,            A * c6 + C * X6 * -1.0, B + C * X7};
}
constexpr std::array<Poly, 6> kDense = dense_weights();
}  // namespace topple::detail::dp5
