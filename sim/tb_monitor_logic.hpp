// SPDX-License-Identifier: Apache-2.0
// shadecore sim — monitor logic, free of SystemC: passive; called once per rising clock edge with the
// pre-edge values of every port, it turns handshakes into transactions for the scoreboard, in this order
// per edge:
//   output taken (out_valid & out_ready) -> input taken (in_valid & in_ready) -> state write
//   (material write of the unit, register write of the lighting core).
// MonitorLogic<PinsT, SbT, DrvT> serves every testbench — the SystemC ones through MonitorT
// (tb_monitor.hpp), the lighting core's bare Verilated harness (sim/light_bare_main.cpp) directly: the
// pins adapter supplies the payloads (in_payload(), out_payload()) and reports state writes
// (observe_state(sb)); its signals need only read(). The handshake, reset, latency and protocol logic is
// the same for the specular unit and the lighting core.
// It also checks the port protocol: a valid output held back by out_ready low must stay valid
// with the same data and tag at the next edge; in_ready_o must be low while rst_ni is low.
// Latency is counted in advancing edges (edges where !out_valid || out_ready, not in reset), the
// pipeline's global enable, and in raw cycles for the report.
// on_edge() says stop kTail cycles after the driver is done and nothing is in flight (so a spurious
// extra output would still be seen), or on a watchdog.
#pragma once

#include <cstdint>
#include <string>

#include "shadecore/stimulus/func_cov.hpp"  // EdgeState: the handshake state of one edge, for the functional model
#include "tb_scoreboard.hpp"

namespace shadecore::sim {

template <class PinsT, class SbT, class DrvT>
class MonitorLogic {
 public:
  MonitorLogic(PinsT& pins, SbT& sb, const DrvT& drv, const std::string& inject = "", uint64_t inject_at = 0)
      : pins_(pins),
        sb_(sb),
        drv_(drv),
        inject_(inject == "value" ? 1 : inject == "drop" ? 2 : inject == "dup" ? 3 : 0),
        inject_at_(inject_at) {}

  [[nodiscard]] uint64_t cycles() const { return cycle_; }
  [[nodiscard]] bool watchdog_fired() const { return watchdog_; }

  static constexpr uint64_t kIdleLimit = 200000;  // cycles without any transfer = stuck
  static constexpr uint64_t kTail = 32;            // cycles watched after the last expected output

  // The unit's input word width (sign extension of in_cos); kept for the unit testbench.
  void set_in_bits(int bits) { pins_.in_bits = bits; }

  using Out = typename SbT::Out;

  // The functional coverage model's per-edge sampler (coverage builds; null otherwise).
  void (*edge_sample)(void* ctx, const EdgeState& e) = nullptr;
  void* edge_ctx = nullptr;

  // One rising clock edge, on the pre-edge values of the pins. Returns true when the run is over (the
  // driver done, nothing in flight and kTail quiet cycles watched, or the watchdog fired).
  bool on_edge() {
    ++cycle_;
    const bool rst_n = pins_.rst_n.read();
    const bool ov = pins_.out_valid.read();
    const bool ordy = pins_.out_ready.read();
    const bool iv = pins_.in_valid.read();
    const bool irdy = pins_.in_ready.read();
    const uint32_t otag = pins_.out_tag.read();
    const Out opay = pins_.out_payload();
    if (edge_sample) edge_sample(edge_ctx, EdgeState{rst_n, iv, irdy, ov, ordy, sb_.in_flight(), pins_.reg_port()});

    if (held_ && (!ov || otag != held_tag_ || opay != held_pay_))
      sb_.error("output changed while held back by out_ready_i low (valid " + std::to_string(ov) +
                    ", tag " + std::to_string(held_tag_) + " -> " + std::to_string(otag) + ")",
                cycle_);
    bool moved = false;
    if (!rst_n) {
      if (irdy) sb_.error("in_ready_o high while rst_ni is low", cycle_);
      if (ov && ordy) {
        output(otag, opay, adv_ + 1);  // taken at the reset edge
        moved = true;
      }
      sb_.on_reset();
      held_ = false;
    } else {
      if (!ov || ordy) ++adv_;
      if (ov && ordy) {
        output(otag, opay, adv_);
        moved = true;
      }
      if (iv && irdy) {
        sb_.on_input(pins_.in_tag.read(), pins_.in_payload(), cycle_, adv_);
        moved = true;
      }
      held_ = ov && !ordy;
      held_tag_ = otag;
      held_pay_ = opay;
    }
    if (pins_.observe_state(sb_, cycle_)) moved = true;

    idle_ = moved ? 0 : idle_ + 1;
    // Done: keep watching kTail more cycles, so a spurious extra output after the last expected one
    // is still caught (the scoreboard reports it as duplicated/spurious).
    if (drv_.done() && sb_.in_flight() == 0) {
      if (++tail_ > kTail) return true;
    } else if (idle_ > kIdleLimit) {
      watchdog_ = true;
      sb_.error("watchdog: no transfer for " + std::to_string(kIdleLimit) + " cycles", cycle_);
      return true;
    }
    return false;
  }

 private:

  void output(uint32_t tag, Out pay, uint64_t adv) {
    if (inject_ != 0 && ++outputs_seen_ == inject_at_) {  // self-test of the checks only
      if (inject_ == 1) pay = PinsT::corrupt(pay);
      if (inject_ == 2) return;
      if (inject_ == 3) sb_.on_output(tag, pay, cycle_, adv);
    }
    sb_.on_output(tag, pay, cycle_, adv);
  }

  PinsT& pins_;
  SbT& sb_;
  const DrvT& drv_;
  const int inject_;
  const uint64_t inject_at_;
  uint64_t outputs_seen_ = 0;
  uint64_t cycle_ = 0, adv_ = 0, idle_ = 0, tail_ = 0;
  bool held_ = false, watchdog_ = false;
  uint32_t held_tag_ = 0;
  Out held_pay_{};
};

}  // namespace shadecore::sim

