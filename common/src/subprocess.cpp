// SPDX-License-Identifier: Apache-2.0
// shadecore — the subprocess runner (see shadecore/common/subprocess.hpp).
#include "shadecore/common/subprocess.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

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

Result run(const std::vector<std::string>& argv, const Options& opt) {
  if (argv.empty()) throw std::invalid_argument("proc::run: empty argv");
  int outp[2] = {-1, -1}, errp[2] = {-1, -1};
  if ((opt.capture_stdout && ::pipe2(outp, O_CLOEXEC) != 0) || (opt.capture_stderr && ::pipe2(errp, O_CLOEXEC) != 0))
    throw std::runtime_error(argv[0] + ": pipe: " + std::strerror(errno));
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  sigset_t all, old;
  sigfillset(&all);
  ::pthread_sigmask(SIG_BLOCK, &all, &old);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::signal(SIGINT, SIG_IGN);
    ::signal(SIGTERM, SIG_DFL);
    ::signal(SIGHUP, SIG_DFL);
    ::signal(SIGPIPE, SIG_DFL);
    ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    if (opt.capture_stdout) ::dup2(outp[1], 1);
    if (opt.capture_stderr) ::dup2(errp[1], 2);
    if (!opt.cwd.empty() && ::chdir(opt.cwd.c_str()) != 0) ::_exit(127);
    ::execvp(args[0], args.data());
    const std::string m = "cannot run " + argv[0] + ": " + std::strerror(errno) + "\n";
    ssize_t r = ::write(2, m.data(), m.size());
    (void)r;
    ::_exit(127);
  }
  if (pid > 0) io::track_child(pid);
  ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
  if (outp[1] >= 0) ::close(outp[1]);
  if (errp[1] >= 0) ::close(errp[1]);
  if (pid < 0) {
    if (outp[0] >= 0) ::close(outp[0]);
    if (errp[0] >= 0) ::close(errp[0]);
    throw std::runtime_error(argv[0] + ": fork: " + std::strerror(errno));
  }
  Result r;
  // Both pipes drained together (a child filling one while we block on the other would deadlock).
  pollfd fds[2] = {{outp[0], POLLIN, 0}, {errp[0], POLLIN, 0}};
  std::string* dst[2] = {&r.out, &r.err};
  int open_fds = (outp[0] >= 0) + (errp[0] >= 0);
  char buf[65536];
  while (open_fds > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t k = ::read(fds[i].fd, buf, sizeof buf);
      if (k > 0) {
        dst[i]->append(buf, static_cast<size_t>(k));
      } else if (k == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
  }
  io::untrack_child(pid);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : WIFSIGNALED(st) ? 128 + WTERMSIG(st) : 1;
  return r;
}

}  // namespace shadecore::proc
