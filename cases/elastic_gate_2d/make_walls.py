#!/usr/bin/python3
"""Writes walls.stl, the fluid's rigid walls of the elastic-gate case, as a 2D
section extruded over z in [-0.02, 0.02] (the case's fluid.section_depth):

  the tank: left wall x = 0, floor y = 0 up to x = 0.5 m, right wall x = 0.5 m,
            all 0.2 m high;
  the gate: a solid 0.8 mm thick whose left face x = 0.1 m runs from its tip
            at y = 0.002 m up to 0.2 m, with a vertex row at the clamp,
            y = 0.081 m. fem_solver's gate (a shell strip on the plane x = 0.1
            m from the tip to the clamp) replaces the part of it below the
            clamp in a coupled run (its triangles lie within L0/2 of the
            strip); the part above stays a rigid wall.

Triangles are oriented with their normals towards the liquid (the left of
each polyline's direction of travel in the x-y plane). Edges are at most
4 mm long. Run from this folder: /usr/bin/python3 make_walls.py
"""
import math

DEPTH = 0.04
EDGE = 0.004
TIP, CLAMP, TOP, GATE_X, GATE_T, END = 0.002, 0.081, 0.2, 0.1, 0.0008, 0.5


def refined(points):
    out = [points[0]]
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        n = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / EDGE - 1e-9))
        out += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(1, n + 1)]
    return out


def extruded(points):
    """Two triangles per segment; the normal is the segment direction turned +90 degrees."""
    low, high = -DEPTH / 2, DEPTH / 2
    out = []
    pts = refined(points)
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        a, b, c, d = (x0, y0, low), (x1, y1, low), (x1, y1, high), (x0, y0, high)
        out += [(a, d, c), (a, c, b)]
    return out


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


triangles = extruded([(0, TOP), (0, 0), (END, 0), (END, TOP)])
triangles += extruded([(GATE_X + GATE_T, TOP), (GATE_X + GATE_T, CLAMP), (GATE_X + GATE_T, TIP),
                       (GATE_X, TIP), (GATE_X, CLAMP), (GATE_X, TOP)])
with open("walls.stl", "w") as f:
    f.write("solid elastic_gate_walls\n")
    for t in triangles:
        f.write(" facet normal %.9g %.9g %.9g\n  outer loop\n" % normal(t))
        for v in t:
            f.write("   vertex %.9g %.9g %.9g\n" % v)
        f.write("  endloop\n endfacet\n")
    f.write("endsolid elastic_gate_walls\n")
print("walls.stl:", len(triangles), "triangles")
