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
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <regex>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "handoff_bundle.hpp"
#include "output.hpp"
#include "rtl_files.hpp"
#include "unit_spec.hpp"

namespace fs = std::filesystem;

namespace shadecore::cli {
namespace {
using namespace handoff;

// ---------------------------------------------------------------------------- the port table
nlohmann::json load_ports() {
  const fs::path p = fs::path(root_dir()) / "config" / "interface.json";
  try {
    return nlohmann::json::parse(read_text(p)).at("ports");
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("malformed " + p.string() + ": " + e.what());
  }
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

// ---------------------------------------------------------------------------- bundle contents
struct HandoffArgs {
  std::shared_ptr<UnitOptions> unit = std::make_shared<UnitOptions>();
  Options light;  // --out, --force, --tagw, ... (shared by both cores)
  bool print_port_table = false;
  std::string core = "specular";
  CLI::App* sub = nullptr;
};

struct Bundle : BundleBase {
  UnitSpec spec;
  int tagw = 8;
  size_t n_hard = 0, n_random = 0;
};


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


// ---------------------------------------------------------------------------- the command
void run(HandoffArgs& ha) {
  Options& a = ha.light;
  if (ha.print_port_table) {
    fmt::print("{}", ha.core == "lighting" ? light_port_table() : generic_port_table());
    return;
  }
  // ---- validate everything before doing anything
  if (ha.core == "lighting") {
    // The feature set fixes the unit and the widths: the unit options do not apply.
    for (const char* opt : {"--variant", "--config", "--frac", "--guard", "--cutoff", "--norm", "--coef"})
      if (ha.sub->count(opt) > 0)
        throw std::invalid_argument(std::string(opt) + " does not apply to --core lighting (the feature set fixes the "
                                    "specular unit and the widths)");
    a.top_given = ha.sub->count("--top") > 0;
    a.count_given = ha.sub->count("--count") > 0;
    run_lighting(a);
    return;
  }
  if (ha.core != "specular") throw std::invalid_argument("unknown --core '" + ha.core + "' (known: specular, lighting)");
  if (!a.features.empty()) throw std::invalid_argument("--features applies to --core lighting only");
  const UnitSpec spec = resolve_unit(*ha.unit);
  if (is_table_variant(spec.variant))
    throw std::invalid_argument("handoff does not support the table variant " + spec.variant_name +
                                " yet (the bundle's testbench cannot load the table RAM); use shadecore cosim");
  if (a.out.empty()) throw std::invalid_argument("--out DIR is required");
  if (a.tagw < 1 || a.tagw > 32) throw std::invalid_argument("--tagw must be in 1..32");
  if (a.count < 1 || a.count > 1'000'000) throw std::invalid_argument("--count must be in 1..1000000");
  const SynthMode synth = parse_synth(a.synth, SynthMode::Flat);
  const std::string top = ha.sub->count("--top") > 0 ? a.top : "shadecore_top";
  check_top_name(top, "tb_shadecore");
  require_tools();
  const fs::path root = root_dir();
  for (const char* f : {"handoff/tb/tb_shadecore.v", "handoff/tb/tb_common.vh", "handoff/run_icarus.sh", "handoff/run_verilator.sh", "LICENSE", "rtl/sc_specular.v"})
    if (!fs::exists(root / f)) throw std::runtime_error("shadecore source file " + (root / f).string() + " not found (SHADECORE_ROOT)");
  const uint64_t seed = checked_seed(a.seed);

  make_bundle(a.out, a.force, [&](const fs::path& dir, const Step& step) {
    Bundle b;
    b.spec = spec;
    b.desc = spec.describe();
    b.tb = "tb_shadecore";
    b.tagw = a.tagw;
    b.top = top;
    b.seed = seed;
    b.synth = synth;
    b.synth_why = synth == SynthMode::Skipped ? "--synth skip" : synth == SynthMode::Hierarchical ? "--synth hier" : "";
    b.ports = concrete_ports(load_ports(), spec, a.tagw);
    const Unit unit = spec.unit();
    b.latency = unit.latency();
    b.latency_min = unit.latency_min();
    step("bundle for " + spec.describe() + fmt::format(", top {}, TAGW {}, seed {}", b.top, b.tagw, b.seed));

    // rtl/
    fs::create_directories(dir / "rtl");
    for (const auto& f : rtl::specular_files(spec.variant, spec.norm)) {
      fs::copy_file(root / "rtl" / f, dir / "rtl" / f, fs::copy_options::none);
      b.rtl_files.push_back("rtl/" + f);
    }
    for (const auto& inc : rtl::specular_includes()) fs::copy_file(root / "rtl" / inc, dir / "rtl" / inc);
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
    fs::copy_file(root / "handoff" / "tb" / "tb_common.vh", dir / "tb" / "tb_common.vh");
    fs::copy_file(root / "LICENSE", dir / "LICENSE");  // Apache-2.0: every file of the bundle carries its SPDX line
    write_text(dir / "tb" / "tb_config.vh", tb_config_vh(b, std::max(vh.size(), vr.size())));
    write_text(dir / "tb" / "tb_dut.vh", tb_dut_vh(b));
    write_run_scripts(b, dir);

    // reports/ and the measured Fmax, then the constraints that use it
    recorded_fmax(b);
    check_and_report(b, dir, a.no_ice40, step);
    write_text(dir / "constraints.sdc", sdc(b));
    write_text(dir / "interface.md", interface_md(b));
    simulate_and_summarise(b, dir, step);
  });
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
  sub->add_option("--synth", l.synth,
                  "Yosys generic synthesis: flat | hier (hierarchical, no flatten) | skip | auto (default: flat for "
                  "the specular unit; for the lighting core by size, docs/handoff.md)")->check(cliargs::NonEmpty("synthesis mode"));
  sub->add_option("--core", a->core, "Which core: specular (default) or lighting")->check(cliargs::NonEmpty("core"));
  sub->add_option("--features", l.features, "Lighting core feature set: a name of config/configs.json \"feature_sets\" "
                                            "or a JSON file (with --core lighting)")->check(cliargs::NonEmpty("feature set"));
  sub->add_flag("--print-port-table", a->print_port_table,
                "Print the port table of sc_specular (with --core lighting: sc_light) from config/interface.json and exit");
  sub->callback([a] { run(*a); });
}

}  // namespace shadecore::cli
