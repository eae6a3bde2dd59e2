// SPDX-License-Identifier: Apache-2.0
#include "output.hpp"
#include "shadecore/features.hpp"
#include "shadecore/render/scene.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <regex>
#include <stdexcept>

#include <fmt/core.h>

#include "shadecore/common/output_files.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/common/subprocess.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must be defined by the build"
#endif
#ifndef SHADECORE_PYTHON
#define SHADECORE_PYTHON "/usr/bin/python3"
#endif
#ifndef SHADECORE_VERSION
#define SHADECORE_VERSION "unknown"
#endif

namespace fs = std::filesystem;

namespace shadecore::cli {

namespace {

// One line: a message never spans lines on stderr.
// One line that cannot drive the terminal: line breaks become blanks, every other control character (in a
// path or name the user gave, e.g. `cannot write /tmp/<ESC>[2J.json`) is shown escaped.
std::string one_line(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return scene::printable(s, 0);
}

}  // namespace

int run_app(CLI::App& app, int argc, char** argv) {
  io::install_interrupt_cleanup("shadecore");
  app.set_version_flag("--version", "shadecore " SHADECORE_VERSION);
  std::string names;
  bool known = false;
  for (const CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) {
    names += (names.empty() ? "" : ", ") + s->get_name();
    if (argc > 1 && s->get_name() == argv[1]) known = true;
  }
  if (argc > 1 && argv[1][0] != '-' && !known) {
    fmt::print(stderr, "shadecore: error: unknown subcommand '{}' (known: {}; see shadecore --help)\n", argv[1], names);
    return kExitError;
  }
  // Usage errors name the help that explains them: the subcommand's own (`shadecore eval --help`) once a
  // subcommand was named, else the top level's.
  const std::string help = known ? "shadecore " + std::string(argv[1]) + " --help" : "shadecore --help";
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::RequiredError& e) {
    // CLI11 says "A subcommand is required" without naming them.
    const std::string what = e.what();
    if (what.find("subcommand") != std::string::npos && !known)
      fmt::print(stderr, "shadecore: error: a subcommand is required ({}; see shadecore --help)\n", names);
    else
      fmt::print(stderr, "shadecore: error: {} (see {})\n", one_line(what), help);
    return kExitError;
  } catch (const CLI::ExtrasError& e) {
    // An option the subcommand does not have: name it, with the nearest option it does have (issue 38).
    if (known) {
      const CLI::App* sub = app.get_subcommand(argv[1]);
      std::vector<std::string> opts;
      for (const CLI::Option* o : sub->get_options())
        for (const std::string& l : o->get_lnames()) opts.push_back("--" + l);
      for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        if (a.rfind("--", 0) != 0 || a == "--") continue;
        const std::string name = a.substr(0, a.find('='));
        if (std::find(opts.begin(), opts.end(), name) != opts.end()) continue;
        const std::string near = nearest_name(name, opts);
        fmt::print(stderr, "shadecore: error: unknown option '{}'{} (see {})\n", one_line(name),
                   near.empty() ? "" : " (did you mean '" + near + "'?)", help);
        return kExitError;
      }
    }
    fmt::print(stderr, "shadecore: error: {} (see {})\n", one_line(e.what()), help);
    return kExitError;
  } catch (const CLI::ParseError& e) {
    // One line, like every other error, and status 1 for every usage error (CLI11's own exit() prints
    // a second "Run with --help" line and uses 100+ statuses).
    fmt::print(stderr, "shadecore: error: {} (see {})\n", one_line(e.what()), help);
    return kExitError;
  } catch (const CheckFailed& e) {
    fmt::print(stderr, "shadecore: {}\n", one_line(e.what()));
    return kExitCheckFailed;
  } catch (const std::invalid_argument& e) {
    // A bad value or combination found by the subcommand itself: a usage error too.
    fmt::print(stderr, "shadecore: error: {} (see {})\n", one_line(e.what()), help);
    return kExitError;
  } catch (const std::exception& e) {
    fmt::print(stderr, "shadecore: error: {}\n", one_line(e.what()));
    return kExitError;
  }
  return 0;
}

void write_staged(const std::string& path, const std::string& content) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) throw io::cannot_write(path, std::strerror(errno));
  try {
    io::write_all(fd, content, path);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) throw io::cannot_write(path, std::strerror(errno));
}

void check_writable_file(const std::string& path) { (void)io::resolve_output(path); }

void write_file_atomic(const std::string& path, const std::string& content) {
  io::OutputSet out;
  const int id = out.file("output", path);
  out.set(id, content);
  out.commit();
}

void ensure_dir(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir))
    throw std::runtime_error("cannot create directory " + dir + (ec ? ": " + ec.message() : ""));
  if (::access(dir.c_str(), W_OK) != 0)
    throw std::runtime_error("cannot write to directory " + dir + ": " + std::strerror(errno));
}

std::pair<int, int> parse_range(const std::string& text) {
  static const std::regex re(R"(^\s*(-?\d{1,9})\s*(?:\.\.\s*(-?\d{1,9})\s*)?$)");
  std::smatch m;
  if (!std::regex_match(text, m, re))
    throw std::invalid_argument("malformed range '" + text + "' (expected N or LO..HI, e.g. 16..1024)");
  const int lo = std::stoi(m[1].str());
  const int hi = m[2].matched ? std::stoi(m[2].str()) : lo;
  if (lo > hi) throw std::invalid_argument("empty range '" + text + "' (LO > HI)");
  return {lo, hi};
}

namespace {
std::string g_command_line = "shadecore";

// Runs a plotting script through the one subprocess runner; on failure its last stderr line is the message.
void run_child(const std::vector<std::string>& argv, const std::string& what) {
  proc::Options o;
  o.capture_stdout = false;
  const proc::Result r = proc::run(argv, o);
  if (r.ok()) return;
  if (r.status == 127 && r.err.find("cannot run") != std::string::npos)
    throw std::runtime_error(what + " failed: cannot run the interpreter " + argv[0]);
  throw std::runtime_error(what + " failed: " + one_line(r.last_line()));
}

std::string scripts_dir() {
  const char* env_dir = std::getenv("SHADECORE_SCRIPTS");
  return env_dir ? env_dir : std::string(SHADECORE_SOURCE_DIR) + "/scripts";
}
}  // namespace

void set_command_line(int argc, char** argv) {
  std::string s = "shadecore";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                          "0123456789-_./=,:+@%") == std::string::npos;
    if (plain) {
      s += " " + a;
    } else {
      std::string q;
      for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
      s += " '" + q + "'";
    }
  }
  g_command_line = s;
}

const std::string& command_line() { return g_command_line; }

void run_python(const std::string& script, const std::vector<std::string>& args) {
  const std::string path = scripts_dir() + "/" + script;
  if (!fs::exists(path)) throw std::runtime_error("plot script not found: " + path);
  std::vector<std::string> argv = {SHADECORE_PYTHON, path};
  argv.insert(argv.end(), args.begin(), args.end());
  run_child(argv, "plotting");
}

void run_python_script(const std::string& script, const std::string& args) {
  const std::string path = scripts_dir() + "/" + script;
  if (!fs::exists(path)) throw std::runtime_error("plot script not found: " + path);
  run_child({"/bin/sh", "-c", std::string(SHADECORE_PYTHON) + " '" + path + "' " + args}, "plotting");
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M UTC", std::gmtime(&t));
  return buf;
}

void commit_with_fit_plots(io::OutputSet& outs, int plots_out, const std::string& plots_dir,
                           const std::string& csv_name, const std::string& csv, const std::string& what) {
  if (plots_out >= 0) {
    const std::string stage = outs.stage(plots_out);
    write_staged(stage + "/" + csv_name, csv);
    std::fflush(stdout);
    run_python("plot_fit.py", {"--dir", stage, what, "--caption", fmt::format("{}, {}", command_line(), utc_now())});
  }
  outs.commit();
  if (plots_out >= 0) fmt::print("plots written to {}/\n", plots_dir);
}

void ProgressFlags::add(CLI::App* sub) {
  auto* a = sub->add_flag("--progress", on, "Progress bar on stderr even when it is not a terminal");
  auto* b = sub->add_flag("--no-progress", off, "No progress bar (default: shown when stderr is a terminal)");
  a->excludes(b);
}

bool ProgressFlags::enabled() const { return io::progress_wanted(on, off); }

}  // namespace shadecore::cli
