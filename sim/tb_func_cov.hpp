// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the functional coverage model in the harnesses (docs/coverage.md "Functional model"): the model
// (stimulus/include/shadecore/stimulus/func_cov.hpp) sampled by the harnesses of the coverage builds and counted into the same Verilator database
// as the code coverage (VL_COVER_INSERT's calls: page v_func/<group>, one point per bin), so it merges over shards
// and runs and ranks with the rest. Every bin is declared when the run starts — a bin never hit is in the database
// as a hole, by name. In a speed build (VM_COVERAGE 0) nothing is declared and the harnesses do not sample
// (kCoverageBuild).
#pragma once

#include "shadecore/stimulus/func_cov.hpp"
#include "tb_coverage.hpp"
#include "tb_monitor_logic.hpp"

namespace shadecore::sim {

// MonitorLogic::edge_sample for a UnitFuncCov / LightFuncCov.
template <class Cov>
void edge_func_sample(void* c, const EdgeState& e) {
  static_cast<Cov*>(c)->sample_edge(e);
}

// LightModel::sample for a LightFuncCov.
inline void light_func_sample(void* c, const LightRegs& r, const Fragment& f, const LightCoreTrace& t) {
  static_cast<LightFuncCov*>(c)->sample(r, f, t);
}

}  // namespace shadecore::sim
