#!/usr/bin/python3
"""Writes the wall meshes of the bad fluid cases (and the valid one) next to
this script. Each is the 0.4 m cube tank [0, 0.4]^3 with normals into the
liquid, with one defect. Run it again after changing it; the files are kept
in the repository so the test needs no generator. (flat_plate.msh and
plate_truncated.msh are copies of the structure tests' Gmsh meshes.)"""
import pathlib
import struct

HERE = pathlib.Path(__file__).parent
L = 0.4
CORNERS = [(x, y, z) for z in (0, L) for y in (0, L) for x in (0, L)]
# Outward-facing quads of the cube (corner indices, counter-clockwise seen from outside).
QUADS = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]


def cube(inward=True):
    triangles = []
    for a, b, c, d in QUADS:
        for t in ((a, b, c), (a, c, d)):
            triangles.append(tuple(reversed(t)) if inward else t)
    return [CORNERS[i] for t in triangles for i in t]


def facets(points):
    return [points[i:i + 3] for i in range(0, len(points), 3)]


def write_ascii(name, triangles, corrupt=None):
    lines = ["solid tank"]
    for tri in triangles:
        lines += ["  facet normal 0 0 0", "    outer loop"]
        lines += [f"      vertex {x:g} {y:g} {z:g}" for x, y, z in tri]
        lines += ["    endloop", "  endfacet"]
    lines.append("endsolid tank")
    text = "\n".join(lines) + "\n"
    if corrupt:
        text = corrupt(text)
    (HERE / name).write_text(text)


def write_binary(name, triangles, drop_bytes=0):
    data = bytearray(b"binary tank".ljust(80, b" "))
    data += struct.pack("<I", len(triangles))
    for tri in triangles:
        data += struct.pack("<3f", 0, 0, 0)
        for p in tri:
            data += struct.pack("<3f", *p)
        data += struct.pack("<H", 0)
    (HERE / name).write_bytes(bytes(data[:len(data) - drop_bytes]))


tank = facets(cube())
write_ascii("tank.stl", tank)
write_ascii("tank_inverted.stl", facets(cube(inward=False)))
# One side-wall triangle turned against its neighbours.
flipped = list(tank)
flipped[4] = (flipped[4][0], flipped[4][2], flipped[4][1])
write_ascii("tank_flipped_triangle.stl", flipped)
# A hole in the side wall x = 0 below the fill level: one of its triangles missing.
write_ascii("tank_hole_below_level.stl", tank[:8] + tank[9:])
# A fin hanging from the floor's diagonal edge: three triangles on one edge.
floor = tank[0]
write_ascii("tank_fin.stl", tank + [(floor[0], floor[2], (0.2, 0.2, 0.1))])
# A degenerate sliver: a triangle with three collinear corners on the floor.
write_ascii("tank_sliver.stl", tank + [((0.1, 0.1, 0.0), (0.2, 0.2, 0.0), (0.3, 0.3, 0.0))])
# A closed tetrahedron (outward normals, an obstacle) poking through the floor.
tet = [(0.1, 0.1, -0.1), (0.3, 0.1, -0.1), (0.2, 0.3, -0.1), (0.2, 0.2, 0.1)]
faces = [(0, 2, 1), (0, 1, 3), (1, 2, 3), (2, 0, 3)]
write_ascii("tank_self_intersecting.stl", tank + [tuple(tet[i] for i in f) for f in faces])
# Syntax and format errors.
write_ascii("tank_missing_endloop.stl", tank, lambda t: t.replace("    endloop\n", "", 1))
write_ascii("tank_nan_vertex.stl", tank, lambda t: t.replace("vertex 0 0 0", "vertex 0 nan 0", 1))
write_binary("tank_truncated_binary.stl", tank, drop_bytes=30)
