// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the lighting core's testbench logic, free of SystemC, shared by the SystemC testbench
// (sim/light_main.cpp: LightPins of sc_signals, LightDriver and MonitorT as SC_METHODs) and the bare
// Verilated harness (sim/light_bare_main.cpp: the same logic called from a plain C++ clock loop):
//   LightModel, LightScoreboard   the C model side (LightCore::eval on the registers written so far);
//   LightPinOps<Pins>             payloads, register-write observation and fragment driving on any pins
//                                 adapter whose signals have read() / write() (README port table);
//   LightDriveLogic<Pins>         the driver, one call per rising clock edge (see below).
//
// The driver owns every input pin of rtl/sc_light.v. At each rising edge it first sees what was taken at
// that edge (pre-edge values), then sets the pins for the next edge:
//   * rst_ni low for `reset_cycles` at start and once mid-stream before the fragment of local index
//     `reset_at` (this run's count; a random run's global index minus its first, so only the shard
//     holding it resets). With `resend` (the default) the fragments the reset flushes (accepted, not yet
//     out) are sent again after it with new tags — before a register write that was waiting for them —
//     so every fragment is checked exactly once, with the registers it had in the stimulus, whatever the
//     timing; without it they are dropped (counted as dropped_by_reset);
//   * commands in stimulus order: a register write is presented (reg_we_i) until it is taken
//     (reg_we_i && reg_ready_o at an edge: the core drains first); a fragment is presented after a random
//     input gap (in_valid_i low with probability in_stall per cycle) and, once raised, held until taken
//     (in_valid_i && in_ready_o);
//   * out_ready_i low with probability out_stall per cycle (backpressure).
// Tags are consecutive in presentation order = acceptance order.
#pragma once

#include <cstdint>
#include <deque>

#include "shadecore/light.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"
#include "shadecore/stimulus/rng.hpp"
#include "tb_scoreboard.hpp"

namespace shadecore::sim {

// The C model side of a lighting-core transaction: registers as written so far, LightCore::eval. The
// latency bounds depend on the registers only, so they are computed at each register write, not per
// fragment (LightCore::latency(regs) decodes the modes: a measurable share of the bare harness's time).
struct LightModel {
  using In = Fragment;
  using Out = Colour;
  static constexpr const char* kNotReadyMessage = "fragment accepted before any register was written";
  const LightCore* core;
  LightRegs regs{};
  bool written = false;
  int lat = 0, lat_min = 0;  // core->latency_max(regs), core->latency_min(regs)
  [[nodiscard]] bool ready() const { return written; }
  [[nodiscard]] int latency() const { return lat; }
  [[nodiscard]] int latency_min() const { return lat_min; }
  // The functional coverage model's sampler (coverage builds, tb_func_cov.hpp; null otherwise): it gets the
  // C model's trace of the fragment.
  void (*sample)(void* ctx, const LightRegs& r, const Fragment& f, const LightCoreTrace& t) = nullptr;
  void* sample_ctx = nullptr;
  [[nodiscard]] Out expected(const In& in) const {
    if (!sample) return core->eval(regs, in);
    LightCoreTrace t;
    const Out o = core->eval(regs, in, &t);
    sample(sample_ctx, regs, in, t);
    return o;
  }
};

class LightScoreboard : public ScoreboardT<LightModel> {
 public:
  LightScoreboard(const LightCore& core, int show) : ScoreboardT<LightModel>(LightModel{&core, {}, false}, show) {}
  void on_write(uint32_t addr, uint32_t data) {
    model_.regs.write(model_.core->widths(), addr, data);
    model_.written = true;
    model_.lat = model_.core->latency_max(model_.regs);
    model_.lat_min = model_.core->latency_min(model_.regs);
    ++material_writes_;
  }
};

// What every pins adapter of the lighting core does with its signals (CRTP: D has the signals of the
// README port table by the names below, and `frac`).
template <class D>
struct LightPinOps {
  [[nodiscard]] Fragment in_payload() const {
    const D& d = self();
    const int nb = light_normal_bits(d.frac), pb = light_pos_bits(d.frac);
    Fragment f;
    f.n[0] = sign_extend(d.in_nx.read(), nb);
    f.n[1] = sign_extend(d.in_ny.read(), nb);
    f.n[2] = sign_extend(d.in_nz.read(), nb);
    f.p[0] = sign_extend(d.in_px.read(), pb);
    f.p[1] = sign_extend(d.in_py.read(), pb);
    f.p[2] = sign_extend(d.in_pz.read(), pb);
    f.back = d.in_back.read() != 0;
    f.col[0] = d.in_cr.read();
    f.col[1] = d.in_cg.read();
    f.col[2] = d.in_cb.read();
    return f;
  }
  [[nodiscard]] Colour out_payload() const {
    const D& d = self();
    Colour c;
    c.c[0] = d.out_r.read();
    c.c[1] = d.out_g.read();
    c.c[2] = d.out_b.read();
    c.s[0] = d.out_sr.read();
    c.s[1] = d.out_sg.read();
    c.s[2] = d.out_sb.read();
    return c;
  }
  static Colour corrupt(Colour c) {
    c.c[0] ^= 1u;
    return c;
  }
  // EdgeState::reg: 0 no register write presented, 1 presented and held (the core drains first), 2 taken.
  [[nodiscard]] int reg_port() const {
    const D& d = self();
    return !d.reg_we.read() ? 0 : d.reg_ready.read() ? 2 : 1;
  }
  // A register write is taken at an edge where reg_we_i && reg_ready_o; reg_ready_o must be low in reset.
  template <class Sb>
  bool observe_state(Sb& sb, uint64_t cycle) {
    const D& d = self();
    const bool rdy = d.reg_ready.read();
    if (!d.rst_n.read()) {
      if (rdy) sb.error("reg_ready_o high while rst_ni is low", cycle);
      return false;
    }
    if (!d.reg_we.read() || !rdy) return false;
    if (d.in_valid.read() && d.in_ready.read()) sb.error("fragment accepted at the edge of a register write", cycle);
    sb.on_write(d.reg_addr.read(), d.reg_data.read());
    return true;
  }

  void drive_fragment(const Fragment& f, uint32_t tag) {
    D& d = static_cast<D&>(*this);
    const uint32_t nm = static_cast<uint32_t>(mask_bits(light_normal_bits(d.frac)));
    const uint32_t pm = static_cast<uint32_t>(mask_bits(light_pos_bits(d.frac)));
    d.in_nx.write(static_cast<uint32_t>(f.n[0]) & nm);
    d.in_ny.write(static_cast<uint32_t>(f.n[1]) & nm);
    d.in_nz.write(static_cast<uint32_t>(f.n[2]) & nm);
    d.in_px.write(static_cast<uint32_t>(f.p[0]) & pm);
    d.in_py.write(static_cast<uint32_t>(f.p[1]) & pm);
    d.in_pz.write(static_cast<uint32_t>(f.p[2]) & pm);
    d.in_back.write(f.back);
    const uint32_t cm = static_cast<uint32_t>(mask_bits(light_colour_bits(d.frac)));
    d.in_cr.write(f.col[0] & cm);
    d.in_cg.write(f.col[1] & cm);
    d.in_cb.write(f.col[2] & cm);
    d.in_tag.write(tag);
  }

 private:
  const D& self() const { return static_cast<const D&>(*this); }
};

// The mid-stream reset as a local fragment count: `reset_at` is a global index (random mode: the run
// starts at `first`); outside [first, first + planned] none (-1).
inline int64_t light_local_reset(int64_t reset_at, uint64_t first, uint64_t planned) {
  if (reset_at < 0) return -1;
  const uint64_t r = static_cast<uint64_t>(reset_at);
  if (r < first || r - first > planned) return -1;
  return static_cast<int64_t>(r - first);
}

template <class PinsT>
class LightDriveLogic {
 public:
  // reset_at: local fragment count (light_local_reset), -1 none. timing_seed: the stall generators' seed.
  LightDriveLogic(PinsT& pins, LightStimulus& stim, uint64_t timing_seed, double in_stall, double out_stall,
                  int64_t reset_at, int reset_cycles, bool resend)
      : pins_(pins),
        stim_(stim),
        reset_at_(reset_at),
        reset_cycles_(reset_cycles),
        resend_(resend),
        in_stall_(in_stall, timing_seed * 0x9E3779B97F4A7C15ull + 1),
        out_stall_(out_stall, timing_seed * 0xD1B54A32D192ED03ull + 2),
        rst_left_(reset_cycles),
        track_(reset_at >= 0 && resend) {}

  [[nodiscard]] bool done() const { return finished_ && !have_ && replay_.empty(); }
  [[nodiscard]] uint64_t accepted() const { return accepted_; }
  [[nodiscard]] uint64_t resets() const { return resets_; }
  // Fragments sent again after the mid-stream reset flushed them.
  [[nodiscard]] uint64_t replayed() const { return replayed_; }

  void on_edge() {
    // --- what happened at this edge
    // What is in flight (accepted, not yet out), as the monitor counts it: an output taken at this edge
    // (a reset edge too) leaves, a fragment accepted here enters; a reset edge flushes the rest.
    if (pins_.out_valid.read() && ready_q_ && !in_flight_.empty()) in_flight_.pop_front();
    if (have_ && rst_q_) {
      if (cmd_.is_write ? (pins_.reg_we.read() && pins_.reg_ready.read()) : (valid_q_ && pins_.in_ready.read())) {
        have_ = false;
        if (!cmd_.is_write) {
          ++accepted_;
          if (track_) in_flight_.push_back(cmd_);
        }
      }
    }
    if (!rst_q_ && resend_ && !in_flight_.empty()) {
      // Flushed: sent again after the reset. They and a fragment being presented share one register
      // state (a write is taken only once the core has drained), so that fragment may go first, as the
      // unit's driver does; a register write waiting for the drain must not overtake them.
      replayed_ += in_flight_.size();
      if (have_ && cmd_.is_write) {
        replay_.push_front(cmd_);
        have_ = false;
      }
      replay_.insert(replay_.begin(), in_flight_.begin(), in_flight_.end());
      in_flight_.clear();
    }
    // --- reset for the next edge
    if (rst_left_ > 0) --rst_left_;
    if (rst_left_ == 0 && !mid_reset_done_ && reset_at_ >= 0 && accepted_ >= static_cast<uint64_t>(reset_at_)) {
      rst_left_ = reset_cycles_;
      mid_reset_done_ = true;
      ++resets_;
    }
    // What is in flight matters only until the mid-stream reset has flushed it.
    track_ = reset_at_ >= 0 && resend_ && !(mid_reset_done_ && rst_left_ == 0);
    const bool same_cmd = have_;  // the command presented at this edge is still to be taken
    rst_q_ = rst_left_ == 0;
    pins_.rst_n.write(rst_q_);
    // --- next command: a flushed one first, then the stimulus
    if (!have_ && !replay_.empty()) {
      cmd_ = replay_.front();
      replay_.pop_front();
      have_ = true;
      if (!cmd_.is_write) tag_ = next_tag_++;
    } else if (!have_ && !finished_) {
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
      // once raised, valid stays until the fragment is taken (a new fragment draws its gap)
      valid = (valid_q_ && rst_q_ && same_cmd) ? true : !in_stall_.stall();
      if (valid) pins_.drive_fragment(cmd_.f, tag_);
    }
    pins_.reg_we.write(we);
    pins_.in_valid.write(valid);
    valid_q_ = valid;
    ready_q_ = !out_stall_.stall();
    pins_.out_ready.write(ready_q_);
  }

 private:
  PinsT& pins_;
  LightStimulus& stim_;
  const int64_t reset_at_;
  const int reset_cycles_;
  const bool resend_;
  StallGen in_stall_, out_stall_;
  CoreCommand cmd_{};
  bool have_ = false, finished_ = false, valid_q_ = false;
  bool rst_q_ = false;    // rst_ni as driven for the coming edge (low at start)
  bool ready_q_ = false;  // out_ready_i as driven for the coming edge
  int rst_left_;
  bool mid_reset_done_ = false;
  bool track_ = false;  // keep in_flight_ (a mid-stream reset with resend still to come or in progress)
  std::deque<CoreCommand> in_flight_, replay_;
  uint32_t tag_ = 0, next_tag_ = 0;
  uint64_t accepted_ = 0, resets_ = 0, replayed_ = 0;
};

}  // namespace shadecore::sim
