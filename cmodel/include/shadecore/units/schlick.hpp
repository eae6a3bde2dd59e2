// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate models of the Schlick-divide specular units (docs/spec.md §6).
//
//   S(t, n) = t / (n − n·t + t) = t / D,   t = cos θ,  D = n(1 − t) + t = n − (n − 1)·t
//
// In codes (c = t·2^F, 1.0 = 2^F):   out = 2^F · c / Dc   with   Dc = n·(2^F − c) + c   (exact integer)
//
// Three hardware forms, one function each, stage by stage as the RTL computes them:
//   schlick_div_eval   rtl/sc_schlick_div.v   pipelined restoring divider, one quotient bit per stage;
//                      the quotient is correctly rounded (half up): |error| <= 1/2 ulp
//   schlick_iter_eval  rtl/sc_schlick_iter.v  the same restoring division, one bit per clock, one unit
//                      → bit-identical to schlick_div_eval
//   schlick_nr_eval    rtl/sc_schlick_nr.v    leading-zero normalisation, 64-entry reciprocal table,
//                      two Newton–Raphson iterations, one multiply, round half up: faithful (< 1 ulp)
// Per-material setup is only the range check of n (no constant is precomputed).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "shadecore/format.hpp"

namespace shadecore {

struct SchlickMaterial {
  int n = 16;
};

inline SchlickMaterial schlick_setup(const Format& f, long long n) {
  validate(f);
  validate_n(n);
  return SchlickMaterial{static_cast<int>(n)};
}

// ---- widths (docs/spec.md §6.2) -------------------------------------------------------------
// Denominator Dc = n·(2^F − c) + c ∈ [2^F, n·2^F] ⊂ [2^F, 2^(F+10)]: F+11 bits, unsigned.
inline constexpr int schlick_den_bits(int F) { return F + 11; }
// Newton–Raphson form.
inline constexpr int kSchlickNrIndexBits = 6;   // P: table index = the 6 bits after the leading one
inline constexpr int kSchlickNrTableFrac = 10;  // T: table entries are 1/md with 10 fraction bits
inline constexpr int kSchlickNrIters = 2;       // Newton–Raphson iterations
inline constexpr int kSchlickNrExtra = 6;       // R − F: reciprocal fraction bits beyond F
inline constexpr int schlick_nr_recip_frac(int F) { return F + kSchlickNrExtra; }  // R

// Table entry i (0 <= i < 2^P): 1 / (midpoint of [1 + i/2^P, 1 + (i+1)/2^P)) rounded half up to
// T fraction bits, in integers:  round(2^(T+P+1) / (2^(P+1) + 2i + 1)).  Values 514..1016 (10 bits).
inline constexpr uint32_t schlick_nr_table(uint32_t i) {
  const uint64_t den = (uint64_t{1} << (kSchlickNrIndexBits + 1)) + 2 * uint64_t{i} + 1;
  const uint64_t num = uint64_t{1} << (kSchlickNrTableFrac + kSchlickNrIndexBits + 1);
  return static_cast<uint32_t>((2 * num + den) / (2 * den));
}

// Every intermediate value of one evaluation, named after the RTL pipeline registers.
struct SchlickTrace {
  uint32_t c = 0;   // S0: cos code clamped to [0, 2^F]
  uint32_t n = 0;   // S0: material exponent, travels with the fragment
  uint64_t den = 0; // S1: Dc = n·(2^F − c) + c, F+11 bits, exact
  // divider forms
  uint64_t quot = 0;  // floor(c·2^(F+1) / Dc), F+2 bits (one guard bit below the output lsb)
  uint64_t rem = 0;   // remainder of that division
  // Newton–Raphson form
  int shift = 0;      // S2: leading-zero count s of Dc in F+11 bits (0..10)
  uint64_t mt = 0;    // S2: normalised Dc = Dc·2^s, truncated to R fraction bits: value in [1, 2), R+1 bits
  uint32_t idx = 0;   // S3: table index (P bits after the leading one)
  uint64_t y[3] = {}; // S3: y0 (T fraction bits); S5: y1, S7: y2 (R fraction bits) ≈ 1/mt
  uint64_t prod = 0;  // S8: c·y2
  uint32_t out = 0;   // output code, F+1 bits, <= 2^F
};

namespace detail {
// S0 + S1 of every Schlick form: clamp, then the exact denominator.
inline void schlick_front(const Format& f, const SchlickMaterial& m, int64_t code, uint32_t& c, uint64_t& den) {
  const int64_t one = int64_t{1} << f.frac;
  c = static_cast<uint32_t>(code < 0 ? 0 : (code > one ? one : code));  // clamp, never wrap
  const uint64_t d = static_cast<uint64_t>(one) - c;                   // 2^F − c, F+1 bits
  den = static_cast<uint64_t>(m.n) * d + c;                            // n·(2^F − c) + c, exact
}
}  // namespace detail

// Restoring division, one quotient bit per step, exactly as the RTL stages do it. Returns
// floor(c·2^(F+1) / den) (F+2 bits) and the remainder. Requires c <= den.
inline uint64_t schlick_restoring_divide(int F, uint64_t c, uint64_t den, uint64_t* rem_out = nullptr) {
  // stage Q0: integer bit (c >= den happens only for c = den = 2^F)
  uint64_t q = (c >= den) ? 1 : 0;
  uint64_t r = q ? c - den : c;
  // stages Q1..Q(F+1): one fraction bit each
  for (int k = 1; k <= F + 1; ++k) {
    r <<= 1;
    const bool b = r >= den;
    if (b) r -= den;
    q = (q << 1) | (b ? 1 : 0);
  }
  if (rem_out) *rem_out = r;
  return q;
}

// Form (a)/(c): pipelined or iterative restoring divider. out = floor((q + 1) / 2): the exact
// quotient 2^F·c/Dc rounded half up (correctly rounded).
inline uint32_t schlick_div_eval(const Format& f, const SchlickMaterial& m, int64_t code, SchlickTrace* tr = nullptr) {
  uint32_t c;
  uint64_t den;
  detail::schlick_front(f, m, code, c, den);
  uint64_t rem = 0;
  // Dc = 0 only at n = 0 with c = 0 (beyond the host's n, docs/spec.md §3.1): the RTL's divider then takes every
  // quotient bit (q = 2^(F+2) − 1) and (q + 1)/2 = 2^(F+1) wraps to 0 in its F+1-bit output register. The division
  // below would divide by zero there (undefined: a SIGFPE, or 0 where the compiler folded it), so that case takes
  // the restoring steps, and the output keeps F+1 bits as the register does (no other input reaches bit F+1).
  const uint64_t q = tr || den == 0 ? schlick_restoring_divide(f.frac, c, den, &rem)
                                    : (static_cast<uint64_t>(c) << (f.frac + 1)) / den;  // same value, faster
  const uint32_t out = static_cast<uint32_t>(((q + 1) >> 1) & ((uint64_t{2} << f.frac) - 1));
  if (tr) {
    tr->c = c; tr->n = static_cast<uint32_t>(m.n); tr->den = den; tr->quot = q; tr->rem = rem; tr->out = out;
  }
  return out;
}

// The iterative form computes the same restoring division one bit per clock.
inline uint32_t schlick_iter_eval(const Format& f, const SchlickMaterial& m, int64_t code, SchlickTrace* tr = nullptr) {
  return schlick_div_eval(f, m, code, tr);
}

// One Newton–Raphson step y' = y·(2 − mt·y) in fixed point. mt has R fraction bits, y has `yf`
// fraction bits; the result has R fraction bits. Two truncations: e = ⌊mt·y / 2^yf⌋ (R fraction
// bits) and y' = ⌊y·(2 − e) / 2^yf⌋. Every product fits in 2R+3 <= 63 bits.
inline uint64_t schlick_nr_step(int R, uint64_t mt, uint64_t y, int yf) {
  const uint64_t e = (mt * y) >> yf;                 // ≈ 1, R fraction bits, R+2 bits
  const uint64_t two = uint64_t{1} << (R + 1);
  const uint64_t g = two - e;                         // 2 − e, R+2 bits, > 0 (e < 2)
  return (y * g) >> yf;                               // R fraction bits, R+1 bits (<= 2^R + 1)
}

// Form (b): reciprocal by table + two Newton–Raphson steps, then one multiply and a rounding shift.
inline uint32_t schlick_nr_eval(const Format& f, const SchlickMaterial& m, int64_t code, SchlickTrace* tr = nullptr) {
  const int F = f.frac, R = schlick_nr_recip_frac(F), DB = schlick_den_bits(F);
  constexpr int P = kSchlickNrIndexBits, T = kSchlickNrTableFrac;
  uint32_t c;
  uint64_t den;
  detail::schlick_front(f, m, code, c, den);
  // S2 — leading-zero count s: den·2^s has its leading one at bit F+10 (den >= 2^F ⇒ s <= 10). As rtl/sc_schlick_nr.v's
  // lzc_d: only bits F..F+10 are looked at and s = 10 when none is set. Dc >= 2^F for every n >= 1; Dc < 2^F needs
  // n = 0 on the port (outside the host's 16..1024, and the RTL's later stages still differ there: docs/spec.md
  // §3.1), where the unbounded search for the leading one this replaced never ended at Dc = 0.
  int s = 10;
  for (int i = 0; i <= 10; ++i)
    if ((den >> (F + i)) & 1) s = 10 - i;
  const uint64_t mn = den << s;                    // F+11 bits, value md = mn / 2^(F+10) in [1, 2)
  const uint64_t mt = mn >> (DB - 1 - R);          // truncate to R fraction bits (drops 4 bits, R+1 bits)
  // S3 — table: index = the P bits after the leading one.
  const uint32_t idx = static_cast<uint32_t>((mn >> (DB - 1 - P)) & ((1u << P) - 1));
  const uint64_t y0 = schlick_nr_table(idx);       // T fraction bits
  // S4/S5 and S6/S7 — two Newton–Raphson iterations.
  const uint64_t y1 = schlick_nr_step(R, mt, y0, T);
  const uint64_t y2 = schlick_nr_step(R, mt, y1, R);
  // S8 — multiply; S9 — round half up: out = 2^F·c/Dc = c·2^s/(md·2^10) ≈ c·y2·2^s / 2^(R+10).
  const uint64_t prod = static_cast<uint64_t>(c) * y2;  // (F+1)+(R+1) = 2F+8 bits
  const int sh = R + 10 - s;                             // R .. R+10
  const uint32_t out = static_cast<uint32_t>((prod + (uint64_t{1} << (sh - 1))) >> sh);
  if (tr) {
    tr->c = c; tr->n = static_cast<uint32_t>(m.n); tr->den = den; tr->shift = s; tr->mt = mt; tr->idx = idx;
    tr->y[0] = y0; tr->y[1] = y1; tr->y[2] = y2; tr->prod = prod; tr->out = out;
  }
  return out;
}

// Worst relative error of the table, ε0 = max |1 − md·y0| over every md in [1, 2): 1 − md·y0 is linear
// in md, so the extremes are at the ends of the 64 intervals. (0.0080872 for P = 6, T = 10.)
inline double schlick_nr_table_eps() {
  double e = 0.0;
  constexpr int P = kSchlickNrIndexBits;
  for (uint32_t i = 0; i < (1u << P); ++i) {
    const double y = std::ldexp(double(schlick_nr_table(i)), -kSchlickNrTableFrac);
    for (double md : {1.0 + std::ldexp(double(i), -P), 1.0 + std::ldexp(double(i + 1), -P)})
      e = std::max(e, std::fabs(1.0 - md * y));
  }
  return e;
}

// Analytic bound of the Newton–Raphson form in output ulps against the exact 2^F·c/Dc
// (docs/spec.md §6.4):  |out − 2^F·S| <= 1/2 + 2^F·(ε1² + 3·2^−R),  ε1 = ε0² + 2·2^−R.
inline double schlick_nr_bound_ulp(int F) {
  const double u = std::ldexp(1.0, -schlick_nr_recip_frac(F));
  const double e0 = schlick_nr_table_eps();
  const double e1 = e0 * e0 + 2.0 * u * (1.0 + 1e-6);
  return 0.5 + std::ldexp(e1 * e1 + 3.0 * u * (1.0 + 1e-6), F);
}

// Dispatch by name: "schlick_div", "schlick_nr", "schlick_iter".
enum class SchlickForm : int { Div = 0, Nr = 1, Iter = 2 };

inline uint32_t schlick_eval(SchlickForm form, const Format& f, const SchlickMaterial& m, int64_t code,
                             SchlickTrace* tr = nullptr) {
  switch (form) {
    case SchlickForm::Nr: return schlick_nr_eval(f, m, code, tr);
    case SchlickForm::Iter: return schlick_iter_eval(f, m, code, tr);
    default: return schlick_div_eval(f, m, code, tr);
  }
}

// Latency (accept edge → first edge at which out_valid_o is high, no stalls) and initiation interval
// of each RTL form (docs/spec.md §6.5).
inline constexpr int schlick_div_latency(int F) { return F + 4; }
inline constexpr int kSchlickNrLatency = 10;
inline constexpr int schlick_iter_latency(int F) { return F + 4; }
inline constexpr int schlick_iter_interval(int F) { return F + 4; }

}  // namespace shadecore

// ---- energy of the lobe (docs/schlick.md §Energy) ---------------------------------------------

namespace shadecore::golden {

// ∫_0^{π/2} S(cos θ, n) sin θ dθ = ∫_0^1 t/(n − (n−1)t) dt = n·ln n/(n−1)² − 1/(n−1)
// (with a = n, b = n − 1, a − b = 1:  t/(a − bt) = −1/b + (a/b)/(a − bt)).
inline double schlick_energy(int n) {
  const double a = n, b = n - 1.0;
  return a * std::log(a) / (b * b) - 1.0 / b;
}

// ∫_0^{π/2} S(cos θ, n) cos θ sin θ dθ = ∫_0^1 t²/(n − (n−1)t) dt = n²·ln n/(n−1)³ − n/(n−1)² − 1/(2(n−1))
// (t²/(a − bt) = −t/b − a/b² + (a²/b²)/(a − bt)).
inline double schlick_energy_cos(int n) {
  const double a = n, b = n - 1.0;
  return a * a * std::log(a) / (b * b * b) - a / (b * b) - 0.5 / b;
}

// The same integrals for cos^n: 1/(n+1) and 1/(n+2).
inline double cos_pow_energy(int n) { return 1.0 / (n + 1.0); }
inline double cos_pow_energy_cos(int n) { return 1.0 / (n + 2.0); }

}  // namespace shadecore::golden
