// SPDX-License-Identifier: Apache-2.0
// shadecore — output files are the user's (library shadecore_common; used by the `shadecore` CLI and the simulators).
//
// Rules (docs/cli.md):
//   * every output path is checked before the run: an empty path, a missing directory, a directory, a
//     socket, a place where no file can be created (/proc, /sys, a read-only file system) is a one-line
//     error and nothing runs;
//   * a symlink is followed: its target is written, the link stays;
//   * a character/block device or a FIFO is written in place (no temporary file, no rename); it is never
//     replaced by a regular file;
//   * a regular file is written to a temporary file in the same directory and renamed over the target at
//     the end (mode bits of an existing target are kept);
//   * two outputs naming the same file (after following symlinks) is an error;
//   * all outputs of a run are committed together at the end: if anything fails before, or the run is
//     interrupted (SIGINT, SIGTERM, SIGHUP), no output is left behind (temporary files are removed,
//     directories the run created are removed again).
#pragma once

#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/statfs.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace shadecore::io {

// ---------------------------------------------------------------------------------------------------
// Interrupt cleanup (common/src/output_files.cpp): paths and child processes registered here are removed /
// terminated by the signal handler (async-signal-safe: kill, waitpid, unlink, rmdir, write, _exit only).

// Installs the handler for SIGINT, SIGTERM and SIGHUP (unless the signal is inherited as ignored).
// (SIGPIPE keeps its default, so `shadecore ... | head` ends quietly; a FIFO output whose reader went
// away is turned into a write error by write_stream(), which blocks SIGPIPE while it writes.)
void install_interrupt_cleanup(const char* prog);
// Registers a path to remove on a signal (kind 1 file, 2 directory); returns its slot (−1: none free).
int track(const std::string& path, int kind);
void untrack(int slot);
// Registers a child process to terminate (SIGTERM, then wait) on a signal; group: it leads its own process
// group, and the whole group is sent the signal.
void track_child(pid_t pid, bool group = false);
void untrack_child(pid_t pid);
// Sends sig to every registered child (their groups where they lead one); async-signal-safe.
void signal_children(int sig);
// A progress line is drawn on stderr (the handler clears it before its message).
void set_progress_line(bool on);

// ---------------------------------------------------------------------------------------------------
inline std::runtime_error cannot_write(const std::string& path, const std::string& why) {
  return std::runtime_error("cannot write " + path + ": " + why);
}

inline std::string parent_of(const std::string& p) {
  const std::filesystem::path x(p);
  return x.has_parent_path() ? x.parent_path().string() : std::string(".");
}

inline unsigned next_serial() {
  static std::atomic<unsigned> k{0};
  return ++k;
}

inline std::string temp_name(const std::string& dir, const char* what) {
  return dir + "/.shadecore." + what + "." + std::to_string(::getpid()) + "." + std::to_string(next_serial());
}

// A file can be created in `dir` (this catches /proc, /sys, read-only file systems and permissions,
// even for root, before the run).
// A kernel file system (/proc, /sys, cgroups, debugfs...) holds no files of ours, whatever errno says.
inline const char* kernel_fs(const std::string& dir) {
  struct statfs fs {};
  if (::statfs(dir.c_str(), &fs) != 0) return nullptr;
  switch (static_cast<unsigned long>(fs.f_type)) {
    case 0x9fa0UL: return "/proc";
    case 0x62656572UL: return "/sys";
    case 0x27e0ebUL: case 0x63677270UL: return "a cgroup file system";
    case 0x64626720UL: return "debugfs";
    case 0x74726163UL: return "tracefs";
    case 0x42494e4dUL: return "binfmt_misc";
    case 0xcafe4a11UL: return "bpffs";
    case 0x73636673UL: return "securityfs";
    default: return nullptr;
  }
}

inline void probe_create(const std::string& dir, const std::string& shown) {
  const std::string t = temp_name(dir, "probe");
  const int fd = ::open(t.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int e = errno;
    if (const char* k = kernel_fs(dir))
      throw cannot_write(shown, std::string("is in ") + k + ", a kernel file system where no output files can be created");
    throw cannot_write(shown, std::strerror(e));
  }
  ::close(fd);
  ::unlink(t.c_str());
}

inline void write_all(int fd, const std::string& data, const std::string& shown) {
  const char* p = data.data();
  size_t left = data.size();
  while (left > 0) {
    const ssize_t k = ::write(fd, p, left);
    if (k < 0) {
      if (errno == EINTR) continue;
      throw cannot_write(shown, std::strerror(errno));
    }
    p += k;
    left -= static_cast<size_t>(k);
  }
}

// The identity of a path for "two outputs name one file" and "an output names an input": device and
// inode when it exists, else the real path of its nearest existing ancestor plus the rest of the name.
inline std::string path_key(const std::string& p) {
  struct stat st {};
  if (::stat(p.c_str(), &st) == 0) return std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
  std::filesystem::path rest, cur = std::filesystem::absolute(p).lexically_normal();
  while (!cur.empty() && cur.has_relative_path() && ::stat(cur.c_str(), &st) != 0) {
    rest = rest.empty() ? cur.filename() : cur.filename() / rest;
    cur = cur.parent_path();
  }
  char buf[PATH_MAX];
  const std::string base = ::realpath(cur.c_str(), buf) ? std::string(buf) : cur.string();
  return (std::filesystem::path(base) / rest).lexically_normal().string();
}

// Follows a chain of symbolic links whose last target does not exist: the name to create.
inline std::string follow_dangling(const std::string& shown) {
  std::string p = shown;
  for (int depth = 0;; ++depth) {
    if (depth > 40) throw cannot_write(shown, "too many levels of symbolic links");
    struct stat lst {};
    if (::lstat(p.c_str(), &lst) != 0) {
      if (errno == ENOENT) return p;
      throw cannot_write(shown, std::strerror(errno));
    }
    if (!S_ISLNK(lst.st_mode)) return p;
    char buf[PATH_MAX];
    const ssize_t k = ::readlink(p.c_str(), buf, sizeof buf - 1);
    if (k < 0) throw cannot_write(shown, std::strerror(errno));
    const std::string link(buf, static_cast<size_t>(k));
    p = !link.empty() && link[0] == '/' ? link : parent_of(p) + "/" + link;
  }
}

// Where the bytes of one output go.
struct Target {
  std::string shown;   // the path as the user gave it
  std::string path;    // after following symlinks
  bool exists = false;
  bool stream = false; // character/block device or FIFO: written in place
  bool chr = false;    // character device (/dev/null, a terminal): may be named by several outputs
  mode_t mode = 0;
  std::string key;     // identity for "two outputs name one file"
};

// Checks one output file now. allow_stream = false for outputs that need a seekable regular file.
inline Target resolve_output(const std::string& shown, bool allow_stream = true) {
  namespace fs = std::filesystem;
  if (shown.empty()) throw std::invalid_argument("empty output path");
  Target t;
  t.shown = shown;
  struct stat st {};
  if (::stat(shown.c_str(), &st) == 0) {
    t.exists = true;
    t.mode = st.st_mode;
    t.key = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    if (S_ISDIR(st.st_mode)) throw cannot_write(shown, "is a directory");
    if (S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) || S_ISFIFO(st.st_mode)) {
      if (!allow_stream) throw cannot_write(shown, "is a device or FIFO; this output must be a regular file");
      if (::access(shown.c_str(), W_OK) != 0) throw cannot_write(shown, std::strerror(errno));
      t.stream = true;
      t.chr = S_ISCHR(st.st_mode);
      t.path = shown;  // opened in place (through any symlink, including /dev/stdout)
      return t;
    }
    if (!S_ISREG(st.st_mode)) throw cannot_write(shown, "is not a regular file, device or FIFO");
    char buf[PATH_MAX];
    if (!::realpath(shown.c_str(), buf)) throw cannot_write(shown, std::strerror(errno));
    t.path = buf;
    if (::access(t.path.c_str(), W_OK) != 0) throw cannot_write(shown, std::strerror(errno));
    probe_create(parent_of(t.path), shown);
    return t;
  }
  if (errno != ENOENT) throw cannot_write(shown, std::strerror(errno));
  // A new file, possibly behind a dangling symlink: follow the links to the name to create.
  const std::string p = follow_dangling(shown);
  const fs::path fp(p);
  const std::string name = fp.filename().string();
  if (name.empty() || name == "." || name == "..") throw cannot_write(shown, "not a file name");
  const std::string dir = parent_of(p);
  struct stat dst {};
  if (::stat(dir.c_str(), &dst) != 0 || !S_ISDIR(dst.st_mode)) throw cannot_write(shown, "no directory " + dir);
  probe_create(dir, shown);
  char buf[PATH_MAX];
  if (!::realpath(dir.c_str(), buf)) throw cannot_write(shown, std::strerror(errno));
  t.path = std::string(buf) + "/" + name;
  t.key = t.path;
  return t;
}

// ---------------------------------------------------------------------------------------------------
// All outputs of one run: declared (and checked) before the run, committed together after it.
class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet() { rollback(); }

  // A file output (`option` names it in messages: "--json"). Checked now.
  int file(const std::string& option, const std::string& path, bool allow_stream = true) {
    if (path.empty()) throw std::invalid_argument(option + ": empty path");
    Out o;
    o.option = option;
    o.target = resolve_output(path, allow_stream);
    add_key(o.target, option);
    outs_.push_back(std::move(o));
    return static_cast<int>(outs_.size()) - 1;
  }

  // A directory output (--plots) with the names of every file the run will put into it. Checked now;
  // the directory itself is created only at stage() and removed again if the run fails.
  int dir(const std::string& option, const std::string& path, const std::vector<std::string>& names) {
    if (path.empty()) throw std::invalid_argument(option + ": empty path");
    Out o;
    o.option = option;
    o.is_dir = true;
    o.names = names;
    struct stat st {};
    // A dangling symlink is followed: its target directory is created (the link stays).
    o.dir = ::stat(path.c_str(), &st) == 0 ? path : follow_dangling(path);
    o.shown_dir = path;
    if (::stat(o.dir.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) throw std::runtime_error("cannot write to directory " + path + ": not a directory");
      probe_create(o.dir, path + "/");
      for (const auto& n : names) o.members.push_back(resolve_output(o.dir + "/" + n));
    } else {
      if (errno != ENOENT) throw std::runtime_error("cannot create directory " + path + ": " + std::strerror(errno));
      // The nearest existing ancestor must be a directory where we can create one.
      std::string anc = o.dir;
      for (;;) {
        anc = parent_of(anc);
        if (::stat(anc.c_str(), &st) == 0) break;
        if (errno != ENOENT) throw std::runtime_error("cannot create directory " + path + ": " + std::strerror(errno));
      }
      if (!S_ISDIR(st.st_mode)) throw std::runtime_error("cannot create directory " + path + ": " + anc + " is not a directory");
      const std::string t = temp_name(anc, "probe");
      if (::mkdir(t.c_str(), 0700) != 0) {
        const int e = errno;
        if (const char* k = kernel_fs(anc))
          throw std::runtime_error("cannot create directory " + path + ": " + anc + " is in " + k +
                                   ", a kernel file system where no output can be created");
        throw std::runtime_error("cannot create directory " + path + ": " + std::strerror(e));
      }
      ::rmdir(t.c_str());
      for (const auto& n : names) {
        Target m;
        m.shown = path + "/" + n;
        m.path = o.dir + "/" + n;
        m.key = path_key(m.path);
        o.members.push_back(m);
      }
    }
    // The directory itself and the missing parents the run creates: no file output may name them.
    for (std::string d = o.dir;;) {
      Target self;
      self.shown = d == o.dir ? path : d;
      self.key = path_key(d);
      add_key(self, option);
      const std::string up = parent_of(d);
      if (up == d || ::stat(up.c_str(), &st) == 0) break;
      d = up;
    }
    for (const auto& m : o.members) add_key(m, option);
    outs_.push_back(std::move(o));
    return static_cast<int>(outs_.size()) - 1;
  }

  // An input of the run (the scene, a mesh it loads): no output may name it. `what` says what it is
  // ("the scene file"). Throws std::invalid_argument before anything runs.
  void check_input(const std::string& path, const std::string& what) const {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return;  // not there: nothing to overwrite
    const std::string key = std::to_string(st.st_dev) + ":" + std::to_string(st.st_ino);
    for (const auto& k : keys_)
      if (k.key == key && !S_ISCHR(st.st_mode))
        throw std::invalid_argument(k.option + " " + k.shown + " is " + what + " " + path +
                                    ": an output must not overwrite an input");
  }

  // A file inside directory output `id` that an earlier run wrote and this one does not (render's
  // manifest): removed at commit(), after everything else is in place, if it is still a regular file.
  void remove_at_commit(int id, const std::string& name) { outs_.at(id).stale.push_back(name); }

  // The content of a file output, written at commit().
  void set(int id, std::string content) {
    outs_.at(id).content = std::move(content);
    outs_.at(id).has_content = true;
  }

  // For a file output written by another program or library (a simulator's waveform): a fresh path
  // beside the target for it to write; installed at commit(), removed on failure. `side_suffixes`: side
  // files the writer keeps next to it while it runs (the FST writer's ".hier"), removed on a signal.
  std::string produce_path(int id, const std::vector<std::string>& side_suffixes = {}) {
    Out& o = outs_.at(id);
    if (o.target.stream) throw cannot_write(o.target.shown, "must be a regular file");
    o.produced = temp_name(parent_of(o.target.path), "part");
    o.slots.push_back(track(o.produced, 1));
    for (const auto& sfx : side_suffixes) {
      o.side.push_back(o.produced + sfx);
      o.slots.push_back(track(o.produced + sfx, 1));
    }
    return o.produced;
  }

  // Creates the directory (and missing parents) and a staging directory inside it; the files named at
  // dir() are to be written into the staging directory, and are moved into place at commit().
  std::string stage(int id) {
    Out& o = outs_.at(id);
    std::vector<std::string> missing;
    for (std::string d = o.dir; !d.empty();) {
      struct stat st {};
      if (::stat(d.c_str(), &st) == 0) break;
      missing.push_back(d);
      const std::string up = parent_of(d);
      if (up == d) break;
      d = up;
    }
    for (auto it = missing.rbegin(); it != missing.rend(); ++it) {
      if (::mkdir(it->c_str(), 0777) != 0 && errno != EEXIST)
        throw std::runtime_error("cannot create directory " + *it + ": " + std::strerror(errno));
      created_.push_back({*it, track(*it, 2)});
    }
    o.staging = temp_name(o.dir, "stage");
    if (::mkdir(o.staging.c_str(), 0700) != 0)
      throw std::runtime_error("cannot write to directory " + o.dir + ": " + std::strerror(errno));
    o.slots.push_back(track(o.staging, 2));
    for (const auto& n : o.names) o.slots.push_back(track(o.staging + "/" + n, 1));
    return o.staging;
  }

  // Writes everything, then moves it into place. Throws (and leaves nothing) on any failure.
  void commit() {
    try {
      for (Out& o : outs_) {
        if (o.is_dir || o.target.stream || !o.has_content) continue;
        o.temp = temp_name(parent_of(o.target.path), "tmp");
        o.slots.push_back(track(o.temp, 1));
        const int fd = ::open(o.temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd < 0) throw cannot_write(o.target.shown, std::strerror(errno));
        try {
          write_all(fd, o.content, o.target.shown);
          if (o.target.exists) ::fchmod(fd, o.target.mode & 07777);
        } catch (...) {
          ::close(fd);
          throw;
        }
        if (::close(fd) != 0) throw cannot_write(o.target.shown, std::strerror(errno));
      }
      for (Out& o : outs_) {
        if (!o.produced.empty()) {
          struct stat st {};
          if (::stat(o.produced.c_str(), &st) != 0 || st.st_size == 0)
            throw cannot_write(o.target.shown, "nothing was written");
        }
        if (o.is_dir && !o.staging.empty())
          for (const auto& n : o.names)
            if (::access((o.staging + "/" + n).c_str(), F_OK) != 0)
              throw std::runtime_error("cannot write " + o.dir + "/" + n + ": it was not produced");
      }
      // Devices and FIFOs first (a full disk behind /dev/full, a reader that went away): they are the
      // outputs that can still fail, so they fail before any regular file has been replaced.
      for (Out& o : outs_) {
        if (!o.is_dir && o.target.stream && o.has_content) write_stream(o.target, o.content);
        if (o.is_dir && !o.staging.empty())
          for (size_t i = 0; i < o.names.size(); ++i)
            if (o.members[i].stream) install(o.staging + "/" + o.names[i], o.members[i]);
      }
      for (Out& o : outs_) {
        if (!o.temp.empty()) install(o.temp, o.target);
        if (!o.produced.empty()) install(o.produced, o.target);
        if (o.is_dir && !o.staging.empty()) {
          for (size_t i = 0; i < o.names.size(); ++i)
            if (!o.members[i].stream) install(o.staging + "/" + o.names[i], o.members[i]);
          ::rmdir(o.staging.c_str());
        }
      }
      for (Out& o : outs_)
        for (const auto& n : o.stale) {
          const std::string p = o.dir + "/" + n;
          struct stat lst {};
          if (::lstat(p.c_str(), &lst) == 0 && S_ISREG(lst.st_mode)) ::unlink(p.c_str());
        }
    } catch (...) {
      rollback();
      throw;
    }
    for (Out& o : outs_)
      for (int s : o.slots) untrack(s);
    for (auto& c : created_) untrack(c.second);
    outs_.clear();
    created_.clear();
  }

  // Removes whatever this run has put on disk (also done by the destructor when commit() did not run).
  void rollback() {
    for (Out& o : outs_) {
      if (!o.temp.empty()) ::unlink(o.temp.c_str());
      if (!o.produced.empty()) ::unlink(o.produced.c_str());
      for (const auto& p : o.side) ::unlink(p.c_str());
      if (!o.staging.empty()) {
        for (const auto& n : o.names) ::unlink((o.staging + "/" + n).c_str());
        ::rmdir(o.staging.c_str());
      }
      for (int s : o.slots) untrack(s);
      o.slots.clear();
    }
    for (auto it = created_.rbegin(); it != created_.rend(); ++it) {
      ::rmdir(it->first.c_str());
      untrack(it->second);
    }
    outs_.clear();
    created_.clear();
  }

 private:
  struct Out {
    std::string option;
    Target target;
    bool is_dir = false;
    std::string dir, shown_dir, staging;
    std::vector<std::string> names, stale;
    std::vector<Target> members;
    std::string content;
    bool has_content = false;
    std::string temp, produced;
    std::vector<std::string> side;
    std::vector<int> slots;
  };

  void add_key(const Target& t, const std::string& option) {
    for (const auto& k : keys_)
      if (k.key == t.key && !(k.chr && t.chr))
        throw std::invalid_argument(k.option + " and " + option + " name the same file " + t.shown);
    keys_.push_back({t.key, option, t.shown, t.chr});
  }

  static void write_stream(const Target& t, const std::string& content) {
    const int fd = ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) throw cannot_write(t.shown, std::strerror(errno));
    // A FIFO without a reader raises SIGPIPE: block it here, so the write fails with EPIPE instead,
    // and take the pending signal away before unblocking.
    sigset_t pipe_set, old;
    sigemptyset(&pipe_set);
    sigaddset(&pipe_set, SIGPIPE);
    ::pthread_sigmask(SIG_BLOCK, &pipe_set, &old);
    std::string error;
    try {
      write_all(fd, content, t.shown);
    } catch (const std::exception& e) {
      error = e.what();
    }
    ::close(fd);
    if (!sigismember(&old, SIGPIPE)) {
      const timespec zero{0, 0};
      while (::sigtimedwait(&pipe_set, nullptr, &zero) > 0) {
      }
      ::pthread_sigmask(SIG_SETMASK, &old, nullptr);
    }
    if (!error.empty()) throw std::runtime_error(error);
  }

  // Moves a finished file onto its target: rename for a regular file (through a temporary beside the
  // target if it lives on another file system), a copy into a device or FIFO.
  static void install(const std::string& from, const Target& t) {
    if (t.stream) {
      std::FILE* f = std::fopen(from.c_str(), "rb");
      if (!f) throw cannot_write(t.shown, std::strerror(errno));
      std::string data;
      char buf[65536];
      size_t k;
      while ((k = std::fread(buf, 1, sizeof buf, f)) > 0) data.append(buf, k);
      std::fclose(f);
      write_stream(t, data);
      ::unlink(from.c_str());
      return;
    }
    if (::rename(from.c_str(), t.path.c_str()) == 0) return;
    if (errno != EXDEV) throw cannot_write(t.shown, std::strerror(errno));
    std::FILE* in = std::fopen(from.c_str(), "rb");
    if (!in) throw cannot_write(t.shown, std::strerror(errno));
    const std::string tmp = temp_name(parent_of(t.path), "tmp");
    const int slot = track(tmp, 1);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    bool ok = fd >= 0;
    char buf[65536];
    size_t k;
    while (ok && (k = std::fread(buf, 1, sizeof buf, in)) > 0) ok = ::write(fd, buf, k) == static_cast<ssize_t>(k);
    std::fclose(in);
    if (fd >= 0) {
      if (t.exists) ::fchmod(fd, t.mode & 07777);
      ok = (::close(fd) == 0) && ok;
    }
    if (!ok || ::rename(tmp.c_str(), t.path.c_str()) != 0) {
      const int e = errno;
      ::unlink(tmp.c_str());
      untrack(slot);
      throw cannot_write(t.shown, std::strerror(e));
    }
    untrack(slot);
    ::unlink(from.c_str());
  }

  struct Key {
    std::string key, option, shown;
    bool chr;
  };
  std::vector<Out> outs_;
  std::vector<Key> keys_;
  std::vector<std::pair<std::string, int>> created_;
};

}  // namespace shadecore::io
