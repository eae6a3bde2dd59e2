#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Writes scenes/meshes/knot.obj: a trefoil knot as a tube (positions and faces only; shadecore computes
area-weighted vertex normals). Deterministic: python3 scenes/meshes/make_knot.py > scenes/meshes/knot.obj"""
import math
import sys

RINGS, SIDES, TUBE = 120, 10, 0.28


def curve(t):
    # trefoil: (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t), scaled to about ±1.2
    s = 0.4
    return (s * (math.sin(t) + 2 * math.sin(2 * t)), s * (math.cos(t) - 2 * math.cos(2 * t)), s * (-math.sin(3 * t)))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


out = sys.stdout
out.write("# trefoil knot tube, %d rings x %d sides (scenes/meshes/make_knot.py)\n" % (RINGS, SIDES))
for i in range(RINGS):
    t = 2 * math.pi * i / RINGS
    p = curve(t)
    d = unit(sub(curve(t + 1e-4), curve(t - 1e-4)))
    n = unit(cross(d, (0.0, 0.0, 1.0)))
    b = cross(d, n)
    for j in range(SIDES):
        a = 2 * math.pi * j / SIDES
        c, s = math.cos(a), math.sin(a)
        v = tuple(p[k] + TUBE * (c * n[k] + s * b[k]) for k in range(3))
        out.write("v %.6f %.6f %.6f\n" % v)
for i in range(RINGS):
    for j in range(SIDES):
        a = i * SIDES + j + 1
        b = ((i + 1) % RINGS) * SIDES + j + 1
        c = ((i + 1) % RINGS) * SIDES + (j + 1) % SIDES + 1
        d = i * SIDES + (j + 1) % SIDES + 1
        out.write("f %d %d %d %d\n" % (a, d, c, b))  # counter-clockwise seen from outside
