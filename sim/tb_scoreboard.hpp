// shadecore sim — scoreboard: the reference side of the co-simulation. No SystemC in here.
//
// The monitor reports, edge by edge, what crossed the unit's ports:
//   on_input()    a fragment accepted (in_valid_i & in_ready_o): the expected result is computed
//                 right here by the C model (shadecore::Unit) with the material registered BEFORE
//                 this edge (spec §4), and queued with its tag, cycle and advance count;
//   on_material() mat_we_i at this edge: the shadow material registers take the port values
//                 (called after on_input of the same edge: a fragment accepted at that edge uses
//                 the old material);
//   on_output()   a result taken (out_valid_o & out_ready_i): checked at once against the head of
//                 the queue — tag (lost / duplicated / reordered), value (bit-exact), latency;
//   on_reset()    rst_ni low at this edge: what is still in flight is dropped, as the spec says.
// The queue is a fixed ring (no allocation per transaction).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "shadecore/unit.hpp"

namespace shadecore::sim {

struct Mismatch {
  int n;
  int64_t code;
  uint32_t expected, got, tag;
  uint64_t cycle;
};

class Scoreboard {
 public:
  Scoreboard(const Unit& unit, int show)
      : unit_(unit), latency_(unit.latency()), latency_min_(unit.latency_min()), show_(show), ring_(kCap) {}

  void on_material(int n, uint32_t thr, uint32_t coef = 0) {
    mat_ = UnitMaterial{n, thr, coef};
    mat_valid_ = true;
    ++material_writes_;
  }

  void on_input(uint32_t tag, int64_t code, uint64_t cycle, uint64_t adv) {
    if (!mat_valid_) {
      error("input accepted before any material was written", cycle);
      return;
    }
    if (size_ == kCap) {
      error("more than " + std::to_string(kCap) + " fragments in flight (outputs missing)", cycle);
      return;
    }
    Entry& e = ring_[(head_ + size_) & (kCap - 1)];
    e.tag = tag;
    e.n = mat_.n;
    e.code = code;
    e.expected = unit_.eval(mat_, code);
    e.cycle = cycle;
    e.adv = adv;
    ++size_;
    ++accepted_;
  }

  void on_output(uint32_t tag, uint32_t got, uint64_t cycle, uint64_t adv) {
    ++outputs_;
    if (size_ == 0) {
      ++unexpected_;
      if (unexpected_ <= static_cast<uint64_t>(show_))
        std::printf("ERROR cycle %llu: output tag %u with nothing in flight (duplicated or spurious)\n",
                    ull(cycle), tag);
      return;
    }
    const uint32_t off = tag - ring_[head_].tag;  // tags are consecutive in acceptance order
    if (off != 0) {
      if (off < size_) {
        if (lost_ < static_cast<uint64_t>(show_))
          std::printf("ERROR cycle %llu: %u transaction(s) lost: expected tag %u, got tag %u\n",
                      ull(cycle), off, ring_[head_].tag, tag);
        lost_ += off;
        pop(off);
      } else {
        ++unexpected_;
        if (unexpected_ <= static_cast<uint64_t>(show_))
          std::printf("ERROR cycle %llu: output tag %u not expected (duplicated or reordered; next expected %u)\n",
                      ull(cycle), tag, ring_[head_].tag);
        return;
      }
    }
    const Entry& e = ring_[head_];
    ++checked_;
    if (got != e.expected) {
      ++mismatches_;
      if (first_.size() < static_cast<size_t>(show_)) first_.push_back({e.n, e.code, e.expected, got, e.tag, cycle});
    }
    const uint64_t lat_adv = adv - e.adv, lat_cyc = cycle - e.cycle;
    // Exactly `latency` advancing edges; a chained NORM stage may catch up through bubbles in front
    // of it under backpressure, so there the contract is the range latency_min..latency.
    if (lat_adv > static_cast<uint64_t>(latency_) || lat_adv < static_cast<uint64_t>(latency_min_)) {
      ++latency_errors_;
      if (latency_errors_ <= static_cast<uint64_t>(show_))
        std::printf("ERROR cycle %llu: tag %u latency %llu advancing cycles (%llu cycles), spec says %d\n",
                    ull(cycle), tag, ull(lat_adv), ull(lat_cyc), latency_);
    }
    if (lat_cyc < lat_min_) lat_min_ = lat_cyc;
    if (lat_cyc > lat_max_) lat_max_ = lat_cyc;
    pop(1);
  }

  void on_reset() {
    dropped_by_reset_ += size_;
    pop(size_);
  }

  void error(const std::string& what, uint64_t cycle) {
    ++protocol_errors_;
    if (protocol_errors_ <= static_cast<uint64_t>(show_)) std::printf("ERROR cycle %llu: %s\n", ull(cycle), what.c_str());
  }

  // Fragments accepted but not yet out; at the end of a run they count as lost.
  [[nodiscard]] uint64_t in_flight() const { return size_; }
  void finish() {
    if (size_ != 0) {
      std::printf("ERROR: %u transaction(s) never came out (first tag %u)\n", size_, ring_[head_].tag);
      lost_ += size_;
      pop(size_);
    }
  }

  [[nodiscard]] bool ok() const {
    return mismatches_ == 0 && lost_ == 0 && unexpected_ == 0 && latency_errors_ == 0 && protocol_errors_ == 0;
  }

  uint64_t accepted_ = 0, outputs_ = 0, checked_ = 0, mismatches_ = 0, lost_ = 0, unexpected_ = 0,
           latency_errors_ = 0, protocol_errors_ = 0, dropped_by_reset_ = 0, material_writes_ = 0;
  uint64_t lat_min_ = ~uint64_t{0}, lat_max_ = 0;
  std::vector<Mismatch> first_;

 private:
  static constexpr uint32_t kCap = 256;  // power of two; the pipeline holds at most `latency` fragments
  struct Entry {
    uint32_t tag;
    int n;
    int64_t code;
    uint32_t expected;
    uint64_t cycle, adv;
  };
  static unsigned long long ull(uint64_t v) { return static_cast<unsigned long long>(v); }
  void pop(uint32_t k) {
    head_ = (head_ + k) & (kCap - 1);
    size_ -= k;
  }

  const Unit& unit_;
  int latency_, latency_min_;
  int show_;
  UnitMaterial mat_;
  bool mat_valid_ = false;
  std::vector<Entry> ring_;
  uint32_t head_ = 0, size_ = 0;
};

}  // namespace shadecore::sim
