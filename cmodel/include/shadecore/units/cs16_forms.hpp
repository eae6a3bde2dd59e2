// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the cs16 forms with folded, truncated squarers
// (rtl/sc_cs16.v FORM = 1 with rtl/sc_square.v; docs/spec.md §3.4). The constants of each form
// (variants with a "squarer" entry in config/configs.json) arrive through the generated
// shadecore/variants.hpp (SquarerForm); the per-width stage parameters are derived here by the
// same rule as the localparams of rtl/sc_cs16.v:
//   B = F + (rel_guard ? G : 0);  W0 = F+4;  W_k = B + stage_frac[k-1]  (k = 1..4)
//   shift_k = 2·W_(k-1) − W_k (k = 1..3),  shift_4 = 2·W3 − F
//   drop_k  = clamp(2·W_(k-1) − W_k − (ceil(log2 W_(k-1)) + keep[k-1]), 0, shift_k)
//   C_k     = square_comp(N = W_(k-1), shift_k, drop_k, rnd = compensate (k < 4) / 1 (k = 4), compensate)
#pragma once

#include <algorithm>
#include <cmath>
#include <string_view>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "shadecore/units/cs16.hpp"
#include "shadecore/format.hpp"
#include "shadecore/units/square.hpp"
#include "shadecore/variants.hpp"

namespace shadecore {

// Pipeline latency of rtl/sc_cs16.v FORM = 1: registers S1 (x0) .. S4 (x3) and S5 (out); the input stage
// (clamp, n·d, cut) is combinational into S1 (docs/spec.md §3.4). The reference form has S0..S6 (7).
inline constexpr int kCs16FormLatency = 5;

struct Cs16Stages {
  int w[5] = {};         // fraction bits of x0..x4 (w[4]: stage 4's truncation point only)
  SquareStage sq[5];     // sq[1..4]; sq[4] gives the F+1-bit output directly
};

inline int ceil_log2(int v) {
  int r = 0;
  while ((1 << r) < v) ++r;
  return r;
}

// Throws std::invalid_argument (one line) if the form gives illegal widths for this format.
inline Cs16Stages cs16_stages(const Format& f, const SquarerForm& form) {
  validate(f);
  const int F = f.frac, B = F + (form.rel_guard ? f.guard : 0);
  Cs16Stages s;
  s.w[0] = F + 4;
  for (int k = 1; k <= 4; ++k) s.w[k] = B + form.stage_frac[k - 1];
  for (int k = 1; k <= 4; ++k)
    if (s.w[k] < F || (k < 4 && s.w[k] > kSquareMaxN))
      throw std::invalid_argument("cs16 squarer form: stage width W" + std::to_string(k) + " = " +
                                  std::to_string(s.w[k]) + " outside [F, 40]");
  for (int k = 0; k < 4; ++k)
    if (form.keep[k] < -8 || form.keep[k] > 99)
      throw std::invalid_argument("cs16 squarer form: keep[" + std::to_string(k) + "] outside [-8, 99]");
  for (int k = 1; k <= 4; ++k) {
    SquareStage& q = s.sq[k];
    q.n = s.w[k - 1];
    q.shift = (k < 4) ? 2 * s.w[k - 1] - s.w[k] : 2 * s.w[3] - F;
    q.ow = (k < 4) ? s.w[k] + 1 : F + 1;
    q.drop = std::clamp(2 * s.w[k - 1] - s.w[k] - (ceil_log2(q.n) + form.keep[k - 1]), 0, q.shift);
    q.comp = square_comp(q.n, q.shift, q.drop, k < 4 ? form.compensate : true, form.compensate);
  }
  return s;
}

// The error contract of a form (docs/spec.md §3.4), in output ulps against the double cs16 of the same
// input code: lo < out − y·2^F <= hi (lo_strict) or lo <= ... <= hi.
struct Cs16Contract {
  double lo, hi;
  bool lo_strict;
};
// "faithful": today's cs16 bound (−(½ + 15·2^−G), +½]; "compact": [−1, +1]. Throws for other names.
inline Cs16Contract cs16_contract(std::string_view name, const Format& f) {
  if (name == "faithful") return {-(0.5 + 15.0 * std::ldexp(1.0, -f.guard)), 0.5, true};
  if (name == "compact") return {-1.0, 1.0, false};
  throw std::invalid_argument("unknown cs16 contract '" + std::string(name) + "' (known: faithful, compact)");
}

// S1..S5 of a form: x0 (F+4 fraction bits, 0 <= x0 <= 2^(F+4)) squared four times; the output code.
// Everything after the cut depends on x0 alone, so the 2^(F+4) + 1 values of x0 cover every fragment.
inline uint32_t cs16f_squarings(const Format& f, const Cs16Stages& s, uint64_t x, Cs16Trace* tr = nullptr) {
  if (tr) tr->x[0] = x;
  for (int k = 1; k <= 4; ++k) {
    // The integer bit (x = 1.0 exactly) is passed on; the squarer sees the fraction bits.
    const int win = s.w[k - 1];
    const uint64_t top = x >> win;
    const uint64_t lo = x & ((uint64_t{1} << win) - 1);
    const int wout = (k < 4) ? s.w[k] : f.frac;
    x = (top << wout) | square_eval(s.sq[k], lo);
    if (tr && k < 4) tr->x[k] = x;
  }
  const uint32_t out = static_cast<uint32_t>(x);
  if (tr) { tr->x[4] = out; tr->out = out; }
  return out;
}

// The per-fragment datapath of a form (Cs16Trace: x[0..3] as the RTL's S1..S4 registers, x[4] = out).
inline uint32_t cs16f_eval(const Format& f, Cutoff cut_mode, const Cs16Stages& s, const Cs16Material& m,
                           int64_t code, Cs16Trace* tr = nullptr) {
  const int F = f.frac;
  const int64_t one = int64_t{1} << F;
  const uint32_t c = static_cast<uint32_t>(code < 0 ? 0 : (code > one ? one : code));
  const uint32_t d = static_cast<uint32_t>(one) - c;
  const int64_t base = (int64_t{1} << (F + 4)) - static_cast<int64_t>(m.n) * d;
  // Cut where base <= 0 in both forms (no |base|); theta_cr also cuts c < thr.
  const bool cut = base <= 0 || (cut_mode == Cutoff::ThetaCr && c < m.thr);
  const uint64_t x0 = cut ? 0 : static_cast<uint64_t>(base);  // <= 2^(F+4) = 1.0
  if (tr) { tr->c = c; tr->d = d; tr->base = base; tr->cut = cut; }
  return cs16f_squarings(f, s, x0, tr);
}

}  // namespace shadecore
