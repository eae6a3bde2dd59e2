// SPDX-License-Identifier: Apache-2.0
// The table-and-interpolate units (docs/spec.md §9; cmodel/include/shadecore/units/table.hpp): table contents,
// index/fraction split, clamps, every entry boundary, the quantisation bound against the double table
// lerp, monotonicity, the Unit hooks, and the consumers that must reject a table unit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <nlohmann/json.hpp>

#include "shadecore/configs.hpp"
#include "shadecore/features.hpp"
#include "shadecore/analysis/sweep.hpp"
#include "shadecore/units/table.hpp"
#include "shadecore/unit.hpp"

using namespace shadecore;

namespace {

const Format kDefault = default_format();
const Format kNarrow{8, 5};
const int kSizes[] = {256, 1024};

// Output minus 2^F times the double table lerp of the same code, in ulps.
double quant_ulps(const Format& f, const TableMaterial& m, const std::vector<double>& t, int64_t code) {
  const int E = static_cast<int>(m.words.size());
  const double c = std::ldexp(static_cast<double>(std::clamp<int64_t>(code, 0, f.one())), -f.frac);
  return static_cast<double>(table_eval(f, m, code)) - std::ldexp(golden::table_lerp(t.data(), E, c), f.frac);
}

}  // namespace

TEST(TableVariants, FromConfigsJson) {
  EXPECT_EQ(table_entries(parse_variant("table256")), 256);
  EXPECT_EQ(table_entries(parse_variant("table1024")), 1024);
  EXPECT_EQ(table_entries(VariantId::cs16), 0);
  EXPECT_FALSE(is_table_variant(VariantId::schlick_nr));
  const auto names = sweep_variants();
  EXPECT_NE(std::find(names.begin(), names.end(), "table256"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "table1024"), names.end());
}

TEST(TableSetup, Contents) {
  for (const Format& f : {kNarrow, kDefault, Format{24, 7}})
    for (int E : kSizes)
      for (int n : {16, 17, 128, 1000, 1024}) {
        const TableMaterial m = table_setup(f, E, n);
        ASSERT_EQ(m.words.size(), static_cast<size_t>(E));
        EXPECT_EQ(table_word_value(f.frac, m.words[0]), 0u);
        EXPECT_EQ(table_word_value(f.frac, m.words[E - 1]), static_cast<uint32_t>(f.one()));
        EXPECT_EQ(table_word_delta(f.frac, m.words[E - 1]), 0u);
        for (int i = 0; i < E; ++i) {
          const uint32_t v = table_word_value(f.frac, m.words[i]);
          const double exact = std::ldexp(std::pow(double(i) / (E - 1), n), f.frac);
          EXPECT_LE(std::fabs(v - exact), 0.5) << "F=" << f.frac << " E=" << E << " n=" << n << " i=" << i;
          if (i + 1 < E) {
            ASSERT_EQ(table_word_delta(f.frac, m.words[i]), table_word_value(f.frac, m.words[i + 1]) - v) << i;
          }
        }
      }
  EXPECT_THROW(table_setup(kDefault, 256, 15), std::invalid_argument);
  EXPECT_THROW(table_setup(kDefault, 256, 1025), std::invalid_argument);
  EXPECT_THROW(table_setup(kDefault, 300, 64), std::invalid_argument);
}

// cos = 0, cos = 1 exactly, just above 1, the saturating maximum, negative codes.
TEST(TableEval, ClampsAndEnds) {
  for (const Format& f : {kNarrow, kDefault, Format{24, 7}})
    for (int E : kSizes)
      for (int n : {16, 100, 1024}) {
        const TableMaterial m = table_setup(f, E, n);
        const uint32_t one = static_cast<uint32_t>(f.one());
        EXPECT_EQ(table_eval(f, m, 0), 0u);
        EXPECT_EQ(table_eval(f, m, f.one()), one);
        EXPECT_EQ(table_eval(f, m, f.one() + 1), one);
        EXPECT_EQ(table_eval(f, m, f.in_max()), one);
        EXPECT_EQ(table_eval(f, m, -1), 0u);
        EXPECT_EQ(table_eval(f, m, f.in_min()), 0u);
        TableTrace tr;
        table_eval(f, m, f.one(), &tr);
        EXPECT_EQ(tr.index, static_cast<uint32_t>(E - 1));  // the last entry, fraction 0
        EXPECT_EQ(tr.frac, 0u);
        table_eval(f, m, -5, &tr);
        EXPECT_EQ(tr.c, 0u);
        EXPECT_EQ(tr.index, 0u);
        // just below 1: an interval below the last entry (E − 2 when 2^F ≥ E), never the last entry itself
        table_eval(f, m, f.one() - 1, &tr);
        EXPECT_EQ(tr.index, static_cast<uint32_t>((uint64_t(E - 1) * uint64_t(f.one() - 1)) >> f.frac));
        if (f.one() >= E) {
          EXPECT_EQ(tr.index, static_cast<uint32_t>(E - 2));
        }
        EXPECT_LT(tr.index, static_cast<uint32_t>(E - 1));
        EXPECT_LE(tr.out, one);
      }
}

// Every entry boundary of one table, exhaustively at F = 8: the first code of entry i has index i and
// the code before it index i − 1; at fraction 0 the output is V[i] exactly; every output lies between
// its two entries; (E−1)·c = i·2^F + fr for every code.
TEST(TableEval, EveryEntryBoundaryF8) {
  const Format f = kNarrow;
  for (int E : kSizes) {
    const int n = 64;
    const TableMaterial m = table_setup(f, E, n);
    for (int64_t code = 0; code <= f.one(); ++code) {
      TableTrace tr;
      table_eval(f, m, code, &tr);
      ASSERT_EQ(uint64_t(tr.index) * uint64_t(f.one()) + tr.frac, uint64_t(E - 1) * uint64_t(code)) << code;
      const uint32_t lo = table_word_value(f.frac, m.words[tr.index]);
      const uint32_t hi = tr.index + 1 < uint32_t(E) ? table_word_value(f.frac, m.words[tr.index + 1]) : lo;
      ASSERT_GE(tr.out, lo) << "E=" << E << " code=" << code;
      ASSERT_LE(tr.out, hi) << "E=" << E << " code=" << code;
      if (tr.frac == 0) {
        ASSERT_EQ(tr.out, lo) << code;
      }
    }
    int boundaries = 0;
    for (int i = 1; i < E; ++i) {
      const int64_t first = (int64_t(i) * f.one() + E - 2) / (E - 1);  // ⌈i·2^F/(E−1)⌉
      if (first > f.one()) break;
      TableTrace a, b;
      table_eval(f, m, first, &a);
      table_eval(f, m, first - 1, &b);
      if (a.index != uint32_t(i)) continue;  // E > 2^F: several entries share no code
      ++boundaries;
      EXPECT_LT(b.index, uint32_t(i)) << "E=" << E << " i=" << i;
      EXPECT_LE(b.out, a.out) << "E=" << E << " i=" << i;
    }
    EXPECT_GT(boundaries, 200) << E;
  }
}

// −1 < out − 2^F·lerp ≤ +1 (spec §9.4), out ≤ 2^F and out non-decreasing in the code: every code and
// every n at F = 8, every code for a few n at F = 16.
TEST(TableEval, BoundAndMonotoneExhaustive) {
  struct Case {
    Format f;
    std::vector<int> ns;
  };
  std::vector<int> all;
  for (int n = kNMin; n <= kNMax; ++n) all.push_back(n);
  const Case cases[] = {{kNarrow, all}, {kDefault, {16, 17, 128, 500, 1024}}};
  for (const Case& cs : cases)
    for (int E : kSizes)
      for (int n : cs.ns) {
        const Format& f = cs.f;
        const TableMaterial m = table_setup(f, E, n);
        const std::vector<double> t = golden::table_golden(E, n);
        uint32_t prev = 0;
        double lo = 0, hi = 0;
        for (int64_t code = 0; code <= f.one(); ++code) {
          const uint32_t out = table_eval(f, m, code);
          ASSERT_LE(out, static_cast<uint32_t>(f.one()));
          ASSERT_GE(out, prev) << "F=" << f.frac << " E=" << E << " n=" << n << " code=" << code;
          prev = out;
          const double q = quant_ulps(f, m, t, code);
          lo = std::min(lo, q);
          hi = std::max(hi, q);
        }
        ASSERT_GT(lo, kTableQuantMin - 1e-9) << "F=" << f.frac << " E=" << E << " n=" << n;
        ASSERT_LE(hi, kTableQuantMax + 1e-9) << "F=" << f.frac << " E=" << E << " n=" << n;
      }
}

TEST(TableUnit, Hooks) {
  for (int E : kSizes) {
    const Unit u(parse_variant(E == 256 ? "table256" : "table1024"), kDefault, Cutoff::ThetaCr);
    EXPECT_EQ(u.entries(), E);
    EXPECT_EQ(u.latency(), kTableLatency);
    EXPECT_EQ(u.latency_min(), kTableLatency);
    const UnitMaterial m = u.setup(300);
    ASSERT_TRUE(m.tab);
    EXPECT_EQ(m.tab->size(), static_cast<size_t>(E));
    EXPECT_EQ(m.thr, 0u);
    const TableMaterial t = table_setup(kDefault, E, 300);
    EXPECT_EQ(*m.tab, t.words);
    for (int64_t code : {int64_t{-3}, int64_t{0}, int64_t{12345}, int64_t{60000}, kDefault.one(), kDefault.in_max()})
      EXPECT_EQ(u.eval(m, code), table_eval(kDefault, t, code)) << code;
    EXPECT_THROW(static_cast<void>(u.eval(UnitMaterial{300, 0}, 100)), std::invalid_argument);  // no table loaded
    Unit un = u;
    un.set_energy(true);
    EXPECT_EQ(un.latency(), kTableLatency + 2);
  }
  EXPECT_EQ(Unit(VariantId::cs16, kDefault, Cutoff::ThetaCr).entries(), 0);
}

// The eval reads whatever the RAM holds (the scoreboard mirrors the RTL's RAM): a word changed by
// hand changes only the codes of its entry.
TEST(TableUnit, EvalReadsTheRam) {
  const Unit u(parse_variant("table256"), kNarrow, Cutoff::ThetaCr);
  UnitMaterial m = u.setup(40);
  auto words = *m.tab;
  words[100] = table_word(kNarrow.frac, 7, 3);
  UnitMaterial m2 = m;
  m2.tab = std::make_shared<const std::vector<uint64_t>>(words);
  for (int64_t code = 0; code <= kNarrow.one(); ++code) {
    TableTrace tr;
    table_eval(kNarrow, words.data(), 256, code, &tr);
    if (tr.index == 100) EXPECT_EQ(u.eval(m2, code), 7u + ((3u * tr.frac + 128u) >> 8)) << code;
    else EXPECT_EQ(u.eval(m2, code), u.eval(m, code)) << code;
  }
}

// The lighting core has no table-load port: a feature set naming a table unit is rejected in one line.
TEST(TableUnit, LightingCoreRejectsTable) {
  for (const char* v : {"table256", "table1024"}) {
    const std::string text = std::string(R"({"specular": ")") + v + "\"}";
    try {
      feature_set_from_json(nlohmann::json::parse(text), "t");
      ADD_FAILURE() << "accepted: " << text;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("not supported by the lighting core"), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos);
    }
  }
}
