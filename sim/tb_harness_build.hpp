// SPDX-License-Identifier: Apache-2.0
// shadecore sim — what a harness executable was built with, as values: the coverage build (VM_COVERAGE,
// tb_coverage.hpp) and the trace build (VM_TRACE_FST, tb_trace.hpp). The code every lighting harness shares is
// compiled once, in the main build (sim/tb_light_run.cpp, library shadecore_light_harness), not per feature set,
// so it cannot read the Verilator build's macros: the harness passes them (HarnessBuild) and the option checks
// take them as arguments. Free of Verilator headers.
#pragma once

#include <cstdint>
#include <string>

namespace shadecore::sim {

struct HarnessBuild {
  bool coverage = false;  // Verilated with --coverage-line --coverage-toggle
  bool trace = false;     // Verilated with --trace-fst
};

// The error of --coverage given to a simulator built without it ("" when it applies).
inline std::string coverage_option_error(const std::string& path, bool coverage_build) {
  if (path.empty() || coverage_build) return {};
  return "--coverage: this simulator is the speed build, without coverage points (`shadecore cosim --coverage DIR` "
         "builds and runs the coverage build)";
}

// The error of --trace given to a simulator built without it ("" when it applies).
inline std::string trace_option_error(const std::string& path, bool trace_build) {
  if (path.empty() || trace_build) return {};
  return "--trace: this simulator is the speed build, without waveform support (`shadecore cosim --core lighting "
         "--trace FILE` builds and runs the trace build)";
}

inline constexpr uint64_t kTraceClockNs = 10;  // one clock cycle in the waveform

// Which monitor cycles a run dumps: [from, to] (to = kTraceToEnd: until the end of the run).
struct TraceWindow {
  static constexpr uint64_t kToEnd = ~uint64_t{0};
  std::string file;  // "" = no waveform
  uint64_t from = 0, to = kToEnd;
  [[nodiscard]] bool on() const { return !file.empty(); }
  // Is the dump open at monitor cycle `cycle` (1-based)?
  [[nodiscard]] bool covers(uint64_t cycle) const { return cycle >= from && cycle <= to; }
};

}  // namespace shadecore::sim
