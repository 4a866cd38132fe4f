#!/usr/bin/env python3
"""Writes scenes/meshes/torus_knot.obj: a closed tube around a (2,3) torus knot.

A shipped mesh with a self-shadowing shape, used by the README's first command and by docs.
Regenerate with: python3 scripts/make_torus_knot.py > scenes/meshes/torus_knot.obj
"""
import math

P, Q = 2, 3          # the knot winds P times around the axis and Q times through the hole
RINGS, SIDES = 240, 12
TUBE = 0.28


def knot(t):
    r = 2.0 + math.cos(Q * t)
    return (r * math.cos(P * t), r * math.sin(P * t), -math.sin(Q * t))


def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1]*b[2]-a[2]*b[1], a[2]*b[0]-a[0]*b[2], a[0]*b[1]-a[1]*b[0])
def norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


print("# (2,3) torus knot tube, %d triangles; made by scripts/make_torus_knot.py" % (2 * RINGS * SIDES))
for i in range(RINGS):
    t = 2 * math.pi * i / RINGS
    c = knot(t)
    tangent = norm(sub(knot(t + 1e-4), knot(t - 1e-4)))
    normal = norm(cross(tangent, (0.0, 0.0, 1.0)))
    binormal = cross(tangent, normal)
    for j in range(SIDES):
        a = 2 * math.pi * j / SIDES
        p = tuple(c[k] + TUBE * (math.cos(a) * normal[k] + math.sin(a) * binormal[k]) for k in range(3))
        print("v %.6f %.6f %.6f" % p)
for i in range(RINGS):
    for j in range(SIDES):
        a = i * SIDES + j + 1
        b = ((i + 1) % RINGS) * SIDES + j + 1
        c = ((i + 1) % RINGS) * SIDES + (j + 1) % SIDES + 1
        d = i * SIDES + (j + 1) % SIDES + 1
        print("f %d %d %d\nf %d %d %d" % (a, d, c, a, c, b))
