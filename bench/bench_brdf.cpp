// SPDX-License-Identifier: Apache-2.0
// Table 5.2 of seed 000 (time of 10^9 BRDF evaluations) on this machine, beside the project's units.
//
// The thesis's method (§5.4): the only inputs of one evaluation are the direction of incidence, the
// direction of reflection, the normal and the model's parameters. Here every iteration takes the next of
// 4096 random (ωi, ωo, N, tangent) sets — ωi, ωo uniform in N's hemisphere — and the next of four
// parameter sets of the model (so neither the geometry nor the parameters are compile-time constants),
// and the result goes through benchmark::DoNotOptimize. Anisotropic models build their local frame from
// N and the tangent on every call, as the thesis's did. ns per evaluation = seconds per 10^9.
//
// Project units (same run, same inputs): the highlight alone for cos δ = N·Θh of the same directions and
// an exponent n in 16..1024 — std::pow (exact), cs16 in double, Schlick's t/(n − n t + t) in double
// (shadecore/analysis/golden.hpp), the bit-accurate fixed-point cs16 (shadecore/units/cs16.hpp, default width) — and
// Blinn-Phong (2.10) with the fixed-point cs16 unit in place of cos^n δ.
// Figures: docs/brdf.md (command, machine, date).
#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "shadecore/analysis/brdf.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/analysis/golden.hpp"
#include "cycle.hpp"

using namespace shadecore;
using namespace shadecore::brdf;
using shadecore::bench::cycle_inputs;

namespace {

constexpr size_t kSets = 4096;  // power of two

struct Set {
  Vec3 wi, wo, n, t;
  double cos_h = 0;   // N·Θh, the highlight units' input
  int nexp = 16;      // exponent for the units, 16..1024
  int64_t code = 0;   // cos_h as the fixed-point unit's input code
  Cs16Material mat;   // cs16 material constants for nexp
};

const std::vector<Set>& sets() {
  static const std::vector<Set> v = [] {
    std::vector<Set> s(kSets);
    std::mt19937_64 rng(2004);
    RandomDirections dir(rng);
    std::uniform_int_distribution<int> nd(16, 1024);
    const Format f = default_format();
    for (Set& e : s) {
      e.n = dir.sphere();
      e.t = dir.sphere();
      e.wi = dir.hemisphere(e.n);
      e.wo = dir.hemisphere(e.n);
      e.cos_h = dot(e.n, normalize(e.wi + e.wo));
      e.nexp = nd(rng);
      e.code = std::llround(std::ldexp(e.cos_h, f.frac));
      e.mat = cs16_setup(f, e.nexp);
    }
    return s;
  }();
  return v;
}

// The same kind of sets restricted to ωo inside Phong's lobe (Θr·Θs > 0): there the highlight's pow is
// always evaluated, whereas for uniform directions Phong's cos α <= 0 (lobe skipped) about half the time.
const std::vector<Set>& lobe_sets() {
  static const std::vector<Set> v = [] {
    std::vector<Set> s;
    std::mt19937_64 rng(1975);
    RandomDirections dir(rng);
    while (s.size() < kSets) {
      Set e;
      e.n = dir.sphere();
      e.t = dir.sphere();
      e.wi = dir.sphere();
      e.wo = dir.sphere();
      if (dot(e.wi, e.n) < 1e-3 || dot(e.wo, e.n) < 1e-3 || dot(e.wo, mirror(e.wi, e.n)) <= 0) continue;
      s.push_back(e);
    }
    return s;
  }();
  return v;
}

template <class M>
void run_model(benchmark::State& st, std::array<M, 4> mats, bool in_lobe = false) {
  const std::vector<Set>& in = in_lobe ? lobe_sets() : sets();
  benchmark::DoNotOptimize(mats);  // the parameters are run-time data
  cycle_inputs(st, kSets, [&](size_t i) {
    const Set& e = in[i];
    return mats[i & 3](e.wi, e.wo, e.n, e.t);
  });
}

void BM_Lambert(benchmark::State& st) { run_model(st, std::array<Lambert, 4>{{{0.2}, {0.4}, {0.6}, {0.8}}}); }
void BM_PhongClassic(benchmark::State& st) {
  run_model(st, std::array<PhongClassic, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}});
}
void BM_PhongBrdf(benchmark::State& st) {
  run_model(st, std::array<PhongBrdf, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}});
}
void BM_BlinnPhong(benchmark::State& st) {
  run_model(st, std::array<BlinnPhong, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}});
}
void BM_SchlickPhong(benchmark::State& st) {
  run_model(st, std::array<SchlickPhong, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}});
}
void BM_CookTorrance(benchmark::State& st) {
  run_model(st, std::array<CookTorrance, 4>{{{0.4, 0.4, 0.6, 1.5, 0},
                                             {0.4, 0.4, 0.2, 1.5, 0},
                                             {0.8, 0.2, 0.15, 1.49, 0},
                                             {0.0, 0.8, 0.25, 1.0, 2.39}}});
}
void BM_SchlickCookTorrance(benchmark::State& st) {
  run_model(st, std::array<SchlickCookTorrance, 4>{{{0.4, 0.4, 0.6, fresnel_f0(1.5, 0)},
                                                    {0.4, 0.4, 0.2, fresnel_f0(1.5, 0)},
                                                    {0.8, 0.2, 0.15, fresnel_f0(1.49, 0)},
                                                    {0.0, 0.8, 0.25, fresnel_f0(1.0, 2.39)}}});
}
void BM_Strauss(benchmark::State& st) {
  run_model(st, std::array<Strauss, 4>{{{0.8, 0.1, 0.0, 0.0}, {0.8, 0.5, 0.5, 0.0}, {0.6, 0.7, 1.0, 0.0},
                                        {1.0, 0.9, 0.3, 0.2}}});
}
void BM_AshikhminShirley(benchmark::State& st) {
  run_model(st, std::array<AshikhminShirley, 4>{{{0.4, 0.4, 10, 10}, {0.4, 0.4, 10, 1000}, {0.0, 0.9, 100, 100},
                                                 {0.6, 0.05, 1000, 10}}});
}
void BM_Ward(benchmark::State& st) {
  run_model(st, std::array<Ward, 4>{{{0.4, 0.4, 0.1, 0.1}, {0.4, 0.4, 0.05, 0.2}, {0.1, 0.8, 0.2, 0.05},
                                     {0.6, 0.3, 0.3, 0.3}}});
}
void BM_Schlick(benchmark::State& st) {
  run_model(st, std::array<Schlick, 4>{{Schlick{{0.4, 0.1, 1.0}}, Schlick{{0.4, 0.4, 0.3}}, Schlick{{0.9, 0.01, 0.1}},
                                        Schlick{{0.05, 0.8, 1.0}}}});
}
void BM_Lafortune(benchmark::State& st) {
  const auto one = [](double kd, double ks, double n) { return Lafortune{kd, {Lafortune::phong_lobe(ks, n)}, 1}; };
  run_model(st, std::array<Lafortune, 4>{{one(0.4, 0.2, 3), one(0.4, 0.4, 10), one(0.4, 0.6, 50), one(0.2, 0.8, 200)}});
}

void BM_PhongBrdf_InLobe(benchmark::State& st) {
  run_model(st, std::array<PhongBrdf, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}}, true);
}
void BM_BlinnPhong_InLobe(benchmark::State& st) {
  run_model(st, std::array<BlinnPhong, 4>{{{0.4, 0.2, 3}, {0.4, 0.4, 10}, {0.4, 0.6, 50}, {0.2, 0.8, 200}}}, true);
}

BENCHMARK(BM_Lambert);
BENCHMARK(BM_PhongClassic);
BENCHMARK(BM_PhongBrdf);
BENCHMARK(BM_BlinnPhong);
BENCHMARK(BM_SchlickPhong);
BENCHMARK(BM_CookTorrance);
BENCHMARK(BM_SchlickCookTorrance);
BENCHMARK(BM_Strauss);
BENCHMARK(BM_AshikhminShirley);
BENCHMARK(BM_Ward);
BENCHMARK(BM_Schlick);
BENCHMARK(BM_Lafortune);
BENCHMARK(BM_PhongBrdf_InLobe);
BENCHMARK(BM_BlinnPhong_InLobe);

// --- the project's units: the highlight alone ---------------------------------------------------

void BM_Unit_PowExact(benchmark::State& st) {
  const std::vector<Set>& in = sets();
  cycle_inputs(st, kSets, [&](size_t i) { return golden::cos_pow(in[i].cos_h, in[i].nexp); });
}
void BM_Unit_Cs16Double(benchmark::State& st) {
  const std::vector<Set>& in = sets();
  cycle_inputs(st, kSets, [&](size_t i) { return golden::cs16_theta_cr(in[i].cos_h, in[i].nexp); });
}
void BM_Unit_SchlickDouble(benchmark::State& st) {
  const std::vector<Set>& in = sets();
  cycle_inputs(st, kSets, [&](size_t i) { return golden::schlick(in[i].cos_h, in[i].nexp); });
}
void BM_Unit_Cs16Fixed(benchmark::State& st) {
  const std::vector<Set>& in = sets();
  const Format f = default_format();
  cycle_inputs(st, kSets, [&](size_t i) { return cs16_eval(f, Cutoff::ThetaCr, in[i].mat, in[i].code); });
}

// Blinn-Phong (2.10) with the fixed-point cs16 unit as its highlight: the vector work in double, then
// cos δ quantised to the unit's input code, the bit-accurate datapath, and the output scaled back.
void BM_BlinnPhong_Cs16Fixed(benchmark::State& st) {
  const std::vector<Set>& in = sets();
  const Format f = default_format();
  std::array<double, 4> kd{0.4, 0.4, 0.4, 0.2}, ks{0.2, 0.4, 0.6, 0.8};
  benchmark::DoNotOptimize(kd);
  benchmark::DoNotOptimize(ks);
  const double scale = std::ldexp(1.0, f.frac), inv = std::ldexp(1.0, -f.frac);
  cycle_inputs(st, kSets, [&](size_t i) {
    const Set& e = in[i];
    const double ci = dot(e.n, e.wi), co = dot(e.n, e.wo);
    double r = 0;
    if (ci > 0 && co > 0) {
      const double cd = dot(e.n, normalize(e.wi + e.wo));
      const uint32_t out = cs16_eval(f, Cutoff::ThetaCr, e.mat, std::llround(cd * scale));
      r = kd[i & 3] / kPi + ks[i & 3] * (e.mat.n + 2) / (2 * kPi) * (out * inv);
    }
    return r;
  });
}

BENCHMARK(BM_Unit_PowExact);
BENCHMARK(BM_Unit_Cs16Double);
BENCHMARK(BM_Unit_SchlickDouble);
BENCHMARK(BM_Unit_Cs16Fixed);
BENCHMARK(BM_BlinnPhong_Cs16Fixed);

}  // namespace

BENCHMARK_MAIN();
