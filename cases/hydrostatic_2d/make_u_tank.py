#!/usr/bin/python3
"""Writes u_tank.stl, the walls of u_tank.yaml: a 2D tank 1 m wide whose floor
is a half circle of radius R = 0.5 m (centre 0.5 m above its lowest point,
y = 0), with vertical side walls from there up to y = 1.2 m; the section
extruded over z in [-0.2, 0.2] (the case's fluid.section_depth). The half
circle is 64 straight segments (0.0245 m, 1.2 L0 at the case's L0), the side
walls are cut into pieces of the same length at most. Normals towards the
liquid. Run from this folder: /usr/bin/python3 make_u_tank.py
"""
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "mesh"))
from section_stl import extruded, refined, write_stl  # noqa: E402

RADIUS, TOP, SEGMENTS, DEPTH = 0.5, 1.2, 64, 0.4
EDGE = math.pi * RADIUS / SEGMENTS

arc = [(RADIUS * math.cos(math.pi * (1 + k / SEGMENTS)), RADIUS + RADIUS * math.sin(math.pi * (1 + k / SEGMENTS)))
       for k in range(SEGMENTS + 1)]
left = refined([(-RADIUS, TOP), arc[0]], EDGE)
right = refined([arc[-1], (RADIUS, TOP)], EDGE)
write_stl("u_tank.stl", "u_tank", extruded(left[:-1] + arc + right[1:], DEPTH))
