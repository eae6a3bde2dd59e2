// SPDX-License-Identifier: Apache-2.0
// shadecore sim — monitor: the SystemC shell of MonitorLogic (tb_monitor_logic.hpp, where the checks are
// described): one SC_METHOD per rising clock edge samples the pre-edge values of every port; it stops the
// simulation (sc_stop) when the logic says the run is over.
#pragma once

#include <systemc.h>

#include <cstdint>
#include <string>

#include "tb_monitor_logic.hpp"

namespace shadecore::sim {

// The SystemC shell of MonitorLogic (tb_monitor_logic.hpp): one SC_METHOD per rising clock edge.
template <class PinsT, class SbT, class DrvT>
class MonitorT : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(MonitorT);
  MonitorT(sc_core::sc_module_name name, PinsT& pins, SbT& sb, const DrvT& drv,
           const std::string& inject = "", uint64_t inject_at = 0)
      : sc_module(name), logic_(pins, sb, drv, inject, inject_at) {
    SC_METHOD(on_clk);
    sensitive << pins.clk.posedge_event();
    dont_initialize();
  }

  using Logic = MonitorLogic<PinsT, SbT, DrvT>;
  static constexpr uint64_t kIdleLimit = Logic::kIdleLimit;
  static constexpr uint64_t kTail = Logic::kTail;

  [[nodiscard]] uint64_t cycles() const { return logic_.cycles(); }
  [[nodiscard]] bool watchdog_fired() const { return logic_.watchdog_fired(); }
  void set_in_bits(int bits) { logic_.set_in_bits(bits); }
  Logic& logic() { return logic_; }

 private:
  void on_clk() {
    if (logic_.on_edge()) sc_core::sc_stop();
  }
  Logic logic_;
};

}  // namespace shadecore::sim

// The specular unit's monitor (rtl/sc_specular.v): tb_pins.hpp's Pins, the unit Scoreboard, Driver.
#include "tb_driver.hpp"
#include "tb_pins.hpp"
namespace shadecore::sim {
using Monitor = MonitorT<Pins, Scoreboard, Driver>;
}  // namespace shadecore::sim
