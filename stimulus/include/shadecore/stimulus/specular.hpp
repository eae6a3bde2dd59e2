// SPDX-License-Identifier: Apache-2.0
// shadecore stimulus — the one random stimulus generator of the specular units, shared by `shadecore vectors`,
// the co-simulation (sim/tb_stimulus.hpp) and the handoff vectors, so one seed gives one stimulus everywhere.
//
// The code of transaction i of a run seeded with `seed` is drawn from its own stream Rng::for_item(seed, i) —
// a function of (seed, i) only, so a run split into shards by index draws the same codes whatever the shard
// count: 70 % uniform in [0, 2^F], 10 % uniform over the whole signed input word (the clamp), 20 % within ±4
// of a special point (0, 2^F, the unit's threshold — cs16's θcr code or a table entry boundary — at a random
// n' of the range, or the last code whose cs16 base is <= 0).
//
// The material of random transaction i is a function of (seed, i) too (random_material): a material
// change comes before transaction i with probability `rate` per transaction (always before transaction 0),
// its exponent drawn uniform in [n_lo, n_hi] from the change's own stream; a shard that starts at index
// `first` finds the material in force by looking back to the last change (about 1/rate steps).
//
// stimulus_digest: a sum over the transactions of a hash of (global index, n, code), n = −1 where the
// material is whatever is loaded (random mode): equal for two runs that drive the same transactions, however
// they are split (the shards' sums add up). `shadecore vectors` and `shadecore cosim` print it.
#pragma once

#include <cstdint>

#include "shadecore/stimulus/rng.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::stimulus {

using sim::mix64;
using sim::Rng;

// The input code of random transaction `index` (n_lo..n_hi: the exponent range the special points use).
inline int64_t random_code(const Unit& unit, uint64_t seed, uint64_t index, int n_lo, int n_hi) {
  const Format& f = unit.format();
  Rng rng = Rng::for_item(seed, index);
  const uint64_t r = rng.next() % 100;
  const int64_t one = f.one();
  if (r < 70) return rng.uniform(0, one);
  if (r < 80) return rng.uniform(f.in_min(), f.in_max());
  const int n = static_cast<int>(rng.uniform(n_lo, n_hi));
  int64_t centre = 0;
  switch (rng.next() % 4) {
    case 0: centre = 0; break;
    case 1: centre = one; break;
    case 2:  // cs16: the θcr threshold; table units: an entry boundary ⌈i·2^F/(E−1)⌉
      if (const int e = unit.entries(); e > 0) {
        const int64_t i = rng.uniform(0, e - 1);
        centre = (i * one + e - 2) / (e - 1);
      } else {
        centre = unit.setup(n).thr;
      }
      break;
    default: centre = one - ((int64_t{1} << (f.frac + 4)) / n); break;  // last code with base <= 0
  }
  int64_t code = centre + rng.uniform(-4, 4);
  if (code < f.in_min()) code = f.in_min();
  if (code > f.in_max()) code = f.in_max();
  return code;
}

// Whether a material change comes before random transaction `index` (rate: probability per transaction).
inline bool material_change(uint64_t seed, uint64_t index, double rate) {
  if (index == 0) return true;
  if (rate <= 0.0) return false;
  if (rate >= 1.0) return true;
  const uint64_t threshold = static_cast<uint64_t>(rate * 18446744073709551616.0);
  return Rng::for_item(seed ^ 0x6D6174657269616Cull, index).next() < threshold;
}

// The exponent a material change before transaction `index` writes.
inline int material_n(uint64_t seed, uint64_t index, int n_lo, int n_hi) {
  Rng rng = Rng::for_item(seed ^ 0x4D41545F4E5F5F5Full, index);
  return static_cast<int>(rng.uniform(n_lo, n_hi));
}

// The index of the last material change at or before `index` (the one in force for that transaction).
inline uint64_t last_material_change(uint64_t seed, uint64_t index, double rate) {
  if (rate <= 0.0) return 0;
  while (!material_change(seed, index, rate)) --index;  // terminates: index 0 always changes
  return index;
}

// The default mid-stream reset of a random run of `count` transactions: before a transaction drawn from the
// seed in the middle half of the run, [count/4, 3·count/4] — a global index, so every shard agrees, and not
// tied to a shard boundary (a reset at a shard's first index would catch nothing in flight).
inline uint64_t default_reset_index(uint64_t seed, uint64_t count) {
  return count / 4 + mix64(seed ^ 0x5245534554415421ull) % (count / 2 + 1);
}

// One transaction's term of the stimulus digest.
inline uint64_t item_digest(uint64_t index, int n, int64_t code) {
  return mix64(mix64(index) ^ mix64(static_cast<uint64_t>(code) + 0x9E3779B97F4A7C15ull) ^
               (static_cast<uint64_t>(n + 1) << 40));
}

}  // namespace shadecore::stimulus
