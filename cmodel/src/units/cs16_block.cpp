// SPDX-License-Identifier: Apache-2.0
// shadecore — block evaluation of cs16 for the exhaustive sweep (see cs16.hpp).
#include <algorithm>

#include "shadecore/units/cs16.hpp"

namespace shadecore {

// Built three times (AVX-512, AVX2, baseline x86-64) and picked at run time; both are the same integer arithmetic.
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target_clones("avx512f", "avx2", "default")))
#endif
void cs16_eval_block(const Format& f, Cutoff cut_mode, const Cs16Material& m, int64_t code0,
                            int64_t count, uint32_t* out) {
  const int F = f.frac, G = f.guard, W = F + G;
  const int64_t one = f.one();
  // First code with base > 0: base = 2^(F+4) − n·(2^F − c) > 0  <=>  c > 2^F − 2^(F+4)/n.
  const int64_t pos0 = one - ((int64_t{1} << (F + 4)) - 1) / m.n;
  const int64_t live0 = std::max<int64_t>(pos0, 0);  // live run: [live0, one], base > 0 there
  int64_t i = 0;
  // Codes below the live run: clamped negatives, cut codes, and (theta_cr) the negative-base sliver.
  for (; i < count && code0 + i < live0; ++i) out[i] = cs16_eval(f, cut_mode, m, code0 + i);
  // Live run. In theta_cr mode codes below thr are cut even with base > 0 (n <= 25).
  const int64_t live_end = std::min<int64_t>(count, one + 1 - code0);  // exclusive, in block indices
  for (; i < live_end && cut_mode == Cutoff::ThetaCr && code0 + i < int64_t{m.thr}; ++i) out[i] = 0;
  if (i < live_end) {
    const uint64_t b0 = static_cast<uint64_t>((int64_t{1} << (F + 4)) - int64_t{m.n} * (one - (code0 + i)));
    const uint64_t half = uint64_t{1} << (G - 1);
    const int64_t len = live_end - i;
    uint32_t* o = out + i;
    const uint64_t n = static_cast<uint64_t>(m.n);
    for (int64_t k = 0; k < len; ++k) {
      uint64_t x = (b0 + n * static_cast<uint64_t>(k)) << (G - 4);
      x = (static_cast<uint64_t>(static_cast<uint32_t>(x)) * static_cast<uint32_t>(x)) >> W;
      x = (static_cast<uint64_t>(static_cast<uint32_t>(x)) * static_cast<uint32_t>(x)) >> W;
      x = (static_cast<uint64_t>(static_cast<uint32_t>(x)) * static_cast<uint32_t>(x)) >> W;
      x = (static_cast<uint64_t>(static_cast<uint32_t>(x)) * static_cast<uint32_t>(x)) >> W;
      o[k] = static_cast<uint32_t>((x + half) >> G);
    }
    i = live_end;
  }
  // Codes above 1.0 saturate.
  for (; i < count; ++i) out[i] = static_cast<uint32_t>(one);
}

}  // namespace shadecore
