// Flexible supports: decoupled and coupled sliding (flexible.hpp has the model, its sources and sign conventions).
#include "topple/solvers/flexible.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <utility>

#include <boost/math/tools/toms748_solve.hpp>
#include <fmt/format.h>

#include "topple/core/error.hpp"
#include "motion/ground_motion_detail.hpp"

namespace topple {
namespace {

// ---- small dense matrices and the exact propagator exp(A t) ----------------------------------------------------

template <std::size_t N>
using Vec = std::array<double, N>;

template <std::size_t N>
struct Mat {
  std::array<double, N * N> v{};
  double& operator()(std::size_t i, std::size_t j) { return v[i * N + j]; }
  double operator()(std::size_t i, std::size_t j) const { return v[i * N + j]; }
};

template <std::size_t N>
Mat<N> mul(const Mat<N>& a, const Mat<N>& b) {
  Mat<N> c;
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t k = 0; k < N; ++k) {
      const double aik = a(i, k);
      if (aik == 0.0) continue;
      for (std::size_t j = 0; j < N; ++j) c(i, j) += aik * b(k, j);
    }
  return c;
}

template <std::size_t N>
Vec<N> mul(const Mat<N>& a, const Vec<N>& x) {
  Vec<N> y{};
  for (std::size_t i = 0; i < N; ++i) {
    double s = 0.0;
    for (std::size_t j = 0; j < N; ++j) s += a(i, j) * x[j];
    y[i] = s;
  }
  return y;
}

/// exp(A t) by balancing, scaling and squaring with a Taylor series. The modal generators are badly scaled (omega^2
/// next to 1), so a diagonal similarity D^-1 A D with powers of 2 (exact; Parlett & Reinsch 1969) first brings the
/// rows and columns to comparable norms; the balanced matrix is scaled below norm 1/4, where the series is summed
/// until a term no longer changes the sum (at most 20 terms: (1/4)^21/21! ~ 1e-32), and squared back.
template <std::size_t N>
Mat<N> expm(const Mat<N>& a, double t) {
  Mat<N> x;
  for (std::size_t i = 0; i < N * N; ++i) x.v[i] = a.v[i] * t;
  std::array<double, N> d;
  d.fill(1.0);
  for (int sweep = 0; sweep < 8; ++sweep) {
    bool changed = false;
    for (std::size_t i = 0; i < N; ++i) {
      double col = 0.0;
      double row = 0.0;
      for (std::size_t j = 0; j < N; ++j) {
        if (j == i) continue;
        col += std::abs(x(j, i));
        row += std::abs(x(i, j));
      }
      if (col == 0.0 || row == 0.0) continue;
      double f = 1.0;
      const double sum = col + row;
      while (col < row / 2.0) {
        col *= 4.0;
        row /= 4.0;
        f *= 2.0;
      }
      while (col >= row * 2.0) {
        col /= 4.0;
        row *= 4.0;
        f /= 2.0;
      }
      if (col + row < 0.95 * sum) {
        changed = true;
        d[i] *= f;
        for (std::size_t j = 0; j < N; ++j) {
          x(i, j) /= f;
          x(j, i) *= f;
        }
      }
    }
    if (!changed) break;
  }
  double norm = 0.0;
  for (std::size_t i = 0; i < N; ++i) {
    double row = 0.0;
    for (std::size_t j = 0; j < N; ++j) row += std::abs(x(i, j));
    norm = std::max(norm, row);
  }
  int squarings = 0;
  while (norm > 0.25) {
    norm *= 0.5;
    ++squarings;
  }
  const double scale = std::ldexp(1.0, -squarings);
  for (double& e : x.v) e *= scale;
  Mat<N> result;
  Mat<N> term;
  for (std::size_t i = 0; i < N; ++i) result(i, i) = term(i, i) = 1.0;
  for (int k = 1; k <= 20; ++k) {
    term = mul(term, x);
    double biggest = 0.0;
    for (double& e : term.v) {
      e /= k;
      biggest = std::max(biggest, std::abs(e));
    }
    for (std::size_t i = 0; i < N * N; ++i) result.v[i] += term.v[i];
    if (biggest < 1e-18) break;  // entries of the sum are O(1): the next terms are below round-off
  }
  for (int sq = 0; sq < squarings; ++sq) result = mul(result, result);
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j) result(i, j) *= d[i] / d[j];
  return result;
}

// ---- the mode, its decoupled response ----------------------------------------------------------------------------

/// Decoupled modal response to piecewise-linear a_g. State (Y, Y', a, a') with a' constant in a step: the exact
/// propagator of  Y'' + 2 zeta omega Y' + omega^2 Y = -p a.
Mat<4> decoupled_generator(const ModalProperties& m) {
  Mat<4> a;
  a(0, 1) = 1.0;
  a(1, 0) = -m.omega_rad_s * m.omega_rad_s;
  a(1, 1) = -2.0 * m.damping_ratio * m.omega_rad_s;
  a(1, 2) = -m.participation;
  a(2, 3) = 1.0;
  return a;
}

void require_uniform(const GroundMotion& ground) {
  if (!ground.is_uniform()) {
    throw parameter_error("record", "flexible-support analyses need a uniformly sampled record (resample it first)");
  }
  if (ground.size() < 2) throw parameter_error("record", "flexible-support analyses need at least 2 samples");
}

struct LinearResponse {
  double max_abs_y = 0.0;              ///< peak |Y| (m): the strain measure of the equivalent-linear iteration
  double max_abs_demand_m_s2 = 0.0;    ///< peak |a_g + (L1/m) Y''|
  std::vector<double> demand_m_s2;     ///< filled when asked
};

/// Sub-steps per record step so that omega h <= limit (coupled: 0.5, for the event search).
int substeps_for(double omega_rad_s, double dt_s, double limit = 0.5) {
  return std::max(1, static_cast<int>(std::ceil(omega_rad_s * dt_s / limit)));
}

/// Decoupled sliding reads the support's demand as piecewise linear between points h apart; its oscillating part
/// (L1/m) Y'' is then off by up to (omega h)^2 / 8 of its amplitude between points. omega h <= 0.1 keeps that under
/// 0.13 %; the cap of 64 sub-steps only binds above omega dt = 6.4, where the support is so stiff (a 50 Hz shelf
/// under a 0.02 s record) that its demand is the ground's, linear between samples, up to decaying transients.
int decoupled_substeps(double omega_rad_s, double dt_s) { return std::min(64, substeps_for(omega_rad_s, dt_s, 0.1)); }

/// The exact recurrence of one linear output z = cy Y + cv Y' of the mode on a grid of step h with piecewise-linear
/// input a. The step propagator gives x_{k+1} = P x_k + G0 a_k + G1 a_{k+1} for x = (Y, Y') (P, G0, G1 from exp(A h):
/// G1 = p(.,3) / h, G0 = p(.,2) - G1), and P^2 = tr(P) P - det(P) I (Cayley-Hamilton) turns it into a second-order
/// recurrence on z alone (the ramp-invariant form of the oscillator, as Nigam & Jennings 1969 is the exact form for
/// linear interpolation between samples):
///   z_{k+1} = a1 z_k + a2 z_{k-1} + b0 a_{k+1} + b1 a_k + b2 a_{k-1},
///   a1 = tr P, a2 = -det P, b0 = C G1, b1 = C G0 + C (P - a1 I) G1, b2 = C (P - a1 I) G0,
/// with z_0 = 0 (rest) and z_1 = C (G0 a_0 + G1 a_1). It is the same exact solution; only one product and one sum
/// lie on the chain from one sample to the next (the state-space form has two of each), which halves the time of the
/// decoupled analysis' first half. Round-off: relative ~1e-16 / (omega h)^2 (poles near 1 when omega h is small).
struct OutputRecurrence {
  double a1 = 0.0, a2 = 0.0, b0 = 0.0, b1 = 0.0, b2 = 0.0;
  double z1_from_a0 = 0.0, z1_from_a1 = 0.0;  ///< z_1 = z1_from_a0 a_0 + z1_from_a1 a_1
};

OutputRecurrence output_recurrence(const Mat<4>& p, double h, double cy, double cv) {
  const double g1y = p(0, 3) / h;
  const double g1v = p(1, 3) / h;
  const double g0y = p(0, 2) - g1y;
  const double g0v = p(1, 2) - g1v;
  OutputRecurrence r;
  r.a1 = p(0, 0) + p(1, 1);
  r.a2 = -(p(0, 0) * p(1, 1) - p(0, 1) * p(1, 0));
  // C (P - a1 I) as a row: (cy (p00 - a1) + cv p10, cy p01 + cv (p11 - a1)).
  const double ry = cy * (p(0, 0) - r.a1) + cv * p(1, 0);
  const double rv = cy * p(0, 1) + cv * (p(1, 1) - r.a1);
  r.b0 = cy * g1y + cv * g1v;
  r.b1 = cy * g0y + cv * g0v + ry * g1y + rv * g1v;
  r.b2 = ry * g0y + rv * g0v;
  r.z1_from_a0 = cy * g0y + cv * g0v;
  r.z1_from_a1 = r.b0;
  return r;
}

/// L doubles in one vector (GCC/Clang vector extension): L = 2 is an SSE2 register, L = 4 an AVX one; Bits: the same
/// lanes as 64-bit integers. (Spelled out per L: GCC drops vector_size on a dependent alias template.)
template <std::size_t L>
struct VectorOf;
template <>
struct VectorOf<2> {
  using Doubles = double __attribute__((vector_size(16)));
  using Bits = std::uint64_t __attribute__((vector_size(16)));
};
template <>
struct VectorOf<4> {
  using Doubles = double __attribute__((vector_size(32)));
  using Bits = std::uint64_t __attribute__((vector_size(32)));
};
template <std::size_t L>
using Lanes = typename VectorOf<L>::Doubles;

/// The L x L matrix whose rows are r[0..L) transposed in place (its own inverse), by shuffles in registers.
template <std::size_t L>
[[gnu::always_inline]] inline void transpose(std::array<Lanes<L>, L>& r) {
  if constexpr (L == 2) {
    const Lanes<2> t0 = __builtin_shufflevector(r[0], r[1], 0, 2);
    const Lanes<2> t1 = __builtin_shufflevector(r[0], r[1], 1, 3);
    r = {t0, t1};
  } else {
    static_assert(L == 4);
    const Lanes<4> t0 = __builtin_shufflevector(r[0], r[1], 0, 4, 2, 6);
    const Lanes<4> t1 = __builtin_shufflevector(r[0], r[1], 1, 5, 3, 7);
    const Lanes<4> t2 = __builtin_shufflevector(r[2], r[3], 0, 4, 2, 6);
    const Lanes<4> t3 = __builtin_shufflevector(r[2], r[3], 1, 5, 3, 7);
    r[0] = __builtin_shufflevector(t0, t2, 0, 1, 4, 5);
    r[1] = __builtin_shufflevector(t1, t3, 0, 1, 4, 5);
    r[2] = __builtin_shufflevector(t0, t2, 2, 3, 6, 7);
    r[3] = __builtin_shufflevector(t1, t3, 2, 3, 6, 7);
  }
}

/// Pass 1 of run_output_recurrence: the particular solutions of S segments of `len` points from point k, written
/// segment-major (that is, in point order) to p; in_m1, in_m2 are the inputs a_{k-1}, a_{k-2}. The forcing
/// f_i = b0 a_i + b1 a_{i-1} + b2 a_{i-2} first (independent per point, vectorised), then the S chains
/// p_i = a1 p_{i-1} + a2 p_{i-2} + f_i side by side, their states in registers: segments gL .. gL + L - 1 in the L
/// lanes of one vector. Each step waits on the previous one (a product and a sum), so S / L chains run side by side to
/// keep the arithmetic units busy. L steps at a time: the L segments' next L points are L full loads, transposed in
/// registers to one vector per step and back for L full stores (a lane at a time, a load and a store per point, was
/// the loop's bound). Every lane does the same operations in the same order whatever L: the results do not depend on
/// it (nor on the clone that runs, run_output_recurrence).
template <std::size_t L, std::size_t S>
[[gnu::always_inline]] inline void particular_solutions(const OutputRecurrence& c, const double* a, std::size_t k,
                                                        std::size_t len, double in_m1, double in_m2, double* p) {
  const std::size_t points = S * len;
  p[0] = c.b0 * a[k] + c.b1 * in_m1 + c.b2 * in_m2;
  if (points > 1) p[1] = c.b0 * a[k + 1] + c.b1 * a[k] + c.b2 * in_m1;
  const double* ak = a + k;
  for (std::size_t i = 2; i < points; ++i) p[i] = c.b0 * ak[i] + c.b1 * ak[i - 1] + c.b2 * ak[i - 2];
  const double a1 = c.a1;  // locals: a store to p could otherwise alias c and force reloads
  const double a2 = c.a2;
  if constexpr (S % L == 0) {
    using V = Lanes<L>;
    constexpr std::size_t kGroups = S / L;
    const V va1 = V{} + a1;
    const V va2 = V{} + a2;
    std::array<V, kGroups> p1{}, p2{};
    std::size_t j = 0;
    for (; j + L <= len; j += L) {
#pragma GCC unroll 8
      for (std::size_t g = 0; g < kGroups; ++g) {  // unrolled: the chains' states stay in registers
        double* row = p + g * L * len + j;  // segment gL at step j; the next segments len, 2 len ... further
        std::array<V, L> f;
#pragma GCC unroll 4
        for (std::size_t i = 0; i < L; ++i) std::memcpy(&f[i], row + i * len, sizeof(V));
        transpose<L>(f);  // f[i]: the L segments' forcing at step j + i
        std::array<V, L> n;
        V prev1 = p1[g];
        V prev2 = p2[g];
#pragma GCC unroll 4
        for (std::size_t i = 0; i < L; ++i) {
          n[i] = va1 * prev1 + (va2 * prev2 + f[i]);
          prev2 = prev1;
          prev1 = n[i];
        }
        p1[g] = prev1;
        p2[g] = prev2;
        transpose<L>(n);  // back to one vector per segment
#pragma GCC unroll 4
        for (std::size_t i = 0; i < L; ++i) std::memcpy(row + i * len, &n[i], sizeof(V));
      }
    }
    for (; j < len; ++j) {  // the last len % L steps, a lane at a time
#pragma GCC unroll 8
      for (std::size_t g = 0; g < kGroups; ++g) {
        double* row = p + g * L * len + j;
        V f;
        for (std::size_t i = 0; i < L; ++i) f[i] = row[i * len];
        const V pn = va1 * p1[g] + (va2 * p2[g] + f);
        for (std::size_t i = 0; i < L; ++i) row[i * len] = pn[i];
        p2[g] = p1[g];
        p1[g] = pn;
      }
    }
  } else {
    std::array<double, S> p1{}, p2{};
    for (std::size_t j = 0; j < len; ++j) {
      for (std::size_t s = 0; s < S; ++s) {
        const double pn = a1 * p1[s] + (a2 * p2[s] + p[s * len + j]);
        p[s * len + j] = pn;
        p2[s] = p1[s];
        p1[s] = pn;
      }
    }
  }
}

/// Pass 2 of run_output_recurrence on one segment: d_j = p_j + S_j z + B_j dz (written to out when kWrite, which may
/// be p itself; z, dz: the entering state, run_output_recurrence), returning max |d_j|. 2 L points at a time in two
/// vectors, the running maximum too: a scalar one is a chain of its own, a max's latency per point.
template <std::size_t L, bool kWrite>
[[gnu::always_inline]] inline double corrected(const double* p, const double* ha, const double* hb, double z_m1,
                                               double dz, double* out, std::size_t len) {
  using V = Lanes<L>;
  using U = typename VectorOf<L>::Bits;
  const U magnitude = U{} + ~(std::uint64_t{1} << 63);  // every bit but the sign
  const V z1 = V{} + z_m1;
  const V z2 = V{} + dz;
  V m0 = {};
  V m1 = {};
  std::size_t j = 0;
  for (; j + 2 * L <= len; j += 2 * L) {
    V pa, pb, aa, ab, ba, bb;
    std::memcpy(&pa, p + j, sizeof(V));
    std::memcpy(&pb, p + j + L, sizeof(V));
    std::memcpy(&aa, ha + j, sizeof(V));
    std::memcpy(&ab, ha + j + L, sizeof(V));
    std::memcpy(&ba, hb + j, sizeof(V));
    std::memcpy(&bb, hb + j + L, sizeof(V));
    const V da_ = pa + aa * z1 + ba * z2;
    const V db_ = pb + ab * z1 + bb * z2;
    if constexpr (kWrite) {
      std::memcpy(out + j, &da_, sizeof(V));
      std::memcpy(out + j + L, &db_, sizeof(V));
    }
    // |d| by clearing the sign bit; the demand is finite (no NaN to order).
    const V ua = reinterpret_cast<V>(reinterpret_cast<U>(da_) & magnitude);
    const V ub = reinterpret_cast<V>(reinterpret_cast<U>(db_) & magnitude);
    m0 = m0 < ua ? ua : m0;
    m1 = m1 < ub ? ub : m1;
  }
  double m = 0.0;
  for (std::size_t i = 0; i < L; ++i) m = std::max(m, std::max(m0[i], m1[i]));
  for (; j < len; ++j) {
    const double d = p[j] + ha[j] * z_m1 + hb[j] * dz;
    if constexpr (kWrite) out[j] = d;
    m = std::max(m, std::abs(d));
  }
  return m;
}

/// Runs the recurrence over the n input points a (n >= 2); makes `out`, when given, the n values d_k = z_k + da a_k
/// and returns max |d_k|. (Appending each chunk to a reserved vector, instead of zeroing it first, copies as much: no
/// faster, measured.)
///
/// The chain z_{k+1} = a1 z_k + ... makes every sample wait on the previous one (a product and a sum of latency). To
/// break it, the points are taken in chunks of kSegments segments of equal length: each segment's particular
/// solution p (the recurrence from zero state, z_{s-1} = z_{s-2} = 0 before its start s) is computed side by side with
/// the others' (independent chains: instruction-level parallelism), then the exact solution is (superposition: the
/// recurrence is linear)
///   z_{s+j} = p_{s+j} + S_j z_{s-1} + B_j (z_{s-2} - z_{s-1}),
/// S and B being the homogeneous solutions from the states (z_{-1}, z_{-2}) = (1, 1) and (0, 1). The states entering
/// each segment are carried serially from segment to segment (two values per segment), the correction added in a
/// second, vectorisable pass. Algebraically the same solution. The basis (1, 1), (0, 1) keeps the correction free of
/// cancellation: with poles near 1 (omega h small) the powers from (1, 0) and (0, 1) grow like +-j and nearly cancel
/// on z_{s-1} ~ z_{s-2}, while S_j stays O(1) and B_j multiplies the small difference. Round-off: of the order of the
/// plain recurrence's ~1e-16 / (omega h)^2 relative (measured against it: docs/method.md). L: doubles per vector (2 or
/// 4, run_output_recurrence picks); the results do not depend on it.
template <std::size_t L>
[[gnu::always_inline]] inline double run_output_recurrence_in(const OutputRecurrence& output, double da,
                                                              const double* a, std::size_t n,
                                                              std::vector<double>* out) {
  // d itself obeys the recurrence, with da folded into the input terms: d_{k+1} - a1 d_k - a2 d_{k-1} = (z's input
  // terms) + da (a_{k+1} - a1 a_k - a2 a_{k-1}), from d_0 = da a_0, d_1 = z_1 + da a_1 (z_0 = 0).
  OutputRecurrence c = output;
  c.b0 += da;
  c.b1 -= c.a1 * da;
  c.b2 -= c.a2 * da;
  constexpr std::size_t kSegments = 16;
  constexpr std::size_t kMaxSegment = 128;
  constexpr std::size_t kChunk = kSegments * kMaxSegment;
  // Homogeneous solutions S_j, B_j, j < kMaxSegment (prefixes serve shorter segments).
  std::array<double, kMaxSegment> ha;
  std::array<double, kMaxSegment> hb;
  {
    double a_m1 = 1.0, a_m2 = 1.0, b_m1 = 0.0, b_m2 = 1.0;  // ha: from the state (1, 1); hb: from (0, 1)
    const std::size_t len = std::min(kMaxSegment, n);
    for (std::size_t j = 0; j < len; ++j) {
      const double an = c.a1 * a_m1 + c.a2 * a_m2;
      const double bn = c.a1 * b_m1 + c.a2 * b_m2;
      ha[j] = an;
      hb[j] = bn;
      a_m2 = a_m1;
      a_m1 = an;
      b_m2 = b_m1;
      b_m1 = bn;
    }
  }
  double z_m2 = da * a[0];                                                // d_0
  double z_m1 = output.z1_from_a0 * a[0] + output.z1_from_a1 * a[1] + da * a[1];  // d_1
  double in_m2 = a[0];  // the inputs before the next point
  double in_m1 = a[1];
  double peak = std::max(std::abs(z_m2), std::abs(z_m1));
  if (out != nullptr) {
    out->resize(n);
    (*out)[0] = z_m2;
    (*out)[1] = z_m1;
  }
  // The particular solutions of the chunk's segments, segment-major (in point order): where the output goes, or here.
  std::array<double, kChunk> buffer;
  std::size_t k = 2;             // next point
  while (k < n) {
    const std::size_t left = n - k;
    const std::size_t seg = left >= kChunk ? kMaxSegment : left / kSegments;
    const std::size_t segments = seg == 0 ? 1 : kSegments;
    const std::size_t len = seg == 0 ? left : seg;  // the last few points: one plain segment
    double* p = out != nullptr ? out->data() + k : buffer.data();
    // Pass 1: particular solutions, the segments' chains interleaved.
    if (segments == kSegments) {
      particular_solutions<L, kSegments>(c, a, k, len, in_m1, in_m2, p);
    } else {
      particular_solutions<L, 1>(c, a, k, len, in_m1, in_m2, p);
    }
    in_m2 = segments * len >= 2 ? a[k + segments * len - 2] : in_m1;
    in_m1 = a[k + segments * len - 1];
    // Pass 2: the states entering each segment (serial, two values per segment) and the correction, in place.
    for (std::size_t s = 0; s < segments; ++s) {
      double* ps = p + s * len;
      const double dz = z_m2 - z_m1;
      const double e1 = ps[len - 1] + ha[len - 1] * z_m1 + hb[len - 1] * dz;
      const double e2 = len >= 2 ? ps[len - 2] + ha[len - 2] * z_m1 + hb[len - 2] * dz : z_m1;
      const double seg_peak = out != nullptr ? corrected<L, true>(ps, ha.data(), hb.data(), z_m1, dz, ps, len)
                                             : corrected<L, false>(ps, ha.data(), hb.data(), z_m1, dz, nullptr, len);
      peak = std::max(peak, seg_peak);
      z_m1 = e1;
      z_m2 = e2;
    }
    k += segments * len;
  }
  return peak;
}

double run_output_recurrence_sse2(const OutputRecurrence& output, double da, const double* a, std::size_t n,
                                  std::vector<double>* out) {
  return run_output_recurrence_in<2>(output, da, a, n, out);
}

#if defined(__GNUC__) && defined(__x86_64__) && !defined(TOPPLE_NO_AVX2_KERNEL)
#define TOPPLE_AVX2_KERNEL 1
/// The same kernel compiled for AVX2 (4 lanes a vector), run where the CPU has it; the build stays baseline x86-64.
/// The same operations on every value as the SSE2 one, in the same order (no FMA: ISO C++ mode contracts nothing),
/// so both give the same bits.
[[gnu::target("avx2")]] double run_output_recurrence_avx2(const OutputRecurrence& output, double da, const double* a,
                                                          std::size_t n, std::vector<double>* out) {
  return run_output_recurrence_in<4>(output, da, a, n, out);
}
#endif

double run_output_recurrence(const OutputRecurrence& output, double da, const double* a, std::size_t n,
                             std::vector<double>* out) {
#ifdef TOPPLE_AVX2_KERNEL
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return run_output_recurrence_avx2(output, da, a, n, out);
#endif
  return run_output_recurrence_sse2(output, da, a, n, out);
}

/// The record's input on its steps split in `substeps` (linear interpolation: the input as the solvers read it), into
/// `grid` ((n - 1) substeps + 1 points).
void substep_input(const std::span<const double> acc, int substeps, std::vector<double>& grid) {
  const std::size_t points = (acc.size() - 1) * static_cast<std::size_t>(substeps) + 1;
  grid.resize(points);
  // The fractions j / substeps once: no division per step (it cost as much as the response itself).
  const auto s = static_cast<std::size_t>(substeps);
  std::vector<double> fraction(s);
  for (std::size_t j = 0; j < s; ++j) fraction[j] = static_cast<double>(j) / substeps;
  double* g = grid.data();
  for (std::size_t k = 0; k + 1 < acc.size(); ++k, g += s) {
    const double a0 = acc[k];
    const double rise = acc[k + 1] - a0;
    g[0] = a0;
    for (std::size_t j = 1; j < s; ++j) g[j] = a0 + rise * fraction[j];
  }
  *g = acc.back();
}

/// The decoupled response on the record's steps split in `substeps` (values at the record's samples do not depend on
/// it: the propagator is exact). The demand history, when kept, has (n - 1) substeps + 1 points; max |Y| is computed
/// only when asked (the equivalent-linear iteration's strain).
LinearResponse linear_response(const GroundMotion& ground, const ModalProperties& m, bool keep_history,
                               int substeps = 1, bool need_max_y = false) {
  const auto acc = ground.accel_m_s2();
  const double h = ground.dt_s() / substeps;
  const Mat<4> p = expm(decoupled_generator(m), h);
  const double w2 = m.omega_rad_s * m.omega_rad_s;
  const double c = 2.0 * m.damping_ratio * m.omega_rad_s;
  LinearResponse out;
  // The input on the grid: the record itself (not copied), or its linear interpolation.
  std::vector<double> grid;
  const double* input = acc.data();
  std::size_t n = acc.size();
  if (substeps > 1) {
    substep_input(acc, substeps, grid);
    input = grid.data();
    n = grid.size();
  }
  // Demand a + q Y'' with Y'' = -p a - c Y' - w2 Y: (1 - q p) a - q c Y' - q w2 Y.
  const double da = 1.0 - m.mass_fraction * m.participation;
  const OutputRecurrence demand = output_recurrence(p, h, -m.mass_fraction * w2, -m.mass_fraction * c);
  if (need_max_y) out.max_abs_y = run_output_recurrence(output_recurrence(p, h, 1.0, 0.0), 0.0, input, n, nullptr);
  out.max_abs_demand_m_s2 = run_output_recurrence(demand, da, input, n, keep_history ? &out.demand_m_s2 : nullptr);
  return out;
}

// Column constants: phi(z) = sin(pi z / 2H), L1/M1 = 4/pi, L1/m = 2/pi.
constexpr double kColumnParticipation = 4.0 / kPi;
constexpr double kColumnMassFraction = 2.0 / kPi;

ModalProperties column_mode(double height_m, double vs_m_s, double damping_total) {
  ModalProperties m;
  m.omega_rad_s = kPi * vs_m_s / (2.0 * height_m);
  m.damping_ratio = damping_total;
  m.participation = kColumnParticipation;
  m.mass_fraction = kColumnMassFraction;
  m.vs_m_s = vs_m_s;
  return m;
}

/// Darendeli's (2001) damping form on the hyperbolic backbone, as SLAMMER uses it (pySLAMMER strain_damp_update):
/// Masing damping of the hyperbola, scaled by 0.62 (G/Gmax)^0.1, plus 1 % small-strain damping.
double equivalent_damping(double g_ratio, double strain, double ref_strain) {
  const double sum = strain + ref_strain;
  const double masing = (4.0 * (strain - ref_strain * std::log(sum / ref_strain)) / (strain * strain / sum) - 2.0) / kPi;
  return 0.62 * std::pow(g_ratio, 0.1) * masing + 0.01;
}

// ---- coupled analysis: the two-phase linear system --------------------------------------------------------------

// State w = (Y, Y', s, s', a_g, a_g', 1) and, with a vertical record, (a_v, a_v'): N = 7 or 9. Without a vertical
// record the 7-state system runs (the same arithmetic as before vertical input existed).
// The components by name, also the rows and columns of the generators (row i: the derivative of component i): Y, Y'
// (the support's modal coordinate and its velocity), s, s' (the slip and its velocity), a_g and its slope within the
// step, the constant 1 (it carries the friction terms), a_v and its slope.
enum Component : std::size_t {
  kY = 0,
  kYDot = 1,
  kSlip = 2,
  kSlipDot = 3,
  kGround = 4,
  kGroundSlope = 5,
  kOne = 6,
  kVertical = 7,       // N = 9 only
  kVerticalSlope = 8,  // N = 9 only
};
constexpr std::size_t kPlain = 7;
constexpr std::size_t kWithVertical = 9;
enum Phase : int { stick = 0, slip_down = 1, slip_up = 2 };

template <std::size_t N>
struct CoupledSystem {
  std::array<Mat<N>, 3> generator;  ///< d/dt state per phase
  Vec<N> demand{};                  ///< stick-phase demand D(w) (m/s^2): sliding force per unit sliding mass
  /// The friction capacity per unit sliding mass, mu (g + a_v) (k_y for mu on the column), as a row on the state.
  Vec<N> yield_row{};
  double g_m_s2 = kStandardGravity;  ///< g of the normal force m (g + a_v)
  double omega_max = 0.0;            ///< fastest mode over the phases (sets the sub-step)
  double mass_fraction = 1.0;        ///< L1/m: the surface's absolute acceleration is a_g + (L1/m) Y''
  bool two_way = false;
};

template <std::size_t N>
void fill_input_rows(Mat<N>& a) {
  a(kY, kYDot) = 1.0;  // Y' = Y'
  a(kSlip, kSlipDot) = 1.0;  // s' = s'
  a(kGround, kGroundSlope) = 1.0;  // a_g' = slope, constant within a step
  if constexpr (N == kWithVertical) a(kVertical, kVerticalSlope) = 1.0;  // a_v' likewise
}

/// The friction terms of the slip phases: the coefficient c of the constant state (c = X mu g) goes with c / g on a_v,
/// so that the term is X mu (g + a_v) (normal force m (g + a_v)).
template <std::size_t N>
void add_friction(Mat<N>& a, std::size_t row, double coefficient_of_one, double g_m_s2) {
  a(row, kOne) = coefficient_of_one;
  if constexpr (N == kWithVertical) a(row, kVertical) = coefficient_of_one / g_m_s2;
}

template <std::size_t N>
Vec<N> yield_row(double yield_m_s2, double g_m_s2) {
  Vec<N> r{};
  r[kOne] = yield_m_s2;
  if constexpr (N == kWithVertical) r[kVertical] = yield_m_s2 / g_m_s2;
  return r;
}

/// Column (Chopra & Zhang 1991 as SLAMMER's Coupled): equations in flexible.hpp.
template <std::size_t N>
CoupledSystem<N> column_system(const ModalProperties& m, double yield_m_s2, double g_m_s2, bool two_way) {
  CoupledSystem<N> sys;
  const double w2 = m.omega_rad_s * m.omega_rad_s;
  const double c = 2.0 * m.damping_ratio * m.omega_rad_s;
  const double p = m.participation;
  const double q = m.mass_fraction;
  const double d1 = 1.0 - p * q;  // 1 - L1^2 / (M1 m) = 1 - 8/pi^2
  for (auto& g : sys.generator) fill_input_rows<N>(g);
  // stick: Y'' = -p a - c Y' - w2 Y
  sys.generator[stick](kYDot, kY) = -w2;
  sys.generator[stick](kYDot, kYDot) = -c;
  sys.generator[stick](kYDot, kGround) = -p;
  // D = a + q Y''
  sys.demand[kY] = -q * w2;
  sys.demand[kYDot] = -q * c;
  sys.demand[kGround] = 1.0 - q * p;
  for (int ph : {slip_down, slip_up}) {
    const double sigma = ph == slip_down ? 1.0 : -1.0;
    auto& g = sys.generator[ph];
    // d1 Y'' = -p sigma ky g - c Y' - w2 Y
    g(kYDot, kY) = -w2 / d1;
    g(kYDot, kYDot) = -c / d1;
    add_friction(g, kYDot, -p * sigma * yield_m_s2 / d1, g_m_s2);
    // s'' = a + q Y'' - sigma ky g
    g(kSlipDot, kY) = q * g(kYDot, kY);
    g(kSlipDot, kYDot) = q * g(kYDot, kYDot);
    g(kSlipDot, kGround) = 1.0;
    add_friction(g, kSlipDot, q * g(kYDot, kOne) - sigma * yield_m_s2, g_m_s2);
  }
  sys.yield_row = yield_row<N>(yield_m_s2, g_m_s2);
  sys.g_m_s2 = g_m_s2;
  sys.omega_max = m.omega_rad_s / std::sqrt(d1);
  sys.mass_fraction = q;
  sys.two_way = two_way;
  return sys;
}

/// Shelf or floor: object of mass r M_s on a one-mode support (flexible.hpp).
template <std::size_t N>
CoupledSystem<N> shelf_system(const ModalProperties& m, double mass_ratio, double yield_m_s2, double g_m_s2,
                              bool two_way) {
  CoupledSystem<N> sys;
  const double w2 = m.omega_rad_s * m.omega_rad_s;
  const double c = 2.0 * m.damping_ratio * m.omega_rad_s;
  const double r = mass_ratio;
  for (auto& g : sys.generator) fill_input_rows<N>(g);
  // stick: Y'' = -a - (c Y' + w2 Y) / (1 + r), D = a + Y''
  sys.generator[stick](kYDot, kY) = -w2 / (1.0 + r);
  sys.generator[stick](kYDot, kYDot) = -c / (1.0 + r);
  sys.generator[stick](kYDot, kGround) = -1.0;
  sys.demand[kY] = -w2 / (1.0 + r);
  sys.demand[kYDot] = -c / (1.0 + r);
  for (int ph : {slip_down, slip_up}) {
    const double sigma = ph == slip_down ? 1.0 : -1.0;
    auto& g = sys.generator[ph];
    // Y'' = -a - c Y' - w2 Y - r sigma mu g ; s'' = a + Y'' - sigma mu g
    g(kYDot, kY) = -w2;
    g(kYDot, kYDot) = -c;
    g(kYDot, kGround) = -1.0;
    add_friction(g, kYDot, -r * sigma * yield_m_s2, g_m_s2);
    g(kSlipDot, kY) = -w2;
    g(kSlipDot, kYDot) = -c;
    add_friction(g, kSlipDot, -r * sigma * yield_m_s2 - sigma * yield_m_s2, g_m_s2);
  }
  sys.yield_row = yield_row<N>(yield_m_s2, g_m_s2);
  sys.g_m_s2 = g_m_s2;
  sys.omega_max = m.omega_rad_s;
  sys.two_way = two_way;
  return sys;
}

template <std::size_t N>
double dot(const Vec<N>& a, const Vec<N>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < N; ++i) s += a[i] * b[i];
  return s;
}

/// The linear quantity an event watches: the demand in stick, the slip velocity s' while slipping.
template <std::size_t N>
Vec<N> watched(const CoupledSystem<N>& sys, Phase phase) {
  if (phase == stick) return sys.demand;
  Vec<N> c{};
  c[kSlipDot] = 1.0;
  return c;
}

/// Event function of a phase from its watched quantity x: an event happens where it rises through 0. Stick: the
/// demand beyond the yield level (either direction in two-way mode); slip: the velocity back through zero.
/// `yield` (stick only) is the friction capacity mu (g + a_v) at the same instant.
template <std::size_t N>
double event_from(const CoupledSystem<N>& sys, Phase phase, double x, double yield) {
  switch (phase) {
    case stick: return sys.two_way ? std::abs(x) - yield : x - yield;
    case slip_down: return -x;
    case slip_up: return x;
  }
  return 0.0;
}

template <std::size_t N>
double event_value(const CoupledSystem<N>& sys, Phase phase, const Vec<N>& w) {
  return event_from(sys, phase, dot(watched(sys, phase), w), dot(sys.yield_row, w));
}

/// c^T P: the watched quantity after the step P as one dot product with the state before it.
template <std::size_t N>
Vec<N> row_through(const Vec<N>& c, const Mat<N>& p) {
  Vec<N> r{};
  for (std::size_t i = 0; i < N; ++i)
    for (std::size_t j = 0; j < N; ++j) r[j] += c[i] * p(i, j);
  return r;
}

/// Phase entered from stick (demand above yield) or after a slip stops (checking that the stick demand holds).
template <std::size_t N>
Phase stick_or_slip(const CoupledSystem<N>& sys, const Vec<N>& w) {
  const double d = dot(sys.demand, w);
  const double yield = dot(sys.yield_row, w);
  if (d > yield) return slip_down;
  if (sys.two_way && d < -yield) return slip_up;
  return stick;
}

/// The state of a coupled run between sub-steps (w, the phase, the summary so far) and the two things done to it: a
/// sub-step of the two-phase linear system with its slip events located, and a row of the history. The propagators
/// over a sub-step of length h (and over its half, for the event search at the midpoint) are formed once per run.
template <std::size_t N>
class CoupledRun {
 public:
  CoupledRun(const CoupledSystem<N>& sys, double h, FlexibleHistory* history) : sys_(sys), h_(h), history_(history) {
    for (int ph = 0; ph < 3; ++ph) {
      const Mat<N> half = expm(sys.generator[ph], 0.5 * h);
      full_[ph] = mul(half, half);
      mid_row_[ph] = row_through(watched(sys, static_cast<Phase>(ph)), half);
      mid_yield_[ph] = row_through(sys.yield_row, half);
    }
    w[kOne] = 1.0;
  }

  /// The state at t into the summary (and the history when kept).
  void note_state(double t) {
    if (history_ != nullptr) {
      // The sliding surface's absolute acceleration a_g + (L1/m) Y'', Y'' from the current phase's equation.
      const Mat<N>& gen = sys_.generator[phase];
      double y_dd = 0.0;
      for (std::size_t j = 0; j < N; ++j) y_dd += gen(kYDot, j) * w[j];
      history_->sliding.time_s.push_back(t);
      history_->sliding.displacement_m.push_back(w[kSlip]);
      history_->sliding.velocity_m_s.push_back(w[kSlipDot]);
      history_->sliding.state.push_back(phase == stick       ? SlipState::stuck
                                       : phase == slip_down ? SlipState::slipping_down
                                                            : SlipState::slipping_up);
      history_->support_accel_m_s2.push_back(w[kGround] + sys_.mass_fraction * y_dd);
    }
    const double s = std::abs(w[kSlip]);
    if (s > out.max_abs_displacement_m) {
      out.max_abs_displacement_m = s;
      out.max_displacement_time_s = t;
    }
    out.max_abs_velocity_m_s = std::max(out.max_abs_velocity_m_s, std::abs(w[kSlipDot]));
  }

  /// One sub-step of length h from time t0 with the current input slope (already in w[kGround], w[kGroundSlope]).
  void substep(double t0) {
    double tau = 0.0;
    int events = 0;
    while (tau < h_) {
      if (++events > 64) {
        throw EventLimitError(fmt::format("coupled sliding: more than 64 slip events in one sub-step of {} s at t = {} s",
                                      h_, t0 + tau));
      }
      const double rest = h_ - tau;
      const bool whole = tau == 0.0;
      if (rest <= 1e-12 * h_) {
        // An event within round-off of the sub-step's end: finish the sub-step without looking for another one.
        w = mul(expm(sys_.generator[phase], rest), w);
        break;
      }
      double e_mid = 0.0;
      Vec<N> w_end;
      if (whole) {
        w_end = mul(full_[phase], w);
        e_mid = event_from(sys_, phase, dot(mid_row_[phase], w), dot(mid_yield_[phase], w));
      } else {
        const Mat<N> p_mid = expm(sys_.generator[phase], 0.5 * rest);
        w_end = mul(mul(p_mid, p_mid), w);
        e_mid = event_value(sys_, phase, mul(p_mid, w));
      }
      const double e_end = event_value(sys_, phase, w_end);
      if (e_mid <= 0.0 && e_end <= 0.0) {
        w = w_end;
        tau = h_;
        break;
      }
      // Bracket [lo, hi]: hi is the first probe where the event function is positive; lo a point before it where it
      // is negative. At a phase's start the function may be exactly 0 (slip has just started: s' = 0): then probe
      // inward from hi by halving until it is negative.
      const Mat<N>& gen = sys_.generator[phase];
      const Vec<N> w0 = w;
      const auto f = [&](double t) { return event_value(sys_, phase, mul(expm(gen, t), w0)); };
      const double hi = e_mid > 0.0 ? 0.5 * rest : rest;
      double lo = e_mid > 0.0 ? 0.0 : 0.5 * rest;
      double f_lo = e_mid > 0.0 ? event_value(sys_, phase, w0) : e_mid;
      for (int halvings = 0; f_lo >= 0.0 && halvings < 60; ++halvings) {
        lo = (lo == 0.0 ? hi : lo) * 0.5;
        f_lo = f(lo);
      }
      double t_event = hi;
      if (f_lo < 0.0) {
        std::uintmax_t iters = 200;
        const auto r = boost::math::tools::toms748_solve(f, lo, hi, f_lo, f(hi),
                                                         boost::math::tools::eps_tolerance<double>(50), iters);
        if (iters >= 200) {
          throw RootFindingError(fmt::format("coupled sliding: slip event not located in 200 iterations at t = {} s", t0 + tau));
        }
        t_event = r.second;  // the side where the event function is >= 0: the event has happened
      } else {
        t_event = lo;  // the function never went negative: the event is at the phase's start (to 2^-60 h)
      }
      w = mul(expm(gen, t_event), w0);
      tau += t_event;
      const double t_now = t0 + tau;
      if (phase == stick) {
        // The demand has reached the yield level: slip in its direction (not re-tested, round-off could undo it).
        phase = dot(sys_.demand, w) >= 0.0 ? slip_down : slip_up;
        ++out.slip_episodes;
        if (!out.first_slip_time_s) out.first_slip_time_s = t_now;
        slip_start_time_ = t_now;
      } else {
        w[kSlipDot] = 0.0;  // the slip velocity is zero at the stop, by definition of the event
        out.total_slip_duration_s += t_now - slip_start_time_;
        const Phase next = stick_or_slip(sys_, w);
        // At a stop s'' has the stopping sign, so the stick demand is inside the yield level on that side (s'' =
        // (D - sigma k_y g) / d1); only a two-way reversal can follow at once.
        phase = next == phase ? stick : next;
        if (phase != stick) {
          ++out.slip_episodes;  // a reversal through s' = 0 counts as a new episode (as sliding.hpp)
          slip_start_time_ = t_now;
        }
      }
      note_state(t_now);
    }
  }

  Vec<N> w{};
  Phase phase = stick;
  SlidingSummary out;

 private:
  const CoupledSystem<N>& sys_;
  double h_;
  FlexibleHistory* history_;
  std::array<Mat<N>, 3> full_;
  std::array<Vec<N>, 3> mid_row_;    // the watched quantity at the sub-step's midpoint, as a row on the state
  std::array<Vec<N>, 3> mid_yield_;  // the friction capacity there, likewise
  double slip_start_time_ = 0.0;
};

/// The coupled response; `history` (optional) receives every sub-step end and every event.
/// And `vertical` (N = 9 only) is read at the sub-step ends, linear between them.
template <std::size_t N>
SlidingSummary run_coupled(const GroundMotion& ground, const CoupledSystem<N>& sys, const GroundMotion* vertical,
                           FlexibleHistory* history) {
  const auto acc = ground.accel_m_s2();
  const double dt = ground.dt_s();
  // omega h <= 0.5 for the event search; capped at 256 sub-steps (omega dt > 128: a support so stiff that its demand
  // follows the ground, linear within a record step, apart from transients that decay within the step).
  const int n_sub = std::min(256, substeps_for(sys.omega_max, dt));
  const double h = dt / n_sub;
  CoupledRun<N> run(sys, h, history);
  Vec<N>& w = run.w;
  SlidingSummary& out = run.out;
  // Vertical input (N = 9): a_v read at the sub-step's ends and linear between them (exact when the vertical record's
  // samples lie on the sub-step grid, e.g. the horizontal's); the normal force m (g + a_v) vanishing is reported as
  // the rigid solver does (contact_lost_time_s), located by the linear root within the sub-step.
  const double g_m_s2 = sys.g_m_s2;
  double av_end = 0.0;
  const auto set_vertical = [&](double t0) {
    if constexpr (N == kWithVertical) {
      const double av0 = vertical->accel_at(t0);
      av_end = vertical->accel_at(t0 + h);
      w[kVertical] = av0;
      w[kVerticalSlope] = (av_end - av0) / h;
      if (!out.contact_lost_time_s && g_m_s2 + av_end <= 0.0) {
        const double n0 = g_m_s2 + av0;
        out.contact_lost_time_s = n0 <= 0.0 ? t0 : t0 + h * n0 / (n0 - (g_m_s2 + av_end));
      }
    } else {
      static_cast<void>(t0);
    }
  };
  const double t_begin = ground.start_time_s();
  if (history != nullptr) {
    w[kGround] = acc[0];
    if constexpr (N == kWithVertical) w[kVertical] = vertical->accel_at(t_begin);
    run.note_state(t_begin);
  }
  for (std::size_t k = 0; k + 1 < acc.size(); ++k) {
    const double slope = (acc[k + 1] - acc[k]) / dt;
    const double tk = t_begin + static_cast<double>(k) * dt;
    for (int j = 0; j < n_sub; ++j) {
      w[kGround] = acc[k] + slope * (static_cast<double>(j) * h);
      w[kGroundSlope] = slope;
      set_vertical(tk + static_cast<double>(j) * h);
      run.substep(tk + static_cast<double>(j) * h);
      run.note_state(tk + static_cast<double>(j + 1) * h);
    }
  }
  // Run-out: the ground is still after the record; a sliding body decelerates to rest on the still-ringing support.
  double t = ground.end_time_s();
  constexpr long kMaxRunOutSubsteps = 10'000'000;
  long runout = 0;
  while (run.phase != stick) {
    if (++runout > kMaxRunOutSubsteps) {
      throw StepLimitError(fmt::format("coupled sliding: still sliding {} s after the record's end", static_cast<double>(runout) * h));
    }
    w[kGround] = 0.0;
    w[kGroundSlope] = 0.0;
    set_vertical(t);  // a vertical record that lasts beyond the horizontal one acts on the run-out
    run.substep(t);
    t += h;
    run.note_state(t);
  }
  out.residual_displacement_m = w[kSlip];
  out.end_time_s = std::max(t, ground.end_time_s());
  out.at_rest_at_end = true;
  return out;
}

double check_ky(double ky_g) {
  if (!std::isfinite(ky_g) || !(ky_g > 0.0)) {
    throw parameter_error("ky", fmt::format("yield coefficient must be positive and finite, got {}", ky_g));
  }
  return ky_g;
}

}  // namespace

// ---- value types ---------------------------------------------------------------------------------------------------

SupportOscillator SupportOscillator::make(double freq_hz, double damping_ratio, double mass_ratio) {
  if (!std::isfinite(freq_hz) || !(freq_hz > 0.0)) {
    throw parameter_error("support_freq", fmt::format("support frequency must be positive and finite, got {} Hz", freq_hz));
  }
  if (freq_hz > kMaxFreqHz) {
    throw parameter_error("support_freq", fmt::format("support frequency {} Hz is above {:g} Hz, where no shelf or floor "
                                                      "is: a support that stiff moves with the ground (leave the "
                                                      "support out for a rigid one)",
                                                      freq_hz, kMaxFreqHz));
  }
  if (!std::isfinite(damping_ratio) || damping_ratio < 0.0 || damping_ratio >= 1.0) {
    throw parameter_error("support_damping",
                          fmt::format("support damping ratio must be in [0, 1), got {}", damping_ratio));
  }
  if (!std::isfinite(mass_ratio) || mass_ratio < 0.0) {
    throw parameter_error("mass_ratio", fmt::format("mass ratio must be finite and >= 0, got {}", mass_ratio));
  }
  return SupportOscillator{freq_hz, damping_ratio, mass_ratio};
}

double SlidingMassColumn::impedance_damping(double vs_base_m_s, double vs_slope_m_s) noexcept {
  return std::min(0.55016 * std::pow(vs_base_m_s / vs_slope_m_s, -0.9904), 0.2);
}

SlidingMassColumn SlidingMassColumn::make(double height_m, double vs_slope_m_s, double vs_base_m_s,
                                          double damping_ratio, std::optional<double> reference_strain) {
  const auto positive = [](double v, const char* field, const char* what, const char* unit) {
    if (!std::isfinite(v) || !(v > 0.0)) {
      throw parameter_error(field, fmt::format("{} must be positive and finite, got {} {}", what, v, unit));
    }
  };
  positive(height_m, "height", "sliding-mass height", "m");
  positive(vs_slope_m_s, "vs_slope", "shear-wave velocity of the sliding mass", "m/s");
  positive(vs_base_m_s, "vs_base", "shear-wave velocity of the base", "m/s");
  // The column's first mode, V_s / 4H (column_mode), under the same limit as a shelf's frequency (SupportOscillator::
  // kMaxFreqHz): beyond it the mass moves with its base, and a column of 1e-150 m would overflow omega^2 in the
  // propagator as a 1e200 Hz shelf does.
  if (const double f1 = vs_slope_m_s / (4.0 * height_m); !(f1 <= SupportOscillator::kMaxFreqHz)) {
    throw parameter_error("height", fmt::format("a {} m column with V_s {} m/s has its first mode at V_s / 4H = {:.4g} Hz, "
                                                "above {:g} Hz: it moves with its base (a rigid block)",
                                                height_m, vs_slope_m_s, f1, SupportOscillator::kMaxFreqHz));
  }
  if (reference_strain) positive(*reference_strain, "reference_strain", "reference strain", "(decimal)");
  const double total = damping_ratio + impedance_damping(vs_base_m_s, vs_slope_m_s);
  if (!std::isfinite(damping_ratio) || total < 0.0 || total >= 1.0) {
    throw parameter_error("damping", fmt::format("damping ratio {} plus the base impedance damping {} must be in "
                                                 "[0, 1), got {}",
                                                 damping_ratio, impedance_damping(vs_base_m_s, vs_slope_m_s), total));
  }
  return SlidingMassColumn{height_m, vs_slope_m_s, vs_base_m_s, damping_ratio, reference_strain};
}

// ---- modal properties ------------------------------------------------------------------------------------------

double max_peak_amplification(double zeta) noexcept {
  if (!(zeta > 0.0)) return std::numeric_limits<double>::infinity();
  // omega = 1: Y = -exp(-zeta t) sin(wd t) / wd for a unit impulse of ground acceleration, and the absolute
  // acceleration h = -(2 zeta Y' + Y) = exp(-zeta t) (2 zeta cos(wd t) + (1 - 2 zeta^2) / wd sin(wd t)).
  const double wd = std::sqrt(1.0 - zeta * zeta);
  const double t1 = (kPi - std::atan2(2.0 * zeta * wd, 1.0 - 2.0 * zeta * zeta)) / wd;  // first zero of h
  const double v1 = -std::exp(-zeta * t1) * (std::cos(wd * t1) - zeta / wd * std::sin(wd * t1));  // Y'(t1); Y'(0+) = -1
  const double q = std::exp(-zeta * kPi / wd);
  return std::abs(1.0 + v1) + std::abs(v1) * (1.0 + q) / (1.0 - q);
}

ModalProperties modal_properties(const SupportOscillator& support) {
  ModalProperties m;
  m.omega_rad_s = 2.0 * kPi * support.freq_hz;
  m.damping_ratio = support.damping_ratio;
  return m;
}

ModalProperties modal_properties(const SlidingMassColumn& column, const GroundMotion& ground) {
  const double imp0 = SlidingMassColumn::impedance_damping(column.vs_base_m_s, column.vs_slope_m_s);
  ModalProperties m = column_mode(column.height_m, column.vs_slope_m_s, column.damping_ratio + imp0);
  if (!column.reference_strain) return m;
  require_uniform(ground);
  // SLAMMER's iteration (pySLAMMER Decoupled.equivalent_linear): response with the current properties, strain,
  // new G and D, convergence when both moved by less than 5 % relative to the previous iteration.
  const double gamma_r = *column.reference_strain;
  const double g_max_ratio = 1.0;
  double g_ratio_prev = g_max_ratio;
  double damp_prev = column.damping_ratio;
  constexpr int kMaxIterations = 100;
  constexpr double kTolerance = 0.05;
  for (int it = 1;; ++it) {
    if (it > kMaxIterations) {
      throw EquivalentLinearError(fmt::format("equivalent-linear iteration did not converge in {} iterations (G/Gmax {}, "
                                    "damping {})", kMaxIterations, g_ratio_prev, damp_prev));
    }
    const double y_max = linear_response(ground, m, false, 1, true).max_abs_y;
    // Effective strain: 0.65 of the peak strain at the base of the mode, phi'(0) = pi / 2H.
    const double strain = 0.65 * (kPi / 2.0) * y_max / column.height_m;
    const double g_ratio = 1.0 / (1.0 + strain / gamma_r);
    const double damp = strain > 0.0 ? equivalent_damping(g_ratio, strain, gamma_r) : 0.01;
    const double vs = column.vs_slope_m_s * std::sqrt(g_ratio);
    m = column_mode(column.height_m, vs, damp + SlidingMassColumn::impedance_damping(column.vs_base_m_s, vs));
    m.iterations = it;
    const double change_g = std::abs(g_ratio - g_ratio_prev) / g_ratio_prev;
    const double change_d = damp_prev != 0.0 ? std::abs(damp - damp_prev) / std::abs(damp_prev) : 1.0;
    g_ratio_prev = g_ratio;
    damp_prev = damp;
    if (change_g <= kTolerance && change_d <= kTolerance) return m;
  }
}

std::vector<double> support_acceleration_m_s2(const GroundMotion& ground, const ModalProperties& mode) {
  require_uniform(ground);
  return linear_response(ground, mode, true).demand_m_s2;
}

// ---- analyses ----------------------------------------------------------------------------------------------------

namespace {

/// The demand as a record on the sub-stepped grid, and its peak.
std::pair<GroundMotion, double> demand_motion(const GroundMotion& ground, const ModalProperties& mode) {
  const int substeps = decoupled_substeps(mode.omega_rad_s, ground.dt_s());
  LinearResponse r = linear_response(ground, mode, true, substeps);
  RecordMetadata meta = ground.metadata();
  // The response's peak is known, so its samples are not checked one by one again (GroundMotionFactory). They are
  // finite: a stable linear recurrence (|a2| <= 1) with finite coefficients on finite samples; an overflow would show
  // as an infinite peak, which the factory refuses.
  const double peak = r.max_abs_demand_m_s2;
  return {detail::GroundMotionFactory::uniform_with_peak(std::move(r.demand_m_s2), peak, ground.dt_s() / substeps,
                                                         ground.start_time_s(), std::move(meta)),
          peak};
}

FlexibleSummary decoupled(const GroundMotion& ground, const ModalProperties& mode, const SlidingBlock& block,
                          const GroundMotion* vertical, FlexibleHistory* history) {
  const auto [support, peak] = demand_motion(ground, mode);
  FlexibleSummary out;
  out.mode = mode;
  out.kmax = peak / block.g_m_s2;
  if (history == nullptr) {
    out.sliding = slide_summary(support, block, vertical);
    return out;
  }
  SlidingResult r = slide(support, block, vertical);
  out.sliding = r.summary;
  history->sliding = std::move(r.history);
  history->support_accel_m_s2.clear();
  for (const double t : history->sliding.time_s) history->support_accel_m_s2.push_back(support.accel_at(t));
  return out;
}

}  // namespace

GroundMotion support_motion(const GroundMotion& ground, const SupportOscillator& support) {
  require_uniform(ground);
  return demand_motion(ground, modal_properties(support)).first;
}

namespace {
FlexibleSummary shelf_analysis(const GroundMotion& ground, const SupportOscillator& support, const SlidingBlock& block,
                               FlexibleAnalysis analysis, const GroundMotion* vertical, FlexibleHistory* history) {
  require_uniform(ground);
  const ModalProperties mode = modal_properties(support);
  if (analysis == FlexibleAnalysis::decoupled) return decoupled(ground, mode, block, vertical, history);
  if (block.slope_rad != 0.0 || block.mu_kinetic != block.mu_static) {
    throw parameter_error("mu_kinetic", "the coupled analysis models level ground with one friction coefficient "
                                        "(mu_kinetic = mu_static, slope 0)");
  }
  FlexibleSummary out;
  out.mode = mode;
  out.kmax = linear_response(ground, mode, false, decoupled_substeps(mode.omega_rad_s, ground.dt_s())).max_abs_demand_m_s2 /
             block.g_m_s2;
  const bool two_way = block.mode == SlidingMode::two_way;
  const double yield = block.mu_static * block.g_m_s2;
  out.sliding =
      vertical != nullptr
          ? run_coupled(ground, shelf_system<kWithVertical>(mode, support.mass_ratio, yield, block.g_m_s2, two_way),
                        vertical, history)
          : run_coupled(ground, shelf_system<kPlain>(mode, support.mass_ratio, yield, block.g_m_s2, two_way), nullptr,
                        history);
  return out;
}

FlexibleSummary column_analysis(const GroundMotion& ground, const SlidingMassColumn& column, double ky_g,
                                FlexibleAnalysis analysis, SlidingMode mode, double g_m_s2,
                                const GroundMotion* vertical, FlexibleHistory* history) {
  require_uniform(ground);
  check_ky(ky_g);
  const SlidingBlock block = SlidingBlock::make(ky_g, ky_g, 0.0, mode, g_m_s2);
  const ModalProperties props = modal_properties(column, ground);
  if (analysis == FlexibleAnalysis::decoupled) return decoupled(ground, props, block, vertical, history);
  FlexibleSummary out;
  out.mode = props;
  out.kmax =
      linear_response(ground, props, false, decoupled_substeps(props.omega_rad_s, ground.dt_s())).max_abs_demand_m_s2 / g_m_s2;
  const bool two_way = mode == SlidingMode::two_way;
  out.sliding = vertical != nullptr
                    ? run_coupled(ground, column_system<kWithVertical>(props, ky_g * g_m_s2, g_m_s2, two_way), vertical,
                                  history)
                    : run_coupled(ground, column_system<kPlain>(props, ky_g * g_m_s2, g_m_s2, two_way), nullptr, history);
  return out;
}
}  // namespace

FlexibleSummary slide_flexible(const GroundMotion& ground, const SupportOscillator& support, const SlidingBlock& block,
                               FlexibleAnalysis analysis, const GroundMotion* vertical) {
  return shelf_analysis(ground, support, block, analysis, vertical, nullptr);
}

FlexibleSummary slide_flexible(const GroundMotion& ground, const SlidingMassColumn& column, double ky_g,
                               FlexibleAnalysis analysis, SlidingMode mode, double g_m_s2,
                               const GroundMotion* vertical) {
  return column_analysis(ground, column, ky_g, analysis, mode, g_m_s2, vertical, nullptr);
}

FlexibleResult slide_flexible_history(const GroundMotion& ground, const SupportOscillator& support,
                                      const SlidingBlock& block, FlexibleAnalysis analysis,
                                      const GroundMotion* vertical) {
  FlexibleResult r;
  r.summary = shelf_analysis(ground, support, block, analysis, vertical, &r.history);
  return r;
}

FlexibleResult slide_flexible_history(const GroundMotion& ground, const SlidingMassColumn& column, double ky_g,
                                      FlexibleAnalysis analysis, SlidingMode mode, double g_m_s2,
                                      const GroundMotion* vertical) {
  FlexibleResult r;
  r.summary = column_analysis(ground, column, ky_g, analysis, mode, g_m_s2, vertical, &r.history);
  return r;
}

}  // namespace topple
