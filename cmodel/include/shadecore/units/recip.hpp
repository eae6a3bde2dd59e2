// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the lighting core's attenuation reciprocal (docs/lighting.md §3;
// RTL: rtl/sc_recip.v, its registers named in RecipTrace).
//
//   recip_att(q)   attenuation 1/q by a reciprocal: leading-one normalisation, the 64-entry table
//                  and Newton–Raphson step of the Schlick NR unit (schlick_nr_table, schlick_nr_step:
//                  the same functions, not copies), a rounding shift and saturation.
//
// Every quantisation happens exactly where the RTL has a register or a shift, and nowhere else.
#pragma once

#include <cstdint>

#include "shadecore/units/schlick.hpp"

namespace shadecore {

// Index of the most significant one (s > 0).
inline int msb_index(uint64_t s) { return 63 - __builtin_clzll(s); }

// ---- attenuation reciprocal ------------------------------------------------------------------
inline constexpr int kAttIntBits = 8;                          // att < 256
inline constexpr int recip_frac(int F) { return F + 8; }       // R: fraction bits of y and of the mantissa
inline constexpr uint64_t att_max(int F) { return (uint64_t{1} << (F + kAttIntBits)) - 1; }

struct RecipTrace {
  uint64_t q = 0;
  int p = 0;           // msb index of q
  bool sat = false;    // q < 2^(F−8): 1/q >= 256, saturated
  uint64_t mt = 0;     // mantissa, R fraction bits, value in [1, 2)
  uint32_t idx = 0;    // the 6 bits after the leading one
  uint64_t y[3] = {};  // y0 (T = 10 fraction bits), y1, y2 (R fraction bits) ≈ 1/mt
  int sh = 0;          // right shift R + p − 2F (>= 0 when not saturated)
  uint64_t att = 0;
};

// att = 2^F / (q / 2^F) = 1/q with F fraction bits: q has F fraction bits; rounded half up, saturated
// to att_max(F) (q = 0 and every q < 2^(F−8) give att_max).
inline uint64_t recip_att(int F, uint64_t q, RecipTrace* tr = nullptr) {
  const int R = recip_frac(F);
  RecipTrace t;
  t.q = q;
  if (q == 0 || msb_index(q) < F - kAttIntBits) {
    t.p = q ? msb_index(q) : 0;
    t.sat = true;
    t.att = att_max(F);
    if (tr) *tr = t;
    return t.att;
  }
  t.p = msb_index(q);
  t.mt = t.p <= R ? (q << (R - t.p)) : (q >> (t.p - R));  // value q/2^p ∈ [1, 2), truncated
  t.idx = static_cast<uint32_t>((t.mt >> (R - kSchlickNrIndexBits)) & ((1u << kSchlickNrIndexBits) - 1));
  t.y[0] = schlick_nr_table(t.idx);
  t.y[1] = schlick_nr_step(R, t.mt, t.y[0], kSchlickNrTableFrac);
  t.y[2] = schlick_nr_step(R, t.mt, t.y[1], R);
  // 1/q_v = (y2/2^R)·2^(F−p) → att·2^F = y2 / 2^(R + p − 2F).
  t.sh = R + t.p - 2 * F;
  uint64_t a = t.sh > 0 ? ((t.y[2] + (uint64_t{1} << (t.sh - 1))) >> t.sh) : t.y[2];
  t.att = a > att_max(F) ? att_max(F) : a;
  if (tr) *tr = t;
  return t.att;
}

}  // namespace shadecore
