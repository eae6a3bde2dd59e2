// shadecore — command-line entry point. Errors are one line on stderr and a non-zero exit.
#include <cstdio>
#include <exception>
#include <fmt/core.h>

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
  shadecore::cli::add_render(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // One line, like every other error (CLI11's own exit() adds a "Run with --help" line).
    fmt::print(stderr, "shadecore: error: {} (see shadecore --help)\n", e.what());
    return e.get_exit_code() != 0 ? e.get_exit_code() : 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "shadecore: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
