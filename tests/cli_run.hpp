// Test helper shared by the CLI tests: run the shadecore executable, capture its status, stdout and
// stderr, and check the one-line-error rule for bad input.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#ifndef SHADECORE_CLI
#error "SHADECORE_CLI must point at the shadecore executable"
#endif

namespace shadecore::testing {

struct CliRun {
  int status;
  std::string out, err;
};

inline CliRun run_cli(const std::string& args) {
  namespace fs = std::filesystem;
  static int calls = 0;
  const fs::path dir = fs::temp_directory_path() /
                       ("shadecore_cli_" + std::to_string(::getpid()) + "_" + std::to_string(calls++));
  fs::create_directories(dir);
  const std::string o = (dir / "stdout").string(), e = (dir / "stderr").string();
  const int rc = std::system((std::string(SHADECORE_CLI) + " " + args + " >" + o + " 2>" + e).c_str());
  auto slurp = [](const std::string& p) {
    std::ifstream in(p);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  CliRun r{WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, slurp(o), slurp(e)};
  fs::remove_all(dir);
  return r;
}

// Bad input: non-zero exit and exactly one line on stderr that contains `needle`.
inline void expect_one_line_error(const std::string& args, const std::string& needle) {
  const CliRun r = run_cli(args);
  EXPECT_NE(r.status, 0) << args;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
}

}  // namespace shadecore::testing
