// SPDX-License-Identifier: Apache-2.0
// The sweep CLI: bad input gets a one-line error and a non-zero exit, outputs are complete.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "cli_run.hpp"

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

TEST(CliSweep, BadArgumentsGiveOneLineErrors) {
  expect_one_line_error("sweep --variant nosuch --no-progress", "unknown variant");
  expect_one_line_error("sweep --n 16..x --no-progress", "malformed range");
  expect_one_line_error("sweep --n 100..20 --no-progress", "LO > HI");
  expect_one_line_error("sweep --n 15..20 --no-progress", "out of range");
  expect_one_line_error("sweep --n 16..1025 --no-progress", "out of range");
  expect_one_line_error("sweep --frac 25 --no-progress", "fraction width 25 out of range");
  expect_one_line_error("sweep --frac 7 --no-progress", "fraction width 7 out of range");
  expect_one_line_error("sweep --config huge --no-progress", "unknown config");
  expect_one_line_error("sweep --cutoff maybe --no-progress", "unknown cutoff");
  expect_one_line_error("sweep --json /nonexistent-dir/x.json --no-progress", "cannot write");
}

TEST(CliSweep, UnwritableOutputLeavesNoFile) {
  const fs::path dir = fs::temp_directory_path() / ("shadecore_cli_ro_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path csv = dir / "ok.csv";
  // The JSON path is a directory: the run must fail before writing anything, including the CSV.
  const CliRun r = run_cli("sweep --n 16..17 --frac 8 --no-progress --csv " + csv.string() + " --json " + dir.string());
  EXPECT_NE(r.status, 0);
  EXPECT_FALSE(fs::exists(csv));
  fs::remove_all(dir);
}

TEST(CliSweep, WritesCompleteJsonAndCsv) {
  const fs::path dir = fs::temp_directory_path() / ("shadecore_cli_out_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path json = dir / "s.json", csv = dir / "s.csv";
  const CliRun r = run_cli("sweep --n 16..40 --frac 10 --no-progress --json " + json.string() + " --csv " + csv.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("quantisation"), std::string::npos);
  EXPECT_NE(r.out.find("NOT CHECKED"), std::string::npos);  // partial n range: no verdict claimed
  std::ifstream c(csv);
  std::string line;
  size_t rows = 0;
  while (std::getline(c, line)) ++rows;
  EXPECT_EQ(rows, 1u + 25u);  // header + one row per n
  std::ifstream j(json);
  std::stringstream ss;
  ss << j.rdbuf();
  EXPECT_NE(ss.str().find("\"quant_ulp\""), std::string::npos);
  for (const auto& e : fs::directory_iterator(dir))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "temporary file left behind";
  fs::remove_all(dir);
}

TEST(CliSweep, ParseErrorsAreOneLine) {
  expect_one_line_error("sweep --no-such-option", "no-such-option");
  expect_one_line_error("sweep --threads many --no-progress", "threads");
  expect_one_line_error("", "subcommand");
  const CliRun help = run_cli("sweep --help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--variant"), std::string::npos);
}

TEST(CliSweep, Cs16OnlyOptionsRejectedForSchlick) {
  expect_one_line_error("sweep --variant schlick_div --cutoff sign_clamp --n 16 --no-progress", "apply to cs16 and its forms only");
  expect_one_line_error("sweep --variant schlick_nr --guard 6 --n 16 --no-progress", "apply to cs16 and its forms only");
}
