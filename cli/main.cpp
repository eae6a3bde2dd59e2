// SPDX-License-Identifier: Apache-2.0
// shadecore — command-line entry point. Errors are one line on stderr and a non-zero exit.
#include "commands.hpp"
#include "output.hpp"

int main(int argc, char** argv) {
  CLI::App app{"shadecore: fixed-point specular shading core — C model, sweeps and co-simulation"};
  app.require_subcommand(1);
  shadecore::cli::set_command_line(argc, argv);
  shadecore::cli::add_sweep(app);
  shadecore::cli::add_fit(app);
  shadecore::cli::add_energy(app);
  shadecore::cli::add_cosim(app);
  shadecore::cli::add_eval(app);
  shadecore::cli::add_vectors(app);
  shadecore::cli::add_handoff(app);
  shadecore::cli::add_light_sweep(app);
  shadecore::cli::add_render(app);
  shadecore::cli::add_gl_compare(app);
  shadecore::cli::add_replay(app);
  shadecore::cli::add_regress(app);
  shadecore::cli::add_coverage(app);
  // Parse and run: one-line errors, exit statuses 0 / 1 / 2 (docs/cli.md), --version.
  return shadecore::cli::run_app(app, argc, argv);
}
