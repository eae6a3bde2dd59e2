#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Checks what the plotting scripts draw (issue 10), on the CSV data a real `shadecore sweep --plots` and
`shadecore fit --plots` wrote: run by tests/test_cli_plots.cpp. Prints every failed check, exit 1 if any."""
import argparse
import math
import os
import sys

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scripts", required=True)
    ap.add_argument("--sweep", action="append", required=True, metavar="DIR:VARIANT:F:G",
                    help="a `shadecore sweep --plots DIR --json DIR.json` output and its parameters (repeatable)")
    ap.add_argument("--fit-dir", required=True)
    a = ap.parse_args()
    sys.path.insert(0, a.scripts)
    import plot_fit

    for spec in a.sweep:
        d, variant, frac, guard = spec.rsplit(":", 3)
        check_sweep(d, variant, int(frac), int(guard))
    check_fit(a.fit_dir)
    for f in failures:
        print("FAIL:", f)
    return 1 if failures else 0


def check_sweep(sweep_dir, variant, frac, guard):
    import numpy as np
    import plot_sweep

    import json

    a = argparse.Namespace(sweep_dir=sweep_dir, variant=variant, frac=frac, guard=guard)
    # the contract the sweep's verdict checked (its --json), passed to the plot as the CLI passes it
    with open(sweep_dir + ".json") as f:
        contract = json.load(f)["contract"]
    args = plot_sweep.parser().parse_args(
        ["--dir", a.sweep_dir, "--variant", a.variant, "--title", f"{a.variant} F={a.frac}", "--frac", str(a.frac),
         "--guard", str(a.guard), "--approx-max=0.0169", "--approx-min=-1e-15", "--contract-name", contract["name"],
         f"--contract-lo={contract['lo']!r}", f"--contract-hi={contract['hi']!r}",
         "--contract-lo-strict" if contract["lo_strict"] else "--contract-lo-inclusive"])
    figs = plot_sweep.build(args)

    # fig3: the unit's name in the legend (not "variant"), and the fixed-point error in its own panel (at
    # n = 128, or the swept n nearest to it: fig3_n<N>.png).
    f3_names = [k for k in figs if k.startswith("fig3_n")]
    check(len(f3_names) == 1, f"fig3: figures {sorted(figs)}")
    f3 = figs[f3_names[0]]
    check(len(f3.axes) == 2, f"fig3: {len(f3.axes)} panels, want 2 (curves, fixed − double)")
    labels = [t.get_text() for t in f3.axes[0].get_legend().get_texts()]
    check(any(l.startswith(f"{a.variant} (double)") for l in labels), f"fig3 legend {labels} does not name the unit")
    check(any(l.startswith(f"{a.variant} (fixed point") for l in labels), f"fig3 legend {labels}: no fixed-point curve")
    check(not any("variant" in l for l in labels), f"fig3 legend still says 'variant': {labels}")
    if len(f3.axes) == 2:
        check("ulp" in f3.axes[1].get_ylabel(), "fig3 error panel is not in ulps")
        err = np.concatenate([ln.get_ydata() for ln in f3.axes[1].get_lines() if len(ln.get_ydata()) > 2])
        check(np.nanmax(np.abs(err)) > 0, "fig3 error panel is empty")
        lo, hi, _, _ = plot_sweep.quant_bounds(args)
        check(np.nanmin(err) >= lo - 1e-9 and np.nanmax(err) <= hi + 1e-9,
              f"fig3 error panel [{np.nanmin(err)}, {np.nanmax(err)}] outside the contract [{lo}, {hi}]")

    # fig4: θ axis in radians, the paper's 20·θ explained, a colour scale fitting one-signed data, and the
    # title says where its max/min come from.
    f4 = figs["fig4_delta.png"]
    ax = f4.axes[0]
    check("theta" in ax.get_xlabel() and "rad" in ax.get_xlabel(), f"fig4 x label '{ax.get_xlabel()}'")
    sec = [c for c in ax.child_axes if "20" in c.get_xlabel()]
    check(len(sec) == 1 and "paper" in sec[0].get_xlabel(), "fig4 has no explained 20·θ axis")
    check("θ grid" in ax.get_title() and "every input code" in ax.get_title(), f"fig4 title: {ax.get_title()}")
    mesh = ax.collections[0]
    z = np.asarray(mesh.get_array(), dtype=float)
    zmin, zmax = float(np.nanmin(z)), float(np.nanmax(z))
    span = max(abs(zmin), abs(zmax))
    if zmin >= -0.01 * span:  # one-signed data (cs16: Δ ≥ 0 up to rounding)
        check(math.isclose(mesh.norm.vmin, zmin, rel_tol=1e-9, abs_tol=1e-30),
              f"fig4 colour scale starts at {mesh.norm.vmin}, data at {zmin} (symmetric scale for one-signed data)")
        check(mesh.get_cmap().name != "RdBu_r", "fig4 uses a diverging colour map for one-signed data")
    else:  # both signs: centred on 0, each side to its own extreme (not a symmetric ±max scale)
        check(math.isclose(mesh.norm.vmin, zmin) and math.isclose(mesh.norm.vmax, zmax),
              f"fig4 colour scale [{mesh.norm.vmin}, {mesh.norm.vmax}] for data [{zmin}, {zmax}]")

    # quant_ulp: the variant's own contract (issue 38: the one the sweep's verdict checks, for every variant), labelled;
    # a unit that MET it has every per-n extreme between the lines.
    q = figs["quant_ulp.png"].axes[0]
    want_lo = -(0.5 + 15 * 2.0 ** -a.guard) if a.variant == "cs16" else {"cs16_compact": -1.0, "table256": -1.0,
                                                                          "schlick_div": -0.5}.get(a.variant)
    check(want_lo is None or math.isclose(contract["lo"], want_lo), f"{a.variant}: contract {contract}")
    hl = {ln.get_label(): ln.get_ydata()[0] for ln in q.get_lines() if len(set(ln.get_ydata())) == 1}
    lows = [v for k, v in hl.items() if "contract" in k and "lower bound" in k]
    highs = [v for k, v in hl.items() if "contract" in k and "upper bound" in k]
    check(len(lows) == 1 and math.isclose(lows[0], contract["lo"]), f"quant_ulp lower bound lines {hl}, want {contract}")
    check(len(highs) == 1 and math.isclose(highs[0], contract["hi"]), f"quant_ulp upper bound lines {hl}")
    check(all(f"'{contract['name']}'" in k for k in hl), f"quant_ulp bound labels {list(hl)} do not name the contract")
    data = [ln for ln in q.get_lines() if len(set(ln.get_ydata())) > 1]
    check(all(not ln.get_label().startswith("_") for ln in data), "quant_ulp has unlabelled lines")
    if contract["met"] and lows and highs:
        ys = np.concatenate([ln.get_ydata() for ln in data])
        check(ys.min() >= lows[0] and ys.max() <= highs[0],
              f"{a.variant}: the sweep says MET but quant_ulp draws data [{ys.min()}, {ys.max()}] outside its lines")



def check_fit(fit_dir):
    import numpy as np
    import plot_fit

    # fig5: every line in the legend is visible (its data mostly above the axis floor).
    f5 = plot_fit.fit_figure(fit_dir)
    drawn = 0
    for ax in f5.axes:
        lo = ax.get_ylim()[0]
        for ln in ax.get_lines():
            y = np.asarray(ln.get_ydata(), dtype=float)
            y = y[np.isfinite(y) & (y > 0)]
            if y.size < 3:
                continue
            drawn += 1
            check(np.mean(y >= lo) >= 0.9, f"fig5 '{ax.get_title()}': line '{ln.get_label()}' is below the floor {lo:g}")
    check(drawn > 0, "fig5 has no lines")


if __name__ == "__main__":
    sys.exit(main())
