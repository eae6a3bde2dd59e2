#!/usr/bin/python3
"""Plots for `shadecore sweep --plots DIR`: reads the CSV files the sweep wrote into DIR and
writes fig3_n128.png (cos^n θ and the variant at n = 128, the paper's Fig. 3), fig4_delta.png
(Δ = cos^n θ − f over n and 20·θ in [0, 30], the paper's Fig. 4), quant_ulp.png (quantisation
error in output ulps over n) and approx_over_n.png (max/min approximation error per n).
Each figure carries the command, machine and date in a footer. Files are written atomically."""
import argparse
import os

import figures  # scripts/figures.py: footer and atomic save
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


machine = figures.machine
save = figures.save


def load(path):
    return np.genfromtxt(path, delimiter=",", names=True)


def main():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--dir", required=True, help="directory with the sweep's CSV files; PNGs go here")
    ap.add_argument("--title", default="cs16", help="variant/format label for titles")
    ap.add_argument("--command", default="shadecore sweep --plots DIR", help="command for the footer")
    a = ap.parse_args()
    footer = figures.footer(a.command)

    f3 = load(os.path.join(a.dir, "fig3_n128.csv"))
    fig, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(f3["theta"], f3["cos_pow"], label=r"$\cos^{128}\theta$", lw=2)
    ax.plot(f3["theta"], f3["golden"], "--", label="variant (double)", lw=1.5)
    if not np.all(np.isnan(f3["fixed"])):
        ax.plot(f3["theta"], f3["fixed"], ":", label="variant (fixed point)", lw=1.5)
    ax.set_xlim(0, 0.6)
    ax.set_xlabel(r"$\theta$ [rad]")
    ax.set_ylabel("highlight")
    ax.set_title(f"Fig. 3: n = 128 — {a.title}")
    ax.legend()
    ax.grid(alpha=0.3)
    save(fig, os.path.join(a.dir, "fig3_n128.png"), footer)

    g = load(os.path.join(a.dir, "fig4_grid.csv"))
    ns = np.unique(g["n"])
    th = np.unique(g["theta"])
    z = g["delta"].reshape(len(ns), len(th))
    fig, ax = plt.subplots(figsize=(7, 4.6))
    lim = np.max(np.abs(z)) or 1.0
    im = ax.pcolormesh(20 * th, ns, z, shading="auto", cmap="RdBu_r", vmin=-lim, vmax=lim)
    fig.colorbar(im, ax=ax, label=r"$\Delta(\theta,n)=\cos^n\theta - f(\theta,n)$")
    ax.set_xlabel(r"$20\cdot\theta$")
    ax.set_ylabel("n")
    ax.set_title(f"Fig. 4: Δ over n and θ — {a.title} (max {z.max():.3g}, min {z.min():.3g})")
    save(fig, os.path.join(a.dir, "fig4_delta.png"), footer)

    r = load(os.path.join(a.dir, "per_n.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(r["n"], r["quant_max_ulp"], label="max (fixed − double)")
    ax.plot(r["n"], r["quant_min_ulp"], label="min (fixed − double)")
    ax.axhline(0.5, color="0.5", ls=":", lw=1)
    ax.axhline(-1.0, color="0.5", ls=":", lw=1)
    ax.set_xlabel("n")
    ax.set_ylabel("output ulps")
    ax.set_title(f"Quantisation error per n — {a.title}")
    ax.legend()
    ax.grid(alpha=0.3)
    save(fig, os.path.join(a.dir, "quant_ulp.png"), footer)

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(r["n"], r["approx_max"], label=r"max $\Delta$ (double)")
    ax.plot(r["n"], r["approx_min"], label=r"min $\Delta$ (double)")
    ax.plot(r["n"], r["total_max"], "--", label=r"max $\Delta$ (fixed point)")
    ax.plot(r["n"], r["total_min"], "--", label=r"min $\Delta$ (fixed point)")
    ax.axhline(1.7e-2, color="C3", ls=":", lw=1, label="published max 1.7e-2")
    ax.axhline(-9.7e-3, color="C4", ls=":", lw=1, label="published min −9.7e-3")
    ax.set_xlabel("n")
    ax.set_ylabel(r"$\cos^n\theta - f$")
    ax.set_title(f"Approximation error per n — {a.title}")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    save(fig, os.path.join(a.dir, "approx_over_n.png"), footer)


if __name__ == "__main__":
    main()
