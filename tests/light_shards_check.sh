#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# A lighting-core random run split into shards by fragment index checks the same fragments as the
# one-process run: `shadecore cosim --core lighting` once with --count N, then as three shards (--first,
# --count and the same global --reset-at); the shards' vectors add up to N, their stimulus digests add up
# to the single run's, and every run passes. Usage: light_shards_check.sh SHADECORE FEATURES HARNESS
set -eu
sc=$1 feat=$2 harness=$3
n=6000 seed=46 reset=2345
run() {  # run NAME ARGS...: one co-simulation, its JSON in light_shards_$NAME.json
  name=$1; shift
  "$sc" cosim --core lighting --harness "$harness" --features "$feat" --mode random --seed $seed \
    --in-stall 0.3 --out-stall 0.3 --reset-at $reset --json "light_shards_$name.json" "$@" >/dev/null
}
run one --count $n
run s0 --count 2000
run s1 --count 2500 --first 2000
run s2 --count 1500 --first 4500
/usr/bin/python3 - "$n" <<'PY'
import json, sys
n = int(sys.argv[1])
one = json.load(open("light_shards_one.json"))
sh = [json.load(open(f"light_shards_s{k}.json")) for k in range(3)]
m = 2**64
assert one["ok"] and all(s["ok"] for s in sh), "a run failed"
assert one["vectors"] == n, f"one run checked {one['vectors']} of {n}"
v = sum(s["vectors"] for s in sh)
assert v == n, f"shards checked {v} of {n}"
assert sum(s["mismatches"] for s in sh) == one["mismatches"] == 0
d = sum(s["stimulus_digest"] for s in sh) % m
assert d == one["stimulus_digest"], f"digest {d} != {one['stimulus_digest']}"
assert one["resets"] == 1 and [s["resets"] for s in sh] == [0, 1, 0], "the reset is not where the global index says"
print(f"PASS: {n} fragments in one run = 3 shards ({v}), digest {d}, resets {[s['resets'] for s in sh]}")
PY
