// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — the files every bundle has, whichever core it delivers (cli/handoff_bundle.hpp):
// rtl/ with filelist.f, tb/ with the run scripts and LICENSE, constraints.sdc, README.md and
// reports/summary.md (their text: cli/templates/handoff/), the concrete port table.
#include <cmath>

#include <fmt/core.h>

#include "handoff_bundle.hpp"
#include "output.hpp"
#include "text_template.hpp"

namespace shadecore::cli::handoff {

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

void require_sources(const std::vector<std::string>& files) {
  const fs::path root = root_dir();
  for (const auto& f : files)
    if (!fs::exists(root / f)) throw std::runtime_error("shadecore source file " + (root / f).string() + " not found (SHADECORE_ROOT)");
}

void write_rtl(BundleBase& b, const fs::path& dir, const std::vector<std::string>& files,
               const std::vector<std::string>& includes, const std::string& wrapper) {
  const fs::path root = root_dir();
  fs::create_directories(dir / "rtl");
  for (const auto& f : files) {
    fs::copy_file(root / "rtl" / f, dir / "rtl" / f, fs::copy_options::none);
    b.rtl_files.push_back("rtl/" + f);
  }
  for (const auto& inc : includes) fs::copy_file(root / "rtl" / inc, dir / "rtl" / inc);
  write_text(dir / "rtl" / (b.top + ".v"), wrapper);
  b.rtl_files.push_back("rtl/" + b.top + ".v");
  write_text(dir / "filelist.f", filelist(b));
}

void write_testbench(const BundleBase& b, const fs::path& dir, const std::string& tb_config, const std::string& tb_dut) {
  const fs::path root = root_dir();
  fs::create_directories(dir / "tb");
  fs::copy_file(root / "handoff" / "tb" / (b.tb + ".v"), dir / "tb" / (b.tb + ".v"));
  fs::copy_file(root / "handoff" / "tb" / "tb_common.vh", dir / "tb" / "tb_common.vh");
  fs::copy_file(root / "LICENSE", dir / "LICENSE");  // Apache-2.0: every file of the bundle carries its SPDX line
  write_text(dir / "tb" / "tb_config.vh", tb_config);
  write_text(dir / "tb" / "tb_dut.vh", tb_dut);
  write_run_scripts(b, dir);
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
  return fill_template("handoff/constraints.sdc",
                       {{"top", b.top},
                        {"desc", b.desc},
                        {"why", why},
                        {"period", fmt::format("{:.1f}", period)},
                        {"ins", ins},
                        {"outs", outs},
                        {"comb", b.comb_paths.empty() ? "out_ready_i -> in_ready_o is a" : b.comb_paths + " are"}});
}

std::string bundle_readme(const BundleBase& b) {
  return fill_template("handoff/README.md", {{"top", b.top},
                                             {"desc", b.desc},
                                             {"cmd", command_line()},
                                             {"date", utc_now()},
                                             {"icarus", b.icarus_line},
                                             {"verilator", b.verilator_line}});
}

std::string summary_md(const BundleBase& b) {
  return fill_template("handoff/summary.md",
                       {{"top", b.top},
                        {"desc", b.desc},
                        {"cmd", command_line()},
                        {"date", utc_now()},
                        {"lint", b.lint_status},
                        {"synth", synth_summary(b)},
                        {"ice40", b.ice40_status},
                        {"icarus", b.icarus_line},
                        {"verilator", b.verilator_line},
                        {"signoff", b.signoff_status},
                        {"fmax", b.fmax_source.empty() ? "no measured Fmax (20 ns placeholder)" : b.fmax_source}});
}

}  // namespace shadecore::cli::handoff
