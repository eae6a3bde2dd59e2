// SPDX-License-Identifier: Apache-2.0
// Lighting core C model (docs/lighting.md): the division-free operators against their stated bounds
// (exhaustive where the input space allows), the hard cases of issue 8 with their documented outputs,
// the feature-set parser and the host-side setup checks.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <utility>

#include "shadecore/features.hpp"
#include "shadecore/light.hpp"
#include "shadecore/limits.hpp"
#include "shadecore/units/normalize.hpp"
#include "shadecore/units/recip.hpp"

using namespace shadecore;

namespace {

// |u_i − 2^F·v_i/|v|| for every component.
double normalize_err(int F, const int64_t v[3]) {
  int64_t u[3];
  normalize3(F, v, u);
  const double l = std::sqrt(double(v[0]) * v[0] + double(v[1]) * v[1] + double(v[2]) * v[2]);
  double e = 0;
  for (int i = 0; i < 3; ++i) e = std::max(e, std::fabs(double(u[i]) - std::ldexp(double(v[i]) / l, F)));
  return e;
}

}  // namespace

// The seed table follows its integer rule: round-to-nearest of 2^T·8/√(2i+1), 1016 .. 513.
TEST(LightOps, RsqrtSeedTable) {
  for (uint32_t i = 32; i < 128; ++i) {
    const double exact = 1024.0 * 8.0 / std::sqrt(2.0 * i + 1.0);
    EXPECT_LE(std::fabs(rsqrt_seed(i) - exact), 0.5) << "i = " << i;
  }
  EXPECT_EQ(rsqrt_seed(32), 1016u);
  EXPECT_EQ(rsqrt_seed(127), 513u);
}

// Bound (docs/lighting.md §3.1): every component within normalize3_bound_ulp(F) output ulps of the exact v_i/|v|.
// Exhaustive over every mantissa of s at F = 8 and 16 (v = (a, 0, 0) and (a, a, 0), a < 2^20 covers
// each even/odd exponent with all its mantissas), plus dense random 3-vectors of every magnitude; the
// same vectors at F = 21, 22 (the specular path at F = 16 with spec_guard 5, the default, and 6) and 24
// (spec_guard 8), where the bound is looser: two Newton steps from the 7-bit seed give about 24 bits, so
// at 24 output bits their residue shows (0.694 measured; docs/lighting.md §3.1).
TEST(LightOps, NormalizeBoundExhaustiveAndDense) {
  for (int F : {8, 16, 21, 22, 24}) {
    const double bound = normalize3_bound_ulp(F);
    double worst = 0;
    for (int64_t a = 1; a < (int64_t{1} << 20); ++a) {
      const int64_t v1[3] = {a, 0, 0}, v2[3] = {a, a, 0}, v3[3] = {-a, a, a};
      worst = std::max({worst, normalize_err(F, v1), normalize_err(F, v2), normalize_err(F, v3)});
    }
    std::mt19937_64 rng(F);
    for (int i = 0; i < 1000000; ++i) {
      int64_t v[3];
      const int bits = 1 + static_cast<int>(rng() % 26);
      for (auto& x : v) x = static_cast<int64_t>(rng() % (uint64_t{1} << bits)) - (int64_t{1} << (bits - 1));
      if (v[0] == 0 && v[1] == 0 && v[2] == 0) continue;
      worst = std::max(worst, normalize_err(F, v));
    }
    EXPECT_LE(worst, bound) << "F = " << F;
    EXPECT_GT(worst, 0.5) << "the bound should be nearly tight (round to nearest)";
  }
}

TEST(LightOps, NormalizeZeroIsZero) {
  const int64_t v[3] = {0, 0, 0};
  int64_t u[3] = {1, 1, 1};
  normalize3(16, v, u);
  EXPECT_EQ(u[0], 0);
  EXPECT_EQ(u[1], 0);
  EXPECT_EQ(u[2], 0);
}

// Bound (docs/lighting.md §3.2): |att − 2^(2F)/q| <= 1 output ulp where not saturated; saturated
// (att_max) exactly where 2^(2F)/q >= att_max. Exhaustive over every q < 2^24 at F = 8 (every
// mantissa of every exponent up to 2^24) and every mantissa of three exponents at F = 16.
TEST(LightOps, RecipBoundExhaustive) {
  auto check = [](int F, uint64_t q, double& worst) {
    const uint64_t a = recip_att(F, q);
    const double ex = std::ldexp(1.0, 2 * F) / double(q);
    if (ex >= double(att_max(F)) + 1) {
      ASSERT_EQ(a, att_max(F)) << "q = " << q;
      return;
    }
    worst = std::max(worst, std::fabs(double(a) - std::min(ex, double(att_max(F)))));
  };
  double worst = 0;
  for (uint64_t q = 1; q < (uint64_t{1} << 24); ++q) check(8, q, worst);
  EXPECT_LE(worst, 1.0);
  worst = 0;
  for (int p : {8, 16, 30})
    for (uint64_t m = 0; m < (uint64_t{1} << 24); m += (p == 16 ? 1 : 7)) check(16, (uint64_t{1} << p) + (m >> (24 - std::min(p, 24))) * (p >= 24 ? (uint64_t{1} << (p - 24)) : 1), worst);
  EXPECT_LE(worst, 1.0);
  EXPECT_EQ(recip_att(16, 0), att_max(16));
}

// The spot factor's square-and-multiply chain (docs/lighting.md §3.4): 0 <= x^e·2^F − chain <= e − 1 codes for
// e >= 1, and x^0 = 1 for every x (0 included). Every x code and exponent at F = 8; every exponent and a dense
// sample of x (with the ends) at F = 16. The exact power is taken in long double.
TEST(LightOps, PowiChainBoundExhaustive) {
  for (int F : {8, 16}) {
    const uint64_t one = uint64_t{1} << F;
    long double worst_ratio = 0;  // the largest (exact − chain) / (e − 1)
    for (uint64_t x = 0; x <= one; x += (F == 8 || x + 97 > one ? 1 : 97)) {
      for (uint32_t e = 0; e < 256; ++e) {
        const uint64_t r = powi_chain(F, x, e, kSpotExpBits);
        ASSERT_LE(r, one);
        if (e == 0) {
          ASSERT_EQ(r, one) << "x^0 must be exactly 1 (x = " << x << ")";
          continue;
        }
        const long double ex = std::pow(static_cast<long double>(x) / one, static_cast<long double>(e)) * one;
        const long double err = ex - static_cast<long double>(r);
        ASSERT_GE(err, -1e-9L) << "chain above the exact power: F " << F << " x " << x << " e " << e;
        ASSERT_LE(err, static_cast<long double>(e - 1) + 1e-9L) << "F " << F << " x " << x << " e " << e;
        if (e > 1) worst_ratio = std::max(worst_ratio, err / (e - 1));
        if (e == 1) {
          ASSERT_EQ(r, x);
        }
      }
    }
    EXPECT_GT(worst_ratio, 0.1L);  // the bound is approached, not vacuous
  }
}

namespace {
FeatureSet named(const std::string& n) { return feature_set_named_or_file(n); }

struct Rig {
  LightCore core;
  LightRegs regs;
  int F;
  explicit Rig(const FeatureSet& fs) : core(fs), F(core.format().frac) {
    double ga[3] = {0.1, 0.1, 0.1};
    apply(global_writes(core, ga));
    MaterialParams m;
    m.specular[0] = m.specular[1] = m.specular[2] = 1.0;
    m.shininess = 64;
    apply(material_writes(core, m));
  }
  void apply(const std::vector<RegWrite>& ws) {
    for (const auto& w : ws) regs.write(core.widths(), w.addr, w.data);
  }
};
// The two-sided tests' program on a core with a directional light in slot 0 and a point_att light in slot 1 at
// (1, 2, z): a front material and a back colour bank far apart (shininess 40 both); returns them.
std::pair<MaterialParams, MaterialParams> two_lights_two_banks(Rig& r, double z) {
  LightParams lp;
  lp.position[0] = 0.2, lp.position[1] = 0.4, lp.position[2] = 1, lp.position[3] = 0;
  r.apply(light_writes(r.core, 0, lp));
  LightParams pp;
  pp.position[0] = 1, pp.position[1] = 2, pp.position[2] = z, pp.position[3] = 1;
  pp.kq = 0.05;
  r.apply(light_writes(r.core, 1, pp));
  MaterialParams front, back;
  for (int c = 0; c < 3; ++c) {
    front.emission[c] = 0.05, front.ambient[c] = 0.3, front.diffuse[c] = 0.7, front.specular[c] = 0.6;
    back.emission[c] = 0.1 * c, back.ambient[c] = 0.5, back.diffuse[c] = 0.2 + 0.3 * c, back.specular[c] = 0.9;
  }
  front.shininess = back.shininess = 40;
  r.apply(material_writes(r.core, front));
  r.apply(back_material_writes(r.core, back));
  return {front, back};
}
}  // namespace

// N = 0: no diffuse, no specular (f = 0): only emission + a·A + Σ att·a·Ia remains.
TEST(LightHardCases, ZeroNormalGivesAmbientOnly) {
  Rig r(named("gl_default"));
  LightParams lp;
  lp.ambient[0] = lp.ambient[1] = lp.ambient[2] = 0.25;
  r.apply(light_writes(r.core, 0, lp));
  LightCoreTrace t;
  const Colour c = r.core.eval(r.regs, Fragment{}, &t);
  EXPECT_EQ(t.light[0].ndl, 0);
  EXPECT_FALSE(t.light[0].f);
  const uint64_t expect = t.scene[0] + ((uint64_t{r.regs.ambient[0]} * r.regs.light[0].ambient[0]) >> r.F);
  EXPECT_EQ(c.c[0], expect);
}

// A spot light (docs/lighting.md §3.4): inside exactly at −L̂·ŝ = the cos register (GL's >=), outside one code
// above; x = 0 with exponent 0 gives the factor 1 (att unchanged), exponent 1 gives 0; cutoff 180 on a spot
// slot is the factor 1; the host rejects a cutoff outside 0..90/180 and an exponent outside 0..128.
TEST(LightHardCases, SpotBoundaryAndZeroPower) {
  const FeatureSet fs = feature_set_from_json(nlohmann::json::parse(R"({"lights": ["spot"], "specular": "cs16"})"), "test");
  Rig r(fs);
  const int64_t one = int64_t{1} << r.F;
  LightParams lp;
  lp.position[0] = 0, lp.position[1] = 0, lp.position[2] = 10, lp.position[3] = 1;
  lp.spot_direction[0] = 0.1, lp.spot_direction[1] = 0.05, lp.spot_direction[2] = -1;
  lp.spot_cutoff = 30;
  lp.spot_exponent = 7;
  r.apply(light_writes(r.core, 0, lp));
  Fragment fr;
  fr.n[2] = one;
  fr.p[0] = one / 3;
  LightCoreTrace t;
  static_cast<void>(r.core.eval(r.regs, fr, &t));
  ASSERT_TRUE(t.light[0].in_cone);
  const uint32_t cmask = static_cast<uint32_t>(mask_bits(r.core.unit_format().frac + 2));
  const uint64_t vone = uint64_t{1} << r.core.unit_format().frac;
  const uint64_t att_in = t.light[0].att;
  for (int64_t d : {-1, 0, 1}) {
    r.regs.write(r.core.widths(), kReg_light_spot_cos, static_cast<uint32_t>(t.light[0].sdl + d) & cmask);
    LightCoreTrace u;
    static_cast<void>(r.core.eval(r.regs, fr, &u));
    EXPECT_EQ(u.light[0].in_cone, d <= 0) << d;
    EXPECT_EQ(u.light[0].spot == 0, d > 0) << d;
    if (d <= 0) {
      EXPECT_EQ(u.light[0].att, att_in);
    }
  }
  // x = 0: L̂ = (0, 0, 1) exactly (P = 0), ŝ = (1, 0, 0); the cos register 0 (inside at the boundary)
  lp.spot_direction[0] = 1, lp.spot_direction[1] = 0, lp.spot_direction[2] = 0;
  lp.spot_cutoff = 90;
  for (int e : {0, 1}) {
    lp.spot_exponent = e;
    r.apply(light_writes(r.core, 0, lp));
    r.regs.write(r.core.widths(), kReg_light_spot_cos, 0);
    LightCoreTrace u;
    static_cast<void>(r.core.eval(r.regs, Fragment{{0, 0, one}, {0, 0, 0}}, &u));
    EXPECT_EQ(u.light[0].sdl, 0);
    EXPECT_TRUE(u.light[0].in_cone);
    EXPECT_EQ(u.light[0].spot, e == 0 ? vone : 0u) << e;  // the factor has VF fraction bits
  }
  lp.spot_cutoff = 180;
  lp.spot_exponent = 50;
  r.apply(light_writes(r.core, 0, lp));
  for (int64_t x : {-one, int64_t{0}, one}) {
    LightCoreTrace u;
    static_cast<void>(r.core.eval(r.regs, Fragment{{0, 0, one}, {x, 0, -x}}, &u));
    EXPECT_EQ(u.light[0].spot, vone);
  }
  // the cos register at the ends of the range: exactly 0 at 90° (a perpendicular ŝ is inside), 2^VF at 0°
  const int VF = r.core.unit_format().frac;
  EXPECT_EQ(spot_cos_code(VF, 90), 0u);
  EXPECT_EQ(spot_cos_code(VF, 0), uint32_t{1} << VF);
  EXPECT_EQ(spot_cos_code(VF, 60), (uint32_t{1} << VF) / 2);  // cos 60° = ½: ⌈2^VF·½⌉ when sin(30°) rounds to ½
  EXPECT_EQ(spot_cos_code(VF, 180), uint32_t{1} << (VF + 1));  // the smallest VF+2-bit word, −2
  for (double c : {-1.0, 90.5, 179.0, 181.0}) {
    lp.spot_cutoff = c;
    EXPECT_THROW(light_writes(r.core, 0, lp), std::invalid_argument) << c;
  }
  lp.spot_cutoff = 45;
  for (int e : {-1, 129}) {
    lp.spot_exponent = e;
    EXPECT_THROW(light_writes(r.core, 0, lp), std::invalid_argument) << e;
  }
}

// Shininess below the units' range (feature low_shininess, docs/lighting.md §3.5): spec is the exact chain's
// x^n on clamp(x, 0, 1), unnormalised, for every n 0..15 — x^0 = 1 also at x = 0 and below (GL) — and the unit's
// value from n = 16 up; the host writes n < 16 only to a core with the chain; the chain's stages lengthen the front.
TEST(LightHardCases, LowShininessChain) {
  const nlohmann::json base = nlohmann::json::parse(
      R"({"lights": ["directional"], "specular": ["cs16", "schlick_nr"], "norm": true, "reflection": ["blinn", "phong"]})");
  nlohmann::json lj = base;
  lj["low_shininess"] = true;
  const FeatureSet fs = feature_set_from_json(lj, "test");
  const FeatureSet plain = feature_set_from_json(base, "test");
  Rig r(fs);
  const int VF = r.core.unit_format().frac;
  const int64_t one = int64_t{1} << r.F, vone = int64_t{1} << VF;
  LightParams lp;
  lp.position[0] = 0.3, lp.position[1] = 0.2, lp.position[2] = 1, lp.position[3] = 0;
  r.apply(light_writes(r.core, 0, lp));
  MaterialParams m;
  m.specular[0] = m.specular[1] = m.specular[2] = 1.0;
  int checked_zero = 0;
  for (int n = 0; n <= 16; ++n) {
    m.shininess = n;
    for (bool phong : {false, true}) {
      ModeParams md = default_modes(fs);
      md.phong = phong;
      double ga[3] = {0, 0, 0};
      r.apply(global_writes(r.core, ga, md));
      r.apply(material_writes(r.core, m));
      for (int k = 0; k < 40; ++k) {
        // normals sweeping from facing the light to grazing: x runs over (−1, 1]
        const double a = -1.2 + 0.06 * k;
        Fragment fr;
        fr.n[0] = static_cast<int64_t>(std::llround(std::sin(a) * static_cast<double>(one)));
        fr.n[2] = static_cast<int64_t>(std::llround(std::cos(a) * static_cast<double>(one)));
        LightCoreTrace t;
        static_cast<void>(r.core.eval(r.regs, fr, &t));
        const LightTrace& l = t.light[0];
        if (n < 16) {
          const uint64_t xc = static_cast<uint64_t>(std::clamp<int64_t>(l.x, 0, vone));
          EXPECT_EQ(l.spec, powi_chain(VF, xc, static_cast<uint32_t>(n), kLowNBits)) << n << " " << k;
          if (n == 0) {
            EXPECT_EQ(l.spec, static_cast<uint32_t>(vone));
          }
          if (xc == 0 && n == 0) ++checked_zero;
        } else {
          EXPECT_EQ(l.spec, r.core.units()[static_cast<size_t>(r.core.modes(r.regs).unit)].eval(
                                UnitMaterial{static_cast<int>(r.regs.mat_n), r.regs.mat_thr, r.regs.mat_coef}, l.x));
        }
      }
    }
  }
  EXPECT_GT(checked_zero, 0);  // some fragment had x <= 0 with n = 0
  // the host: n < 16 only with the chain; n > 1024 never
  LightCore pc(plain);
  m.shininess = 15;
  EXPECT_THROW(material_writes(pc, m), std::invalid_argument);
  m.shininess = -1;
  EXPECT_THROW(material_writes(r.core, m), std::invalid_argument);
  m.shininess = 1025;
  EXPECT_THROW(material_writes(r.core, m), std::invalid_argument);
  // the chain takes x at the unit's input stage: the front is at least kLowNBits stages longer than x's
  EXPECT_GE(r.core.latency(), pc.latency());
  EXPECT_LE(r.core.latency(), pc.latency() + kLowNBits);
}

// Separate specular colour (feature separate_specular, docs/lighting.md §3.6): light_model bit 4 makes the
// specular sum the secondary output, each sum saturated apart; clear, the output is bit for bit the core without
// the capability and s = 0; a saturating specular term leaves the primary below 1 in the separate mode; without
// the capability bit 4 is ignored; the double reference returns the two apart only when asked and in the mode.
TEST(LightHardCases, SeparateSpecularSplitsTheSums) {
  const nlohmann::json base = nlohmann::json::parse(R"({"lights": ["directional", "point_att"], "specular": "cs16"})");
  nlohmann::json sj = base;
  sj["separate_specular"] = true;
  Rig r(feature_set_from_json(sj, "test"));
  const LightCore plain(feature_set_from_json(base, "test"));
  const uint32_t one = 1u << r.F;
  LightParams lp;
  lp.position[0] = 0, lp.position[1] = 0, lp.position[2] = 1, lp.position[3] = 0;
  lp.specular[0] = lp.specular[1] = lp.specular[2] = 1.9;
  lp.diffuse[0] = 0.3, lp.diffuse[1] = 0.2, lp.diffuse[2] = 0.1;
  r.apply(light_writes(r.core, 0, lp));
  LightParams pp;
  pp.position[0] = 1, pp.position[1] = 2, pp.position[2] = 3, pp.position[3] = 1;
  pp.kq = 0.1;
  r.apply(light_writes(r.core, 1, pp));
  MaterialParams m;
  m.specular[0] = m.specular[1] = m.specular[2] = 1.5;
  m.shininess = 32;
  r.apply(material_writes(r.core, m));
  int saturated = 0;
  for (int k = 0; k < 30; ++k) {
    Fragment fr;
    fr.n[0] = (k - 15) * (int64_t{1} << r.F) / 20;
    fr.n[2] = int64_t{1} << r.F;
    fr.p[2] = -(int64_t{k + 1} << r.F);
    for (bool sep : {false, true}) {
      ModeParams md = default_modes(r.core.features());
      md.separate_specular = sep;
      double ga[3] = {0.1, 0.1, 0.1};
      r.apply(global_writes(r.core, ga, md));
      LightCoreTrace t;
      const Colour c = r.core.eval(r.regs, fr, &t);
      for (int ch = 0; ch < 3; ++ch) {
        const uint64_t p = std::min<uint64_t>(t.total[ch], one), s = std::min<uint64_t>(t.stotal[ch], one);
        EXPECT_EQ(t.total[ch], t.scene[ch] + t.light[0].term[ch] + t.light[1].term[ch]);
        EXPECT_EQ(t.stotal[ch], t.light[0].sterm[ch] + t.light[1].sterm[ch]);
        EXPECT_EQ(c.c[ch], p);
        EXPECT_EQ(c.s[ch], s);
        if (sep && s == one && p < one) ++saturated;
        if (!sep) {
          EXPECT_EQ(s, 0u);
          EXPECT_EQ(c, plain.eval(r.regs, fr));  // the single mode is the core without the capability
        }
      }
      std::array<double, 3> sd{};
      const auto pd = r.core.eval_double(r.regs, fr, LightCore::SpecRef::Exact, nullptr, &sd);
      const auto sum = r.core.eval_double(r.regs, fr, LightCore::SpecRef::Exact);
      for (int ch = 0; ch < 3; ++ch) {
        if (!sep) {
          EXPECT_EQ(sd[ch], 0.0);
        }
        EXPECT_NEAR(sum[ch], std::min(1.0, pd[ch] + sd[ch]), 1e-12);
      }
    }
  }
  EXPECT_GT(saturated, 0);  // the separate mode kept a primary below 1 beside a saturated specular sum
  // without the capability, bit 4 changes nothing and s stays 0
  LightRegs pr = r.regs;
  pr.light_model |= kModelSeparateSpecular;
  const Colour pc = plain.eval(pr, Fragment{{0, 0, int64_t{1} << r.F}, {0, 0, -(int64_t{3} << r.F)}});
  pr.light_model &= ~kModelSeparateSpecular;
  EXPECT_EQ(pc, plain.eval(pr, Fragment{{0, 0, int64_t{1} << r.F}, {0, 0, -(int64_t{3} << r.F)}}));
  EXPECT_EQ(pc.s[0] + pc.s[1] + pc.s[2], 0u);
}

// Two-sided lighting (feature two_side, docs/lighting.md §3.7): in the two-sided mode a back fragment is lit
// exactly as the front fragment with −N and the back colour bank in place of the front one; −N saturates at the
// most negative code; outside the mode, or without the capability, the facing bit changes nothing.
TEST(LightHardCases, TwoSidedBackFaceIsTheFrontWithMinusNAndTheBackBank) {
  const nlohmann::json base = nlohmann::json::parse(R"({"lights": ["directional", "point_att"], "specular": "cs16"})");
  nlohmann::json tj = base;
  tj["two_side"] = true;
  Rig r(feature_set_from_json(tj, "test"));
  const LightCore plain(feature_set_from_json(base, "test"));
  const int64_t one = int64_t{1} << r.F;
  MaterialParams back = two_lights_two_banks(r, -3).second;
  // the same core with the back bank as its front material: the reference for a back fragment
  Rig swapped(feature_set_from_json(tj, "test"));
  swapped.regs = r.regs;
  for (int c = 0; c < 3; ++c) {
    swapped.regs.emission[c] = r.regs.back_emission[c], swapped.regs.ambient[c] = r.regs.back_ambient[c];
    swapped.regs.diffuse[c] = r.regs.back_diffuse[c], swapped.regs.specular[c] = r.regs.back_specular[c];
  }
  double ga[3] = {0.1, 0.1, 0.1};
  ModeParams md = default_modes(r.core.features());
  md.two_side = true;
  r.apply(global_writes(r.core, ga, md));
  swapped.regs.light_model = r.regs.light_model;
  int lit_back = 0;
  for (int k = 0; k < 40; ++k) {
    Fragment fr;
    fr.n[0] = (k % 7 - 3) * one / 3;
    fr.n[1] = (k % 5 - 2) * one / 2;
    fr.n[2] = (k % 3 - 1) * one;
    fr.p[0] = k * one / 10, fr.p[2] = -(int64_t{5} << r.F);
    Fragment bf = fr;
    bf.back = true;
    Fragment neg = fr;
    for (int i = 0; i < 3; ++i) neg.n[i] = -fr.n[i];
    const Colour cb = r.core.eval(r.regs, bf);
    EXPECT_EQ(cb, swapped.core.eval(swapped.regs, neg)) << k;
    if (cb != r.core.eval(r.regs, fr)) ++lit_back;
  }
  EXPECT_GT(lit_back, 20);
  // −N saturates: the most negative code becomes the largest positive one
  Fragment ext;
  for (int i = 0; i < 3; ++i) ext.n[i] = -(int64_t{2} << r.F);
  ext.back = true;
  Fragment sat;
  for (int i = 0; i < 3; ++i) sat.n[i] = (int64_t{2} << r.F) - 1;
  EXPECT_EQ(r.core.eval(r.regs, ext), swapped.core.eval(swapped.regs, sat));
  // the facing bit is ignored outside the two-sided mode and without the capability
  md.two_side = false;
  r.apply(global_writes(r.core, ga, md));
  Fragment f1;
  f1.n[2] = one, f1.p[2] = -one;
  Fragment f2 = f1;
  f2.back = true;
  EXPECT_EQ(r.core.eval(r.regs, f1), r.core.eval(r.regs, f2));
  LightRegs pr = r.regs;
  pr.light_model |= kModelTwoSide;
  EXPECT_EQ(plain.eval(pr, f1), plain.eval(pr, f2));
  // the back colour bank holds only colours: the shininess is the unit material's (unit_material_writes), the same
  // words as material_writes' first ones
  back.shininess = 41;
  for (const auto& w : back_material_writes(r.core, back))
    EXPECT_TRUE(w.addr != kReg_mat_n && w.addr != kReg_mat_thr && w.addr != kReg_mat_coef && w.addr != kReg_mat_unit);
  const auto uw = unit_material_writes(r.core, back), mw = material_writes(r.core, back);
  ASSERT_LE(uw.size(), mw.size());
  for (size_t i = 0; i < uw.size(); ++i) EXPECT_TRUE(uw[i].addr == mw[i].addr && uw[i].data == mw[i].data) << i;
}

// Colour material (feature colour_material, docs/lighting.md §3.8): with the register's bit 0 the fragment's
// colour stands for the material colour(s) its mode names, of the bank the fragment is lit with — exactly as
// the same registers holding that colour (eval and eval_double); mode fields 5..7, bit 0 clear and a core without
// the capability ignore the colour.
TEST(LightHardCases, ColourMaterialIsTheChosenRegistersHoldingTheColour) {
  const nlohmann::json base = nlohmann::json::parse(R"({"lights": ["directional", "point_att"], "specular": "cs16"})");
  nlohmann::json cj = base;
  cj["colour_material"] = true;
  cj["two_side"] = true;
  Rig r(feature_set_from_json(cj, "test"));
  const LightCore plain(feature_set_from_json(base, "test"));
  const int64_t one = int64_t{1} << r.F;
  two_lights_two_banks(r, 3);
  double ga[3] = {0.3, 0.6, 1.2};
  ModeParams md = default_modes(r.core.features());
  md.two_side = true;
  r.apply(global_writes(r.core, ga, md));
  const uint32_t cmax = (2u << r.F) - 1;
  const uint32_t cols[][3] = {{0, 0, 0}, {1u << r.F, 1u << r.F, 1u << r.F}, {cmax, 0, 12345}, {77777, cmax, 1}};
  using CM = ColourMaterial;
  int changed = 0;
  for (CM m : {CM::Emission, CM::Ambient, CM::Diffuse, CM::Specular, CM::AmbientAndDiffuse}) {
    LightRegs on = r.regs;
    on.write(r.core.widths(), kReg_colour_material, colour_material_word(true, m));
    for (const auto& col : cols)
      for (int k = 0; k < 24; ++k) {
        Fragment fr;
        fr.n[0] = (k % 7 - 3) * one / 3, fr.n[1] = (k % 5 - 2) * one / 2, fr.n[2] = (k % 3 - 1) * one + one / 2;
        fr.p[0] = k * one / 10, fr.p[2] = -(int64_t{5} << r.F);
        fr.back = k % 2 == 1;
        for (int c = 0; c < 3; ++c) fr.col[c] = col[c];
        // the reference: colour material off, the colour in the registers of the fragment's bank
        LightRegs ref = r.regs;
        for (int c = 0; c < 3; ++c) {
          const uint32_t bank = fr.back ? kReg_back_mat_emission : kReg_mat_emission;
          const uint32_t off = bank - kReg_mat_emission;  // the back bank keeps the front's layout
          auto put = [&](uint32_t a) { ref.write(r.core.widths(), a + off + static_cast<uint32_t>(c), col[c]); };
          if (m == CM::Emission) put(kReg_mat_emission);
          if (m == CM::Ambient || m == CM::AmbientAndDiffuse) put(kReg_mat_ambient);
          if (m == CM::Diffuse || m == CM::AmbientAndDiffuse) put(kReg_mat_diffuse);
          if (m == CM::Specular) put(kReg_mat_specular);
        }
        const Colour got = r.core.eval(on, fr);
        EXPECT_EQ(got, r.core.eval(ref, fr)) << static_cast<int>(m) << " " << k;
        EXPECT_EQ(r.core.eval_double(on, fr, LightCore::SpecRef::Exact), r.core.eval_double(ref, fr, LightCore::SpecRef::Exact));
        if (got != r.core.eval(r.regs, fr)) ++changed;
        // ignored: bit 0 clear, mode fields 5..7, a core without the capability
        LightRegs off = on;
        off.colour_material &= ~1u;
        EXPECT_EQ(r.core.eval(off, fr), r.core.eval(r.regs, fr));
        for (uint32_t w : {11u, 13u, 15u}) {
          LightRegs none = r.regs;
          none.write(r.core.widths(), kReg_colour_material, w);
          EXPECT_EQ(r.core.eval(none, fr), r.core.eval(r.regs, fr)) << w;
        }
        Fragment front_only = fr;
        front_only.back = false;
        EXPECT_EQ(plain.eval(on, front_only), plain.eval(r.regs, front_only));
      }
  }
  EXPECT_GT(changed, 5 * 4 * 24 / 2);
}

// N·L exactly 0 and one code either side, with L = (0, 0, 1) exactly.
TEST(LightHardCases, NdotLAroundZero) {
  Rig r(named("gl_default"));
  r.apply(light_writes(r.core, 0, LightParams{}));  // directional (0, 0, 1)
  const int64_t one = int64_t{1} << r.F;
  for (int64_t d : {-1, 0, 1}) {
    Fragment fr;
    fr.n[0] = one;
    fr.n[2] = d * 65;  // after GL_NORMALIZE the z component stays of the order of a code
    LightCoreTrace t;
    static_cast<void>(r.core.eval(r.regs, fr, &t));  // the trace is what is checked
    EXPECT_EQ(t.light[0].f, d > 0) << d;
    // ndl carries the specular path's VF = F + spec_guard fraction bits; diff is ⌊ndl / 2^spec_guard⌋
    const int sg = r.core.unit_format().frac - r.F;
    EXPECT_EQ(t.light[0].diff, d > 0 ? static_cast<uint32_t>(t.light[0].ndl >> sg) : 0u) << d;
    if (d <= 0) {
      EXPECT_EQ(t.light[0].term[0], uint64_t{0} + ((uint64_t{r.regs.ambient[0]} * r.regs.light[0].ambient[0]) >> r.F));
    }
  }
}

// Light at the surface point: D = 0 → L = 0, d = 0, att = 1/kc; with kc = 0 the reciprocal saturates.
TEST(LightHardCases, LightAtSurfacePoint) {
  FeatureSet fs = named("full");
  Rig r(fs);
  LightParams lp;
  lp.position[0] = 1, lp.position[1] = 2, lp.position[2] = -3, lp.position[3] = 1;
  lp.kc = 0.5, lp.kl = 1, lp.kq = 0;
  r.apply(light_writes(r.core, 0, lp));
  const double n[3] = {0, 0, 1}, p[3] = {1, 2, -3};
  LightCoreTrace t;
  static_cast<void>(r.core.eval(r.regs, make_fragment(r.F, n, p), &t));  // the trace is what is checked
  EXPECT_EQ(t.light[0].l[0], 0);
  EXPECT_EQ(t.light[0].d, 0u);
  EXPECT_EQ(t.light[0].att, uint64_t{2} << r.F);  // 1/0.5
  r.regs.light[0].kc = 0;                          // raw q = 0 (setup would reject all-zero coefficients)
  r.regs.light[0].kl = 1 << r.F;
  static_cast<void>(r.core.eval(r.regs, make_fragment(r.F, n, p), &t));  // the trace is what is checked
  EXPECT_EQ(t.light[0].att, att_max(r.F));
}

// Huge distance: the farthest corner of the position range; att stays > 0 and the sum does not wrap.
TEST(LightHardCases, HugeDistance) {
  Rig r(named("full"));
  LightParams lp;
  lp.position[0] = lp.position[1] = lp.position[2] = 127.99, lp.position[3] = 1;
  lp.kc = 0, lp.kl = 0, lp.kq = 0.001;
  r.apply(light_writes(r.core, 0, lp));
  const double n[3] = {1, 1, 1}, p[3] = {-128, -128, -128};
  LightCoreTrace t;
  const Colour c = r.core.eval(r.regs, make_fragment(r.F, n, p), &t);
  // d = (P_j − P)·L̂ against the exact length of the coded difference (0.55-ulp unit vector: < 0.01)
  const Fragment fr = make_fragment(r.F, n, p);
  double d2 = 0;
  for (int i = 0; i < 3; ++i) d2 += std::pow(std::ldexp(double(r.regs.light[0].pos[i] - fr.p[i]), -r.F), 2);
  EXPECT_NEAR(std::ldexp(double(t.light[0].d), -r.F), std::sqrt(d2), 0.01);
  EXPECT_GT(std::sqrt(d2), 443.0);
  EXPECT_GT(t.light[0].att, 0u);
  EXPECT_LE(c.c[0], 1u << r.F);
}

// Back-facing: N·L < 0 → no diffuse, no specular.
TEST(LightHardCases, BackFacing) {
  Rig r(named("gl_default"));
  r.apply(light_writes(r.core, 0, LightParams{}));
  Fragment fr;
  fr.n[2] = -(int64_t{1} << r.F);
  LightCoreTrace t;
  static_cast<void>(r.core.eval(r.regs, fr, &t));  // the trace is what is checked
  EXPECT_LT(t.light[0].ndl, 0);
  EXPECT_EQ(t.light[0].diff, 0u);
  EXPECT_FALSE(t.light[0].f);
}

// H = 0 (L = −V): the half vector normalises to 0, so x = 0 and the unit's output is 0.
TEST(LightHardCases, HalfVectorZero) {
  Rig r(named("gl_default"));
  LightParams lp;
  lp.position[2] = -1;  // L = (0, 0, −1) = −V for the infinite viewer
  r.apply(light_writes(r.core, 0, lp));
  Fragment fr;
  fr.n[2] = int64_t{1} << r.F;
  LightCoreTrace t;
  static_cast<void>(r.core.eval(r.regs, fr, &t));  // the trace is what is checked
  EXPECT_EQ(t.light[0].x, 0);
  EXPECT_EQ(t.light[0].spec, 0u);
}

// Colour sums far above 1 saturate to exactly 2^F, never wrap; mono leaves channels 1 and 2 at 0.
TEST(LightHardCases, SaturatesNeverWraps) {
  for (const char* name : {"full", "mono_spec"}) {
    Rig r(named(name));
    const uint32_t cmax = (1u << (r.F + 1)) - 1;
    for (auto& reg : kRegisters) {
      if (reg.format != "colour") continue;
      for (int j = 0; j < (reg.per_light ? kMaxLights : 1); ++j)
        for (int c = 0; c < reg.count; ++c) r.regs.write(r.core.widths(), reg.addr + c + (reg.per_light ? j * kLightStride : 0), cmax);
    }
    for (int j = 0; j < r.core.features().num_lights(); ++j) {
      r.regs.light[j].kc = 1;  // att saturates
      LightKind k = r.core.features().slot_kind(j);  // the slot's most general kind, enabled
      for (int i = 0; i < kNumLightKinds; ++i)
        if (r.core.features().slot_can(j, static_cast<LightKind>(i))) k = static_cast<LightKind>(i);
      r.regs.light[j].mode = light_mode_word(true, k);
    }
    const double n[3] = {0, 0, 1}, p[3] = {0, 0, -1};
    const Colour c = r.core.eval(r.regs, make_fragment(r.F, n, p));
    EXPECT_EQ(c.c[0], 1u << r.F) << name;
    if (r.core.features().channels == 1) {
      EXPECT_EQ(c.c[1], 0u);
      EXPECT_EQ(c.c[2], 0u);
    }
  }
}

// Every light off (light colours 0): colour = emission + a·A exactly.
TEST(LightHardCases, EveryLightOff) {
  Rig r(named("full"));
  for (int j = 0; j < kMaxLights; ++j) {
    LightParams lp;
    lp.position[3] = 1;
    lp.diffuse[0] = lp.diffuse[1] = lp.diffuse[2] = 0;
    lp.specular[0] = lp.specular[1] = lp.specular[2] = 0;
    r.apply(light_writes(r.core, j, lp));
  }
  const double n[3] = {0.2, 0.3, 0.9}, p[3] = {1, 1, -5};
  LightCoreTrace t;
  const Colour c = r.core.eval(r.regs, make_fragment(r.F, n, p), &t);
  for (int ch = 0; ch < 3; ++ch) EXPECT_EQ(c.c[ch], t.scene[ch]);
}

TEST(LightSetup, RejectsAllZeroAttenuationAndBadValues) {
  LightCore core(named("full"));
  LightParams lp;
  lp.position[3] = 1;
  lp.kc = lp.kl = lp.kq = 0;
  EXPECT_THROW(light_writes(core, 0, lp), std::invalid_argument);
  lp.kc = 1;
  lp.diffuse[0] = -0.1;
  EXPECT_THROW(light_writes(core, 0, lp), std::invalid_argument);
  lp.diffuse[0] = 0.5;
  lp.position[0] = 200;
  EXPECT_THROW(light_writes(core, 0, lp), std::invalid_argument);
  EXPECT_THROW(light_writes(core, 8, LightParams{}), std::invalid_argument);
  MaterialParams m;
  m.shininess = -1;  // full has the low-shininess chain: 0..1024
  EXPECT_THROW(material_writes(core, m), std::invalid_argument);
  m.shininess = 1025;
  EXPECT_THROW(material_writes(core, m), std::invalid_argument);
  m.shininess = 15;
  EXPECT_NO_THROW(material_writes(core, m));
  EXPECT_THROW(material_writes(LightCore(named("gl_default")), m), std::invalid_argument);
}

TEST(FeatureSets, NamedSetsParseAndDiffer) {
  const auto sets = named_feature_sets();
  ASSERT_GE(sets.size(), 2u);
  std::set<std::string> keys;
  for (const auto& s : sets) keys.insert(s.key());
  EXPECT_EQ(keys.size(), sets.size());
  const FeatureSet full = named("full");
  EXPECT_EQ(full.num_lights(), kMaxLights);
  EXPECT_EQ(full.channels, 3);
  const FeatureSet diff = named("diffuse");
  EXPECT_FALSE(diff.specular);
  EXPECT_EQ(diff.num_lights(), 1);
}

TEST(FeatureSets, StrictParsing) {
  using nlohmann::json;
  auto bad = [](const std::string& text, const std::string& needle) {
    try {
      feature_set_from_json(json::parse(text), "t");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  };
  bad(R"({"lightz": []})", "unknown key 'lightz'");
  bad(R"({"lights": []})", "1..8");
  bad(R"({"lights": ["spotlight"]})", "unknown light kind 'spotlight' (known: directional, point, point_att, spot)");
  bad(R"({"lights": ["lamp"]})", "unknown light kind 'lamp'");
  bad(R"({"lights": [["point", "point"]]})", "names a kind twice");
  bad(R"({"lights": ["point"], "lanes": 2})", "exceeds the 1 light slots");
  bad(R"({"lanes": 0})", "'lanes' must be an integer 1..8");
  bad(R"({"share": 0})", "'share' must be an integer 1..4");
  bad(R"({"share": 5})", "'share' must be an integer 1..4");
  bad(R"({"share": 2.5})", "'share' must be an integer 1..4");
  bad(R"({"lights": ["point", "point"], "lanes": 2, "share": 2})", "'share' 2 needs 'lanes' 1");
  bad(R"({"mreg": 2})", "'mreg' must be 0 or 1");
  bad(R"({"mreg": true})", "'mreg' must be 0 or 1");
  // the pipelining parameter at share > 1 (issue 35: full_shared + mreg): accepted, its latency grows as at share 1
  EXPECT_EQ(feature_set_from_json(json::parse(R"({"mreg": 1, "share": 2})"), "t").mreg, 1);
  bad(R"({"specular": ["cs16", "cs16"]})", "named twice");
  bad(R"({"specular": ["cs16", "none"]})", "none cannot be listed");
  bad(R"({"specular": ["schlick_iter", "cs16"]})", "cannot share a core");
  bad(R"({"specular": ["cs16", "table256"]})", "no table-load port");
  bad(R"({"reflection": ["blinn", "torrance"]})", "blinn, phong or a list of both");
  bad(R"({"lights": ["point","point","point","point","point","point","point","point","point"]})", "1..8");
  bad(R"({"channels": 2})", "1 or 3");
  bad(R"({"ambient": 1})", "true or false");
  bad(R"({"config": "wide"})", "frac <= 16");
  bad(R"({"specular": "none", "norm": true})", "'norm' needs a specular unit");
  bad(R"({"specular": "schlick_div", "cutoff": "sign_clamp"})", "cs16 unit only");
  bad(R"({"specular": "phong"})", "unknown variant 'phong'");
  EXPECT_THROW(feature_set_named_or_file("no_such_set_or_file"), std::invalid_argument);
}

// The capability JSON: lists of kinds per slot, several units, both reflections, lanes; canonical
// round trip; today's one-kind `lights` lists keep parsing.
TEST(FeatureSets, CapabilitiesParseAndRoundTrip) {
  using nlohmann::json;
  const FeatureSet f = feature_set_from_json(
      json::parse(R"({"lights": [["directional", "point_att"], "point"], "specular": ["cs16", "schlick_nr"],
                      "reflection": ["blinn", "phong"], "local_viewer": true, "norm": true, "lanes": 2})"),
      "t");
  EXPECT_EQ(f.slots, (std::vector<uint8_t>{uint8_t(kind_bit(LightKind::Directional) | kind_bit(LightKind::PointAtt)),
                                           kind_bit(LightKind::Point)}));
  EXPECT_EQ(f.units(), (std::vector<VariantId>{VariantId::cs16, VariantId::schlick_nr}));
  EXPECT_TRUE(f.blinn && f.phong);
  EXPECT_EQ(f.lanes, 2);
  const FeatureSet g = feature_set_from_json(json::parse(f.canonical().dump()), "t");
  EXPECT_EQ(g.key(), f.key());
  const FeatureSet old = feature_set_from_json(json::parse(R"({"lights": ["point_att", "directional"]})"), "t");
  EXPECT_EQ(old.lanes, 1);
  EXPECT_EQ(old.slot_kind(0), LightKind::PointAtt);
  EXPECT_FALSE(old.slot_can(0, LightKind::Directional));
  const FeatureSet full = named("full"), par = named("full_parallel");
  EXPECT_EQ(full.lanes, 1);
  EXPECT_EQ(par.lanes, 8);
  EXPECT_TRUE(full.has_unit(VariantId::cs16) && full.has_unit(VariantId::schlick_nr));
  for (int j = 0; j < kMaxLights; ++j) EXPECT_EQ(full.slots[j], kAllKinds);
  EXPECT_NE(full.key(), par.key());
}

// Mode registers naming an absent capability (docs/lighting.md §4): a kind the slot cannot take or the
// reserved spot kind leaves the light off; local viewer / normalize without the hardware are off; with
// one reflection the bit is ignored; a mat_unit naming an absent unit gives specular 0.
TEST(LightModes, AbsentCapabilitiesDecodeAsDocumented) {
  using nlohmann::json;
  const FeatureSet fs = feature_set_from_json(
      json::parse(R"({"lights": ["directional", ["point", "point_att"]], "specular": "cs16", "reflection": "phong",
                      "local_viewer": false, "normalize": false})"),
      "t");
  const LightCore core(fs);
  LightRegs r;
  const int F = core.format().frac;
  r.write(core.widths(), kReg_light_model, kModelLocalViewer | kModelNormalize);  // both absent; bit 1 clear but only Phong exists
  r.write(core.widths(), kReg_mat_unit, static_cast<uint32_t>(VariantId::cs16));
  r.write(core.widths(), kReg_light_mode, light_mode_word(true, LightKind::Point));  // slot 0 cannot be a point light
  r.write(core.widths(), kLightStride + kReg_light_mode, light_mode_word(true, LightKind::Point));
  LightModes m = core.modes(r);
  EXPECT_FALSE(m.local_viewer);
  EXPECT_FALSE(m.normalize);
  EXPECT_TRUE(m.phong);
  EXPECT_EQ(m.on, 2u);
  EXPECT_EQ(m.unit, 0);
  r.write(core.widths(), kLightStride + kReg_light_mode, (3u << 1) | 1u);  // spot: reserved
  EXPECT_EQ(core.modes(r).on, 0u);
  EXPECT_EQ(core.passes(r), 1);
  // mat_unit names schlick_nr, which this core lacks: the specular term is 0 (f false), nothing else changes
  r.write(core.widths(), kReg_light_mode, light_mode_word(true, LightKind::Directional));
  for (int c = 0; c < 3; ++c) {
    r.write(core.widths(), kReg_mat_specular + c, 1u << F);
    r.write(core.widths(), kReg_light_specular + c, 1u << F);
    r.write(core.widths(), kReg_mat_diffuse + c, 1u << (F - 1));
    r.write(core.widths(), kReg_light_diffuse + c, 1u << F);
  }
  r.write(core.widths(), kReg_mat_n, 16);
  r.write(core.widths(), kReg_light_position + 2, 1u << F);  // L = (0, 0, 1)
  Fragment fr;
  fr.n[2] = int64_t{1} << F;  // N = L = V: x = 1, spec = 1
  LightCoreTrace with, without;
  const Colour a = core.eval(r, fr, &with);
  r.write(core.widths(), kReg_mat_unit, static_cast<uint32_t>(VariantId::schlick_nr));
  EXPECT_EQ(core.modes(r).unit, -1);
  const Colour b = core.eval(r, fr, &without);
  EXPECT_TRUE(with.light[0].f);
  EXPECT_FALSE(without.light[0].f);
  EXPECT_EQ(a.c[0], 1u << F);           // diffuse ½ + specular 1, saturated
  EXPECT_EQ(b.c[0], 1u << (F - 1));     // diffuse only
}

// A directional light's position register holds a unit direction; the core reads each component
// saturated to the signed F+2 bits of [−2, 2) (docs/lighting.md §1): a code beyond gives what the range's
// end gives, and a unit code is taken as written.
TEST(LightModes, DirectionalCodeSaturatesToTheUnitRange) {
  using nlohmann::json;
  const FeatureSet fs = feature_set_from_json(
      json::parse(R"({"lights": ["directional"], "specular": "cs16", "reflection": "blinn"})"), "t");
  const LightCore core(fs);
  const int F = core.format().frac;
  const int E = core.unit_format().frac - F;
  LightRegs r;
  r.write(core.widths(), kReg_mat_unit, static_cast<uint32_t>(VariantId::cs16));
  r.write(core.widths(), kReg_light_mode, light_mode_word(true, LightKind::Directional));
  const uint32_t pmask = static_cast<uint32_t>(mask_bits(light_pos_bits(F)));
  const int64_t hi = (int64_t{1} << (F + 1)) - 1, lo = -(int64_t{1} << (F + 1));
  Fragment fr;
  fr.n[0] = int64_t{1} << (F - 1), fr.n[1] = -(int64_t{1} << (F - 2)), fr.n[2] = int64_t{1} << F;
  auto trace = [&](int64_t x, int64_t y, int64_t z) {
    r.write(core.widths(), kReg_light_position + 0, static_cast<uint32_t>(x) & pmask);
    r.write(core.widths(), kReg_light_position + 1, static_cast<uint32_t>(y) & pmask);
    r.write(core.widths(), kReg_light_position + 2, static_cast<uint32_t>(z) & pmask);
    LightCoreTrace t;
    const Colour c = core.eval(r, fr, &t);
    return std::make_pair(c, t.light[0]);
  };
  const auto big = trace(int64_t{1} << (F + 6), -(int64_t{1} << (F + 7)), hi + 1);   // beyond [−2, 2)
  const auto edge = trace(hi, lo, hi);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(big.first.c[c], edge.first.c[c]);
  EXPECT_EQ(big.second.l[0], hi << E);
  EXPECT_EQ(big.second.l[1], lo << E);
  EXPECT_EQ(big.second.l[2], hi << E);
  EXPECT_EQ(big.second.x, edge.second.x);
  const auto unit = trace(0, -(int64_t{1} << F), 0);   // a unit code: as written
  EXPECT_EQ(unit.second.l[1], -(int64_t{1} << (F + E)));
  EXPECT_EQ(unit.second.l[0], 0);
  // N̂·L saturates to [−8, 8) (signed VF+4 bits): reachable only with a code beyond the unit range —
  // here N = (2, 2, 2) − 1 code each (no GL_NORMALIZE) and L = (2, 2, 2) − 1 code: N·L ≈ 12
  fr.n[0] = fr.n[1] = fr.n[2] = hi;
  const auto sat = trace(hi, hi, hi);
  EXPECT_EQ(sat.second.ndl, (int64_t{1} << (F + E + 3)) - 1);
  EXPECT_EQ(sat.second.diff, 1u << F);   // diff clamps to 1 as it would unsaturated
  EXPECT_TRUE(sat.second.f);
}

// Passes and latency: ⌈k/lanes⌉ passes (one with no light), one more issue interval per pass.
TEST(LightModes, PassesAndLatencyFollowTheEnabledLights) {
  for (int lanes : {1, 2, 3, 8}) {
    FeatureSet fs = named("full");
    fs.lanes = lanes;
    fs.share = 1;
    const LightCore core(fs);
    LightRegs r;
    r.mat_unit = static_cast<uint32_t>(VariantId::cs16);
    const int base = core.latency(r);
    EXPECT_EQ(core.passes(r), 1);
    for (int k = 1; k <= kMaxLights; ++k) {
      r.light[static_cast<size_t>(k - 1)].mode = light_mode_word(true, LightKind::PointAtt);
      EXPECT_EQ(core.passes(r), (k + lanes - 1) / lanes) << lanes << " " << k;
      EXPECT_EQ(core.latency(r), base + (k + lanes - 1) / lanes - 1);
      EXPECT_LE(core.latency(r), core.latency());
    }
    r.mat_unit = static_cast<uint32_t>(VariantId::schlick_nr);  // 3 edges longer than cs16
    EXPECT_EQ(core.latency(r), base + 3 + (kMaxLights + lanes - 1) / lanes - 1);
  }
}

// share S (docs/lighting.md §2.1): a pass issues every S-th front-advancing edge, and the pass's
// normalisations enter the shared normalisers at stages ≡ their number (mod S), which moves V̂, L̂ and
// H = L + V later. The stage times of `full` (N, V, L, H all exist), worked out by hand from the rule:
//   S = 1: V̂, L̂ at 10, H at 10, x (Blinn) at 21: front 21; + cs16 7 + norm 2 + back 4 = 34
//   S = 2: V̂ at 11, L̂ at 10, H at 11 (≡ 1), x at 22: 35
//   S = 3: V̂ 11, L̂ 12, H 12 (≡ 0), x at 23; spot (§3.4): att at 12+3+7+1 = 23, the chain's factor at 12+2+8 = 22,
//          att·spot registered at 24: front 24: 37
//   S = 4: V̂ at 11, L̂ at 12, H at 15 (≡ 3), x at 26 (att·spot at 24): 39, + 2 for the channel-serial back
//          (S >= 4, RGB): 41
//   (S = 1, 2: att·spot at 21, 22, no later than x)
// That is `full` without its low-shininess chain; with it (§3.5) the chain's value is there 4 stages after x:
// front 25, 26, 27, 30: 38, 39, 40, 45.
// Each further pass adds S edges; schlick_iter's F+4 (25 at F = 16 + spec_guard 5) rounds up to S's multiple.
TEST(LightModes, ShareSpacesThePassesAndMovesTheSharedNormalisations) {
  for (bool low : {false, true})
  for (int share = 1; share <= kShareMax; ++share) {
    const int expect_base[5] = {0, low ? 38 : 34, low ? 39 : 35, low ? 40 : 37, low ? 45 : 41};
    FeatureSet fs = named("full");
    fs.low_shininess = low;
    fs.lanes = 1;
    fs.share = share;
    const LightCore core(fs);
    EXPECT_EQ(core.pass_interval(), share);
    LightRegs r;
    r.mat_unit = static_cast<uint32_t>(VariantId::cs16);
    EXPECT_EQ(core.latency(r), expect_base[share]) << "share " << share;
    for (int k = 1; k <= kMaxLights; ++k) {
      r.light[static_cast<size_t>(k - 1)].mode = light_mode_word(true, LightKind::PointAtt);
      EXPECT_EQ(core.latency(r), expect_base[share] + (k - 1) * share) << share << " " << k;
    }
    FeatureSet it = named("gl_default");
    it.variant = VariantId::schlick_iter;
    it.share = share;
    EXPECT_EQ(LightCore(it).pass_interval(), (25 + share - 1) / share * share);
  }
  // the key and the Verilog parameters carry it
  FeatureSet a = named("gl_default"), b = a;
  b.share = 2;
  EXPECT_NE(a.key(), b.key());
  EXPECT_EQ(b.canonical()["share"], 2);
  bool found = false;
  for (const auto& p : b.verilog_params(8)) found = found || p == "SHARE=2";
  EXPECT_TRUE(found);
}

// The pipelining parameter: every normalisation on a pass's path takes kMregNormalize cycles more, every dot
// product kMregDot, each unit its mreg_stages (configs.json); a set without it keeps its key (and so its
// cached builds), a set with it gets its own key and the MREG parameter.
TEST(LightModes, MregLengthensThePathThroughTheNormalisersAndTheUnits) {
  const FeatureSet base = named("gl_default");  // N̂ and Ĥ = normalise(L̂ + V̂) side by side: one on the path
  FeatureSet m = base;
  m.mreg = 1;
  EXPECT_EQ(base.key(), FeatureSet(base).key());
  EXPECT_FALSE(base.canonical().contains("mreg"));
  EXPECT_NE(base.key(), m.key());
  bool found = false;
  for (const auto& p : m.verilog_params(8)) found = found || p == "MREG=1";
  EXPECT_TRUE(found);
  for (const auto& p : base.verilog_params(8)) EXPECT_EQ(p.find("MREG"), std::string::npos) << p;
  const LightCore c0(base), c1(m);
  LightRegs r;
  r.mat_unit = static_cast<uint32_t>(VariantId::cs16);
  // (the back without attenuation: B1 and B2 one stage more each; N̂ registered once more before N̂·L, which with
  // directional lights and an infinite viewer is what sets the front's length)
  EXPECT_EQ(c1.latency(r) - c0.latency(r),
            kMregNormalize + kMregN + kMregDot + 2 * kMregBack + mreg_stages(VariantId::cs16));
  // a point light's P_j − P registered (kMregP), its L̂, then Ĥ = normalise(L̂ + V̂): two in series
  FeatureSet p = base, pm;
  p.slots = {kind_bit(LightKind::Point)};
  pm = p;
  pm.mreg = 1;
  r.light[0].mode = light_mode_word(true, LightKind::Point);
  EXPECT_EQ(LightCore(pm).latency(r) - LightCore(p).latency(r),
            kMregP + 2 * kMregNormalize + kMregDot + 2 * kMregBack + mreg_stages(VariantId::cs16));
  // an attenuated point light on a diffuse-only core: the attenuation sets the front's length (P_j − P registered,
  // L̂, the distance's dot product, q's two products and sc_recip's four), and the back has B3 too
  FeatureSet a = named("diffuse"), am;
  a.slots = {kind_bit(LightKind::PointAtt)};
  am = a;
  am.mreg = 1;
  r.light[0].mode = light_mode_word(true, LightKind::PointAtt);
  EXPECT_EQ(LightCore(am).latency(r) - LightCore(a).latency(r),
            kMregP + kMregNormalize + kMregDot + kMregAtt + kMregRecip + 3 * kMregBack);
  // the same light at share 2 (q's extra shared stage at share > 1 gives way to the MREG cuts, hence the − 1). Without
  // GL_NORMALIZE, L is normalisation 0 of the pass: its phase-0 entry comes before P_j − P's register, so it enters a
  // full turn (2 edges) later instead of kMregP; with GL_NORMALIZE it is normalisation 1, entering at phase 1 after
  // that register: no extra edge at all
  FeatureSet a2 = a, a2m;
  a2.share = 2;
  a2m = a2;
  a2m.mreg = 1;
  ASSERT_FALSE(a2.normalize);
  EXPECT_EQ(LightCore(a2m).latency(r) - LightCore(a2).latency(r),
            2 + kMregNormalize + kMregDot + kMregAtt + kMregRecip - 1 + 3 * kMregBack);
  FeatureSet n2 = a2, n2m;
  n2.normalize = true;
  n2m = n2;
  n2m.mreg = 1;
  EXPECT_EQ(LightCore(n2m).latency(r) - LightCore(n2).latency(r),
            kMregNormalize + kMregDot + kMregAtt + kMregRecip - 1 + 3 * kMregBack);
  // a spot light: the spot factor's power chain takes 1 + kMregPowi edges per exponent bit, the attenuation
  // its cuts; att · spot is registered one stage after the later of the two (at every share)
  FeatureSet sp = named("diffuse"), spm;
  sp.slots = {kind_bit(LightKind::Spot)};
  spm = sp;
  spm.mreg = 1;
  r.light[0].mode = light_mode_word(true, LightKind::Spot);
  const int att0 = 3 + kRecipLatency, spot0 = 2 + kSpotExpBits;
  const int att1 = 3 + kMregDot + kRecipLatency + kMregAtt + kMregRecip;
  const int spot1 = 2 + kMregDot + kSpotExpBits * (1 + kMregPowi);
  EXPECT_EQ(LightCore(spm).latency(r) - LightCore(sp).latency(r),
            kMregP + kMregNormalize + std::max(att1, spot1) - std::max(att0, spot0) + 3 * kMregBack);
  // (that the RTL computes the same colours at that latency is the co-simulation's: ctest sim.light.mreg.*,
  // sim.light.share3_mreg.*, sim.light.full_shared_mreg.*)
}

// The lighting core's legal ranges in features.hpp state config/configs.json "limits" (generated
// shadecore/limits.hpp); rtl/sc_light.v's checks state them too (ctest rtl.limits_agree). A mismatch
// does not compile.
static_assert(kLightFracMax == limits::kLightFracMax, "features.hpp kLightFracMax != configs.json limits.light_frac.max");
static_assert(kSpecGuardMax == limits::kSpecGuardMax, "features.hpp kSpecGuardMax != configs.json limits.spec_guard.max");
static_assert(kShareMax == limits::kShareMax, "features.hpp kShareMax != configs.json limits.share.max");
static_assert(kLightFracMax + kSpecGuardMax <= limits::kFracMax, "F + spec_guard must stay within the units' widest format");

TEST(Limits, LightingRangesAreTheConfigured) {
  EXPECT_EQ(kLightFracMax, limits::kLightFracMax);
  EXPECT_EQ(kSpecGuardMax, limits::kSpecGuardMax);
  EXPECT_EQ(kShareMax, limits::kShareMax);
  EXPECT_EQ(kFracMin, limits::kLightFracMin);  // the core takes the units' narrowest format too
}
