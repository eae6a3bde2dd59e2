// SPDX-License-Identifier: Apache-2.0
// shadecore sim — one co-simulation run of the lighting core, free of SystemC: the command line, the
// stimulus, the scoreboard, the summary and the COSIM-RESULT line, shared by both harnesses of a feature
// set's build (sim/light_core): the SystemC testbench (sim/light_main.cpp, `shadecore_light_sim`) and the
// bare Verilated harness (sim/light_bare_main.cpp, `shadecore_light_bare`). A harness supplies only its
// clock loop (LightHarnessFn); what is driven, checked and reported is the same, so the two give the same
// verdict, the same counts and the same JSON fields for the same options (cycle counts may differ: none).
//
//   <harness> --mode random --count 200000 --in-stall 0.3 --out-stall 0.3 --seed 7
//   <harness> --mode random --count 50000 --first 50000 --reset-at 61234 --seed 7     (a shard)
//   <harness> --mode directed
//   <harness> --mode stream --in cmds.bin --out colours.bin     (a scene's fragments)
//
// Exit status (docs/cli.md): 0 every output matched the C model bit for bit, nothing was lost, duplicated
// or reordered, every latency was within the core's contract and the port protocol held; 2 the run
// completed and FAILED (or checked nothing); 1 a bad argument or an error (one line on stderr).
//
// The program itself (options, stimulus, report: light_harness_main) is sim/tb_light_run.cpp, compiled once in the
// main build as the library shadecore_light_harness and linked into every feature set's harnesses (sim/light_core):
// a feature set's build compiles only its clock loop and the Verilated model (~40 s less per harness).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include <nlohmann/json.hpp>

#include "shadecore/light.hpp"
#include "shadecore/stimulus/light_stimulus.hpp"
#include "tb_harness_build.hpp"
#include "tb_light_logic.hpp"

namespace shadecore::sim {

struct LightOptions {
  std::string mode = "random";
  uint64_t count = 100000;
  uint64_t seed = 1;
  uint64_t first = 0;  // random: global index of this run's first fragment (a shard of a longer run)
  double in_stall = 0.0, out_stall = 0.0, write_rate = 0.002;
  int64_t reset_at = -2;  // global fragment index; -1 none; -2 auto
  int reset_cycles = 3;
  bool resend = true;
  std::string in_file, out_file;
  int show = 10;
  std::string inject;
  uint64_t inject_at = 100;
  bool quiet = false;
  std::string label = "custom";
  std::string coverage;  // coverage build: the database written at the end of the run (tb_coverage.hpp)
  TraceWindow trace;     // trace build: the FST waveform written while the run lasts (tb_trace.hpp)
};

// What a harness's clock loop reports back (the scoreboard holds the rest).
struct LightHarnessStats {
  uint64_t cycles = 0;
  bool watchdog = false;
  uint64_t resets = 0, replayed = 0;
  nlohmann::json extra;  // the AXI harness's bus counts (sim/tb_light_axi.hpp), null otherwise
};

// The stats of a finished run, from its monitor (cycles(), watchdog_fired()) and driver (resets(), replayed()).
template <class Mon, class Drv>
LightHarnessStats light_harness_stats(const Mon& mon, const Drv& drv) {
  LightHarnessStats s;
  s.cycles = mon.cycles();
  s.watchdog = mon.watchdog_fired();
  s.resets = drv.resets();
  s.replayed = drv.replayed();
  return s;
}

// One harness: run the stimulus through the core until done. reset_local: the mid-stream reset as this
// run's fragment count (light_local_reset); timing_seed: the stall generators' seed.
using LightHarnessFn = std::function<LightHarnessStats(const LightOptions&, const LightCore&, LightStimulus&,
                                                       int64_t reset_local, uint64_t timing_seed, LightScoreboard&)>;

// The whole program of a harness: options, the feature set the build was made for (its canonical JSON,
// light_features.hpp), the run. `harness` names it in the report ("systemc" / "bare" / "axi"); `build`: what the
// harness was Verilated with (its option checks: --coverage, --trace).
int light_harness_main(int argc, char** argv, const char* harness, const char* features_json, const LightHarnessFn& loop,
                       const HarnessBuild& build);

}  // namespace shadecore::sim
