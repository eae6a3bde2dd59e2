// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of the table-and-interpolate specular unit (rtl/sc_table.v), the
// fixed-function GPUs' shine table (Mesa: 256 entries tab[i] = (i/255)^n, f = 255·cos θ, lerp).
//
//   per material (host, double):  T(i) = (i/(E−1))^n, i = 0..E−1;  V[i] = ⌊T(i)·2^F + ½⌋,
//                                 D[i] = V[i+1] − V[i] (D[E−1] = 0); RAM word i = {D[i], V[i]}
//   per fragment (integers):      c = clamp(code, 0, 2^F);  p = (E−1)·c = (c << K) − c  (exact)
//                                 i = p >> F,  fr = p mod 2^F          (f = (E−1)·cos θ = i + fr/2^F)
//                                 out = V[i] + ⌊(D[i]·fr + 2^(F−1)) / 2^F⌋     (mod 2^(F+1))
// docs/spec.md §9 is the contract; the variants are config/configs.json "table256" and "table1024".
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/format.hpp"
#include "shadecore/variants.hpp"

namespace shadecore {

// Table size of a variant (config/configs.json "entries"; 0 for a unit that is not a table).
inline int table_entries(VariantId v) {
  for (const auto& nv : kVariants)
    if (nv.id == v) return nv.contract == "table" ? nv.entries : 0;
  return 0;
}
inline bool is_table_variant(VariantId v) { return table_entries(v) > 0; }

// log2 of a legal table size (256 -> 8, 1024 -> 10); throws std::invalid_argument otherwise.
inline int table_index_bits(int entries) {
  for (int k = 1; k <= 16; ++k)
    if (entries == (1 << k)) return k;
  throw std::invalid_argument("table entries " + std::to_string(entries) + " is not a power of two");
}

// Width of tab_addr_i in rtl/sc_specular.v: enough for the largest table (1024 entries).
inline constexpr int kTableAddrBits = 10;

// The RAM word of one entry: value in bits F..0, delta in bits 2F+1..F+1 (2F+2 bits <= 50).
inline uint64_t table_word(int frac, uint32_t value, uint32_t delta) {
  return (uint64_t{delta} << (frac + 1)) | value;
}
inline uint32_t table_word_value(int frac, uint64_t w) { return static_cast<uint32_t>(w & ((uint64_t{1} << (frac + 1)) - 1)); }
inline uint32_t table_word_delta(int frac, uint64_t w) {
  return static_cast<uint32_t>((w >> (frac + 1)) & ((uint64_t{1} << (frac + 1)) - 1));
}

// Per-material contents of the table RAM, computed once by the host (E writes through tab_*_i).
struct TableMaterial {
  int n = 16;
  std::vector<uint64_t> words;  // E entries, word i = table_word(F, V[i], D[i])
};

// T(i) = (i/(E−1))^n in double (the golden table; exact at i = 0 and i = E−1).
inline double table_golden_entry(int entries, int n, int i) {
  return std::pow(static_cast<double>(i) / static_cast<double>(entries - 1), n);
}

// Throws std::invalid_argument for an illegal format, n or table size.
inline TableMaterial table_setup(const Format& f, int entries, long long n) {
  validate(f);
  validate_n(n);
  table_index_bits(entries);
  TableMaterial m;
  m.n = static_cast<int>(n);
  std::vector<uint32_t> v(static_cast<size_t>(entries));
  for (int i = 0; i < entries; ++i)
    v[i] = static_cast<uint32_t>(std::floor(std::ldexp(table_golden_entry(entries, m.n, i), f.frac) + 0.5));
  m.words.resize(static_cast<size_t>(entries));
  for (int i = 0; i < entries; ++i) m.words[i] = table_word(f.frac, v[i], i + 1 < entries ? v[i + 1] - v[i] : 0);
  return m;
}

// Every intermediate value of one evaluation, named after the RTL's registers.
struct TableTrace {
  uint32_t c = 0;      // clamped cos code (combinational, before S0)
  uint32_t index = 0;  // i = ((E−1)·c) >> F: the RAM read address at the accepting edge
  uint32_t frac = 0;   // fr = ((E−1)·c) mod 2^F, F bits (S0)
  uint32_t value = 0;  // S0: V[i] (RAM read data)
  uint32_t delta = 0;  // S0: D[i]
  uint64_t prod = 0;   // S1: D·fr + 2^(F−1), 2F+1 bits
  uint32_t out = 0;    // S2: V + (prod >> F), F+1 bits
};

// Index and fraction of the clamped code: (E−1)·c = i·2^F + fr (exact; K = log2 E).
inline void table_split(const Format& f, int k, int64_t code, uint32_t& c, uint32_t& index, uint32_t& fr) {
  const int64_t one = f.one();
  c = static_cast<uint32_t>(code < 0 ? 0 : (code > one ? one : code));
  const uint64_t p = (uint64_t{c} << k) - c;  // (E−1)·c < 2^(F+K)
  index = static_cast<uint32_t>(p >> f.frac);
  fr = static_cast<uint32_t>(p & (uint64_t(one) - 1));
}

// The per-fragment datapath for the RAM contents `words` (E words; any contents: the RTL's arithmetic,
// including the wrap of the (F+1)-bit sum, which cannot happen for contents from table_setup()).
inline uint32_t table_eval(const Format& f, const uint64_t* words, int entries, int64_t code,
                           TableTrace* tr = nullptr) {
  const int F = f.frac, k = table_index_bits(entries);
  uint32_t c, index, fr;
  table_split(f, k, code, c, index, fr);
  const uint64_t w = words[index];
  const uint32_t value = table_word_value(F, w), delta = table_word_delta(F, w);
  const uint64_t prod = uint64_t{delta} * fr + (uint64_t{1} << (F - 1));
  const uint32_t out = static_cast<uint32_t>((value + (prod >> F)) & ((uint64_t{1} << (F + 1)) - 1));
  if (tr) *tr = TableTrace{c, index, fr, value, delta, prod, out};
  return out;
}

inline uint32_t table_eval(const Format& f, const TableMaterial& m, int64_t code, TableTrace* tr = nullptr) {
  return table_eval(f, m.words.data(), static_cast<int>(m.words.size()), code, tr);
}

// Latency of rtl/sc_table.v: S0 (RAM read at the accepting edge), S1 (multiply), S2 (add).
inline constexpr int kTableLatency = 3;

// Quantisation bound against the double table-lerp of the same code (docs/spec.md §9.4), in output ulps:
// −1 < out − 2^F·lerp ≤ +1 (entries rounded half up: (−½, ½]; interpolation term rounded half up: (−½, ½]).
inline constexpr double kTableQuantMin = -1.0, kTableQuantMax = 1.0;

namespace golden {
// The exact function the unit approximates in fixed point: the table of T(i) = (i/(E−1))^n in double,
// indexed and interpolated at f = (E−1)·c exactly as the unit does (c in [0, 1]).
inline double table_lerp(const double* t, int entries, double c) {
  c = c < 0 ? 0.0 : (c > 1 ? 1.0 : c);
  const double fpos = (entries - 1) * c;  // exact for c = code/2^F, F <= 24, E <= 1024
  const int i = static_cast<int>(std::floor(fpos));
  if (i >= entries - 1) return t[entries - 1];
  const double phi = fpos - i;
  return t[i] + phi * (t[i + 1] - t[i]);
}
inline std::vector<double> table_golden(int entries, int n) {
  std::vector<double> t(static_cast<size_t>(entries));
  for (int i = 0; i < entries; ++i) t[i] = table_golden_entry(entries, n, i);
  return t;
}
inline double table_lerp(int entries, int n, double c) {
  const std::vector<double> t = table_golden(entries, n);
  return table_lerp(t.data(), entries, c);
}
}  // namespace golden

}  // namespace shadecore
