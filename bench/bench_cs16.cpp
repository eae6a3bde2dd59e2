// SPDX-License-Identifier: Apache-2.0
// Evaluation rate of the bit-accurate cs16 model against the double references, one core,
// and wall time of the full default sweep (all n × all input codes, both cores).
// Figures are recorded in docs/performance.md (command, machine, date).
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "shadecore/configs.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/analysis/sweep.hpp"
#include "cycle.hpp"

using namespace shadecore;
using shadecore::bench::cycle_inputs;

namespace {

struct Inputs {
  std::vector<int64_t> codes;
  std::vector<double> cosines;
  std::vector<Cs16Material> mats;
  std::vector<int> ns;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs v;
    const Format f = default_format();
    std::mt19937_64 rng(1);
    std::uniform_int_distribution<int> nd(kNMin, kNMax);
    for (int i = 0; i < 4096; ++i) {
      const int n = nd(rng);
      // Codes inside the lobe (the expensive part of the function), from thr to 1.0.
      const Cs16Material m = cs16_setup(f, n);
      std::uniform_int_distribution<int64_t> cd(m.thr, f.one());
      const int64_t code = cd(rng);
      v.codes.push_back(code);
      v.cosines.push_back(std::ldexp(double(code), -f.frac));
      v.mats.push_back(m);
      v.ns.push_back(n);
    }
    return v;
  }();
  return in;
}

void BM_Cs16Fixed(benchmark::State& st) {
  const Format f = default_format();
  const Inputs& in = inputs();
  cycle_inputs(st, in.codes.size(), [&](size_t i) { return cs16_eval(f, Cutoff::ThetaCr, in.mats[i], in.codes[i]); });
}
BENCHMARK(BM_Cs16Fixed);

// The exhaustive-sweep form: consecutive codes for one material (vectorised integer arithmetic).
void BM_Cs16FixedBlock(benchmark::State& st) {
  const Format f = default_format();
  const Cs16Material m = cs16_setup(f, 300);
  std::vector<uint32_t> out(4096);
  int64_t code0 = f.one() - 4096;
  for (auto _ : st) {
    cs16_eval_block(f, Cutoff::ThetaCr, m, code0, 4096, out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  st.SetItemsProcessed(st.iterations() * 4096);
}
BENCHMARK(BM_Cs16FixedBlock);

// The rate of a double reference ref(cos θ, n) on the same inputs.
template <class Ref>
void double_rate(benchmark::State& st, Ref&& ref) {
  const Inputs& in = inputs();
  cycle_inputs(st, in.cosines.size(), [&](size_t i) { return ref(in.cosines[i], in.ns[i]); });
}

void BM_PowDouble(benchmark::State& st) { double_rate(st, [](double c, int n) { return golden::cos_pow(c, n); }); }
BENCHMARK(BM_PowDouble);

void BM_SchlickDouble(benchmark::State& st) { double_rate(st, [](double c, int n) { return golden::schlick(c, n); }); }
BENCHMARK(BM_SchlickDouble);

void BM_Cs16Double(benchmark::State& st) {
  double_rate(st, [](double c, int n) { return golden::cs16_theta_cr(c, n); });
}
BENCHMARK(BM_Cs16Double);

// The full default sweep: every n in 16..1024 × every code in [0, 2^F], all cores.
void BM_FullDefaultSweep(benchmark::State& st) {
  SweepOptions opt;
  opt.format = default_format();
  for (auto _ : st) {
    const SweepResult r = run_sweep(opt);
    benchmark::DoNotOptimize(r.approx.max.value);
    st.counters["evaluations"] = double(r.evaluations);
  }
}
BENCHMARK(BM_FullDefaultSweep)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

}  // namespace

BENCHMARK_MAIN();
