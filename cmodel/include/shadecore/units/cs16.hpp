// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the cs16 specular unit (rtl/sc_cs16.v).
//
//   cs16(θ, n) = ((n/16)(cos θ − 1) + 1)^16   for θ <= θcr(n) = 6/√n, else 0
//
// Integer arithmetic only on the per-fragment path, stage by stage as the RTL computes it
// (docs/spec.md §3). Per-material constants are computed once by cs16_setup().
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shadecore/format.hpp"

namespace shadecore {

// How the lobe is cut where the approximation stops being meaningful.
enum class Cutoff : int {
  ThetaCr = 0,    // the paper's θcr = 6/√n, as a threshold on the cos θ code (material constant)
  SignClamp = 1,  // zero wherever the base (n/16)(c − 1) + 1 is <= 0 (no material constant)
};

inline const char* to_string(Cutoff c) { return c == Cutoff::ThetaCr ? "theta_cr" : "sign_clamp"; }

// The inverse of to_string(); throws std::invalid_argument (one line) for any other name.
inline Cutoff parse_cutoff_name(std::string_view s) {
  if (s == "theta_cr") return Cutoff::ThetaCr;
  if (s == "sign_clamp") return Cutoff::SignClamp;
  throw std::invalid_argument("unknown cutoff '" + std::string(s) + "' (known: theta_cr, sign_clamp)");
}

// Per-material constants, computed once at material setup (docs/spec.md §3.1).
struct Cs16Material {
  int n = 16;        // specular exponent; the scale n/16 is n with 4 implied fraction bits (exact)
  uint32_t thr = 0;  // θcr threshold: fragments with clamped cos code < thr are cut to 0
};

// thr = ceil(cos(6/√n) · 2^frac): the smallest code whose cos is >= cos θcr.
// Throws std::invalid_argument for an illegal format or n.
inline Cs16Material cs16_setup(const Format& f, long long n) {
  validate(f);
  validate_n(n);
  Cs16Material m;
  m.n = static_cast<int>(n);
  const double ccr = std::cos(6.0 / std::sqrt(static_cast<double>(n)));
  m.thr = static_cast<uint32_t>(std::ceil(std::ldexp(ccr, f.frac)));
  return m;
}

// Every intermediate value of one evaluation, named after the RTL's pipeline registers.
struct Cs16Trace {
  uint32_t c = 0;       // S0: cos code clamped to [0, 2^F]
  uint32_t d = 0;       // S0: 2^F − c (1 − cos θ), F+1 bits
  int64_t base = 0;     // S1: 2^(F+4) − n·d, signed, F+4 fraction bits (exact)
  bool cut = false;     // S1: cut-off decision
  uint64_t x[5] = {};   // S1..S5: x0 = |base| aligned to W bits; x1..x4 the truncated squares
                        // (cs16 forms, cs16_forms.hpp: x0 = base, x1..x3 per-stage widths, x4 = out)
  uint32_t out = 0;     // S6: x4 rounded half-up to F bits
};

// The per-fragment datapath. `code` is the signed (frac+2)-bit input word as an integer.
inline uint32_t cs16_eval(const Format& f, Cutoff cut_mode, const Cs16Material& m, int64_t code,
                          Cs16Trace* tr = nullptr) {
  const int F = f.frac, G = f.guard, W = F + G;
  // S0 — input clamp: negative codes become 0, codes above 1.0 saturate to 1.0.
  const int64_t one = int64_t{1} << F;
  const uint32_t c = static_cast<uint32_t>(code < 0 ? 0 : (code > one ? one : code));
  const uint32_t d = static_cast<uint32_t>(one) - c;
  // S1 — scale and offset: base = 1 − (n/16)(1 − c), exact with F+4 fraction bits.
  const int64_t base = (int64_t{1} << (F + 4)) - static_cast<int64_t>(m.n) * d;
  const bool cut = (cut_mode == Cutoff::ThetaCr) ? (c < m.thr) : (base <= 0);
  const uint64_t mag = cut ? 0 : static_cast<uint64_t>(base < 0 ? -base : base);
  // Align to W fraction bits (exact, G >= 4). x <= 2^W <= 2^31 fits 32 bits; each square fits 64.
  uint32_t x = static_cast<uint32_t>(mag << (G - 4));
  if (tr) { tr->c = c; tr->d = d; tr->base = base; tr->cut = cut; tr->x[0] = x; }
  // S2..S5 — four squarings, each truncated (floor) to W fraction bits.
  for (int k = 1; k <= 4; ++k) {
    x = static_cast<uint32_t>((uint64_t{x} * x) >> W);
    if (tr) tr->x[k] = x;
  }
  // S6 — round half up to F fraction bits; x4 <= 2^W so the result is <= 2^F.
  const uint32_t out = static_cast<uint32_t>((uint64_t{x} + (uint64_t{1} << (G - 1))) >> G);
  if (tr) tr->out = out;
  return out;
}

// A block of consecutive input codes [code0, code0 + count) for one material: bit-identical to
// cs16_eval() on every code (tests check it exhaustively); the fast path for whole code ranges. The codes
// split into runs: cut or clamped codes (constant outputs) and the live lobe with base > 0, where
// base grows by n per code and the four squarings are 32×32→64-bit products that vectorise.
void cs16_eval_block(const Format& f, Cutoff cut_mode, const Cs16Material& m, int64_t code0, int64_t count,
                     uint32_t* out);

}  // namespace shadecore
