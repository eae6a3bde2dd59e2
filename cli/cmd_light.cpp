// SPDX-License-Identifier: Apache-2.0
// shadecore light-sweep — error of the lighting core against the double-precision reference of the
// same equation (docs/lighting.md §7): per specular unit and channel, the total error against exact
// cos^n split, as `sweep` does for the unit, into the approximation part (double variant − exact) and
// the quantisation part (fixed-point core − double variant, in output LSBs of 2^−F).
// Inputs: random but realistic register programs (a material with random n, every light of the
// feature set with random colours/positions/attenuation) and fragments (unit normals facing the
// viewer, positions in front of it), deterministic from --seed.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "commands.hpp"
#include "light_rtl.hpp"
#include "output.hpp"
#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/units/table.hpp"

namespace shadecore::cli {
namespace {

struct Stats {
  double total_max = 0, approx_max = 0, quant_max = -1e300, quant_min = 1e300, abs_sum = 0, sq_sum = 0;
  uint64_t samples = 0, lit = 0;
  // Spot cone edges: fragments where the fixed-point cone test (sdl >= the cos code) and the double one
  // disagree for some light. The spot factor is a step there (up to the whole light term with exponent 0), so
  // they are counted and measured apart, not in the quantisation figures above (docs/lighting.md §7).
  uint64_t edge_fragments = 0;
  double edge_quant_max_abs = 0;
  // The new terms apart (docs/lighting.md §3.4, §3.5, §7): programs whose shininess is below 16 (low_shininess:
  // every fourth program) — the whole colour's quantisation against the double core there; and each spot light's
  // factor against (−L̂·ŝ)^e in double (LSBs of 2^−F), where both cone tests agree.
  // A subset's quantisation range (LSBs of 2^-F, fixed-point colour sum against the double core's).
  struct Range {
    uint64_t samples = 0;
    double min = 1e300, max = -1e300;
    void add(double q) { min = std::min(min, q), max = std::max(max, q), ++samples; }
    [[nodiscard]] double lo() const { return samples ? min : 0.0; }
    [[nodiscard]] double hi() const { return samples ? max : 0.0; }
  };
  Range low;         // shininess below 16 (every fourth program)
  Range colour_mat;  // colour material (colour_material: every third program, the mode in turn, random colours)
  Range back;        // back fragments in the two-sided mode (two_side: every fifth program, half the fragments)
  uint64_t spot_samples = 0;
  double spot_factor_max_abs = 0;
};

Stats sweep_one(const FeatureSet& fs, uint64_t programs, uint64_t per_program, uint64_t seed) {
  const LightCore core(fs);
  const int F = core.format().frac;
  std::mt19937_64 rng(seed);
  auto u = [&rng](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); };
  // colour material's and two-sided lighting's draws from a stream of their own (the other draws stay as they were)
  std::mt19937_64 rng2(seed ^ 0xC0102u);
  auto u2 = [&rng2](double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng2); };
  Stats st;
  for (uint64_t prog = 0; prog < programs; ++prog) {
    LightRegs regs;
    auto apply = [&](const std::vector<RegWrite>& ws) {
      for (const auto& w : ws) regs.write(core.widths(), w.addr, w.data);
    };
    double ga[3] = {u(0, 0.2), u(0, 0.2), u(0, 0.2)};
    // separate_specular: every other program in the separate mode, compared as GL's colour sum
    ModeParams modes = default_modes(fs);
    modes.separate_specular = fs.separate_specular && prog % 2 == 1;
    modes.two_side = fs.two_side && prog % 5 == 4;
    apply(global_writes(core, ga, modes));
    const bool cm = fs.colour_material && prog % 3 == 2;
    if (fs.colour_material)
      apply(colour_material_writes(cm ? std::optional(static_cast<ColourMaterial>(prog / 3 % 5)) : std::nullopt));
    MaterialParams m;
    for (int c = 0; c < 3; ++c) m.ambient[c] = u(0, 0.3), m.diffuse[c] = u(0, 0.8), m.specular[c] = u(0.2, 1);
    m.shininess = static_cast<int>(std::lround(std::exp(u(std::log(16.0), std::log(1024.0)))));
    const bool low = fs.specular && fs.low_shininess && prog % 4 == 3;
    if (low) m.shininess = static_cast<int>(prog / 4 % static_cast<uint64_t>(kNMin));  // 0..15 in turn
    apply(material_writes(core, m));
    if (fs.two_side) {
      MaterialParams b = m;
      for (int c = 0; c < 3; ++c) b.ambient[c] = u2(0, 0.3), b.diffuse[c] = u2(0, 0.8), b.specular[c] = u2(0.2, 1);
      apply(back_material_writes(core, b));
    }
    for (int j = 0; j < fs.num_lights(); ++j) {
      LightParams lp;
      // the most general kind the slot can take (spot on 'full': point_att times a random cone)
      LightKind kind = fs.slot_kind(j);
      for (int k = 0; k < kNumLightKinds; ++k)
        if (fs.slot_can(j, static_cast<LightKind>(k))) kind = static_cast<LightKind>(k);
      lp.kind = kind;
      const bool dir = kind == LightKind::Directional;
      lp.position[0] = u(-1, 1) * (dir ? 1 : 20);
      lp.position[1] = u(-1, 1) * (dir ? 1 : 20);
      lp.position[2] = dir ? u(0.2, 1) : u(-10, 20);
      lp.position[3] = dir ? 0 : 1;
      for (int c = 0; c < 3; ++c) lp.ambient[c] = u(0, 0.1), lp.diffuse[c] = u(0, 1), lp.specular[c] = u(0, 1);
      lp.kc = 1, lp.kl = u(0, 0.05), lp.kq = u(0, 0.005);
      if (kind == LightKind::Spot) {  // aimed at a point of the fragments' region; cut-off 5..90°, exponent 0..128
        const double target[3] = {u(-15, 15), u(-15, 15), u(-60, -2)};
        for (int i = 0; i < 3; ++i) lp.spot_direction[i] = target[i] - lp.position[i];
        lp.spot_cutoff = u(5, 90);
        lp.spot_exponent = static_cast<int>(std::lround(u(0, kSpotExpMax)));
      }
      apply(light_writes(core, j, lp));
    }
    for (uint64_t i = 0; i < per_program; ++i) {
      double n[3] = {u(-1, 1), u(-1, 1), u(0.05, 1)};
      const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      for (double& x : n) x /= len;
      const double p[3] = {u(-15, 15), u(-15, 15), u(-60, -2)};
      Fragment fr = make_fragment(F, n, p);
      if (cm) {
        const double col[3] = {u2(0, 1), u2(0, 1), u2(0, 1)};
        set_fragment_colour(F, fr, col);
      }
      fr.back = modes.two_side && u2(0, 1) < 0.5;
      LightCoreTrace t;
      const Colour c = core.eval(regs, fr, &t);
      uint32_t cone = 0, fixed_cone = 0;
      const auto ex = core.eval_double(regs, fr, LightCore::SpecRef::Exact, &cone);
      const auto va = core.eval_double(regs, fr, LightCore::SpecRef::Variant);
      for (int j = 0; j < fs.num_lights(); ++j)
        if (t.light[static_cast<size_t>(j)].in_cone) fixed_cone |= 1u << j;
      if (cone != fixed_cone) {
        ++st.edge_fragments;
        for (int ch = 0; ch < fs.channels; ++ch)
          st.edge_quant_max_abs = std::max(
              st.edge_quant_max_abs,
              std::fabs(std::ldexp(static_cast<double>(c.colour_sum(ch, 1u << F)), -F) - va[ch]) * std::ldexp(1.0, F));
        continue;
      }
      // each spot light's factor against the double one on the double geometry (the register codes read exactly)
      for (int j = 0; j < fs.num_lights(); ++j) {
        const LightTrace& lt = t.light[static_cast<size_t>(j)];
        if (!lt.on || lt.kind != LightKind::Spot || !lt.in_cone) continue;
        const LightRegs::Light& L = regs.light[static_cast<size_t>(j)];
        double l[3], ll = 0, sd = 0;
        for (int k = 0; k < 3; ++k) {
          l[k] = std::ldexp(static_cast<double>(L.pos[k] - fr.p[k]), -F);
          ll += l[k] * l[k];
        }
        for (int k = 0; k < 3; ++k) sd -= l[k] / std::sqrt(ll) * std::ldexp(static_cast<double>(L.sdir[k]), -F);
        const double sp = L.sexp == 0 ? 1.0 : std::pow(std::clamp(sd, 0.0, 1.0), static_cast<double>(L.sexp));
        const double fx = std::ldexp(static_cast<double>(lt.spot), -core.unit_format().frac);
        st.spot_factor_max_abs = std::max(st.spot_factor_max_abs, std::fabs(fx - sp) * std::ldexp(1.0, F));
        ++st.spot_samples;
      }
      for (int ch = 0; ch < fs.channels; ++ch) {
        const double fx = std::ldexp(static_cast<double>(c.colour_sum(ch, 1u << F)), -F);
        const double tot = (fx - ex[ch]) * std::ldexp(1.0, F), q = (fx - va[ch]) * std::ldexp(1.0, F);
        st.total_max = std::max(st.total_max, std::fabs(tot));
        st.approx_max = std::max(st.approx_max, std::fabs(va[ch] - ex[ch]));
        st.quant_max = std::max(st.quant_max, q);
        st.quant_min = std::min(st.quant_min, q);
        st.abs_sum += std::fabs(tot);
        st.sq_sum += tot * tot;
        ++st.samples;
        if (ex[ch] > 0) ++st.lit;
        if (low) st.low.add(q);
        if (cm) st.colour_mat.add(q);
        if (fr.back) st.back.add(q);
      }
    }
  }
  return st;
}

}  // namespace

void add_light_sweep(CLI::App& app) {
  using namespace cliargs;
  auto* sub = app.add_subcommand("light-sweep", "error of the lighting core against the exact double reference");
  struct A {
    std::string features = "full", specular = "own", json;
    uint64_t programs = 200, per_program = 2000, seed = 0;
    int spec_guard = -1;
  };
  auto a = std::make_shared<A>();
  sub->add_option("--features", a->features, "named feature set of config/configs.json or a JSON file")
      ->check(NonEmpty("feature set"))
      ->type_name("NAME|FILE")
      ->capture_default_str();
  sub->add_option("--specular", a->specular, "own (the set's unit) | all (each unit in turn but the table units) | a variant name")
      ->check(NonEmpty("--specular"))
      ->type_name("UNIT")
      ->capture_default_str();
  sub->add_option("--programs", a->programs, "random register programs, 1..1000000")
      ->check(UInt(1, 1000000).description(""))
      ->type_name("COUNT")
      ->capture_default_str();
  sub->add_option("--per-program", a->per_program, "fragments per program, 1..100000000")
      ->check(UInt(1, 100000000).description(""))
      ->type_name("COUNT")
      ->capture_default_str();
  sub->add_option("--seed", a->seed,
                  "random seed, 0..2^64-1 (default or 0: pick one and print it); the same seed gives the same "
                  "programs and fragments")
      ->check(UInt(0).description(""))
      ->type_name("SEED");
  sub->add_option("--spec-guard", a->spec_guard,
                  "override the set's spec_guard: extra fraction bits of the specular path, 0..8")
      ->check(UInt(0, kSpecGuardMax).description(""))
      ->type_name("BITS");
  sub->add_option("--json", a->json, "write the results as JSON (atomically)")->check(NonEmpty("path"))->type_name("FILE");
  sub->callback([a]() {
    if (!a->json.empty()) check_writable_file(a->json);
    // 0 or absent: pick a seed and print it (docs/cli.md), as cosim does.
    const bool picked = a->seed == 0;
    uint64_t seed = a->seed;
    if (picked) {
      seed = (static_cast<uint64_t>(std::random_device{}()) << 32) ^ std::random_device{}();
      if (seed == 0) seed = 1;
    }
    FeatureSet base = feature_set_named_or_file(a->features);
    if (a->spec_guard >= 0) {
      base.spec_guard = a->spec_guard;
      validate(base.unit_format());  // F + spec_guard within the units' formats
    }
    std::vector<FeatureSet> sets;
    if (a->specular == "own") {
      sets.push_back(base);
    } else {
      if (!base.specular) throw std::invalid_argument("feature set '" + base.name + "' has no specular unit");
      for (const auto& v : kVariants) {
        if (a->specular != "all" && a->specular != v.name) continue;
        // The lighting core has no table units (docs/table.md): `all` skips them, naming one is an error.
        if (is_table_variant(v.id)) {
          if (a->specular == "all") continue;
          throw std::invalid_argument("--specular " + a->specular + ": the lighting core has no table units");
        }
        FeatureSet s = base;  // the same datapath with this unit programmed (alone)
        s.variant = v.id;
        s.more_units.clear();
        if (v.id != VariantId::cs16) s.cutoff = Cutoff::ThetaCr;
        sets.push_back(s);
      }
      if (sets.empty()) throw std::invalid_argument("unknown --specular '" + a->specular + "' (own, all or a variant)");
    }
    const int F = base.format().frac;
    fmt::print("light-sweep: feature set '{}': {}\n  {} programs x {} fragments, seed {}{}; errors in output LSBs (2^-{})\n",
               base.name, base.summary(), a->programs, a->per_program, seed,
               picked ? fmt::format(" (picked; --seed {} reproduces this run)", seed) : std::string(), F);
    fmt::print("  {:<13} {:>12} {:>14} {:>12} {:>12} {:>12} {:>9}\n", "specular", "total max", "approx max",
               "quant min", "quant max", "mean |err|", "PSNR dB");
    nlohmann::json units = nlohmann::json::array();
    std::vector<std::pair<std::string, std::string>> rows;  // (figures as printed, unit): identical rows get a note
    for (const auto& s : sets) {
      const Stats st = sweep_one(s, a->programs, a->per_program, seed);
      const double rms = std::sqrt(st.sq_sum / st.samples) * std::ldexp(1.0, -F);
      const double psnr = rms > 0 ? 20 * std::log10(1.0 / rms) : INFINITY;
      const std::string name = s.specular ? std::string(variant_name(s.variant)) : "none";
      // Every column in output LSBs (2^-F) but PSNR: the approximation error too (approx_max is a value in
      // [0, 1], the unit's double formula against exact cos^n).
      const double approx_lsb = std::ldexp(st.approx_max, F);
      const std::string figures = fmt::format("{:>12.2f} {:>14.2f} {:>12.2f} {:>12.2f} {:>12.3f} {:>9.1f}", st.total_max,
                                              approx_lsb, st.quant_min, st.quant_max, st.abs_sum / st.samples, psnr);
      fmt::print("  {:<13} {}\n", name, figures);
      rows.emplace_back(figures, name);
      if (st.low.samples)
        fmt::print("  {:<13} shininess 0..15 (low_shininess chain, every 4th program): quant {:.2f}..{:.2f} LSB over {} samples\n",
                   "", st.low.min, st.low.max, st.low.samples);
      if (st.colour_mat.samples)
        fmt::print("  {:<13} colour material (every 3rd program, each mode in turn): quant {:.2f}..{:.2f} LSB over {} samples\n",
                   "", st.colour_mat.min, st.colour_mat.max, st.colour_mat.samples);
      if (st.back.samples)
        fmt::print("  {:<13} back fragments, two-sided mode (every 5th program): quant {:.2f}..{:.2f} LSB over {} samples\n",
                   "", st.back.min, st.back.max, st.back.samples);
      if (st.spot_samples)
        fmt::print("  {:<13} spot factor against (-L.s)^e in double: max |error| {:.2f} LSB over {} lit spot terms\n", "",
                   st.spot_factor_max_abs, st.spot_samples);
      if (st.edge_fragments)
        fmt::print("  {:<13} spot cone edge: {} fragments where the fixed-point and the double cone test disagree "
                   "(not above); there |fixed - double unit| up to {:.2f} LSB\n",
                   "", st.edge_fragments, st.edge_quant_max_abs);
      units.push_back({{"specular", name},
                       {"total_max_lsb", st.total_max},
                       {"approx_max", st.approx_max},  // a value in [0, 1] (docs/lighting.md §7)
                       {"approx_max_lsb", approx_lsb},
                       {"quant_min_lsb", st.quant_min},
                       {"quant_max_lsb", st.quant_max},
                       {"mean_abs_lsb", st.abs_sum / st.samples},
                       {"psnr_db", psnr},
                       {"samples", st.samples},
                       {"spot_edge_fragments", st.edge_fragments},
                       {"spot_edge_quant_max_abs_lsb", st.edge_quant_max_abs},
                       {"low_shininess_samples", st.low.samples},
                       {"low_shininess_quant_min_lsb", st.low.lo()},
                       {"low_shininess_quant_max_lsb", st.low.hi()},
                       {"colour_material_samples", st.colour_mat.samples},
                       {"colour_material_quant_min_lsb", st.colour_mat.lo()},
                       {"colour_material_quant_max_lsb", st.colour_mat.hi()},
                       {"two_side_back_samples", st.back.samples},
                       {"two_side_back_quant_min_lsb", st.back.lo()},
                       {"two_side_back_quant_max_lsb", st.back.hi()},
                       {"spot_factor_samples", st.spot_samples},
                       {"spot_factor_max_abs_lsb", st.spot_factor_max_abs}});
    }
    // Units whose rows print the same figures (issue 38: a reader suspects the unit was not swapped).
    std::vector<std::string> noted;
    for (size_t i = 0; i < rows.size(); ++i) {
      std::string same;
      for (size_t k = i + 1; k < rows.size(); ++k)
        if (rows[k].first == rows[i].first && std::find(noted.begin(), noted.end(), rows[k].second) == noted.end()) {
          same += ", " + rows[k].second;
          noted.push_back(rows[k].second);
        }
      if (!same.empty() && std::find(noted.begin(), noted.end(), rows[i].second) == noted.end())
        fmt::print("  note: {}{} print identical rows. Each unit was run in turn; their outputs differ by about one ulp of "
                   "the unit's {} fraction bits at most, which the lane's products and the rounding to {} bits rarely let "
                   "through to these figures (docs/lighting.md §7)\n",
                   rows[i].second, same, base.unit_format().frac, F);
    }
    if (!a->json.empty()) {
      nlohmann::json j = {{"features", base.name},
                          {"feature_set", nlohmann::json::parse(base.canonical().dump())},
                          {"feature_key", base.key()},
                          {"verilog_params", base.verilog_params(8)},
                          {"latency", LightCore(base).latency()},
                          {"latency_min", LightCore(base).latency_min()},
                          {"frac", F},
                          {"programs", a->programs},
                          {"per_program", a->per_program},
                          {"seed", seed},
                          {"seed_picked", picked},
                          {"units", units}};
      write_file_atomic(a->json, j.dump(2) + "\n");
    }
  });
}

}  // namespace shadecore::cli
