// SPDX-License-Identifier: Apache-2.0
// Energy-normalisation coefficients and the fixed-point normalisation stage (docs/spec.md §7).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "shadecore/units/coef.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/analysis/fit.hpp"

using namespace shadecore;

namespace {
constexpr long double kPi = 3.141592653589793238462643383279502884L;
}

// The setup constant at both ends of the exponent range, against the paper's formulas evaluated
// independently here in long double and rounded half up.
TEST(CoefSetup, FittedConstantsAtEnds) {
  const EnergyFormat f{16, kCoefIntBits};
  struct Row { Model m; long double a, b, k; };
  const Row rows[] = {{Model::Phong, 1.063L, 0, 2},   {Model::PhongMod, 1.063L, 1, 2}, {Model::Blinn, 1.068L, 0.96L, 8},
                      {Model::BlinnMod, 1.027L, 4.8L, 8}, {Model::BlinnNdf, 1.063L, 0, 2}, {Model::BlinnHeightfield, 1.063L, 1, 2}};
  for (const Row& r : rows)
    for (int n : {16, 1024}) {
      const long double c = (r.a * n + r.b) / (r.k * kPi);
      const auto expect = static_cast<uint32_t>(std::floor(c * 65536.0L + 0.5L));
      EXPECT_EQ(energy_setup(f, r.m, CoefKind::Fitted, n), expect) << info(r.m).key << " n=" << n;
    }
  // The largest coefficient of all: fitted modified Phong at n = 1024, (1.063·1024 + 1)/2π ≈ 173.4.
  EXPECT_NEAR(fitted_coef(Model::PhongMod, 1024), 173.40, 0.01);
}

// Every coefficient of every model and kind over n = 16..1024 fits the I = 8 integer bits at every
// legal F, and the per-fragment product at the largest coefficient and output 1.0 does not overflow.
TEST(CoefSetup, LargestCoefficientFitsAndProductDoesNotOverflow) {
  for (int F = kFracMin; F <= kFracMax; ++F) {
    const EnergyFormat f{F, kCoefIntBits};
    uint32_t cmax = 0;
    for (const auto& mi : kModels)
      for (CoefKind k : {CoefKind::Fitted, CoefKind::Classical})
        for (int n = kNMin; n <= kNMax; ++n) cmax = std::max(cmax, energy_setup(f, mi.model, k, n));
    EXPECT_LT(cmax, uint64_t{1} << f.coef_bits());
    for (uint32_t coef : {cmax, static_cast<uint32_t>((uint64_t{1} << f.coef_bits()) - 1)}) {
      const uint32_t spec = 1u << F;  // 1.0, the largest unit output
      const unsigned __int128 exact = (static_cast<unsigned __int128>(spec) * coef + (1u << (F - 1))) >> F;
      const uint64_t got = energy_eval(f, coef, spec);
      EXPECT_EQ(got, static_cast<uint64_t>(exact)) << "F=" << F;
      EXPECT_LT(got, uint64_t{1} << f.out_bits()) << "F=" << F;
    }
  }
}

TEST(CoefSetup, RoundsHalfUpAndRejectsBadValues) {
  const EnergyFormat f{16, 8};
  EXPECT_EQ(coef_code(f, (1000 + 0.5) / 65536.0), 1001u);
  EXPECT_EQ(coef_code(f, (1000 + 0.49) / 65536.0), 1000u);
  EXPECT_EQ(coef_code(f, (1000 + 0.51) / 65536.0), 1001u);
  EXPECT_EQ(coef_code(f, 0.0), 0u);
  EXPECT_EQ(coef_code(f, 255.0 + 65535.49 / 65536.0), (1u << 24) - 1);
  EXPECT_THROW(coef_code(f, 256.0), std::invalid_argument);
  EXPECT_THROW(coef_code(f, 255.0 + 65535.5 / 65536.0), std::invalid_argument);  // rounds up to 256
  EXPECT_THROW(coef_code(f, -1.0), std::invalid_argument);
  EXPECT_THROW(coef_code(f, std::nan("")), std::invalid_argument);
  EXPECT_THROW(coef_code(EnergyFormat{7, 8}, 1.0), std::invalid_argument);
  EXPECT_THROW(coef_code(EnergyFormat{16, 0}, 1.0), std::invalid_argument);
  EXPECT_THROW(energy_setup(f, Model::Phong, CoefKind::Fitted, 15), std::invalid_argument);
  EXPECT_THROW(energy_setup(f, Model::Phong, CoefKind::Fitted, 1025), std::invalid_argument);
}

// coef·2^F is never within 64 double ulps (of coef·2^F) of a rounding tie, so a last-few-ulp
// difference in the double evaluation (libm exp2, FMA contraction) cannot change a setup constant
// (the argument of thr(n), spec §3.1). The closest case, measured: F = 18, modified Blinn classical,
// n = 900, 4.6e-7 from the tie = 245 ulps.
TEST(CoefSetup, SetupConstantNotNearTie) {
  for (int F = kFracMin; F <= kFracMax; ++F)
    for (const auto& mi : kModels)
      for (CoefKind k : {CoefKind::Fitted, CoefKind::Classical})
        for (int n = kNMin; n <= kNMax; ++n) {
          const double x = std::ldexp(coef_value(mi.model, k, n), F);
          const double frac = x - std::floor(x);
          const double ulp = std::nextafter(x, 1e300) - x;
          ASSERT_GT(std::fabs(frac - 0.5), 64 * ulp) << mi.key << " " << to_string(k) << " n=" << n << " F=" << F;
        }
}

// Exhaustive at F = 8: out = round-half-up(spec·coef / 2^F), error in (−½, ½] ulp, no overflow.
TEST(NormEval, ExhaustiveRoundingAtF8) {
  const EnergyFormat f{8, 8};
  for (uint32_t spec = 0; spec <= 256; ++spec)
    for (uint32_t coef = 0; coef < (1u << 16); ++coef) {
      const uint64_t out = energy_eval(f, coef, spec);
      const double exact = spec * static_cast<double>(coef) / 256.0;
      const double e = static_cast<double>(out) - exact;
      ASSERT_TRUE(e > -0.5 && e <= 0.5) << spec << " " << coef;
      ASSERT_LT(out, 1u << 16);
    }
}

// Against the ideal coef·(spec/2^F): the normalised output is within 1 ulp_F (½ from the setup
// rounding of coef times spec <= 1, ½ from the output rounding), every spec code, F = 16.
TEST(NormEval, WithinOneUlpOfIdealProduct) {
  const EnergyFormat f{16, 8};
  for (const auto& mi : kModels)
    for (CoefKind k : {CoefKind::Fitted, CoefKind::Classical})
      for (int n : {16, 100, 1024}) {
        const double c = coef_value(mi.model, k, n);
        const uint32_t q = energy_setup(f, mi.model, k, n);
        double worst = 0;
        for (uint32_t spec = 0; spec <= 65536; ++spec) {
          const double ideal = c * spec;  // in units of 2^-16 of the output
          worst = std::max(worst, std::fabs(static_cast<double>(energy_eval(f, q, spec)) - ideal));
        }
        EXPECT_LE(worst, 1.0) << mi.key << " n=" << n;
      }
}

// The classical column: 2π·coef·∫cos^n = 1 for each model (closed form), the bounds the paper prints,
// and the paper's printed modified-Blinn form (4π in the denominator) is 2× the correct one.
TEST(ClassicalCoef, NormalisesCosPowAndRespectsPrintedBounds) {
  const fit::Lobe cp{fit::LobeKind::CosPow, Cutoff::ThetaCr};
  for (const auto& mi : kModels)
    for (int n : {16, 17, 64, 333, 1024}) {
      const long double I = fit::int_exact(mi.model, cp, fit::Reading::Paper, n);
      EXPECT_NEAR(2 * M_PI * classical_coef(mi.model, n) * static_cast<double>(I), 1.0, 1e-14) << mi.key << " n=" << n;
    }
  for (int n = 16; n <= 1024; ++n) {
    const double c3 = classical_coef(Model::Blinn, n), c4 = classical_coef(Model::BlinnMod, n);
    // Strict mathematically; in double the lower bound is reached once 2^(−n/2) is below an ulp.
    EXPECT_GE(c3, (n + 2) / (8 * M_PI));
    EXPECT_LT(c3, (n + 4) / (8 * M_PI));
    EXPECT_GT(c4, (n + 6) / (8 * M_PI));
    EXPECT_LT(c4, (n + 8) / (8 * M_PI));
    const double printed = (n + 2.0) * (n + 4.0) / (4 * M_PI * (std::exp2(-n / 2.0) + n));
    EXPECT_NEAR(printed / c4, 2.0, 1e-12);
  }
}

TEST(CoefModels, ParseAndTable) {
  EXPECT_EQ(parse_model("blinn_mod"), Model::BlinnMod);
  EXPECT_THROW(parse_model("cook"), std::invalid_argument);
  EXPECT_EQ(parse_coef_kind("classical"), CoefKind::Classical);
  EXPECT_THROW(parse_coef_kind("best"), std::invalid_argument);
  for (int i = 0; i < kNumModels; ++i) EXPECT_EQ(static_cast<int>(kModels[i].model), i);
}
