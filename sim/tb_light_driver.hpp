// SPDX-License-Identifier: Apache-2.0
// shadecore sim — lighting-core driver: the SystemC shell of LightDriveLogic (tb_light_logic.hpp, where
// the rules are described: reset and resend, register writes held until taken, input gaps, backpressure).
// One SC_METHOD per rising clock edge; it reads the pre-edge values and its writes take effect after the
// edge (sc_signal semantics).
#pragma once

#include <systemc.h>

#include <cstdint>

#include "tb_light_logic.hpp"
#include "tb_light_pins.hpp"

namespace shadecore::sim {

class LightDriver : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(LightDriver);
  LightDriver(sc_core::sc_module_name name, LightPins& pins, LightStimulus& stim, uint64_t timing_seed,
              double in_stall, double out_stall, int64_t reset_at, int reset_cycles, bool resend)
      : sc_module(name), logic_(pins, stim, timing_seed, in_stall, out_stall, reset_at, reset_cycles, resend) {
    SC_METHOD(on_clk);
    sensitive << pins.clk.posedge_event();
    dont_initialize();
  }

  [[nodiscard]] bool done() const { return logic_.done(); }
  [[nodiscard]] uint64_t accepted() const { return logic_.accepted(); }
  [[nodiscard]] uint64_t resets() const { return logic_.resets(); }
  [[nodiscard]] uint64_t replayed() const { return logic_.replayed(); }

 private:
  void on_clk() { logic_.on_edge(); }
  LightDriveLogic<LightPins> logic_;
};

}  // namespace shadecore::sim
