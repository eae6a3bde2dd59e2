// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the signals between the testbench and the unit (docs/spec.md §4 port table).
// Every port of sc_specular is at most 32 bits wide in every configuration, so the Verilated
// --sc model uses bool / uint32_t ports (no slow sc_bv).
#pragma once

#include <systemc.h>

#include <cstdint>

namespace shadecore::sim {

struct Pins {
  sc_core::sc_clock clk{"clk", 10, sc_core::SC_NS};
  sc_core::sc_signal<bool> rst_n{"rst_n", false};
  sc_core::sc_signal<bool> mat_we{"mat_we", false};
  sc_core::sc_signal<uint32_t> mat_n{"mat_n", 16};
  sc_core::sc_signal<uint32_t> mat_thr{"mat_thr", 0};
  sc_core::sc_signal<uint32_t> mat_coef{"mat_coef", 0};  // ENERGY = 1 only (ignored otherwise)
  // Table write port (table units only, docs/spec.md §9; tied low for the others by the driver).
  sc_core::sc_signal<bool> tab_we{"tab_we", false};
  sc_core::sc_signal<uint32_t> tab_addr{"tab_addr", 0};
  sc_core::sc_signal<uint32_t> tab_value{"tab_value", 0};
  sc_core::sc_signal<uint32_t> tab_delta{"tab_delta", 0};
  sc_core::sc_signal<bool> in_valid{"in_valid", false};
  sc_core::sc_signal<bool> in_ready{"in_ready", false};
  sc_core::sc_signal<uint32_t> in_cos{"in_cos", 0};
  sc_core::sc_signal<uint32_t> in_tag{"in_tag", 0};
  sc_core::sc_signal<bool> out_valid{"out_valid", false};
  sc_core::sc_signal<bool> out_ready{"out_ready", false};
  sc_core::sc_signal<uint32_t> out_spec{"out_spec", 0};
  sc_core::sc_signal<uint32_t> out_tag{"out_tag", 0};

  // Adapter for MonitorT (tb_monitor.hpp): payloads as the scoreboard sees them.
  int in_bits = 18;  // signed input word width (F+2)
  [[nodiscard]] int64_t in_payload() const {
    const int sh = 64 - in_bits;
    return static_cast<int64_t>(static_cast<uint64_t>(in_cos.read()) << sh) >> sh;
  }
  [[nodiscard]] uint32_t out_payload() const { return out_spec.read(); }
  [[nodiscard]] int reg_port() const { return 0; }  // EdgeState::reg: a unit has no register port
  static uint32_t corrupt(uint32_t v) { return v ^ 1u; }  // self-test: flip bit 0
  // A material or table write at this edge (after the input of the same edge: it uses the old state).
  template <class Sb>
  bool observe_state(Sb& sb, uint64_t /*cycle*/) {
    if (mat_we.read()) sb.on_material(static_cast<int>(mat_n.read()), mat_thr.read(), mat_coef.read());
    if (tab_we.read()) sb.on_table_write(tab_addr.read(), tab_value.read(), tab_delta.read());
    return false;  // a state write is not a data transfer (the watchdog counts transfers)
  }

  template <class M>
  void bind(M& dut) {
    dut.clk_i(clk);
    dut.rst_ni(rst_n);
    dut.mat_we_i(mat_we);
    dut.mat_n_i(mat_n);
    dut.mat_thr_i(mat_thr);
    dut.mat_coef_i(mat_coef);
    dut.tab_we_i(tab_we);
    dut.tab_addr_i(tab_addr);
    dut.tab_value_i(tab_value);
    dut.tab_delta_i(tab_delta);
    dut.in_valid_i(in_valid);
    dut.in_ready_o(in_ready);
    dut.in_cos_i(in_cos);
    dut.in_tag_i(in_tag);
    dut.out_valid_o(out_valid);
    dut.out_ready_i(out_ready);
    dut.out_spec_o(out_spec);
    dut.out_tag_o(out_tag);
  }
};

}  // namespace shadecore::sim
