#pragma once
// The step-size law of the Dormand-Prince 5(4) integrators (rocking.cpp, slide_rock.cpp): Boost.Odeint's
// default_step_adjuster without libm pow. Internal to the library (not installed).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

namespace topple::detail {

/// The step-size law of Hairer, Norsett & Wanner (1993, II.4, eq 4.13) as Boost.Odeint's default_step_adjuster
/// applies it: after a rejected step dt *= max(0.9 err^(-1/3), 1/5) (err^(-1/(q-1)) with q = 4, the embedded order);
/// after an accepted one with err < 0.5, dt *= 0.9 max(err, 5^-5)^(-1/5), at most x4.5; otherwise unchanged.
struct StepLaw {
  [[nodiscard]] static double decrease(double dt, double error) {
    return dt * std::max(0.9 * std::pow(error, -1.0 / 3.0), 0.2);
  }
  [[nodiscard]] static double increase(double dt, double error) {
    if (!(error < 0.5)) return dt;
    constexpr double kFloor = 1.0 / 3125.0;  // 5^-5: below it the growth cap 0.9 * 5 applies
    if (error <= kFloor) return dt * 4.5;
    return dt * 0.9 * inverse_fifth_root(error);
  }

  /// x^(-1/5) for 5^-5 < x < 0.5 (the range increase uses it on), to round-off: a first guess from the
  /// exponent bits, then Newton on y^-5 = x (y <- y (6 - x y^5) / 5, quadratic). IEEE operations only, so the same
  /// steps on every machine; a tenth of a libm pow (which was 4 % of the inversion's instructions).
  static double inverse_fifth_root(double x) {
    // x = m 2^e, m in [0.5, 1): y0 = 2^(-e/5) times the chord of m^(-1/5) on [0.5, 1] (within 1.5 % of the root).
    // The exponent and mantissa from the bits (x is normal and positive here): std::frexp is a library call.
    const auto bits = std::bit_cast<std::uint64_t>(x);
    const int e = static_cast<int>((bits >> 52) & 0x7ff) - 1022;
    const double m = std::bit_cast<double>((bits & 0x000f'ffff'ffff'ffffULL) | 0x3fe0'0000'0000'0000ULL);
    double y = std::bit_cast<double>(static_cast<std::uint64_t>(1023 - e / 5) << 52);  // 2^(-e/5), e/5 truncated
    const int r = -e % 5;  // remaining exponent fifths, -4 .. 4
    constexpr double kFifth[9] = {0.5743491774985174, 0.6597539553864471, 0.7578582832551990,
                                  0.8705505632961241, 1.0, 1.1486983549970351, 1.3195079107728942,
                                  1.5157165665103980, 1.7411011265922482};  // 2^(k/5), k = -4 .. 4
    y *= kFifth[r + 4] * (1.2973967099940701 - 0.2973967099940701 * m);
    for (int k = 0; k < 4; ++k) {  // error 1.5e-2 -> 6e-4 -> 1e-6 -> 3e-12 -> round-off
      const double y2 = y * y;
      y = y * (6.0 - x * (y2 * y2 * y)) * 0.2;
    }
    return y;
  }
};

}  // namespace topple::detail
