// SPDX-License-Identifier: Apache-2.0
// shadecore — the process-wide part of the output rules: the interrupt handler and what it cleans up
// (see shadecore/common/output_files.hpp).
#include "shadecore/common/output_files.hpp"

#include <limits.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <mutex>

namespace shadecore::io {

// ---------------------------------------------------------------------------------------------------
// Interrupt cleanup: paths and child processes registered here are removed / terminated by the signal
// handler (async-signal-safe: kill, waitpid, unlink, rmdir, write, _exit only).
namespace detail {
constexpr int kSlots = 256;
struct Slot {
  std::atomic<int> kind{0};  // 0 free, 1 file (unlink), 2 directory (rmdir)
  std::atomic<unsigned> seq{0};
  char path[PATH_MAX] = {};
};
Slot g_slots[kSlots];
std::atomic<pid_t> g_children[64];
std::atomic<bool> g_child_group[64];
std::atomic<unsigned> g_seq{0};
std::atomic<int> g_progress_line{0};  // a progress bar is drawn on stderr (clear it first)
char g_prog[64] = "shadecore";
std::mutex g_mu;

void write_str(const char* s) {
  const size_t n = std::strlen(s);
  ssize_t r = ::write(2, s, n);
  (void)r;
}

void kill_children(int sig) {
  for (int i = 0; i < 64; ++i) {
    const pid_t p = g_children[i].load();
    if (p > 0) ::kill(g_child_group[i].load() ? -p : p, sig);
  }
}

extern "C" void on_fatal_signal(int sig) {
  kill_children(SIGTERM);
  for (auto& c : g_children) {
    const pid_t p = c.load();
    if (p > 0) ::waitpid(p, nullptr, 0);
  }
  for (auto& s : g_slots)
    if (s.kind.load(std::memory_order_acquire) == 1) ::unlink(s.path);
  // Directories: newest first (a staging directory before the directory it lives in).
  unsigned last = ~0u;
  for (;;) {
    int best = -1;
    unsigned best_seq = 0;
    for (int i = 0; i < kSlots; ++i)
      if (g_slots[i].kind.load(std::memory_order_acquire) == 2) {
        const unsigned q = g_slots[i].seq.load();
        if (q < last && (best < 0 || q > best_seq)) best = i, best_seq = q;
      }
    if (best < 0) break;
    ::rmdir(g_slots[best].path);
    last = best_seq;
  }
  if (g_progress_line.load()) write_str("\r\033[K");
  write_str(g_prog);
  write_str(sig == SIGINT ? ": interrupted\n" : ": terminated by a signal\n");
  ::_exit(128 + sig);
}
}  // namespace detail

// Installs the handler for SIGINT, SIGTERM and SIGHUP (unless the signal is inherited as ignored).
// (SIGPIPE keeps its default, so `shadecore ... | head` ends quietly; a FIFO output whose reader went
// away is turned into a write error by write_stream(), which blocks SIGPIPE while it writes.)
void install_interrupt_cleanup(const char* prog) {
  std::snprintf(detail::g_prog, sizeof detail::g_prog, "%s", prog);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction old {};
    if (::sigaction(sig, nullptr, &old) == 0 && old.sa_handler == SIG_IGN) continue;
    struct sigaction sa {};
    sa.sa_handler = detail::on_fatal_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;
    ::sigaction(sig, &sa, nullptr);
  }
}

int track(const std::string& path, int kind) {
  std::lock_guard<std::mutex> lk(detail::g_mu);
  for (int i = 0; i < detail::kSlots; ++i) {
    auto& s = detail::g_slots[i];
    if (s.kind.load() != 0) continue;
    std::snprintf(s.path, sizeof s.path, "%s", path.c_str());
    s.seq.store(++detail::g_seq);
    s.kind.store(kind, std::memory_order_release);
    return i;
  }
  return -1;  // more than kSlots live outputs: not cleaned on a signal (never happens here)
}
void untrack(int slot) {
  if (slot >= 0) detail::g_slots[slot].kind.store(0, std::memory_order_release);
}
void track_child(pid_t pid, bool group) {
  for (int i = 0; i < 64; ++i) {
    pid_t z = 0;
    if (detail::g_children[i].compare_exchange_strong(z, pid)) {
      detail::g_child_group[i].store(group);  // (callers register with signals blocked)
      return;
    }
  }
}
void signal_children(int sig) { detail::kill_children(sig); }
void untrack_child(pid_t pid) {
  for (auto& c : detail::g_children) {
    pid_t p = pid;
    if (c.compare_exchange_strong(p, 0)) return;
  }
}
void set_progress_line(bool on) { detail::g_progress_line.store(on ? 1 : 0); }

}  // namespace shadecore::io
