// SPDX-License-Identifier: Apache-2.0
// shadecore — the directed hard-case list, shared by the C model tests (tests/) and the
// co-simulation's directed stimulus (sim/): one list, not two copies.
#pragma once

#include <algorithm>
#include <cstdint>
#include <map>
#include <mutex>
#include <utility>
#include <vector>

#include "shadecore/units/cs16.hpp"
#include "shadecore/format.hpp"

namespace shadecore {

struct HardCase {
  int n;
  int64_t code;  // signed input word of the unit (may be outside [0, 2^F] on purpose)
};

// Exponents at and next to the ends of the legal range and where θcr crosses the base zero, and every power of two
// of the range: a decode of n (n == 0, n < 16) that drops bit k errs only at n = 2^k (docs/mutation.md, schlick_iter
// m112: n = 512 taken for n = 0).
inline std::vector<int> hard_case_exponents() {
  return {16, 17, 25, 26, 27, 32, 64, 100, 128, 255, 256, 512, 1000, 1023, 1024};
}

// The Schlick quotient's nearest ties at exponent n: the codes c in [0, 2^F] whose c·2^F / D, D = n·(2^F − c) + c
// (the divide t/(n − n·t + t) at F fraction bits), has its remainder r closest to D/2 from below and from above
// (0 < |2r − D| smallest, an exact tie too if there is one). Round half up errs by one LSB there and almost nowhere
// else, so a rounding error of the dividers that directed and random vectors miss shows here (docs/mutation.md,
// the exhaustive stage's kills; schlick_iter m004: n = 16, code 0x07b24, |2r − D| = 4).
// (Every code up to F = 20, every 2^(F−20)-th above: at F = 24 the full search would take seconds per process.
// Memoised per (F, n).)
inline std::vector<int64_t> schlick_near_ties(const Format& f, int n) {
  static std::mutex mu;
  static std::map<std::pair<int, int>, std::vector<int64_t>> memo;
  const std::lock_guard<std::mutex> lock(mu);
  const auto key = std::make_pair(f.frac, n);
  if (const auto it = memo.find(key); it != memo.end()) return it->second;
  const int64_t one = f.one();
  const int64_t step = f.frac > 20 ? int64_t{1} << (f.frac - 20) : 1;
  int64_t best_lo = -1, best_hi = -1, d_lo = 0, d_hi = 0;  // |2r − D| / D compared exactly by cross-multiplying
  int64_t den_lo = 1, den_hi = 1;
  for (int64_t c = 1; c < one; c += step) {
    const int64_t den = n * (one - c) + c;
    const int64_t r = (c << f.frac) % den;
    const int64_t gap = 2 * r - den;  // < 0: just below the tie, >= 0: at or above it
    if (gap < 0 && (best_lo < 0 || (-gap) * den_lo < d_lo * den)) { best_lo = c; d_lo = -gap; den_lo = den; }
    if (gap >= 0 && (best_hi < 0 || gap * den_hi < d_hi * den)) { best_hi = c; d_hi = gap; den_hi = den; }
  }
  std::vector<int64_t> v;
  if (best_lo >= 0) v.push_back(best_lo);
  if (best_hi >= 0 && best_hi != best_lo) v.push_back(best_hi);
  memo.emplace(key, v);
  return v;
}

// For each exponent: the input extremes (most negative, −1, 0, 1), cos θ = 1 and one code either
// side, the saturating maximum, the θcr threshold ±1 and the code where the base crosses 0, ±1.
// For the first exponent also 1.0 + 2^k for every k < F: the clamp's compare `code > 1.0` sees one bit of the
// code above 1.0 at a time (a compare that drops or flips bit k errs only at 1.0 + 2^k; docs/mutation.md).
inline std::vector<HardCase> hard_cases(const Format& f) {
  std::vector<HardCase> v;
  const int64_t one = f.one();
  for (int n : hard_case_exponents()) {
    const Cs16Material m = cs16_setup(f, n);
    const int64_t base_zero = one - ((int64_t{1} << (f.frac + 4)) / n);  // last code with base <= 0
    const int64_t codes[] = {f.in_min(), f.in_min() + 1, -2, -1, 0, 1, 2,
                             one - 2, one - 1, one, one + 1, one + 2, f.in_max() - 1, f.in_max(),
                             int64_t(m.thr) - 2, int64_t(m.thr) - 1, int64_t(m.thr), int64_t(m.thr) + 1,
                             base_zero - 1, base_zero, base_zero + 1, base_zero + 2};
    for (int64_t c : codes)
      if (c >= f.in_min() && c <= f.in_max()) v.push_back({n, c});
    for (int64_t c : schlick_near_ties(f, n)) v.push_back({n, c});
    if (n == hard_case_exponents().front())
      for (int k = 2; k < f.frac; ++k)  // 1.0 + 1 and 1.0 + 2 are in the list above
        if (one + (int64_t{1} << k) <= f.in_max()) v.push_back({n, one + (int64_t{1} << k)});
  }
  return v;
}

}  // namespace shadecore
