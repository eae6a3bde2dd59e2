// SPDX-License-Identifier: Apache-2.0
// shadecore — fixed-point formats of the specular unit (see docs/spec.md §2).
//
// One Format describes every width of the per-fragment datapath:
//   cos θ input   : signed two's complement, frac+2 bits, 1.0 == 2^frac
//   squaring chain: unsigned, W = frac+guard fraction bits (value in [0, 1])
//   output        : unsigned, frac+1 bits, 1.0 == 2^frac
// The named configurations (narrow/default/wide) come from config/configs.json through the
// generated header shadecore/configs.hpp; the RTL gets the same numbers as Verilog parameters.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>

#include "shadecore/limits.hpp"

namespace shadecore {

// The legal ranges come from config/configs.json "limits" (generated shadecore/limits.hpp), the same
// numbers the RTL's elaboration checks state (ctest rtl.limits_agree).
inline constexpr int kFracMin = limits::kFracMin;
inline constexpr int kFracMax = limits::kFracMax;
inline constexpr int kGuardMin = limits::kGuardMin;  // base = 1 - (n/16)(1-c) has frac+4 fraction bits: exact when guard >= 4
inline constexpr int kGuardMax = limits::kGuardMax;
inline constexpr int kWorkMax = limits::kWorkMax;    // frac+guard <= 31 keeps every squaring product within 64 bits
inline constexpr int kNMin = 16;
inline constexpr int kNMax = 1024;
inline constexpr int kNBits = 11;  // n in [16, 1024] as an unsigned integer; n/16 is n with 4 implied fraction bits

struct Format {
  int frac = 16;  // F: fraction bits of cos θ and of the output
  int guard = 5;  // G: extra fraction bits carried through the four squarings

  [[nodiscard]] constexpr int work() const { return frac + guard; }        // W
  [[nodiscard]] constexpr int in_bits() const { return frac + 2; }         // signed input word
  [[nodiscard]] constexpr int out_bits() const { return frac + 1; }        // unsigned output word
  [[nodiscard]] constexpr int64_t one() const { return int64_t{1} << frac; }  // code of 1.0
  [[nodiscard]] constexpr int64_t in_min() const { return -(int64_t{1} << (frac + 1)); }
  [[nodiscard]] constexpr int64_t in_max() const { return (int64_t{1} << (frac + 1)) - 1; }
};

// Throws std::invalid_argument "<what> <v> out of range [lo, hi]" unless lo <= v <= hi.
inline void check_in_range(const char* what, long long v, long long lo, long long hi) {
  if (v < lo || v > hi)
    throw std::invalid_argument(std::string(what) + " " + std::to_string(v) + " out of range [" + std::to_string(lo) +
                                ", " + std::to_string(hi) + "]");
}

// The value of the entry of `table` whose name is `key` (name_of, value_of: an entry's name and value);
// else throws std::invalid_argument "unknown <what> '<key>' (known: <every name>)".
template <class Table, class NameOf, class ValueOf>
auto find_named(const Table& table, std::string_view key, const char* what, NameOf name_of, ValueOf value_of) {
  for (const auto& e : table)
    if (name_of(e) == key) return value_of(e);
  std::string known;
  for (const auto& e : table) known += (known.empty() ? "" : ", ") + std::string(name_of(e));
  throw std::invalid_argument("unknown " + std::string(what) + " '" + std::string(key) + "' (known: " + known + ")");
}

// Throws std::invalid_argument with a one-line message when the format is illegal.
inline void validate(const Format& f) {
  check_in_range("fraction width", f.frac, kFracMin, kFracMax);
  check_in_range("guard width", f.guard, kGuardMin, kGuardMax);
  if (f.work() > kWorkMax)
    throw std::invalid_argument("frac+guard = " + std::to_string(f.work()) + " exceeds " +
                                std::to_string(kWorkMax));
}

// Throws std::invalid_argument unless n is an integer in [16, 1024].
inline void validate_n(long long n) { check_in_range("specular exponent n =", n, kNMin, kNMax); }

}  // namespace shadecore
