// SPDX-License-Identifier: Apache-2.0
// shadecore — argument checks shared by the `shadecore` CLI and the simulator executables (header-only,
// CLI11 validators). Every bad value is rejected with a one-line message; nothing wraps, nothing falls back
// to a default silently.
#pragma once

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "shadecore/format.hpp"

namespace shadecore::cliargs {

// Worker threads and simulator shards: 0 = one per core, at most kMaxParallel (every subcommand).
inline constexpr int kMaxParallel = 64;
inline int resolve_parallel(int k) {
  if (k > 0) return std::min(k, kMaxParallel);
  const int hw = static_cast<int>(std::thread::hardware_concurrency());
  return std::clamp(hw, 1, kMaxParallel);
}

// Strict unsigned decimal: digits only (no sign, no blanks), no overflow.
inline bool parse_u64(const std::string& s, uint64_t& v) {
  if (s.empty() || s[0] < '0' || s[0] > '9') return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// Strict signed decimal (optional leading '-'), no overflow.
inline bool parse_i64(const std::string& s, int64_t& v) {
  if (s.empty()) return false;
  const size_t digits = s[0] == '-' ? 1 : 0;
  if (s.size() == digits || s[digits] < '0' || s[digits] > '9') return false;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

// An integer in [lo, hi] read by parse (parse_u64 or parse_i64); `name` is the type shown in --help.
template <class T>
CLI::Validator IntegerIn(bool (*parse)(const std::string&, T&), T lo, T hi, const char* name) {
  return CLI::Validator(
      [parse, lo, hi](std::string& s) -> std::string {
        T v = 0;
        if (!parse(s, v) || v < lo || v > hi)
          return "'" + s + "' is not an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
        return {};
      },
      name);
}

// An unsigned integer in [lo, hi] (CLI11 itself would wrap "-5" to 2^64 - 5).
inline CLI::Validator UInt(uint64_t lo, uint64_t hi = std::numeric_limits<uint64_t>::max()) {
  return IntegerIn<uint64_t>(parse_u64, lo, hi, "UINT");
}

// A signed integer in [lo, hi].
inline CLI::Validator Int(int64_t lo, int64_t hi) { return IntegerIn<int64_t>(parse_i64, lo, hi, "INT"); }

// -1 (none) or a count >= 0: the --reset-at rule.
inline CLI::Validator ResetAt() {
  return CLI::Validator(
      [](std::string& s) -> std::string {
        int64_t v = 0;
        if (!parse_i64(s, v) || v < -1) return "'" + s + "' is neither -1 (no reset) nor a count >= 0";
        return {};
      },
      "K");
}

// A probability: a finite number in [0, 1) (allow_one: [0, 1]). NaN, inf and hex floats are rejected.
inline CLI::Validator Probability(bool allow_one) {
  return CLI::Validator(
      [allow_one](std::string& s) -> std::string {
        const std::string range = allow_one ? "[0, 1]" : "[0, 1)";
        errno = 0;
        char* end = nullptr;
        const double v = s.empty() ? 0.0 : std::strtod(s.c_str(), &end);
        const bool hex = s.find_first_of("xX") != std::string::npos;
        if (s.empty() || hex || end != s.c_str() + s.size() || !std::isfinite(v) || v < 0.0 ||
            (allow_one ? v > 1.0 : v >= 1.0))
          return "'" + s + "' is not a probability in " + range +
                 (!allow_one && end == s.c_str() + s.size() && v == 1.0 ? " (1 would stall forever)" : "");
        return {};
      },
      "P");
}

// Names and paths given explicitly must not be empty (an empty --json would silently write nothing,
// an empty --config would silently mean the default).
inline CLI::Validator NonEmpty(const char* what = "value") {
  return CLI::Validator(
      [what](std::string& s) -> std::string { return s.empty() ? std::string("empty ") + what : std::string(); },
      "");
}

// "N" or "LO..HI", each within [16, 1024]: the exponent range of every command.
// Malformed text, a value out of range and LO > HI each get their own one-line message.
inline std::pair<int, int> parse_n_range(const std::string& text) {
  const auto bad = [&] {
    return std::invalid_argument("malformed range '" + text + "' (expected N or LO..HI, e.g. 16..1024)");
  };
  const auto trim = [](std::string s) {
    const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
    return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
  };
  const auto dots = text.find("..");
  const std::string a = trim(text.substr(0, dots)), b = dots == std::string::npos ? a : trim(text.substr(dots + 2));
  // First the syntax of both ends (digits, optional '-'), then their range.
  const auto syntax_ok = [](const std::string& s) {
    const size_t d = !s.empty() && s[0] == '-' ? 1 : 0;
    return s.size() > d && s.find_first_not_of("0123456789", d) == std::string::npos;
  };
  if (!syntax_ok(a) || !syntax_ok(b) || (dots != std::string::npos && b.find("..") != std::string::npos)) throw bad();
  const auto value = [](const std::string& s) -> long long {
    int64_t v = 0;
    if (!parse_i64(s, v))  // digits only but too long for 64 bits
      throw std::invalid_argument("specular exponent n = " + s + " out of range [" + std::to_string(kNMin) + ", " +
                                  std::to_string(kNMax) + "]");
    validate_n(v);
    return v;
  };
  const long long lo = value(a), hi = value(b);
  if (lo > hi) throw std::invalid_argument("empty range '" + text + "' (LO > HI)");
  return {static_cast<int>(lo), static_cast<int>(hi)};
}

}  // namespace shadecore::cliargs
