// SPDX-License-Identifier: Apache-2.0
// shadecore sim — what the driver feeds the unit, by mode:
//   exhaustive: for every n in [n_lo, n_hi]: every code in [0, 2^F], then the out-of-range codes
//               in_min, -1, 2^F+1, in_max (the clamp must saturate, never wrap);
//   random:     `count` codes from the one specular generator, stimulus::random_code
//               (stimulus/include/shadecore/stimulus/specular.hpp, shared with `shadecore vectors`):
//               70 % uniform in [0, 2^F], 10 % over the whole signed input word, 20 % within ±4 of a
//               special point; the material (n) of each transaction from stimulus::material_change /
//               material_n: a change before transaction i with probability mat_rate per transaction
//               (always before the first), the driver writing it in a bubble before that transaction.
//               Code and material of transaction i (i = first, first+1, ...) are functions of (seed, i)
//               only, and so is the mid-stream reset (before global index reset_at, the driver), so one
//               seeded run split into shards by index drives the same transactions whatever the shard
//               count; the transactions a reset flushes are sent again, so each index is checked once.
//               (Input gaps and backpressure come from per-shard generators: timing, not stimulus.)
//   directed:   shadecore::hard_cases() — the list the C model tests use — repeated until `count`
//               items (at least once).
// No allocation per item; the directed list is built once.
#pragma once

#include <cstdint>
#include <vector>

#include "shadecore/units/hard_cases.hpp"
#include "shadecore/unit.hpp"
#include "tb_options.hpp"
#include "shadecore/stimulus/rng.hpp"
#include "shadecore/stimulus/specular.hpp"

namespace shadecore::sim {

struct Item {
  int n = -1;        // material this item must be shaded with; -1 = whatever is loaded (random mode)
  int64_t code = 0;  // signed input word
};

class Stimulus {
 public:
  Stimulus(const Options& o, const Unit& unit)
      : o_(o), unit_(unit), f_(unit.format()), n_(o.n_lo) {
    if (o_.mode == Mode::Random) {
      const uint64_t c = stimulus::last_material_change(o_.seed, o_.first, o_.mat_rate);
      mat_n_ = stimulus::material_n(o_.seed, c, o_.n_lo, o_.n_hi);
    }
    const int64_t one = f_.one();
    extras_[0] = f_.in_min();
    extras_[1] = -1;
    extras_[2] = one + 1;
    extras_[3] = f_.in_max();
    if (o_.mode == Mode::Directed) {
      directed_ = hard_cases(f_);
      const uint64_t len = directed_.size();
      repeats_ = o_.count > len ? (o_.count + len - 1) / len : 1;
    }
  }

  // Number of items this stimulus produces in total.
  uint64_t planned() const {
    switch (o_.mode) {
      case Mode::Exhaustive:
        return static_cast<uint64_t>(o_.n_hi - o_.n_lo + 1) * static_cast<uint64_t>(f_.one() + 1 + kExtras);
      case Mode::Random: return o_.count;
      case Mode::Directed: return directed_.size() * repeats_;
    }
    return 0;
  }

  bool next(Item& it) {
    uint64_t index = 0;
    bool more = false;
    switch (o_.mode) {
      case Mode::Exhaustive:
        index = static_cast<uint64_t>(n_ - kNMin) * static_cast<uint64_t>(f_.one() + 1 + kExtras) +
                static_cast<uint64_t>(idx_);
        more = next_exhaustive(it);
        break;
      case Mode::Random:
        index = o_.first + done_;
        more = next_random(it);
        break;
      case Mode::Directed:
        index = rep_ * directed_.size() + static_cast<uint64_t>(idx_);
        more = next_directed(it);
        break;
    }
    // Random mode: the digest covers the codes (n = -1), as `shadecore vectors --mode random` computes it.
    if (more) digest_ += item_digest(index, o_.mode == Mode::Random ? Item{-1, it.code} : it);
    return more;
  }

  // Sum over the items produced of a hash of (global index, n, code): equal for two runs that produce
  // the same transactions, however they are split into shards (the sums of the shards add up).
  [[nodiscard]] uint64_t digest() const { return digest_; }

 private:
  static constexpr int kExtras = 4;

  static uint64_t item_digest(uint64_t index, const Item& it) { return stimulus::item_digest(index, it.n, it.code); }


  bool next_exhaustive(Item& it) {
    if (n_ > o_.n_hi) return false;
    const int64_t in_range = f_.one() + 1;
    it.n = n_;
    it.code = idx_ < in_range ? idx_ : extras_[idx_ - in_range];
    if (++idx_ == in_range + kExtras) {
      idx_ = 0;
      ++n_;
    }
    return true;
  }

  bool next_random(Item& it) {
    if (done_ == o_.count) return false;
    // The one specular generator (stimulus/specular.hpp): `shadecore vectors` draws the same codes.
    const uint64_t index = o_.first + done_;
    it.code = stimulus::random_code(unit_, o_.seed, index, o_.n_lo, o_.n_hi);
    if (done_ > 0 && stimulus::material_change(o_.seed, index, o_.mat_rate))
      mat_n_ = stimulus::material_n(o_.seed, index, o_.n_lo, o_.n_hi);
    ++done_;
    it.n = mat_n_;
    return true;
  }

  bool next_directed(Item& it) {
    if (rep_ == repeats_) return false;
    it.n = directed_[idx_].n;
    it.code = directed_[idx_].code;
    if (++idx_ == static_cast<int64_t>(directed_.size())) {
      idx_ = 0;
      ++rep_;
    }
    return true;
  }

  const Options& o_;
  const Unit& unit_;
  Format f_;
  int n_;
  int64_t idx_ = 0;
  int64_t extras_[kExtras] = {};
  uint64_t done_ = 0;
  int mat_n_ = -1;  // random mode: the material in force
  std::vector<HardCase> directed_;
  uint64_t repeats_ = 1, rep_ = 0;
  uint64_t digest_ = 0;
};

}  // namespace shadecore::sim
