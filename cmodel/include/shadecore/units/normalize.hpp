// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the lighting core's vector normaliser (docs/lighting.md §3; RTL:
// rtl/sc_normalize.v, its registers named in NormalizeTrace).
//
//   normalize3(v)  unit vector v/|v| by a reciprocal square root: leading-one normalisation of
//                  s = v·v to an even power of two, a 96-entry seed table of 1/√m (10 fraction bits)
//                  and two Newton–Raphson steps y ← y·(3 − m·y²)/2 (multiplies only), then one
//                  multiply and a rounding shift per component.
//
// Every quantisation (truncation ⌊·⌋, rounding, saturation) happens exactly where the RTL has a
// register or a shift, and nowhere else. All values are integers ("codes"); a code with k fraction
// bits means code / 2^k.
#pragma once

#include <cstdint>

#include "shadecore/units/recip.hpp"

namespace shadecore {

// ---- reciprocal square root ------------------------------------------------------------------
inline constexpr int kRsqrtIndexBits = 7;  // table index = the top 7 bits of m ∈ [2^MB, 2^(MB+2))
inline constexpr int kRsqrtTableFrac = 10; // T: seeds carry 10 fraction bits
inline constexpr int kRsqrtExtra = 6;      // R − F
inline constexpr int rsqrt_frac(int F) { return F + kRsqrtExtra; }             // R: fraction bits of y
inline constexpr int rsqrt_mant_frac(int F) { return F + 6 + (F & 1); }        // MB: even

// Seed for index i ∈ [32, 128) (mantissa interval [i/32, (i+1)/32) ⊂ [1, 4)): 1/√(midpoint) with
// T fraction bits, rounded to nearest, in integers only: the largest y with (2y−1)²·(2i+1) <= 2^(2T+8)
// (i.e. y − ½ <= 2^T·8/√(2i+1)). Values 1016 .. 513. The RTL computes the same integer rule in a
// constant function.
inline constexpr uint32_t rsqrt_seed(uint32_t i) {
  const uint64_t lim = uint64_t{1} << (2 * kRsqrtTableFrac + 8);
  const uint64_t k = 2 * uint64_t{i} + 1;
  uint32_t lo = 0, hi = 1u << kRsqrtTableFrac;  // (2·1024 − 1)²·255 < 2^31: the search stays in 32 bits
  while (lo < hi) {                               // largest y in [0, 2^T] with (2y−1)²·k <= lim
    const uint32_t mid = (lo + hi + 1) / 2;
    const uint64_t t = 2 * uint64_t{mid} - 1;
    if (t * t * k <= lim) lo = mid;
    else hi = mid - 1;
  }
  return lo;
}

// Every intermediate of one normalisation (names of rtl/sc_normalize.v's registers).
struct NormalizeTrace {
  uint64_t s = 0;    // v·v, exact
  int p = 0;         // msb index of s
  int e2 = 0;        // even shift: m = s·2^e2 (truncated when e2 < 0)
  uint64_t m = 0;    // mantissa, MB fraction bits, value in [1, 4)
  uint32_t idx = 0;  // table index, 32..127
  uint64_t y[3] = {};// y0 (seed << (R−T)), y1, y2: ≈ 1/√(m/2^MB), R fraction bits
  int sh = 0;        // final right shift R + MB/2 − F − e2/2 (>= R − F)
};

// One Newton–Raphson step for 1/√m: a = ⌊y²/2^R⌋, b = ⌊m·a/2^MB⌋, c = 3·2^R − b, y' = ⌊y·c/2^(R+1)⌋.
inline uint64_t rsqrt_nr_step(int R, int MB, uint64_t m, uint64_t y) {
  const uint64_t a = (y * y) >> R;
  const uint64_t b = (m * a) >> MB;
  const uint64_t c = (uint64_t{3} << R) - b;  // b ≈ 2^R after the seed (|rel. error| < 2^-6), so c > 0
  return (y * c) >> (R + 1);
}

// The stated bound of normalize3 in output ulps (docs/lighting.md §3.1): 0.55 up to F = 22; above it the two
// Newton steps from the 7-bit seed (about 24 bits) show, 0.70 (0.694 measured at F = 24). One source for
// the test (LightOps.NormalizeBoundExhaustiveAndDense) and the handoff's interface.md.
inline constexpr double normalize3_bound_ulp(int F) { return F <= 22 ? 0.55 : 0.70; }

// u = v / |v| as signed codes with F fraction bits (1.0 = 2^F), each component rounded half up
// (toward +∞ on ties). v = 0 gives u = 0. The components of v are signed integers (any common
// fraction: the result does not depend on it) with |v_i| < 2^40.
inline void normalize3(int F, const int64_t v[3], int64_t u[3], NormalizeTrace* tr = nullptr) {
  const int R = rsqrt_frac(F), MB = rsqrt_mant_frac(F);
  NormalizeTrace t;
  t.s = static_cast<uint64_t>(v[0] * v[0]) + static_cast<uint64_t>(v[1] * v[1]) + static_cast<uint64_t>(v[2] * v[2]);
  if (t.s == 0) {
    u[0] = u[1] = u[2] = 0;
    if (tr) *tr = t;
    return;
  }
  t.p = msb_index(t.s);
  t.e2 = MB - t.p + (t.p & 1);  // even; s·2^e2 ∈ [2^MB, 2^(MB+2))
  t.m = t.e2 >= 0 ? (t.s << t.e2) : (t.s >> -t.e2);
  t.idx = static_cast<uint32_t>(t.m >> (MB + 2 - kRsqrtIndexBits));
  t.y[0] = uint64_t{rsqrt_seed(t.idx)} << (R - kRsqrtTableFrac);
  t.y[1] = rsqrt_nr_step(R, MB, t.m, t.y[0]);
  t.y[2] = rsqrt_nr_step(R, MB, t.m, t.y[1]);
  // 1/√s = (y2/2^R)·2^(e2/2 − MB/2); u_i·2^F = v_i·y2 / 2^(R + MB/2 − F − e2/2).
  t.sh = R + MB / 2 - F - t.e2 / 2;
  const int64_t half = int64_t{1} << (t.sh - 1);
  for (int i = 0; i < 3; ++i) u[i] = (v[i] * static_cast<int64_t>(t.y[2]) + half) >> t.sh;  // arithmetic shift
  if (tr) *tr = t;
}

}  // namespace shadecore
