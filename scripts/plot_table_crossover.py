#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Max |total error| against cos^n per n for the table units and cs16 (docs/table.md).

Reads the `per_n` rows of `shadecore sweep --json` files (total = cos^n − fixed/2^F, exhaustive over
every input code) and plots max(|total_max|, |total_min|) over n for each file, on a log scale, with
the crossover n where cs16 becomes more accurate than each table unit.

  scripts/plot_table_crossover.py --out docs/table/crossover.png \
      --note "shadecore sweep --config default --n 16..1024 --json ..., AMD EPYC 2 cores, 2026-11-29" \
      out/table/table256.json out/table/table1024.json out/table/cs16.json

Prints the crossover n per table file (first n from which cs16's max |total| stays below the table's)
and, with --json, writes them. Needs matplotlib (Debian's /usr/bin/python3).
"""
import argparse
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402  scripts/figures.py: footer, atomic save, the overlap check
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def load(path):
    with open(path) as f:
        j = json.load(f)
    rows = j.get("per_n")
    if not rows:
        sys.exit(f"plot_table_crossover: error: {path} has no per_n rows (a shadecore sweep --json file is needed)")
    ns = [r["n"] for r in rows]
    err = [max(abs(r["total_max"]), abs(r["total_min"])) for r in rows]
    return j["variant"], j["format"]["frac"], ns, err


def crossover(ns_t, e_t, ns_c, e_c):
    """Smallest n such that for every n' >= n (on the common grid) cs16's error < the table's."""
    c = dict(zip(ns_c, e_c))
    common = [(n, e) for n, e in zip(ns_t, e_t) if n in c]
    cross = None
    for n, e in reversed(common):
        if c[n] < e:
            cross = n
        else:
            break
    return cross


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", help="shadecore sweep --json files (one per variant; cs16 is the reference)")
    ap.add_argument("--out", required=True, help="PNG to write")
    ap.add_argument("--note", default="", help="provenance line printed under the plot (command, machine, date; "
                    "default: this command line, this machine, today)")
    ap.add_argument("--json", help="also write the crossovers and the errors at a few n as JSON")
    a = ap.parse_args()

    data = [load(p) for p in a.files]
    ref = [d for d in data if d[0] == "cs16"]
    if not ref:
        sys.exit("plot_table_crossover: error: no cs16 sweep among the files (it is the reference)")
    _, _, ns_c, e_c = ref[0]

    fig, ax = plt.subplots(figsize=(8, 5))
    styles = {"table256": ("tab:blue", "-"), "table1024": ("tab:green", "-"), "cs16": ("tab:red", "--")}
    summary = {}
    for variant, frac, ns, err in data:
        col, ls = styles.get(variant, (None, "-"))
        ax.plot(ns, err, ls, color=col, label=f"{variant} (F = {frac})")
        at = {n: e for n, e in zip(ns, err) if n in (16, 128, 1024)}
        entry = {"max_abs_total_at": at}
        if variant != "cs16":
            x = crossover(ns, err, ns_c, e_c)
            entry["cs16_wins_from_n"] = x
            if x is not None:
                ax.axvline(x, color=col, lw=0.8, ls=":")
                ax.annotate(f"cs16 better\nfrom n = {x}", xy=(x, max(err) * 0.5), color=col, fontsize=8,
                            xytext=(4, 0), textcoords="offset points")
            print(f"{variant}: cs16 more accurate (max |total|) for every n >= {x}")
        print(f"{variant}: max |total| " + ", ".join(f"n={n}: {e:.3e}" for n, e in sorted(at.items())))
        summary[variant] = entry
    ax.set_yscale("log")
    ax.set_xlabel("specular exponent n")
    ax.set_ylabel("max |cos^n θ − unit output| over every input code")
    ax.set_title("Table-and-interpolate (Mesa shine table) vs cs16: total error against cos^n")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    short = [os.path.basename(x) if os.path.isabs(x) else x for x in sys.argv[1:]]  # keeps the footer on the figure
    note = a.note or figures.footer("scripts/plot_table_crossover.py " + " ".join(short))
    figures.save(fig, a.out, note, dpi=120)
    if a.json:
        with open(a.json, "w") as f:
            json.dump(summary, f, indent=2)
            f.write("\n")


if __name__ == "__main__":
    main()
