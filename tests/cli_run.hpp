// SPDX-License-Identifier: Apache-2.0
// Test helper shared by the CLI tests: run the shadecore executable (or any command), capture its status,
// stdout and stderr, temporary directories, and the one-line-error rule for bad input.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#ifndef SHADECORE_CLI
#error "SHADECORE_CLI must point at the shadecore executable"
#endif

namespace shadecore::testing {

struct CliRun {
  int status;  // exit status; 128 + N when killed by signal N
  std::string out, err;
};

inline std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A fresh, empty directory under the system temp dir, removed with everything in it at scope end.
class TempDir {
 public:
  TempDir() {
    static int calls = 0;
    path_ = std::filesystem::temp_directory_path() /
            ("shadecore_t_" + std::to_string(::getpid()) + "_" + std::to_string(calls++));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::string str() const { return path_.string(); }
  [[nodiscard]] std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  // Names of everything in the directory (hidden files included: temporaries must not be left).
  [[nodiscard]] std::set<std::string> entries() const {
    std::set<std::string> s;
    for (const auto& e : std::filesystem::directory_iterator(path_)) s.insert(e.path().filename().string());
    return s;
  }

 private:
  std::filesystem::path path_;
};

// Runs a shell command line (in `cwd` if given), capturing stdout and stderr.
inline CliRun run_shell(const std::string& cmd, const std::string& cwd = "") {
  const TempDir io;
  const std::string o = io / "stdout", e = io / "stderr";
  const std::string full = (cwd.empty() ? "" : "cd '" + cwd + "' && ") + "(" + cmd + ") >" + o + " 2>" + e;
  const int rc = std::system(full.c_str());
  return CliRun{WIFEXITED(rc) ? WEXITSTATUS(rc) : 128 + (WIFSIGNALED(rc) ? WTERMSIG(rc) : 0), slurp(o), slurp(e)};
}

inline CliRun run_cli(const std::string& args, const std::string& cwd = "") {
  return run_shell(std::string(SHADECORE_CLI) + " " + args, cwd);
}

inline long lines(const std::string& s) { return static_cast<long>(std::count(s.begin(), s.end(), '\n')); }

// Bad input: non-zero exit and exactly one line on stderr that contains `needle`.
inline void expect_one_line_error(const std::string& args, const std::string& needle) {
  const CliRun r = run_cli(args);
  EXPECT_NE(r.status, 0) << args;
  EXPECT_EQ(lines(r.err), 1) << args << "\n" << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << args << "\n" << r.err;
}

}  // namespace shadecore::testing
