// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — output helpers: all-or-nothing file outputs, the command line, the plotting hand-off,
// and the exit-status convention (docs/cli.md).
#pragma once

#include <CLI/CLI.hpp>

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "shadecore/common/output_files.hpp"

namespace shadecore::cli {

// Exit statuses (docs/cli.md): 0 success; 1 any error (bad argument, unwritable output, failed step;
// nothing is written); 2 a check ran to the end and FAILED (co-simulation mismatch etc.: the outputs
// that record the failure are written); 128+N stopped by signal N (nothing is written).
inline constexpr int kExitError = 1;
inline constexpr int kExitCheckFailed = 2;

// Thrown when a run completed but its verdict is FAIL (exit status 2); the message is the one line.
class CheckFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses the command line and runs the chosen subcommand with the rules above: one line on stderr for
// every error, "unknown subcommand", --version. Called by main().
int run_app(CLI::App& app, int argc, char** argv);

// Writes `content` to `path` with the rules of output_files.hpp (symlinks followed, devices and FIFOs
// written in place, regular files through a temporary file and a rename). Throws one line on failure.
void write_file_atomic(const std::string& path, const std::string& content);

// Writes a file of ours (inside a staging directory of io::OutputSet): plain write, throws one line.
void write_staged(const std::string& path, const std::string& content);

// Checks up front that `path` can be written (see output_files.hpp). Throws std::runtime_error.
void check_writable_file(const std::string& path);

// Creates `dir` (and parents) if needed; throws if it cannot be created or written.
void ensure_dir(const std::string& dir);

// Parses "LO..HI" or "N" into an inclusive range of integers. Throws std::invalid_argument.
// (For exponent ranges use args::parse_n_range, which also checks 16..1024.)
std::pair<int, int> parse_range(const std::string& text);

// The command line shadecore was started with (for plot footers and reports), set by main().
void set_command_line(int argc, char** argv);
const std::string& command_line();

// Runs scripts/<script> with the python that has matplotlib, without a shell. Its stderr is captured:
// on failure one line "plotting failed: <its last line>" is thrown. Ctrl-C stops it cleanly.
void run_python(const std::string& script, const std::vector<std::string>& args);

// Older form: `args` is a shell-quoted string (kept for callers written against it).
void run_python_script(const std::string& script, const std::string& args);

// The current date and time, "YYYY-MM-DD HH:MM UTC" (JSON "date", report headers, plot captions).
std::string utc_now();

// The end of `shadecore fit` and `shadecore energy`: with --plots (plots_out >= 0) writes `csv` as
// <stage>/<csv_name> and runs scripts/plot_fit.py --dir <stage> <what> (--fit or --energy) with the command
// line and date as caption; commits every output; then says where the plots went.
void commit_with_fit_plots(io::OutputSet& outs, int plots_out, const std::string& plots_dir,
                           const std::string& csv_name, const std::string& csv, const std::string& what);

// Adds --progress / --no-progress to a subcommand; progress_enabled() then says whether to draw.
struct ProgressFlags {
  bool on = false, off = false;
  void add(CLI::App* sub);
  [[nodiscard]] bool enabled() const;
};

}  // namespace shadecore::cli
