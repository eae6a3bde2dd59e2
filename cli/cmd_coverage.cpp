// SPDX-License-Identifier: Apache-2.0
// shadecore coverage — merge coverage databases and summarise them with the reviewed waivers (docs/coverage.md):
//
//   shadecore coverage DAT... --out DIR [--waivers FILE | --no-waivers] [--no-html] [--params-map BUILD]
//
// DIR gets coverage.dat (the merge, verilator_coverage -write), summary.json (per module: line, branch, toggle
// and functional points hit / total / waived, the holes by name, the waivers applied) and html/ (genhtml). The
// same report `cosim --coverage` and `regress --coverage` write. A waiver that matches nothing in a module the
// databases hold, or a waived point that was hit, is an error (exit 1, nothing written).
#include <unistd.h>

#include <filesystem>

#include <fmt/core.h>

#include "commands.hpp"
#include "coverage.hpp"
#include "shadecore/common/args.hpp"

namespace shadecore::cli {

void add_coverage(CLI::App& app) {
  struct Args {
    std::vector<std::string> dats;
    std::string out, waivers, params_map;
    bool no_waivers = false, no_html = false;
  };
  auto a = std::make_shared<Args>();
  using namespace cliargs;
  auto* sub = app.add_subcommand("coverage", "merge Verilator coverage databases and summarise them per RTL module with the "
                                             "reviewed waivers (docs/coverage.md)");
  sub->add_option("databases", a->dats, "coverage.dat files (cosim --coverage, regress --coverage)")->required()
      ->check(CLI::ExistingFile);
  sub->add_option("--out", a->out, "directory: coverage.dat, summary.json, html/")->required()->check(NonEmpty("path"));
  auto* w = sub->add_option("--waivers", a->waivers, "waiver file (default config/coverage_waivers.json)")->check(NonEmpty("path"));
  sub->add_flag("--no-waivers", a->no_waivers, "summarise without waivers")->excludes(w);
  sub->add_flag("--no-html", a->no_html, "no HTML report");
  sub->add_option("--params-map", a->params_map,
                  "give the databases' points their parameterisations from this coverage build (its directory, its "
                  "verilated_params.xml or params.json) before merging: for databases its simulators wrote by hand "
                  "(cosim and regress --coverage do it themselves)")
      ->check(CLI::ExistingPath);
  sub->callback([a, w] {
    coverage::check_output_dir(a->out, "--out");
    const std::string wf = a->no_waivers ? "" : (w->count() ? a->waivers : coverage::waivers_in_use());
    std::vector<std::string> dats = a->dats;
    std::string tmp;
    struct Cleanup {
      std::string& d;
      ~Cleanup() {
        std::error_code ec;
        if (!d.empty()) std::filesystem::remove_all(d, ec);
      }
    } cleanup{tmp};
    if (!a->params_map.empty()) {
      // canonical copies beside --out (the inputs are left as they are), removed at the end
      const coverage::ParamsMap map = coverage::load_params_map(a->params_map);
      const auto out_abs = std::filesystem::absolute(a->out).lexically_normal();
      tmp = out_abs.string() + fmt::format(".params.{}", ::getpid());
      std::filesystem::create_directories(tmp);
      for (size_t i = 0; i < dats.size(); ++i) {
        const std::string c = fmt::format("{}/{}.dat", tmp, i);
        if (coverage::canonicalise(dats[i], map, c) == 0) std::filesystem::copy_file(dats[i], c);
        dats[i] = c;
      }
    }
    coverage::report(dats, a->out, wf, !a->no_html, /*quiet=*/false);
    fmt::print("coverage: wrote {0}/coverage.dat, {0}/summary.json{1}\n", a->out, a->no_html ? "" : fmt::format(", {}/html/index.html", a->out));
  });
}

}  // namespace shadecore::cli
