// SPDX-License-Identifier: Apache-2.0
// shadecore — bit-accurate model of rtl/sc_square.v: the folded, optionally truncated squarer
//   sq = ((S + C) >> shift) mod 2^ow,   S = sum of the kept partial-product bits of x·x
// (docs/spec.md §3.4). The folded matrix has the diagonal bit x_i in column 2i and each
// off-diagonal product x_i·x_j (i < j) once, in column i+j+1; the bits in columns < drop are
// dropped. square_kept() computes S exactly as x·x minus the dropped bits (an identity, not an
// approximation); square_kept_columns() is the literal column-by-column sum (tests compare them).
#pragma once

#include <cstdint>
#include <stdexcept>

namespace shadecore {

__extension__ typedef unsigned __int128 u128;  // GCC/Clang: products up to 2^81

inline constexpr int kSquareMaxN = 40;  // rtl/sc_square.v: 1 <= N <= 40 (product < 2^81)

// Sum of the folded partial-product bits of x (n bits) in columns < drop.
inline u128 square_dropped(uint64_t x, int n, int drop) {
  u128 d = 0;
  const u128 mask = drop >= 128 ? ~u128{0} : ((u128{1} << drop) - 1);
  for (int i = 0; i < n && 2 * i < drop; ++i) {
    const u128 xi = (x >> i) & 1u;
    // row i: {x[n-1:i+1], 0, 1} << 2i, masked to the dropped columns
    const u128 row = ((u128{x >> (i + 1)} << (2 * i + 2)) | (u128{1} << (2 * i))) & mask;
    d += xi * row;
  }
  return d;
}

// S: the kept partial-product bits of x (n bits, x < 2^n), summed.
inline u128 square_kept(uint64_t x, int n, int drop) { return u128{x} * x - square_dropped(x, n, drop); }

// The same sum, column by column from the individual partial-product bits (slow; for tests).
inline u128 square_kept_columns(uint64_t x, int n, int drop) {
  u128 s = 0;
  for (int col = drop; col <= 2 * n; ++col) {
    u128 count = 0;
    for (int i = 0; i < n; ++i) {
      const unsigned xi = (x >> i) & 1u;
      if (2 * i == col) count += xi;                                   // diagonal x_i·x_i = x_i
      const int j = col - 1 - i;                                       // off-diagonal, i < j < n
      if (j > i && j < n) count += xi & ((x >> j) & 1u);
    }
    s += count << col;
  }
  return s;
}

// C of rtl/sc_square.v: (rnd ? 2^(shift-1) : 0) + (ecomp ? round(E[dropped sum]) : 0), E for
// independent uniform bits (½ per diagonal bit, ¼ per off-diagonal bit), round = ties up.
inline u128 square_comp(int n, int shift, int drop, bool rnd, bool ecomp) {
  u128 e4 = 0;  // 4·E
  for (int i = 0; i < n; ++i) {
    if (2 * i < drop) e4 += u128{2} << (2 * i);
    for (int j = i + 1; j < n; ++j)
      if (i + j + 1 < drop) e4 += u128{1} << (i + j + 1);
  }
  u128 c = ecomp ? (e4 + 2) >> 2 : 0;
  if (rnd) c += u128{1} << (shift - 1);
  return c;
}

// One squarer: the parameters of rtl/sc_square.v (C from square_comp()).
struct SquareStage {
  int n = 1, ow = 1, shift = 0, drop = 0;
  u128 comp = 0;
};

inline uint64_t square_eval(const SquareStage& s, uint64_t x) {
  const u128 sum = square_kept(x, s.n, s.drop) + s.comp;
  return static_cast<uint64_t>((sum >> s.shift) & ((u128{1} << s.ow) - 1));
}

}  // namespace shadecore
