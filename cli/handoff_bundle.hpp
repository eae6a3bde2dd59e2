// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — what every bundle has in common, whichever core it delivers (cli/handoff_specular.cpp:
// the specular unit; cli/handoff_light.cpp: the lighting core; cli/cmd_handoff.cpp: the command, and there
// the list of the parts by job):
//   * the destination rules and the transaction: --out DIR refused when not empty unless --force, the
//     bundle built in a hidden staging directory beside DIR, MANIFEST.sha256, DIR.tar.gz, moved into
//     place only when everything passed; a failure or an interrupt leaves nothing (make_bundle);
//   * child processes in their own process group (an interrupt stops a whole tool tree);
//   * the reports: Verilator lint, Yosys generic synthesis (flat or hierarchical, or skipped with a
//     recorded note), iCE40 where installed, both simulators through the bundle's own run scripts;
//   * constraints.sdc, filelist.f, README.md, reports/summary.md (text: cli/templates/handoff/), the run
//     scripts (templates handoff/), rtl/ and tb/.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "shadecore/variants.hpp"

namespace shadecore {
struct FeatureSet;
}
namespace shadecore::cli {
struct UnitSpec;
}

namespace shadecore::cli::handoff {

namespace fs = std::filesystem;

// ---- small helpers
std::string root_dir();  // $SHADECORE_ROOT or the source tree the CLI was built from
std::string read_text(const fs::path& p);
void write_text(const fs::path& p, const std::string& s, bool exec = false);
bool on_path(const std::string& tool);
std::string first_line(const std::string& s);
std::string last_line_with(const std::string& out, const std::string& needle);
std::string sha256_hex(const std::string& data);
std::string shell_join(const std::vector<std::string>& argv);

// ---- child processes (stdout and stderr interleaved; an interrupt throws Interrupted)
struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct Proc {
  int status = -1;
  std::string out;
};
// The CLI's subprocess runner for the handoff bundles and the lighting core's build and simulations
// (cli/light_rtl.cpp): fork + execvp of argv (no shell), in cwd, its output collected in Proc::out.
struct ProcOptions {
  // Called with each complete output line (with its '\n'; a last unterminated line at the end) as it
  // arrives, for output that should be shown while the child runs.
  std::function<void(const std::string&)> on_line;
  // true: the child leads its own process group (the handoff's interrupt handler stops the whole tool
  // tree); false: it stays in the CLI's group, so a terminal's ^C reaches it and its children directly.
  bool own_group = true;
};
Proc run_proc(const std::vector<std::string>& argv, const fs::path& cwd, const ProcOptions& opt = {});

// ---- ports of a wrapper top
struct Port {
  std::string name, dir;
  int width;
  std::string meaning;
};
struct Widths {
  int frac, tagw, coefw;
};
// A symbolic width of config/interface.json ("F+1", "F+2", "F+8", "TAGW", "COEFW", "AXIS_IN", "AXIS_OUT", a number).
int eval_width(const std::string& expr, const Widths& w);
// A port list of config/interface.json ("ports": sc_specular, "light_ports": sc_light), read at run time.
nlohmann::json interface_ports(const std::string& key);
std::string concrete_port_table(const std::vector<Port>& ports);

// ---- what every bundle records about itself
enum class SynthMode { Flat, Hierarchical, Skipped };
struct BundleBase {
  std::string top;             // wrapper module
  std::string desc;            // one line: the configuration
  std::string tb;              // testbench module (tb/<tb>.v)
  uint64_t seed = 0;
  std::vector<Port> ports;
  std::vector<std::string> rtl_files;  // relative to the bundle
  int latency = 0, latency_min = 0;
  int latency_slack = 0;  // lighting: LightCore::latency_max() − latency() (a shared unit's gap under backpressure)
  SynthMode synth = SynthMode::Flat;
  std::string synth_why;       // why this synthesis mode (recorded in the report)
  std::string comb_paths;      // the combinational input → output paths (constraints.sdc, interface.md)
  std::string ice40_skip_why;  // non-empty: iCE40 place and route not run, for this reason
  long ice40_max_cells = 0;    // > 0: iCE40 not run when the flat generic synthesis has more cells
  // measured
  std::string lint_status, synth_cells = "—", synth_ffs = "—", synth_depth = "—", ice40_status, icarus_line,
      verilator_line;
  double fmax_mhz = 0.0;
  std::string fmax_source;
  // OSU 0.18 um sign-off (signoff/signoff.py, docs/signoff.md): mode auto | on | off, the target period (ns)
  std::string signoff_mode = "auto";
  double signoff_target = 4.0;
  // ABC's script (signoff.py --abc): full for the units unless config/configs.json variants[].signoff_abc says lean
  // (schlick_nr); lean for the lighting cores (no SAT sweeping: the full script does not finish on their multiplier
  // trees in hours; docs/signoff.md), keep for a lighting core with MREG = 1 (no AIG rewriting either)
  std::string signoff_abc = "full";
  std::string signoff_status = "not run";
  bool no_sim = false;  // --no-sim: run_icarus.sh / run_verilator.sh not run at generation time
};

// The command's options shared by both cores (cli/cmd_handoff.cpp registers them).
struct Options {
  std::string features;      // lighting: a named feature set or a JSON file
  int mreg = -1;             // lighting: --mreg (the feature set's key mreg replaced); -1 = the set's own
  std::string out;
  bool force = false;
  int tagw = 8;
  uint64_t seed = 0;         // 0: picked
  uint64_t count = 2000;     // random vectors (fragments for the lighting core)
  std::string top = "shadecore_top";
  bool no_ice40 = false;
  bool no_sim = false;       // --no-sim: the bundle's benches not run (with --signoff off only)
  bool axi = false;          // lighting: --axi, the core behind its AXI wrapper rtl/sc_light_axi.v
  std::string synth = "auto";
  std::string signoff = "auto";  // OSU 0.18 um timing, gate-level simulation and power: auto | on | off
  double clock_target = 4.0;     // its target period, ns
  bool top_given = false, count_given = false;
};
// The specular unit's bundle for the resolved unit options (cli/handoff_specular.cpp).
void run_specular(const Options& o, const UnitSpec& spec);
// The port table of sc_specular from config/interface.json "ports" (symbolic widths; the README's).
std::string specular_port_table();
// The lighting-core bundle (cli/handoff_light.cpp).
void run_lighting(const Options& o);
// A lighting-core vector file (format in its header; docs/handoff.md): mode "hard" (the directed hard
// cases of the co-simulation) or "random" (`count` fragments from `seed`). Also `shadecore vectors
// --core lighting`.
std::string lighting_vectors(const FeatureSet& fset, const std::string& mode, uint64_t count, uint64_t seed,
                             size_t* records = nullptr, size_t* fragments = nullptr);
// The port table of sc_light from config/interface.json "light_ports" (symbolic widths).
std::string light_port_table(bool axi = false);  // axi: rtl/sc_light_axi.v's ("light_axi_ports")

SynthMode parse_synth(const std::string& text, SynthMode auto_mode);
void check_top_name(const std::string& top, const std::string& tb);  // a Verilog identifier, no clash
uint64_t checked_seed(uint64_t seed);                                 // picks one for 0; 1..2^31-1

std::string filelist(const BundleBase& b);
std::string synth_summary(const BundleBase& b);
std::string sdc(const BundleBase& b);
std::string bundle_readme(const BundleBase& b);
std::string summary_md(const BundleBase& b);
void report_lint(BundleBase& b, const fs::path& dir);
void report_yosys(BundleBase& b, const fs::path& dir);
void report_ice40(BundleBase& b, const fs::path& dir, bool skip);
// Runs one of the bundle's simulator scripts; returns its last line (PASS ...); throws unless PASS.
std::string run_sim(const fs::path& dir, const std::string& script, const std::string& log);
// run_icarus.sh / run_verilator.sh from the templates in handoff/, for testbench module b.tb.
void write_run_scripts(const BundleBase& b, const fs::path& dir);
// Throws unless each file (relative to root_dir()) exists.
void require_sources(const std::vector<std::string>& files);
// rtl/: `files` and `includes` copied from the source tree's rtl/, the wrapper top rtl/<b.top>.v; records
// them in b.rtl_files (the files, then the wrapper) and writes filelist.f.
void write_rtl(BundleBase& b, const fs::path& dir, const std::vector<std::string>& files,
               const std::vector<std::string>& includes, const std::string& wrapper);
// tb/: the testbench tb/<b.tb>.v and tb_common.vh from handoff/tb/, its tb_config.vh and tb_dut.vh; LICENSE;
// the run scripts.
void write_testbench(const BundleBase& b, const fs::path& dir, const std::string& tb_config, const std::string& tb_dut);
// Lint, Yosys, iCE40 (reports/), each with a step line; throws when lint or Yosys fails.
void check_and_report(BundleBase& b, const fs::path& dir, bool no_ice40, const std::function<void(const std::string&)>& step);
// Both run scripts on the bundle as delivered (throws unless both PASS), then reports/summary.md, README.md.
void simulate_and_summarise(BundleBase& b, const fs::path& dir, const std::function<void(const std::string&)>& step);
// Throws unless every tool the bundle's checks need is on PATH.
void require_tools();

// ---- the transaction
// Prints "handoff: [  t s] what" (elapsed time since the bundle was started).
using Step = std::function<void(const std::string&)>;
// Validates --out (a non-empty directory or an existing tarball need `force`), then calls
// fill(dir, step) on an empty directory inside a staging directory beside DIR, writes
// MANIFEST.sha256 and the tarball and moves both into place. Any exception (or SIGINT/SIGTERM/SIGHUP)
// leaves nothing behind: no directory, no tarball, no staging directory, no parent directory it created.
void make_bundle(const std::string& out, bool force, const std::function<void(const fs::path&, const Step&)>& fill);

}  // namespace shadecore::cli::handoff
