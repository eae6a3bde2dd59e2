// SPDX-License-Identifier: Apache-2.0
// shadecore — the one subprocess runner of the CLI and the tools (the handoff bundles' tool runs, the
// lighting core's build, `cosim`'s simulator shards, `regress --local`'s shard pool): fork/exec of an argv
// (never a shell string), searched in PATH when argv[0] has no '/'.
//   * output: stdout and stderr captured apart, or interleaved in one stream (merge_stderr, the order the
//     child wrote them), or written to a log file; complete stdout lines can be handed to a callback as
//     they arrive;
//   * signals: SIGINT ignored in the child by default, so only the parent reports an interrupt (no Python
//     traceback on the terminal); the child optionally leads its own process group (own_group), so one
//     signal stops a whole tool tree (make, g++; a shard and its simulators);
//   * every running child is registered with the interrupt cleanup (shadecore/common/output_files.hpp):
//     the fatal-signal handler terminates it (its group when it leads one) and removes the run's outputs;
//   * InterruptScope: for commands that must act on an interrupt themselves (remove a staging directory,
//     cancel a Slurm array) — the signal only sets a flag and terminates the running children; the command
//     polls interrupt_signal() and ends the way it chooses.
#pragma once

#include <signal.h>
#include <sys/types.h>

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace shadecore::proc {

struct Options {
  std::string cwd;              // run there (empty: the current directory)
  bool capture_stdout = true;   // false: the child's stdout is ours
  bool capture_stderr = true;   // false: the child's stderr is ours (a progress line of its own)
  bool merge_stderr = false;    // stderr into the stdout stream: one interleaved Result::out
  bool own_group = false;       // the child leads its own process group (terminate() reaches its tree)
  bool ignore_sigint = true;    // SIGINT ignored in the child (the parent stops it)
  std::string log_path;         // non-empty: stdout and stderr (interleaved) written to this file, not captured
  std::vector<std::pair<std::string, std::string>> env;  // set in the child's environment
  // Called with each complete stdout line (with its '\n'; a last unterminated line at the end) as it arrives.
  std::function<void(const std::string&)> on_line;
};

struct Result {
  int status = -1;              // exit status; 128 + N when killed by signal N; 127 when it could not be run
  std::string out, err;         // captured streams (err empty when merged)
  [[nodiscard]] bool ok() const { return status == 0; }
  // The last non-empty line of err (or of out), or "exit status N" / "killed by signal N".
  [[nodiscard]] std::string last_line() const;
};

// Several children at once, read by one thread (poll): the shards of `cosim`, the local regression pool.
class Pool {
 public:
  Pool();
  ~Pool();  // children still running are terminated (their group) and reaped
  Pool(const Pool&) = delete;
  Pool& operator=(const Pool&) = delete;

  // Starts argv; returns its id (0, 1, ...). Throws std::runtime_error when it cannot be started at all
  // (pipe, fork or log file failure); a program that does not exist ends with status 127.
  size_t start(const std::vector<std::string>& argv, const Options& opt = {});
  // Waits up to timeout_ms (−1: until something happens) for output or an exit, delivers the output,
  // reaps what ended; returns the ids of the children that ended during this call.
  std::vector<size_t> poll(int timeout_ms);
  [[nodiscard]] size_t running() const;
  [[nodiscard]] bool finished(size_t id) const;
  [[nodiscard]] pid_t pid(size_t id) const;
  [[nodiscard]] const Result& result(size_t id) const;
  // Sends sig to a running child (to its group when it leads one).
  void terminate(size_t id, int sig = SIGTERM);
  void terminate_all(int sig = SIGTERM);

 private:
  struct Child;
  std::vector<std::unique_ptr<Child>> kids_;
};

// Runs one child to its end. Throws std::runtime_error only when it cannot be started at all.
Result run(const std::vector<std::string>& argv, const Options& opt = {});

// Handles SIGINT, SIGTERM and SIGHUP while it lives: the signal is recorded and every running child of
// the runner is sent SIGTERM; the previous handlers come back at restore() or destruction.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;
  void restore();

 private:
  struct sigaction old_[3];
  bool active_ = true;
};
// The signal received inside an InterruptScope (0: none); clear_interrupt() forgets it.
int interrupt_signal();
void clear_interrupt();

}  // namespace shadecore::proc
