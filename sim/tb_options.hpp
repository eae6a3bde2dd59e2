// SPDX-License-Identifier: Apache-2.0
// shadecore sim — options of one co-simulation run (the simulator executable's command line).
#pragma once

#include <cstdint>
#include <string>

namespace shadecore::sim {

enum class Mode { Exhaustive, Random, Directed };

struct Options {
  std::string variant = "cs16";
  std::string cutoff = "theta_cr";
  Mode mode = Mode::Directed;
  int n_lo = 16, n_hi = 1024;   // exponent range (exhaustive, random)
  uint64_t count = 100000;      // random: transactions; directed: at least this many (list repeated)
  uint64_t seed = 1;
  // Random mode: global index of this run's first transaction. Transaction i's stimulus is a function of
  // (seed, i) only, so `shadecore cosim` can split one seeded run into shards (shard k runs `count`
  // transactions from `first`) and the same seed gives the same stimulus whatever the shard count.
  uint64_t first = 0;
  double in_stall = 0.0;        // probability per cycle that the driver withholds in_valid_i
  double out_stall = 0.0;       // probability per cycle that out_ready_i is low
  double mat_rate = 0.01;       // random mode: probability per transaction of a material change before it
  // rst_ni pulses low once, before the transaction of this index (random: global index, so a shard holding it
  // resets there and the others do not); -1 none, -2 auto (half way through the run)
  int64_t reset_at = -2;
  int reset_cycles = 3;
  bool resend = true;           // the transactions a reset flushes are sent again (false: --no-resend, dropped)
  std::string trace;            // FST file ("" = no trace)
  int show = 10;                // mismatches printed in full
  // Self-test of the checks (must make the run FAIL): corrupt what the monitor reports for the
  // inject_at-th output transfer: "value" flips bit 0 of out_spec, "drop" hides the transfer,
  // "dup" reports it twice. "" = off.
  std::string inject;
  uint64_t inject_at = 100;
  bool quiet = false;
};

inline const char* to_string(Mode m) {
  return m == Mode::Exhaustive ? "exhaustive" : (m == Mode::Random ? "random" : "directed");
}

}  // namespace shadecore::sim
