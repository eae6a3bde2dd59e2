// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the signals between the testbench and the lighting core rtl/sc_light.v (README port
// table, docs/lighting.md §4), and its adapter for MonitorT / ScoreboardT (tb_monitor.hpp,
// tb_scoreboard.hpp). Every port is at most 32 bits wide for F <= 16 (no slow sc_bv).
#pragma once

#include <systemc.h>

#include <cstdint>

#include "shadecore/light.hpp"
#include "tb_scoreboard.hpp"

namespace shadecore::sim {

// The C model side of a lighting-core transaction: registers as written so far, LightCore::eval.
struct LightModel {
  using In = Fragment;
  using Out = Colour;
  static constexpr const char* kNotReadyMessage = "fragment accepted before any register was written";
  const LightCore* core;
  LightRegs regs{};
  bool written = false;
  [[nodiscard]] bool ready() const { return written; }
  [[nodiscard]] int latency() const { return core->latency(regs); }
  [[nodiscard]] int latency_min() const { return core->latency_min(regs); }
  [[nodiscard]] Out expected(const In& in) const { return core->eval(regs, in); }
};

class LightScoreboard : public ScoreboardT<LightModel> {
 public:
  LightScoreboard(const LightCore& core, int show) : ScoreboardT<LightModel>(LightModel{&core, {}, false}, show) {}
  void on_write(uint32_t addr, uint32_t data) {
    model_.regs.write(model_.core->widths(), addr, data);
    model_.written = true;
    ++material_writes_;
  }
};

struct LightPins {
  sc_core::sc_clock clk{"clk", 10, sc_core::SC_NS};
  sc_core::sc_signal<bool> rst_n{"rst_n", false};
  sc_core::sc_signal<bool> reg_we{"reg_we", false};
  sc_core::sc_signal<uint32_t> reg_addr{"reg_addr", 0};
  sc_core::sc_signal<uint32_t> reg_data{"reg_data", 0};
  sc_core::sc_signal<bool> reg_ready{"reg_ready", false};
  sc_core::sc_signal<bool> in_valid{"in_valid", false};
  sc_core::sc_signal<bool> in_ready{"in_ready", false};
  sc_core::sc_signal<uint32_t> in_nx{"in_nx", 0}, in_ny{"in_ny", 0}, in_nz{"in_nz", 0};
  sc_core::sc_signal<uint32_t> in_px{"in_px", 0}, in_py{"in_py", 0}, in_pz{"in_pz", 0};
  sc_core::sc_signal<uint32_t>* const in_n[3] = {&in_nx, &in_ny, &in_nz};
  sc_core::sc_signal<uint32_t>* const in_p[3] = {&in_px, &in_py, &in_pz};
  sc_core::sc_signal<uint32_t> in_tag{"in_tag", 0};
  sc_core::sc_signal<bool> out_valid{"out_valid", false};
  sc_core::sc_signal<bool> out_ready{"out_ready", false};
  sc_core::sc_signal<uint32_t> out_r{"out_r", 0}, out_g{"out_g", 0}, out_b{"out_b", 0};
  sc_core::sc_signal<uint32_t>* const out_c[3] = {&out_r, &out_g, &out_b};
  sc_core::sc_signal<uint32_t> out_tag{"out_tag", 0};

  int frac = 16;
  int in_bits = 0;  // unused here (MonitorT::set_in_bits is for the unit)

  [[nodiscard]] Fragment in_payload() const {
    Fragment f;
    for (int i = 0; i < 3; ++i) {
      f.n[i] = sign_extend(in_n[i]->read(), light_normal_bits(frac));
      f.p[i] = sign_extend(in_p[i]->read(), light_pos_bits(frac));
    }
    return f;
  }
  [[nodiscard]] Colour out_payload() const {
    Colour c;
    for (int i = 0; i < 3; ++i) c.c[i] = out_c[i]->read();
    return c;
  }
  static Colour corrupt(Colour c) {
    c.c[0] ^= 1u;
    return c;
  }
  // A register write is taken at an edge where reg_we_i && reg_ready_o; reg_ready_o must be low in reset.
  template <class Sb>
  bool observe_state(Sb& sb, uint64_t cycle) {
    const bool rdy = reg_ready.read();
    if (!rst_n.read()) {
      if (rdy) sb.error("reg_ready_o high while rst_ni is low", cycle);
      return false;
    }
    if (!reg_we.read() || !rdy) return false;
    if (in_valid.read() && in_ready.read()) sb.error("fragment accepted at the edge of a register write", cycle);
    sb.on_write(reg_addr.read(), reg_data.read());
    return true;
  }

  void drive_fragment(const Fragment& f, uint32_t tag) {
    const uint32_t nm = static_cast<uint32_t>(mask_bits(light_normal_bits(frac)));
    const uint32_t pm = static_cast<uint32_t>(mask_bits(light_pos_bits(frac)));
    for (int i = 0; i < 3; ++i) {
      in_n[i]->write(static_cast<uint32_t>(f.n[i]) & nm);
      in_p[i]->write(static_cast<uint32_t>(f.p[i]) & pm);
    }
    in_tag.write(tag);
  }

  template <class M>
  void bind(M& dut) {
    dut.clk_i(clk);
    dut.rst_ni(rst_n);
    dut.reg_we_i(reg_we);
    dut.reg_addr_i(reg_addr);
    dut.reg_data_i(reg_data);
    dut.reg_ready_o(reg_ready);
    dut.in_valid_i(in_valid);
    dut.in_ready_o(in_ready);
    dut.in_nx_i(in_nx);
    dut.in_ny_i(in_ny);
    dut.in_nz_i(in_nz);
    dut.in_px_i(in_px);
    dut.in_py_i(in_py);
    dut.in_pz_i(in_pz);
    dut.in_tag_i(in_tag);
    dut.out_valid_o(out_valid);
    dut.out_ready_i(out_ready);
    dut.out_r_o(out_r);
    dut.out_g_o(out_g);
    dut.out_b_o(out_b);
    dut.out_tag_o(out_tag);
  }
};

}  // namespace shadecore::sim
