// SPDX-License-Identifier: Apache-2.0
// shadecore sim — driver: owns every input pin of the unit. One SC_METHOD per rising clock edge:
// it first sees whether the fragment it presented was taken at that edge (in_valid & in_ready,
// pre-edge values), then sets the pins for the next edge:
//   * rst_ni: low for `reset_cycles` at start and once mid-stream before transaction `reset_at`
//     (random mode: a global transaction index, so only the shard holding it resets). The transactions
//     the reset flushes (accepted, not yet out) and the one being presented are sent again after it, in
//     order with new tags, so every transaction is checked exactly once whatever the timing;
//   * material: before a fragment that needs another n, one cycle with mat_we_i and a bubble (every
//     mode: in random mode the n of each transaction comes from the stimulus, a function of
//     (seed, index));
//   * table units (docs/spec.md §9): a material change is a table load of E cycles — mat_we_i (n, for
//     the reports) with the write of entry 0, then entries 1..E−1 through tab_we_i/tab_addr_i/
//     tab_value_i/tab_delta_i, one per edge. The host rule is obeyed: no fragment is presented during
//     a load (in_valid_i low), and a load starts only when no raised in_valid_i waits to be taken;
//     fragments in flight need no drain;
//   * in_valid_i with random gaps (StallGen), held until taken once raised (AXI-Stream rule);
//   * out_ready_i low with probability out_stall (backpressure).
// Tags are consecutive in presentation order = acceptance order.
#pragma once

#include <systemc.h>

#include <cstdint>
#include <deque>

#include "shadecore/unit.hpp"
#include "tb_options.hpp"
#include "tb_pins.hpp"
#include "tb_reset.hpp"
#include "shadecore/stimulus/rng.hpp"
#include "tb_stimulus.hpp"

namespace shadecore::sim {

class Driver : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(Driver);
  Driver(sc_core::sc_module_name name, Pins& pins, Stimulus& stim, const Unit& unit, const Options& o)
      : sc_module(name),
        pins_(pins),
        stim_(stim),
        unit_(unit),
        reset_(local_reset(o, stim.planned()), o.reset_cycles),
        resend_(o.resend),
        in_stall_(o.in_stall, o.seed * 0x9E3779B97F4A7C15ull + 1),
        out_stall_(o.out_stall, o.seed * 0xD1B54A32D192ED03ull + 2),
        code_mask_((uint32_t{1} << unit.format().in_bits()) - 1),
        entries_(unit.entries()) {
    SC_METHOD(on_clk);
    sensitive << pins_.clk.posedge_event();
    dont_initialize();
  }

  [[nodiscard]] bool done() const { return finished_ && !have_ && replay_.empty(); }
  // Transactions sent again after the mid-stream reset flushed them.
  [[nodiscard]] uint64_t replayed() const { return replayed_; }
  [[nodiscard]] uint64_t accepted() const { return accepted_; }
  [[nodiscard]] uint64_t resets() const { return reset_.resets(); }
  [[nodiscard]] uint64_t table_writes() const { return table_writes_; }

 private:
  // The mid-stream reset as a count of this run's transactions: random mode gives a global index
  // (o.first is this shard's first), outside this shard's range none.
  static int64_t local_reset(const Options& o, uint64_t planned) {
    if (o.reset_at < 0) return -1;
    const uint64_t r = static_cast<uint64_t>(o.reset_at);
    if (r < o.first || r - o.first > planned) return -1;  // (= planned: after the last one is accepted)
    return static_cast<int64_t>(r - o.first);
  }

  void begin_load(const UnitMaterial& m) {
    load_words_ = m.tab;
    load_addr_ = 0;
    load_left_ = static_cast<uint32_t>(entries_);
  }

  void on_clk() {
    // --- what happened at this edge
    const bool took = rst_q_ && valid_q_ && pins_.in_ready.read();
    // What is in flight (accepted, not yet out), as the monitor counts it: an output taken at this edge
    // (a reset edge too) leaves, an input accepted here enters; a reset edge flushes the rest.
    if (pins_.out_valid.read() && ready_q_ && !in_flight_.empty()) in_flight_.pop_front();
    if (took) {
      have_ = false;
      ++accepted_;
      if (reset_.reset_at() >= 0 && resend_) in_flight_.push_back(item_);
    }
    if (!rst_q_ && !in_flight_.empty() && resend_) {
      // Flushed: sent again after the reset, in their order, with new tags (after the one being
      // presented, which is held through the reset; the material registers keep their value).
      replayed_ += in_flight_.size();
      replay_.insert(replay_.end(), in_flight_.begin(), in_flight_.end());
      in_flight_.clear();
    }
    // --- reset for the next edge
    rst_q_ = reset_.next(accepted_);
    pins_.rst_n.write(rst_q_);

    // --- material
    bool we = false;
    UnitMaterial m;
    // --- next fragment: a flushed one first, then the stimulus
    if (!have_ && !replay_.empty()) {
      item_ = replay_.front();
      replay_.pop_front();
      have_ = true;
      tag_ = next_tag_++;
    } else if (!have_ && !finished_) {
      if (stim_.next(item_)) {
        have_ = true;
        tag_ = next_tag_++;
      } else {
        finished_ = true;
      }
    }
    const bool held = valid_q_ && !took;  // a raised in_valid_i not yet taken must stay raised
    bool valid = false;
    if (have_ && load_left_ == 0) {
      if (item_.n >= 0 && item_.n != rtl_n_) {
        m = unit_.setup(item_.n);  // bubble: the new material is registered at this edge
        we = true;
        rtl_n_ = item_.n;
        if (entries_ > 0) begin_load(m);  // and the table is written from this edge on
      } else if (held) {
        valid = true;  // once raised, valid stays until the fragment is taken
      } else {
        valid = !in_stall_.stall();
      }
    }
    pins_.mat_we.write(we);
    if (we) {
      pins_.mat_n.write(static_cast<uint32_t>(m.n));
      pins_.mat_thr.write(m.thr);
      pins_.mat_coef.write(m.coef);
    }
    // --- table load: one entry per edge, in_valid_i low throughout (valid stayed false above)
    const bool twe = load_left_ > 0;
    pins_.tab_we.write(twe);
    if (twe) {
      const int frac = unit_.format().frac;
      const uint64_t w = (*load_words_)[load_addr_];
      pins_.tab_addr.write(load_addr_);
      pins_.tab_value.write(table_word_value(frac, w));
      pins_.tab_delta.write(table_word_delta(frac, w));
      ++load_addr_;
      --load_left_;
      ++table_writes_;
    }
    pins_.in_valid.write(valid);
    if (valid) {
      pins_.in_cos.write(static_cast<uint32_t>(item_.code) & code_mask_);
      pins_.in_tag.write(tag_);
    }
    valid_q_ = valid;
    ready_q_ = !out_stall_.stall();
    pins_.out_ready.write(ready_q_);
  }

  Pins& pins_;
  Stimulus& stim_;
  const Unit& unit_;
  ResetPlan reset_;
  const bool resend_;
  StallGen in_stall_, out_stall_;
  const uint32_t code_mask_;
  const int entries_;  // table units: E; 0 otherwise

  Item item_;
  bool have_ = false, finished_ = false, valid_q_ = false;
  bool rst_q_ = false;  // rst_ni as driven for the coming edge (low at start)
  bool ready_q_ = false;  // out_ready_i as driven for the coming edge
  std::deque<Item> in_flight_, replay_;
  uint64_t replayed_ = 0;
  int rtl_n_ = -1;
  uint32_t tag_ = 0, next_tag_ = 0;
  uint64_t accepted_ = 0;
  // table load in progress
  std::shared_ptr<const std::vector<uint64_t>> load_words_;
  uint32_t load_addr_ = 0, load_left_ = 0;
  uint64_t table_writes_ = 0;
};

}  // namespace shadecore::sim
