// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — the back end's RTL step, shared by `render` and `replay`: every core group's command stream of a
// prepared frame through its Verilated lighting core (built on demand, cli/light_rtl.hpp), one colour per fragment.
#pragma once

#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "shadecore/render/render.hpp"

namespace shadecore::cli {

struct RtlTotals {
  double sim_seconds = 0, build_seconds = 0;
  uint64_t cycles = 0, core_mismatches = 0;
  bool ok = true;
  nlohmann::ordered_json cores = nlohmann::ordered_json::array();  // per core: key, fragments, writes, cycles, …
};

// Every fragment of every core through the Verilated RTL (progress and builds reported on stderr).
std::vector<std::vector<Colour>> run_rtl(const render::Frame& fr, RtlTotals& tot);

}  // namespace shadecore::cli
