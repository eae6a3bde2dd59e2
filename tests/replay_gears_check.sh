#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Issue 37's check (ctest replay.glxgears_rtl, labels long and sim): glxgears captured here with apitrace under
# xvfb-run, its frame 10 replayed through the GL front end, the C model and the Verilated core, against Mesa's
# snapshot of the same frame: rtl.png = cmodel.png bit for bit, and the exact image within 2 LSB at p99, max <= 4,
# with identical coverage up to silhouette centres within 1/256 px of an edge (pass_within_snapping: each capture's
# frame 10 is at another angle; tests/data/captures/README.md). Skipped (exit 77) without apitrace, mesa-utils or xvfb.
set -euo pipefail
shadecore="$1"
work="$2"
for t in apitrace glretrace glxgears xvfb-run; do
  command -v "$t" >/dev/null || { echo "skipped: needs $t (Debian apitrace, mesa-utils, xvfb; scripts/setup.sh)"; exit 77; }
done
rm -rf "$work"
mkdir -p "$work"
LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" \
  apitrace trace -o "$work/gears.trace" timeout 3 glxgears -geometry 300x300 >"$work/capture.log" 2>&1 || true
status=0
"$shadecore" replay "$work/gears.trace" --frame 10 --mesa --rtl --out "$work/out" --json "$work/replay.json" || status=$?
[ "$status" -eq 0 ] || [ "$status" -eq 2 ] || exit "$status"  # 2: the comparison's strict verdict, checked below
cmp "$work/out/rtl.png" "$work/out/cmodel.png"
python3 - "$work/replay.json" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
c = j["comparison"]
assert j["rtl"]["ok"] and j["rtl"]["mismatching_pixels"] == 0, j["rtl"]
assert c["pass_within_snapping"] and c["p99_lsb"] <= 2, c
assert c["coverage_mismatch"] == c["coverage_mismatch_at_edge"], c
assert c["compared_pixels"] > 10000, c
print(f"glxgears frame 10: p99 {c['p99_lsb']} / max {c['max_lsb']} LSB over {c['compared_pixels']} px, "
      f"{c['coverage_mismatch']} px covered by one only (all at an edge), "
      f"{j['register_writes']} register writes, {j['core_cycles']} core cycles, rtl.png = cmodel.png")
PY
