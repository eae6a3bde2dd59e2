// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — a self-contained, simulator-independent RTL bundle for an implementation team
// (issue 11). One configuration of rtl/sc_specular.v with every parameter fixed in a wrapper top:
//
//   DIR/rtl/            the RTL files this configuration needs + the wrapper <top>.v; filelist.f
//   DIR/constraints.sdc clock (period from the measured Fmax, editable) and I/O delay assumptions
//   DIR/interface.md    ports (config/interface.json, the README port table's source), formats,
//                       handshake, reset, latency, programming sequence, error contract
//   DIR/vectors/        hard cases + random vectors from the C model (shadecore vectors format)
//   DIR/tb/             plain Verilog-2005 self-checking testbench (template handoff/tb/) + its config
//   DIR/run_icarus.sh, DIR/run_verilator.sh   exit 0 only on PASS
//   DIR/reports/        Verilator lint, Yosys generic synthesis, iCE40 (where installed), both sim runs
//   DIR/MANIFEST.sha256 every file (sha256sum -c MANIFEST.sha256)
//   DIR.tar.gz          the directory as a tarball
//
// Everything is built in a hidden staging directory beside DIR; both simulators run on it; only then
// is it moved into place (a failed or interrupted run leaves nothing). A non-empty DIR needs --force.
// The lighting core's bundle has the same layout (--core lighting, cli/handoff_light.cpp).
//
// This file is the command: its options and which core's bundle to make. The parts, by job:
//   cli/handoff_specular.cpp  the specular unit's bundle (wrapper, testbench configuration, vectors, interface.md)
//   cli/handoff_light.cpp     the lighting core's bundle
//   cli/handoff_files.cpp     the files both have (rtl/, tb/, run scripts, constraints.sdc, README.md, summary)
//   cli/handoff_reports.cpp   lint, synthesis, iCE40 and simulation reports
//   cli/handoff_bundle.cpp    the transaction (staging, manifest, tarball, commit) and the child processes
//   cli/handoff_util.cpp      small helpers (files, tools, text, SHA-256, option checks)
//   cli/templates/handoff/    the text of interface.md, README.md, reports/summary.md, constraints.sdc
#include <memory>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "handoff_bundle.hpp"
#include "output.hpp"
#include "unit_spec.hpp"

namespace shadecore::cli {
namespace {
using namespace handoff;

struct HandoffArgs {
  std::shared_ptr<UnitOptions> unit = std::make_shared<UnitOptions>();
  Options light;  // --out, --force, --tagw, ... (shared by both cores)
  bool print_port_table = false;
  std::string core = "specular";
  CLI::App* sub = nullptr;
};

void run(HandoffArgs& ha) {
  Options& a = ha.light;
  if (ha.print_port_table) {
    if (a.axi && ha.core != "lighting") throw std::invalid_argument("--axi applies to --core lighting only");
    fmt::print("{}", ha.core == "lighting" ? light_port_table(a.axi) : specular_port_table());
    return;
  }
  // ---- validate everything before doing anything
  a.top_given = ha.sub->count("--top") > 0;
  a.count_given = ha.sub->count("--count") > 0;
  if (a.no_sim && a.signoff != "off")
    throw std::invalid_argument("--no-sim needs --signoff off (a sign-off simulates the netlist of a bundle whose own "
                                "benches must pass first)");
  if (ha.core == "lighting") {
    // The feature set fixes the unit and the widths: the unit options do not apply.
    for (const char* opt : {"--variant", "--config", "--frac", "--guard", "--cutoff", "--norm", "--coef"})
      if (ha.sub->count(opt) > 0)
        throw std::invalid_argument(std::string(opt) + " does not apply to --core lighting (the feature set fixes the "
                                    "specular unit and the widths)");
    if (ha.sub->count("--mreg") > 0) {
      if (ha.unit->mreg < 0) throw std::invalid_argument(fmt::format("--mreg {} out of range (0 or 1)", ha.unit->mreg));
      a.mreg = ha.unit->mreg;
    }
    run_lighting(a);
    return;
  }
  if (ha.core != "specular") throw std::invalid_argument("unknown --core '" + ha.core + "' (known: specular, lighting)");
  if (!a.features.empty()) throw std::invalid_argument("--features applies to --core lighting only");
  if (a.axi) throw std::invalid_argument("--axi applies to --core lighting only (the AXI wrapper is the lighting core's)");
  run_specular(a, resolve_unit(*ha.unit));
}

}  // namespace

void add_handoff(CLI::App& app) {
  auto a = std::make_shared<HandoffArgs>();
  auto* sub = app.add_subcommand("handoff", "Write a self-contained RTL bundle (RTL, constraints, interface, vectors, "
                                            "testbench, run scripts, reports, manifest) and a tarball of it");
  a->sub = sub;
  add_unit_options(sub, a->unit);
  Options& l = a->light;
  sub->add_option("--out", l.out, "Bundle directory (refused if not empty, unless --force); DIR.tar.gz beside it")->check(cliargs::NonEmpty("path"));
  sub->add_flag("--force", l.force, "Replace the contents of a non-empty --out and an existing DIR.tar.gz");
  sub->add_option("--tagw", l.tagw, "Tag width TAGW of the wrapper top (1..32, default 8)");
  sub->add_option("--seed", l.seed, "Seed of the random vectors and of the testbench's gaps/backpressure (default: picked)");
  sub->add_option("--count", l.count, "Random vectors (default 2000; lighting: random fragments, default 1000)");
  sub->add_option("--top", l.top, "Module name of the wrapper top (default shadecore_top; lighting: shadecore_light_top)")->check(cliargs::NonEmpty("module name"));
  sub->add_flag("--no-ice40", l.no_ice40, "Skip iCE40 place and route even where nextpnr-ice40/icetime are installed");
  sub->add_flag("--no-sim", l.no_sim,
                "Write the bundle without running its Icarus and Verilator benches (its summary says so; needs "
                "--signoff off): the bundle's files for a script that compares them (scripts/timing_report.py)");
  sub->add_flag("--axi", l.axi,
                "--core lighting: the core behind its AXI wrapper rtl/sc_light_axi.v (AXI4-Lite registers, AXI4-Stream "
                "fragments and colours; docs/handoff.md \"The AXI view\"), with the testbench driving it through AXI");
  sub->add_option("--synth", l.synth,
                  "Yosys generic synthesis: flat | hier (hierarchical, no flatten) | skip | auto (default: flat for "
                  "the specular unit; for the lighting core by size, docs/handoff.md)")->check(cliargs::NonEmpty("synthesis mode"));
  sub->add_option("--signoff", l.signoff,
                  "OSU 0.18 um sign-off of the bundle (signoff/signoff.py: cell mapping, OpenSTA timing, gate-level "
                  "simulation, energy per result; docs/signoff.md): auto (default: run when yosys, sta, iverilog and "
                  "qflow-tech-osu018 are installed) | on (required) | off")
      ->check(CLI::IsMember({"auto", "on", "off"}));
  sub->add_option("--clock-target", l.clock_target, "Target clock period of the sign-off in ns (default 4.0)")
      ->check(CLI::Range(0.5, 1000.0));
  sub->add_option("--mreg", a->unit->mreg,
                  "The pipelining parameter MREG (cs16, schlick_div, schlick_nr, cs16_faithful, cs16_compact: "
                  "config/configs.json variants[].mreg_stages): 1 puts a register inside each product (cs16 latency "
                  "7 -> 12, schlick_div 20 -> 21, schlick_nr 10 -> 16, the cs16 forms 5 -> 11; the same outputs; "
                  "docs/signoff.md), default 0; with --core lighting it replaces the feature set's key mreg (every "
                  "share: the normalisers' products registered, 10 -> 18 cycles each, and the units' MREG)");
  sub->add_option("--core", a->core, "Which core: specular (default) or lighting")->check(cliargs::NonEmpty("core"));
  sub->add_option("--features", l.features, "Lighting core feature set: a name of config/configs.json \"feature_sets\" "
                                            "or a JSON file (with --core lighting)")->check(cliargs::NonEmpty("feature set"));
  sub->add_flag("--print-port-table", a->print_port_table,
                "Print the port table of sc_specular (with --core lighting: sc_light) from config/interface.json and exit");
  sub->callback([a] { run(*a); });
}

}  // namespace shadecore::cli
