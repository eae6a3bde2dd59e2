#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# The long co-simulation runs (not part of ctest): builds, then
#   1. full exhaustive co-simulation at the default width: every n 16..1024 x every code in [0, 2^F]
#      (+ 4 out-of-range codes per n), both cut-off forms;
#   2. 10 million random transactions with random input gaps and output backpressure (p = 0.3 each)
#      and a mid-stream reset per shard;
#   3. with WIDE=1: every n 16..1024 x every code at the wide width (F = 24: 16.9 G vectors) through the
#      bare Verilated harness (no SystemC scheduler, no stalls; each output compared with the C model),
#      one process per core — about 4 minutes on 2 cores instead of ~45 with the SystemC testbench.
# Results (merged JSON) go to ${OUT:-out}/cosim/. Exit non-zero on any mismatch or lost/duplicated/
# reordered transaction or latency violation.  Usage: scripts/cosim_full.sh  (BUILD_DIR, OUT, SEED)
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${BUILD_DIR:-build}
OUT=${OUT:-out}
SEED=${SEED:-20261122}
scripts/build.sh
mkdir -p "$OUT/cosim"
cli="$BUILD_DIR/cli/shadecore"
for cut in theta_cr sign_clamp; do
  "$cli" cosim --mode exhaustive --n 16..1024 --cutoff "$cut" --json "$OUT/cosim/exhaustive_default_${cut}.json"
done
"$cli" cosim --mode random --count 10000000 --in-stall 0.3 --out-stall 0.3 --seed "$SEED" \
  --json "$OUT/cosim/random_10M_stalls.json"
if [ "${WIDE:-0}" = 1 ]; then
  bare="$BUILD_DIR/sim/shadecore_bare_wide"
  "$bare" --n 16..519 > "$OUT/cosim/bare_wide_16_519.txt" &
  p1=$!
  "$bare" --n 520..1024 > "$OUT/cosim/bare_wide_520_1024.txt" &
  p2=$!
  rc=0
  wait $p1 || rc=1
  wait $p2 || rc=1
  cat "$OUT/cosim/bare_wide_16_519.txt" "$OUT/cosim/bare_wide_520_1024.txt"
  exit $rc
fi
