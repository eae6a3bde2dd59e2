// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — each subcommand registers itself on the app from its own file (cmd_*.cpp).
#pragma once

#include <CLI/CLI.hpp>

namespace shadecore::cli {

void add_sweep(CLI::App& app);
void add_fit(CLI::App& app);
void add_energy(CLI::App& app);
void add_cosim(CLI::App& app);
void add_eval(CLI::App& app);      // cmd_eval.cpp: one input through the C model, every intermediate
void add_vectors(CLI::App& app);   // cmd_vectors.cpp: hex test vectors from the C model
void add_handoff(CLI::App& app);   // cmd_handoff.cpp: self-contained RTL bundle
void add_light_sweep(CLI::App& app);  // cmd_light.cpp: lighting core error against the exact reference
void add_render(CLI::App& app);
void add_gl_compare(CLI::App& app);  // cmd_gl_compare.cpp: the exact image against Mesa's fixed-function GL (docs/gl_compare.md)
void add_replay(CLI::App& app);    // cmd_replay.cpp: an apitrace capture's frame through the GL front end and the core (docs/replay.md)
void add_regress(CLI::App& app);   // cmd_regress.cpp: plans, shards, local / Slurm backends, merge (docs/regress.md)    // cmd_render.cpp: a scene through the lighting core (docs/scenes.md)
void add_coverage(CLI::App& app);  // cmd_coverage.cpp: merge and summarise coverage databases with waivers (docs/coverage.md)
// Further subcommands (cosim, fit, ...) add a line here and in main.cpp.

}  // namespace shadecore::cli
