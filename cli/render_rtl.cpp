// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — the back end's RTL step (render_rtl.hpp), moved from cmd_render.cpp for `replay`.
#include "render_rtl.hpp"

#include <stdexcept>

#include <fmt/core.h>

#include "light_rtl.hpp"

namespace shadecore::cli {

using json = nlohmann::ordered_json;

// Every fragment of every core through the Verilated RTL.
std::vector<std::vector<Colour>> run_rtl(const render::Frame& fr, RtlTotals& tot) {
  std::vector<std::vector<Colour>> out;
  for (size_t g = 0; g < fr.groups.size(); ++g) {
    const auto& grp = fr.groups[g];
    std::vector<sim::CoreCommand> cmds;
    cmds.reserve(grp.cmds.size());
    for (const auto& c : grp.cmds) {
      sim::CoreCommand k;
      k.is_write = c.is_write;
      k.w = c.w;
      k.f = c.f;
      cmds.push_back(k);
    }
    RtlRunOptions o;
    o.quiet = false;
    // run_core_rtl reports the build (when the core is new) and the simulation on stderr itself.
    RtlRunResult r = run_core_rtl(grp.fs, cmds, o);
    if (r.colours.size() != grp.dests.size())
      throw std::runtime_error(fmt::format("RTL core {} returned {} colours for {} fragments ({})", grp.fs.key(),
                                           r.colours.size(), grp.dests.size(), r.summary));
    tot.sim_seconds += r.sim_seconds;
    tot.build_seconds += r.build.build_seconds;
    tot.cycles += r.cycles;
    tot.core_mismatches += r.mismatches;
    tot.ok = tot.ok && r.ok;
    tot.cores.push_back({{"key", grp.fs.key()},
                         {"fragments", grp.dests.size()},
                         {"register_writes", grp.writes},
                         {"cycles", r.cycles},
                         {"sim_seconds", r.sim_seconds},
                         {"core_mismatches", r.mismatches},
                         {"ok", r.ok},
                         {"built_now", r.build.built_now},
                         {"build_seconds", r.build.build_seconds},
                         {"simulator", r.build.exe},
                         {"summary", r.summary}});
    out.push_back(std::move(r.colours));
  }
  return out;
}

}  // namespace shadecore::cli
