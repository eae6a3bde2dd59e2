#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""cs16 against cos^n, and a sphere lit with the bit-accurate units, from the shadecore Python package.

    PYTHONPATH=build/python /usr/bin/python3 python/examples/cs16_vs_cos.py --out out/cs16_vs_cos.png

Left: the unit's output codes (every input code at F = 16) against the exact cos^n θ for three n. Middle: the error
cos^n − cs16 of the fixed-point outputs. Right: a sphere under one directional light, the normal N̂ and the half
vector Ĥ normalised by the core's normaliser (normalize3), N̂·Ĥ fed to the cs16 unit and to cos^n in double — the
difference image at the unit's resolution. Everything is whole arrays: no Python loop over pixels or codes.
"""
import argparse

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import shadecore  # noqa: E402


def lit_sphere(n, size=256, frac=16):
    """Specular term of a sphere: cs16 (fixed point) and cos^n (double) of N̂·Ĥ per pixel; NaN outside."""
    y, x = np.mgrid[1:-1:size * 1j, -1:1:size * 1j]
    inside = x * x + y * y < 1.0
    z = np.sqrt(np.clip(1.0 - x * x - y * y, 0.0, None))
    one = 1 << frac
    normals = np.stack([x, y, z], axis=-1)[inside]
    n_hat = shadecore.normalize3(np.round(normals * one).astype(np.int64), frac)
    light = np.array([0.45, 0.55, 0.70])
    h = light / np.linalg.norm(light) + np.array([0.0, 0.0, 1.0])  # Blinn: L + V, V = +z
    h_hat = shadecore.normalize3(np.round(h * one).astype(np.int64), frac)
    ndh = (n_hat @ h_hat) >> frac  # N̂·Ĥ as an input code (1.0 = 2^F)
    fixed = np.full(x.shape, np.nan)
    exact = np.full(x.shape, np.nan)
    fixed[inside] = shadecore.cs16(ndh, n) / one
    exact[inside] = shadecore.golden.cos_pow(shadecore.code_to_cos(ndh), n)
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
    ax[2].imshow(fixed, cmap="gray", vmin=0, vmax=1)
    ax[2].set_title(f"sphere, cs16 specular (n = {args.sphere_n})")
    ax[2].axis("off")
    diff = (exact - fixed) * 65536.0
    m = np.nanmax(np.abs(diff))
    im = ax[3].imshow(diff, cmap="coolwarm", vmin=-m, vmax=m)
    ax[3].set_title("cos^n − cs16 on the sphere")
    ax[3].axis("off")
    fig.colorbar(im, ax=ax[3], label="output ulps (2^-16)")
    fig.savefig(args.out, dpi=110)
    print(f"wrote {args.out} (shadecore {shadecore.__version__})")


if __name__ == "__main__":
    main()
