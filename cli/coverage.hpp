// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — code and functional coverage of the RTL (docs/coverage.md).
//
//   * the coverage builds: every Verilated model again with --coverage-line --coverage-toggle, built on demand
//     and cached apart from the speed builds (the unit: sim/unit_core per variant × width × cut-off × ENERGY;
//     the lighting core: sim/light_core -DSHADECORE_COVERAGE=ON per feature set, cli/light_rtl.hpp);
//   * a run's database (Verilator's coverage.dat), merged over shards and runs by `verilator_coverage -write`;
//   * the summary: per RTL module, line, branch and toggle points hit / total, less the reviewed waivers
//     (config/coverage_waivers.json); the functional bins the harnesses insert (page v_func/...) likewise;
//   * the HTML report: `verilator_coverage -write-info` + lcov's `genhtml`.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "light_rtl.hpp"

namespace shadecore::cli::coverage {

// One point of a coverage database.
struct Point {
  std::string key;      // Verilator's key, as in the file (the identity merges sum by)
  std::string kind;     // line | branch | toggle | functional (page v_line, v_branch, v_toggle, v_func)
  std::string module;   // the RTL module (the page's, less Verilator's parameterisation suffix) or the functional group
  std::string variant;  // the parameterisation suffix: canonical "{FRAC=16,GUARD=5,...}" (see canonicalise), or Verilator's
                        // own ("F10_G5_T20", "pi3": build-specific) in a database not canonicalised
  // The point's parameterisation, NAME -> VALUE (sorted by name), when the page is canonical; `params_known` false
  // for Verilator's own names (they do not say all the values, and __piN means another thing in every build).
  std::vector<std::pair<std::string, std::string>> params;
  bool params_known = false;
  std::string file;     // source file as Verilator saw it ("" for functional bins)
  int line = 0;
  std::string comment;  // line/branch: block, if, else, case...; toggle: the signal bit; functional: the bin
  std::string hier;     // hierarchy below the harness's top (instances of one parameterisation share a point: "x.u*")
  std::string id;       // the point's identity for the summary: the key without the harness's top
  uint64_t count = 0;
};

// Reads a coverage.dat ("# SystemC::Coverage-3"). Throws std::runtime_error (one line) if it is not one.
std::vector<Point> read_dat(const std::string& path);

// The parameterisation map of one coverage build (docs/coverage.md "Parameterisations"): every Verilated module name
// of the build (sc_mul_pool__pi1, sc_cs16__F10_G5_T20, the top's plain name) -> its RTL module, its parameters' values
// (canonical text: a number of at most 64 bits in decimal, signed where Verilator says so; anything else Verilator's
// text, %-escaped) and the instance names it has. Made from `verilator --xml-only` of the build's own top, sources
// and flags (<build>/verilated_params.xml, written by the CMake projects sim/unit_core and sim/light_core), kept
// beside it as <build>/params.json.
struct ParamsMap {
  struct Module {
    std::string module;                                        // origName
    std::vector<std::pair<std::string, std::string>> params;   // sorted by name
    std::set<std::string> instances;                           // cell names that instantiate it (the top: its own)
  };
  std::string source;                       // the XML or params.json it was read from
  std::map<std::string, Module> modules;    // by Verilated name
};
// From a build directory (its params.json, (re)made from verilated_params.xml when older), an XML file or a
// params.json. Throws std::runtime_error (one line) when there is none or it cannot be read.
ParamsMap load_params_map(const std::string& build_dir_or_file);
// "<module>__{NAME=VALUE,...}" ("<module>__{}" without parameters): the page name of a parameterisation.
std::string canonical_name(const std::string& module, const std::vector<std::pair<std::string, std::string>>& params);
// Rewrites a database (in place when out == in; atomically) so every code point's page names its module canonically:
// page v_line/sc_mul_pool__pi1 -> v_line/sc_mul_pool__{AMX=22,AW=370546198,...,SH=1,...}. Pages already canonical and
// the functional pages (v_func/...) are kept. A module the map does not have, or a point whose instance the map
// places in another module, is an error (the database is not of this build). Returns the pages renamed.
size_t canonicalise(const std::string& in, const ParamsMap& map, const std::string& out);
// canonicalise(dat, load_params_map(build_dir), dat) when the database holds a page that is not canonical (so a
// database canonicalised already needs no map); the coverage runs call it on each database their build wrote.
void canonicalise_from_build(const std::string& dat, const std::string& build_dir);

// Merges databases into `out` (verilator_coverage -write; written beside it and renamed).
void merge(const std::vector<std::string>& inputs, const std::string& out);

// The reviewed waivers of unreachable points (config/coverage_waivers.json, docs/coverage.md).
struct Waiver {
  // module: a glob on the RTL module; file: a glob on the source file's name; function: a glob on the Verilog
  // function the point is in (constant functions run at elaboration only); signal: a glob on the toggle bit or
  // functional bin; source: a substring of the point's source line; comment, hier as the points have them.
  std::string id, module, kind, file, function, signal, source, comment, hier, reason, property;
  // params: {"SH": 1, ...} — only the parameterisations whose parameters have these values (canonical text: an
  // integer as its decimal, a string as given); empty: every parameterisation.
  std::vector<std::pair<std::string, std::string>> params;
};
std::vector<Waiver> read_waivers(const std::string& path);  // throws std::invalid_argument on a malformed file
std::string default_waivers();                              // <source tree>/config/coverage_waivers.json
std::string waivers_in_use();  // the default file, or "" (no waivers) where this tree has none

// --coverage DIR / --out DIR of a coverage report: a directory or a path one can be made at (checked before a run).
void check_output_dir(const std::string& dir, const std::string& option);

// The summary of a database with waivers: {"modules": [{module, line, branch, toggle, functional: {hit,
// total, waived, percent}}], "totals", "waivers": {file, applied, not_applicable}, "holes": {module: [...]}},
// and the waiver errors (a waiver that matches nothing in a module the database has; a waived point that
// was hit) in `errors`.
nlohmann::ordered_json summarise(const std::vector<Point>& points, const std::vector<Waiver>& waivers,
                                 const std::string& waivers_file, std::vector<std::string>& errors);
// The per-module table of a summary, one line per module (what the commands print).
std::string table(const nlohmann::ordered_json& summary);

// HTML of a database into `dir` (replaced as a whole): verilator_coverage -write-info, genhtml.
void write_html(const std::string& dat, const std::string& dir);

// The coverage build of one unit model (sim/unit_core), its SystemC testbench or (bare) its bare harness.
struct UnitModel {
  std::string variant = "cs16", config = "default", cutoff = "theta_cr";
  bool norm = false;
};
CoreBuild ensure_unit(const UnitModel& m, bool bare, bool quiet);

// What a coverage run leaves in DIR: coverage.dat (merged), summary.json (unless !summary_file) and html/ (with
// html). Merges `dats`, summarises with the waivers of `waivers` ("" none) and prints the table unless quiet.
// Throws on waiver errors (then nothing is written).
nlohmann::ordered_json report(const std::vector<std::string>& dats, const std::string& dir, const std::string& waivers,
                              bool html, bool quiet, bool summary_file = true);

}  // namespace shadecore::cli::coverage
