// SPDX-License-Identifier: Apache-2.0
// The loop every rate benchmark here shares: one evaluation per iteration, on the next of `size` prepared
// inputs (a power of two, taken cyclically), its result through benchmark::DoNotOptimize; the rate is
// reported as items processed (one per iteration).
#pragma once

#include <benchmark/benchmark.h>

#include <cstddef>

namespace shadecore::bench {

// eval(i) evaluates input i (0 <= i < size).
template <class Eval>
void cycle_inputs(benchmark::State& st, size_t size, Eval&& eval) {
  size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(eval(i));
    i = (i + 1) & (size - 1);
  }
  st.SetItemsProcessed(st.iterations());
}

}  // namespace shadecore::bench
