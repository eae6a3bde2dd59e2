// shadecore sim — speed reference: the same sc_specular (cs16, default config, CUTOFF 0) Verilated
// WITHOUT SystemC, driven by a plain C++ loop (no scheduler, no signals): one eval per clock edge,
// in_valid_i and out_ready_i always high, exhaustive codes for an n range. With --check each output
// is compared with the C model, exactly as the SystemC scoreboard does (minus tags and latency).
//
//   shadecore_bare_default [--n LO..HI] [--no-check]
#include <verilated.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

#include "Vbare_cs16.h"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"

int main(int argc, char** argv) {
  using namespace shadecore;
  int n_lo = 16, n_hi = 1024;
  bool check = true;
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--n") && i + 1 < argc) {
      const std::string s = argv[++i];
      const auto d = s.find("..");
      n_lo = std::stoi(s.substr(0, d));
      n_hi = d == std::string::npos ? n_lo : std::stoi(s.substr(d + 2));
    } else if (!std::strcmp(argv[i], "--no-check")) {
      check = false;
    } else {
      std::fprintf(stderr, "usage: %s [--n LO..HI] [--no-check]\n", argv[0]);
      return 2;
    }
  }
  Format f{};
  for (const auto& c : kConfigs)
    if (c.name == SHADECORE_BARE_CONFIG) f = c.format;
  const Unit unit(VariantId::cs16, f, Cutoff::ThetaCr);
  const int L = unit.latency();

  VerilatedContext ctx;
  Vbare_cs16 top{&ctx};
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
  uint32_t exp_ring[16] = {};
  uint64_t sent = 0, got = 0, mismatches = 0, cycles = 0;
  // One clock: take the output visible before the edge (out_ready_i is always 1), then the edge.
  auto step = [&]() {
    if (top.out_valid_o) {
      if (check && top.out_spec_o != exp_ring[got & 15]) ++mismatches;
      ++got;
    }
    tick();
    ++cycles;
  };
  const uint32_t mask = (uint32_t{1} << f.in_bits()) - 1;
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = n_lo; n <= n_hi; ++n) {
    const UnitMaterial m = unit.setup(n);
    top.mat_we_i = 1;  // written with a bubble, like the SystemC driver
    top.mat_n_i = static_cast<uint32_t>(m.n);
    top.mat_thr_i = m.thr;
    top.in_valid_i = 0;
    step();
    top.mat_we_i = 0;
    for (int64_t code = 0; code <= f.one(); ++code) {
      top.in_valid_i = 1;
      top.in_cos_i = static_cast<uint32_t>(code) & mask;
      top.in_tag_i = static_cast<uint32_t>(sent);
      if (check) exp_ring[sent & 15] = unit.eval(m, code);
      step();
      ++sent;
    }
  }
  top.in_valid_i = 0;
  for (int i = 0; i <= L + 1; ++i) step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  top.final();
  std::printf("bare: config %s n %d..%d: %llu sent, %llu out, %llu mismatches%s, %llu cycles, %.3f s, "
              "%.0f vectors/s, %.0f cycles/s\n",
              SHADECORE_BARE_CONFIG, n_lo, n_hi, (unsigned long long)sent, (unsigned long long)got,
              (unsigned long long)mismatches, check ? "" : " (not checked)", (unsigned long long)cycles, wall,
              got / wall, cycles / wall);
  return (got == sent && mismatches == 0) ? 0 : 1;
}
