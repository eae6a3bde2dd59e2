#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Plots for `shadecore fit --plots DIR` and `shadecore energy --plots DIR`.

--fit    reads DIR/fit_res.csv and writes fig5_res.png: res(n) = |2π·coef(n)·Int(n) − 1| per model
         (the paper's Fig. 5) for the published, least-squares and minimax coefficients, the paper's
         reading (θ up to θcr = 6/√n) and, for the Blinn rows, the hemisphere reading min(2θcr, π/2).
--energy reads DIR/energy.csv and writes energy_vs_angle.png (R(θi) for a few n per model) and
         energy_max_vs_n.png (max over θi of R per n).
Each figure carries the command, machine and date in a footer. Files are written atomically."""
import argparse
import csv
import datetime
import math
import os
from collections import defaultdict

import figures  # scripts/figures.py: footer, atomic save, import check

figures.require("numpy", "matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

TITLES = {
    "phong": "Phong (RDF)",
    "phong_mod": "Phong, modified",
    "blinn": "Blinn-Phong (RDF)",
    "blinn_mod": "Blinn-Phong, modified",
    "blinn_ndf": "Blinn-Phong (NDF)",
    "blinn_hf": "Blinn-Phong (heightfield)",
}
CLAIMS = {"phong": 4.7e-4, "phong_mod": 1.3e-3, "blinn": 1.5e-3, "blinn_mod": 9.5e-3}


machine = figures.machine
save = figures.save


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def fit_figure(d):
    """fig5_res.png: res(n) per model; the y range covers every plotted line (none hides below the axis)."""
    rows = read_csv(os.path.join(d, "fit_res.csv"))
    series = defaultdict(lambda: defaultdict(list))
    for r in rows:
        key = (r["model"], r["lobe"], r["reading"])
        for col in ("n", "res_published", "res_lsq", "res_minimax"):
            series[key][col].append(float(r[col]))
    models = [m for m in CLAIMS if any(k[0] == m for k in series)]
    if not models:
        models = sorted({k[0] for k in series})
    fig, axes = plt.subplots(2, 2, figsize=(10, 7), squeeze=False)
    for ax, m in zip(axes.flat, models):
        keys = [k for k in series if k[0] == m]
        paper = [k for k in keys if k[2] == "paper" and ("theta_cr" in k[1] or "cs16" not in k[1])]
        hemi = [k for k in keys if k[2] == "double_capped" and "theta_cr" in k[1]]
        for k in paper[:1]:
            s = series[k]
            n = np.array(s["n"])
            ax.semilogy(n, np.abs(s["res_published"]), "C0", lw=1, label="published, θ ≤ θcr (paper)")
            ax.semilogy(n, np.abs(s["res_lsq"]), "C1", lw=1, label="least squares, θ ≤ θcr")
            ax.semilogy(n, np.abs(s["res_minimax"]), "C2", lw=0.8, label="minimax, θ ≤ θcr")
        for k in hemi[:1]:
            s = series[k]
            ax.semilogy(s["n"], np.abs(s["res_published"]), "C3--", lw=1, label="published, θ ≤ min(2θcr, π/2)")
        if m in CLAIMS:
            ax.axhline(CLAIMS[m], color="k", lw=0.8, ls=":", label=f"claimed max {CLAIMS[m]:.1e}")
        ax.set_title(TITLES.get(m, m))
        ax.set_xlabel("n")
        ax.set_ylabel("res(n) = |2π·coef(n)·Int(n) − 1|")
        # The y range follows the data: the floor is a decade below the 5th percentile of the lowest line
        # (so every line is visible, also fits that are exact to rounding, while the isolated dips where
        # a residual changes sign do not stretch the axis over many empty decades).
        lows, top = [], 1.0
        for line in ax.get_lines():
            y = np.asarray(line.get_ydata(), dtype=float)
            y = y[np.isfinite(y) & (y > 0)]
            if y.size:
                lows.append(np.percentile(y, 5))
                top = max(top, float(y.max()))
        floor = 10.0 ** (math.floor(math.log10(min(lows))) - 1) if lows else 1e-9
        ax.set_ylim(floor, top * 2)
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=6)
    for ax in list(axes.flat)[len(models):]:
        ax.axis("off")
    return fig


def plot_fit(d, footer):
    figures.save_all({"fig5_res.png": fit_figure(d)}, d, footer)


def energy_figures(d):
    rows = read_csv(os.path.join(d, "energy.csv"))
    data = defaultdict(lambda: defaultdict(dict))  # model -> n -> angle -> R
    for r in rows:
        data[r["model"]][int(r["n"])][float(r["theta_i_deg"])] = float(r["R"])
    models = [m for m in TITLES if m in data]
    fig, axes = plt.subplots(2, 3, figsize=(12, 7), squeeze=False)
    for ax, m in zip(axes.flat, models):
        ns = sorted(data[m])
        pick = sorted({min(ns, key=lambda x: abs(x - t)) for t in (16, 64, 256, 1024)})
        for i, n in enumerate(pick):
            angs = sorted(data[m][n])
            ax.plot(angs, [data[m][n][a] for a in angs], marker="o", ms=3, lw=1, color=f"C{i}", label=f"n = {n}")
        ax.axhline(1.0, color="k", lw=0.8, ls=":")
        ax.set_title(TITLES[m])
        ax.set_xlabel("incidence θi (degrees)")
        ax.set_ylabel("R(θi) = ∫ f_r cos θo dωo")
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7)
    for ax in list(axes.flat)[len(models):]:
        ax.axis("off")
    out = {"energy_vs_angle.png": fig}

    fig, ax = plt.subplots(figsize=(8, 5))
    for i, m in enumerate(models):
        ns = sorted(data[m])
        ax.plot(ns, [max(data[m][n].values()) for n in ns], lw=1, color=f"C{i}", label=TITLES[m])
    ax.axhline(1.0, color="k", lw=0.8, ls=":")
    ax.set_xlabel("n")
    ax.set_ylabel("max over θi of R(θi)")
    ax.set_title("Energy check: maximum directional-hemispherical reflectance per n (fixed point)")
    ax.grid(True, lw=0.3)
    ax.legend(fontsize=7)
    out["energy_max_vs_n.png"] = fig
    return out


def plot_energy(d, footer):
    figures.save_all(energy_figures(d), d, footer)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--dir", required=True, help="directory with the CSV files; PNGs are written there")
    ap.add_argument("--fit", action="store_true", help="plot fit_res.csv")
    ap.add_argument("--energy", action="store_true", help="plot energy.csv")
    ap.add_argument("--caption", default="shadecore fit --plots DIR", help="command and date for the footer")
    a = ap.parse_args()
    footer = f"{a.caption} | {machine()} | plotted {datetime.date.today().isoformat()}"
    if not (a.fit or a.energy):
        ap.error("give --fit and/or --energy")
    if a.fit:
        plot_fit(a.dir, footer)
    if a.energy:
        plot_energy(a.dir, footer)


if __name__ == "__main__":
    figures.run(main)
