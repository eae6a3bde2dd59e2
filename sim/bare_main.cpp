// SPDX-License-Identifier: Apache-2.0
// shadecore sim — speed reference: the same sc_specular (cs16, default config, CUTOFF 0) Verilated
// WITHOUT SystemC, driven by a plain C++ loop (no scheduler, no signals): one eval per clock edge,
// in_valid_i and out_ready_i always high, exhaustive codes for an n range. With --check each output
// is compared with the C model, exactly as the SystemC scoreboard does (minus tags and latency).
//
//   shadecore_bare_default [--n LO..HI] [--all-codes] [--no-check] [--progress | --no-progress] [--coverage FILE]
//
// --all-codes: every F+2-bit input code (negative ones and those above 1.0 too, which the input clamp maps to 0
// and 1.0), not only 0..2^F — the whole input domain of the unit (scripts/mutation.py's exhaustive stage).
//
// Exit status (docs/cli.md): 0 every output checked and equal (and at least one checked); 2 the run
// completed with a mismatch or a missing output (or nothing checked); 1 a bad argument (one line).
#include <verilated.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "Vbare_cs16.h"
#include "tb_coverage.hpp"
#include "tb_func_cov.hpp"
#include "shadecore/common/args.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"

int main(int argc, char** argv) {
  using namespace shadecore;
  std::string prog = argv[0];
  if (const auto slash = prog.rfind('/'); slash != std::string::npos) prog = prog.substr(slash + 1);
  const auto usage_error = [&](const std::string& msg) {
    std::fprintf(stderr, "%s: error: %s (usage: %s [--n LO..HI] [--all-codes] [--no-check] [--progress|--no-progress] [--coverage FILE])\n",
                 prog.c_str(), msg.c_str(), prog.c_str());
    return 1;
  };
  int n_lo = 16, n_hi = 1024;
  bool check = true, force_progress = false, no_progress = false, all_codes = false;
  std::string coverage;  // the coverage build's database (sim/unit_core; tb_coverage.hpp)
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--n")) {
      if (i + 1 >= argc) return usage_error("--n needs a value");
      try {
        std::tie(n_lo, n_hi) = cliargs::parse_n_range(argv[++i]);
      } catch (const std::exception& e) {
        return usage_error(std::string("--n: ") + e.what());
      }
    } else if (!std::strcmp(argv[i], "--coverage")) {
      if (i + 1 >= argc || !*argv[i + 1]) return usage_error("--coverage needs a path");
      coverage = argv[++i];
      if (const std::string e = shadecore::sim::coverage_option_error(coverage); !e.empty()) return usage_error(e);
    } else if (!std::strcmp(argv[i], "--all-codes")) {
      all_codes = true;
    } else if (!std::strcmp(argv[i], "--no-check")) {
      check = false;
    } else if (!std::strcmp(argv[i], "--progress")) {
      force_progress = true;
    } else if (!std::strcmp(argv[i], "--no-progress")) {
      no_progress = true;
    } else if (!std::strcmp(argv[i], "--help") || !std::strcmp(argv[i], "-h")) {
      std::printf("usage: %s [--n LO..HI] [--all-codes] [--no-check] [--progress|--no-progress] [--coverage FILE]\n"
                  "cs16 (theta_cr) Verilated without SystemC, every code of every n in LO..HI (default 16..1024),\n"
                  "each output compared with the C model unless --no-check; --all-codes: every F+2-bit input code\n"
                  "(negative and above 1.0 too), not only 0..2^F.\n",
                  prog.c_str());
      return 0;
    } else {
      return usage_error(std::string("unknown argument '") + argv[i] + "'");
    }
  }
  if (force_progress && no_progress) return usage_error("--progress and --no-progress exclude each other");
  Format f{};
  for (const auto& c : kConfigs)
    if (c.name == SHADECORE_BARE_CONFIG) f = c.format;
#ifndef SHADECORE_BARE_MREG
#define SHADECORE_BARE_MREG 0
#endif
#ifndef SHADECORE_BARE_VARIANT
#define SHADECORE_BARE_VARIANT 0  // cs16 (the -GVARIANT of this build)
#endif
  constexpr auto kVariant = static_cast<VariantId>(SHADECORE_BARE_VARIANT);
  Unit unit(kVariant, f, Cutoff::ThetaCr);
  unit.set_mreg(SHADECORE_BARE_MREG);  // the model's MREG (-GMREG of this build): the latency follows it
  const int L = unit.latency();

  VerilatedContext ctx;
  Vbare_cs16 top{&ctx};
  // Coverage builds with --coverage: the functional model samples every input (tb_func_cov.hpp).
  shadecore::sim::UnitFuncCov fcov(unit);
  const bool sampling = shadecore::sim::kCoverageBuild && !coverage.empty();
  if (sampling) fcov.attach(&ctx);
  auto tick = [&]() {
    top.clk_i = 0;
    top.eval();
    top.clk_i = 1;
    top.eval();
  };
  top.rst_ni = 0;
  top.in_valid_i = 0;
  top.out_ready_i = 1;
  tick();
  tick();
  top.rst_ni = 1;

  // Expected values in flight (ring of size > latency), no allocation in the loop.
  // Each input's accepting cycle too: with out_ready_i high throughout, the output is due exactly L cycles later.
  constexpr uint64_t kRing = 64;  // > every latency a bare model is built with (schlick_div at F = 24 + MREG: 29)
  uint32_t exp_ring[kRing] = {};
  uint64_t cyc_ring[kRing] = {};
  int64_t in_ring[kRing] = {};   // the input code and n of each output (the first mismatch is named)
  int n_ring[kRing] = {};
  int64_t bad_code = 0;
  int bad_n = 0;
  uint32_t bad_exp = 0, bad_got = 0;
  if (L >= static_cast<int>(kRing)) return usage_error("latency " + std::to_string(L) + " exceeds the harness's ring");
  uint64_t sent = 0, got = 0, mismatches = 0, cycles = 0, late = 0;
  // One clock: take the output visible before the edge (out_ready_i is always 1), then the edge.
  auto step = [&]() {
    if (sampling)  // always ready on both sides: the transfer and reset bins only
      fcov.sample_edge({top.rst_ni != 0, top.in_valid_i != 0, true, top.out_valid_o != 0, true, sent - got});
    if (top.out_valid_o) {
      if (check && top.out_spec_o != exp_ring[got % kRing] && mismatches++ == 0) {
        bad_code = in_ring[got % kRing];
        bad_n = n_ring[got % kRing];
        bad_exp = exp_ring[got % kRing];
        bad_got = top.out_spec_o;
      }
      if (cycles != cyc_ring[got % kRing] + static_cast<uint64_t>(L)) ++late;
      ++got;
    }
    tick();
    ++cycles;
  };
  const uint32_t mask = (uint32_t{1} << f.in_bits()) - 1;
  const int64_t code_lo = all_codes ? -(int64_t{1} << (f.in_bits() - 1)) : 0;
  const int64_t code_hi = all_codes ? (int64_t{1} << (f.in_bits() - 1)) - 1 : f.one();
  io::Progress bar(static_cast<uint64_t>(n_hi - n_lo + 1) * static_cast<uint64_t>(code_hi - code_lo + 1),
                   io::progress_wanted(force_progress, no_progress), "bare");
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = n_lo; n <= n_hi; ++n) {
    bar.set(sent);
    const UnitMaterial m = unit.setup(n);
    top.mat_we_i = 1;  // written with a bubble, like the SystemC driver
    top.mat_n_i = static_cast<uint32_t>(m.n);
    top.mat_thr_i = m.thr;
    top.in_valid_i = 0;
    step();
    top.mat_we_i = 0;
    for (int64_t code = code_lo; code <= code_hi; ++code) {
      top.in_valid_i = 1;
      top.in_cos_i = static_cast<uint32_t>(code) & mask;
      top.in_tag_i = static_cast<uint32_t>(sent);
      if (check) exp_ring[sent % kRing] = unit.eval(m, code);
      if (sampling) fcov.sample(m, code);
      cyc_ring[sent % kRing] = cycles;
      in_ring[sent % kRing] = code;
      n_ring[sent % kRing] = n;
      step();
      ++sent;
    }
  }
  top.in_valid_i = 0;
  for (int i = 0; i <= L + 1; ++i) step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  bar.stop();
  top.final();
  try {
    shadecore::sim::write_coverage(&ctx, coverage);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", prog.c_str(), e.what());
    return 1;
  }
  std::printf("bare: %s config %s MREG %d n %d..%d%s: %llu sent, %llu out, %llu mismatches%s, %llu off latency %d, "
              "%llu cycles, %.3f s, %.0f vectors/s, %.0f cycles/s\n",
              std::string(variant_name(kVariant)).c_str(), SHADECORE_BARE_CONFIG, SHADECORE_BARE_MREG, n_lo, n_hi,
              all_codes ? " every input code" : "", (unsigned long long)sent, (unsigned long long)got,
              (unsigned long long)mismatches, check ? "" : " (not checked)", (unsigned long long)late, L,
              (unsigned long long)cycles, wall, got / wall, cycles / wall);
  if (mismatches > 0)
    std::printf("bare: first mismatch: n %d code %lld (0x%llx) expected 0x%x got 0x%x\n", bad_n, (long long)bad_code,
                (unsigned long long)(static_cast<uint64_t>(bad_code) & mask), bad_exp, bad_got);
  // A run that compared nothing is not a pass; --no-check (a speed run) still needs every output.
  const bool ok = got == sent && got > 0 && late == 0 && (!check || mismatches == 0);
  std::printf("bare: %s%s\n", ok ? "PASS" : "FAIL", check ? "" : " (outputs counted, not compared: --no-check)");
  return ok ? 0 : 2;
}
