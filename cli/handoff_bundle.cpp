// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — the parts every bundle shares (cli/handoff_bundle.hpp).
#include "handoff_bundle.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/core.h>

#include "output.hpp"
#include "shadecore/common/subprocess.hpp"
#include "unit_spec.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must be defined by the build"
#endif

namespace shadecore::cli::handoff {

// ---------------------------------------------------------------------------- small helpers
std::string root_dir() {
  const char* env = std::getenv("SHADECORE_ROOT");
  return env && *env ? env : SHADECORE_SOURCE_DIR;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& s, bool exec) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << s;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
  if (exec) fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

bool on_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && ::access((fs::path(dir) / tool).c_str(), X_OK) == 0) return true;
  return false;
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

// SHA-256 (FIPS 180-4), for MANIFEST.sha256 in `sha256sum` format.
std::string sha256_hex(const std::string& data) {
  static const uint32_t K[64] = {
      0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5, 0xd807aa98,
      0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786,
      0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8,
      0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13,
      0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819,
      0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a,
      0x5b9cca4f, 0x682e6ff3, 0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
      0xc67178f2};
  uint32_t h[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  std::string m = data;
  const uint64_t bits = static_cast<uint64_t>(data.size()) * 8;
  m += static_cast<char>(0x80);
  while (m.size() % 64 != 56) m += '\0';
  for (int i = 7; i >= 0; --i) m += static_cast<char>((bits >> (8 * i)) & 0xff);
  auto rotr = [](uint32_t x, int r) { return (x >> r) | (x << (32 - r)); };
  for (size_t off = 0; off < m.size(); off += 64) {
    uint32_t w[64];
    for (int i = 0; i < 16; ++i)
      w[i] = (uint32_t(uint8_t(m[off + 4 * i])) << 24) | (uint32_t(uint8_t(m[off + 4 * i + 1])) << 16) |
             (uint32_t(uint8_t(m[off + 4 * i + 2])) << 8) | uint32_t(uint8_t(m[off + 4 * i + 3]));
    for (int i = 16; i < 64; ++i) {
      const uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
      const uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
      w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
    for (int i = 0; i < 64; ++i) {
      const uint32_t t1 = hh + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + K[i] + w[i];
      const uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      hh = g; g = f; f = e; e = d + t1; d = c; c = b; b = a; a = t1 + t2;
    }
    h[0] += a; h[1] += b; h[2] += c; h[3] += d; h[4] += e; h[5] += f; h[6] += g; h[7] += hh;
  }
  std::string out;
  for (uint32_t v : h) out += fmt::format("{:08x}", v);
  return out;
}

// ---------------------------------------------------------------------------- child processes
// The common runner (shadecore/common/subprocess.hpp): children in their own process group so an interrupt
// can stop a whole tool tree (make, g++); its InterruptScope records the signal and stops them.
namespace {
using SignalGuard = proc::InterruptScope;

void check_interrupt() {
  if (const int sig = proc::interrupt_signal()) throw Interrupted(fmt::format("interrupted by signal {}", sig));
}
}  // namespace

Proc run_proc(const std::vector<std::string>& argv, const fs::path& cwd, const ProcOptions& opt) {
  check_interrupt();
  proc::Options o;
  o.cwd = cwd.string();
  o.merge_stderr = true;
  o.own_group = opt.own_group;
  o.ignore_sigint = false;  // not in its own group: a terminal's ^C reaches it directly
  o.on_line = opt.on_line;
  const proc::Result r = proc::run(argv, o);
  check_interrupt();
  return Proc{r.status, r.out};
}

std::string shell_join(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) {
    const bool plain = !a.empty() && a.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./:,@%") == std::string::npos;
    s += (s.empty() ? "" : " ") + (plain ? a : "'" + a + "'");
  }
  return s;
}


std::string concrete_port_table(const std::vector<Port>& ports) {
  std::string s = "| port | dir | width | bits | meaning |\n|---|---|---|---|---|\n";
  for (const auto& p : ports)
    s += fmt::format("| `{}` | {} | {} | {} | {} |\n", p.name, p.dir, p.width,
                     p.width == 1 ? "" : fmt::format("`[{}:0]`", p.width - 1), p.meaning);
  return s;
}

std::string filelist(const BundleBase& b) {
  std::string s = "+incdir+rtl\n";
  for (const auto& f : b.rtl_files) s += f + "\n";
  return s;
}


std::string sdc(const BundleBase& b) {
  double period = 20.0;
  std::string why;
  if (b.fmax_mhz > 0) {
    period = std::ceil(10000.0 / b.fmax_mhz) / 10.0;  // rounded up to 0.1 ns
    why = "# Target period from the measured Fmax: " + b.fmax_source + ".\n";
  } else {
    why = "# No measured Fmax for this configuration (it does not fit the iCE40 used for the measurements,\n"
          "# or it was not measured): 20 ns is a placeholder. Set it for your technology.\n";
  }
  std::string ins, outs;
  for (const auto& p : b.ports) {
    if (p.name == "clk_i") continue;
    std::string& dst = p.dir == "in" ? ins : outs;
    dst += (dst.empty() ? "" : " ") + (p.width == 1 ? p.name : p.name + "[*]");
  }
  return fmt::format(
      "# constraints.sdc — {top}: {desc}\n"
      "# Generated by shadecore handoff. Every number here is an assumption to edit for your flow.\n"
      "{why}"
      "set CLK_PERIOD {period:.1f}\n"
      "create_clock -name clk -period $CLK_PERIOD [get_ports clk_i]\n"
      "\n"
      "# Assumed environment: every input is launched by a flip-flop on the same clock outside the core and\n"
      "# arrives 30 % of the period after the edge; every output must be valid 30 % of the period before the\n"
      "# next edge at a flip-flop outside the core. rst_ni is synchronous: it is timed like any input.\n"
      "set IO_FRACTION 0.3\n"
      "set_input_delay  -clock clk [expr {{$IO_FRACTION * $CLK_PERIOD}}] [get_ports {{{ins}}}]\n"
      "set_output_delay -clock clk [expr {{$IO_FRACTION * $CLK_PERIOD}}] [get_ports {{{outs}}}]\n"
      "\n"
      "# {comb} combinational through the core (AXI-Stream allows ready to depend\n"
      "# on ready): with the delays above it has (1 - 2 * IO_FRACTION) of the period. Every other path starts\n"
      "# and ends at a flip-flop of the core. No multicycle or false paths: every register is a single-cycle\n"
      "# path of the pipeline.\n",
      fmt::arg("top", b.top), fmt::arg("desc", b.desc), fmt::arg("why", why), fmt::arg("period", period),
      fmt::arg("ins", ins), fmt::arg("outs", outs),
      fmt::arg("comb", b.comb_paths.empty() ? "out_ready_i -> in_ready_o is a" : b.comb_paths + " are"));
}

std::string bundle_readme(const BundleBase& b) {
  return fmt::format(
      "# shadecore handoff: `{top}` ({desc})\n\n"
      "Made by `{cmd}` on {date}.\n\n"
      "| path | what |\n|---|---|\n"
      "| `rtl/` | the RTL: `{top}.v` (all parameters fixed) and the files it needs; `filelist.f` lists them |\n"
      "| `interface.md` | ports, formats, handshake, reset, latency, programming sequence, error contract |\n"
      "| `constraints.sdc` | clock and I/O delay assumptions |\n"
      "| `vectors/` | test vectors from the bit-exact C model (hard cases, random) |\n"
      "| `tb/` | plain Verilog-2005 self-checking testbench and its configuration |\n"
      "| `run_icarus.sh`, `run_verilator.sh` | run the testbench on every vector file; exit 0 only on PASS |\n"
      "| `reports/` | lint, synthesis and simulation results at generation time, each with its command |\n"
      "| `MANIFEST.sha256` | `sha256sum -c MANIFEST.sha256` |\n\n"
      "    ./run_icarus.sh       # {icarus}\n"
      "    ./run_verilator.sh    # {verilator}\n",
      fmt::arg("top", b.top), fmt::arg("desc", b.desc), fmt::arg("cmd", command_line()),
      fmt::arg("date", utc_now()), fmt::arg("icarus", b.icarus_line), fmt::arg("verilator", b.verilator_line));
}

std::string last_line_with(const std::string& out, const std::string& needle) {
  std::stringstream ss(out);
  std::string line, found;
  while (std::getline(ss, line))
    if (line.find(needle) != std::string::npos) found = line;
  return found;
}

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

std::string summary_md(const BundleBase& b) {
  return fmt::format(
      "# Reports: `{top}` ({desc})\n\n"
      "Generated by `{cmd}` on {date}.\n\n"
      "| check | result | log (with its command) |\n|---|---|---|\n"
      "| Verilator lint `-Wall` | {lint} | `verilator_lint.log` |\n"
      "| Yosys generic synthesis | {synth} | `yosys_synth.log` (`yosys -s yosys_synth.ys`) |\n"
      "| iCE40 | {ice40} | `ice40.log` |\n"
      "| Icarus simulation | {icarus} | `sim_icarus.log` |\n"
      "| Verilator simulation | {verilator} | `sim_verilator.log` |\n\n"
      "Clock target in `constraints.sdc`: {fmax}.\n",
      fmt::arg("top", b.top), fmt::arg("desc", b.desc), fmt::arg("cmd", command_line()),
      fmt::arg("date", utc_now()), fmt::arg("lint", b.lint_status), fmt::arg("synth", synth_summary(b)),
      fmt::arg("ice40", b.ice40_status),
      fmt::arg("icarus", b.icarus_line), fmt::arg("verilator", b.verilator_line),
      fmt::arg("fmax", b.fmax_source.empty() ? "no measured Fmax (20 ns placeholder)" : b.fmax_source));
}

namespace {
std::string manifest(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      const std::string rel = fs::relative(e.path(), dir).generic_string();
      if (rel != "MANIFEST.sha256") files.push_back(rel);
    }
  std::sort(files.begin(), files.end());
  std::string s;
  for (const auto& f : files) s += sha256_hex(read_text(dir / f)) + "  " + f + "\n";
  return s;
}
}  // namespace

int eval_width(const std::string& expr, const Widths& w) {
  if (expr == "F+1") return w.frac + 1;
  if (expr == "F+2") return w.frac + 2;
  if (expr == "F+8") return w.frac + 8;
  if (expr == "TAGW") return w.tagw;
  if (expr == "COEFW") return w.coefw;
  if (!expr.empty() && expr.find_first_not_of("0123456789") == std::string::npos) return std::stoi(expr);
  throw std::runtime_error("config/interface.json: unknown width '" + expr + "'");
}

SynthMode parse_synth(const std::string& text, SynthMode auto_mode) {
  if (text == "auto") return auto_mode;
  if (text == "flat") return SynthMode::Flat;
  if (text == "hier") return SynthMode::Hierarchical;
  if (text == "skip") return SynthMode::Skipped;
  throw std::invalid_argument("unknown --synth '" + text + "' (known: auto, flat, hier, skip)");
}

void check_top_name(const std::string& top, const std::string& tb) {
  static const std::regex ident(R"(^[A-Za-z_][A-Za-z0-9_]{0,62}$)");
  if (!std::regex_match(top, ident)) throw std::invalid_argument("--top '" + top + "' is not a Verilog identifier");
  if (top.rfind("sc_", 0) == 0 || top == tb)
    throw std::invalid_argument("--top '" + top + "' clashes with the bundle's module names (sc_*, " + tb + ")");
}

uint64_t checked_seed(uint64_t seed) {
  const uint64_t s = seed != 0 ? seed : pick_seed();
  if (s > 0x7fffffffull) throw std::invalid_argument("--seed must be in 1..2147483647 (the testbench's +seed= is 32-bit)");
  return s;
}

void check_and_report(BundleBase& b, const fs::path& dir, bool no_ice40, const std::function<void(const std::string&)>& step) {
  report_lint(b, dir);
  step("Verilator lint -Wall: " + b.lint_status);
  report_yosys(b, dir);
  step("Yosys: " + synth_summary(b));
  report_ice40(b, dir, no_ice40);
  step("iCE40: " + b.ice40_status);
}

void simulate_and_summarise(BundleBase& b, const fs::path& dir, const std::function<void(const std::string&)>& step) {
  b.icarus_line = run_sim(dir, "run_icarus.sh", "sim_icarus.log");
  step(b.icarus_line);
  b.verilator_line = run_sim(dir, "run_verilator.sh", "sim_verilator.log");
  step(b.verilator_line);
  write_text(dir / "reports" / "summary.md", summary_md(b));
  write_text(dir / "README.md", bundle_readme(b));
}

void require_tools() {
  for (const char* tool : {"iverilog", "vvp", "verilator", "yosys", "tar", "gzip"})
    if (!on_path(tool)) throw std::runtime_error(std::string("'") + tool + "' not found on PATH (scripts/setup.sh installs it)");
}

// The templates name the testbench in one line, `tb=tb_shadecore`; each bundle sets its own.
void write_run_scripts(const BundleBase& b, const fs::path& dir) {
  const fs::path root = root_dir();
  for (const char* script : {"run_icarus.sh", "run_verilator.sh"}) {
    std::string text = read_text(root / "handoff" / script);
    const std::string line = "\ntb=tb_shadecore ";
    const size_t at = text.find(line);
    if (at == std::string::npos)
      throw std::runtime_error(std::string("handoff/") + script + " has no 'tb=tb_shadecore' line (SHADECORE_ROOT)");
    text.replace(at, line.size(), "\ntb=" + b.tb + " ");
    write_text(dir / script, text, true);
  }
}

void make_bundle(const std::string& out, bool force, const std::function<void(const fs::path&, const Step&)>& fill) {
  // Destination: a symlink to a directory is followed (the link stays); a non-directory is refused.
  std::string out_text = out;
  while (out_text.size() > 1 && out_text.back() == '/') out_text.pop_back();
  const fs::path given = fs::path(out_text).lexically_normal();
  std::error_code ec;
  fs::path dest = given;
  if (fs::is_symlink(fs::symlink_status(given, ec))) {
    dest = fs::canonical(given, ec);
    if (ec || !fs::is_directory(dest)) throw std::runtime_error("--out " + out + " is a symlink that does not lead to a directory");
  }
  const bool dest_exists = fs::exists(fs::symlink_status(dest, ec));
  if (dest_exists && !fs::is_directory(fs::symlink_status(dest, ec)))
    throw std::runtime_error("--out " + out + " exists and is not a directory");
  if (dest_exists && !fs::is_empty(dest, ec) && !force)
    throw std::runtime_error("--out " + out + " is not empty (use --force to replace its contents)");
  if (dest == fs::current_path().lexically_normal() || dest.filename().empty() || dest.filename() == "..")
    throw std::runtime_error("--out " + out + " cannot be used as a bundle directory");
  const std::string tar_path = given.string() + ".tar.gz";
  if (fs::exists(fs::symlink_status(tar_path, ec))) {
    if (!force) throw std::runtime_error(tar_path + " exists (use --force to replace it)");
  }
  fs::path parent = fs::absolute(dest).parent_path();
  // Missing parents are created, and removed again if the run fails.
  std::vector<fs::path> created;
  for (fs::path p = parent; !p.empty() && !fs::exists(p); p = p.parent_path()) created.push_back(p);
  std::reverse(created.begin(), created.end());

  SignalGuard guard;
  proc::clear_interrupt();
  fs::path staging;
  bool committed = false;
  auto cleanup = [&] {
    std::error_code e2;
    if (!staging.empty()) fs::remove_all(staging, e2);
    if (!committed)
      for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, e2);  // only if empty
  };
  try {
    for (const auto& p : created) {
      fs::create_directory(p, ec);
      if (ec) throw std::runtime_error("cannot create directory " + p.string() + ": " + ec.message());
    }
    if (::access(parent.c_str(), W_OK) != 0)
      throw std::runtime_error("cannot write to directory " + parent.string() + ": " + std::strerror(errno));
    check_output_path(tar_path);
    staging = parent / fmt::format(".{}.handoff-tmp.{}", dest.filename().string(), ::getpid());
    fs::remove_all(staging, ec);
    if (!fs::create_directory(staging, ec) || ec)
      throw std::runtime_error("cannot create " + staging.string() + ": " + ec.message());
    const std::string name = given.filename().string();
    const fs::path dir = staging / name;
    fs::create_directories(dir);
    const auto t0 = std::chrono::steady_clock::now();
    const Step step = [t0](const std::string& what) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print("handoff: [{:5.1f} s] {}\n", s, what);
      std::fflush(stdout);
    };

    fill(dir, step);
    write_text(dir / "MANIFEST.sha256", manifest(dir));

    // The tarball of the directory (top-level folder = the --out name).
    const std::string tmp_tar = (staging / (name + ".tar.gz")).string();
    const Proc t = run_proc({"tar", "-C", staging.string(), "--sort=name", "--owner=0", "--group=0", "--numeric-owner",
                             "-czf", tmp_tar, name},
                            staging);
    if (t.status != 0) throw std::runtime_error("tar failed: " + first_line(t.out));
    const std::string tar_bytes = read_text(tmp_tar);
    check_interrupt();

    // ---- commit: swap the directory into place, then the tarball; undo the swap if that fails.
    const fs::path old = staging / ".old";
    if (dest_exists) {
      fs::rename(dest, old, ec);
      if (ec) throw std::runtime_error("cannot replace " + dest.string() + ": " + ec.message());
    }
    fs::rename(dir, dest, ec);
    if (ec) {
      std::error_code e2;
      if (dest_exists) fs::rename(old, dest, e2);
      throw std::runtime_error("cannot move the bundle to " + dest.string() + ": " + ec.message());
    }
    try {
      write_output_file(tar_path, tar_bytes);
    } catch (...) {
      std::error_code e2;
      fs::rename(dest, staging / ".failed", e2);
      if (dest_exists) fs::rename(old, dest, e2);
      throw;
    }
    committed = true;
    cleanup();
    const std::string man = read_text(dest / "MANIFEST.sha256");
    step(fmt::format("wrote {} and {} ({} files in MANIFEST.sha256)", given.string(), tar_path,
                     std::count(man.begin(), man.end(), '\n')));
  } catch (...) {
    cleanup();
    if (proc::interrupt_signal()) {  // interrupted: nothing is left behind; end the way the signal would have
      const int sig = proc::interrupt_signal();
      guard.restore();
      fmt::print(stderr, "shadecore: error: handoff interrupted by signal {}; nothing written\n", sig);
      ::signal(sig, SIG_DFL);
      ::raise(sig);
    }
    throw;
  }
}

}  // namespace shadecore::cli::handoff
