// SPDX-License-Identifier: Apache-2.0
// shadecore — the directed hard-case list, shared by the C model tests (tests/) and the
// co-simulation's directed stimulus (sim/): one list, not two copies.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "shadecore/units/cs16.hpp"
#include "shadecore/format.hpp"

namespace shadecore {

struct HardCase {
  int n;
  int64_t code;  // signed input word of the unit (may be outside [0, 2^F] on purpose)
};

// Exponents at and next to the ends of the legal range and where θcr crosses the base zero.
inline std::vector<int> hard_case_exponents() { return {16, 17, 25, 26, 27, 100, 128, 255, 256, 1000, 1023, 1024}; }

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
    if (n == hard_case_exponents().front())
      for (int k = 2; k < f.frac; ++k)  // 1.0 + 1 and 1.0 + 2 are in the list above
        if (one + (int64_t{1} << k) <= f.in_max()) v.push_back({n, one + (int64_t{1} << k)});
  }
  return v;
}

}  // namespace shadecore
