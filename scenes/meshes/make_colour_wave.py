#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes scenes/meshes/colour_wave.obj: a height field z = 0.25 sin(pi x) cos(pi y / 2) over [-1, 1]^2 with
analytic unit normals (vn), faces counter-clockwise seen from +z, and a colour on every vertex (the
`v x y z r g b` extension): red grows with x, green with y, blue with the height, so GL_COLOR_MATERIAL shows
a gradient (scenes/gl_colour_material.json). Deterministic:
python3 scenes/meshes/make_colour_wave.py > scenes/meshes/colour_wave.obj"""
import math
import sys

N = 16  # quads per side

out = sys.stdout
out.write("# height field z = 0.25 sin(pi x) cos(pi y / 2), x, y in [-1, 1], %dx%d quads; per-vertex colours\n"
          "# written by scenes/meshes/make_colour_wave.py\n" % (N, N))
for j in range(N + 1):
    y = -1.0 + 2.0 * j / N
    for i in range(N + 1):
        x = -1.0 + 2.0 * i / N
        z = 0.25 * math.sin(math.pi * x) * math.cos(math.pi * y / 2)
        r = 0.15 + 0.8 * (x + 1) / 2
        g = 0.15 + 0.7 * (y + 1) / 2
        b = 0.2 + 0.6 * (z + 0.25) / 0.5
        out.write("v %.6f %.6f %.6f %.4f %.4f %.4f\n" % (x, y, z, r, g, b))
for j in range(N + 1):
    y = -1.0 + 2.0 * j / N
    for i in range(N + 1):
        x = -1.0 + 2.0 * i / N
        dzdx = 0.25 * math.pi * math.cos(math.pi * x) * math.cos(math.pi * y / 2)
        dzdy = -0.25 * math.pi / 2 * math.sin(math.pi * x) * math.sin(math.pi * y / 2)
        n = (-dzdx, -dzdy, 1.0)
        l = math.sqrt(sum(c * c for c in n))
        out.write("vn %.6f %.6f %.6f\n" % tuple(c / l for c in n))


def vid(i, j):
    return j * (N + 1) + i + 1


for j in range(N):
    for i in range(N):
        q = [vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)]  # counter-clockwise from +z
        out.write("f " + " ".join("%d//%d" % (v, v) for v in q) + "\n")
