#!/usr/bin/python3
# SPDX-License-Identifier: Apache-2.0
"""Contact sheet of seed 000's lighting models: one sphere per model, rendered by the double-precision
references of cmodel/include/shadecore/analysis/brdf.hpp through `brdf_tool render` (software path: orthographic
camera, one directional light), drawn here with matplotlib.

    scripts/brdf_sheet.py [--tool build/bench/brdf_tool] [--size 160] [--out docs/brdf/contact_sheet.png]

Tone mapping: radiance L (a white Lambert surface facing the light has L = 1) is clipped to [0, 1] and
gamma-encoded (L^(1/2.2)); highlights brighter than 1 are clipped, as in the thesis's renders.
"""
import argparse
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figures  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--tool", default="build/bench/brdf_tool")
    ap.add_argument("--size", type=int, default=160)
    ap.add_argument("--out", default="docs/brdf/contact_sheet.png")
    a = ap.parse_args()
    if not os.access(a.tool, os.X_OK):
        sys.exit(f"brdf_sheet: {a.tool} not found (build it: cmake --build build --target brdf_tool)")

    import numpy as np
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    with tempfile.TemporaryDirectory() as tmp:
        subprocess.run([a.tool, "render", tmp, str(a.size)], check=True)
        with open(os.path.join(tmp, "spheres.txt")) as f:
            size = int(f.readline())
            labels = [line.rstrip("\n").split("|", 1) for line in f if line.strip()]
        data = np.fromfile(os.path.join(tmp, "spheres.f32"), dtype=np.float32)
    imgs = data.reshape(len(labels), size, size)

    cols = 4
    rows = (len(labels) + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(cols * 2.6, rows * 2.7))
    for k, ax in enumerate(axes.flat):
        ax.axis("off")
        if k >= len(labels):
            continue
        name, params = labels[k]
        off = imgs[k] < 0
        img = np.clip(imgs[k], 0, 1) ** (1 / 2.2)
        rgb = np.repeat(img[:, :, None], 3, axis=2)
        rgb[off] = (0.16, 0.18, 0.22)  # background: shows the unlit side's silhouette
        ax.imshow(rgb, interpolation="nearest")
        eq = params.rsplit(" (", 1)
        ax.set_title(f"{name} ({eq[1]}\n{eq[0]}" if len(eq) == 2 else f"{name}\n{params}", fontsize=6.5)
        peak = float(imgs[k].max())
        ax.text(0.02, 0.02, f"peak L = {peak:.3g}", transform=ax.transAxes, fontsize=5.5, color="0.6")
    fig.suptitle("Seed 000 lighting models, double-precision BRDF references (one light, upper left)", fontsize=9)
    os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
    cmd = "scripts/brdf_sheet.py --tool " + a.tool
    figures.save(fig, a.out, figures.footer(cmd))
    print(a.out)


if __name__ == "__main__":
    main()
