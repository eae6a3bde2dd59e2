// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the coverage database of a run (docs/coverage.md). A simulator built with Verilator's
// --coverage-line --coverage-toggle (the coverage builds: sim/unit_core, sim/light_core with
// -DSHADECORE_COVERAGE=ON; VM_COVERAGE=1) writes its counts with `--coverage FILE` at the end of the run;
// the normal (speed) builds refuse the option. The file is written beside its target and renamed, so a
// reader never sees half a database. It must be written while the model is alive: Verilator's database
// holds pointers into the model's counters.
#pragma once

#include <unistd.h>
#include <verilated.h>
#if VM_COVERAGE
#include <verilated_cov.h>
#endif

#include <cstdio>
#include <stdexcept>
#include <string>

#include "tb_harness_build.hpp"

namespace shadecore::sim {

inline constexpr bool kCoverageBuild = VM_COVERAGE != 0;

// The error of --coverage given to this simulator ("" when it applies: a coverage build, or no --coverage).
inline std::string coverage_option_error(const std::string& path) { return coverage_option_error(path, kCoverageBuild); }

inline void write_coverage(VerilatedContext* ctx, const std::string& path) {
  if (path.empty()) return;
#if VM_COVERAGE
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  ctx->coveragep()->write(tmp.c_str());
  if (std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write the coverage database " + path);
  }
#else
  (void)ctx;
  throw std::runtime_error(coverage_option_error(path));
#endif
}

}  // namespace shadecore::sim
