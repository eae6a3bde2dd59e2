// SPDX-License-Identifier: Apache-2.0
// shadecore sim — seeded random sources of the testbench. Cheap (one 64-bit mix per draw, no
// allocation), and deterministic from the seed the run prints, so any run can be replayed.
#pragma once

#include <cstdint>

namespace shadecore::sim {

// The SplitMix64 output function: a 64-bit bijective mix.
inline uint64_t mix64(uint64_t z) {
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

// SplitMix64 (Steele, Lea, Flood 2014): full-period 64-bit generator, good enough for stimulus.
class Rng {
 public:
  explicit Rng(uint64_t seed) : s_(seed) {}
  // An independent stream for item `index` of a run seeded with `seed`: a function of (seed, index)
  // only (hashed, so neighbouring items do not share draws).
  static Rng for_item(uint64_t seed, uint64_t index) {
    return Rng(mix64(mix64(seed ^ 0x5eed5eed5eedull) ^ mix64(index + 0x632BE59BD9B4E019ull)));
  }
  uint64_t next() {
    uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  // Uniform integer in [lo, hi] (hi - lo < 2^32; the modulo bias is < 2^-32, irrelevant here).
  int64_t uniform(int64_t lo, int64_t hi) {
    return lo + static_cast<int64_t>((next() >> 32) % static_cast<uint64_t>(hi - lo + 1));
  }

 private:
  uint64_t s_;
};

// A pluggable stall source: each cycle, stall() says whether this side holds off. Bernoulli with
// probability p (0 = never, 1 = always); its own Rng so input and output stalls are independent.
class StallGen {
 public:
  StallGen(double p, uint64_t seed) : rng_(seed) {
    if (p <= 0.0) threshold_ = 0;
    else if (p >= 1.0) threshold_ = ~uint64_t{0};
    else threshold_ = static_cast<uint64_t>(p * 18446744073709551616.0);
    always_ = p >= 1.0;
  }
  bool stall() {
    if (threshold_ == 0) return false;
    if (always_) return true;
    return rng_.next() < threshold_;
  }

 private:
  Rng rng_;
  uint64_t threshold_ = 0;
  bool always_ = false;
};

}  // namespace shadecore::sim
