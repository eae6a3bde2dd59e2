// SPDX-License-Identifier: Apache-2.0
// shadecore sim — the drivers' reset schedule (tb_driver.hpp, tb_light_driver.hpp): rst_ni low for
// `reset_cycles` cycles at the start and once more, mid-stream, when `reset_at` fragments have been
// accepted (reset_at < 0: never).
#pragma once

#include <cstdint>

namespace shadecore::sim {

class ResetPlan {
 public:
  ResetPlan(int64_t reset_at, int reset_cycles) : reset_at_(reset_at), reset_cycles_(reset_cycles), left_(reset_cycles) {}

  // rst_ni for the coming edge, `accepted` fragments taken so far: counts the current reset down and
  // starts the mid-stream one.
  bool next(uint64_t accepted) {
    if (left_ > 0) --left_;
    if (left_ == 0 && !mid_done_ && reset_at_ >= 0 && accepted >= static_cast<uint64_t>(reset_at_)) {
      left_ = reset_cycles_;
      mid_done_ = true;
      ++resets_;
    }
    return left_ == 0;
  }
  [[nodiscard]] int64_t reset_at() const { return reset_at_; }
  [[nodiscard]] uint64_t resets() const { return resets_; }

 private:
  const int64_t reset_at_;
  const int reset_cycles_;
  int left_;
  bool mid_done_ = false;
  uint64_t resets_ = 0;
};

}  // namespace shadecore::sim
