// SPDX-License-Identifier: Apache-2.0
// Issue 10, plots and scripts: what the figures show (checked on real CLI output by
// tests/cli_plots_check.py), and scripts/cost_report.py's import check and all-or-nothing report.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <cmath>
#include <set>
#include <sstream>
#include <string>

#include "cli_run.hpp"

#if defined(SHADECORE_SCRIPTS_DIR) && defined(SHADECORE_TESTS_DIR)

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

namespace {
const std::string kPython = "/usr/bin/python3";
}

TEST(CliPlots, FiguresShowWhatTheySay) {
  const TempDir d;
  const CliRun s = run_cli("sweep --n 16..200 --frac 10 --guard 5 --no-progress --plots sweep --json sweep.json", d.str());
  ASSERT_EQ(s.status, 0) << s.err;
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(d / "sweep")) files.insert(e.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"approx_over_n.png", "fig3_n128.csv", "fig3_n128.png", "fig4_delta.png",
                                          "fig4_grid.csv", "per_n.csv", "quant_ulp.png"}));
  const CliRun sd = run_cli("sweep --variant schlick_div --n 16..40 --frac 8 --no-progress --plots schlick --json schlick.json", d.str());
  ASSERT_EQ(sd.status, 0) << sd.err;
  // issue 38: a form and a table unit, whose contracts are not ±½ (compact and table: ±1)
  for (const char* v : {"cs16_compact", "table256"}) {
    const CliRun r = run_cli(std::string("sweep --variant ") + v + " --n 16..100 --frac 10 --no-progress --plots " + v +
                             " --json " + v + ".json", d.str());
    ASSERT_EQ(r.status, 0) << r.err;
    EXPECT_NE(r.out.find("→ MET"), std::string::npos) << r.out;
  }
  // cos_pow: the least-squares fit is exact to rounding, so its res(n) lies far below the old 1e-9 floor.
  const CliRun f = run_cli("fit --lobe cos_pow --model phong --plots fit", d.str());
  ASSERT_EQ(f.status, 0) << f.err;
  EXPECT_TRUE(fs::exists(d / "fit/fig5_res.png"));
  const CliRun c = run_shell(kPython + " " + SHADECORE_TESTS_DIR + "/cli_plots_check.py --scripts " +
                             SHADECORE_SCRIPTS_DIR + " --sweep " + (d / "sweep") + ":cs16:10:5 --sweep " +
                             (d / "schlick") + ":schlick_div:8:5 --sweep " + (d / "cs16_compact") +
                             ":cs16_compact:10:5 --sweep " + (d / "table256") + ":table256:10:5 --fit-dir " + (d / "fit"));
  EXPECT_EQ(c.status, 0) << c.out << c.err;
}

// A python without matplotlib (here: Debian's python with site-packages switched off, -S) fails at once
// with one line and writes nothing; it does not run for minutes first.
TEST(CostReport, MissingMatplotlibFailsFirstAndWritesNothing) {
  const TempDir d;
  const CliRun r = run_shell(kPython + " -S " + SHADECORE_SCRIPTS_DIR + "/cost_report.py --out " + (d / "new/out"));
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find("python module 'matplotlib' is not installed"), std::string::npos) << r.err;
  EXPECT_TRUE(d.entries().empty());
  // Same for the sweep plotting script run by hand.
  const CliRun p = run_shell(kPython + " -S " + SHADECORE_SCRIPTS_DIR + "/plot_sweep.py --dir " + d.str());
  EXPECT_EQ(p.status, 1);
  EXPECT_EQ(lines(p.err), 1) << p.err;
}

// The report is all three files or none; --out is created when missing (and removed again on failure).
TEST(CostReport, ReportIsAllOrNothingAndCreatesOut) {
  const TempDir d;
  const std::string rows =
      R"([{"variant": "cs16", "config": "default", "frac": 16, "guard": 5, "quant_max": 0.5, "quant_min": -0.9,)"
      R"( "total_max": 0.017, "total_min": -1e-15, "latency": 7, "vectors_per_s": 1e6, "luts": 900}])";
  const auto report = [&](const std::string& rows_json, const std::string& out) {
    return run_shell("cd " + std::string(SHADECORE_SCRIPTS_DIR) + " && " + kPython +
                     " -c 'import json, sys, cost_report; cost_report.write_report(json.loads(sys.argv[1]), \"x\", "
                     "sys.argv[2])' '" + rows_json + "' " + out);
  };
  const CliRun ok = report(rows, d / "a/b");
  ASSERT_EQ(ok.status, 0) << ok.err;
  std::set<std::string> files;
  for (const auto& e : fs::directory_iterator(d / "a/b")) files.insert(e.path().filename().string());
  EXPECT_EQ(files, (std::set<std::string>{"tradeoffs.json", "tradeoffs.md", "tradeoffs.png"}));
  // The plot step fails (F given as text: the table prints it, the plot cannot compute 2^-F): no file is
  // written, the new directories are removed.
  std::string broken = rows;
  broken.replace(broken.find("\"frac\": 16"), 10, "\"frac\": \"16\"");
  const CliRun bad = report(broken, d / "c/d");
  EXPECT_NE(bad.status, 0);
  EXPECT_FALSE(fs::exists(d / "c"));
  // An existing report is kept as it was when the new one fails.
  const std::string before = slurp(d / "a/b/tradeoffs.md");
  EXPECT_NE(report(broken, d / "a/b").status, 0);
  EXPECT_EQ(slurp(d / "a/b/tradeoffs.md"), before);
  files.clear();
  for (const auto& e : fs::directory_iterator(d / "a/b")) files.insert(e.path().filename().string());
  EXPECT_EQ(files.size(), 3u);
}

// Issue 23: Fig. 3 is drawn at an n the sweep covered: n = 128 when it is inside --n (fig3_n128.png, as
// the README says), else the swept n nearest to it, named in the file names, the title and on stdout.
TEST(CliPlots, Fig3IsDrawnInsideTheSweptRange) {
  const TempDir d;
  struct Case {
    std::string range;
    int n;
  };
  for (const Case& c : {Case{"100..120", 120}, Case{"200..210", 200}, Case{"128", 128}}) {
    const std::string dir = "p" + c.range;
    const CliRun s = run_cli("sweep --n " + c.range + " --frac 8 --guard 5 --no-progress --plots " + dir, d.str());
    ASSERT_EQ(s.status, 0) << s.err;
    const std::string f3 = "fig3_n" + std::to_string(c.n);
    std::set<std::string> files;
    for (const auto& e : fs::directory_iterator(d / dir)) files.insert(e.path().filename().string());
    EXPECT_EQ(files, (std::set<std::string>{"approx_over_n.png", f3 + ".csv", f3 + ".png", "fig4_delta.png",
                                            "fig4_grid.csv", "per_n.csv", "quant_ulp.png"}))
        << c.range;
    // The CSV's cos^n column is cos(θ)^n at that n.
    std::istringstream csv(slurp(d / (dir + "/" + f3 + ".csv")));
    std::string line;
    std::getline(csv, line);
    int rows = 0;
    double worst = 0;
    while (std::getline(csv, line)) {
      double th = 0, cp = 0;
      char comma = 0;
      std::istringstream ls(line);
      ls >> th >> comma >> cp;
      worst = std::max(worst, std::fabs(cp - std::pow(std::cos(th), c.n)));
      ++rows;
    }
    EXPECT_GT(rows, 100);
    EXPECT_LT(worst, 1e-6) << c.range << ": " << f3 << ".csv is not at n = " << c.n;
    const bool note = s.out.find(f3 + ".png: Fig. 3 at n = " + std::to_string(c.n)) != std::string::npos;
    EXPECT_EQ(note, c.n != 128) << s.out;
    // The figure's title names the n, and says why when it is not the paper's 128.
    const CliRun t = run_shell(kPython + " -c 'import sys; sys.path.insert(0, \"" + std::string(SHADECORE_SCRIPTS_DIR) +
                               "\"); import plot_sweep as p; a = p.parser().parse_args([\"--dir\", sys.argv[1], "
                               "\"--fig3-n\", sys.argv[2], \"--n-range\", sys.argv[3]]); "
                               "print(p.build(a)[\"" + f3 + ".png\"].axes[0].get_title())' " +
                               (d / dir) + " " + std::to_string(c.n) + " " + c.range);
    ASSERT_EQ(t.status, 0) << t.err;
    EXPECT_NE(t.out.find("Fig. 3: n = " + std::to_string(c.n)), std::string::npos) << t.out;
    EXPECT_EQ(t.out.find("outside the swept range " + c.range) != std::string::npos, c.n != 128) << t.out;
  }
}

#endif
