// SPDX-License-Identifier: Apache-2.0
// shadecore — progress bar on stderr for long runs (header-only; the CLI and the simulators).
// Drawn only when enabled (by default: stderr is a terminal), from its own thread at once and every 200 ms:
//   [##########                    ]  33.0%  4.1 s, ETA 8 s
// and erased when the run ends, so stdout and the final stderr lines stay clean.
#pragma once

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>
#include <thread>

#include "shadecore/common/output_files.hpp"

namespace shadecore::io {

// --progress / --no-progress / neither (auto: only when stderr is a terminal).
inline bool progress_wanted(bool force_on, bool force_off) {
  if (force_off) return false;
  return force_on || ::isatty(STDERR_FILENO);
}

inline std::string eta_text(double seconds) {
  if (seconds < 0) return "--";
  char buf[32];
  if (seconds < 60) std::snprintf(buf, sizeof buf, "%.0f s", seconds);
  else if (seconds < 3600) std::snprintf(buf, sizeof buf, "%d min %02d s", int(seconds) / 60, int(seconds) % 60);
  else std::snprintf(buf, sizeof buf, "%d h %02d min", int(seconds) / 3600, (int(seconds) / 60) % 60);
  return buf;
}

class Progress {
 public:
  Progress(uint64_t total, bool enabled, std::string label = {}) : total_(total), label_(std::move(label)) {
    if (enabled) {
      set_progress_line(true);
      th_ = std::thread([this] { loop(); });
    }
  }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  ~Progress() { stop(); }

  void add(uint64_t k) { done_.fetch_add(k, std::memory_order_relaxed); }
  void set(uint64_t v) { done_.store(v, std::memory_order_relaxed); }
  void stop() {
    if (!th_.joinable()) return;
    {
      std::lock_guard<std::mutex> lk(mu_);
      stopping_ = true;
    }
    cv_.notify_all();
    th_.join();
    std::fputs("\r\033[K", stderr);
    std::fflush(stderr);
    set_progress_line(false);
  }

 private:
  void loop() {
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_lock<std::mutex> lk(mu_);
    // Drawn at once (so even a short run shows that it is working), then every 200 ms.
    do {
      const uint64_t d = done_.load(std::memory_order_relaxed);
      const double frac = total_ ? std::min(1.0, double(d) / double(total_)) : 0.0;
      const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const double eta = frac > 0.005 && el > 0.5 ? el * (1 - frac) / frac : -1;
      const int w = 30, fill = static_cast<int>(frac * w);
      std::fprintf(stderr, "\r%s%s[%s%s] %5.1f%%  %.1f s, ETA %s\033[K", label_.c_str(), label_.empty() ? "" : " ",
                   std::string(fill, '#').c_str(), std::string(w - fill, ' ').c_str(), 100 * frac, el,
                   eta_text(eta).c_str());
      std::fflush(stderr);
    } while (!cv_.wait_for(lk, std::chrono::milliseconds(200), [this] { return stopping_; }));
  }

  uint64_t total_;
  std::string label_;
  std::atomic<uint64_t> done_{0};
  std::mutex mu_;
  std::condition_variable cv_;
  bool stopping_ = false;
  std::thread th_;
};

}  // namespace shadecore::io
