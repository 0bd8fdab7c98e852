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
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "mesh"))
from section_stl import extruded, refined, write_stl  # noqa: E402

DEPTH = 0.04
EDGE = 0.004
TIP, CLAMP, TOP, GATE_X, GATE_T, END = 0.002, 0.081, 0.2, 0.1, 0.0008, 0.5


def walls_of(points):
    return extruded(refined(points, EDGE), DEPTH)


triangles = walls_of([(0, TOP), (0, 0), (END, 0), (END, TOP)])
triangles += walls_of([(GATE_X + GATE_T, TOP), (GATE_X + GATE_T, CLAMP), (GATE_X + GATE_T, TIP),
                       (GATE_X, TIP), (GATE_X, CLAMP), (GATE_X, TOP)])
write_stl("walls.stl", "elastic_gate_walls", triangles)
