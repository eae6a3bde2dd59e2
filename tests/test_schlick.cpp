// SPDX-License-Identifier: Apache-2.0
// Hard cases and exhaustive properties of the bit-accurate Schlick-divide models (docs/spec.md §6).
//   S(t, n) = t / (n − (n−1)·t);  out = 2^F·c/Dc,  Dc = n·(2^F − c) + c
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "shadecore/configs.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/units/hard_cases.hpp"
#include "shadecore/units/schlick.hpp"
#include "shadecore/analysis/sweep.hpp"

using namespace shadecore;

namespace {

const Format kDefault = default_format();

const SchlickForm kForms[] = {SchlickForm::Div, SchlickForm::Nr, SchlickForm::Iter};
const char* name(SchlickForm f) { return f == SchlickForm::Div ? "div" : f == SchlickForm::Nr ? "nr" : "iter"; }

// Correctly rounded (half up) quotient computed independently of the model: ⌊2^F·c/D + ½⌋.
uint64_t exact_round(int F, uint64_t c, uint64_t D) { return ((c << (F + 1)) + D) / (2 * D); }

uint64_t den_of(const Format& f, int n, int64_t code) {
  SchlickTrace tr;
  schlick_div_eval(f, schlick_setup(f, n), code, &tr);
  return tr.den;
}

// The double Schlick of the same clamped code, in output ulps.
double golden_ulps(const Format& f, int n, uint64_t c) {
  return golden::schlick(std::ldexp(double(c), -f.frac), n) * std::ldexp(1.0, f.frac);
}

// Stated bounds (spec §6.4): div/iter |e| <= 1/2; nr |e| <= schlick_nr_bound_ulp(F). Slack for the
// rounding of the double reference itself (relative 2^-50 of a value <= 2^F).
double bound(SchlickForm form, int F) {
  const double slack = std::ldexp(1.0, F - 50);
  return (form == SchlickForm::Nr ? schlick_nr_bound_ulp(F) : 0.5) + slack;
}

}  // namespace

TEST(SchlickSetup, RejectsIllegal) {
  EXPECT_THROW(schlick_setup(kDefault, 15), std::invalid_argument);
  EXPECT_THROW(schlick_setup(kDefault, 1025), std::invalid_argument);
  EXPECT_THROW(schlick_setup(Format{7, 5}, 100), std::invalid_argument);
  EXPECT_THROW(schlick_setup(Format{25, 5}, 100), std::invalid_argument);
  EXPECT_NO_THROW(schlick_setup(Format{24, 7}, 1024));
}

// The denominator over its whole range, every n and every clamped code at the default width:
// exact n·2^F − (n−1)·c, within [c, n·2^F], >= 2^F, fits F+11 bits; smallest (= 2^F) only at t = 1.
TEST(SchlickDenominator, WholeRangeExact) {
  const Format f = kDefault;
  const int F = f.frac;
  for (int n = kNMin; n <= kNMax; ++n) {
    const SchlickMaterial m = schlick_setup(f, n);
    for (int64_t code = 0; code <= f.one(); ++code) {
      uint32_t c;
      uint64_t D;
      detail::schlick_front(f, m, code, c, D);
      const int64_t want = int64_t(n) * f.one() - int64_t(n - 1) * code;
      const bool ok = int64_t(D) == want && D >= c && D >= uint64_t(f.one()) && D <= (uint64_t(n) << F) &&
                      D < (uint64_t{1} << schlick_den_bits(F)) &&
                      (code == f.one() || D >= uint64_t(f.one()) + uint64_t(n - 1));  // smallest D below t = 1
      if (!ok) {
        ADD_FAILURE() << "denominator " << D << " wrong/out of range at n=" << n << " code=" << code;
        return;
      }
    }
  }
  // The extremes: D = n·2^F at t = 0 (the largest, 2^(F+10) for n = 1024), D = 2^F at t = 1.
  EXPECT_EQ(den_of(f, 1024, 0), uint64_t{1} << (F + 10));
  EXPECT_EQ(den_of(f, 16, f.one()), uint64_t(f.one()));
}

// t = 0 → 0, t = 1 → exactly 1.0, t > 1 saturates (never wraps), t < 0 → 0; every form, every n,
// every legal F.
TEST(SchlickEndpoints, AllFormsAllWidths) {
  for (int F = kFracMin; F <= kFracMax; ++F) {
    const Format f{F, 5};
    for (int n = kNMin; n <= kNMax; ++n) {
      const SchlickMaterial m = schlick_setup(f, n);
      for (SchlickForm form : kForms) {
        SCOPED_TRACE(std::string(name(form)) + " F=" + std::to_string(F) + " n=" + std::to_string(n));
        ASSERT_EQ(schlick_eval(form, f, m, 0), 0u);
        ASSERT_EQ(schlick_eval(form, f, m, -1), 0u);
        ASSERT_EQ(schlick_eval(form, f, m, f.in_min()), 0u);
        ASSERT_EQ(schlick_eval(form, f, m, f.one()), uint32_t(f.one()));
        ASSERT_EQ(schlick_eval(form, f, m, f.one() + 1), uint32_t(f.one()));
        ASSERT_EQ(schlick_eval(form, f, m, f.in_max()), uint32_t(f.one()));
        ASSERT_LT(schlick_eval(form, f, m, f.one() - 1), uint32_t(f.one()));
      }
    }
  }
}

// The smallest denominators (t just below 1) and the shared directed list: each form against the
// independently computed correctly rounded quotient.
TEST(SchlickHardCases, SmallestDenominatorsAndDirectedList) {
  for (int F : {8, 16, 24}) {
    const Format f{F, F == 24 ? 7 : 5};
    std::vector<HardCase> cases = hard_cases(f);
    for (int n : hard_case_exponents())
      for (int64_t k = 0; k < 64; ++k) cases.push_back({n, f.one() - k});
    for (const auto& hc : cases) {
      const SchlickMaterial m = schlick_setup(f, hc.n);
      SchlickTrace tr;
      const uint32_t div = schlick_div_eval(f, m, hc.code, &tr);
      ASSERT_EQ(div, exact_round(F, tr.c, tr.den)) << "F=" << F << " n=" << hc.n << " code=" << hc.code;
      ASSERT_EQ(schlick_iter_eval(f, m, hc.code), div);
      const double g = golden_ulps(f, hc.n, tr.c);
      ASSERT_LE(std::fabs(double(schlick_nr_eval(f, m, hc.code)) - g), bound(SchlickForm::Nr, F))
          << "F=" << F << " n=" << hc.n << " code=" << hc.code;
    }
  }
}

// The restoring-division steps (what the RTL stages compute) give the integer quotient and remainder.
TEST(SchlickDivider, RestoringStepsEqualIntegerDivision) {
  std::mt19937_64 rng(5);
  for (int F : {8, 16, 24}) {
    const Format f{F, F == 24 ? 7 : 5};
    for (int i = 0; i < 200000; ++i) {
      const int n = kNMin + int(rng() % (kNMax - kNMin + 1));
      const int64_t code = int64_t(rng() % uint64_t(f.one() + 1));
      SchlickTrace tr;
      const uint32_t out = schlick_div_eval(f, schlick_setup(f, n), code, &tr);
      const uint64_t num = uint64_t(tr.c) << (F + 1);
      ASSERT_EQ(tr.quot, num / tr.den);
      ASSERT_EQ(tr.rem, num % tr.den);
      ASSERT_LT(tr.quot, uint64_t{1} << (F + 2));
      ASSERT_EQ(out, schlick_div_eval(f, schlick_setup(f, n), code));  // fast path == traced path
    }
  }
}

// n = 0 (a port value beyond the host's, docs/spec.md §3.1; `vectors --mode ports` draws it for the dividers): Dc = c,
// the quotient is 1.0 for every c > 0, and at c = 0 (Dc = 0) the RTL's divider takes every quotient bit and its F+1-bit
// output register wraps (q + 1)/2 = 2^(F+1) to 0. The fast path and the traced path give that, never a division by 0.
TEST(SchlickDivider, ZeroExponentIsTheRtlsPathNotADivisionByZero) {
  for (int F : {8, 16, 24}) {
    const Format f{F, F == 24 ? 7 : 5};
    SchlickMaterial m = schlick_setup(f, kNMin);
    m.n = 0;
    for (int64_t code : {int64_t{0}, int64_t{-3}, int64_t{1}, f.one() / 3, f.one(), f.one() + 7}) {
      SchlickTrace tr;
      const uint32_t traced = schlick_div_eval(f, m, code, &tr);
      EXPECT_EQ(schlick_div_eval(f, m, code), traced) << F << " " << code;
      EXPECT_EQ(schlick_iter_eval(f, m, code), traced) << F << " " << code;
      if (tr.c == 0) {
        EXPECT_EQ(tr.den, 0u);
        EXPECT_EQ(tr.quot, (uint64_t{1} << (F + 2)) - 1);  // every step b = 1
        EXPECT_EQ(traced, 0u);                              // 2^(F+1) wrapped in F+1 bits
      } else {
        EXPECT_EQ(traced, uint32_t(f.one()));
      }
    }
  }
}

// Table contents rule and worst case: 64 entries, 514..1016, strictly decreasing, ε0 < 2^−6.9.
TEST(SchlickNr, TableWorstCase) {
  constexpr int P = kSchlickNrIndexBits, T = kSchlickNrTableFrac;
  for (uint32_t i = 0; i < (1u << P); ++i) {
    const double mid = 1.0 + (i + 0.5) / double(1u << P);
    EXPECT_LE(std::fabs(schlick_nr_table(i) - std::ldexp(1.0 / mid, T)), 0.5) << i;
    if (i) {
      EXPECT_LT(schlick_nr_table(i), schlick_nr_table(i - 1));
    }
  }
  EXPECT_EQ(schlick_nr_table(0), 1016u);
  EXPECT_EQ(schlick_nr_table(63), 514u);
  const double e0 = schlick_nr_table_eps();
  EXPECT_LT(e0, 0.00809);
  EXPECT_GT(e0, 0.00808);  // the worst case is the table's first interval (md near 1)
}

// Newton–Raphson convergence over EVERY normalised denominator mt (R+1 bits, leading one) for
// F = 8..16 (2^14..2^22 values each), sampled at F = 20 and 24: ε2 = 1 − mt·y2 within the
// analytic |ε2| <= ε1² + 2·2^−R, ε1 = ε0² + 2·2^−R, and y2 never exceeds R+1 bits.
TEST(SchlickNr, ConvergenceEveryNormalisedDenominator) {
  const double e0 = schlick_nr_table_eps();
  for (int F : {8, 10, 12, 14, 16, 20, 24}) {
    const int R = schlick_nr_recip_frac(F);
    const double u = std::ldexp(1.0, -R);
    const double e1b = e0 * e0 + 2 * u * (1 + 1e-6);
    const double e2b = e1b * e1b + 2 * u * (1 + 1e-6);
    const bool exhaustive = F <= 16;
    const uint64_t count = exhaustive ? (uint64_t{1} << R) : (uint64_t{1} << 22);
    std::mt19937_64 rng(F);
    double worst = 0.0;
    for (uint64_t k = 0; k < count; ++k) {
      const uint64_t mt = (uint64_t{1} << R) + (exhaustive ? k : (rng() & ((uint64_t{1} << R) - 1)));
      const uint32_t idx = uint32_t((mt >> (R - kSchlickNrIndexBits)) & ((1u << kSchlickNrIndexBits) - 1));
      const uint64_t y0 = schlick_nr_table(idx);
      const uint64_t y1 = schlick_nr_step(R, mt, y0, kSchlickNrTableFrac);
      const uint64_t y2 = schlick_nr_step(R, mt, y1, R);
      const double md = std::ldexp(double(mt), -R);
      ASSERT_LE(std::fabs(1.0 - md * std::ldexp(double(y1), -R)), e1b) << "F=" << F << " mt=" << mt;
      const double e2 = 1.0 - md * std::ldexp(double(y2), -R);
      ASSERT_LE(std::fabs(e2), e2b) << "F=" << F << " mt=" << mt;
      ASSERT_LT(y1, uint64_t{1} << (R + 1));  // the RTL keeps y1, y2 in R+1 bits
      ASSERT_LT(y2, uint64_t{1} << (R + 1));
      worst = std::max(worst, std::fabs(e2));
    }
    RecordProperty("nr_eps2_F" + std::to_string(F), std::to_string(worst));
  }
}

// Bit-accurate models against double Schlick of the same code, every n × every code at the default
// width: div/iter correctly rounded (bit-equal to the independent integer formula, |e| <= ½),
// nr within its bound; every output <= 1.0 and non-decreasing in t.
TEST(SchlickExhaustive, DefaultWidthAllNAllCodes) {
  const Format f = kDefault;
  const int F = f.frac;
  double nr_lo = 0, nr_hi = 0;
  uint64_t nr_differs = 0;
  // Plain comparisons in the 66M-iteration loop (gtest assertions there cost ~20x); the first
  // failure is reported with its location and ends the test.
  auto fail = [](const char* what, int n, int64_t code) {
    ADD_FAILURE() << what << " at n=" << n << " code=" << code;
  };
  const double bound_div = bound(SchlickForm::Div, F), bound_nr = bound(SchlickForm::Nr, F);
  for (int n = kNMin; n <= kNMax; ++n) {
    const SchlickMaterial m = schlick_setup(f, n);
    uint32_t prev_div = 0, prev_nr = 0;
    for (int64_t code = 0; code <= f.one(); ++code) {
      uint32_t c;
      uint64_t D;
      detail::schlick_front(f, m, code, c, D);
      const uint32_t div = schlick_div_eval(f, m, code), nr = schlick_nr_eval(f, m, code);
      const double g = golden_ulps(f, n, c);
      const double e = double(nr) - g;
      if (div != exact_round(F, c, D)) return fail("div not correctly rounded", n, code);
      if (std::fabs(div - g) > bound_div) return fail("div outside bound", n, code);
      if (std::fabs(e) > bound_nr) return fail("nr outside bound", n, code);
      if (div > uint32_t(f.one()) || nr > uint32_t(f.one())) return fail("output above 1.0", n, code);
      if (div < prev_div) return fail("div not monotonic", n, code);
      if (nr < prev_nr) return fail("nr not monotonic", n, code);
      nr_lo = std::min(nr_lo, e);
      nr_hi = std::max(nr_hi, e);
      nr_differs += nr != div;
      prev_div = div;
      prev_nr = nr;
    }
  }
  // The NR form is faithful but not always correctly rounded: it must differ somewhere (else this
  // test could not tell the forms apart) and stay below 1 ulp.
  EXPECT_GT(nr_differs, 0u);
  EXPECT_LT(std::max(nr_hi, -nr_lo), 1.0);
  RecordProperty("nr_err_min", std::to_string(nr_lo));
  RecordProperty("nr_err_max", std::to_string(nr_hi));
}

// Other widths: F = 8 exhaustive for every n; F = 24 (wide) every code for a few n is 2^24 each, so
// a stratified random subset of 2^18 codes per hard-case exponent plus all hard cases.
TEST(SchlickExhaustive, OtherWidths) {
  {
    const Format f{8, 5};
    for (int n = kNMin; n <= kNMax; ++n) {
      const SchlickMaterial m = schlick_setup(f, n);
      uint32_t prev = 0;
      for (int64_t code = f.in_min(); code <= f.in_max(); ++code) {
        SchlickTrace tr;
        const uint32_t div = schlick_div_eval(f, m, code, &tr);
        ASSERT_EQ(div, exact_round(8, tr.c, tr.den));
        const uint32_t nr = schlick_nr_eval(f, m, code);
        ASSERT_LE(std::fabs(nr - golden_ulps(f, n, tr.c)), bound(SchlickForm::Nr, 8)) << n << " " << code;
        ASSERT_GE(nr, prev);
        prev = nr;
      }
    }
  }
  {
    const Format f{24, 7};
    std::mt19937_64 rng(24);
    const double bound_nr = bound(SchlickForm::Nr, 24);
    for (int n : hard_case_exponents()) {
      const SchlickMaterial m = schlick_setup(f, n);
      for (int i = 0; i < (1 << 18); ++i) {
        const int64_t code = (int64_t(i) << 6) + int64_t(rng() & 63);
        uint32_t c;
        uint64_t D;
        detail::schlick_front(f, m, code, c, D);
        ASSERT_EQ(schlick_div_eval(f, m, code), exact_round(24, c, D));
        ASSERT_LE(std::fabs(schlick_nr_eval(f, m, code) - golden_ulps(f, n, c)), bound_nr)
            << n << " " << code;
      }
    }
  }
}

// The sweep kernels: registered names, quantisation within the stated bound, golden = Schlick.
TEST(SchlickSweep, KernelsRegisteredAndWithinBound) {
  for (const char* v : {"schlick_div", "schlick_nr", "schlick_iter"}) {
    SweepOptions o;
    o.variant = v;
    o.format = kDefault;
    o.n_lo = 100;
    o.n_hi = 103;
    o.threads = 1;
    const SweepResult r = run_sweep(o);
    const SchlickForm form = std::string(v) == "schlick_nr" ? SchlickForm::Nr : SchlickForm::Div;
    EXPECT_LE(r.quant.max.value, bound(form, kDefault.frac)) << v;
    EXPECT_GE(r.quant.min.value, -bound(form, kDefault.frac)) << v;
    EXPECT_GT(r.quant.max.value, 0.4) << v;  // the rounding is really exercised
    EXPECT_DOUBLE_EQ(variant_golden(v, Cutoff::ThetaCr, 100, 0.5), golden::schlick(0.5, 100));
    // The Schlick tail is much heavier than cos^n: the approximation error is negative somewhere large.
    EXPECT_LT(r.approx.min.value, -0.05) << v;
  }
}

// Closed-form energies against a fine Simpson integration of the double function.
TEST(SchlickEnergy, ClosedFormsMatchQuadrature) {
  for (int n : {16, 17, 100, 512, 1024}) {
    const int N = 1 << 20;
    double e1 = 0, e2 = 0;
    for (int i = 0; i <= N; ++i) {
      const double t = double(i) / N, w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
      e1 += w * golden::schlick(t, n);
      e2 += w * golden::schlick(t, n) * t;
    }
    e1 /= 3.0 * N;
    e2 /= 3.0 * N;
    EXPECT_NEAR(golden::schlick_energy(n) / e1, 1.0, 1e-9) << n;
    EXPECT_NEAR(golden::schlick_energy_cos(n) / e2, 1.0, 1e-9) << n;
    EXPECT_GT(golden::schlick_energy(n), 2.0 * golden::cos_pow_energy(n)) << n;  // the heavy tail
  }
}
