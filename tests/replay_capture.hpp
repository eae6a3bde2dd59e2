// SPDX-License-Identifier: Apache-2.0
// Tests of `shadecore replay`: a capture of glxgears made on this machine (apitrace trace under xvfb-run, Mesa's
// software GL), once per build tree and reused; not made (with a note naming what is missing) without apitrace,
// mesa-utils (glxgears) and xvfb (xvfb-run), as the Slurm tests skip without slurm-wlm.
#pragma once

#include <fcntl.h>
#include <snappy.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

namespace shadecore::test {

// The decompressed stream, written with the format's encodings.
struct Stream {
  std::string b;
  Stream& byte(unsigned v) {
    b += static_cast<char>(v);
    return *this;
  }
  Stream& uint(uint64_t v) {
    do {
      unsigned c = v & 0x7f;
      v >>= 7;
      if (v) c |= 0x80;
      b += static_cast<char>(c);
    } while (v);
    return *this;
  }
  Stream& str(const std::string& s) {
    uint(s.size());
    b += s;
    return *this;
  }
  Stream& f32(float f) {
    char c[4];
    std::memcpy(c, &f, 4);
    b.append(c, 4);
    return *this;
  }
  Stream& f64(double d) {
    char c[8];
    std::memcpy(c, &d, 8);
    b.append(c, 8);
    return *this;
  }
};

// A capture file: 'at' and the stream in Snappy chunks of at most `chunk` bytes.
inline std::string container(const std::string& stream, size_t chunk = 1 << 20) {
  std::string f = "at";
  for (size_t at = 0; at < stream.size(); at += chunk) {
    std::string c;
    snappy::Compress(stream.data() + at, std::min(chunk, stream.size() - at), &c);
    const uint32_t n = static_cast<uint32_t>(c.size());
    for (int k = 0; k < 4; ++k) f += static_cast<char>((n >> (8 * k)) & 0xff);
    f += c;
  }
  return f;
}

// A capture's stream built byte by byte: `frames` frames of one triangle each (fake glViewport 32x32, glClear,
// glBegin…); with `arrays` each frame also draws a quad from a vertex array, once directly and once from a list.
inline std::string tiny_stream(int frames, bool core_profile = false, bool arrays = false) {
  Stream s;
  s.uint(6).uint(6).str("");
  uint64_t no = 0;
  std::map<std::string, uint64_t> ids;
  auto call = [&](const std::string& name, const std::vector<std::function<void(Stream&)>>& args, bool fake = false) {
    s.byte(0).uint(0);
    auto it = ids.find(name);
    if (it == ids.end()) {
      const uint64_t id = ids.size();
      ids[name] = id;
      s.uint(id).str(name).uint(args.size());
      for (size_t k = 0; k < args.size(); ++k) s.str("a" + std::to_string(k));
    } else {
      s.uint(it->second);
    }
    for (size_t k = 0; k < args.size(); ++k) {
      s.byte(1).uint(k);
      args[k](s);
    }
    if (fake) s.byte(5).uint(1);
    s.byte(0);
    s.byte(1).uint(no++).byte(0);
  };
  auto u = [](uint64_t v) { return [v](Stream& t) { t.byte(4).uint(v); }; };
  auto f = [](float v) { return [v](Stream& t) { t.byte(5).f32(v); }; };
  if (core_profile)
    call("glXCreateContextAttribsARB", {u(1), u(2), u(0), u(1), [](Stream& t) {
           t.byte(0x0b).uint(6).byte(4).uint(0x2091).byte(4).uint(3).byte(4).uint(0x9126).byte(4).uint(1).byte(4).uint(0).byte(4).uint(0);
         }});
  call("glXMakeCurrent", {u(1), u(2), u(3)});
  call("glViewport", {u(0), u(0), u(32), u(32)}, true);
  call("glEnable", {u(0x0B71)});
  for (int k = 0; k < frames; ++k) {
    call("glClear", {u(0x4100)});
    call("glBegin", {u(4)});
    call("glVertex3f", {f(-1), f(-1), f(-0.5)});
    call("glVertex3f", {f(1), f(-1), f(-0.5)});
    call("glVertex3f", {f(0), f(1), f(-0.5)});
    call("glEnd", {});
    if (arrays) {
      const float q[12] = {-1, -1, -0.7f, 1, -1, -0.7f, 1, 1, -0.7f, -1, 1, -0.7f};
      auto blob = [&q](Stream& t) {
        t.byte(8).uint(sizeof q);
        t.b.append(reinterpret_cast<const char*>(q), sizeof q);
      };
      call("glEnableClientState", {u(0x8074)});
      call("glVertexPointer", {u(3), u(0x1406), u(0), blob});
      call("glNewList", {u(1), u(0x1301)});
      call("glDrawArrays", {u(7), u(0), u(4)});
      call("glEndList", {});
      call("glCallList", {u(1)});
    }
    call("glXSwapBuffers", {u(1), u(2)});
  }
  return s.b;
}
struct Capture {
  bool ok = false;
  std::string path, note;
};

inline bool on_path(const std::string& tool) {
  const char* p = std::getenv("PATH");
  std::string path = p ? p : "/usr/bin:/bin";
  size_t at = 0;
  while (at <= path.size()) {
    const size_t end = path.find(':', at);
    const std::string dir = path.substr(at, end == std::string::npos ? std::string::npos : end - at);
    if (!dir.empty() && ::access((dir + "/" + tool).c_str(), X_OK) == 0) return true;
    if (end == std::string::npos) break;
    at = end + 1;
  }
  return false;
}

// The tools replay's capture and --mesa need; "" when all are there, else the note.
inline std::string missing_capture_tools() {
  std::string miss;
  for (const char* t : {"apitrace", "glretrace", "glxgears", "xvfb-run"})
    if (!on_path(t)) miss += std::string(miss.empty() ? "" : ", ") + t;
  if (miss.empty()) return "";
  return "needs " + miss + " (Debian apitrace, mesa-utils, xvfb: scripts/setup.sh installs them)";
}

// glxgears for `seconds` at 300x300 (about 40 frames a second here), captured into DIR/glxgears.trace.
inline Capture glxgears_capture(int seconds = 3) {
  Capture c;
  c.note = missing_capture_tools();
  if (!c.note.empty()) return c;
  namespace fs = std::filesystem;
  const fs::path dir = fs::current_path() / "replay_captures";
  std::error_code ec;
  fs::create_directories(dir, ec);
  c.path = (dir / "glxgears.trace").string();
  // ctest runs the tests that use it at once: one of them captures, the others wait for it (a capture replaced
  // between `shadecore replay` and glretrace reading it made them compare two different frames)
  const int lock = ::open((dir / "capture.lock").c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644);
  if (lock < 0 || ::flock(lock, LOCK_EX) != 0) {
    if (lock >= 0) ::close(lock);
    c.note = "cannot lock " + (dir / "capture.lock").string();
    return c;
  }
  struct Unlock {
    int fd;
    ~Unlock() { ::close(fd); }
  } unlock{lock};
  if (fs::exists(c.path) && fs::file_size(c.path) > 0) {
    c.ok = true;
    return c;
  }
  const std::string tmp = c.path + ".tmp" + std::to_string(::getpid());
  const std::string cmd = "LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s '-screen 0 640x480x24' apitrace trace -o '" + tmp +
                          "' timeout " + std::to_string(seconds) + " glxgears -geometry 300x300 >/dev/null 2>&1";
  (void)std::system(cmd.c_str());  // timeout ends glxgears with status 124
  if (!fs::exists(tmp) || fs::file_size(tmp) == 0) {
    c.note = "apitrace trace of glxgears under xvfb-run wrote no capture";
    return c;
  }
  fs::rename(tmp, c.path, ec);
  c.ok = !ec;
  if (!c.ok) c.note = "cannot move the capture into place: " + ec.message();
  return c;
}

}  // namespace shadecore::test
