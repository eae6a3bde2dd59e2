// SPDX-License-Identifier: Apache-2.0
// shadecore — exhaustive error sweep: every integer n in a range × every input code in [0, 2^F].
//
// For a variant f (a fixed-point unit and its double-precision twin) it measures
//   approximation error  Δa(c, n) = cos^n θ − f_double(c, n)            (absolute)
//   quantisation error   Δq(c, n) = (f_fixed(code, n) − f_double(c, n)·2^F)   (output ulps)
//   total error          Δ (c, n) = cos^n θ − f_fixed(code, n)/2^F        (absolute)
// with c = code/2^F, θ = acos(c), and records max/min with where they occur.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "shadecore/units/cs16.hpp"
#include "shadecore/format.hpp"

namespace shadecore {

struct Extreme {
  double value = 0.0;
  int n = 0;
  int64_t code = -1;  // input code; θ = acos(code / 2^F)
  bool valid() const { return code >= 0; }
};

struct ErrorStats {
  Extreme max, min;
  void add(double v, int n, int64_t code) {
    // Ties keep the first (smallest n, then smallest code) so results are deterministic.
    if (!max.valid() || v > max.value) max = {v, n, code};
    if (!min.valid() || v < min.value) min = {v, n, code};
  }
  void merge(const ErrorStats& o);
};

struct SweepRow {
  int n = 0;
  ErrorStats approx, quant, total;
  uint64_t nonzero_codes = 0;  // codes with a non-zero fixed-point output (lobe width)
};

struct SweepOptions {
  std::string variant = "cs16";
  Format format{};
  Cutoff cutoff = Cutoff::ThetaCr;
  int n_lo = kNMin, n_hi = kNMax;
  int threads = 0;  // 0: std::thread::hardware_concurrency()
  // Called from the worker threads with the number of (n, code) evaluations just finished.
  std::function<void(uint64_t)> progress;
};

struct SweepResult {
  SweepOptions options;
  std::vector<SweepRow> rows;  // one per n, ascending
  ErrorStats approx, quant, total;
  uint64_t evaluations = 0;
  double seconds = 0.0;
  int threads_used = 0;
};

// Names accepted by SweepOptions::variant.
std::vector<std::string> sweep_variants();

// Throws std::invalid_argument on an unknown variant, illegal format or n range.
SweepResult run_sweep(const SweepOptions& opt);

// Double-precision value of a variant (the same function the sweep measures against).
double variant_golden(const std::string& variant, Cutoff cutoff, int n, double c);

// A variant's contract on the quantisation error q = f_fixed − 2^F·f_double of the same input code, in output
// ulps: lo < q (lo <= q when !lo_strict) and q <= hi (docs/spec.md: cs16 §3, its forms §3.4, Schlick §6.4, table
// units §9.4). The one source of `shadecore sweep`'s verdict and of the bounds its quant_ulp.png draws.
struct QuantContract {
  std::string name;  // configs.json's contract of the variant (cs16: faithful)
  double lo = 0, hi = 0;
  bool lo_strict = false;
  [[nodiscard]] bool met(double qmin, double qmax) const { return (lo_strict ? qmin > lo : qmin >= lo) && qmax <= hi; }
};
// Throws std::invalid_argument for an unknown variant.
QuantContract quant_contract(const std::string& variant, const Format& f);

}  // namespace shadecore
