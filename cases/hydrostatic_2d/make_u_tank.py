#!/usr/bin/python3
"""Writes u_tank.stl, the walls of u_tank.yaml: a 2D tank 1 m wide whose floor
is a half circle of radius R = 0.5 m (centre 0.5 m above its lowest point,
y = 0), with vertical side walls from there up to y = 1.2 m; the section
extruded over z in [-0.2, 0.2] (the case's fluid.section_depth). The half
circle is 64 straight segments (0.0245 m, 1.2 L0 at the case's L0), the side
walls are cut into pieces of the same length at most. Normals towards the
liquid. Run from this folder: /usr/bin/python3 make_u_tank.py
(--segments N and --output FILE write other half circles elsewhere: the tests
of coarse facets, README.md "Coarse facets").
"""
import argparse
import math
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "mesh"))
from section_stl import extruded, refined, write_stl  # noqa: E402

RADIUS, TOP, DEPTH = 0.5, 1.2, 0.4

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--segments", type=int, default=64, help="straight segments of the half circle")
parser.add_argument("--output", default="u_tank.stl")
args = parser.parse_args()
edge = math.pi * RADIUS / args.segments

arc = [(RADIUS * math.cos(math.pi * (1 + k / args.segments)), RADIUS + RADIUS * math.sin(math.pi * (1 + k / args.segments)))
       for k in range(args.segments + 1)]
left = refined([(-RADIUS, TOP), arc[0]], edge)
right = refined([arc[-1], (RADIUS, TOP)], edge)
write_stl(args.output, "u_tank", extruded(left[:-1] + arc + right[1:], DEPTH))
