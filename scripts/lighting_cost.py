#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Cost against throughput of the lighting core (issue 18): docs/lighting_cost.json.

One row per (feature set, lanes, share, spec_guard): Yosys generic cells counted hierarchically (`synth -top sc_light; abc;
stat -top sc_light`, as docs/lighting.md §8), `synth_xilinx -family xc7 -flatten` LUT / FF / DSP48E1,
`synth_ecp5` LUT4 / MULT18X18D, the latency (LightCore::latency, every slot on, the slowest unit), the
fragments per clock for 0, 1, 2, 4 and 8 enabled lights (⌈k/lanes⌉ passes, one pass per `share` clocks:
the scheduler of rtl/sc_light.v, checked cycle for cycle by the co-simulation's latency checks) and the
SystemC co-simulation speed. The feature set of a row is the named set with its `lanes` (`share`) replaced; its
Verilog parameters come from the CLI (`shadecore light-sweep --json`: FeatureSet::verilog_params), so
nothing here restates the feature-set rules.

    scripts/lighting_cost.py --build build --sets full --lanes 1,2,4,8 --steps generic,xc7,ecp5,cosim
    scripts/lighting_cost.py --build build --sets full --spec-guard 0,5 --steps xc7
    scripts/lighting_cost.py --build build --sets full --share 1,2,4 --steps xc7,cosim
    scripts/lighting_cost.py --build build --sets diffuse,gl_default,phong_point,mono_spec

Rows are cached in the output file by (set, lanes, step, source hash): rerunning resumes, an edited RTL
reruns. A step that fails or exceeds --timeout is recorded as null with the reason.
"""
import argparse
import datetime
import hashlib
import json
import math
import os
import platform
import re
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def one_line(s, limit=300):
    s = " ".join(str(s).split())
    return s if len(s) <= limit else s[:limit] + "..."


def run(cmd, timeout):
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError(f"{cmd[0]} exited {p.returncode}: {one_line(p.stderr or p.stdout)}")
    return p.stdout


def light_files():
    cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    r = cfg["rtl"]
    files = list(r["sc_light"]["files"]) + r["sc_light"]["normalize"] + r["sc_light"]["recip"]
    files += r["sc_specular"]["files"] + r["sc_specular"]["energy"]
    for v in cfg["variants"]:
        files += v["rtl"]
    out = []
    for f in files:
        if f not in out:
            out.append(f)
    return [os.path.join(ROOT, "rtl", f) for f in out]


def source_hash():
    h = hashlib.sha256()
    for f in sorted(light_files()) + [os.path.join(ROOT, "rtl", "sc_light_regs.vh"),
                                      os.path.join(ROOT, "rtl", "sc_variants.vh")]:
        h.update(open(f, "rb").read())
    return h.hexdigest()[:16]


def read_core(params):
    ch = " ".join(f"-chparam {p.split('=')[0]} {p.split('=')[1]}" for p in params if not p.startswith("TAGW="))
    return (f"read_verilog -I{os.path.join(ROOT, 'rtl')} {' '.join(light_files())}; "
            f"hierarchy -check -top sc_light {ch}")


def count(stat_text, pattern):
    """Sum of the cell counts whose type matches `pattern` in the last `stat` summary."""
    total = 0
    for m in re.finditer(r"^\s+(\S+)\s+(\d+)\s*$", stat_text, re.M):
        if re.fullmatch(pattern, m.group(1)):
            total += int(m.group(2))
    return total


def last_block(text, marker):
    i = text.rfind(marker)
    return text[i:] if i >= 0 else text


def step_generic(params, timeout):
    out = run(["yosys", "-q", "-p", f"{read_core(params)}; synth -top sc_light; abc; tee -o /dev/stdout stat -top sc_light"],
              timeout)
    m = re.findall(r"Number of cells:\s+(\d+)", last_block(out, "design hierarchy"))
    if not m:
        raise RuntimeError("no cell count in the yosys output")
    return {"cells": int(m[0])}


def step_xc7(params, timeout):
    out = run(["yosys", "-q", "-p", f"{read_core(params)}; synth_xilinx -family xc7 -flatten -top sc_light; "
               "tee -o /dev/stdout stat"], timeout)
    return {"x7_lut": count(out, r"LUT[1-6]"), "x7_ff": count(out, r"FD\w*"), "x7_dsp48": count(out, r"DSP48E1"),
            "x7_carry4": count(out, r"CARRY4")}


def step_ecp5(params, timeout):
    out = run(["yosys", "-q", "-p", f"{read_core(params)}; synth_ecp5 -top sc_light; tee -o /dev/stdout stat"],
              timeout)
    return {"ecp5_lut4": count(out, r"LUT4"), "ecp5_mult18": count(out, r"MULT18X18D"),
            "ecp5_ff": count(out, r"TRELLIS_FF")}


def step_cosim(shadecore, fs_file, count_, timeout):
    with tempfile.TemporaryDirectory() as tmp:
        js = os.path.join(tmp, "cosim.json")
        p = subprocess.run([shadecore, "cosim", "--core", "lighting", "--features", fs_file, "--mode", "random",
                            "--count", str(count_), "--in-stall", "0", "--out-stall", "0", "--seed", "1", "--json", js],
                           capture_output=True, text=True, timeout=timeout)
        if p.returncode != 0:
            raise RuntimeError(f"cosim exited {p.returncode}: {one_line(p.stderr or p.stdout)}")
        j = json.load(open(js))
        return {"cosim_fragments_per_s": round(j["vectors_per_s"]), "cosim_mismatches": j["mismatches"],
                "cosim_vectors": j["vectors"]}


FRACS = {0: "0", 1: "1", 2: "½", 4: "¼", 8: "⅛", 16: "1/16", 32: "1/32"}
MARK_BEGIN = "<!-- lighting-cost: generated by scripts/lighting_cost.py --report, do not edit -->"
MARK_END = "<!-- /lighting-cost -->"
XC7A35T = {"lut": 20800, "dsp": 90}


def _fmt(v, spec=","):
    return "—" if v is None else format(v, spec)


def _old(r):
    """The label of a row kept for the record (`superseded`): which RTL it was measured on."""
    return f" ({r.get('superseded_label', 'first RTL')})" if r.get("superseded") else ""


def _fpc(v):
    if v is None:
        return "—"
    for k, t in FRACS.items():
        if k and abs(v - 1.0 / k) < 1e-9:
            return t
    return f"{v:.3g}"


def report_markdown(doc):
    """The cost/throughput table of docs/lighting_cost.json (one row per set, lanes, spec_guard), for
    docs/lighting.md §8.1 and docs/tradeoffs.md: one source for both."""
    rows = sorted(doc["rows"], key=lambda r: (r["set"] != "full", r["set"], not r.get("superseded"), r["lanes"],
                                             r.get("share", 1), r.get("spec_guard", 0)))
    L = ["| set | lanes | share | spec_guard | generic cells | xc7 LUT / FF / DSP48E1 | fits XC7A35T | ECP5 LUT4 / MULT18 | "
         "latency | fragments per clock at 0 / 1 / 2 / 4 / 8 lights | cosim fragments/s | measured |",
         "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        fpc = r.get("fragments_per_clock", {})
        fits = "—"
        if r.get("x7_lut") is not None and r.get("x7_dsp48") is not None:
            fits = "yes" if r["x7_lut"] <= XC7A35T["lut"] and r["x7_dsp48"] <= XC7A35T["dsp"] else (
                f"no ({r['x7_lut'] / XC7A35T['lut']:.2f}× LUT, {r['x7_dsp48'] / XC7A35T['dsp']:.2f}× DSP)")
        gen = _fmt(r.get("cells"))
        if r.get("generic_error"):
            gen = "not finished"
        when = sorted(set(v[:10] for v in r.get("when", {}).values()))
        src = sorted(set(r.get("source", {}).values()))
        L.append(f"| {r['set']}{_old(r)} | {r['lanes']} | {r.get('share', 1)} | {r.get('spec_guard', 0)} | {gen} | "
                 f"{_fmt(r.get('x7_lut'))} / {_fmt(r.get('x7_ff'))} / {_fmt(r.get('x7_dsp48'))} | {fits} | "
                 f"{_fmt(r.get('ecp5_lut4'))} / {_fmt(r.get('ecp5_mult18'))} | {r.get('latency', '—')} | "
                 f"{' / '.join(_fpc(fpc.get(k)) for k in ('0', '1', '2', '4', '8') if k in fpc)} | "
                 f"{_fmt(r.get('cosim_fragments_per_s'))} | {', '.join(when)} (RTL {', '.join(src)}) |")
    errs = [f"- {r['set']} lanes {r['lanes']} share {r.get('share', 1)} spec_guard {r.get('spec_guard', 0)}: {k[:-6]}: {r[k]}"
            for r in rows for k in sorted(r) if k.endswith("_error") and r[k]]
    if errs:
        L += ["", "Steps that failed or timed out (reported, not hidden):", ""] + errs
    L += ["", "![cells against fragments per clock](lighting_cost.png)", ""]
    L += standard_cell_markdown()
    return "\n".join(L)


def standard_cell_markdown(path=os.path.join(ROOT, "docs", "timing.json")):
    """The sets' rows of docs/timing.json (scripts/timing_report.py: OSU 0.18 um cells, OpenSTA, gate-level energy):
    clock, latency in ns, fragments per second, area and energy per fragment, beside the table above."""
    if not os.path.exists(path):
        return []
    doc = json.load(open(path))
    rows = [t for t in doc["rows"] if t["kind"] == "lighting"]
    if not rows:
        return []
    L = ["In a standard-cell library (OSU 0.18 µm typical, pre-layout, cell delays ×"
         f"{doc['derate_late']}; from docs/timing.json, `{doc['command']}`, {doc['machine']}, {doc['date']}; "
         "docs/signoff.md). Latency: the largest over register states (every slot enabled, the slowest unit: "
         "`LightCore::latency()`); fragments/s and energy from the gate-level run of the "
         "bundle's random fragments (the set's lights as the generator enables them), energy = power × period × "
         "cycles / fragments:", "",
         f"| set | closes at (ns) | meets {doc['target_ns']} ns | latency (cycles / ns) | fragments/s | area (µm²) | "
         "cells | energy (pJ/fragment) | gate-level sim | critical path |", "|---|---|---|---|---|---|---|---|---|---|"]
    for t in rows:
        lat = f"{t['latency_cycles']} / {t['latency_ns']}" if t.get("latency_cycles") is not None else "—"
        gs = figures_mod().gate_sim_text(t)
        meets = "yes" if t["met"] else f"no (WNS {t['wns_ns']:+.3f})"
        L.append(f"| {t['name']} | {t['period_ns']} | {meets} | {lat} | "
                 f"{t['results_per_s']:,} | {t['area_um2']:,} | {t['cells']:,} | "
                 f"{_fmt(t.get('energy_pj_per_result'), '.1f')} | {gs} | `{t['critical_path']}` |")
    missing = [m for m in doc.get("not_measured", []) if m.startswith("lighting:")]
    if missing:
        L += ["", "Not measured in that run: " + ", ".join(m.split(":")[1] for m in missing) + "."]
    return L + [""]


def figures_mod():
    """scripts/figures.py (imported on use: the measuring steps run without matplotlib)."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import figures
    return figures


def _label(r):
    """A row's short name on the figure: set, L lanes, S share (only when > 1), g spec_guard."""
    share = r.get("share", 1)
    return f"{r['set']} L{r['lanes']}{'' if share == 1 else f' S{share}'} g{r.get('spec_guard', 0)}"


def plot(doc, path, footer_text):
    """Cells and DSPs against throughput: the current rows coloured and labelled (labels placed clear of each
    other, leader lines when moved away), the superseded rows (measurements of earlier RTL, listed with
    their labels in docs/lighting.md §8.1's table) as small light-grey marks without labels."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.ticker import FuncFormatter, LogLocator
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import figures
    fig, axes = plt.subplots(1, 2, figsize=(12, 5.4))
    labels = []
    for ax, key, label in ((axes[0], "cells", "Yosys generic cells"), (axes[1], "x7_dsp48", "xc7 DSP48E1")):
        current = []
        for r in doc["rows"]:
            v = r.get(key)
            if v is None:
                continue
            x = r["fragments_per_clock"].get("8", r["fragments_per_clock"].get("1"))
            mk = "o" if r.get("spec_guard", 0) else "s"
            if r.get("superseded"):
                ax.scatter([x], [v], marker=mk, s=14, facecolors="none", edgecolors="0.72", linewidths=0.7, zorder=2)
                continue
            colour = "C0" if r["set"].startswith("full") else "C1"
            ax.scatter([x], [v], marker=mk, s=40, color=colour, zorder=3)
            current.append((x, v, _label(r)))
        obstacles = []
        if key == "x7_dsp48":
            ax.axhline(XC7A35T["dsp"], color="0.5", ls="--", lw=0.8, zorder=1)
            obstacles.append(ax.text(0.985, XC7A35T["dsp"], f"XC7A35T holds {XC7A35T['dsp']} DSP48E1", fontsize=7,
                                     ha="right", va="bottom", color="0.3", transform=ax.get_yaxis_transform(),
                                     bbox=dict(facecolor="white", edgecolor="none", pad=1.0)))
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        ax.set_xlim(0.015, 2.5)
        ys = [r[key] for r in doc["rows"] if r.get(key) is not None]
        if ys:
            ax.set_ylim(min(ys) / 2, max(ys) * 2)
        ax.yaxis.set_major_locator(LogLocator(base=10, subs=(1, 2, 5)))
        ax.yaxis.set_minor_locator(LogLocator(base=10, subs=(1, 2, 3, 4, 5, 6, 7, 8, 9)))
        ax.yaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:,.0f}"))
        ax.yaxis.set_minor_formatter(FuncFormatter(lambda v, _: ""))
        ax.xaxis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}" if v >= 1 else f"1/{1 / v:g}"))
        ax.set_xlabel("fragments per clock, every light slot enabled")
        ax.set_ylabel(label)
        ax.set_title(f"{label} against throughput")
        ax.grid(alpha=0.25, which="both")
        labels.append((ax, current, obstacles))
    handles = [Line2D([], [], marker="o", ls="", color="C0", label="full sets (8 light slots)"),
               Line2D([], [], marker="o", ls="", color="C1", label="other named sets"),
               Line2D([], [], marker="o", ls="", mfc="none", color="0.3", label="○ spec_guard 5, □ spec_guard 0"),
               Line2D([], [], marker="o", ls="", mfc="none", color="0.72", markersize=4,
                      label="earlier RTL of the same sets (history: docs/lighting.md §8.1 table)")]
    axes[0].legend(handles=handles, fontsize=7, loc="lower left")
    fig.suptitle("Lighting core cost against throughput (docs/lighting_cost.json). Labels: feature set, L lanes, "
                 "S share (clocks per light, when > 1),\ng spec_guard (extra fraction bits of the specular path)",
                 fontsize=9)
    figures.layout(fig)
    for ax, current, obstacles in labels:
        obstacles = obstacles + [l for l in [ax.get_legend()] if l is not None]
        figures.place_labels(ax, sorted(current), fontsize=7, obstacles=obstacles)
    figures.save(fig, path, footer_text)


def provenance(doc, out_json, how):
    """The figure's footer: where its rows came from (file, machine, measurement dates), then how it was drawn."""
    when = sorted(v[:10] for r in doc["rows"] for v in r.get("when", {}).values())
    span = f"{when[0]} to {when[-1]}" if when else doc.get("date", "?")
    return (f"rows: {os.path.relpath(out_json, ROOT)}, scripts/lighting_cost.py --steps ... | {doc.get('machine', '?')} | "
            f"measured {span}; drawn {datetime.date.today().isoformat()} by {how}")


def write_report(doc, out_json):
    """docs/lighting.md §8.1 (between the markers) and docs/lighting_cost.png from the JSON."""
    sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
    import figures
    md_path = os.path.join(ROOT, "docs", "lighting.md")
    md = open(md_path).read()
    if MARK_BEGIN not in md or MARK_END not in md:
        sys.exit(f"lighting_cost.py: error: {md_path} has no {MARK_BEGIN} ... {MARK_END} block")
    cmd = doc.get("command", "scripts/lighting_cost.py")
    block = MARK_BEGIN + "\n\n" + report_markdown(doc) + "\n" + MARK_END
    md = md[:md.index(MARK_BEGIN)] + block + md[md.index(MARK_END) + len(MARK_END):]
    png = os.path.join(ROOT, "docs", "lighting_cost.png")
    plot(doc, png, provenance(doc, out_json, "scripts/lighting_cost.py --report"))
    tmp = md_path + ".tmp"
    open(tmp, "w").write(md)
    os.replace(tmp, md_path)
    print(f"wrote {md_path} §8.1 table and {png}")


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--sets", default="full")
    ap.add_argument("--lanes", default="", help="lanes to try for every set (default: the set's own)")
    ap.add_argument("--spec-guard", default="", help="spec_guard values to try for every set (default: the set's own)")
    ap.add_argument("--share", default="", help="share values (clocks per pass) to try for every set (default: the set's own)")
    ap.add_argument("--steps", default="generic,xc7,ecp5,cosim")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs", "lighting_cost.json"))
    ap.add_argument("--cosim-count", type=int, default=100000)
    ap.add_argument("--timeout", type=int, default=7200, help="seconds per synthesis step")
    ap.add_argument("--report", action="store_true",
                    help="only write docs/lighting.md §8.1's table and docs/lighting_cost.png from --out")
    ap.add_argument("--plot", metavar="PNG",
                    help="only redraw the figure of --out into PNG (docs/lighting.md is not touched)")
    a = ap.parse_args()
    if a.plot:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import figures
        figures.require("matplotlib")
        if not os.path.exists(a.out):
            sys.exit(f"lighting_cost.py: error: {a.out} does not exist")
        plot(json.load(open(a.out)), a.plot, provenance(json.load(open(a.out)), a.out, "scripts/lighting_cost.py --plot"))
        return
    if a.report:
        sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
        import figures
        figures.require("matplotlib")
        if not os.path.exists(a.out):
            sys.exit(f"lighting_cost.py: error: {a.out} does not exist")
        write_report(json.load(open(a.out)), a.out)
        return
    shadecore = os.path.join(a.build, "cli", "shadecore")
    if not os.access(shadecore, os.X_OK):
        sys.exit(f"lighting_cost.py: error: {shadecore} not found (build first: scripts/build.sh)")
    steps = [s for s in a.steps.split(",") if s]
    for s in steps:
        if s not in ("generic", "xc7", "ecp5", "cosim"):
            sys.exit(f"lighting_cost.py: error: unknown step '{s}' (generic, xc7, ecp5, cosim)")
    doc = {"rows": []}
    if os.path.exists(a.out):
        doc = json.load(open(a.out))
    src = source_hash()
    machine = f"{platform.node()} ({os.cpu_count()} cores, {platform.machine()})"
    yosys_v = one_line(subprocess.run(["yosys", "-V"], capture_output=True, text=True).stdout)
    cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    named = {f["name"]: f for f in cfg["feature_sets"]}
    for name in a.sets.split(","):
        if name not in named:
            sys.exit(f"lighting_cost.py: error: unknown feature set '{name}' (named: {', '.join(named)})")
        base = dict(named[name])
        lanes_list = [int(x) for x in a.lanes.split(",")] if a.lanes else [base.get("lanes", 1)]
        sg_list = [int(x) for x in a.spec_guard.split(",")] if a.spec_guard else [None]
        sh_list = [int(x) for x in a.share.split(",")] if a.share else [base.get("share", 1)]
        for lanes, sg, share in [(l, g, h) for l in lanes_list for g in sg_list for h in sh_list]:
            slots = len(base["lights"])
            if lanes > slots or (share > 1 and lanes != 1):
                continue
            fs = dict(base)
            fs["lanes"] = lanes
            fs["share"] = share
            if sg is not None:
                fs["spec_guard"] = sg
            fs.pop("_comment", None)
            with tempfile.TemporaryDirectory() as tmp:
                fs_file = os.path.join(tmp, f"{name}_lanes{lanes}.json")
                json.dump(fs, open(fs_file, "w"))
                sweep = os.path.join(tmp, "ls.json")
                run([shadecore, "light-sweep", "--features", fs_file, "--programs", "1", "--per-program", "1",
                     "--json", sweep], 600)
                info = json.load(open(sweep))
                guard = info["feature_set"]["spec_guard"]
                # rows of an earlier RTL kept for the record (`superseded`) are never updated
                row = next((r for r in doc["rows"] if r["set"] == name and r["lanes"] == lanes
                            and r.get("share", 1) == share
                            and r.get("spec_guard", 0) == guard and not r.get("superseded")), None)
                if row is None:
                    row = {"set": name, "lanes": lanes, "share": share, "spec_guard": guard}
                    doc["rows"].append(row)
                row.update({
                    "spec_guard": guard,
                    "share": share,
                    "design_point": (f"one light per lane per clock, spec_guard {guard}" if share == 1 else
                                     f"one light per {share} clocks (normalisers and dot-product multipliers "
                                     f"shared), spec_guard {guard}"),
                    "feature_key": info["feature_key"],
                    "verilog_params": info["verilog_params"],
                    "slots": slots,
                    "cycles_per_light": share / lanes,
                    "latency": info["latency"],
                    "latency_min": info["latency_min"],
                    "fragments_per_clock": {str(k): 1.0 / (share * max(1, math.ceil(k / lanes)))
                                            for k in (0, 1, 2, 4, 8) if k <= slots},
                })
                for st in steps:
                    if row.get("source", {}).get(st) == src and row.get(st + "_error") is None and st + "_s" in row:
                        print(f"{name} lanes {lanes} share {share} {st}: cached", flush=True)
                        continue
                    print(f"{name} lanes {lanes} share {share} {st} ...", flush=True)
                    t0 = time.time()
                    try:
                        if st == "generic":
                            res = step_generic(info["verilog_params"], a.timeout)
                        elif st == "xc7":
                            res = step_xc7(info["verilog_params"], a.timeout)
                        elif st == "ecp5":
                            res = step_ecp5(info["verilog_params"], a.timeout)
                        else:
                            res = step_cosim(shadecore, fs_file, a.cosim_count, a.timeout)
                        row.update(res)
                        row[st + "_error"] = None
                    except (RuntimeError, subprocess.TimeoutExpired) as e:
                        row[st + "_error"] = one_line(e)
                        print(f"  failed: {one_line(e)}", flush=True)
                    row[st + "_s"] = round(time.time() - t0, 1)
                    row.setdefault("source", {})[st] = src
                    row.setdefault("when", {})[st] = datetime.datetime.utcnow().strftime("%Y-%m-%d %H:%M UTC")
                    row.setdefault("command", {})[st] = "scripts/lighting_cost.py " + " ".join(sys.argv[1:])
                    doc.update({
                        "command": "scripts/lighting_cost.py " + " ".join(sys.argv[1:]),
                        "machine": machine, "yosys": yosys_v,
                        "date": datetime.datetime.utcnow().strftime("%Y-%m-%d"),
                        "method": "generic cells: synth -top sc_light; abc; stat -top sc_light (hierarchical); "
                                  "xc7: synth_xilinx -family xc7 -flatten; ecp5: synth_ecp5; cosim: shadecore "
                                  "cosim --core lighting --mode random, no stalls, SystemC testbench",
                    })
                    tmpf = a.out + ".tmp"
                    with open(tmpf, "w") as f:
                        json.dump(doc, f, indent=1)
                        f.write("\n")
                    os.replace(tmpf, a.out)
                    print(f"  {st}: {res if row[st + '_error'] is None else 'error'} ({row[st + '_s']} s)", flush=True)


if __name__ == "__main__":
    main()
