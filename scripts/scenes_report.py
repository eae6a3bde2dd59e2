#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Renders every example scene for docs/scenes.md and measures what the specialisation saves.

    scripts/scenes_report.py [--shadecore build/cli/shadecore] [--runs 5] [--yosys] [--scenes diffuse,spheres]

Per scene in scenes/ (diffuse, spheres, shading_modes, mesh):
  * `shadecore render SCENE --rtl` at the scene's full resolution into docs/scenes/<scene>/ (rtl.png — byte-identical
    to the C model's image, which is checked and then not kept —, exact.png, diff_exact.png, contact_sheet.png where
    the scene has one, render.json);
  * the same with --full-core (render_full.json); the RTL images of both must be byte-identical;
  * RTL simulation time specialised vs full: --runs more renders of each, alternating (A B A B ...), the median of the
    simulator's own wall time (rtl.sim_seconds: the simulation, not the build or the host rasteriser);
  * with --yosys: generic cells of every core used (specialised and full): `synth -top sc_light; abc;
    stat -top sc_light` (hierarchical) on rtl/*.v with FeatureSet::verilog_params (slow: ~5–15 min per specialised
    core, longer for the full ones on 2 shared cores); cached in docs/scenes/yosys.json by feature key and a hash
    of rtl/*.v.
Writes docs/scenes/results.json and the tables of docs/scenes.md between the "scenes-report" markers, with the
command, the machine and the date. Exit status 1 on any mismatching pixel or any difference between the images.
"""
import argparse
import datetime
import filecmp
import hashlib
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = ["diffuse", "spheres", "shading_modes", "mesh"]
DOCS = os.path.join(ROOT, "docs", "scenes")


def fail(msg):
    print("scenes_report: error: " + msg, file=sys.stderr)
    sys.exit(1)


def render(exe, scene, out, json_path, extra):
    cmd = [exe, "render", os.path.join(ROOT, "scenes", scene + ".json"), "--rtl", "--out", out, "--json", json_path] + extra
    p = subprocess.run(cmd, cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    if p.returncode != 0:
        fail("%s failed (%d): %s" % (" ".join(cmd), p.returncode, p.stderr.strip().splitlines()[-1:] or ""))
    with open(json_path) as f:
        return json.load(f)


def machine():
    cpu = platform.processor() or ""
    try:
        with open("/proc/cpuinfo") as f:
            m = re.search(r"model name\s*:\s*(.*)", f.read())
            if m:
                cpu = m.group(1).strip()
    except OSError:
        pass
    return "%s, %d cores, %s" % (cpu, os.cpu_count() or 0, platform.platform())


def rtl_hash():
    h = hashlib.sha256()
    d = os.path.join(ROOT, "rtl")
    for n in sorted(os.listdir(d)):
        if n.endswith(".v") or n.endswith(".vh"):
            h.update(n.encode())
            with open(os.path.join(d, n), "rb") as f:
                h.update(f.read())
    return h.hexdigest()[:16]


def yosys_cells(params):
    chp = "".join(" -chparam %s %s" % tuple(p.split("=", 1)) for p in params)
    with tempfile.TemporaryDirectory() as tmp:
        stat = os.path.join(tmp, "stat.txt")
        # Hierarchical: each distinct module parameterisation is synthesised once and `stat -top` sums the
        # hierarchy (a flat synthesis of the 8-light full core does not finish in hours on 2 cores; on the
        # diffuse set the two differ by 0.4 %: 62449 hierarchical, 62212 flat).
        script = ("read_verilog -Irtl rtl/*.v; hierarchy -check -top sc_light%s; synth -top sc_light; abc; "
                  "tee -q -o %s stat -top sc_light" % (chp, stat))
        p = subprocess.run(["yosys", "-q", "-p", script], cwd=ROOT, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           text=True)
        if p.returncode != 0:
            fail("yosys failed: " + (p.stdout.strip().splitlines() or ["?"])[-1])
        with open(stat) as f:
            m = re.findall(r"Number of cells:\s+(\d+)", f.read())
        return int(m[-1])


def fmt_s(x):
    return "%.3f" % x if x < 10 else "%.1f" % x


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--shadecore", default=os.path.join(ROOT, "build", "cli", "shadecore"))
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--yosys", action="store_true")
    ap.add_argument("--scenes", default=",".join(SCENES))
    a = ap.parse_args()
    if not os.access(a.shadecore, os.X_OK):
        fail("no shadecore executable at %s (build first, or --shadecore PATH)" % a.shadecore)
    scenes = [s for s in a.scenes.split(",") if s]
    for s in scenes:
        if s not in SCENES:
            fail("unknown scene %s (known: %s)" % (s, ", ".join(SCENES)))
    os.makedirs(DOCS, exist_ok=True)
    res_path = os.path.join(DOCS, "results.json")
    results = {}
    if os.path.exists(res_path):
        with open(res_path) as f:
            results = json.load(f).get("scenes", {})
    ycache_path = os.path.join(DOCS, "yosys.json")
    ycache = {}
    if os.path.exists(ycache_path):
        with open(ycache_path) as f:
            ycache = json.load(f)
    rh = rtl_hash()

    for s in scenes:
        print("scenes_report: %s" % s, file=sys.stderr)
        out = os.path.join(DOCS, s)
        with tempfile.TemporaryDirectory() as tmp:
            spec_dir, full_dir = os.path.join(tmp, "spec"), os.path.join(tmp, "full")
            spec = render(a.shadecore, s, spec_dir, os.path.join(tmp, "render.json"), [])
            full = render(a.shadecore, s, full_dir, os.path.join(tmp, "render_full.json"), ["--full-core"])
            for d, j in ((spec_dir, spec), (full_dir, full)):
                if j["rtl"]["mismatching_pixels"] != 0 or not filecmp.cmp(os.path.join(d, "rtl.png"),
                                                                            os.path.join(d, "cmodel.png"), shallow=False):
                    fail("%s: RTL image differs from the C model's" % s)
            if not filecmp.cmp(os.path.join(spec_dir, "rtl.png"), os.path.join(full_dir, "rtl.png"), shallow=False):
                fail("%s: specialised and full-core images differ" % s)
            # Timing: alternate specialised and full renders; the simulator's own wall time.
            t_spec = [spec["rtl"]["sim_seconds"]]
            t_full = [full["rtl"]["sim_seconds"]]
            for _ in range(max(0, a.runs - 1)):
                t_spec.append(render(a.shadecore, s, os.path.join(tmp, "t"), os.path.join(tmp, "t.json"), [])["rtl"]["sim_seconds"])
                t_full.append(render(a.shadecore, s, os.path.join(tmp, "t"), os.path.join(tmp, "t.json"),
                                     ["--full-core"])["rtl"]["sim_seconds"])
            os.makedirs(out, exist_ok=True)
            for n in ("rtl.png", "exact.png", "diff_exact.png", "contact_sheet.png"):
                src = os.path.join(spec_dir, n)
                if os.path.exists(src):
                    shutil.copyfile(src, os.path.join(out, n))
            for n, j in (("render.json", spec), ("render_full.json", full)):
                with open(os.path.join(out, n), "w") as f:
                    json.dump(j, f, indent=2)
                    f.write("\n")
        cores = []
        for g, gf in zip(spec["features"], full["features"]):
            entry = {"unit": g["unit"], "materials": g["materials"], "summary": g["summary"], "key": g["key"],
                     "full_key": gf["key"], "full_summary": gf["summary"], "full_substitutions": gf["full_substitutions"],
                     "fragments": g["fragments"], "error_vs_exact": g["error_vs_exact"],
                     "error_vs_unit_double": g["error_vs_unit_double"],
                     "params": g["verilog_params"], "full_params": gf["verilog_params"]}
            if a.yosys:
                for k, p in ((g["key"], g["verilog_params"]), (gf["key"], gf["verilog_params"])):
                    c = ycache.get(k)
                    if not c or c.get("rtl") != rh:
                        print("scenes_report: yosys %s ..." % k, file=sys.stderr)
                        ycache[k] = {"rtl": rh, "cells": yosys_cells(p), "params": p}
                        with open(ycache_path, "w") as f:
                            json.dump(ycache, f, indent=2, sort_keys=True)
                            f.write("\n")
            cores.append(entry)
        results[s] = {
            "size": [spec["width"], spec["height"]],
            "fragments": spec["fragments"],
            "cores": cores,
            "rtl_cycles": spec["rtl"]["cycles"],
            "rtl_cycles_full": full["rtl"]["cycles"],
            "sim_seconds": t_spec,
            "sim_seconds_full": t_full,
            "sim_median": statistics.median(t_spec),
            "sim_median_full": statistics.median(t_full),
            "mismatching_pixels": spec["rtl"]["mismatching_pixels"],
            "mismatching_pixels_full": full["rtl"]["mismatching_pixels"],
            "identical_full": True,
            "contact_sheet": spec.get("contact_sheet"),
            "error_vs_exact": spec["error_vs_exact"],
        }
    meta = {"command": " ".join(["scripts/scenes_report.py"] + sys.argv[1:]), "machine": machine(),
            "date": datetime.date.today().isoformat()}
    with open(res_path, "w") as f:
        json.dump({"meta": meta, "scenes": results}, f, indent=2)
        f.write("\n")
    update_doc(results, ycache, meta)


def update_doc(results, ycache, meta):
    doc = os.path.join(ROOT, "docs", "scenes.md")
    lines = []
    lines.append("Measured by `%s` on %s, %s. Images at full resolution in `docs/scenes/<scene>/`; "
                 "`render.json` / `render_full.json` there are the `--json` reports." % (meta["command"], meta["machine"], meta["date"]))
    lines.append("")
    lines.append("| scene | size | core (unit) | feature set | fragments | Yosys cells specialised / full | RTL sim specialised / full (median) | speed-up | mismatching pixels (spec., full) | images identical |")
    lines.append("|---|---|---|---|---|---|---|---|---|---|")
    for s in SCENES:
        r = results.get(s)
        if not r:
            continue
        for i, c in enumerate(r["cores"]):
            yc = ycache.get(c["key"], {}).get("cells")
            yf = ycache.get(c["full_key"], {}).get("cells")
            cells = ("%d / %d (%.1f×)" % (yc, yf, yf / yc)) if yc and yf else "—"
            first = i == 0
            sim = "%s s / %s s" % (fmt_s(r["sim_median"]), fmt_s(r["sim_median_full"])) if first else "″"
            speed = "%.1f×" % (r["sim_median_full"] / r["sim_median"]) if first and r["sim_median"] > 0 else ("″" if not first else "—")
            lines.append("| %s | %s | %s | %s `%s` | %d | %s | %s | %s | %s | %s |" % (
                "`%s.json`" % s if first else "″", "%d×%d" % tuple(r["size"]) if first else "″", c["unit"],
                c["summary"], c["key"], c["fragments"]["total"], cells, sim, speed,
                "%d, %d" % (r["mismatching_pixels"], r["mismatching_pixels_full"]) if first else "″",
                "yes" if r["identical_full"] else "NO"))
    lines.append("")
    lines.append("Error of the core's image against the exact double reference (cos^n), per core / specular unit, over the pixels "
                 "that unit shades (LSB = 2^−16 of full scale; PSNR over those pixels, peak 1.0); and against the unit's own "
                 "double formula (quantisation only):")
    lines.append("")
    lines.append("| scene | unit (materials) | vs exact cos^n: max / mean LSB, PSNR | vs the unit's double: max / mean LSB, PSNR |")
    lines.append("|---|---|---|---|")

    def st(e):
        p = "%.1f dB" % e["psnr_db"] if e["psnr_db"] is not None else "∞"
        return "%.0f / %.2f, %s" % (e["max_lsb"], e["mean_lsb"], p)

    for s in SCENES:
        r = results.get(s)
        if not r:
            continue
        for c in r["cores"]:
            lines.append("| `%s.json` | %s (%s) | %s | %s |" % (s, c["unit"], ", ".join(c["materials"]),
                                                                st(c["error_vs_exact"]), st(c["error_vs_unit_double"])))
        cs = r.get("contact_sheet")
        if cs:
            for row in cs["rows"]:
                for cell in row["cells"]:
                    lines.append("| `%s.json` contact sheet, %s | %s | %s | — |" % (s, row["mode"], cell["unit"], st(cell["error_vs_exact"])))
    text = "\n".join(lines) + "\n"
    with open(doc) as f:
        d = f.read()
    b, e = "<!-- scenes-report:begin -->\n", "<!-- scenes-report:end -->"
    if b not in d or e not in d:
        fail("docs/scenes.md has no scenes-report markers")
    d = d[: d.index(b) + len(b)] + text + d[d.index(e):]
    tmp = doc + ".tmp"
    with open(tmp, "w") as f:
        f.write(d)
    os.replace(tmp, doc)
    print("scenes_report: updated docs/scenes.md and docs/scenes/results.json", file=sys.stderr)


if __name__ == "__main__":
    main()
