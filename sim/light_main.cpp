// SPDX-License-Identifier: Apache-2.0
// shadecore sim — co-simulation of the lighting core rtl/sc_light.v (Verilated with --sc for ONE
// feature set) against the C model LightCore, in SystemC: sc_clock, the driver and the monitor as
// SC_METHODs (LightDriver, MonitorT) around the logic the bare harness shares (tb_light_logic.hpp,
// tb_monitor_logic.hpp). Built on demand per feature set by `shadecore cosim --core lighting` /
// `shadecore render --rtl` (cli/light_rtl.cpp), which generate light_features.hpp (the feature set's
// canonical JSON) beside the build. Options, report and exit status: tb_light_run.hpp.
//
//   shadecore_light_sim --mode random --count 200000 --in-stall 0.3 --out-stall 0.3 --seed 7
//   shadecore_light_sim --mode directed
//   shadecore_light_sim --mode stream --in cmds.bin --out colours.bin     (a scene's fragments)
#include <systemc.h>
#include <verilated.h>

#include <cstdlib>
#include <memory>

#include "Vlight.h"
#include "light_features.hpp"
#include "tb_func_cov.hpp"
#include "tb_light_driver.hpp"
#include "tb_light_pins.hpp"
#include "tb_light_run.hpp"
#include "tb_monitor.hpp"
#include "tb_trace.hpp"
#if VM_TRACE_FST
#include <verilated_fst_sc.h>
#endif

namespace shadecore::sim {
namespace {

#if VM_TRACE_FST
// The trace build's waveform (tb_trace.hpp): the dump is opened at the rising edge of the window's first
// monitor cycle and closed after its last; outside it the trace file is closed and dumps nothing.
class TraceProbe : public sc_core::sc_module {
 public:
  SC_HAS_PROCESS(TraceProbe);
  TraceProbe(sc_core::sc_module_name name, const sc_core::sc_clock& clk, const TraceWindow& w) : sc_module(name), w_(w) {
    SC_METHOD(on_clk);
    sensitive << clk.posedge_event();
    dont_initialize();
  }
  // After every module is built: elaborate, attach the model, open the dump if the window starts at once.
  void start(Vlight& dut) {
    Verilated::traceEverOn(true);
    sc_core::sc_start(sc_core::SC_ZERO_TIME);  // elaborate before tracing (Verilator + SystemC)
    fst_ = std::make_unique<VerilatedFstSc>();
    dut.trace(fst_.get(), 99);
    if (w_.from <= 1) fst_->open(w_.file.c_str());
  }
  void close() {
    if (fst_) fst_->close();
  }

 private:
  void on_clk() {
    ++cycle_;  // the monitor's count: cycle k is the k-th rising edge
    if (!fst_) return;
    if (cycle_ == w_.from && !fst_->isOpen() && !done_) fst_->open(w_.file.c_str());
    if (cycle_ > w_.to && fst_->isOpen()) fst_->close(), done_ = true;
  }
  const TraceWindow& w_;
  std::unique_ptr<VerilatedFstSc> fst_;
  uint64_t cycle_ = 0;
  bool done_ = false;
};
#endif

LightHarnessStats run_systemc(const LightOptions& o, const LightCore& core, LightStimulus& stim, int64_t reset_local,
                              uint64_t timing_seed, LightScoreboard& sb) {
  LightPins pins;
  pins.frac = core.format().frac;
  Vlight dut("dut");
  pins.bind(dut);
  LightDriver drv("driver", pins, stim, timing_seed, o.in_stall, o.out_stall, reset_local, o.reset_cycles, o.resend);
  MonitorT<LightPins, LightScoreboard, LightDriver> mon("monitor", pins, sb, drv, o.inject, o.inject_at);
  LightFuncCov fcov(core);  // coverage builds with --coverage: the functional model (tb_func_cov.hpp)
  if (kCoverageBuild && !o.coverage.empty()) {
    fcov.attach(Verilated::threadContextp());
    sb.model().sample = light_func_sample;
    sb.model().sample_ctx = &fcov;
    mon.logic().edge_sample = edge_func_sample<LightFuncCov>;
    mon.logic().edge_ctx = &fcov;
  }
#if VM_TRACE_FST
  std::unique_ptr<TraceProbe> trace;
  if (o.trace.on()) {
    trace = std::make_unique<TraceProbe>("trace", pins.clk, o.trace);
    trace->start(dut);
  }
#endif
  sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO, sc_core::SC_DO_NOTHING);
  sc_core::sc_start();
#if VM_TRACE_FST
  if (trace) trace->close();
#endif
  dut.final();
  write_coverage(Verilated::threadContextp(), o.coverage);  // while the model (its counters) lives
  sb.model().sample = nullptr;
  return light_harness_stats(mon, drv);
}

}  // namespace
}  // namespace shadecore::sim

int sc_main(int argc, char** argv) {
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
  return shadecore::sim::light_harness_main(argc, argv, "systemc", kLightFeaturesJson, shadecore::sim::run_systemc,
                                          {shadecore::sim::kCoverageBuild, shadecore::sim::kTraceBuild});
}
