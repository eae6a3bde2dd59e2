// SPDX-License-Identifier: Apache-2.0
// Issue 23: `shadecore light-sweep` follows docs/cli.md — defaults shown in --help, readable ranges, --seed 0
// or absent picks a seed and prints it (the printed seed reproduces the run), every column in the unit its
// header states (output LSBs of 2^-F), empty values and out-of-range counts rejected in one line.
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

using namespace shadecore::testing;  // tests/cli_run.hpp

namespace {
const std::string kSmall = "light-sweep --features phong_point --specular all --programs 2 --per-program 10";

// The table (its column header and rows), without the lines above it (the seed line).
std::string table_of(const std::string& out) {
  const auto t = out.find("total max");
  const auto h = t == std::string::npos ? t : out.rfind('\n', t);
  return h == std::string::npos ? std::string() : out.substr(h);
}
}  // namespace

TEST(LightSweep, HelpShowsDefaultsAndReadableRanges) {
  const CliRun r = run_cli("light-sweep --help");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* want : {"=full", "=own", "=200", "=2000", "1..1000000", "1..100000000", "pick one and print it"})
    EXPECT_NE(r.out.find(want), std::string::npos) << "no '" << want << "' in\n" << r.out;
  EXPECT_EQ(r.out.find("18446744073709551615"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("UINT"), std::string::npos) << r.out;
}

TEST(LightSweep, SeedZeroOrAbsentPicksOneAndPrintsIt) {
  const TempDir d;
  for (const std::string seed_arg : {"", " --seed 0"}) {
    const CliRun r = run_cli(kSmall + seed_arg + " --json " + (d / "a.json"));
    ASSERT_EQ(r.status, 0) << seed_arg << ": " << r.err;
    std::smatch m;
    ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(seed (\d+) \(picked; --seed (\d+) reproduces this run\))")))
        << r.out;
    EXPECT_EQ(m[1].str(), m[2].str());
    EXPECT_NE(m[1].str(), "0");
    const auto j = nlohmann::json::parse(slurp(d / "a.json"));
    EXPECT_EQ(std::to_string(j["seed"].get<uint64_t>()), m[1].str());
    EXPECT_TRUE(j["seed_picked"].get<bool>());
    // The printed seed replays the run: the same table.
    const CliRun again = run_cli(kSmall + " --seed " + m[1].str());
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_EQ(table_of(again.out), table_of(r.out));
    EXPECT_EQ(again.out.find("picked"), std::string::npos) << again.out;
  }
}

// Every column but PSNR in output LSBs (2^-F), as the header says; the JSON keeps approx_max (a value in
// [0, 1]) and adds approx_max_lsb = approx_max·2^F.
TEST(LightSweep, ColumnsAreInTheUnitTheHeaderStates) {
  const TempDir d;
  const CliRun r = run_cli(kSmall + " --seed 7 --json " + (d / "l.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("errors in output LSBs (2^-"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(d / "l.json"));
  const int F = j["frac"].get<int>();
  ASSERT_GT(j["units"].size(), 1u);
  bool some_approx = false;
  for (const auto& u : j["units"]) {
    const double a = u["approx_max"].get<double>(), al = u["approx_max_lsb"].get<double>();
    EXPECT_GE(a, 0.0);
    EXPECT_LE(a, 1.0);
    EXPECT_DOUBLE_EQ(al, std::ldexp(a, F));
    some_approx |= al > 1.0;
    // The printed row: name, total max, approx max, ... — approx max printed in LSB (2 decimals).
    const std::string name = u["specular"].get<std::string>();
    std::istringstream rows(table_of(r.out));
    std::string line;
    bool found = false;
    while (std::getline(rows, line)) {
      std::istringstream ls(line);
      std::string n;
      double total = 0, approx = 0;
      if (!(ls >> n >> total >> approx) || n != name) continue;
      found = true;
      EXPECT_NEAR(approx, al, 0.006) << line;
      EXPECT_NEAR(total, u["total_max_lsb"].get<double>(), 0.006) << line;
    }
    EXPECT_TRUE(found) << name << " not in\n" << r.out;
  }
  EXPECT_TRUE(some_approx) << "no unit with an approximation error above 1 LSB: the test would not tell the units apart";
}

TEST(LightSweep, BadValuesAreOneLineErrors) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"light-sweep --seed -1", "--seed: '-1' is not an integer"},
      {"light-sweep --seed 99999999999999999999999", "--seed"},
      {"light-sweep --programs 0", "--programs: '0' is not an integer in [1, 1000000]"},
      {"light-sweep --programs 1000001", "--programs"},
      {"light-sweep --per-program 0", "--per-program"},
      {"light-sweep --per-program -3", "--per-program"},
      {"light-sweep --features ''", "empty feature set"},
      {"light-sweep --specular ''", "empty --specular"},
      {"light-sweep --json ''", "empty path"},
      {"light-sweep --spec-guard 9", "--spec-guard"},
      {"light-sweep --features nosuch --programs 1 --per-program 1", "nosuch"},
      {"light-sweep --specular bogus --programs 1 --per-program 1", "unknown --specular 'bogus'"},
      {"light-sweep --specular table256 --programs 1 --per-program 1", "the lighting core has no table units"},
      {"light-sweep --programs 1 --per-program 1 --json /proc/x.json", "cannot write /proc/x.json"},
  };
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& [args, needle] = cases[i];
    const TempDir d;
    const CliRun r = run_cli(args, d.str());
    EXPECT_EQ(r.status, 1) << args << "\n" << r.err;
    EXPECT_EQ(lines(r.err), 1) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
    if (i < 10) {  // usage errors (not the unknown names or the unwritable output) name the subcommand's help
      EXPECT_NE(r.err.find("(see shadecore light-sweep --help)"), std::string::npos) << args << "\n" << r.err;
    }
    EXPECT_TRUE(r.out.empty()) << args << "\n" << r.out;
    EXPECT_TRUE(d.entries().empty()) << args;
  }
}

// The quantisation contract of docs/lighting.md §7 (issue 18): with the default spec_guard every F = 16
// named set's core − the same equation in double with the same unit stays within ±128 LSB of 2^−16, for
// every lighting-core unit; with spec_guard 0 (the specular path at F bits) it does not on `full` — so
// this test tells the two apart. Seeded (a reproducible sample, as in §7's table).
TEST(LightSweep, QuantisationContractAtTheDefaultGuard) {
  for (const char* set : {"full", "gl_default", "phong_point"}) {
    const TempDir d;
    const CliRun r = run_cli(std::string("light-sweep --features ") + set +
                             " --specular all --programs 30 --per-program 1000 --seed 3 --json " + (d / "o.json"));
    ASSERT_EQ(r.status, 0) << r.err;
    const auto j = nlohmann::json::parse(slurp(d / "o.json"));
    EXPECT_EQ(j["feature_set"]["spec_guard"].get<int>(), 5);
    for (const auto& u : j["units"]) {
      EXPECT_GE(u["quant_min_lsb"].get<double>(), -128.0) << set << " " << u["specular"];
      EXPECT_LE(u["quant_max_lsb"].get<double>(), 128.0) << set << " " << u["specular"];
      // spot cone edges (full has spot slots) are counted apart: a step, rare (docs/lighting.md §7)
      EXPECT_LE(u["spot_edge_fragments"].get<uint64_t>() * 1000, u["samples"].get<uint64_t>()) << set;
    }
  }
  const TempDir d;
  const CliRun r = run_cli(std::string("light-sweep --features full --specular cs16 --spec-guard 0 --programs 30 ") +
                           "--per-program 1000 --seed 3 --json " + (d / "o.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto j = nlohmann::json::parse(slurp(d / "o.json"));
  EXPECT_EQ(j["feature_set"]["spec_guard"].get<int>(), 0);
  EXPECT_LT(j["units"][0]["quant_min_lsb"].get<double>(), -128.0) << "spec_guard 0 should break the contract on full";
}
