// SPDX-License-Identifier: Apache-2.0
// shadecore — the subprocess runner (see shadecore/common/subprocess.hpp).
#include "shadecore/common/subprocess.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

#include "shadecore/common/output_files.hpp"

namespace shadecore::proc {

std::string Result::last_line() const {
  for (const std::string* s : {&err, &out}) {
    size_t end = s->size();
    while (end > 0) {
      const size_t b = s->rfind('\n', end - 1);
      const size_t a = b == std::string::npos ? 0 : b + 1;
      const std::string line = s->substr(a, end - a);
      if (line.find_first_not_of(" \t\r") != std::string::npos) return line;
      if (b == std::string::npos) break;
      end = b;
    }
  }
  return status > 128 ? "killed by signal " + std::to_string(status - 128) : "exit status " + std::to_string(status);
}

struct Pool::Child {
  pid_t pid = -1;
  bool group = false;
  int fd[2] = {-1, -1};  // stdout (or the merged stream), stderr
  std::string partial;   // stdout since the last '\n' (line callback)
  std::function<void(const std::string&)> on_line;
  bool done = false;
  Result r;

  void deliver(bool flush) {
    if (!on_line) return;
    size_t nl;
    while ((nl = partial.find('\n')) != std::string::npos) {
      on_line(partial.substr(0, nl + 1));
      partial.erase(0, nl + 1);
    }
    if (flush && !partial.empty()) on_line(partial), partial.clear();
  }
};

Pool::Pool() = default;

Pool::~Pool() {
  for (auto& k : kids_)
    if (!k->done) {
      ::kill(k->group ? -k->pid : k->pid, SIGTERM);
      for (int& f : k->fd)
        if (f >= 0) ::close(f), f = -1;
      while (::waitpid(k->pid, nullptr, 0) < 0 && errno == EINTR) {
      }
      io::untrack_child(k->pid);
    }
}

size_t Pool::start(const std::vector<std::string>& argv, const Options& opt) {
  if (argv.empty()) throw std::invalid_argument("proc::Pool::start: empty argv");
  int outp[2] = {-1, -1}, errp[2] = {-1, -1}, logfd = -1;
  auto close_all = [&] {
    for (int f : {outp[0], outp[1], errp[0], errp[1], logfd})
      if (f >= 0) ::close(f);
  };
  if (!opt.log_path.empty()) {
    logfd = ::open(opt.log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (logfd < 0) throw std::runtime_error("cannot write " + opt.log_path + ": " + std::strerror(errno));
  } else {
    const bool out = opt.capture_stdout || opt.merge_stderr, err = opt.capture_stderr && !opt.merge_stderr;
    if ((out && ::pipe2(outp, O_CLOEXEC) != 0) || (err && ::pipe2(errp, O_CLOEXEC) != 0)) {
      const std::string why = std::strerror(errno);
      close_all();
      throw std::runtime_error(argv[0] + ": pipe: " + why);
    }
  }
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  sigset_t all, old;
  sigfillset(&all);
  ::pthread_sigmask(SIG_BLOCK, &all, &old);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (opt.own_group) ::setpgid(0, 0);
    ::signal(SIGINT, opt.ignore_sigint ? SIG_IGN : SIG_DFL);
    ::signal(SIGTERM, SIG_DFL);
    ::signal(SIGHUP, SIG_DFL);
    ::signal(SIGPIPE, SIG_DFL);
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    if (logfd >= 0) {
      ::dup2(logfd, 1);
      ::dup2(logfd, 2);
    } else {
      if (outp[1] >= 0) ::dup2(outp[1], 1);
      if (opt.merge_stderr && outp[1] >= 0) ::dup2(outp[1], 2);
      else if (errp[1] >= 0) ::dup2(errp[1], 2);
    }
    for (const auto& [k, v] : opt.env) ::setenv(k.c_str(), v.c_str(), 1);
    if (!opt.cwd.empty() && ::chdir(opt.cwd.c_str()) != 0) {
      const std::string m = "cannot change to " + opt.cwd + ": " + std::strerror(errno) + "\n";
      ssize_t r = ::write(2, m.data(), m.size());
      (void)r;
      ::_exit(126);
    }
    ::execvp(args[0], args.data());
    const std::string m = "cannot run " + argv[0] + ": " + std::strerror(errno) + "\n";
    ssize_t r = ::write(2, m.data(), m.size());
    (void)r;
    ::_exit(127);
  }
  if (pid > 0) {
    if (opt.own_group) ::setpgid(pid, pid);  // (both sides: no race with an early terminate)
    io::track_child(pid, opt.own_group);
  }
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (pid < 0) {
    const std::string why = std::strerror(errno);
    close_all();
    throw std::runtime_error(argv[0] + ": fork: " + why);
  }
  for (int* f : {&outp[1], &errp[1], &logfd})
    if (*f >= 0) ::close(*f), *f = -1;
  auto k = std::make_unique<Child>();
  k->pid = pid;
  k->group = opt.own_group;
  k->fd[0] = outp[0];
  k->fd[1] = errp[0];
  k->on_line = opt.on_line;
  kids_.push_back(std::move(k));
  return kids_.size() - 1;
}

std::vector<size_t> Pool::poll(int timeout_ms) {
  std::vector<size_t> ended;
  std::vector<pollfd> fds;
  std::vector<std::pair<size_t, int>> who;
  bool pipeless = false;  // a running child with no open pipe: its exit is seen by waitpid only
  for (size_t i = 0; i < kids_.size(); ++i) {
    const Child& k = *kids_[i];
    if (k.done) continue;
    bool any = false;
    for (int s = 0; s < 2; ++s)
      if (k.fd[s] >= 0) fds.push_back({k.fd[s], POLLIN, 0}), who.push_back({i, s}), any = true;
    if (!any) pipeless = true;
  }
  int wait_ms = timeout_ms;
  if (pipeless) wait_ms = wait_ms < 0 ? 50 : std::min(wait_ms, 50);
  if (fds.empty() && !pipeless) return ended;
  const int n = ::poll(fds.data(), fds.size(), wait_ms);
  if (n < 0 && errno != EINTR) throw std::runtime_error(std::string("poll: ") + std::strerror(errno));
  char buf[65536];
  for (size_t j = 0; n > 0 && j < fds.size(); ++j) {
    if (!(fds[j].revents & (POLLIN | POLLHUP | POLLERR))) continue;
    Child& k = *kids_[who[j].first];
    const int s = who[j].second;
    const ssize_t r = ::read(k.fd[s], buf, sizeof buf);
    if (r < 0 && errno == EINTR) continue;
    if (r <= 0) {
      ::close(k.fd[s]);
      k.fd[s] = -1;
      continue;
    }
    (s == 0 ? k.r.out : k.r.err).append(buf, static_cast<size_t>(r));
    if (s == 0 && k.on_line) {
      k.partial.append(buf, static_cast<size_t>(r));
      k.deliver(false);
    }
  }
  for (size_t i = 0; i < kids_.size(); ++i) {
    Child& k = *kids_[i];
    if (k.done || k.fd[0] >= 0 || k.fd[1] >= 0) continue;
    int st = 0;
    // Pipes closed: the child has ended (or closed them itself; then it is polled without blocking).
    const pid_t w = ::waitpid(k.pid, &st, pipeless ? WNOHANG : 0);
    if (w == 0 || (w < 0 && errno == EINTR)) continue;
    io::untrack_child(k.pid);
    k.r.status = w < 0 ? 1 : WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : 1;
    k.deliver(true);
    k.done = true;
    ended.push_back(i);
  }
  return ended;
}

size_t Pool::running() const {
  return static_cast<size_t>(std::count_if(kids_.begin(), kids_.end(), [](const auto& k) { return !k->done; }));
}
bool Pool::finished(size_t id) const { return kids_.at(id)->done; }
pid_t Pool::pid(size_t id) const { return kids_.at(id)->pid; }
const Result& Pool::result(size_t id) const { return kids_.at(id)->r; }

void Pool::terminate(size_t id, int sig) {
  const Child& k = *kids_.at(id);
  if (!k.done) ::kill(k.group ? -k.pid : k.pid, sig);
}
void Pool::terminate_all(int sig) {
  for (size_t i = 0; i < kids_.size(); ++i) terminate(i, sig);
}

Result run(const std::vector<std::string>& argv, const Options& opt) {
  Pool p;
  const size_t id = p.start(argv, opt);
  while (!p.finished(id)) p.poll(-1);
  return p.result(id);
}

// ---------------------------------------------------------------------------------------------------
namespace {
volatile sig_atomic_t g_signal = 0;
const int kSigs[3] = {SIGINT, SIGTERM, SIGHUP};

extern "C" void on_scope_signal(int sig) {
  g_signal = sig;
  io::signal_children(SIGTERM);
}
}  // namespace

InterruptScope::InterruptScope() {
  struct sigaction sa {};
  sa.sa_handler = on_scope_signal;
  sigemptyset(&sa.sa_mask);
  for (int i = 0; i < 3; ++i) ::sigaction(kSigs[i], &sa, &old_[i]);
}
void InterruptScope::restore() {
  if (!active_) return;
  for (int i = 0; i < 3; ++i) ::sigaction(kSigs[i], &old_[i], nullptr);
  active_ = false;
}
InterruptScope::~InterruptScope() { restore(); }

int interrupt_signal() { return g_signal; }
void clear_interrupt() { g_signal = 0; }

}  // namespace shadecore::proc
