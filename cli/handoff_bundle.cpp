// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — the transaction every bundle goes through (make_bundle: staging directory,
// MANIFEST.sha256, tarball, commit or leave nothing) and the child processes it runs (run_proc, in their
// own process group so that an interrupt stops a whole tool tree). cli/handoff_bundle.hpp.
#include "handoff_bundle.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstring>

#include <fmt/core.h>

#include "output.hpp"
#include "shadecore/common/subprocess.hpp"
#include "unit_spec.hpp"

namespace shadecore::cli::handoff {

// ---------------------------------------------------------------------------- child processes
// The common runner (shadecore/common/subprocess.hpp): children in their own process group so an interrupt
// can stop a whole tool tree (make, g++); its InterruptScope records the signal and stops them.
namespace {
using SignalGuard = proc::InterruptScope;

void check_interrupt() {
  if (const int sig = proc::interrupt_signal()) throw Interrupted(fmt::format("interrupted by signal {}", sig));
}
}  // namespace

Proc run_proc(const std::vector<std::string>& argv, const fs::path& cwd, const ProcOptions& opt) {
  check_interrupt();
  proc::Options o;
  o.cwd = cwd.string();
  o.merge_stderr = true;
  o.own_group = opt.own_group;
  o.ignore_sigint = false;  // not in its own group: a terminal's ^C reaches it directly
  o.on_line = opt.on_line;
  const proc::Result r = proc::run(argv, o);
  check_interrupt();
  return Proc{r.status, r.out};
}

namespace {
std::string manifest(const fs::path& dir) {
  std::vector<std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.is_regular_file()) {
      const std::string rel = fs::relative(e.path(), dir).generic_string();
      if (rel != "MANIFEST.sha256") files.push_back(rel);
    }
  std::sort(files.begin(), files.end());
  std::string s;
  for (const auto& f : files) s += sha256_hex(read_text(dir / f)) + "  " + f + "\n";
  return s;
}
}  // namespace

void make_bundle(const std::string& out, bool force, const std::function<void(const fs::path&, const Step&)>& fill) {
  // Destination: a symlink to a directory is followed (the link stays); a non-directory is refused.
  std::string out_text = out;
  while (out_text.size() > 1 && out_text.back() == '/') out_text.pop_back();
  const fs::path given = fs::path(out_text).lexically_normal();
  std::error_code ec;
  fs::path dest = given;
  if (fs::is_symlink(fs::symlink_status(given, ec))) {
    dest = fs::canonical(given, ec);
    if (ec || !fs::is_directory(dest)) throw std::runtime_error("--out " + out + " is a symlink that does not lead to a directory");
  }
  const bool dest_exists = fs::exists(fs::symlink_status(dest, ec));
  if (dest_exists && !fs::is_directory(fs::symlink_status(dest, ec)))
    throw std::runtime_error("--out " + out + " exists and is not a directory");
  if (dest_exists && !fs::is_empty(dest, ec) && !force)
    throw std::runtime_error("--out " + out + " is not empty (use --force to replace its contents)");
  if (dest == fs::current_path().lexically_normal() || dest.filename().empty() || dest.filename() == "..")
    throw std::runtime_error("--out " + out + " cannot be used as a bundle directory");
  const std::string tar_path = given.string() + ".tar.gz";
  if (fs::exists(fs::symlink_status(tar_path, ec))) {
    if (!force) throw std::runtime_error(tar_path + " exists (use --force to replace it)");
  }
  fs::path parent = fs::absolute(dest).parent_path();
  // Missing parents are created, and removed again if the run fails.
  std::vector<fs::path> created;
  for (fs::path p = parent; !p.empty() && !fs::exists(p); p = p.parent_path()) created.push_back(p);
  std::reverse(created.begin(), created.end());

  SignalGuard guard;
  proc::clear_interrupt();
  fs::path staging;
  bool committed = false;
  auto cleanup = [&] {
    std::error_code e2;
    if (!staging.empty()) fs::remove_all(staging, e2);
    if (!committed)
      for (auto it = created.rbegin(); it != created.rend(); ++it) fs::remove(*it, e2);  // only if empty
  };
  try {
    for (const auto& p : created) {
      fs::create_directory(p, ec);
      if (ec) throw std::runtime_error("cannot create directory " + p.string() + ": " + ec.message());
    }
    if (::access(parent.c_str(), W_OK) != 0)
      throw std::runtime_error("cannot write to directory " + parent.string() + ": " + std::strerror(errno));
    check_output_path(tar_path);
    staging = parent / fmt::format(".{}.handoff-tmp.{}", dest.filename().string(), ::getpid());
    fs::remove_all(staging, ec);
    if (!fs::create_directory(staging, ec) || ec)
      throw std::runtime_error("cannot create " + staging.string() + ": " + ec.message());
    const std::string name = given.filename().string();
    const fs::path dir = staging / name;
    fs::create_directories(dir);
    const auto t0 = std::chrono::steady_clock::now();
    const Step step = [t0](const std::string& what) {
      const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      fmt::print("handoff: [{:5.1f} s] {}\n", s, what);
      std::fflush(stdout);
    };

    fill(dir, step);
    write_text(dir / "MANIFEST.sha256", manifest(dir));

    // The tarball of the directory (top-level folder = the --out name).
    const std::string tmp_tar = (staging / (name + ".tar.gz")).string();
    const Proc t = run_proc({"tar", "-C", staging.string(), "--sort=name", "--owner=0", "--group=0", "--numeric-owner",
                             "-czf", tmp_tar, name},
                            staging);
    if (t.status != 0) throw std::runtime_error("tar failed: " + first_line(t.out));
    const std::string tar_bytes = read_text(tmp_tar);
    check_interrupt();

    // ---- commit: swap the directory into place, then the tarball; undo the swap if that fails.
    const fs::path old = staging / ".old";
    if (dest_exists) {
      fs::rename(dest, old, ec);
      if (ec) throw std::runtime_error("cannot replace " + dest.string() + ": " + ec.message());
    }
    fs::rename(dir, dest, ec);
    if (ec) {
      std::error_code e2;
      if (dest_exists) fs::rename(old, dest, e2);
      throw std::runtime_error("cannot move the bundle to " + dest.string() + ": " + ec.message());
    }
    try {
      write_output_file(tar_path, tar_bytes);
    } catch (...) {
      std::error_code e2;
      fs::rename(dest, staging / ".failed", e2);
      if (dest_exists) fs::rename(old, dest, e2);
      throw;
    }
    committed = true;
    cleanup();
    const std::string man = read_text(dest / "MANIFEST.sha256");
    step(fmt::format("wrote {} and {} ({} files in MANIFEST.sha256)", given.string(), tar_path,
                     std::count(man.begin(), man.end(), '\n')));
  } catch (...) {
    cleanup();
    if (proc::interrupt_signal()) {  // interrupted: nothing is left behind; end the way the signal would have
      const int sig = proc::interrupt_signal();
      guard.restore();
      fmt::print(stderr, "shadecore: error: handoff interrupted by signal {}; nothing written\n", sig);
      ::signal(sig, SIG_DFL);
      ::raise(sig);
    }
    throw;
  }
}

}  // namespace shadecore::cli::handoff
