#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes scenes/meshes/tube.obj: an open cylinder (no caps) of radius 1 around the y axis, y in [-1, 1], with
outward radial normals (vn) and faces counter-clockwise seen from outside, so its inside shows back faces
(scenes/gl_two_side.json, GL_LIGHT_MODEL_TWO_SIDE). Deterministic:
python3 scenes/meshes/make_tube.py > scenes/meshes/tube.obj"""
import math
import sys

SIDES, ROWS = 32, 4

out = sys.stdout
out.write("# open cylinder: radius 1, y in [-1, 1], %d sides, %d rows; outward normals, CCW faces from outside\n"
          "# written by scenes/meshes/make_tube.py\n" % (SIDES, ROWS))
for r in range(ROWS + 1):
    y = -1.0 + 2.0 * r / ROWS
    for i in range(SIDES):
        t = 2.0 * math.pi * i / SIDES
        out.write("v %.6f %.6f %.6f\n" % (math.cos(t), y, math.sin(t)))
for i in range(SIDES):
    t = 2.0 * math.pi * i / SIDES
    out.write("vn %.6f 0 %.6f\n" % (math.cos(t), math.sin(t)))


def vid(i, r):
    return r * SIDES + i % SIDES + 1


for r in range(ROWS):
    for i in range(SIDES):
        # (i, r), (i, r+1), (i+1, r+1), (i+1, r): normal cross(up, tangent) points outward
        q = [(i, r), (i, r + 1), (i + 1, r + 1), (i + 1, r)]
        out.write("f " + " ".join("%d//%d" % (vid(a, b), a % SIDES + 1) for a, b in q) + "\n")
