#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""cs16 against cos^n, and a sphere lit with the bit-accurate units, from the shadecore Python package.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/cs16_vs_cos.py --out out/cs16_vs_cos.png

Left: the unit's output codes (every input code at F = 16) against the exact cos^n θ for three n. Middle: the error
cos^n − cs16 of the fixed-point outputs. Right: a sphere lit by the lighting core's bit-accurate model (LightCore of
the feature set gl_default, programmed from a GL-like state dict; one fragment per pixel) and its difference from the
core's double reference with exact cos^n. Everything is whole arrays: no Python loop over pixels or codes.
"""
import argparse
import datetime
import os
import platform
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import shadecore  # noqa: E402


def footer(command):
    """Command, machine and date, as every figure of the project names them (scripts/figures.py)."""
    cpu = platform.machine()
    try:
        with open("/proc/cpuinfo") as f:
            cpu = next((ln.split(":", 1)[1].strip() + f", {os.cpu_count()} cores" for ln in f
                        if ln.startswith("model name")), cpu)
    except OSError:
        pass
    return f"{command} | {cpu} | {datetime.date.today().isoformat()}"


def lit_sphere(n, size=200):
    """A sphere lit by the lighting core's C model (LightCore, feature set gl_default: one directional light,
    ambient + diffuse + cs16 specular, Blinn, GL_NORMALIZE): RGB codes per pixel, and the exact double reference
    (cos^n in place of cs16); NaN outside the sphere."""
    core = shadecore.LightCore("gl_default")
    core.program({
        "global_ambient": [0.15, 0.15, 0.15],
        "material": {"ambient": [0.6, 0.2, 0.1], "diffuse": [0.75, 0.25, 0.1], "specular": [0.6, 0.6, 0.6],
                     "shininess": n},
        "lights": [{"position": [-0.4, 0.5, 0.8, 0.0], "diffuse": [1, 1, 1], "specular": [1, 1, 1]}],
    })
    y, x = np.mgrid[1:-1:size * 1j, -1:1:size * 1j]
    inside = x * x + y * y < 1.0
    normals = np.stack([x, y, np.sqrt(np.clip(1.0 - x * x - y * y, 0.0, None))], axis=-1)[inside]
    nc, pc = core.fragment_codes(normals, normals * 2.0 + [0.0, 0.0, -6.0])  # eye space: the sphere at z = -6
    fixed = np.full(x.shape + (3,), np.nan)
    exact = np.full(x.shape + (3,), np.nan)
    fixed[inside] = core.eval(nc, pc)["colour"] / 2.0 ** core.frac
    exact[inside] = core.eval_double(nc, pc)["colour"]
    return fixed, exact


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", default="cs16_vs_cos.png", help="PNG to write")
    ap.add_argument("--sphere-n", type=int, default=64, help="shininess of the sphere (16..1024)")
    args = ap.parse_args()

    codes = np.arange(65537)
    c = shadecore.code_to_cos(codes)
    theta = np.arccos(c)
    fig, ax = plt.subplots(1, 4, figsize=(17, 4.2), constrained_layout=True)
    for n, colour in ((16, "tab:blue"), (128, "tab:orange"), (1024, "tab:green")):
        out = shadecore.cs16(codes, n) / 65536.0
        exact = shadecore.golden.cos_pow(c, n)
        lim = 1.3 * float(shadecore.golden.theta_cr([n])[0])
        sel = theta <= lim
        ax[0].plot(theta[sel] / lim, exact[sel], color=colour, lw=2.5, alpha=0.35, label=f"cos^{n} θ")
        ax[0].plot(theta[sel] / lim, out[sel], color=colour, lw=1, ls="--", label=f"cs16, n = {n}")
        ax[1].plot(theta[sel] / lim, exact[sel] - out[sel], color=colour, lw=1, label=f"n = {n}")
    ax[0].set_xlabel("θ / (1.3 θcr(n)),  θcr = 6/√n")
    ax[0].set_ylabel("specular term")
    ax[0].set_title("cs16 unit (F = 16) against cos^n θ")
    ax[0].legend(fontsize=8)
    ax[1].set_xlabel("θ / (1.3 θcr(n))")
    ax[1].set_ylabel("cos^n θ − cs16 (output / 2^16)")
    ax[1].set_title("error of the fixed-point unit")
    ax[1].legend(fontsize=8)

    fixed, exact = lit_sphere(args.sphere_n)
    ax[2].imshow(np.nan_to_num(np.clip(fixed, 0, 1), nan=1.0))
    ax[2].set_title(f"lit sphere (LightCore, n = {args.sphere_n})")
    ax[2].axis("off")
    diff = ((exact - fixed) * 65536.0).max(axis=2)  # the channel with the largest difference
    m = np.nanmax(np.abs(diff))
    im = ax[3].imshow(diff, cmap="coolwarm", vmin=-m, vmax=m)
    ax[3].set_title("exact (cos^n, double) − C model")
    ax[3].axis("off")
    fig.colorbar(im, ax=ax[3], label="output LSBs (2^-16), largest channel")
    fig.supxlabel(footer("python/examples/cs16_vs_cos.py " + " ".join(sys.argv[1:])), x=0.01, ha="left", fontsize=6,
                  color="0.35")
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out} (shadecore {shadecore.__version__})")


if __name__ == "__main__":
    main()
