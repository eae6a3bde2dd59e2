// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the signals between the testbench and the lighting core rtl/sc_light.v (README port
// table, docs/lighting.md §4), for MonitorT / ScoreboardT (tb_monitor.hpp, tb_scoreboard.hpp) through
// LightPinOps (tb_light_logic.hpp). Every port is at most 32 bits wide for F <= 16 (no slow sc_bv).
#pragma once

#include <systemc.h>

#include <cstdint>

#include "tb_light_logic.hpp"

namespace shadecore::sim {

// The SystemC signals; what is done with them is LightPinOps (tb_light_logic.hpp), shared with the bare harness.
struct LightPins : LightPinOps<LightPins> {
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
  sc_core::sc_signal<uint32_t> in_tag{"in_tag", 0};
  sc_core::sc_signal<bool> in_back{"in_back", false};
  sc_core::sc_signal<uint32_t> in_cr{"in_cr", 0}, in_cg{"in_cg", 0}, in_cb{"in_cb", 0};
  sc_core::sc_signal<bool> out_valid{"out_valid", false};
  sc_core::sc_signal<bool> out_ready{"out_ready", false};
  sc_core::sc_signal<uint32_t> out_r{"out_r", 0}, out_g{"out_g", 0}, out_b{"out_b", 0};
  sc_core::sc_signal<uint32_t> out_sr{"out_sr", 0}, out_sg{"out_sg", 0}, out_sb{"out_sb", 0};
  sc_core::sc_signal<uint32_t> out_tag{"out_tag", 0};

  int frac = 16;
  int in_bits = 0;  // unused here (MonitorT::set_in_bits is for the unit)

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
    dut.in_back_i(in_back);
    dut.in_cr_i(in_cr);
    dut.in_cg_i(in_cg);
    dut.in_cb_i(in_cb);
    dut.out_valid_o(out_valid);
    dut.out_ready_i(out_ready);
    dut.out_r_o(out_r);
    dut.out_g_o(out_g);
    dut.out_b_o(out_b);
    dut.out_sr_o(out_sr);
    dut.out_sg_o(out_sg);
    dut.out_sb_o(out_sb);
    dut.out_tag_o(out_tag);
  }
};

}  // namespace shadecore::sim
