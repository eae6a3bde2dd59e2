#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Plots for `shadecore sweep --plots DIR`: reads the CSV files the sweep wrote into DIR and writes
fig3_n128.png (cos^n θ and the unit at n = 128, the paper's Fig. 3, with the fixed-point error in a
second panel; when 128 is outside the swept range, fig3_n<N>.png at the swept N nearest to it, --fig3-n), fig4_delta.png (Δ = cos^n θ − f over n and θ, the paper's Fig. 4, whose axis is 20·θ),
quant_ulp.png (quantisation error in output ulps per n against the contract's bounds) and
approx_over_n.png (max/min approximation error per n).
Each figure carries the command, machine and date in a footer. Files are written atomically."""
import argparse
import os

import figures  # scripts/figures.py: footer, atomic save, import check

figures.require("numpy", "matplotlib")
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.colors import TwoSlopeNorm  # noqa: E402

machine = figures.machine
save = figures.save


def load(path):
    return np.genfromtxt(path, delimiter=",", names=True)


def quant_bounds(a):
    """The variant's contract on f_fixed − f_double in output ulps as the sweep passed it (--contract-*: from
    quant_contract(), the source of its verdict), or None when the script runs without them."""
    if a.contract_lo is None or a.contract_hi is None:
        return None
    lo_rel = "<" if a.contract_lo_strict else "≤"
    return a.contract_lo, a.contract_hi, f"{a.contract_lo:+.4f} ({lo_rel} quant)", f"{a.contract_hi:+.4f}"


def fig3_name(n):
    return f"fig3_n{n}"


def fig3(d, unit, frac, n=128, n_range=None):
    f3 = load(os.path.join(d, fig3_name(n) + ".csv"))
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(7, 6), sharex=True, gridspec_kw={"height_ratios": [3, 1.4]})
    ax.plot(f3["theta"], f3["cos_pow"], label=rf"$\cos^{{{n}}}\theta$", lw=2)
    ax.plot(f3["theta"], f3["golden"], "--", label=f"{unit} (double)", lw=1.5)
    has_fixed = not np.all(np.isnan(f3["fixed"]))
    if has_fixed:
        ax.plot(f3["theta"], f3["fixed"], ":", label=f"{unit} (fixed point, F = {frac})", lw=1.5)
    ax.set_xlim(0, 0.6)
    ax.set_ylabel("highlight")
    title = f"Fig. 3: n = {n} — {unit}"
    if n != 128:  # the paper's n = 128 was not swept: say so, not silently another figure
        where = f" {n_range}" if n_range else ""
        title += f"\n(the paper's n = 128 is outside the swept range{where}; n = {n} is the nearest swept n)"
    ax.set_title(title)
    ax.legend()
    ax.grid(alpha=0.3)
    # The fixed-point and double curves coincide at this scale: their difference, in output ulps, against
    # the double function of the same input code (the contract's quantisation error; the input rounding
    # of θ to a code is not part of it).
    if has_fixed:
        ref = f3["golden_at_code"] if "golden_at_code" in f3.dtype.names else f3["golden"]
        err = (f3["fixed"] - ref) * 2.0 ** frac
        ax2.plot(f3["theta"], err, lw=0.8, color="C2", label=f"{unit}: fixed − double of the same input code")
        ax2.legend(fontsize=7)
    ax2.axhline(0, color="0.5", lw=0.6)
    ax2.set_xlabel(r"$\theta$ [rad]")
    ax2.set_ylabel("fixed − double\n[output ulps]")
    ax2.grid(alpha=0.3)
    return fig


def fig4(d, unit, approx_max=None, approx_min=None):
    g = load(os.path.join(d, "fig4_grid.csv"))
    ns = np.unique(g["n"])
    th = np.unique(g["theta"])
    z = g["delta"].reshape(len(ns), len(th))
    fig, ax = plt.subplots(figsize=(7, 4.8))
    zmax, zmin = float(z.max()), float(z.min())
    span = max(abs(zmax), abs(zmin)) or 1.0
    if zmin < -0.01 * span and zmax > 0.01 * span:
        # Both signs matter: a diverging scale centred on 0 (each side to its own extreme).
        im = ax.pcolormesh(th, ns, z, shading="auto", cmap="RdBu_r", norm=TwoSlopeNorm(0.0, zmin, zmax))
    else:
        # One-signed (up to rounding noise): a sequential scale over the data's own range.
        im = ax.pcolormesh(th, ns, z, shading="auto", cmap="viridis", vmin=zmin, vmax=zmax)
    fig.colorbar(im, ax=ax, label=r"$\Delta(\theta,n)=\cos^n\theta - f(\theta,n)$")
    ax.set_xlabel(r"$\theta$ [rad]")
    top = ax.secondary_xaxis("top", functions=(lambda x: 20 * x, lambda x: x / 20))
    top.set_xlabel(r"$20\cdot\theta$ (the axis of the paper's Fig. 4)", fontsize=8)
    ax.set_ylabel("n")
    title = f"Fig. 4: Δ over n and θ — {unit}\non this θ grid ({len(th)} points): max {zmax:.3g}, min {zmin:.3g}"
    if approx_max is not None and approx_min is not None:
        title += f"\nover every input code (the sweep): max {approx_max:.3g}, min {approx_min:.3g}"
    ax.set_title(title)
    return fig


def quant(d, unit, a):
    r = load(os.path.join(d, "per_n.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(r["n"], r["quant_max_ulp"], label="max over codes (fixed − double)")
    ax.plot(r["n"], r["quant_min_ulp"], label="min over codes (fixed − double)")
    bounds = quant_bounds(a)
    title = f"Quantisation error per n — {unit}"
    if bounds:  # the sweep's own contract (the one its verdict on stdout checks)
        lo, hi, lo_text, hi_text = bounds
        name = f"'{a.contract_name}' " if a.contract_name else ""
        ax.axhline(hi, color="C3", ls=":", lw=1, label=f"contract {name}upper bound {hi_text}")
        ax.axhline(lo, color="C4", ls=":", lw=1, label=f"contract {name}lower bound {lo_text}")
    else:
        title += "\n(no contract lines: drawn without the sweep's --contract-lo/--contract-hi)"
    ax.set_xlabel("n")
    ax.set_ylabel("output ulps")
    ax.set_title(title)
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    return fig


def approx(d, unit, variant):
    r = load(os.path.join(d, "per_n.csv"))
    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(r["n"], r["approx_max"], label=r"max $\Delta$ (double)")
    ax.plot(r["n"], r["approx_min"], label=r"min $\Delta$ (double)")
    ax.plot(r["n"], r["total_max"], "--", label=r"max $\Delta$ (fixed point)")
    ax.plot(r["n"], r["total_min"], "--", label=r"min $\Delta$ (fixed point)")
    if variant == "cs16":
        ax.axhline(1.7e-2, color="C3", ls=":", lw=1, label="published max 1.7e-2")
        ax.axhline(-9.7e-3, color="C4", ls=":", lw=1, label="published min −9.7e-3")
    ax.set_xlabel("n")
    ax.set_ylabel(r"$\cos^n\theta - f$")
    ax.set_title(f"Approximation error per n — {unit}")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    return fig


def fig3_n_of(a):
    """Fig. 3's n: --fig3-n, else the n of the one fig3_n<N>.csv in --dir (the sweep wrote it), else 128."""
    if a.fig3_n is not None:
        return a.fig3_n
    found = sorted(f for f in os.listdir(a.dir) if f.startswith("fig3_n") and f.endswith(".csv"))
    if len(found) == 1:
        try:
            return int(found[0][len("fig3_n"):-len(".csv")])
        except ValueError:
            pass
    return 128


def build(a):
    """The four figures, by file name (not saved: the tests inspect them)."""
    unit = a.variant
    a.fig3_n = fig3_n_of(a)
    return {
        fig3_name(a.fig3_n) + ".png": fig3(a.dir, unit, a.frac, a.fig3_n, a.n_range),
        "fig4_delta.png": fig4(a.dir, a.title, a.approx_max, a.approx_min),
        "quant_ulp.png": quant(a.dir, a.title, a),
        "approx_over_n.png": approx(a.dir, a.title, a.variant),
    }


def parser():
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--dir", required=True, help="directory with the sweep's CSV files; PNGs go here")
    ap.add_argument("--title", default="cs16", help="variant/format label for titles")
    ap.add_argument("--variant", default="cs16", help="the unit's name (legends, contract bounds)")
    ap.add_argument("--frac", type=int, default=16, help="fraction bits F")
    ap.add_argument("--guard", type=int, default=5, help="guard bits G (cs16)")
    ap.add_argument("--fig3-n", type=int, default=None,
                    help="n of Fig. 3 (reads fig3_n<N>.csv in --dir; default: the one there, else 128)")
    ap.add_argument("--n-range", default=None, help="the swept range LO..HI (Fig. 3's title when n != 128)")
    ap.add_argument("--approx-max", type=float, default=None, help="max Δ over every input code (sweep)")
    ap.add_argument("--approx-min", type=float, default=None, help="min Δ over every input code (sweep)")
    ap.add_argument("--contract-name", default=None, help="the variant's quantisation contract (the sweep's verdict)")
    ap.add_argument("--contract-lo", type=float, default=None, help="its lower bound in output ulps")
    ap.add_argument("--contract-hi", type=float, default=None, help="its upper bound in output ulps")
    ap.add_argument("--contract-lo-strict", dest="contract_lo_strict", action="store_true", default=True,
                    help="lo < quant (default)")
    ap.add_argument("--contract-lo-inclusive", dest="contract_lo_strict", action="store_false", help="lo <= quant")
    ap.add_argument("--command", default="shadecore sweep --plots DIR", help="command for the footer")
    return ap


def main():
    a = parser().parse_args()
    figures.save_all(build(a), a.dir, figures.footer(a.command))


if __name__ == "__main__":
    figures.run(main)
