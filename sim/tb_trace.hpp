// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the FST waveform of a lighting-core run (issue 36). A harness built with Verilator's
// --trace-fst (the trace build of a feature set: sim/light_core with -DSHADECORE_TRACE=ON, cached apart from
// the speed build as <key>-trace; VM_TRACE_FST=1) writes one with `--trace FILE`; the speed builds refuse the
// option, as they refuse --coverage (tb_coverage.hpp). `--trace-from C` / `--trace-to C` cut the waveform to
// the monitor cycles C..C' (the window `shadecore cosim --core lighting --trace` asks for around the first
// failure when it re-runs a failed run on the trace build); without them the whole run is written.
// Time in the file: the rising edge of monitor cycle k is at (k - 1) * 10 ns in both harnesses (the SystemC
// testbench's sc_clock of 10 ns; the bare harness dumps at the same times).
// The file is an output like any other (output_files.hpp): checked before the run, written beside its
// target and renamed at the end — also when the run FAILS (it is the evidence), never after an error.
#pragma once

#include <verilated.h>

#include <cstdint>
#include <string>

#include "tb_harness_build.hpp"

namespace shadecore::sim {

#if defined(VM_TRACE_FST) && VM_TRACE_FST
inline constexpr bool kTraceBuild = true;
#else
inline constexpr bool kTraceBuild = false;
#endif

// The error of --trace given to this simulator ("" when it applies: a trace build, or no --trace).
inline std::string trace_option_error(const std::string& path) { return trace_option_error(path, kTraceBuild); }

}  // namespace shadecore::sim
