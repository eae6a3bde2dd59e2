// SPDX-License-Identifier: Apache-2.0
// shadecore sim — driver: owns every input pin of the unit. One SC_METHOD per rising clock edge:
// it first sees whether the fragment it presented was taken at that edge (in_valid & in_ready,
// pre-edge values), then sets the pins for the next edge:
//   * rst_ni: low for `reset_cycles` at start and once mid-stream after `reset_at` accepted
//     fragments (the fragment being presented is held and goes in after the reset);
//   * material: before a fragment that needs another n, one cycle with mat_we_i and a bubble
//     (exhaustive, directed); in random mode material writes at random cycles instead, independent
//     of the stream (the scoreboard uses whatever was registered before each acceptance edge);
//   * table units (docs/spec.md §9): a material change is a table load of E cycles — mat_we_i (n, for
//     the reports) with the write of entry 0, then entries 1..E−1 through tab_we_i/tab_addr_i/
//     tab_value_i/tab_delta_i, one per edge. The host rule is obeyed: no fragment is presented during
//     a load (in_valid_i low), and a load starts only when no raised in_valid_i waits to be taken
//     (random mode defers a drawn material change until then); fragments in flight need no drain;
//   * in_valid_i with random gaps (StallGen), held until taken once raised (AXI-Stream rule);
//   * out_ready_i low with probability out_stall (backpressure).
// Tags are consecutive in presentation order = acceptance order.
#pragma once

#include <systemc.h>

#include <cstdint>

#include "shadecore/unit.hpp"
#include "tb_options.hpp"
#include "tb_pins.hpp"
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
        random_mode_(o.mode == Mode::Random),
        n_lo_(o.n_lo),
        n_hi_(o.n_hi),
        reset_at_(o.reset_at),
        reset_cycles_(o.reset_cycles),
        in_stall_(o.in_stall, o.seed * 0x9E3779B97F4A7C15ull + 1),
        out_stall_(o.out_stall, o.seed * 0xD1B54A32D192ED03ull + 2),
        mat_gen_(o.mat_rate, o.seed * 0x8CB92BA72F3D8DD7ull + 3),
        rng_(o.seed * 0xA0761D6478BD642Full + 4),
        code_mask_((uint32_t{1} << unit.format().in_bits()) - 1),
        entries_(unit.entries()),
        rst_left_(o.reset_cycles) {
    SC_METHOD(on_clk);
    sensitive << pins_.clk.posedge_event();
    dont_initialize();
  }

  [[nodiscard]] bool done() const { return finished_ && !have_; }
  [[nodiscard]] uint64_t accepted() const { return accepted_; }
  [[nodiscard]] uint64_t resets() const { return resets_; }
  [[nodiscard]] uint64_t table_writes() const { return table_writes_; }

 private:
  void begin_load(const UnitMaterial& m) {
    load_words_ = m.tab;
    load_addr_ = 0;
    load_left_ = static_cast<uint32_t>(entries_);
  }

  void on_clk() {
    // --- what happened at this edge
    const bool took = rst_q_ && valid_q_ && pins_.in_ready.read();
    if (took) {
      have_ = false;
      ++accepted_;
    }
    // --- reset for the next edge
    if (rst_left_ > 0) --rst_left_;
    if (rst_left_ == 0 && !mid_reset_done_ && reset_at_ >= 0 &&
        accepted_ >= static_cast<uint64_t>(reset_at_)) {
      rst_left_ = reset_cycles_;
      mid_reset_done_ = true;
      ++resets_;
    }
    rst_q_ = rst_left_ == 0;
    pins_.rst_n.write(rst_q_);

    // --- material
    bool we = false;
    UnitMaterial m;
    // A material change is drawn only while none is pending or loading: a table load takes E edges, and
    // changes drawn during it would queue up and starve the fragments (table1024 at --mat-rate 0.01).
    if (random_mode_ && !pending_load_ && load_left_ == 0 && (!any_material_ || mat_gen_.stall())) {
      if (entries_ > 0) {
        pending_load_ = true;  // a table load waits until no raised fragment is held (below)
      } else {
        m = unit_.setup(rng_.uniform(n_lo_, n_hi_));
        we = true;
      }
      any_material_ = true;
    }
    // --- next fragment
    if (!have_ && !finished_) {
      if (stim_.next(item_)) {
        have_ = true;
        tag_ = next_tag_++;
      } else {
        finished_ = true;
      }
    }
    const bool held = valid_q_ && !took;  // a raised in_valid_i not yet taken must stay raised
    if (pending_load_ && load_left_ == 0 && !held) {
      m = unit_.setup(rng_.uniform(n_lo_, n_hi_));
      we = true;
      begin_load(m);
      pending_load_ = false;
    }
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
    pins_.out_ready.write(!out_stall_.stall());
  }

  Pins& pins_;
  Stimulus& stim_;
  const Unit& unit_;
  const bool random_mode_;
  const int n_lo_, n_hi_;
  const int64_t reset_at_;
  const int reset_cycles_;
  StallGen in_stall_, out_stall_, mat_gen_;
  Rng rng_;
  const uint32_t code_mask_;
  const int entries_;  // table units: E; 0 otherwise

  Item item_;
  bool have_ = false, finished_ = false, valid_q_ = false;
  bool rst_q_ = false;  // rst_ni as driven for the coming edge (low at start)
  int rst_left_;
  bool mid_reset_done_ = false;
  bool any_material_ = false;
  int rtl_n_ = -1;
  uint32_t tag_ = 0, next_tag_ = 0;
  uint64_t accepted_ = 0, resets_ = 0;
  // table load in progress
  std::shared_ptr<const std::vector<uint64_t>> load_words_;
  uint32_t load_addr_ = 0, load_left_ = 0;
  bool pending_load_ = false;
  uint64_t table_writes_ = 0;
};

}  // namespace shadecore::sim
