#!/bin/sh
# SPDX-License-Identifier: Apache-2.0
# The waveform of a failed lighting-core run (issue 36): `shadecore cosim --core lighting --trace F` with a
# corrupted output (--inject value --inject-at K: the run must FAIL) re-runs the failure on the set's trace
# build (<key>-trace) and writes the FST of the cycles around the first failure; the file exists, is not
# empty, and its header's time range is that window (cycle k's rising edge at (k - 1) * 10 ns) and holds the
# failing transfer. A passing run with --trace writes nothing; --trace-all writes the whole run from time 0.
# Usage: light_trace_check.sh SHADECORE FEATURES HARNESS
set -eu
sc=$1 feat=$2 harness=$3
d=light_trace_$harness
rm -rf "$d"
mkdir "$d"
run() {  # run EXPECTED_STATUS ARGS...
  want=$1; shift
  set +e
  "$sc" cosim --core lighting --harness "$harness" --features "$feat" --mode random --count 3000 --seed 43 \
    --in-stall 0.2 --out-stall 0.3 --no-progress "$@" >"$d/out.txt" 2>&1
  rc=$?
  set -e
  cat "$d/out.txt"
  [ "$rc" -eq "$want" ] || { echo "FAIL: exit $rc, expected $want"; exit 1; }
}
# 1. a FAIL: the window around the first failure
run 2 --inject value --inject-at 777 --trace "$d/fail.fst" --trace-window 40 --json "$d/fail.json"
grep -q "waveform written to $d/fail.fst" "$d/out.txt"
test -s "$d/fail.fst"
# 2. a PASS: no waveform
run 0 --trace "$d/pass.fst" --json "$d/pass.json"
test ! -e "$d/pass.fst"
grep -q "no waveform written" "$d/out.txt"
# 3. --trace-all: the whole run
run 2 --inject value --inject-at 777 --trace "$d/all.fst" --trace-all --json "$d/all.json"
test -s "$d/all.fst"
# 4. the trace build's simulator stopped by SIGTERM while it writes a waveform leaves nothing
tb=$(sed -n 's/.*"build_dir": "\(.*-trace\)".*/\1/p' "$d/fail.json")
exe=$tb/shadecore_light_sim
[ "$harness" = bare ] && exe=$tb/shadecore_light_bare
"$exe" --mode random --count 100000000 --seed 3 --trace "$d/int.fst" >/dev/null 2>&1 &
pid=$!
sleep 2
kill -TERM $pid
set +e; wait $pid; rc=$?; set -e
echo "stopped by SIGTERM: exit $rc"
[ "$rc" -ne 0 ] || { echo "FAIL: the run was not stopped"; exit 1; }
# nothing else left in the directory (no temporary file)
left=$(ls -A "$d" | grep -v -x -e fail.fst -e fail.json -e pass.json -e all.fst -e all.json -e out.txt || true)
[ -z "$left" ] || { echo "FAIL: left behind: $left"; exit 1; }
/usr/bin/python3 - "$d" <<'PY'
import json, struct, sys
d = sys.argv[1]
def header(path):
    b = open(path, "rb").read(330)
    assert b[0] == 0, f"{path}: not an FST file (first block type {b[0]})"
    # the header block: type 0, length, start and end time, endian test, memory, scopes, hierarchy vars, vars, ...
    start, end = struct.unpack(">QQ", b[9:25])
    scopes, _, nvars = struct.unpack(">QQQ", b[41:65])
    scale = struct.unpack("b", b[73:74])[0]  # 10^scale seconds per time unit
    assert b[74:83] == b"fstWriter", f"{path}: no FST writer signature"
    assert scopes > 1 and nvars > 20, f"{path}: {scopes} scopes, {nvars} signals: not the core's"
    return start, end, scale
fail = json.load(open(f"{d}/fail.json"))
assert not fail["ok"] and fail["mismatches"] == 1, fail
t = fail["trace"]
at = fail["first_error_cycle"]
assert t["from_cycle"] == at - 40 and t["to_cycle"] == at + 40, (t, at)
start, end, scale = header(f"{d}/fail.fst")
ns = 10 ** (-9 - scale)  # time units per ns
cyc = lambda k: (k - 1) * 10 * ns  # the rising edge of monitor cycle k
assert start == cyc(t["from_cycle"]), f"window starts at {start}, expected {cyc(t['from_cycle'])}"
assert cyc(at) <= end <= cyc(t["to_cycle"]) + 5 * ns, f"window ends at {end}; first error at {cyc(at)}"
assert end - start <= 81 * 10 * ns, "more than the window"
print(f"fail.fst: time {start}..{end} (x 1e{scale} s) = cycles {t['from_cycle']}..{t['to_cycle']}, first error at cycle {at}")
alls, alle, _ = header(f"{d}/all.fst")
allj = json.load(open(f"{d}/all.json"))
assert alls == 0 and alle >= cyc(allj["cycles"] - 1), (alls, alle, allj["cycles"])  # the last edge stops the run
assert allj["first_error_cycle"] == at, "--trace-all ran another failure"
print(f"all.fst: time 0..{alle}, {allj['cycles']} cycles")
PY
echo "light_trace_check: PASS"
