#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""ctest readme.numbers (issue 38): the numbers README.md states, each against the source that produced it.

    /usr/bin/python3 tests/readme_numbers_check.py [--build build]

| README statement | source |
|---|---|
| the nightly plan's size (tasks = shards, jobs), twice | regress/plans/nightly.json |
| the default suite's size (`ctest -LE long`: N tests) | `ctest --test-dir BUILD -N -LE long` |
| the cs16 forms' generic cells, CMOS transistors, ratios to schlick_div, SB_MAC16, HX8K MHz, latency | docs/tradeoffs.json (scripts/cost_report.py's flow) |
| cs16_compact's cell count in its handoff bundle (4,958) | docs/handoff.md's matrix table (the bundle's own flow) |
| full_shared's xc7 LUT / DSP48E1 and the XC7A35T's capacity | docs/lighting_cost.json (current row), scripts/lighting_cost.py |
| the table units' errors and crossovers | docs/table/crossover.json |
| the hard-case list's length at F = 16 | `shadecore vectors --mode hard` |
| the nightly run's vectors | docs/performance.md (the recorded run) |
| the tool versions | the installed tools (a tool that is not installed is skipped) |

| the Timing and energy section's closing periods (`name` after or "name closes at") | docs/timing.json (rows) |
Exit 0 when every number agrees, 1 otherwise (one line per disagreement, naming the README's text and the source)."""
import argparse
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
failures, checked = [], []


def num(s):
    return float(s.replace(",", ""))


def expect(what, readme_value, source_value, source):
    checked.append(what)
    if readme_value != source_value:
        failures.append(f"{what}: README says {readme_value}, {source} says {source_value}")


def find(readme, regex, what):
    m = re.search(regex, readme, re.S)
    if not m:
        failures.append(f"{what}: the README no longer has the statement /{regex}/ (update this check with it)")
    return m


def tool_version(cmd, regex):
    if shutil.which(cmd[0]) is None:
        return None
    r = subprocess.run(cmd, capture_output=True, text=True)
    m = re.search(regex, r.stdout + r.stderr)
    return m.group(1) if m else "?"


def dpkg_version(pkg):
    if shutil.which("dpkg-query") is None:
        return None
    r = subprocess.run(["dpkg-query", "-W", "-f=${Version}", pkg], capture_output=True, text=True)
    if r.returncode != 0 or not r.stdout:
        return None
    return re.sub(r"^\d+:", "", r.stdout).split("-")[0].split("+")[0]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"))
    a = ap.parse_args()
    readme = open(a.readme, encoding="utf-8").read()
    flat = " ".join(readme.split())

    # the nightly plan
    plan = json.load(open(os.path.join(ROOT, "regress", "plans", "nightly.json")))
    jobs, shards = len(plan["jobs"]), sum(j.get("shards", 1) for j in plan["jobs"])
    m = find(flat, r"The array has ([\d,]+) tasks \((\d+) jobs", "nightly plan size")
    if m:
        expect("nightly plan: array tasks", int(num(m.group(1))), shards, "regress/plans/nightly.json (sum of shards)")
        expect("nightly plan: jobs", int(m.group(2)), jobs, "regress/plans/nightly.json")
    m = find(flat, r"`nightly` takes .*?: (\d+) jobs, ([\d,]+) shards, all PASS, ([\d,]+) vectors", "nightly run")
    if m:
        # jobs the README names as added to the plan after the recorded run ("added since: `a`, `b` ... (run apart")
        since = re.search(r"[Aa]dded to the plan since that run: ((?:`[\w-]+`(?:, )?)+)", flat)
        added = re.findall(r"`([\w-]+)`", since.group(1)) if since else []
        names = {j["name"]: j.get("shards", 1) for j in plan["jobs"]}
        for x in added:
            expect("nightly run: a job added since", x in names, True, "regress/plans/nightly.json")
        rj, rs = jobs - len(added), shards - sum(names.get(x, 0) for x in added)
        expect("nightly run: jobs", int(m.group(1)), rj, "regress/plans/nightly.json less the jobs added since")
        expect("nightly run: shards", int(num(m.group(2))), rs, "regress/plans/nightly.json (sum of shards) less those added since")
        perf = open(os.path.join(ROOT, "docs", "performance.md"), encoding="utf-8").read()
        expect("nightly run: vectors", m.group(3) in perf, True, "docs/performance.md (the recorded run)")

    # the Timing and energy section: every closing period it names against docs/timing.json's row of that name
    sec = re.search(r"## Timing and energy.*?(?=\n## )", readme, re.S)
    tj = os.path.join(ROOT, "docs", "timing.json")
    if sec and os.path.exists(tj):
        rows = {r["name"]: r for r in json.load(open(tj))["rows"]}
        text = " ".join(sec.group(0).split())
        said = re.findall(r"([\d.]+)(?: ns)? \(`([\w+]+)`", text) + \
            [(v, n) for n, v in re.findall(r"\b([a-z][\w+]*) closes at ([\d.]+) ns", text)]
        cfg = json.load(open(os.path.join(ROOT, "config", "configs.json")))
        known = {v["name"] for v in cfg["variants"]} | {v["name"] + "+mreg" for v in cfg["variants"]} | \
            {f["name"] for f in cfg["feature_sets"]}
        for value, name in said:
            if name in known:  # a unit or lighting set (other words before "closes at" are not rows)
                expect(f"timing: {name} closes at", float(value), rows[name]["period_ns"] if name in rows else None,
                       "docs/timing.json")
        if not said:
            failures.append("README's Timing and energy section names no closing period (the check's patterns)")

    # the suite's size
    m = find(flat, r"`ctest -LE long`: ([\d,]+) tests", "suite size")
    if m:
        r = subprocess.run(["ctest", "--test-dir", a.build, "-N", "-LE", "long"], capture_output=True, text=True)
        t = re.search(r"Total Tests: (\d+)", r.stdout)
        if t:
            # Tests registered in tests/CMakeLists.txt since the build was last configured count too (a build
            # directory that is not reconfigured yet does not list them).
            listed = set(re.findall(r"Test\s+#\d+: (\S+)", r.stdout))
            src = open(os.path.join(ROOT, "tests", "CMakeLists.txt"), encoding="utf-8").read()
            new = [n for n in re.findall(r"add_test\(NAME ([\w.]+)\s", src) if n not in listed
                   and n not in subprocess.run(["ctest", "--test-dir", a.build, "-N", "-R", "^" + re.escape(n) + "$"],
                                               capture_output=True, text=True).stdout]
            if new:
                print(f"readme_numbers_check: note: {a.build} is not reconfigured yet: counting {', '.join(new)} too")
            expect("default suite size", int(num(m.group(1))), int(t.group(1)) + len(new),
                   f"ctest --test-dir {a.build} -N -LE long")
        else:
            failures.append(f"suite size: ctest -N gave no total ({r.stderr.strip()[:200]})")

    # the cs16 forms' table (scripts/cost_report.py's flow, docs/tradeoffs.json)
    trade = {r["variant"]: r for r in json.load(open(os.path.join(ROOT, "docs", "tradeoffs.json")))
             if r["config"] == "default"}
    base = trade["schlick_div"]
    for v in ("cs16", "cs16_faithful", "cs16_compact"):
        m = find(readme, r"\| `" + v + r"` \(\d\b[^|]*\|[^|]*(?:\\\|[^|]*)*\| ([\d,]+)(?: \(([\d.]+) × schlick_div\))? / "
                 r"([\d,]+)(?: \(([\d.]+) ×\))?[^|]*?(\d+) SB_MAC16[^|]*latency (\d+), HX8K (\d+) MHz", f"{v} row")
        if not m:
            continue
        r = trade[v]
        expect(f"{v}: generic cells", int(num(m.group(1))), r["cells"], "docs/tradeoffs.json")
        expect(f"{v}: CMOS transistors", int(num(m.group(3))), r["transistors"], "docs/tradeoffs.json")
        if m.group(2):
            expect(f"{v}: cells / schlick_div", m.group(2), f"{r['cells'] / base['cells']:.2f}", "docs/tradeoffs.json")
        if m.group(4):
            expect(f"{v}: transistors / schlick_div", m.group(4), f"{r['transistors'] / base['transistors']:.2f}",
                   "docs/tradeoffs.json")
        expect(f"{v}: SB_MAC16", int(m.group(5)), r["dsp_up5k"], "docs/tradeoffs.json")
        expect(f"{v}: latency", int(m.group(6)), r["latency"], "docs/tradeoffs.json")
        expect(f"{v}: HX8K MHz", int(m.group(7)), round(r["fmax_mhz"]), "docs/tradeoffs.json")
    m = find(flat, r"its `reports/yosys_synth.log` says ([\d,]+) for `cs16_compact` at the default width", "handoff cells")
    if m:
        h = re.search(r"^\| cs16_compact\.default \|(?:[^|]*\|){3} (\d+) \|",
                      open(os.path.join(ROOT, "docs", "handoff.md"), encoding="utf-8").read(), re.M)
        expect("cs16_compact handoff bundle cells", int(num(m.group(1))), int(h.group(1)) if h else None,
               "docs/handoff.md (matrix table)")

    # the lighting core
    sys.path.insert(0, os.path.join(ROOT, "scripts"))
    import lighting_cost
    rows = [r for r in json.load(open(os.path.join(ROOT, "docs", "lighting_cost.json")))["rows"]
            if r["set"] == "full_shared" and not r.get("superseded")]
    m = find(flat, r"`full_shared` is ([\d,]+) LUT / (\d+) DSP48E1 .*?holds ([\d,]+) / (\d+)", "full_shared cost")
    if m and rows:
        expect("full_shared xc7 LUT", int(num(m.group(1))), rows[-1]["x7_lut"], "docs/lighting_cost.json")
        expect("full_shared xc7 DSP48E1", int(m.group(2)), rows[-1]["x7_dsp48"], "docs/lighting_cost.json")
        expect("XC7A35T LUT", int(num(m.group(3))), lighting_cost.XC7A35T["lut"], "scripts/lighting_cost.py")
        expect("XC7A35T DSP48E1", int(m.group(4)), lighting_cost.XC7A35T["dsp"], "scripts/lighting_cost.py")

    # the table units
    xo = json.load(open(os.path.join(ROOT, "docs", "table", "crossover.json")))
    m = find(flat, r"more accurate for n ≥ (\d+) \(256 entries\) and n ≥ (\d+) \(1024 entries\)", "table crossovers")
    if m:
        expect("table256 crossover", int(m.group(1)), xo["table256"]["cs16_wins_from_n"], "docs/table/crossover.json")
        expect("table1024 crossover", int(m.group(2)), xo["table1024"]["cs16_wins_from_n"], "docs/table/crossover.json")
    m = find(flat, r"table256 ([\d.]+)·10⁻⁴ / ([\d.]+)·10⁻² / ([\d.]+) at n = 16 / 128 / 1024 \(table1024 ([\d.]+)·10⁻⁵ / "
             r"([\d.]+)·10⁻³ / ([\d.]+)\)", "table errors")
    if m:
        for i, (unit, n, scale) in enumerate((("table256", "16", 1e-4), ("table256", "128", 1e-2), ("table256", "1024", 1),
                                              ("table1024", "16", 1e-5), ("table1024", "128", 1e-3),
                                              ("table1024", "1024", 1))):
            said = m.group(i + 1)
            digits = len(said.split(".")[1]) if "." in said else 0
            expect(f"{unit} max error at n = {n}", said,
                   f"{xo[unit]['max_abs_total_at'][n] / scale:.{digits}f}", "docs/table/crossover.json")

    # the hard cases
    m = find(flat, r"the hard-case list \((\d+) at F = 16\)", "hard cases")
    if m:
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "hard.hex")
            r = subprocess.run([os.path.join(a.build, "cli", "shadecore"), "vectors", "--mode", "hard", "--out", out],
                               capture_output=True, text=True)
            n = None
            if r.returncode == 0:
                n = sum(1 for line in open(out) if line.strip() and not line.startswith("//"))
            expect("hard cases at F = 16", int(m.group(1)), n, "shadecore vectors --mode hard")

    # tool versions
    m = find(flat, r"\*\*Tool versions\.\*\*(.*?)checks these", "tool versions")
    if m:
        said = m.group(1)
        tools = [("GCC", tool_version(["gcc", "-dumpfullversion"], r"([\d.]+)")),
                 ("CMake", tool_version(["cmake", "--version"], r"version ([\d.]+)")),
                 ("Verilator", tool_version(["verilator", "--version"], r"Verilator ([\d.]+)")),
                 ("SystemC", dpkg_version("libsystemc-dev")),
                 ("Yosys", tool_version(["yosys", "-V"], r"Yosys ([\d.]+)")),
                 ("OpenSTA", tool_version(["sta", "-version"], r"([\d.]+)")),
                 ("Icarus Verilog", tool_version(["iverilog", "-V"], r"version ([\d.]+)")),
                 ("Mesa", dpkg_version("libosmesa6")),
                 ("Python", tool_version([sys.executable, "--version"], r"Python ([\d.]+)"))]
        import matplotlib
        import numpy
        tools += [("NumPy", numpy.__version__), ("matplotlib", matplotlib.__version__)]
        for name, have in tools:
            w = re.search(re.escape(name) + r" ([\d.]*\d)", said)
            if have is None:
                print(f"readme_numbers_check: note: {name} not installed here, its version not checked")
                continue
            expect(f"{name} version", w.group(1) if w else None, have, "the installed tool")

    for f in failures:
        print(f"readme_numbers_check: FAIL {f}")
    print(f"readme_numbers_check: {len(checked)} numbers checked, {'PASS' if not failures else 'FAIL'}")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
