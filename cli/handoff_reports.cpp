// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — the checks and reports of every bundle (cli/handoff_bundle.hpp): Verilator lint,
// Yosys generic synthesis, iCE40 place and route where installed, both simulators through the bundle's
// own run scripts; each report records its command, tool version and date.
#include <unistd.h>

#include <cmath>
#include <regex>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "handoff_bundle.hpp"
#include "output.hpp"

namespace shadecore::cli::handoff {
namespace {
std::string tool_version(const std::vector<std::string>& argv) {
  try {
    return first_line(run_proc(argv, ".").out);
  } catch (const Interrupted&) {
    throw;
  } catch (const std::exception&) {
    return "?";
  }
}

std::string report_header(const std::string& what, const std::string& cmd, const std::string& version) {
  return fmt::format("# {}\n# command (in the bundle directory): {}\n# tool: {}\n# date: {}\n\n", what, cmd, version,
                     utc_now());
}
}  // namespace

// ---------------------------------------------------------------------------- reports
void report_lint(BundleBase& b, const fs::path& dir) {
  const std::vector<std::string> cmd = {"verilator", "--lint-only", "-Wall", "-f", "filelist.f", "--top-module", b.top};
  const Proc r = run_proc(cmd, dir);
  const bool warn = r.out.find("%Warning") != std::string::npos || r.out.find("%Error") != std::string::npos;
  b.lint_status = r.status == 0 && !warn ? "clean (no warnings)" : "FAILED";
  write_text(dir / "reports" / "verilator_lint.log",
             report_header("Verilator lint, all warnings enabled", shell_join(cmd), tool_version({"verilator", "--version"})) +
                 (r.out.empty() ? "(no output: no warnings)\n" : r.out) + fmt::format("# exit status {}\n", r.status));
  if (r.status != 0 || warn)
    throw std::runtime_error("Verilator lint of the bundle is not clean: " + first_line(r.out) + " (reports/verilator_lint.log)");
}

void report_yosys(BundleBase& b, const fs::path& dir) {
  std::string files;
  for (const auto& f : b.rtl_files) files += " " + f;
  const bool flat = b.synth != SynthMode::Hierarchical;  // a skipped synthesis records the flat script
  const std::string script = fmt::format(
      "# Yosys generic synthesis of the bundle (technology independent): cells, flip-flops{what}.\n"
      "read_verilog -defer -Irtl{files}\n"
      "hierarchy -check -top {top}\n"
      "{synth}\n"
      "check -assert\n"
      "dffunmap\n"
      "{stat}",
      fmt::arg("what", flat ? ", logic depth" : " (hierarchical: each distinct module once, totals over the hierarchy)"),
      fmt::arg("files", files), fmt::arg("top", b.top),
      fmt::arg("synth", flat ? "synth -flatten -top " + b.top : "synth -top " + b.top),
      fmt::arg("stat", flat ? "tee -o /dev/stdout stat\ntee -o /dev/stdout ltp -noff\n"
                            : "tee -o /dev/stdout stat -top " + b.top + "\n"));
  write_text(dir / "reports" / "yosys_synth.ys", script);
  const std::vector<std::string> cmd = {"yosys", "-q", "-s", "reports/yosys_synth.ys"};
  if (b.synth == SynthMode::Skipped) {
    b.synth_cells = b.synth_ffs = b.synth_depth = "—";
    write_text(dir / "reports" / "yosys_synth.log",
               fmt::format("# Yosys generic synthesis: skipped: {}\n# to run it: {} (in the bundle directory)\n",
                           b.synth_why, shell_join(cmd)));
    return;
  }
  const Proc r = run_proc(cmd, dir);
  std::string cells = "?", depth = flat ? "?" : "— (hierarchical)";
  long ffs = 0;
  {
    // Hierarchical: only the totals after "design hierarchy" (the per-module lists come before).
    const size_t from = flat ? 0 : std::min(r.out.size(), r.out.rfind("design hierarchy") == std::string::npos
                                                              ? r.out.size() : r.out.rfind("design hierarchy"));
    const std::string text = r.out.substr(from);
    static const std::regex re_cells(R"(Number of cells:\s+(\d+))"), re_ff(R"(\$_S?DFFE?_\w+\s+(\d+))"),
        re_depth(R"(Longest topological path in \S+ \(length=(\d+)\))");
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re_cells); it != std::sregex_iterator(); ++it)
      cells = (*it)[1];
    for (auto it = std::sregex_iterator(text.begin(), text.end(), re_ff); it != std::sregex_iterator(); ++it)
      ffs += std::stol((*it)[1]);
    if (flat)
      for (auto it = std::sregex_iterator(text.begin(), text.end(), re_depth); it != std::sregex_iterator(); ++it)
        depth = (*it)[1];
  }
  b.synth_cells = cells;
  b.synth_ffs = std::to_string(ffs);
  b.synth_depth = depth;
  write_text(dir / "reports" / "yosys_synth.log",
             report_header(flat ? "Yosys generic synthesis (synth -flatten; dffunmap; stat; ltp -noff)"
                                : "Yosys generic synthesis, hierarchical (synth; dffunmap; stat -top): " + b.synth_why,
                           shell_join(cmd), tool_version({"yosys", "-V"})) +
                 fmt::format("# summary: {} cells, {} flip-flops, logic depth {}{}\n\n", cells, ffs, depth,
                             flat ? " (longest path, flip-flops excluded)" : "") +
                 r.out + fmt::format("# exit status {}\n", r.status));
  if (r.status != 0)
    throw std::runtime_error(fmt::format("Yosys synthesis of the bundle failed, exit status {}{}: {}", r.status,
                                         r.status > 128 ? fmt::format(" (signal {})", r.status - 128) : "",
                                         last_line_with(r.out, "ERROR").empty() ? "no ERROR line (killed?)"
                                                                                : last_line_with(r.out, "ERROR")));
}

void report_ice40(BundleBase& b, const fs::path& dir, bool skip) {
  const fs::path log = dir / "reports" / "ice40.log";
  const bool have = on_path("nextpnr-ice40") && on_path("icetime");
  if (b.ice40_max_cells > 0 && b.ice40_skip_why.empty() && !b.synth_cells.empty() &&
      b.synth_cells.find_first_not_of("0123456789") == std::string::npos && std::stol(b.synth_cells) > b.ice40_max_cells)
    b.ice40_skip_why = fmt::format("{} generic cells, far more than an iCE40 HX8K holds (7680 LUT4; limit {} cells)",
                                   b.synth_cells, b.ice40_max_cells);
  if (skip || !have || !b.ice40_skip_why.empty()) {
    b.ice40_status = skip ? "not run (--no-ice40)"
                     : !b.ice40_skip_why.empty() ? "not run: " + b.ice40_skip_why
                                                 : "not run: nextpnr-ice40 / icetime not installed";
    write_text(log, fmt::format("# iCE40 place and route: {}\n# (install: scripts/setup.sh nextpnr-ice40 fpga-icestorm fpga-icestorm-chipdb)\n"
                                "# recorded measurement: {}\n",
                                b.ice40_status, b.fmax_source.empty() ? "none for this configuration" : b.fmax_source));
    return;
  }
  const fs::path tmp = fs::temp_directory_path() / fmt::format("shadecore_ice40_{}", ::getpid());
  fs::create_directories(tmp);
  struct Rm {
    fs::path p;
    ~Rm() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } rm{tmp};
  std::string files;
  for (const auto& f : b.rtl_files) files += " " + f;
  const std::string js = (tmp / "ice40.json").string(), asc = (tmp / "ice40.asc").string();
  const std::vector<std::string> syn = {"yosys", "-q", "-p",
                                        fmt::format("read_verilog -defer -Irtl{}; synth_ice40 -top {} -json {}; tee -o /dev/stdout stat",
                                                    files, b.top, js)};
  std::string text = report_header("iCE40: synth_ice40, nextpnr-ice40 (HX8K ct256), icetime", shell_join(syn),
                                   tool_version({"yosys", "-V"}));
  Proc r = run_proc(syn, dir);
  text += r.out;
  std::smatch m;
  static const std::regex re_lut(R"(SB_LUT4\s+(\d+))");
  long luts = -1;
  for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), re_lut); it != std::sregex_iterator(); ++it)
    luts = std::stol((*it)[1]);
  if (r.status != 0 || luts < 0) {
    b.ice40_status = "synth_ice40 failed";
  } else if (luts > 7680) {
    b.ice40_status = fmt::format("{} LUT4: does not fit an HX8K (7680); no place and route", luts);
  } else {
    const std::vector<std::string> pnr = {"nextpnr-ice40", "--hx8k", "--package", "ct256", "--json", js, "--asc", asc,
                                          "--freq", "40", "--timing-allow-fail", "--pcf-allow-unconstrained", "--seed", "1"};
    r = run_proc(pnr, dir);
    text += "\n# " + shell_join(pnr) + "\n" + fmt::format("# exit status {}\n", r.status);
    if (r.status == 0) {
      const std::vector<std::string> tim = {"icetime", "-d", "hx8k", "-P", "ct256", "-m", "-t", asc};
      r = run_proc(tim, dir);
      text += "\n# " + shell_join(tim) + "\n" + r.out;
      static const std::regex re_mhz(R"(\(([\d.]+) MHz\))");
      if (std::regex_search(r.out, m, re_mhz)) {
        b.fmax_mhz = std::stod(m[1]);
        b.fmax_source = fmt::format("{:.2f} MHz on an iCE40 HX8K ct256 (icetime after nextpnr-ice40, this run, "
                                    "reports/ice40.log)", b.fmax_mhz);
        b.ice40_status = fmt::format("{} LUT4, Fmax {:.2f} MHz (icetime)", luts, b.fmax_mhz);
      } else {
        b.ice40_status = fmt::format("{} LUT4; icetime gave no Fmax", luts);
      }
    } else {
      b.ice40_status = fmt::format("{} LUT4; nextpnr-ice40 failed", luts);
    }
  }
  write_text(log, text + "\n# result: " + b.ice40_status + "\n");
}

// Runs one of the bundle's simulator scripts; returns its last line (PASS ...).
std::string run_sim(const fs::path& dir, const std::string& script, const std::string& log) {
  const std::vector<std::string> cmd = {"sh", "./" + script};
  const Proc r = run_proc(cmd, dir);
  write_text(dir / "reports" / log, report_header(script + " at generation time", "./" + script, "see the script") + r.out +
                                        fmt::format("# exit status {}\n", r.status));
  const std::string last = last_line_with(r.out, script + ":");
  if (r.status != 0 || last.find(script + ": PASS") == std::string::npos)
    throw std::runtime_error(script + " did not pass: " + (last.empty() ? first_line(r.out) : last) + " " +
                             last_line_with(r.out, "FAIL"));
  return last;
}

std::string synth_summary(const BundleBase& b) {
  switch (b.synth) {
    case SynthMode::Skipped: return "skipped: " + b.synth_why;
    case SynthMode::Hierarchical:
      return fmt::format("{} cells, {} flip-flops (hierarchical: {})", b.synth_cells, b.synth_ffs, b.synth_why);
    default: return fmt::format("{} cells, {} flip-flops, logic depth {}", b.synth_cells, b.synth_ffs, b.synth_depth);
  }
}

void check_and_report(BundleBase& b, const fs::path& dir, bool no_ice40, const std::function<void(const std::string&)>& step) {
  report_lint(b, dir);
  step("Verilator lint -Wall: " + b.lint_status);
  report_yosys(b, dir);
  step("Yosys: " + synth_summary(b));
  report_ice40(b, dir, no_ice40);
  step("iCE40: " + b.ice40_status);
}

// The OSU 0.18 um sign-off of the staged bundle (docs/signoff.md): signoff/signoff.py, copied into the bundle,
// maps it to cells, times it with OpenSTA, rewrites constraints.sdc with the measured clock, runs the bundle's
// bench on the netlist and reports the energy per result. A failed gate-level run fails the handoff.
void report_signoff(BundleBase& b, const fs::path& dir, const std::function<void(const std::string&)>& step) {
  if (b.signoff_mode == "off") {
    b.signoff_status = "not run (--signoff off)";
    return;
  }
  const fs::path lib = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";
  const std::string python = fs::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  std::string missing;
  for (const char* tool : {"yosys", "sta", "iverilog", "vvp"})
    if (!on_path(tool)) missing += std::string(missing.empty() ? "" : ", ") + tool;
  if (!on_path(python)) missing += std::string(missing.empty() ? "" : ", ") + "python3";
  if (!fs::exists(lib)) missing += std::string(missing.empty() ? "" : ", ") + lib.string();
  if (!missing.empty()) {
    if (b.signoff_mode == "on")
      throw std::runtime_error("--signoff on needs " + missing + " (scripts/setup.sh installs opensta and qflow-tech-osu018)");
    b.signoff_status = "not run: " + missing + " not installed (scripts/setup.sh installs them)";
    return;
  }
  const fs::path root = root_dir();
  fs::create_directories(dir / "signoff");
  for (const char* f : {"signoff.py", "fastmul.py"}) fs::copy_file(root / "signoff" / f, dir / "signoff" / f);
  const std::vector<std::string> cmd = {python, "signoff/signoff.py", ".", "--target", fmt::format("{}", b.signoff_target),
                                        "--abc", b.signoff_abc};
  step("OSU 0.18 um sign-off: " + shell_join(cmd) + " (cell mapping, OpenSTA, gate-level simulation, power)");
  ProcOptions po;
  po.on_line = [&step](const std::string& line) {
    if (line.rfind("signoff: ", 0) == 0) step(line.substr(0, line.size() - (line.back() == '\n' ? 1 : 0)));
  };
  const Proc r = run_proc(cmd, dir, po);
  write_text(dir / "reports" / "signoff.log",
             report_header("OSU 0.18 um sign-off (signoff/signoff.py)", shell_join(cmd), tool_version({"sta", "-version"})) +
                 r.out + fmt::format("# exit status {}\n", r.status));
  if (r.status == 2)
    throw std::runtime_error("the gate-level simulation of the mapped netlist failed (signoff/gatesim_*.log): " +
                             last_line_with(r.out, "gatesim"));
  if (r.status != 0) {  // its own one-line error, else the last line it printed (a crash, a traceback's last line)
    const std::string why = last_line_with(r.out, "signoff: error");
    throw std::runtime_error("the sign-off failed (reports/signoff.log): " + (why.empty() ? last_line_with(r.out, "") : why));
  }
  const nlohmann::json j = nlohmann::json::parse(read_text(dir / "signoff" / "signoff.json"));
  const auto& st = j.at("sta");
  const double period = st.at("period_ns").get<double>(), wns = st.at("wns_ns").get<double>();
  const bool met = st.at("met").get<bool>();
  b.fmax_mhz = st.at("fmax_mhz").get<double>();
  b.fmax_source = fmt::format(
      "{:.3f} ns, measured in OSU 0.18 um (typical, pre-layout, cell delays x1.15): the {} ns target is {} (WNS {:+.3f} ns), "
      "Fmax {:.1f} MHz (signoff/timing.rpt, signoff/signoff.json)",
      period, b.signoff_target, met ? "met" : "missed and the period is Fmax rounded up", wns, b.fmax_mhz);
  const auto& sy = j.at("synth");
  const auto& gs = j.at("gatesim");
  std::string energy = "no power run";
  if (j.contains("power"))
    energy = fmt::format("{:.2f} pJ per result ({:.3f} mW)", j.at("power").at("energy_pj_per_result").get<double>(),
                         j.at("power").at("power_mw").get<double>());
  std::string simulator = gs.value("simulator", std::string("icarus"));
  simulator = simulator == "verilator" ? "Verilator" : "Icarus";
  b.signoff_status = fmt::format("{} ns ({}, WNS {:+.3f} ns at {} ns), {:.0f} um2, {} cells; gate-level {} {} {} vectors, "
                                 "{} mismatches; {}",
                                 period, met ? "target met" : "target missed", wns, b.signoff_target,
                                 sy.at("area_um2").get<double>(), sy.at("cells").get<long>(), simulator,
                                 gs.at("passed").get<bool>() ? "PASS" : "FAIL", gs.at("vectors").get<long>(),
                                 gs.at("mismatches").get<long>(), energy);
  step("sign-off: " + b.signoff_status);
}

void simulate_and_summarise(BundleBase& b, const fs::path& dir, const std::function<void(const std::string&)>& step) {
  if (b.no_sim) {
    b.icarus_line = "run_icarus.sh: not run at generation time (--no-sim)";
    b.verilator_line = "run_verilator.sh: not run at generation time (--no-sim)";
  } else {
    b.icarus_line = run_sim(dir, "run_icarus.sh", "sim_icarus.log");
    b.verilator_line = run_sim(dir, "run_verilator.sh", "sim_verilator.log");
  }
  step(b.icarus_line);
  step(b.verilator_line);
  report_signoff(b, dir, step);
  write_text(dir / "reports" / "summary.md", summary_md(b));
  write_text(dir / "README.md", bundle_readme(b));
}

void require_tools() {
  for (const char* tool : {"iverilog", "vvp", "verilator", "yosys", "tar", "gzip"})
    if (!on_path(tool)) throw std::runtime_error(std::string("'") + tool + "' not found on PATH (scripts/setup.sh installs it)");
}

}  // namespace shadecore::cli::handoff
