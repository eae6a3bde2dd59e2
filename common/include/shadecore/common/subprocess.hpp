// SPDX-License-Identifier: Apache-2.0
// shadecore — the one subprocess runner of the CLI and the tools: fork/exec of an argv (never a shell
// string), stdout and stderr captured, the child registered with the interrupt cleanup (Ctrl-C terminates it
// and removes the run's outputs, shadecore/common/output_files.hpp), SIGINT ignored in the child so only the
// parent reports the interrupt (no Python traceback on the terminal).
#pragma once

#include <string>
#include <vector>

namespace shadecore::proc {

struct Options {
  std::string cwd;            // run there (empty: the current directory)
  bool capture_stdout = true; // false: the child's stdout is ours
  bool capture_stderr = true; // false: the child's stderr is ours (a progress line of its own)
};

struct Result {
  int status = 0;             // exit status; 128 + N when killed by signal N; 127 when it could not be run
  std::string out, err;       // captured streams
  [[nodiscard]] bool ok() const { return status == 0; }
  // The last non-empty line of err (or of out), or "exit status N" / "killed by signal N".
  [[nodiscard]] std::string last_line() const;
};

// Runs argv[0] (searched in PATH when it has no '/') with the arguments argv[1..]. Throws std::runtime_error
// only when the process cannot be started at all (pipe or fork failure).
Result run(const std::vector<std::string>& argv, const Options& opt = {});

}  // namespace shadecore::proc
