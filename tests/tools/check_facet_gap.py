#!/usr/bin/python3
"""Checks what sph_solver reports of a curved wall's coarse facets: the 2D tank
with a half-circle floor (cases/hydrostatic_2d/u_tank.yaml) on walls of N
segments (make_u_tank.py --segments N), run for one step. Its summary.json's
wall_facet_gap_L0 must be the chords' sagitta, R sin^2(pi / 2N) / 2 over L0
(to 1e-3: the corner normal where the half circle meets a side wall is the
mean of the two facets', which moves the last chords' figure by about 1e-4),
and run.log must warn of it exactly when it exceeds 0.05 L0 (fluid_run.cpp,
facet_gap_in_spacings).

Usage: check_facet_gap.py --launcher "mpiexec -n 2" --segments 16 SOLVER
"""
import argparse
import math
import pathlib
import subprocess
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from fluid_run import run_solver, summary  # noqa: E402

REPO = pathlib.Path(__file__).resolve().parents[2]
CASE = REPO / "cases" / "hydrostatic_2d" / "u_tank.yaml"
RADIUS, SPACING, HARMLESS = 0.5, 0.02, 0.05
WARNING = "warning: the wall's facets lie up to"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="mpiexec -n 1")
    parser.add_argument("--segments", type=int, required=True)
    parser.add_argument("solver")
    args = parser.parse_args()
    expected = RADIUS * math.sin(math.pi / (2 * args.segments)) ** 2 / 2 / SPACING
    with tempfile.TemporaryDirectory() as scratch:
        walls = pathlib.Path(scratch) / "walls.stl"
        subprocess.run([sys.executable, str(CASE.parent / "make_u_tank.py"), "--segments", str(args.segments),
                        "--output", str(walls)], check=True, capture_output=True)
        folder = run_solver(args.launcher, args.solver, CASE, pathlib.Path(scratch) / "run",
                            [f"fluid.geometry.file={walls}", "end_time=1e-4"])
        gap = summary(folder)["fluid"]["wall_facet_gap_L0"]
        warned = WARNING in (folder / "run.log").read_text()
    failures = []
    print(f"{args.segments} segments: facets up to {gap:.6f} L0 from the smooth wall (sagitta {expected:.6f} L0), "
          f"{'warned' if warned else 'no warning'}")
    if abs(gap / expected - 1) > 1e-3:
        failures.append(f"wall_facet_gap_L0 {gap} is not the sagitta {expected} (relative tolerance 1e-3)")
    if warned != (gap > HARMLESS):
        failures.append(f"the run {'warned' if warned else 'did not warn'} of facets {gap} L0 off "
                        f"(the warning is due beyond {HARMLESS} L0)")
    for failure in failures:
        print("FAIL:", failure)
    print("FAILED" if failures else "PASS")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
