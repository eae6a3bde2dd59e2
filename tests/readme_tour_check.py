#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""ctest readme.tour (issue 38): runs the README's "Already built? Try these" commands — taken from the README
itself, between its `readme-tour` markers, so the README and this test cannot drift — and checks that each
finishes within a minute and prints every line shown under it (whitespace-insensitive; `…` stands for any text).

    /usr/bin/python3 tests/readme_tour_check.py [--build build] [--limit 60]

`build/cli/shadecore` in a command is replaced by --build's, `out/` by a temporary folder (nothing is written into
the checkout). A lighting core built on first use is not counted against the limit (the README says so: its
build time is printed as "+X s core build" and subtracted). Exit 0 all as the README says, 1 otherwise."""
import argparse
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN, END = "<!-- readme-tour: begin", "<!-- readme-tour: end -->"


def tour(readme):
    """[(command, [expected lines])] from the README's tour block: `    $ cmd` lines and the indented lines after."""
    text = open(readme, encoding="utf-8").read()
    if BEGIN not in text or END not in text:
        raise SystemExit(f"readme_tour_check: {readme} has no readme-tour markers")
    block = text[text.index(BEGIN):text.index(END)]
    steps = []
    for line in block.splitlines():
        if line.startswith("    $ "):
            steps.append((line[6:].strip(), []))
        elif line.startswith("    ") and line.strip() and steps:
            steps[-1][1].append(line.strip())
    return steps


def pattern(expected):
    """An expected line as a regular expression: whitespace runs match any whitespace, `…` any text."""
    parts = [r"\s+".join(re.escape(w) for w in chunk.split()) for chunk in expected.split("…")]
    return re.compile(".*?".join(parts))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--limit", type=float, default=60.0, help="seconds per command (default 60)")
    ap.add_argument("--readme", default=os.path.join(ROOT, "README.md"))
    a = ap.parse_args()
    steps = tour(a.readme)
    if len(steps) != 5:
        print(f"readme_tour_check: FAIL: the README's tour has {len(steps)} commands, the README promises five")
        return 1
    tmp = tempfile.mkdtemp(prefix="readme_tour.")
    exe = os.path.join(os.path.abspath(a.build), "cli", "shadecore")
    failures = []
    try:
        for cmd, expected in steps:
            argv = shlex.split(cmd)
            if argv[0] == "build/cli/shadecore":
                argv[0] = exe
            argv = [os.path.join(tmp, x[4:]) if x.startswith("out/") else x for x in argv]
            t0 = time.monotonic()
            try:
                r = subprocess.run(argv, cwd=ROOT, capture_output=True, text=True, timeout=max(600, 5 * a.limit))
            except subprocess.TimeoutExpired:
                failures.append(f"`{cmd}`: did not finish")
                continue
            wall = time.monotonic() - t0
            out = r.stdout + r.stderr
            build = sum(float(x) for x in re.findall(r"\+([\d.]+) s core build", out))
            state = f"exit {r.returncode}, {wall:.1f} s" + (f" ({build:.1f} s of it building a core)" if build else "")
            if r.returncode != 0:
                failures.append(f"`{cmd}`: {state}: {out.strip()[-300:]}")
            if wall - build > a.limit:
                failures.append(f"`{cmd}`: took {wall - build:.1f} s (limit {a.limit:g} s)")
            flat = " ".join(out.split())
            for e in expected:
                if not pattern(e).search(flat):
                    failures.append(f"`{cmd}`: does not print the README's line: {e}")
            print(f"readme_tour_check: {cmd}: {state}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    for f in failures:
        print(f"readme_tour_check: FAIL {f}")
    print(f"readme_tour_check: {len(steps)} commands, {'PASS' if not failures else 'FAIL'}")
    return 0 if not failures else 1


if __name__ == "__main__":
    sys.exit(main())
