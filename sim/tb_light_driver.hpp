// SPDX-License-Identifier: Apache-2.0
// shadecore sim — lighting-core driver: owns every input pin of rtl/sc_light.v. One SC_METHOD per
// rising clock edge: it first sees what was taken at that edge (pre-edge values), then sets the pins
// for the next edge. The same rules as the unit's driver (tb_driver.hpp):
//   * rst_ni low for `reset_cycles` at start and once mid-stream after `reset_at` accepted fragments;
//   * commands in stimulus order: a register write is presented (reg_we_i) until it is taken
//     (reg_we_i && reg_ready_o at an edge: the core drains first); a fragment is presented with random
//     input gaps (in_valid_i) and, once raised, held until taken (in_valid_i && in_ready_o);
//   * out_ready_i low with probability out_stall (backpressure).
// Tags are consecutive in presentation order = acceptance order.
#pragma once

#include <systemc.h>

#include <cstdint>

#include "tb_light_pins.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"
#include "shadecore/stimulus/rng.hpp"

namespace shadecore::sim {

class LightDriver : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(LightDriver);
  LightDriver(sc_core::sc_module_name name, LightPins& pins, LightStimulus& stim, uint64_t seed, double in_stall,
              double out_stall, int64_t reset_at, int reset_cycles)
      : sc_module(name),
        pins_(pins),
        stim_(stim),
        reset_at_(reset_at),
        reset_cycles_(reset_cycles),
        in_stall_(in_stall, seed * 0x9E3779B97F4A7C15ull + 1),
        out_stall_(out_stall, seed * 0xD1B54A32D192ED03ull + 2),
        rst_left_(reset_cycles) {
    SC_METHOD(on_clk);
    sensitive << pins_.clk.posedge_event();
    dont_initialize();
  }

  [[nodiscard]] bool done() const { return finished_ && !have_; }
  [[nodiscard]] uint64_t accepted() const { return accepted_; }
  [[nodiscard]] uint64_t resets() const { return resets_; }

 private:
  void on_clk() {
    // --- what happened at this edge
    if (have_ && rst_q_) {
      if (cmd_.is_write ? (pins_.reg_we.read() && pins_.reg_ready.read())
                        : (valid_q_ && pins_.in_ready.read())) {
        have_ = false;
        if (!cmd_.is_write) ++accepted_;
      }
    }
    // --- reset for the next edge
    if (rst_left_ > 0) --rst_left_;
    if (rst_left_ == 0 && !mid_reset_done_ && reset_at_ >= 0 && accepted_ >= static_cast<uint64_t>(reset_at_)) {
      rst_left_ = reset_cycles_;
      mid_reset_done_ = true;
      ++resets_;
    }
    rst_q_ = rst_left_ == 0;
    pins_.rst_n.write(rst_q_);
    // --- next command
    if (!have_ && !finished_) {
      if (stim_.next(cmd_)) {
        have_ = true;
        if (!cmd_.is_write) tag_ = next_tag_++;
      } else {
        finished_ = true;
      }
    }
    bool we = false, valid = false;
    if (have_ && cmd_.is_write) {
      we = true;  // held until taken
      pins_.reg_addr.write(cmd_.w.addr);
      pins_.reg_data.write(cmd_.w.data);
    } else if (have_) {
      valid = (valid_q_ && rst_q_) ? true : !in_stall_.stall();  // once raised, valid stays until taken
      if (valid) pins_.drive_fragment(cmd_.f, tag_);
    }
    pins_.reg_we.write(we);
    pins_.in_valid.write(valid);
    valid_q_ = valid;
    pins_.out_ready.write(!out_stall_.stall());
  }

  LightPins& pins_;
  LightStimulus& stim_;
  const int64_t reset_at_;
  const int reset_cycles_;
  StallGen in_stall_, out_stall_;
  CoreCommand cmd_{};
  bool have_ = false, finished_ = false, valid_q_ = false;
  bool rst_q_ = false;
  int rst_left_;
  bool mid_reset_done_ = false;
  uint32_t tag_ = 0, next_tag_ = 0;
  uint64_t accepted_ = 0, resets_ = 0;
};

}  // namespace shadecore::sim
