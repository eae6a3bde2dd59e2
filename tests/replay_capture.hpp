// SPDX-License-Identifier: Apache-2.0
// Tests of `shadecore replay`: a capture of glxgears made on this machine (apitrace trace under xvfb-run, Mesa's
// software GL), once per build tree and reused; not made (with a note naming what is missing) without apitrace,
// mesa-utils (glxgears) and xvfb (xvfb-run), as the Slurm tests skip without slurm-wlm.
#pragma once

#include <snappy.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

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
