// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the lighting core's bare harness: rtl/sc_light.v Verilated WITHOUT SystemC (--cc) for
// ONE feature set, driven by a plain C++ clock loop (no scheduler, no signals, two evals per clock), for
// long random regressions. Everything else is the SystemC testbench's (sim/light_main.cpp): the stimulus
// (LightStimulus: register program, write bursts, fragments — a function of (seed, index)), the driver
// (LightDriveLogic: reset and resend, input gaps, backpressure), the monitor (MonitorLogic: transfers,
// tags, latency, protocol), the scoreboard (every output against LightCore::eval, bit for bit, lost /
// duplicated / reordered fragments), the options, the report and the exit status (tb_light_run.hpp).
// Built on demand per feature set by `shadecore cosim --core lighting --harness bare` (cli/light_rtl.cpp)
// into the same cache as the SystemC testbench. Built with SHADECORE_LIGHT_AXI=1 (target shadecore_light_axi,
// `--harness axi` / `--axi`) it drives the core inside its AXI wrapper rtl/sc_light_axi.v through the bus model of
// sim/tb_light_axi.hpp instead, with the same stimulus, driver, monitor and scoreboard.
//
//   shadecore_light_bare --mode random --count 1000000 --in-stall 0.3 --out-stall 0.3 --seed 7
//
// The clock loop mirrors SystemC's evaluation order: at each rising edge the monitor and the driver see
// the pre-edge values (inputs as driven for this edge, outputs settled from them); the driver's writes
// are held (BareIn::pend) and applied after the edge, as an sc_signal's are; then the model settles.
#include <verilated.h>

#include <cstdint>
#include <type_traits>

#if SHADECORE_LIGHT_AXI
#include "Vlight_axi.h"
#include "tb_light_axi.hpp"
#else
#include "Vlight_bare.h"
#endif
#include "light_features.hpp"
#include "tb_func_cov.hpp"
#include "tb_light_logic.hpp"
#include "tb_light_run.hpp"
#include "tb_monitor_logic.hpp"
#include "tb_trace.hpp"
#if VM_TRACE_FST
#include <verilated_fst_c.h>

#include <memory>
#endif

namespace shadecore::sim {
namespace {

template <class F>
using Field = std::remove_cv_t<std::remove_reference_t<F>>;

// An input port of the Verilated model: read() is the value the model sees (pre-edge), write() takes
// effect at commit(), after the edge.
template <class T>
struct BareIn {
  T& f;
  T pend;
  explicit BareIn(T& field) : f(field), pend(field) {}
  [[nodiscard]] T read() const { return f; }
  void write(uint64_t v) { pend = static_cast<T>(v); }
  void commit() { f = pend; }
};
// An output port: read() only.
template <class T>
struct BareOut {
  const T& f;
  [[nodiscard]] T read() const { return f; }
};

#if !SHADECORE_LIGHT_AXI
struct BarePins : LightPinOps<BarePins> {
  using M = Vlight_bare;
  explicit BarePins(M& t)
      : rst_n(t.rst_ni), reg_we(t.reg_we_i), reg_addr(t.reg_addr_i), reg_data(t.reg_data_i), reg_ready{t.reg_ready_o},
        in_valid(t.in_valid_i), in_ready{t.in_ready_o}, in_nx(t.in_nx_i), in_ny(t.in_ny_i), in_nz(t.in_nz_i),
        in_px(t.in_px_i), in_py(t.in_py_i), in_pz(t.in_pz_i), in_tag(t.in_tag_i), in_back(t.in_back_i),
        in_cr(t.in_cr_i), in_cg(t.in_cg_i), in_cb(t.in_cb_i), out_valid{t.out_valid_o},
        out_ready(t.out_ready_i), out_r{t.out_r_o}, out_g{t.out_g_o}, out_b{t.out_b_o},
        out_sr{t.out_sr_o}, out_sg{t.out_sg_o}, out_sb{t.out_sb_o}, out_tag{t.out_tag_o} {}
  BareIn<Field<decltype(M::rst_ni)>> rst_n;
  BareIn<Field<decltype(M::reg_we_i)>> reg_we;
  BareIn<Field<decltype(M::reg_addr_i)>> reg_addr;
  BareIn<Field<decltype(M::reg_data_i)>> reg_data;
  BareOut<Field<decltype(M::reg_ready_o)>> reg_ready;
  BareIn<Field<decltype(M::in_valid_i)>> in_valid;
  BareOut<Field<decltype(M::in_ready_o)>> in_ready;
  BareIn<Field<decltype(M::in_nx_i)>> in_nx, in_ny, in_nz;
  BareIn<Field<decltype(M::in_px_i)>> in_px, in_py, in_pz;
  BareIn<Field<decltype(M::in_tag_i)>> in_tag;
  BareIn<Field<decltype(M::in_back_i)>> in_back;
  BareIn<Field<decltype(M::in_cr_i)>> in_cr, in_cg, in_cb;
  BareOut<Field<decltype(M::out_valid_o)>> out_valid;
  BareIn<Field<decltype(M::out_ready_i)>> out_ready;
  BareOut<Field<decltype(M::out_r_o)>> out_r, out_g, out_b, out_sr, out_sg, out_sb;
  BareOut<Field<decltype(M::out_tag_o)>> out_tag;
  int frac = 16;
  int in_bits = 0;  // unused (MonitorLogic::set_in_bits is for the unit)

  void commit() {
    rst_n.commit(), reg_we.commit(), reg_addr.commit(), reg_data.commit(), in_valid.commit();
    in_nx.commit(), in_ny.commit(), in_nz.commit(), in_px.commit(), in_py.commit(), in_pz.commit(), in_back.commit();
    in_cr.commit(), in_cg.commit(), in_cb.commit();
    in_tag.commit(), out_ready.commit();
  }
  void settled() {}
  static void init(M& top) {
    top.clk_i = 0;
    top.rst_ni = 0;
    top.reg_we_i = 0;
    top.in_valid_i = 0;
    top.out_ready_i = 0;
  }
};

#endif

// The model this harness drives: the bare core, or (SHADECORE_LIGHT_AXI, target shadecore_light_axi) the core inside
// its AXI wrapper rtl/sc_light_axi.v through the bus model of tb_light_axi.hpp — the same driver, monitor and scoreboard.
#if SHADECORE_LIGHT_AXI
using Top = Vlight_axi;
using Pins = AxiPins<Vlight_axi>;
constexpr const char* kHarness = "axi";
Pins make_pins(Top& t, const LightCore& core, const LightOptions& o, uint64_t timing_seed) {
  return Pins(t, core.features(), core.format().frac, timing_seed, o.out_stall, o.inject, o.inject_at);
}
nlohmann::json pins_stats(const Pins& p) { return p.stats(); }
#else
using Top = Vlight_bare;
using Pins = BarePins;
constexpr const char* kHarness = "bare";
Pins make_pins(Top& t, const LightCore& core, const LightOptions&, uint64_t) {
  Pins p(t);
  p.frac = core.format().frac;
  return p;
}
nlohmann::json pins_stats(const Pins&) { return nullptr; }
#endif

LightHarnessStats run_bare(const LightOptions& o, const LightCore& core, LightStimulus& stim, int64_t reset_local,
                           uint64_t timing_seed, LightScoreboard& sb) {
  VerilatedContext ctx;
  if (kTraceBuild && o.trace.on()) ctx.traceEverOn(true);  // before the model is built
  Top top{&ctx};
  Pins::init(top);
  Pins pins = make_pins(top, core, o, timing_seed);
  using Drv = LightDriveLogic<Pins>;
  Drv drv(pins, stim, timing_seed, o.in_stall, o.out_stall, reset_local, o.reset_cycles, o.resend);
  MonitorLogic<Pins, LightScoreboard, Drv> mon(pins, sb, drv, o.inject, o.inject_at);
  LightFuncCov fcov(core);  // coverage builds with --coverage: the functional model (tb_func_cov.hpp)
  if (kCoverageBuild && !o.coverage.empty()) {
    fcov.attach(&ctx);
    sb.model().sample = light_func_sample;
    sb.model().sample_ctx = &fcov;
    mon.edge_sample = edge_func_sample<LightFuncCov>;
    mon.edge_ctx = &fcov;
  }
#if VM_TRACE_FST
  // The trace build's waveform (tb_trace.hpp): dumped at SystemC's times (cycle k's rising edge at
  // (k - 1) * 10 ns, the falling edge 5 ns later), opened at the window's first cycle, closed after its last.
  std::unique_ptr<VerilatedFstC> fst;
  uint64_t cycle = 0;
  const auto ticks_per_ns = [&ctx] {
    uint64_t t = 1;
    for (int p = ctx.timeprecision(); p < -9; ++p) t *= 10;
    return t;
  }();
  if (o.trace.on()) {
    fst = std::make_unique<VerilatedFstC>();
    top.trace(fst.get(), 99);
  }
#endif
  top.eval();
  pins.settled();
  for (;;) {
    const bool stop = mon.on_edge();  // pre-edge values
    drv.on_edge();                    // pre-edge values in, next inputs held in pend
    top.clk_i = 1;
    top.eval();                       // the edge, on the pre-edge inputs
    pins.commit();
#if VM_TRACE_FST
    if (fst) {
      ++cycle;
      if (cycle == o.trace.from || (cycle == 1 && o.trace.from == 0)) fst->open(o.trace.file.c_str());
      if (cycle > o.trace.to && fst->isOpen()) fst->close();
      if (fst->isOpen()) {
        top.eval();  // the new inputs settle while the clock is high (no edge: the same state as below)
        const uint64_t t0 = (cycle - 1) * kTraceClockNs * ticks_per_ns;
        fst->dump(t0);
        top.clk_i = 0;
        top.eval();
        pins.settled();
        fst->dump(t0 + kTraceClockNs * ticks_per_ns / 2);
        if (stop) break;
        continue;
      }
    }
#endif
    top.clk_i = 0;
    top.eval();                       // settle on the new inputs
    pins.settled();
    if (stop) break;
  }
#if VM_TRACE_FST
  if (fst) fst->close();
#endif
  top.final();
  write_coverage(&ctx, o.coverage);  // while the model (its counters) lives
  sb.model().sample = nullptr;
  LightHarnessStats hs = light_harness_stats(mon, drv);
  hs.extra = pins_stats(pins);
  return hs;
}

}  // namespace
}  // namespace shadecore::sim

int main(int argc, char** argv) {
  return shadecore::sim::light_harness_main(argc, argv, shadecore::sim::kHarness, kLightFeaturesJson, shadecore::sim::run_bare,
                                            {shadecore::sim::kCoverageBuild, shadecore::sim::kTraceBuild});
}
