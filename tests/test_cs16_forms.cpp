// SPDX-License-Identifier: Apache-2.0
// cs16 forms with folded, truncated squarers (docs/spec.md §3.4; rtl/sc_square.v, rtl/sc_cs16.v FORM = 1):
// the squarer model against x·x and against its literal column sums, the forms' contracts on every code
// of every n at F = 8, on a sample of n at F = 16 and on every x0 = base at F = 8 and 16, the `sweep --bases`
// output against the model, and the folded untruncated form against cs16.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cli_run.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/units/cs16.hpp"
#include "shadecore/units/cs16_forms.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/units/square.hpp"
#include "shadecore/unit.hpp"

using namespace shadecore;

namespace {

// y·2^F: the double cs16 of the same input code with the reference (cs16) cut decision.
double golden_code(const Format& f, Cutoff cut, const Cs16Material& m, int64_t code) {
  Cs16Trace tr;
  cs16_eval(f, cut, m, code, &tr);
  if (tr.cut) return 0.0;
  return golden::pow16(golden::cs16_base(std::ldexp(double(tr.c), -f.frac), m.n)) * std::ldexp(1.0, f.frac);
}

struct Extremes {
  double lo = 1e9, hi = -1e9;
  int failures = 0;
};

// Every code in [-2, 2^F + 2] for each n in ns; checks the form's contract and output <= 2^F.
template <class Ns>
Extremes check_contract(VariantId v, const Format& f, Cutoff cut, const Ns& ns) {
  const Unit u(v, f, cut);
  const Cs16Contract c = cs16_contract(squarer_form(v)->contract, f);
  Extremes x;
  for (int n : ns) {
    const UnitMaterial um = u.setup(n);
    const Cs16Material m{um.n, um.thr};
    for (int64_t code = -2; code <= f.one() + 2; ++code) {
      const uint32_t out = u.eval(um, code);
      const double e = double(out) - golden_code(f, cut, m, code);
      x.lo = std::min(x.lo, e);
      x.hi = std::max(x.hi, e);
      const bool ok = (c.lo_strict ? e > c.lo : e >= c.lo) && e <= c.hi && out <= uint32_t(f.one());
      if (!ok && ++x.failures <= 5)
        ADD_FAILURE() << variant_name(v) << " F=" << f.frac << " n=" << n << " code=" << code << " out=" << out
                      << " err=" << e << " ulp outside the '" << squarer_form(v)->contract << "' contract";
    }
  }
  return x;
}

std::vector<int> all_n() {
  std::vector<int> v;
  for (int n = kNMin; n <= kNMax; ++n) v.push_back(n);
  return v;
}

// Every x0 in [0, 2^(F+4)] through a form's squarings (cs16f_squarings): the extremes of out − (x0/2^(F+4))^16·2^F
// and the number of x0 outside the form's contract (the first few reported).
Extremes check_bases(const Format& f, const NamedSquarer& s, const char* label) {
  const Cs16Stages st = cs16_stages(f, s.form);
  const Cs16Contract c = cs16_contract(s.form.contract, f);
  const uint64_t top = uint64_t{1} << (f.frac + 4);
  Extremes x;
  for (uint64_t x0 = 0; x0 <= top; ++x0) {
    const uint32_t out = cs16f_squarings(f, st, x0);
    const double e = double(static_cast<long double>(out) -
                            powl(static_cast<long double>(x0) / top, 16) * (uint64_t{1} << f.frac));
    x.lo = std::min(x.lo, e);
    x.hi = std::max(x.hi, e);
    if (!((c.lo_strict ? e > c.lo : e >= c.lo) && e <= c.hi) && ++x.failures <= 5)
      ADD_FAILURE() << variant_name(s.id) << " " << label << " x0=" << x0 << " out=" << out << " err=" << e;
  }
  return x;
}

}  // namespace

TEST(Square, FoldedUntruncatedEqualsProduct) {
  std::mt19937_64 rng(7);
  for (int n = 1; n <= kSquareMaxN; ++n) {
    const uint64_t mask = (uint64_t{1} << n) - 1;
    for (int k = 0; k < 2000; ++k) {
      const uint64_t x = (k == 0) ? mask : (k == 1 ? 0 : rng() & mask);
      ASSERT_EQ(square_kept(x, n, 0), u128{x} * x) << "n=" << n << " x=" << x;
      if (n <= 32) ASSERT_EQ(square_eval(SquareStage{n, 2 * n, 0, 0, 0}, x), u128{x} * x) << "n=" << n;  // 64-bit result
    }
  }
  for (uint64_t x = 0; x < (1u << 12); ++x) ASSERT_EQ(square_kept_columns(x, 12, 0), u128{x} * x) << x;
}

TEST(Square, TruncatedSumIsTheKeptColumns) {
  // square_kept (x·x minus the dropped bits) equals the literal sum of the kept partial-product bits.
  std::mt19937_64 rng(8);
  for (int n : {5, 12, 21, 26, 33}) {
    const uint64_t mask = (uint64_t{1} << n) - 1;
    for (int drop = 0; drop <= 2 * n; drop += 3)
      for (int k = 0; k < 300; ++k) {
        const uint64_t x = (k == 0) ? mask : rng() & mask;
        ASSERT_EQ(square_kept(x, n, drop), square_kept_columns(x, n, drop)) << "n=" << n << " drop=" << drop << " x=" << x;
      }
  }
  // The compensation is the rounded expected value of the dropped bits: brute force for a small n.
  const int n = 8, drop = 7;
  u128 total = 0;
  for (uint64_t x = 0; x < 256; ++x) total += square_dropped(x, n, drop);
  EXPECT_EQ(square_comp(n, 4, drop, false, true), (total * 4 / 256 + 2) / 4);  // 4·E exact for uniform x
  EXPECT_EQ(square_comp(n, 9, 0, true, true), u128{1} << 8);
}

TEST(Cs16Forms, FoldedUntruncatedFormEqualsCs16) {
  // FORM = 1 with the reference widths (rel_guard, 0,0,0,0, nothing dropped, floor) is cs16 bit for bit,
  // including cutting where base <= 0 instead of squaring |base| (the negative-base sliver gives 0).
  const SquarerForm exact{true, {0, 0, 0, 0}, {99, 99, 99, 99}, false, "faithful"};
  for (const Format f : {Format{8, 5}, Format{16, 5}, Format{24, 7}}) {
    const Cs16Stages st = cs16_stages(f, exact);
    for (int k = 1; k <= 4; ++k) ASSERT_EQ(st.sq[k].drop, 0);
    const int step = f.frac == 8 ? 1 : (f.frac == 16 ? 37 : 997);
    for (Cutoff cut : {Cutoff::ThetaCr, Cutoff::SignClamp})
      for (int n = kNMin; n <= kNMax; n += (f.frac == 8 ? 1 : 101)) {
        const Cs16Material m = cs16_setup(f, n);
        for (int64_t code = -1; code <= f.one() + 1; code += (code < f.one() - 4096 ? step : 1))
          ASSERT_EQ(cs16f_eval(f, cut, st, m, code), cs16_eval(f, cut, m, code))
              << "F=" << f.frac << " n=" << n << " code=" << code << " cutoff " << to_string(cut);
      }
  }
}

TEST(Cs16Forms, ContractExhaustiveNarrow) {
  const Format f = config_named("narrow").format;
  for (const auto& s : kSquarerForms)
    for (Cutoff cut : {Cutoff::ThetaCr, Cutoff::SignClamp}) {
      const Extremes x = check_contract(s.id, f, cut, all_n());
      EXPECT_EQ(x.failures, 0);
      EXPECT_LT(x.lo, -0.25) << "the check sees real errors";  // not vacuous
    }
}

TEST(Cs16Forms, ContractSampleDefault) {
  // A sample of n at the default width (every code); the full range is `shadecore sweep` (docs/spec.md §3.4).
  const Format f = default_format();
  const std::vector<int> ns = {16, 17, 19, 21, 23, 41, 157, 1024};
  for (const auto& s : kSquarerForms) EXPECT_EQ(check_contract(s.id, f, Cutoff::ThetaCr, ns).failures, 0);
}

TEST(Cs16Forms, ContractEveryBase) {
  // After the cut everything depends on x0 = base alone (cs16f_squarings), so the 2^(F+4) + 1 values of
  // x0 cover every fragment of every n: the contract on all of them at F = 8 and 16 (F = 24: 2^28 values,
  // `shadecore sweep --bases`, docs/spec.md §3.4).
  for (const char* cfg : {"narrow", "default"}) {
    const Format f = config_named(cfg).format;
    for (const auto& s : kSquarerForms) {
      const Extremes x = check_bases(f, s, cfg);
      EXPECT_EQ(x.failures, 0) << variant_name(s.id) << " " << cfg << ": " << x.lo << " .. " << x.hi;
      EXPECT_LT(x.lo, -0.25) << "the check sees real errors";
      const Cs16Stages st = cs16_stages(f, s.form);
      EXPECT_EQ(cs16f_squarings(f, st, uint64_t{1} << (f.frac + 4)), uint32_t(f.one())) << "1.0^16 = 1.0 exactly";
      EXPECT_EQ(cs16f_squarings(f, st, 0), 0u);
    }
  }
}

TEST(Cs16Forms, StagesFollowTheRule) {
  // The stage widths of docs/spec.md §3.4 for every named width (and that they are legal there).
  for (const auto& c : kConfigs)
    for (const auto& s : kSquarerForms) {
      const Cs16Stages st = cs16_stages(c.format, s.form);
      const int F = c.format.frac, B = F + (s.form.rel_guard ? c.format.guard : 0);
      EXPECT_EQ(st.w[0], F + 4);
      for (int k = 1; k <= 4; ++k) {
        EXPECT_EQ(st.w[k], B + s.form.stage_frac[k - 1]);
        EXPECT_EQ(st.sq[k].n, st.w[k - 1]);
        EXPECT_GE(st.sq[k].drop, 0);
        EXPECT_LE(st.sq[k].drop, st.sq[k].shift);
        EXPECT_LT(st.sq[k].comp, u128{1} << st.sq[k].shift) << "0 must square to 0";
      }
    }
  EXPECT_THROW(cs16_stages(Format{16, 5}, SquarerForm{false, {-1, 0, 0, 0}, {0, 0, 0, 0}, false, "compact"}), std::invalid_argument);
}

TEST(Cs16Forms, SweepBasesCliMatchesTheModel) {
  // `shadecore sweep --bases` prints the extremes of cs16f_squarings over every x0 and the contract verdict.
  const Format f = config_named("narrow").format;
  for (const auto& s : kSquarerForms) {
    const Extremes x = check_bases(f, s, "narrow");
    const std::string v(variant_name(s.id));
    const auto r = shadecore::testing::run_cli("sweep --variant " + v + " --config narrow --bases --no-progress");
    ASSERT_EQ(r.status, 0) << r.err;
    char want[96];
    std::snprintf(want, sizeof want, "measured [%.5f, %.5f] → %s", x.lo, x.hi, x.failures ? "VIOLATED" : "MET");
    EXPECT_NE(r.out.find(want), std::string::npos) << v << ": expected '" << want << "' in\n" << r.out;
    EXPECT_NE(r.out.find(std::to_string((uint64_t{1} << (f.frac + 4)) + 1) + " evaluations"), std::string::npos) << r.out;
  }
}
