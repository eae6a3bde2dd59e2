// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — the lighting core in RTL, built on demand for one feature set and cached by its key
// (docs/lighting.md §6). Like Mesa's program cache keyed on the fixed-function state: the first use of a
// feature set Verilates rtl/sc_light.v with exactly that set's parameters together with the SystemC
// testbench (sim/light_main.cpp) — or, for `--harness bare`, without SystemC together with the bare
// harness (sim/light_bare_main.cpp) — into <cache>/<key>/ (one CMake project, sim/light_core, a target
// per harness, each built when first asked for); every later use reuses the executable.
//
// The cache directory: $SHADECORE_CORE_CACHE if set, else <build dir>/cores.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "shadecore/stimulus/light_stream.hpp"
#include "shadecore/features.hpp"

namespace shadecore::cli {

struct CoreBuild {
  std::string exe;         // the simulator executable for this feature set
  std::string dir;         // its cache directory
  bool built_now = false;  // false: reused from the cache
  double build_seconds = 0.0;
};

// The two harnesses of a feature set's build: the SystemC testbench (shadecore_light_sim; protocol-rich
// runs, `render --rtl`) and the bare Verilated harness (shadecore_light_bare; long random regressions).
enum class Harness { SystemC, Bare, Axi };  // Axi: the bare harness through the AXI wrapper rtl/sc_light_axi.v
Harness parse_harness(const std::string& name);  // "systemc" | "bare" | "axi"; throws std::invalid_argument
const char* harness_name(Harness h);

// Build (or find) the simulator of `fs` for harness `h`. Progress on stderr when building (it takes
// ~30–90 s). Throws std::runtime_error with one line (and the log path) if Verilator or the compiler fails.
// `coverage`: the coverage build of the set (line, branch and toggle points; docs/coverage.md), cached apart
// (<key>-cov) from the speed build. `trace`: the trace build (Verilated with --trace-fst: the harnesses take
// --trace FILE; sim/tb_trace.hpp), cached apart (<key>-trace). Not both.
CoreBuild ensure_core(const FeatureSet& fs, bool quiet = false, Harness h = Harness::SystemC, bool coverage = false,
                      bool trace = false);

// One simulator built on demand from a CMake project of sim/ and cached by key (the lighting core per
// feature set; the coverage builds, cli/coverage.hpp): configured and built into <cache>/<key>/, stamped with
// a hash of everything it is made of, a lock file serialising concurrent builds of one key.
struct ProjectBuild {
  std::string key;                           // cache subdirectory
  std::string project;                       // the CMake project, relative to the source tree ("sim/light_core")
  std::vector<std::string> harness_sources;  // the sim/ .cpp files it compiles (hashed into the stamp)
  std::vector<std::string> defines;          // -D... for the configure step (after the source/generated dirs)
  std::string target;                        // the executable target (and file name in <cache>/<key>/)
  std::string stamp = "stamp", log = "build.log";  // per target
  std::string noun = "core";                 // "building its <noun> into ..."
  std::string first_use;                     // why a first build starts
  std::string what;                          // the progress line while it builds
  std::function<void(const std::filesystem::path& dir)> prepare;  // generated files, before configuring
};
CoreBuild ensure_build(const ProjectBuild& pb, bool quiet);

struct RtlRunOptions {
  double in_stall = 0.0, out_stall = 0.0;
  uint64_t seed = 1;
  bool quiet = false;
};

struct RtlRunResult {
  std::vector<Colour> colours;  // one per fragment command, in order
  uint64_t mismatches = 0;      // outputs that differ from LightCore::eval (checked inside the simulator)
  uint64_t cycles = 0;
  double sim_seconds = 0.0;     // wall time of the simulation itself (not the build)
  CoreBuild build;
  bool ok = false;              // every output matched, nothing lost, latency and protocol held
  std::string summary;          // the simulator's one-line summary
};

// Run the command stream (register writes and fragments) through the Verilated core of `fs`.
RtlRunResult run_core_rtl(const FeatureSet& fs, const std::vector<sim::CoreCommand>& cmds, const RtlRunOptions& o);

}  // namespace shadecore::cli

namespace shadecore::cli {

// `shadecore cosim --core lighting`: build (or reuse) the core of `features` for the chosen harness and
// co-simulate it in the simulator's random or directed mode. Returns the exit status (0 pass, 2 FAIL); throws for errors.
struct LightCosimArgs {
  std::string features = "full";  // a named set of config/configs.json or a JSON file
  std::string mode = "random";     // random | directed
  std::string harness = "systemc"; // systemc | bare (parse_harness)
  uint64_t count = 100000;
  uint64_t first = 0;              // random: global index of the first fragment (a shard of a longer run)
  double write_rate = -1.0;        // random: register-write bursts per fragment (< 0: the simulator's default)
  int64_t reset_at = -2;           // global fragment index of the mid-stream reset; -1 none; -2 the simulator's default
  uint64_t seed = 0;               // 0 = pick one (printed)
  double in_stall = 0.0, out_stall = 0.0;
  std::string json_path;
  std::string coverage_dir;        // --coverage DIR: the set's coverage build; DIR/coverage.dat, summary.json, html
  bool coverage_report = true;     // false (regress shards): DIR/coverage.dat only, the merge makes the report
  // --trace FILE: an FST waveform from the set's trace build (<key>-trace). By default only for a FAILED run:
  // the run goes on the speed (or coverage) build as without --trace and, if it fails, is run again — same
  // options, so the same stimulus, timing and first failure — on the trace build, dumping the trace_window
  // cycles before the first failure to trace_window cycles after it. trace_all: the whole run, on the trace
  // build, pass or fail.
  std::string trace_path;
  uint64_t trace_window = 200;
  bool trace_all = false;
  std::string inject;      // self-test: the simulator corrupts one observed output (value | drop | dup)
  uint64_t inject_at = 0;  // which output transfer (0: the simulator's default)
  bool quiet = false;
};
int lighting_cosim(const LightCosimArgs& a);

}  // namespace shadecore::cli
