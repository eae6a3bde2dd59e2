#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""The plot-overlap test (issue 38): every plotting script of scripts/ (and the Python example) drawn on its
recorded data (docs/*.json) or on small data generated here in seconds, and every figure checked after
layout: no two text boxes (titles, axis and tick labels, annotations, legend entries, footer) overlap and
none reaches outside the figure (matplotlib window extents of the texts actually drawn:
scripts/figures.py text_problems), and every figure names its command, machine and date in a footer.

    /usr/bin/python3 tests/figures_check.py [--build build] [--keep DIR]

Scripts that save through scripts/figures.py are checked through its SHADECORE_FIGURE_CHECK hook (so the
`shadecore sweep/fit/energy --plots` subprocesses are checked too); scripts/timing_report.py's plot and the
Python example are drawn in this process with Figure.savefig wrapped. Exit 0 all readable, 1 otherwise
(one line per problem)."""
import argparse
import contextlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
import figures  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.figure  # noqa: E402
import matplotlib.text  # noqa: E402

PY = sys.executable


def plain(path):
    """A figure's file name without the temporary-file decorations of the atomic saves
    ('.tradeoffs.png.tmp.123.tmp.png' -> 'tradeoffs.png')."""
    name = os.path.basename(path).lstrip(".")
    name = re.sub(r"\.tmp\.png$", "", name)
    return re.sub(r"\.tmp(\.\d+)?$", "", name)


def footer_ok(fig):
    """A footer naming command, machine and date (figures.footer: 'command | machine | date')."""
    return any(figures.FOOTER.search(t.get_text()) for t in fig.findobj(matplotlib.text.Text))


@contextlib.contextmanager
def in_process_check(results):
    """Wraps Figure.savefig: each figure saved is checked first (figures.text_problems) and recorded."""
    original = matplotlib.figure.Figure.savefig

    def checking_savefig(self, fname, *args, **kwargs):
        problems = figures.text_problems(self, kwargs.get("dpi"))
        if not footer_ok(self):
            problems.append("no footer naming command, machine and date")
        results.append({"path": os.path.abspath(str(fname)), "problems": problems})
        return original(self, fname, *args, **kwargs)

    matplotlib.figure.Figure.savefig = checking_savefig
    try:
        yield
    finally:
        matplotlib.figure.Figure.savefig = original


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--keep", help="write the figures into this directory (default: a temporary one)")
    a = ap.parse_args()
    exe = os.path.join(a.build, "cli", "shadecore")
    tmp = a.keep or tempfile.mkdtemp(prefix="figures_check.")
    os.makedirs(tmp, exist_ok=True)
    log = os.path.join(tmp, "checks.jsonl")
    if os.path.exists(log):
        os.unlink(log)
    # every figure drawn with a CPU name longer than any seen (the footer must fit whatever machine draws it)
    os.environ["SHADECORE_FIGURE_MACHINE"] = "AMD EPYC 7B13 64-Core Processor (a long model name, as CI has), 2 cores"
    env = dict(os.environ, SHADECORE_FIGURE_CHECK=log)
    failures = []
    expected = []  # figure paths that must have been checked

    def run(name, cmd, pngs):
        r = subprocess.run(cmd, env=env, cwd=ROOT, capture_output=True, text=True, timeout=300)
        got = []
        if os.path.exists(log):
            with open(log) as f:
                got = [json.loads(line) for line in f if line.strip()]
            os.unlink(log)
        if r.returncode != 0:
            failures.append(f"{name}: exit {r.returncode}: {(r.stderr or r.stdout).strip()[-400:]}")
            return
        match(name, pngs, got)

    def match(name, pngs, got):
        """The checks of one run, by file name (the scripts draw into temporary names or staging folders)."""
        by_name = {}
        for e in got:
            by_name.setdefault(plain(e["path"]), []).extend(e["problems"])
        for p in pngs:
            rel = os.path.relpath(p, tmp)
            if os.path.basename(p) not in by_name:
                failures.append(f"{rel} ({name}): not drawn or not checked")
                continue
            probs = by_name[os.path.basename(p)]
            failures.extend(f"{rel}: {q}" for q in probs)
            print(f"figures_check: {rel}: {'OK' if not probs else str(len(probs)) + ' problem(s)'}")
            expected.append(p)

    d = lambda *p: os.path.join(tmp, *p)  # noqa: E731
    # shadecore sweep --plots (scripts/plot_sweep.py): cs16, a unit with its own contract, a Schlick form, a table unit
    for v in ("cs16", "cs16_compact", "schlick_nr", "table256"):
        run(f"sweep --variant {v} --plots", [exe, "sweep", "--variant", v, "--n", "16..64", "--threads", "2",
                                             "--plots", d("sweep_" + v)],
            [d("sweep_" + v, f) for f in ("fig3_n64.png", "fig4_delta.png", "quant_ulp.png", "approx_over_n.png")])
    # shadecore fit / energy --plots (scripts/plot_fit.py)
    run("fit --plots", [exe, "fit", "--plots", d("fit")], [d("fit", "fig5_res.png")])
    run("energy --plots", [exe, "energy", "--model", "blinn_hf", "--n", "16..64", "--angles", "0,45,85",
                           "--threads", "2", "--plots", d("energy")],
        [d("energy", "energy_max_vs_n.png"), d("energy", "energy_vs_angle.png")])
    # scripts/plot_table_crossover.py on three small sweeps (both crossovers, 96 and 413, inside 16..480)
    sweeps = []
    for v in ("table256", "table1024", "cs16"):
        p = d(f"xo_{v}.json")
        r = subprocess.run([exe, "sweep", "--variant", v, "--n", "16..480", "--threads", "2", "--json", p],
                           capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            failures.append(f"sweep {v} for the crossover: exit {r.returncode}: {r.stderr.strip()}")
        sweeps.append(p)
    run("plot_table_crossover.py", [PY, "scripts/plot_table_crossover.py", "--out", d("crossover.png")] + sweeps,
        [d("crossover.png")])
    # scripts/cost_report.py --replot on the recorded docs/tradeoffs.json
    os.makedirs(d("cost"), exist_ok=True)
    for f in ("tradeoffs.json", "tradeoffs.md"):
        shutil.copy(os.path.join(ROOT, "docs", f), d("cost", f))
    run("cost_report.py --replot", [PY, "scripts/cost_report.py", "--replot", "--out", d("cost")],
        [d("cost", "tradeoffs.png")])
    # scripts/lighting_cost.py on the recorded docs/lighting_cost.json
    run("lighting_cost.py --plot", [PY, "scripts/lighting_cost.py", "--plot", d("lighting_cost.png")],
        [d("lighting_cost.png")])
    # scripts/brdf_sheet.py (small spheres)
    tool = os.path.join(a.build, "bench", "brdf_tool")
    if os.access(tool, os.X_OK):
        run("brdf_sheet.py", [PY, "scripts/brdf_sheet.py", "--tool", tool, "--size", "48", "--out", d("brdf.png")],
            [d("brdf.png")])
    else:
        print(f"figures_check: note: {tool} not built, brdf_sheet.py not checked")

    # scripts/timing_report.py's plot on the recorded docs/timing.json (drawn in this process)
    import timing_report
    rows = json.load(open(os.path.join(ROOT, "docs", "timing.json")))["rows"]
    results = []
    with in_process_check(results):
        timing_report.plot(d("timing.png"), rows, figures.footer("scripts/timing_report.py (rows: docs/timing.json)"))
    match("timing_report.plot", [d("timing.png")], results)
    # the Python package's example (needs build/python)
    pkg = os.path.join(a.build, "python")
    if os.path.isdir(pkg):
        ex = os.path.join(ROOT, "python", "examples", "cs16_vs_cos.py")
        r = subprocess.run([PY, "-c", f"""
import runpy, sys, json
sys.path[:0] = [{pkg!r}, {os.path.join(ROOT, 'tests')!r}, {os.path.join(ROOT, 'scripts')!r}]
import figures_check
res = []
sys.argv = [{ex!r}, "--out", {d('cs16_vs_cos.png')!r}]
with figures_check.in_process_check(res):
    runpy.run_path(sys.argv[0], run_name="__main__")
print("RESULTS " + json.dumps(res))
"""], cwd=ROOT, capture_output=True, text=True, timeout=300)
        if r.returncode != 0:
            failures.append(f"python/examples/cs16_vs_cos.py: exit {r.returncode}: {r.stderr.strip()[-400:]}")
        else:
            match("python/examples/cs16_vs_cos.py", [d("cs16_vs_cos.png")],
                  json.loads(r.stdout.split("RESULTS ", 1)[1]))
    if not a.keep:
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f"figures_check: FAIL {f}")
    print(f"figures_check: {len(expected)} figures, {'PASS' if not failures else 'FAIL'}")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
