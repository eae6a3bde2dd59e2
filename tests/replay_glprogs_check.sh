#!/usr/bin/env bash
# SPDX-License-Identifier: Apache-2.0
# Issue 37's programs of our own (ctest replay.glprogs_rtl, labels long and sim; docs/replay.md): lamp.c,
# twinlights.c, relight.c, depthstate.c and matbatch.c (tests/data/glprogs/) built with cc against libGL and libX11, captured with apitrace
# under xvfb-run, frame 10 replayed through the GL front end, the C model and the Verilated core against Mesa's
# snapshot: rtl.png = cmodel.png bit for bit, the exact image within 2 LSB at p99 and max <= 4 with identical
# coverage, the frame lit by attenuated point lights; lamp and twinlights with glMaterial between glBegin and glEnd
# carried per vertex, relight with the lights and the light model changing between its draws (three lighting
# states, the core reprogrammed between the batches); depthstate.c (a directional light) with glDepthMask(GL_FALSE)
# and GL_DEPTH_TEST off between its draws (docs/replay.md "Depth test off and glDepthMask"); matbatch.c with
# glMaterial changing the diffuse and specular colours and the shininess between the vertices of its strips (each
# vertex lit under its own material: material batches).
# Skipped (exit 77) without a C compiler, the GL/X11 headers, apitrace, glretrace or xvfb-run.
set -euo pipefail
shadecore="$1"
src="$2"
work="$3"
for t in cc apitrace glretrace xvfb-run; do
  command -v "$t" >/dev/null || { echo "skipped: needs $t (Debian gcc, apitrace, xvfb; scripts/setup.sh)"; exit 77; }
done
for h in /usr/include/GL/gl.h /usr/include/GL/glx.h /usr/include/X11/Xlib.h; do
  [ -f "$h" ] || { echo "skipped: needs $h (Debian libgl-dev, mesa-common-dev, libx11-dev; scripts/setup.sh)"; exit 77; }
done
rm -rf "$work"
mkdir -p "$work"
for p in lamp twinlights relight depthstate matbatch; do
  cc -O2 -Wall -Wextra -Werror -std=c99 -o "$work/$p" "$src/$p.c" -lGL -lX11 -lm
  LIBGL_ALWAYS_SOFTWARE=1 xvfb-run -a -s "-screen 0 640x480x24" \
    apitrace trace -o "$work/$p.trace" "$work/$p" >"$work/$p.capture.log" 2>&1
  "$shadecore" replay "$work/$p.trace" --frame 10 --mesa --rtl --out "$work/$p.out" --json "$work/$p.out/replay.json"
  cmp "$work/$p.out/rtl.png" "$work/$p.out/cmodel.png"
  python3 - "$work/$p.out/replay.json" "$p" <<'PY'
import json, sys
j = json.load(open(sys.argv[1]))
c = j["comparison"]
assert j["rtl"]["ok"] and j["rtl"]["mismatching_pixels"] == 0, j["rtl"]
assert c["p99_lsb"] <= 2 and c["max_lsb"] <= 4 and c["coverage_mismatch"] == 0, c
assert c["compared_pixels"] > 20000, c
assert j["unsupported_calls"] == {}, j["unsupported_calls"]
# the features the programs exist for: attenuated point lights, per-vertex glMaterial inside glBegin/glEnd, the
# lighting state changing between draws
if sys.argv[2] == "depthstate":
    assert j["objects"] and len(j["objects"]) == 5, j["objects"]  # one run per ball: five depth states and materials
elif sys.argv[2] == "matbatch":
    assert j["notes"].get("glMaterial between a smooth primitive's vertices: vertices lit under their own material "
                          "(material batches)", 0) > 0, j["notes"]
else:
    assert all("point_att" in core["summary"] for core in j["cores"]), j["cores"]
if sys.argv[2] in ("depthstate", "matbatch"):
    pass
elif sys.argv[2] == "relight":
    assert j["lighting_states"] == 3 and j["lighting_state_changes"] == 2, j["lighting_states"]
    assert j["state_change_register_writes"] > 0, j["state_change_register_writes"]
else:
    assert j["notes"].get("glMaterial between a smooth primitive's vertices carried as colour material", 0) > 0, j["notes"]
assert all(o["shading"] == "gouraud" for o in j["objects"]), "a flat-shaded object"
print(f"{sys.argv[2]} frame 10: p99 {c['p99_lsb']} / max {c['max_lsb']} LSB over {c['compared_pixels']} px, "
      f"{j['register_writes']} register writes ({j['state_change_register_writes']} for "
      f"{j['lighting_state_changes']} lighting-state changes), {j['core_cycles']} core cycles, rtl.png = cmodel.png")
PY
done
