// SPDX-License-Identifier: Apache-2.0
// Hard cases and exhaustive properties of the bit-accurate cs16 model (docs/spec.md §2–3).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>
#include <string>

#include "shadecore/configs.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/units/hard_cases.hpp"

using namespace shadecore;

namespace {

const Format kDefault = default_format();

// Spec §3.3: −(½ + 15·2^−G) < out − y·2^F ≤ +½, y the double cs16 of the same code (same cut).
struct Bound {
  double lo, hi;
};
Bound spec_bound(const Format& f) { return {-(0.5 + 15.0 * std::ldexp(1.0, -f.guard)), 0.5}; }

double golden_same_cut(const Format& f, Cutoff cut, const Cs16Material& m, int64_t code) {
  Cs16Trace tr;
  cs16_eval(f, cut, m, code, &tr);
  if (tr.cut) return 0.0;
  return golden::pow16(golden::cs16_base(std::ldexp(double(tr.c), -f.frac), m.n));
}

// Checks the error bound for one (n, code); returns the error in ulps.
double check_bound(const Format& f, Cutoff cut, const Cs16Material& m, int64_t code) {
  const double y = golden_same_cut(f, cut, m, code) * std::ldexp(1.0, f.frac);
  const double e = double(cs16_eval(f, cut, m, code)) - y;
  const Bound b = spec_bound(f);
  EXPECT_GT(e, b.lo) << "F=" << f.frac << " G=" << f.guard << " n=" << m.n << " code=" << code;
  EXPECT_LE(e, b.hi) << "F=" << f.frac << " G=" << f.guard << " n=" << m.n << " code=" << code;
  return e;
}

void exhaustive_bound(const Format& f, int n, Cutoff cut = Cutoff::ThetaCr) {
  const Cs16Material m = cs16_setup(f, n);
  int failures = 0;
  const Bound b = spec_bound(f);
  for (int64_t code = 0; code <= f.one() && failures < 5; ++code) {
    const double y = golden_same_cut(f, cut, m, code) * std::ldexp(1.0, f.frac);
    const double e = double(cs16_eval(f, cut, m, code)) - y;
    if (!(e > b.lo && e <= b.hi)) {
      ++failures;
      ADD_FAILURE() << "bound violated: F=" << f.frac << " n=" << n << " code=" << code << " err=" << e << " ulp";
    }
  }
}

}  // namespace

TEST(Format, RejectsIllegalWidths) {
  EXPECT_THROW(validate(Format{7, 5}), std::invalid_argument);
  EXPECT_THROW(validate(Format{25, 5}), std::invalid_argument);
  EXPECT_THROW(validate(Format{16, 3}), std::invalid_argument);
  EXPECT_THROW(validate(Format{16, 9}), std::invalid_argument);
  EXPECT_THROW(validate(Format{24, 8}), std::invalid_argument);  // F+G = 32 > 31
  EXPECT_NO_THROW(validate(Format{24, 7}));
  EXPECT_NO_THROW(validate(Format{8, 4}));
}

TEST(Format, NamedConfigsAreLegal) {
  ASSERT_GE(kConfigs.size(), 3u);
  bool has_default = false;
  for (const auto& c : kConfigs) {
    EXPECT_NO_THROW(validate(c.format)) << c.name;
    has_default |= (c.name == kDefaultConfig);
  }
  EXPECT_TRUE(has_default);
}

TEST(Cs16Setup, RejectsIllegalExponents) {
  for (long long n : {0LL, 15LL, 1025LL, -1LL, -16LL, 1LL << 40}) {
    try {
      cs16_setup(kDefault, n);
      ADD_FAILURE() << "n = " << n << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("out of range [16, 1024]"), std::string::npos) << e.what();
    }
  }
  EXPECT_NO_THROW(cs16_setup(kDefault, 16));
  EXPECT_NO_THROW(cs16_setup(kDefault, 1024));
}

// thr must not depend on the last ulp of libm's cos: cos(6/√n)·2^F is never within 1e-6 of an integer.
TEST(Cs16Setup, ThresholdNotNearInteger) {
  for (int F = kFracMin; F <= kFracMax; ++F)
    for (int n = kNMin; n <= kNMax; ++n) {
      const double v = std::ldexp(std::cos(6.0 / std::sqrt(double(n))), F);
      EXPECT_GT(std::fabs(v - std::round(v)), 1e-6) << "F=" << F << " n=" << n;
    }
}

// thr is the exact code boundary of θ > θcr, and the code 0 is always cut (spec §2).
TEST(Cs16Setup, ThresholdIsTheCutBoundary) {
  for (const auto& cfg : kConfigs)
    for (int n = kNMin; n <= kNMax; ++n) {
      const Format f = cfg.format;
      const Cs16Material m = cs16_setup(f, n);
      const double ccr = std::cos(golden::theta_cr(n));
      ASSERT_GE(m.thr, 1u);
      EXPECT_GE(std::ldexp(double(m.thr), -f.frac), ccr);
      EXPECT_LT(std::ldexp(double(m.thr) - 1, -f.frac), ccr);
    }
}

// With theta_cr, a shaded fragment has |base| <= 1 (no overflow of the squaring chain).
TEST(Cs16Datapath, BaseMagnitudeBoundedAtThreshold) {
  for (const auto& cfg : kConfigs)
    for (int n = kNMin; n <= kNMax; ++n) {
      const Format f = cfg.format;
      const Cs16Material m = cs16_setup(f, n);
      Cs16Trace tr;
      cs16_eval(f, Cutoff::ThetaCr, m, m.thr, &tr);
      ASSERT_FALSE(tr.cut);
      EXPECT_LE(std::llabs(tr.base), int64_t{1} << (f.frac + 4)) << "n=" << n;
      EXPECT_GT(double(tr.base) / std::ldexp(1.0, f.frac + 4), -0.1218) << "n=" << n;
    }
}

TEST(Cs16Datapath, CosOneGivesExactlyOne) {
  for (const auto& cfg : kConfigs)
    for (Cutoff cut : {Cutoff::ThetaCr, Cutoff::SignClamp})
      for (int n = kNMin; n <= kNMax; ++n)
        ASSERT_EQ(cs16_eval(cfg.format, cut, cs16_setup(cfg.format, n), cfg.format.one()), cfg.format.one())
            << cfg.name << " n=" << n;
}

// Every code above 1.0 (up to the most positive word) saturates to exactly 1.0; never wraps.
TEST(Cs16Datapath, AboveOneSaturates) {
  for (const auto& cfg : kConfigs) {
    const Format f = cfg.format;
    for (int n : hard_case_exponents()) {
      const Cs16Material m = cs16_setup(f, n);
      const int64_t step = std::max<int64_t>(1, f.one() >> 12);
      for (int64_t code = f.one() + 1; code <= f.in_max(); code += (code < f.one() + 64 ? 1 : step))
        ASSERT_EQ(cs16_eval(f, Cutoff::ThetaCr, m, code), f.one()) << cfg.name << " n=" << n << " code=" << code;
      ASSERT_EQ(cs16_eval(f, Cutoff::ThetaCr, m, f.in_max()), f.one());
    }
  }
}

// Every code <= 0 (down to the most negative word) gives 0.
TEST(Cs16Datapath, NonPositiveCosGivesZero) {
  for (const auto& cfg : kConfigs) {
    const Format f = cfg.format;
    for (Cutoff cut : {Cutoff::ThetaCr, Cutoff::SignClamp})
      for (int n : hard_case_exponents()) {
        const Cs16Material m = cs16_setup(f, n);
        const int64_t step = std::max<int64_t>(1, f.one() >> 12);
        for (int64_t code = f.in_min(); code <= 0; code += (code > -64 ? 1 : step))
          ASSERT_EQ(cs16_eval(f, cut, m, code), 0u) << cfg.name << " n=" << n << " code=" << code;
      }
  }
}

// At and one code either side of the θcr threshold and of the base zero.
TEST(Cs16Datapath, CutDecisionsAroundThresholdAndBaseZero) {
  const Format f = kDefault;
  for (int n = kNMin; n <= kNMax; ++n) {
    const Cs16Material m = cs16_setup(f, n);
    Cs16Trace tr;
    cs16_eval(f, Cutoff::ThetaCr, m, m.thr - 1, &tr);
    EXPECT_TRUE(tr.cut) << "n=" << n;
    cs16_eval(f, Cutoff::ThetaCr, m, m.thr, &tr);
    EXPECT_FALSE(tr.cut) << "n=" << n;
    cs16_eval(f, Cutoff::ThetaCr, m, m.thr + 1, &tr);
    EXPECT_FALSE(tr.cut) << "n=" << n;
    // Base zero: base = 2^(F+4) − n·d <= 0  <=>  d >= 2^(F+4)/n.
    const int64_t dz = ((int64_t{1} << (f.frac + 4)) + n - 1) / n;  // smallest d with base <= 0
    const int64_t cz = f.one() - dz;                                // largest code with base <= 0
    cs16_eval(f, Cutoff::SignClamp, m, cz, &tr);
    EXPECT_TRUE(tr.cut) << "n=" << n;
    EXPECT_LE(tr.base, 0);
    cs16_eval(f, Cutoff::SignClamp, m, cz + 1, &tr);
    EXPECT_FALSE(tr.cut) << "n=" << n;
    EXPECT_GT(tr.base, 0);
    if (cz >= 1) {
      cs16_eval(f, Cutoff::SignClamp, m, cz - 1, &tr);
      EXPECT_TRUE(tr.cut);
    }
    for (int64_t code : {int64_t(m.thr) - 1, int64_t(m.thr), int64_t(m.thr) + 1, cz - 1, cz, cz + 1})
      if (code >= 0) check_bound(f, Cutoff::ThetaCr, m, code);
  }
}

// n = 16: the base is exactly cos θ, so cs16 is t^16 with the documented rounding only.
TEST(Cs16Datapath, N16IsTPow16) {
  for (const auto& cfg : kConfigs) {
    const Format f = cfg.format;
    const Cs16Material m = cs16_setup(f, 16);
    const int64_t step = std::max<int64_t>(1, f.one() >> 14);
    for (int64_t code = m.thr; code <= f.one(); code += step) {
      Cs16Trace tr;
      const uint32_t out = cs16_eval(f, Cutoff::ThetaCr, m, code, &tr);
      ASSERT_EQ(tr.x[0], uint64_t(code) << f.guard) << "base must be exactly c at n = 16";
      const double t = std::ldexp(double(code), -f.frac);
      const double e = double(out) - std::pow(t, 16) * std::ldexp(1.0, f.frac);
      const Bound b = spec_bound(f);
      ASSERT_GT(e, b.lo) << code;
      ASSERT_LE(e, b.hi) << code;
    }
  }
}

TEST(Cs16Datapath, N1024WithinBound) {
  for (const auto& cfg : kConfigs) {
    if (cfg.format.frac > 20) continue;  // wide: covered by WideExhaustiveFewN
    exhaustive_bound(cfg.format, 1024);
    exhaustive_bound(cfg.format, 1024, Cutoff::SignClamp);
  }
}

// Exhaustive over every code and every n at the default width: the bound, ≤ 1.0, monotonic.
TEST(Cs16Exhaustive, DefaultWidthBoundMonotonicNeverAboveOne) {
  const Format f = kDefault;
  const Bound b = spec_bound(f);
  const double scale = std::ldexp(1.0, f.frac);
  int failures = 0;
  for (int n = kNMin; n <= kNMax && failures < 5; ++n) {
    const Cs16Material m = cs16_setup(f, n);
    const double ccr = std::cos(golden::theta_cr(n));
    uint32_t prev = 0;
    for (int64_t code = 0; code <= f.one(); ++code) {
      const uint32_t out = cs16_eval(f, Cutoff::ThetaCr, m, code);
      const double c = double(code) / scale;
      const double y = c < ccr ? 0.0 : golden::pow16(golden::cs16_base(c, n)) * scale;
      const double e = double(out) - y;
      if (!(e > b.lo && e <= b.hi) || out < prev || out > f.one()) {
        if (++failures <= 5)
          ADD_FAILURE() << "n=" << n << " code=" << code << " out=" << out << " prev=" << prev << " err=" << e;
      }
      prev = out;
    }
  }
}

// Evidence for spec §1: the two cut-off forms give identical fixed-point outputs.
TEST(CutoffForms, IdenticalOutputs) {
  const Format f = kDefault;
  uint64_t differ = 0;
  for (int n = kNMin; n <= kNMax; ++n) {
    const Cs16Material m = cs16_setup(f, n);
    for (int64_t code = 0; code <= f.one(); ++code)
      differ += cs16_eval(f, Cutoff::ThetaCr, m, code) != cs16_eval(f, Cutoff::SignClamp, m, code);
  }
  EXPECT_EQ(differ, 0u);
}

// Other widths: exhaustive for a few n, random (seeded) for the rest.
TEST(Cs16Widths, NarrowExhaustiveAllN) {
  const Format f{8, 5};
  for (int n = kNMin; n <= kNMax; ++n) exhaustive_bound(f, n);
  const Format g{8, 4};
  for (int n = kNMin; n <= kNMax; ++n) exhaustive_bound(g, n);
}

TEST(Cs16Widths, MidAndWideExhaustiveFewNRandomRest) {
  std::mt19937_64 rng(20261122);
  for (const Format f : {Format{12, 4}, Format{20, 6}, Format{24, 7}}) {
    for (int n : {16, 17, 181, 1024}) exhaustive_bound(f, n);
    std::uniform_int_distribution<int64_t> code_d(0, f.one());
    for (int n = kNMin; n <= kNMax; ++n) {
      const Cs16Material m = cs16_setup(f, n);
      for (int i = 0; i < 2000; ++i) check_bound(f, Cutoff::ThetaCr, m, code_d(rng));
      // Near the peak and near the threshold, where the lobe is steep.
      for (int64_t d = 0; d < 64; ++d) {
        check_bound(f, Cutoff::ThetaCr, m, f.one() - d);
        check_bound(f, Cutoff::ThetaCr, m, int64_t(m.thr) + d);
      }
    }
  }
}

TEST(HardCases, AllWithinSpec) {
  for (const auto& cfg : kConfigs) {
    const auto cases = hard_cases(cfg.format);
    ASSERT_GT(cases.size(), 100u);
    for (const auto& hc : cases) {
      const Cs16Material m = cs16_setup(cfg.format, hc.n);
      const uint32_t out = cs16_eval(cfg.format, Cutoff::ThetaCr, m, hc.code);
      ASSERT_LE(out, cfg.format.one());
      if (hc.code >= 0 && hc.code <= cfg.format.one()) check_bound(cfg.format, Cutoff::ThetaCr, m, hc.code);
    }
  }
}

// The clamp's compare `code > 1.0` is seen one bit at a time: 1.0 + 2^k for every k < F is a hard case.
TEST(HardCases, EveryBitAboveOne) {
  for (const auto& cfg : kConfigs) {
    const auto cases = hard_cases(cfg.format);
    for (int k = 0; k < cfg.format.frac; ++k) {
      const int64_t code = cfg.format.one() + (int64_t{1} << k);
      EXPECT_TRUE(std::any_of(cases.begin(), cases.end(), [code](const HardCase& h) { return h.code == code; }))
          << cfg.name << " k=" << k;
    }
  }
}

// The block form is bit-identical to the per-fragment model on every code, including the
// out-of-range words and both cut-off forms, at every named width (exhaustive at narrow/default).
TEST(Cs16Block, BitIdenticalToScalar) {
  for (const auto& cfg : kConfigs) {
    const Format f = cfg.format;
    const bool full = f.frac <= 16;
    for (Cutoff cut : {Cutoff::ThetaCr, Cutoff::SignClamp})
      for (int n = kNMin; n <= kNMax; n += (full ? 1 : 97)) {
        const Cs16Material m = cs16_setup(f, n);
        // Blocks that straddle every boundary: below 0, the cut, the live lobe, above 1.0.
        const int64_t lo = full ? -3 : int64_t(m.thr) - 1000, hi = full ? f.one() + 3 : f.one() + 1000;
        std::vector<uint32_t> blk(static_cast<size_t>(hi - lo + 1));
        cs16_eval_block(f, cut, m, lo, hi - lo + 1, blk.data());
        for (int64_t code = lo; code <= hi; ++code)
          ASSERT_EQ(blk[size_t(code - lo)], cs16_eval(f, cut, m, code)) << cfg.name << " n=" << n << " code=" << code;
        // A short block starting inside the lobe.
        std::vector<uint32_t> part(7);
        cs16_eval_block(f, cut, m, f.one() - 5, 7, part.data());
        for (int k = 0; k < 7; ++k) ASSERT_EQ(part[size_t(k)], cs16_eval(f, cut, m, f.one() - 5 + k));
      }
  }
}
