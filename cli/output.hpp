// shadecore CLI — output helpers: atomic file writes, argument parsing, plotting hand-off.
#pragma once

#include <string>
#include <utility>

namespace shadecore::cli {

// Writes `content` to `path` atomically: a temporary file in the same directory, then rename.
// Throws std::runtime_error("cannot write PATH: reason") on failure; no partial file is left.
void write_file_atomic(const std::string& path, const std::string& content);

// Checks up front that `path` can be created (its directory exists and is writable), so that a
// long run does not fail at the end. Throws std::runtime_error with a one-line message.
void check_writable_file(const std::string& path);

// Creates `dir` (and parents) if needed; throws if it cannot be created or written.
void ensure_dir(const std::string& dir);

// Parses "LO..HI" or "N" into an inclusive range of integers. Throws std::invalid_argument.
std::pair<int, int> parse_range(const std::string& text);

// The command line shadecore was started with (for plot footers and reports), set by main().
void set_command_line(int argc, char** argv);
const std::string& command_line();

// Runs the python plotting script `script` (a file in scripts/) with `args`; throws on failure.
void run_python_script(const std::string& script, const std::string& args);

}  // namespace shadecore::cli
