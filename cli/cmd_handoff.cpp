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
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "unit_spec.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must be defined by the build"
#endif

namespace fs = std::filesystem;

namespace shadecore::cli {
namespace {

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

void write_text(const fs::path& p, const std::string& s, bool exec = false) {
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
// Children run in their own process group so an interrupt can stop a whole tool tree (make, g++).
std::atomic<pid_t> g_child{0};
volatile sig_atomic_t g_signal = 0;

extern "C" void on_handoff_signal(int sig) {
  g_signal = sig;
  const pid_t p = g_child.load();
  if (p > 0) ::kill(-p, SIGTERM);
}

// Installs on_handoff_signal for the run; restore() puts the previous handlers back (idempotent).
struct SignalGuard {
  struct sigaction old[3];
  const int sigs[3] = {SIGINT, SIGTERM, SIGHUP};
  bool active = true;
  SignalGuard() {
    struct sigaction sa {};
    sa.sa_handler = on_handoff_signal;
    sigemptyset(&sa.sa_mask);
    for (int i = 0; i < 3; ++i) ::sigaction(sigs[i], &sa, &old[i]);
  }
  void restore() {
    if (!active) return;
    for (int i = 0; i < 3; ++i) ::sigaction(sigs[i], &old[i], nullptr);
    active = false;
  }
  ~SignalGuard() { restore(); }
};

struct Interrupted : std::runtime_error {
  using std::runtime_error::runtime_error;
};

void check_interrupt() {
  if (g_signal) throw Interrupted(fmt::format("interrupted by signal {}", int(g_signal)));
}

struct Proc {
  int status = -1;
  std::string out;  // stdout and stderr, interleaved
};

Proc run_proc(const std::vector<std::string>& argv, const fs::path& cwd) {
  check_interrupt();
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  std::vector<char*> args;
  std::vector<std::string> copy = argv;
  for (auto& s : copy) args.push_back(s.data());
  args.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    ::setpgid(0, 0);
    ::dup2(fds[1], 1);
    ::dup2(fds[1], 2);
    ::close(fds[0]);
    ::close(fds[1]);
    if (::chdir(cwd.c_str()) != 0) ::_exit(126);
    ::execvp(args[0], args.data());
    std::fprintf(stderr, "cannot run %s: %s\n", args[0], std::strerror(errno));
    ::_exit(127);
  }
  ::setpgid(pid, pid);
  g_child = pid;
  ::close(fds[1]);
  Proc r;
  char buf[65536];
  for (;;) {
    const ssize_t k = ::read(fds[0], buf, sizeof buf);
    if (k > 0) r.out.append(buf, static_cast<size_t>(k));
    else if (k == 0 || errno != EINTR) break;
  }
  ::close(fds[0]);
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
  }
  g_child = 0;
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
  check_interrupt();
  return r;
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

// ---------------------------------------------------------------------------- the port table
nlohmann::json load_ports() {
  const fs::path p = fs::path(root_dir()) / "config" / "interface.json";
  try {
    return nlohmann::json::parse(read_text(p)).at("ports");
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("malformed " + p.string() + ": " + e.what());
  }
}

struct Widths {
  int frac, tagw, coefw;
};

int eval_width(const std::string& expr, const Widths& w) {
  if (expr == "F+1") return w.frac + 1;
  if (expr == "F+2") return w.frac + 2;
  if (expr == "TAGW") return w.tagw;
  if (expr == "COEFW") return w.coefw;
  if (!expr.empty() && expr.find_first_not_of("0123456789") == std::string::npos) return std::stoi(expr);
  throw std::runtime_error("config/interface.json: unknown width '" + expr + "'");
}

std::string sym_width(const std::string& expr) {
  return (expr == "TAGW" || expr == "COEFW") ? "`" + expr + "`" : expr;
}

bool port_present(const nlohmann::json& p, const UnitSpec& spec) {
  const std::string when = p.value("when", "");
  if (when == "thr") return spec.uses_thr();
  if (when == "norm") return spec.norm;
  if (when == "table") return is_table_variant(spec.variant);
  return true;
}

struct Port {
  std::string name, dir;
  int width;
  std::string meaning;
};

std::vector<Port> concrete_ports(const nlohmann::json& ports, const UnitSpec& spec, int tagw) {
  const Widths w{spec.format.frac, tagw, spec.coef_bits()};
  std::vector<Port> v;
  for (const auto& p : ports) {
    if (!port_present(p, spec)) continue;
    const std::string expr = spec.norm && p.contains("width_norm") ? p.at("width_norm").get<std::string>()
                                                                   : p.at("width").get<std::string>();
    v.push_back({p.at("name"), p.at("dir"), eval_width(expr, w), p.at("meaning")});
  }
  return v;
}

// The README's port table (symbolic widths, every port of sc_specular). Also used by the test that
// keeps README.md in step (scripts/update_readme_ports.sh --check).
std::string generic_port_table() {
  std::string s = "| port | dir | width | meaning |\n|---|---|---|---|\n";
  for (const auto& p : load_ports()) {
    std::string width = sym_width(p.at("width"));
    if (p.contains("width_norm")) width += " (" + sym_width(p.at("width_norm")) + " with `NORM` = 1)";
    s += fmt::format("| `{}` | {} | {} | {} |\n", p.at("name").get<std::string>(), p.at("dir").get<std::string>(), width,
                     p.at("meaning").get<std::string>());
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

// ---------------------------------------------------------------------------- bundle contents
struct HandoffArgs {
  std::shared_ptr<UnitOptions> unit = std::make_shared<UnitOptions>();
  std::string out;
  bool force = false;
  int tagw = 8;
  uint64_t seed = 0;
  uint64_t count = 2000;
  std::string top = "shadecore_top";
  bool no_ice40 = false;
  bool print_port_table = false;
  std::string core = "specular";
  std::string features;
};

struct Bundle {
  UnitSpec spec;
  int tagw;
  std::string top;
  uint64_t seed;
  std::vector<Port> ports;
  std::vector<std::string> rtl_files;  // relative to the bundle
  int latency, latency_min;
  size_t n_hard = 0, n_random = 0;
  // measured
  std::string lint_status, synth_cells, synth_ffs, synth_depth, ice40_status, icarus_line, verilator_line;
  double fmax_mhz = 0.0;
  std::string fmax_source;
};

std::vector<std::string> unit_files(const UnitSpec& s) {
  std::vector<std::string> v = {"sc_specular.v"};
  switch (s.variant) {
    case VariantId::cs16: v.push_back("sc_cs16.v"); break;
    case VariantId::schlick_div: v.push_back("sc_schlick_div.v"); break;
    case VariantId::schlick_nr: v.push_back("sc_schlick_nr.v"); break;
    case VariantId::schlick_iter: v.push_back("sc_schlick_iter.v"); break;
    case VariantId::table256:
    case VariantId::table1024: v.push_back("sc_table.v"); break;
    default:
      if (squarer_form(s.variant)) {  // cs16 forms: sc_cs16 FORM = 1 with the folded squarer
        v.push_back("sc_cs16.v");
        v.push_back("sc_square.v");
      }
      break;
  }
  if (s.norm) v.push_back("sc_norm.v");
  return v;
}

std::string wrapper_v(const Bundle& b) {
  const UnitSpec& s = b.spec;
  std::string ports, conns;
  for (size_t i = 0; i < b.ports.size(); ++i) {
    const Port& p = b.ports[i];
    const std::string range = p.width == 1 ? std::string(13, ' ') : fmt::format("{:<13}", fmt::format("[{}:0]", p.width - 1));
    ports += fmt::format("    {} wire {}{}{}\n", p.dir == "in" ? "input " : "output", range, p.name,
                         i + 1 < b.ports.size() ? "," : "");
  }
  auto has = [&](const std::string& n) {
    return std::any_of(b.ports.begin(), b.ports.end(), [&](const Port& p) { return p.name == n; });
  };
  const char* names[] = {"clk_i",       "rst_ni",     "mat_we_i",    "mat_n_i",     "mat_thr_i",  "mat_coef_i",
                         "tab_we_i",    "tab_addr_i", "tab_value_i", "tab_delta_i", "in_valid_i", "in_ready_o",
                         "in_cos_i",    "in_tag_i",   "out_valid_o", "out_ready_i", "out_spec_o", "out_tag_o"};
  for (size_t i = 0; i < std::size(names); ++i) {
    const std::string n = names[i];
    std::string expr = n;
    if (!has(n)) {
      if (n == "mat_thr_i") expr = fmt::format("{{{}{{1'b0}}}}", s.format.frac + 1);
      else if (n == "mat_coef_i") expr = fmt::format("{{{}{{1'b0}}}}", s.coef_bits());
      else if (n == "tab_we_i") expr = "1'b0";
      else if (n == "tab_addr_i") expr = "10'd0";
      else if (n == "tab_value_i" || n == "tab_delta_i") expr = fmt::format("{{{}{{1'b0}}}}", s.format.frac + 1);
      else throw std::runtime_error("internal: port " + n + " missing from config/interface.json");
    }
    conns += fmt::format("      .{:<12}({}){}\n", n, expr, i + 1 < std::size(names) ? "," : "");
  }
  std::string unused;
  if (!has("mat_thr_i")) unused += fmt::format("//   mat_thr_i  tied to 0 (not used by {}{})\n", s.variant_name,
                                               s.is_cs16() ? " with CUTOFF = 1" : "");
  if (!has("mat_coef_i")) unused += "//   mat_coef_i tied to 0 (NORM = 0)\n";
  if (!has("tab_we_i")) unused += "//   tab_we_i, tab_addr_i, tab_value_i, tab_delta_i tied to 0 (no table RAM in this unit)\n";
  return fmt::format(
      "// ============================================================================================\n"
      "// Filename : rtl/{top}.v  (generated by shadecore handoff — do not edit; regenerate instead)\n"
      "// Purpose  : the bundle's top level: rtl/sc_specular.v with every parameter fixed, so no -G / -P /\n"
      "//            defparam is needed downstream.\n"
      "//              VARIANT = {vid} ({vname}), FRAC = {F}, GUARD = {G}, CUTOFF = {cut} ({cutname}),\n"
      "//              TAGW = {tagw}, NORM = {norm}, COEFW = {coefw}\n"
      "//            Ports, formats, handshake, reset, latency ({lat} cycles) and programming: interface.md.\n"
      "// Ports of sc_specular not brought out:\n{unused}"
      "// Made by  : {cmd}\n"
      "// ============================================================================================\n"
      "`default_nettype none\n\n"
      "module {top} (\n{ports});\n\n"
      "  sc_specular #(\n"
      "      .VARIANT({vid}),\n      .FRAC   ({F}),\n      .GUARD  ({G}),\n      .CUTOFF ({cut}),\n"
      "      .TAGW   ({tagw}),\n      .NORM   ({norm}),\n      .COEFW  ({coefw})\n"
      "  ) u_core (\n{conns}  );\n\nendmodule\n\n`default_nettype wire\n",
      fmt::arg("top", b.top), fmt::arg("vid", static_cast<int>(s.variant)), fmt::arg("vname", s.variant_name),
      fmt::arg("F", s.format.frac), fmt::arg("G", s.format.guard), fmt::arg("cut", static_cast<int>(s.cutoff)),
      fmt::arg("cutname", to_string(s.cutoff)), fmt::arg("tagw", b.tagw), fmt::arg("norm", s.norm ? 1 : 0),
      fmt::arg("coefw", s.coef_bits()), fmt::arg("lat", b.latency), fmt::arg("unused", unused.empty() ? "//   (none)\n" : unused),
      fmt::arg("cmd", command_line()), fmt::arg("ports", ports), fmt::arg("conns", conns));
}

std::string tb_config_vh(const Bundle& b, size_t maxvec) {
  const UnitSpec& s = b.spec;
  return fmt::format(
      "// tb/tb_config.vh — generated by shadecore handoff for {desc}; included by tb/tb_shadecore.v\n"
      "// (inside the module). The widths are those of rtl/{top}.v; the latency is the C model's\n"
      "// (shadecore::Unit::latency / latency_min), as docs in interface.md.\n"
      "localparam integer FRAC         = {F};        // F: 1.0 = 2^F\n"
      "localparam integer OUTW         = {outw};        // out_spec_o width\n"
      "localparam integer COEFW        = {coefw};        // mat_coef_i width (driven only with NORM = 1)\n"
      "localparam integer TAGW         = {tagw};\n"
      "localparam integer LATENCY      = {lat};        // advancing edges from acceptance to the taking edge\n"
      "localparam integer LATENCY_MIN  = {latmin};        // under output backpressure (NORM = 1 can close up)\n"
      "localparam integer MAXVEC       = {maxvec};     // the largest vector file in vectors/\n"
      "localparam integer NVEC_DEFAULT = {nhard};      // vectors in vectors/hard.hex (the default file)\n"
      "localparam integer TB_SEED      = {seed};  // random input gaps / backpressure (+seed= overrides)\n",
      fmt::arg("desc", s.describe()), fmt::arg("top", b.top), fmt::arg("F", s.format.frac), fmt::arg("outw", s.out_bits()),
      fmt::arg("coefw", s.coef_bits()), fmt::arg("tagw", b.tagw), fmt::arg("lat", b.latency),
      fmt::arg("latmin", b.latency_min), fmt::arg("maxvec", maxvec), fmt::arg("nhard", b.n_hard), fmt::arg("seed", b.seed));
}

std::string tb_dut_vh(const Bundle& b) {
  std::map<std::string, std::string> sig = {
      {"clk_i", "clk"},         {"rst_ni", "rst_n"},       {"mat_we_i", "mat_we"},     {"mat_n_i", "mat_n"},
      {"mat_thr_i", "mat_thr"}, {"mat_coef_i", "mat_coef"}, {"in_valid_i", "in_valid"}, {"in_ready_o", "in_ready"},
      {"in_cos_i", "in_cos"},   {"in_tag_i", "in_tag"},     {"out_valid_o", "out_valid"}, {"out_ready_i", "out_ready"},
      {"out_spec_o", "out_spec"}, {"out_tag_o", "out_tag"},   {"tab_we_i", "tab_we"},     {"tab_addr_i", "tab_addr"},
      {"tab_value_i", "tab_value"}, {"tab_delta_i", "tab_delta"}};
  std::string s = fmt::format("// tb/tb_dut.vh — generated by shadecore handoff: the design under test, rtl/{}.v.\n", b.top);
  bool thr = false, coef = false;
  s += fmt::format("  {} dut (\n", b.top);
  for (size_t i = 0; i < b.ports.size(); ++i) {
    const Port& p = b.ports[i];
    if (p.name == "mat_thr_i") thr = true;
    if (p.name == "mat_coef_i") coef = true;
    s += fmt::format("      .{:<12}({}){}\n", p.name, sig.at(p.name), i + 1 < b.ports.size() ? "," : "");
  }
  s += "  );\n";
  // Testbench registers that drive no port of this configuration: marked unused for lint.
  if (!thr || !coef)
    s += fmt::format("  wire unused_tb_mat = &{{1'b0{}{}}};\n", thr ? "" : ", mat_thr", coef ? "" : ", mat_coef");
  return s;
}

std::string filelist(const Bundle& b) {
  std::string s = "+incdir+rtl\n";
  for (const auto& f : b.rtl_files) s += f + "\n";
  return s;
}

// Fmax recorded by scripts/cost_report.py (docs/tradeoffs.json: iCE40 HX8K, icetime after nextpnr).
void recorded_fmax(Bundle& b) {
  const fs::path p = fs::path(root_dir()) / "docs" / "tradeoffs.json";
  if (!fs::exists(p)) return;
  try {
    for (const auto& r : nlohmann::json::parse(read_text(p)))
      if (r.value("variant", "") == b.spec.variant_name && r.value("config", "") == b.spec.config_name &&
          r.contains("fmax_mhz") && r["fmax_mhz"].is_number()) {
        b.fmax_mhz = r["fmax_mhz"].get<double>();
        b.fmax_source = fmt::format("{:.2f} MHz on an iCE40 {} (nextpnr-ice40 + icetime, docs/tradeoffs.json, "
                                    "scripts/cost_report.py{})",
                                    b.fmax_mhz, r.value("pnr", "HX8K"), b.spec.norm ? "; measured without NORM" : "");
      }
  } catch (const nlohmann::json::exception&) {
  }
}

std::string sdc(const Bundle& b) {
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
      "# out_ready_i -> in_ready_o is a combinational path through the core (AXI-Stream allows ready to depend\n"
      "# on ready): with the delays above it has (1 - 2 * IO_FRACTION) of the period. Every other path starts\n"
      "# and ends at a flip-flop of the core. No multicycle or false paths: every register is a single-cycle\n"
      "# path of the pipeline.\n",
      fmt::arg("top", b.top), fmt::arg("desc", b.spec.describe()), fmt::arg("why", why), fmt::arg("period", period),
      fmt::arg("ins", ins), fmt::arg("outs", outs));
}

std::string error_contract(const UnitSpec& s) {
  const int F = s.format.frac, G = s.format.guard;
  std::string e;
  switch (s.variant) {
    case VariantId::cs16:
      e = fmt::format(
          "cs16(c, n) = ((n/16)(c − 1) + 1)^16, cut to 0 by the {cut} test. Against the double-precision cs16 of the\n"
          "same input code and the same cut decision y (docs/spec.md §3.3):\n\n"
          "    −(½ + 15·2^−G) < out − y·2^F ≤ +½ ulp    (G = {G}: ({lo:.5f}, +0.5] ulp, 1 ulp = 2^−{F})\n\n"
          "Rounding happens in five places only: four truncating squarings (W = F + G = {W} fraction bits) and the\n"
          "final round half up. The output never exceeds 2^F and is non-decreasing in the input code for every n.\n"
          "Both cut-off forms give bit-identical outputs at every legal width.\n",
          fmt::arg("cut", s.cutoff == Cutoff::ThetaCr ? "θcr (c < thr(n))" : "sign (base ≤ 0)"), fmt::arg("G", G),
          fmt::arg("lo", -(0.5 + 15.0 * std::ldexp(1.0, -G))), fmt::arg("F", F), fmt::arg("W", F + G));
      break;
    case VariantId::schlick_div:
    case VariantId::schlick_iter:
      e = "S(t, n) = t / (n − (n − 1)·t). The output is the exact quotient 2^F·c/Dc (Dc = n(2^F − c) + c) rounded\n"
          "half up: |out − 2^F·S| ≤ ½ ulp (correctly rounded) against the double S of the same clamped code;\n"
          "t = 0 gives 0 and t = 1 gives exactly 2^F; the output is non-decreasing in the code (docs/spec.md §6.4).\n";
      break;
    case VariantId::schlick_nr:
      e = fmt::format(
          "S(t, n) = t / (n − (n − 1)·t) by a 64-entry reciprocal table, two Newton–Raphson iterations and one\n"
          "multiply: |out − 2^F·S| ≤ {:.4f} ulp against the double S of the same clamped code (faithful, not\n"
          "always correctly rounded); output ≤ 2^F, non-decreasing in the code (docs/spec.md §6.4).\n",
          schlick_nr_bound_ulp(F));
      break;
    case VariantId::table256:
    case VariantId::table1024:
      e = "Table of T(i) = (i/(E−1))^n (E entries {D, V}, loaded per material) interpolated at f = (E−1)·c:\n"
          "−1 < out − 2^F·lerp ≤ +1 ulp against the double table lerp of the same clamped code (docs/spec.md §9.4).\n";
      break;
    default:
      if (const SquarerForm* form = squarer_form(s.variant)) {
        const Cs16Contract c = cs16_contract(form->contract, s.format);
        e = fmt::format(
            "cs16(c, n) = ((n/16)(c − 1) + 1)^16, cut to 0 by the {cut} test and where the base is ≤ 0, computed with\n"
            "folded, truncated squarers (form {name}, docs/spec.md §3.4). Against the double-precision cs16 of the\n"
            "same input code y, the '{contract}' contract:\n\n"
            "    {lo:.5f} {op} out − y·2^F ≤ +{hi:.1f} ulp    (1 ulp = 2^−{F})\n\n"
            "checked exhaustively (every code, n = 16..1024) at F = 8 and 16 (tests/test_cs16_forms.cpp, `shadecore sweep`).\n",
            fmt::arg("cut", s.cutoff == Cutoff::ThetaCr ? "θcr (c < thr(n))" : "sign (base ≤ 0)"),
            fmt::arg("name", s.variant_name), fmt::arg("contract", form->contract), fmt::arg("lo", c.lo),
            fmt::arg("op", c.lo_strict ? "<" : "≤"), fmt::arg("hi", c.hi), fmt::arg("F", F));
      }
      break;
  }
  if (s.norm)
    e += "\nWith NORM = 1 the unit output u is multiplied by the material's coefficient code k and rounded half up:\n"
         "out = ⌊(u·k + 2^(F−1)) / 2^F⌋ (COEFW bits, never overflows). Against the ideal coef(n)·u/2^F this is\n"
         "within 1 ulp (½ from the coefficient's rounding, ½ from the product's); relative to the double\n"
         "coef·(the unit's double reference) the bound above is scaled by coef, plus 1 ulp (docs/spec.md §7.3).\n";
  return e;
}

std::string interface_md(const Bundle& b) {
  const UnitSpec& s = b.spec;
  const Format& f = s.format;
  const Unit u = s.unit();
  // Example materials from the C model.
  std::string examples;
  for (int n : {16, 128, 1024}) {
    const UnitMaterial m = u.setup(n);
    examples += fmt::format("| {} | 0x{:x} | {} |", n, n, s.uses_thr() ? fmt::format("0x{:x} ({})", m.thr, m.thr) : "—");
    examples += s.norm ? fmt::format(" 0x{:x} ({}) |\n", m.coef, m.coef) : " — |\n";
  }
  std::string lat;
  if (s.norm)
    lat = fmt::format("**{} cycles** with `out_ready_i` high (the unit's {} + 2 for the normalisation multiply): a fragment "
                      "accepted at the edge ending cycle t is on `out_*` in cycle t+{}. Under backpressure the unit and "
                      "the normalisation stage advance separately, so a fragment can close up on the one ahead: "
                      "{}..{} advancing edges (an edge advances when `!out_valid_o || out_ready_i` before it).",
                      b.latency, b.latency - 2, b.latency, b.latency_min, b.latency);
  else if (s.variant == VariantId::schlick_iter)
    lat = fmt::format("**{} cycles** from the accepting edge to the first edge at which the result can be taken.",
                      b.latency);
  else
    lat = fmt::format("**{} cycles**: a fragment accepted at the edge ending cycle t is on `out_*` in cycle t+{} when "
                      "`out_ready_i` stays high. Under backpressure the whole pipeline holds (one global enable); the "
                      "result appears after the {}th advancing edge (an edge advances when `!out_valid_o || "
                      "out_ready_i` before it).",
                      b.latency, b.latency, b.latency);
  const std::string thru = s.variant == VariantId::schlick_iter
                               ? fmt::format("one fragment every {} clocks (`in_ready_o` is low while a division is in "
                                             "progress and while an untaken result waits)", schlick_iter_interval(f.frac))
                               : "one fragment per clock while `out_ready_i` is high";
  const std::string ready = s.variant == VariantId::schlick_iter
                                ? "`in_ready_o = rst_ni && !busy && (!out_valid_o || out_ready_i)`"
                                : "`in_ready_o = rst_ni && (!out_valid_o || out_ready_i)`";
  return fmt::format(
      R"(# `{top}` — shadecore {vname}, {cfg} configuration

Generated by `{cmd}` on {date}. The port table comes from `config/interface.json` (the source of the
shadecore README's port table too), the numbers from the bit-exact C model. The contract this bundle
implements is shadecore's docs/spec.md; this file is the part an integrator needs.

## Configuration

| parameter of `sc_specular` | value | meaning |
|---|---|---|
| `VARIANT` | {vid} | `{vname}` |
| `FRAC` (F) | {F} | fraction bits of cos θ and of the output; 1.0 = 2^F = 0x{one:x} |
| `GUARD` (G) | {G} | extra fraction bits through the cs16 squarings (unused by the Schlick units) |
| `CUTOFF` | {cut} | `{cutname}` (cs16 only) |
| `TAGW` | {tagw} | width of the opaque tag |
| `NORM` | {norm} | energy normalisation after the unit: {normlabel} |
| `COEFW` | {coefw} | coefficient width (8 integer + F fraction bits), used with `NORM` = 1 |

All of them are fixed in `rtl/{top}.v`; the RTL needs no parameter overrides. Files: `filelist.f`
(`+incdir+rtl` for `sc_variants.vh`), plain Verilog-2005 (Icarus `-g2005`, Verilator, Yosys). `rtl/` holds
only the units this configuration uses: with Yosys read it with `read_verilog -defer` (as
`reports/yosys_synth.ys` does), otherwise Yosys also elaborates `sc_specular` with its default parameters,
which name a unit that is not in the bundle. Tools that elaborate from the top (Icarus, Verilator, most
synthesis tools) need nothing special.

## Ports

All synchronous to the rising edge of `clk_i`.

{ports}
## Number formats

- 1.0 is the code 2^F = 0x{one:x} ({onedec}) on `in_cos_i`, `out_spec_o`, `mat_thr_i` and `mat_coef_i`.
- `in_cos_i`: {inw}-bit two's complement: bit {sign} is the sign bit, bit {F} the integer bit, bits {Fm1}..0 the
  fraction; range [−2, 2 − 2^−{F}]. Codes below 0 are treated as 0 (output 0); codes above 2^F as 1.0
  (output 2^F); nothing wraps.
- `out_spec_o`: {outdesc}
- `mat_n_i`: unsigned integer n, 16 ≤ n ≤ 1024 (other values are outside the contract).
{thrline}{coefline}
| n | `mat_n_i` | `mat_thr_i` | `mat_coef_i` |
|---|---|---|---|
{examples}
(`shadecore eval --variant {vname} ... --n N --code 0` prints the material words for any n.)

## Handshake

AXI-Stream style valid/ready on both sides. A fragment is transferred at a rising edge where
`in_valid_i` and `in_ready_o` are both high; a result at a rising edge where `out_valid_o` and
`out_ready_i` are both high. {ready}: the path `out_ready_i` → `in_ready_o` is combinational (ready may
depend on ready; no valid depends on a ready). While `out_valid_o` is high and `out_ready_i` low the
result holds: `out_spec_o` and `out_tag_o` do not change until it is taken. Results leave in the order
the fragments came in, each with its `in_tag_i` on `out_tag_o`.

## Reset

`rst_ni` is synchronous and active low (sampled at the rising edge). An edge with `rst_ni` low clears
every valid bit: fragments in flight are dropped and `out_valid_o` is low afterwards. `in_ready_o` is
low while `rst_ni` is low, so nothing is accepted during reset (a fragment waiting on the input goes in
afterwards). A result taken at a reset edge (`out_valid_o` & `out_ready_i` before it) counts as
transferred. The material registers are **not** reset: they keep their values through a reset, and
`mat_we_i` loads them also while `rst_ni` is low. Data registers are not reset either (the valid bits
qualify them). After power-up hold `rst_ni` low for at least one rising edge.

## Latency and throughput

- Latency: {lat}
- Throughput: {thru}.

## Programming sequence

1. Hold `rst_ni` low for at least one rising edge, then high.
2. Load a material: drive `mat_n_i`{matports} and pulse `mat_we_i` high for one rising edge (before the
   first fragment: the material registers power up undefined).
3. Stream fragments (`in_cos_i`, `in_tag_i`, `in_valid_i`); take results (`out_ready_i`).
4. To change the material, repeat step 2 at any time. A fragment accepted at the write edge still uses
   the old material; fragments accepted at later edges use the new one. Fragments already in flight are
   never affected (n{thrflow} travel with each fragment). No draining is needed.

## Error contract

{contract}
## Verification in this bundle

- `vectors/hard.hex` ({nhard} vectors: input extremes, 1.0 ± 2, thr ± 2, the base zero ± 2, for 12
  exponents) and `vectors/random.hex` ({nrand} vectors, seed {seed}): stimulus and expected results from
  the C model (`shadecore vectors`; format in each file's header: N THR COEF COS EXPECTED, hex).
- `tb/tb_shadecore.v`: plain Verilog-2005 self-checking testbench (value, order, latency, output
  stability; material writes at the edge that takes the previous fragment and during a reset in the
  middle of the stream; random input gaps and output backpressure from `+seed=`); prints one
  `PASS <n> vectors` or `FAIL ...` line and exits non-zero on failure.
- `./run_icarus.sh` and `./run_verilator.sh` (`SEED=`, `IN_GAP=`, `OUT_STALL=`, `RESET_AT=` to vary):
  exit 0 only on PASS. Their results at generation time, the lint and the synthesis reports: `reports/`.
- `sha256sum -c MANIFEST.sha256` checks that no file changed.

## Timing constraints

`constraints.sdc`: one clock on `clk_i` ({period}), input and output delays of 30 % of the period as
stated assumptions. Every path is register to register except `out_ready_i` → `in_ready_o`.
)",
      fmt::arg("top", b.top), fmt::arg("vname", s.variant_name), fmt::arg("cfg", s.config_name),
      fmt::arg("cmd", command_line()), fmt::arg("date", utc_now()), fmt::arg("vid", static_cast<int>(s.variant)),
      fmt::arg("F", f.frac), fmt::arg("Fm1", f.frac - 1), fmt::arg("G", f.guard), fmt::arg("one", f.one()),
      fmt::arg("onedec", f.one()), fmt::arg("cut", static_cast<int>(s.cutoff)), fmt::arg("cutname", to_string(s.cutoff)),
      fmt::arg("tagw", b.tagw), fmt::arg("norm", s.norm ? 1 : 0), fmt::arg("normlabel", s.norm_label()),
      fmt::arg("coefw", s.coef_bits()), fmt::arg("ports", concrete_port_table(b.ports)), fmt::arg("inw", f.in_bits()),
      fmt::arg("sign", f.frac + 1),
      fmt::arg("outdesc", s.norm ? fmt::format("{} bits unsigned, 8 integer and {} fraction bits (the normalised term; "
                                               "< 256)", s.coef_bits(), f.frac)
                                 : fmt::format("{} bits unsigned, 1 integer and {} fraction bits, ≤ 2^F", f.frac + 1, f.frac)),
      fmt::arg("thrline", s.uses_thr() ? fmt::format("- `mat_thr_i`: thr(n) = ⌈cos(6/√n)·2^F⌉ evaluated in IEEE double "
                                                     "(the smallest code with cos ≥ cos θcr; never within 10⁻⁶ of an "
                                                     "integer, so any libm gives the same code), {} bits unsigned. A "
                                                     "fragment is cut to 0 when its clamped code is below thr.\n",
                                                     f.frac + 1)
                                       : ""),
      fmt::arg("coefline", s.norm ? fmt::format("- `mat_coef_i`: ⌊coef(n)·2^F + ½⌋ for the material's energy-normalisation "
                                                "coefficient coef(n) (docs/spec.md §7: (a·n + b)/(k·π) fitted, or the "
                                                "classical closed forms), {} bits unsigned; the hardware takes any code. "
                                                "This bundle's vectors: {}.\n",
                                                s.coef_bits(), s.norm_label())
                                  : ""),
      fmt::arg("examples", examples), fmt::arg("ready", ready), fmt::arg("lat", lat), fmt::arg("thru", thru),
      fmt::arg("matports", std::string(s.uses_thr() ? ", `mat_thr_i`" : "") + (s.norm ? ", `mat_coef_i`" : "")),
      fmt::arg("thrflow", std::string(s.uses_thr() ? ", thr" : "") + (s.norm ? " and the coefficient" : "")),
      fmt::arg("contract", error_contract(s)), fmt::arg("nhard", b.n_hard), fmt::arg("nrand", b.n_random),
      fmt::arg("seed", b.seed),
      fmt::arg("period", b.fmax_mhz > 0 ? fmt::format("{:.1f} ns from the measured {:.2f} MHz", std::ceil(10000.0 / b.fmax_mhz) / 10.0, b.fmax_mhz)
                                        : "20 ns placeholder: no measured Fmax"));
}

std::string bundle_readme(const Bundle& b) {
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
      fmt::arg("top", b.top), fmt::arg("desc", b.spec.describe()), fmt::arg("cmd", command_line()),
      fmt::arg("date", utc_now()), fmt::arg("icarus", b.icarus_line), fmt::arg("verilator", b.verilator_line));
}

std::string last_line_with(const std::string& out, const std::string& needle) {
  std::stringstream ss(out);
  std::string line, found;
  while (std::getline(ss, line))
    if (line.find(needle) != std::string::npos) found = line;
  return found;
}

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

// ---------------------------------------------------------------------------- reports
void report_lint(Bundle& b, const fs::path& dir) {
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

void report_yosys(Bundle& b, const fs::path& dir) {
  std::string files;
  for (const auto& f : b.rtl_files) files += " " + f;
  const std::string script = fmt::format(
      "# Yosys generic synthesis of the bundle (technology independent): cells, flip-flops, logic depth.\n"
      "read_verilog -defer -Irtl{files}\n"
      "hierarchy -check -top {top}\n"
      "synth -flatten -top {top}\n"
      "check -assert\n"
      "dffunmap\n"
      "tee -o /dev/stdout stat\n"
      "tee -o /dev/stdout ltp -noff\n",
      fmt::arg("files", files), fmt::arg("top", b.top));
  write_text(dir / "reports" / "yosys_synth.ys", script);
  const std::vector<std::string> cmd = {"yosys", "-q", "-s", "reports/yosys_synth.ys"};
  const Proc r = run_proc(cmd, dir);
  std::string cells = "?", depth = "?";
  long ffs = 0;
  {
    static const std::regex re_cells(R"(Number of cells:\s+(\d+))"), re_ff(R"(\$_S?DFFE?_\w+\s+(\d+))"),
        re_depth(R"(Longest topological path in \S+ \(length=(\d+)\))");
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), re_cells); it != std::sregex_iterator(); ++it)
      cells = (*it)[1];
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), re_ff); it != std::sregex_iterator(); ++it)
      ffs += std::stol((*it)[1]);
    for (auto it = std::sregex_iterator(r.out.begin(), r.out.end(), re_depth); it != std::sregex_iterator(); ++it)
      depth = (*it)[1];
  }
  b.synth_cells = cells;
  b.synth_ffs = std::to_string(ffs);
  b.synth_depth = depth;
  write_text(dir / "reports" / "yosys_synth.log",
             report_header("Yosys generic synthesis (synth -flatten; dffunmap; stat; ltp -noff)", shell_join(cmd),
                           tool_version({"yosys", "-V"})) +
                 fmt::format("# summary: {} cells, {} flip-flops, logic depth {} (longest path, flip-flops excluded)\n\n",
                             cells, ffs, depth) +
                 r.out + fmt::format("# exit status {}\n", r.status));
  if (r.status != 0)
    throw std::runtime_error("Yosys synthesis of the bundle failed (reports/yosys_synth.log): " +
                             last_line_with(r.out, "ERROR"));
}

void report_ice40(Bundle& b, const fs::path& dir, bool skip) {
  const fs::path log = dir / "reports" / "ice40.log";
  const bool have = on_path("nextpnr-ice40") && on_path("icetime");
  if (skip || !have) {
    b.ice40_status = skip ? "not run (--no-ice40)" : "not run: nextpnr-ice40 / icetime not installed";
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

std::string summary_md(const Bundle& b) {
  return fmt::format(
      "# Reports: `{top}` ({desc})\n\n"
      "Generated by `{cmd}` on {date}.\n\n"
      "| check | result | log (with its command) |\n|---|---|---|\n"
      "| Verilator lint `-Wall` | {lint} | `verilator_lint.log` |\n"
      "| Yosys generic synthesis | {cells} cells, {ffs} flip-flops, logic depth {depth} | `yosys_synth.log` (`yosys -s yosys_synth.ys`) |\n"
      "| iCE40 | {ice40} | `ice40.log` |\n"
      "| Icarus simulation | {icarus} | `sim_icarus.log` |\n"
      "| Verilator simulation | {verilator} | `sim_verilator.log` |\n\n"
      "Clock target in `constraints.sdc`: {fmax}.\n",
      fmt::arg("top", b.top), fmt::arg("desc", b.spec.describe()), fmt::arg("cmd", command_line()),
      fmt::arg("date", utc_now()), fmt::arg("lint", b.lint_status), fmt::arg("cells", b.synth_cells),
      fmt::arg("ffs", b.synth_ffs), fmt::arg("depth", b.synth_depth), fmt::arg("ice40", b.ice40_status),
      fmt::arg("icarus", b.icarus_line), fmt::arg("verilator", b.verilator_line),
      fmt::arg("fmax", b.fmax_source.empty() ? "no measured Fmax (20 ns placeholder)" : b.fmax_source));
}

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

// ---------------------------------------------------------------------------- the command
void run(HandoffArgs& a) {
  if (a.print_port_table) {
    fmt::print("{}", generic_port_table());
    return;
  }
  // ---- validate everything before doing anything
  if (a.core == "lighting")
    throw std::invalid_argument("--core lighting is not available yet (the lighting core is not in this tree); use --core specular");
  if (a.core != "specular") throw std::invalid_argument("unknown --core '" + a.core + "' (known: specular)");
  if (!a.features.empty()) throw std::invalid_argument("--features applies to --core lighting only");
  const UnitSpec spec = resolve_unit(*a.unit);
  if (is_table_variant(spec.variant))
    throw std::invalid_argument("handoff does not support the table variant " + spec.variant_name +
                                " yet (the bundle's testbench cannot load the table RAM); use shadecore cosim");
  if (a.out.empty()) throw std::invalid_argument("--out DIR is required");
  if (a.tagw < 1 || a.tagw > 32) throw std::invalid_argument("--tagw must be in 1..32");
  if (a.count < 1 || a.count > 1'000'000) throw std::invalid_argument("--count must be in 1..1000000");
  static const std::regex ident(R"(^[A-Za-z_][A-Za-z0-9_]{0,62}$)");
  if (!std::regex_match(a.top, ident)) throw std::invalid_argument("--top '" + a.top + "' is not a Verilog identifier");
  if (a.top.rfind("sc_", 0) == 0 || a.top == "tb_shadecore")
    throw std::invalid_argument("--top '" + a.top + "' clashes with the bundle's module names (sc_*, tb_shadecore)");
  for (const char* tool : {"iverilog", "vvp", "verilator", "yosys", "tar", "gzip"})
    if (!on_path(tool)) throw std::runtime_error(std::string("'") + tool + "' not found on PATH (scripts/setup.sh installs it)");
  const fs::path root = root_dir();
  for (const char* f : {"handoff/tb/tb_shadecore.v", "handoff/run_icarus.sh", "handoff/run_verilator.sh", "rtl/sc_specular.v"})
    if (!fs::exists(root / f)) throw std::runtime_error("shadecore source file " + (root / f).string() + " not found (SHADECORE_ROOT)");

  // Destination: a symlink to a directory is followed (the link stays); a non-directory is refused.
  std::string out_text = a.out;
  while (out_text.size() > 1 && out_text.back() == '/') out_text.pop_back();
  const fs::path given = fs::path(out_text).lexically_normal();
  std::error_code ec;
  fs::path dest = given;
  if (fs::is_symlink(fs::symlink_status(given, ec))) {
    dest = fs::canonical(given, ec);
    if (ec || !fs::is_directory(dest)) throw std::runtime_error("--out " + a.out + " is a symlink that does not lead to a directory");
  }
  const bool dest_exists = fs::exists(fs::symlink_status(dest, ec));
  if (dest_exists && !fs::is_directory(fs::symlink_status(dest, ec)))
    throw std::runtime_error("--out " + a.out + " exists and is not a directory");
  if (dest_exists && !fs::is_empty(dest, ec) && !a.force)
    throw std::runtime_error("--out " + a.out + " is not empty (use --force to replace its contents)");
  if (dest == fs::current_path().lexically_normal() || dest.filename().empty() || dest.filename() == "..")
    throw std::runtime_error("--out " + a.out + " cannot be used as a bundle directory");
  const std::string tar_path = given.string() + ".tar.gz";
  if (fs::exists(fs::symlink_status(tar_path, ec))) {
    if (!a.force) throw std::runtime_error(tar_path + " exists (use --force to replace it)");
  }
  fs::path parent = fs::absolute(dest).parent_path();
  // Missing parents are created, and removed again if the run fails.
  std::vector<fs::path> created;
  for (fs::path p = parent; !p.empty() && !fs::exists(p); p = p.parent_path()) created.push_back(p);
  std::reverse(created.begin(), created.end());

  const uint64_t seed = a.seed != 0 ? a.seed : pick_seed();
  if (seed > 0x7fffffffull) throw std::invalid_argument("--seed must be in 1..2147483647 (the testbench's +seed= is 32-bit)");

  SignalGuard guard;
  g_signal = 0;
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
    auto step = [&](const std::string& what) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print("handoff: [{:5.1f} s] {}\n", s, what);
      std::fflush(stdout);
    };

    Bundle b;
    b.spec = spec;
    b.tagw = a.tagw;
    b.top = a.top;
    b.seed = seed;
    b.ports = concrete_ports(load_ports(), spec, a.tagw);
    const Unit unit = spec.unit();
    b.latency = unit.latency();
    b.latency_min = unit.latency_min();
    step("bundle for " + spec.describe() + fmt::format(", top {}, TAGW {}, seed {}", b.top, b.tagw, b.seed));

    // rtl/
    fs::create_directories(dir / "rtl");
    for (const auto& f : unit_files(spec)) {
      fs::copy_file(root / "rtl" / f, dir / "rtl" / f, fs::copy_options::none);
      b.rtl_files.push_back("rtl/" + f);
    }
    fs::copy_file(root / "rtl" / "sc_variants.vh", dir / "rtl" / "sc_variants.vh");
    write_text(dir / "rtl" / (b.top + ".v"), wrapper_v(b));
    b.rtl_files.push_back("rtl/" + b.top + ".v");
    write_text(dir / "filelist.f", filelist(b));

    // vectors/ (the C model, as `shadecore vectors`)
    VectorRequest hard;
    hard.mode = "hard";
    const auto vh = make_vectors(spec, hard);
    VectorRequest rnd;
    rnd.mode = "random";
    rnd.count = a.count;
    rnd.seed = seed;
    const auto vr = make_vectors(spec, rnd);
    write_text(dir / "vectors" / "hard.hex", format_vectors(spec, hard, vh));
    write_text(dir / "vectors" / "random.hex", format_vectors(spec, rnd, vr));
    b.n_hard = vh.size();
    b.n_random = vr.size();
    step(fmt::format("vectors: {} hard cases, {} random (seed {})", vh.size(), vr.size(), seed));

    // tb/, scripts
    fs::create_directories(dir / "tb");
    fs::copy_file(root / "handoff" / "tb" / "tb_shadecore.v", dir / "tb" / "tb_shadecore.v");
    write_text(dir / "tb" / "tb_config.vh", tb_config_vh(b, std::max(vh.size(), vr.size())));
    write_text(dir / "tb" / "tb_dut.vh", tb_dut_vh(b));
    write_text(dir / "run_icarus.sh", read_text(root / "handoff" / "run_icarus.sh"), true);
    write_text(dir / "run_verilator.sh", read_text(root / "handoff" / "run_verilator.sh"), true);

    // reports/ and the measured Fmax, then the constraints that use it
    recorded_fmax(b);
    report_lint(b, dir);
    step("Verilator lint -Wall: " + b.lint_status);
    report_yosys(b, dir);
    step(fmt::format("Yosys: {} cells, {} flip-flops, depth {}", b.synth_cells, b.synth_ffs, b.synth_depth));
    report_ice40(b, dir, a.no_ice40);
    step("iCE40: " + b.ice40_status);
    write_text(dir / "constraints.sdc", sdc(b));
    write_text(dir / "interface.md", interface_md(b));

    // Both simulators on the bundle as it will be delivered.
    b.icarus_line = run_sim(dir, "run_icarus.sh", "sim_icarus.log");
    step(b.icarus_line);
    b.verilator_line = run_sim(dir, "run_verilator.sh", "sim_verilator.log");
    step(b.verilator_line);
    write_text(dir / "reports" / "summary.md", summary_md(b));
    write_text(dir / "README.md", bundle_readme(b));
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
    if (g_signal) {  // interrupted: nothing is left behind; end the way the signal would have
      const int sig = g_signal;
      guard.restore();
      fmt::print(stderr, "shadecore: error: handoff interrupted by signal {}; nothing written\n", sig);
      ::signal(sig, SIG_DFL);
      ::raise(sig);
    }
    throw;
  }
}

}  // namespace

void add_handoff(CLI::App& app) {
  auto a = std::make_shared<HandoffArgs>();
  auto* sub = app.add_subcommand("handoff", "Write a self-contained RTL bundle (RTL, constraints, interface, vectors, "
                                            "testbench, run scripts, reports, manifest) and a tarball of it");
  add_unit_options(sub, a->unit);
  sub->add_option("--out", a->out, "Bundle directory (refused if not empty, unless --force); DIR.tar.gz beside it");
  sub->add_flag("--force", a->force, "Replace the contents of a non-empty --out and an existing DIR.tar.gz");
  sub->add_option("--tagw", a->tagw, "Tag width TAGW of the wrapper top (1..32, default 8)");
  sub->add_option("--seed", a->seed, "Seed of the random vectors and of the testbench's gaps/backpressure (default: picked)");
  sub->add_option("--count", a->count, "Random vectors (default 2000)");
  sub->add_option("--top", a->top, "Module name of the wrapper top (default shadecore_top)");
  sub->add_flag("--no-ice40", a->no_ice40, "Skip iCE40 place and route even where nextpnr-ice40/icetime are installed");
  sub->add_option("--core", a->core, "Which core: specular (default); lighting is not available yet");
  sub->add_option("--features", a->features, "Lighting core feature set (with --core lighting; not available yet)");
  sub->add_flag("--print-port-table", a->print_port_table,
                "Print the port table of sc_specular from config/interface.json (the README's table) and exit");
  sub->callback([a] { run(*a); });
}

}  // namespace shadecore::cli
