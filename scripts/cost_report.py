#!/usr/bin/python3
"""What accuracy costs: for every variant and width configuration in config/configs.json, gather
  * error      — `shadecore sweep --json` (exhaustive over every code, n range as given),
  * latency and simulation speed — `shadecore cosim --json` (random stimulus, one shard),
  * area/depth — Yosys generic synthesis of rtl/sc_specular.v (`synth -flatten; abc; stat; ltp -noff`),
  * iCE40      — `synth_ice40` logic cells, and where the design fits an HX8K (ct256), place and route
                 with nextpnr-ice40 and the clock rate from icetime (LUT logic only: no DSP blocks, so
                 nextpnr's DSP timing gap does not apply),
and write docs/tradeoffs.md (a table, generated, do not edit) and docs/tradeoffs.png (error against cost).
Long: several minutes per (variant, width); run it by hand, it is not a test."""
import argparse
import concurrent.futures as cf
import datetime
import json
import os
import re
import subprocess
import sys
import tempfile

import figures  # scripts/figures.py: machine line

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
HX8K_LCS = 7680


machine = figures.machine


def run(cmd, cwd=None, timeout=3600):
    p = subprocess.run(cmd, cwd=cwd, capture_output=True, text=True, timeout=timeout)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}): {(p.stderr or p.stdout).strip()[-400:]}")
    return p.stdout


INCDIR = os.path.join(ROOT, "rtl")  # sc_variants.vh (generated from config/configs.json by CMake)


def rtl_files():
    return sorted(os.path.join(ROOT, "rtl", f) for f in os.listdir(os.path.join(ROOT, "rtl")) if f.endswith(".v"))


def chparams(variant_id, cfg):
    return f"chparam -set VARIANT {variant_id} -set FRAC {cfg['frac']} -set GUARD {cfg['guard']} sc_specular"


def yosys_generic(variant_id, cfg):
    script = (f"read_verilog -I{INCDIR} {' '.join(rtl_files())}; {chparams(variant_id, cfg)}; "
              "synth -flatten -top sc_specular; abc; opt_clean; stat; ltp -noff")
    out = run(["yosys", "-q", "-p", script.replace("stat;", "tee -o /dev/stdout stat;")
               .replace("ltp -noff", "tee -o /dev/stdout ltp -noff")])
    cells = [int(m) for m in re.findall(r"Number of cells:\s+(\d+)", out)]
    ffs = sum(int(m) for m in re.findall(r"\$_S?DFFE?_\w+\s+(\d+)", out))
    depth = re.findall(r"Longest topological path in \S+ \(length=(\d+)\)", out)
    return {"cells": cells[-1] if cells else None, "ffs": ffs, "depth": int(depth[-1]) if depth else None}


def ice40(variant_id, cfg, tmp):
    js = os.path.join(tmp, "ice40.json")
    out = run(["yosys", "-q", "-p",
               f"read_verilog -I{INCDIR} {' '.join(rtl_files())}; {chparams(variant_id, cfg)}; "
               f"synth_ice40 -top sc_specular -json {js}; tee -o /dev/stdout stat"])
    lcs = re.findall(r"SB_LUT4\s+(\d+)", out)
    dffs = sum(int(m) for m in re.findall(r"SB_DFF\w*\s+(\d+)", out))
    res = {"luts": int(lcs[-1]) if lcs else None, "dffs": dffs, "fmax_mhz": None, "pnr": "not run"}
    if res["luts"] is None or res["luts"] + 0 > HX8K_LCS:
        res["pnr"] = "does not fit an HX8K"
        return res
    asc = os.path.join(tmp, "x.asc")
    try:
        run(["nextpnr-ice40", "--hx8k", "--package", "ct256", "--json", js, "--asc", asc, "--freq", "40",
             "--timing-allow-fail", "--pcf-allow-unconstrained", "--seed", "1"])
        rpt = run(["icetime", "-d", "hx8k", "-P", "ct256", "-m", "-t", asc])
        m = re.search(r"\(([\d.]+) MHz\)", rpt)
        res["fmax_mhz"] = float(m.group(1)) if m else None
        res["pnr"] = "HX8K ct256"
    except RuntimeError as e:
        res["pnr"] = f"failed: {str(e)[-120:]}"
    return res


def evaluate(cli, variant, cfg, n_range, cosim_count):
    tag = f"{variant['name']}/{cfg['name']}"
    row = {"variant": variant["name"], "config": cfg["name"], "frac": cfg["frac"], "guard": cfg["guard"]}
    with tempfile.TemporaryDirectory() as tmp:
        sj = os.path.join(tmp, "sweep.json")
        try:
            run([cli, "sweep", "--variant", variant["name"], "--config", cfg["name"], "--n", n_range,
                 "--threads", "1", "--no-progress", "--json", sj])
            s = json.load(open(sj))
            row.update(quant_max=s["quant_ulp"]["max"]["value"], quant_min=s["quant_ulp"]["min"]["value"],
                       total_max=s["total"]["max"]["value"], total_min=s["total"]["min"]["value"],
                       sweep_n=n_range)
        except RuntimeError as e:
            row["sweep_error"] = str(e)
        cj = os.path.join(tmp, "cosim.json")
        try:
            run([cli, "cosim", "--variant", variant["name"], "--config", cfg["name"], "--mode", "random",
                 "--count", str(cosim_count), "--shards", "1", "--seed", "1", "--json", cj])
            c = json.load(open(cj))
            row.update(latency=c["latency_spec"], vectors_per_s=c["vectors_per_s"], cycles=c["cycles"],
                       vectors=c["vectors"], mismatches=c["mismatches"])
        except (RuntimeError, KeyError) as e:
            row["cosim_error"] = str(e)
        try:
            row.update(yosys_generic(variant["id"], cfg))
        except RuntimeError as e:
            row["yosys_error"] = str(e)
        try:
            row.update(ice40(variant["id"], cfg, tmp))
        except RuntimeError as e:
            row["ice40_error"] = str(e)
    print(f"cost_report: {tag} done", file=sys.stderr, flush=True)
    return row


def fmt(v, spec):
    return "—" if v is None else format(v, spec)


def check_out_dir(out):
    """--out may be missing (it is created when the report is written), but it must be creatable: the
    nearest existing ancestor is a writable directory. Checked before the long run."""
    d = os.path.abspath(out)
    if os.path.exists(d):
        if not os.path.isdir(d):
            sys.exit(f"cost_report: error: --out {out} is not a directory")
    else:
        anc = d
        while not os.path.exists(anc):
            anc = os.path.dirname(anc)
        if not os.path.isdir(anc):
            sys.exit(f"cost_report: error: cannot create --out {out}: {anc} is not a directory")
        d = anc
    if not os.access(d, os.W_OK):
        sys.exit(f"cost_report: error: cannot write to {d}")


def plot(rows, path, footer):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(13, 4.2))
    for var in sorted({r["variant"] for r in rows}):
        rs = [r for r in rows if r["variant"] == var and r.get("quant_max") is not None]
        if not rs:
            continue
        # Quantisation error in absolute units: what the width buys (the approximation error of each
        # function, 1.7e-2 for cs16 and 0.20 for Schlick, does not depend on the width).
        err = [max(abs(r["quant_max"]), abs(r["quant_min"])) * 2.0 ** -r["frac"] for r in rs]
        for ax, key, label in ((axes[0], "luts", "iCE40 LUT4s"), (axes[1], "latency", "latency [cycles]"),
                               (axes[2], "vectors_per_s", "co-simulation vectors/s")):
            pts = [(r.get(key), e, r["config"]) for r, e in zip(rs, err) if r.get(key) is not None]
            if not pts:
                continue
            ax.plot([p[0] for p in pts], [p[1] for p in pts], "o-", label=var)
            for x, y, name in pts:
                ax.annotate(name, (x, y), fontsize=6, xytext=(3, 3), textcoords="offset points")
            ax.set_xlabel(label)
    for ax in axes:
        ax.set_yscale("log")
        ax.set_ylabel("max |fixed − double of the same function|")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("What accuracy costs: quantisation error (absolute) against area, latency and simulation speed",
                 fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 1))
    fig.text(0.01, 0.005, footer, fontsize=6, color="0.35")
    try:
        fig.savefig(path, dpi=120, format="png")
    finally:
        plt.close(fig)


def write_report(rows, cmd, out):
    """docs/tradeoffs.md (table), tradeoffs.json (rows) and tradeoffs.png from the measured rows."""
    footer = figures.footer(cmd)
    lines = [
        "# What accuracy costs — error against latency, clock rate, area and simulation speed",
        "",
        "<!-- generated by scripts/cost_report.py, do not edit -->",
        f"Command: `{cmd.strip()}`  ",
        f"Machine: {machine()}; date: {datetime.date.today().isoformat()}; "
        f"Yosys 0.23, nextpnr-ice40 0.4, icetime, Verilator 5.006 + SystemC 2.3.4.",
        "",
        "Errors are exhaustive over every input code for the n range in the *sweep n* column (`shadecore sweep`); *quant* is the "
        "fixed-point output against the double version of the same variant (output ulps), *total* is "
        "cos^n θ − output. Latency is the unit's documented pipeline latency, checked by the co-simulation; "
        "sim speed is one SystemC co-simulation process (random stimulus, scoreboard on every transaction), "
        "vectors checked per second of wall time including the simulator's start-up and elaboration; "
        "G (guard bits) is a cs16 parameter only. "
        "Generic cells/depth: Yosys `synth -flatten; abc` (gate count and longest path in gates). iCE40: "
        "`synth_ice40` LUT4/DFF counts; Fmax from icetime after nextpnr place and route on an HX8K (ct256), "
        "only where the design fits (the HX8K has no DSP blocks, so multipliers are LUT logic).",
        "",
        "| variant | F | G | sweep n | quant max/min (ulp) | total max | total min | latency | sim vectors/s | generic cells | FFs | depth | iCE40 LUT4 | iCE40 DFF | Fmax HX8K (MHz) |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['variant']} | {r['frac']} | {r['guard'] if r['variant'] == 'cs16' else '—'} | {r.get('sweep_n', '—')} | "
            f"{fmt(r.get('quant_max'), '+.3f')} / {fmt(r.get('quant_min'), '+.3f')} | "
            f"{fmt(r.get('total_max'), '.3e')} | {fmt(r.get('total_min'), '.3e')} | {fmt(r.get('latency'), 'd')} | "
            f"{fmt(r.get('vectors_per_s'), ',.0f')} | {fmt(r.get('cells'), 'd')} | {fmt(r.get('ffs'), 'd')} | "
            f"{fmt(r.get('depth'), 'd')} | {fmt(r.get('luts'), 'd')} | {fmt(r.get('dffs'), 'd')} | "
            f"{fmt(r.get('fmax_mhz'), '.1f') if r.get('fmax_mhz') else r.get('pnr', '—')} |")
    errs = [f"- {r['variant']}/{r['config']}: {k}: {r[k]}" for r in rows for k in r if k.endswith("_error")]
    if errs:
        lines += ["", "Steps that failed (reported, not hidden):", ""] + errs
    lines += ["", "Reading it: the approximation error of each function (cs16 ≈ 1.7·10⁻², Schlick ≈ 0.20 against "
              "cos^n) does not depend on the width; the width buys quantisation error (≤ 1 ulp = 2^−F), which "
              "the plot shows in absolute units against cost.", "",
              "![error against cost](tradeoffs.png)", ""]
    # All three or none: written to temporary files in OUT (created if missing), renamed together at the end.
    created = []
    d = os.path.abspath(out)
    while not os.path.exists(d):
        created.append(d)
        d = os.path.dirname(d)
    for c in reversed(created):
        os.mkdir(c)
    tmps = {name: os.path.join(out, f".{name}.tmp.{os.getpid()}") for name in ("tradeoffs.md", "tradeoffs.json", "tradeoffs.png")}
    try:
        with open(tmps["tradeoffs.md"], "w") as f:
            f.write("\n".join(lines))
        with open(tmps["tradeoffs.json"], "w") as f:
            f.write(json.dumps(rows, indent=2) + "\n")
        plot(rows, tmps["tradeoffs.png"], footer)
    except BaseException:
        for t in tmps.values():
            if os.path.exists(t):
                os.unlink(t)
        for c in created:
            os.rmdir(c)
        raise
    for name, t in tmps.items():
        os.replace(t, os.path.join(out, name))
    print("\n".join(lines))


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"), help="CMake build directory")
    ap.add_argument("--variants", default="", help="comma-separated variant names (default: all)")
    ap.add_argument("--configs", default="", help="comma-separated config names (default: all)")
    ap.add_argument("--n", default="16..1024", help="sweep n range")
    ap.add_argument("--n-for", action="append", default=[], metavar="CONFIG=RANGE",
                    help="sweep n range for one config (e.g. wide=16..64: the wide sweep is 17 G evaluations)")
    ap.add_argument("--cosim-count", type=int, default=1000000, help="random co-simulation transactions")
    ap.add_argument("--jobs", type=int, default=1,
                    help="parallel (variant, width) jobs; >1 is faster but makes the speed figures noisy")
    ap.add_argument("--out", default=os.path.join(ROOT, "docs"), help="directory for tradeoffs.md/.png/.json")
    ap.add_argument("--replot", action="store_true",
                    help="only redraw tradeoffs.png from OUT/tradeoffs.json (no synthesis or simulation)")
    a = ap.parse_args()
    a.cli = os.path.join(a.build, "cli", "shadecore")
    # Everything that can fail quickly is checked before the long run: the plotting modules, the output
    # directory, the build.
    figures.require("matplotlib")
    check_out_dir(a.out)
    if a.replot:
        if not os.path.exists(os.path.join(a.out, "tradeoffs.json")):
            sys.exit(f"cost_report: error: no {a.out}/tradeoffs.json to replot (run without --replot first)")
        rows = json.load(open(os.path.join(a.out, "tradeoffs.json")))
        md = open(os.path.join(a.out, "tradeoffs.md")).read()
        m = re.search(r"Command: `([^`]*)`", md)
        write_report(rows, m.group(1) if m else "scripts/cost_report.py", a.out)
        return
    if not os.access(a.cli, os.X_OK):
        sys.exit(f"cost_report: error: {a.cli} is not an executable (build first: scripts/build.sh)")
    # The iCE40 flow is not part of the default setup; install it the same way (idempotent, quiet).
    try:
        run([os.path.join(ROOT, "scripts", "setup.sh"), "nextpnr-ice40", "fpga-icestorm", "yosys"])
    except RuntimeError as e:
        sys.exit(f"cost_report: error: {e}")
    cfgs = json.load(open(os.path.join(ROOT, "config", "configs.json")))
    variants = [v for v in cfgs["variants"] if not a.variants or v["name"] in a.variants.split(",")]
    configs = [c for c in cfgs["configs"] if not a.configs or c["name"] in a.configs.split(",")]
    if not variants or not configs:
        sys.exit("cost_report: error: no variant/config selected")
    n_for = {}
    for item in a.n_for:
        name, sep, rng = item.partition("=")
        if not sep or not re.fullmatch(r"\d+(\.\.\d+)?", rng):
            sys.exit(f"cost_report: error: malformed --n-for '{item}' (expected CONFIG=LO..HI)")
        n_for[name] = rng
    jobs = [(v, c) for v in variants for c in configs]
    with cf.ThreadPoolExecutor(max_workers=a.jobs) as ex:
        rows = list(ex.map(lambda vc: evaluate(a.cli, vc[0], vc[1], n_for.get(vc[1]["name"], a.n), a.cosim_count),
                           jobs))

    write_report(rows, "scripts/cost_report.py " + " ".join(sys.argv[1:]), a.out)


if __name__ == "__main__":
    try:
        main()
    except KeyboardInterrupt:
        sys.exit("cost_report: interrupted")
