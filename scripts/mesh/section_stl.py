"""A 2D case's walls as an STL file: polylines in the x-y plane extruded over
z in [-depth/2, depth/2] (the fluid's section_depth), the triangles' normals
towards the liquid — the left of each polyline's direction of travel — as the
fluid's wall model takes them (sph_solver/walls/stl_reader.hpp).

Used by the cases' own mesh scripts (cases/*/make_*.py).
"""
import math


def refined(points, max_edge):
    """The polyline with every segment cut into equal pieces of at most max_edge."""
    out = [points[0]]
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        n = max(1, math.ceil(math.hypot(x1 - x0, y1 - y0) / max_edge - 1e-9))
        out += [(x0 + (x1 - x0) * k / n, y0 + (y1 - y0) * k / n) for k in range(1, n + 1)]
    return out


def extruded(points, depth):
    """Two triangles per segment; the normal is the segment's direction turned +90 degrees."""
    low, high = -depth / 2, depth / 2
    out = []
    for (x0, y0), (x1, y1) in zip(points, points[1:]):
        a, b, c, d = (x0, y0, low), (x1, y1, low), (x1, y1, high), (x0, y0, high)
        out += [(a, d, c), (a, c, b)]
    return out


def normal(t):
    (ax, ay, az), (bx, by, bz), (cx, cy, cz) = t
    u, v = (bx - ax, by - ay, bz - az), (cx - ax, cy - ay, cz - az)
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    length = math.sqrt(sum(c * c for c in n))
    return tuple(c / length for c in n)


def write_stl(path, name, triangles):
    with open(path, "w") as f:
        f.write(f"solid {name}\n")
        for t in triangles:
            f.write(" facet normal %.9g %.9g %.9g\n  outer loop\n" % normal(t))
            for v in t:
                f.write("   vertex %.9g %.9g %.9g\n" % v)
            f.write("  endloop\n endfacet\n")
        f.write(f"endsolid {name}\n")
    print(f"{path}:", len(triangles), "triangles")
