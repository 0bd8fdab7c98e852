#!/usr/bin/python3
"""fem_solver as the structure side of a coupled job against the fluid dummy's
constant force F along x at every interface vertex: the structure must carry
exactly n F (n the interface vertices it reports) as its external force at
every probe row, and apply the impulse the fluid gave, n F T over the run.

Usage: check_structure_coupling.py --mpiexec MPIEXEC --dummy DUMMY --fem FEM_SOLVER
                                   --case CASE --force F [--fluid-ranks A] [--structure-ranks B]
Prints "1 passed, 0 failed" on success.
"""
import argparse
import csv
import json
import pathlib
import subprocess
import sys
import tempfile


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--mpiexec", required=True)
    p.add_argument("--dummy", required=True)
    p.add_argument("--fem", required=True)
    p.add_argument("--case", required=True)
    p.add_argument("--force", type=float, required=True)
    p.add_argument("--fluid-ranks", type=int, default=1)
    p.add_argument("--structure-ranks", type=int, default=2)
    args = p.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        run = pathlib.Path(scratch) / "run"
        command = [args.mpiexec, "--oversubscribe", "-np", str(args.fluid_ranks), args.dummy, "--side", "fluid",
                   args.case, "--constant-force", str(args.force), ":", "-np", str(args.structure_ranks), args.fem,
                   args.case, "--output", str(run)]
        print("running:", " ".join(command), flush=True)
        result = subprocess.run(command, capture_output=True, text=True, timeout=600)
        print(result.stdout[-3000:], result.stderr[-3000:])
        if result.returncode != 0:
            print(f"FAILED: exit status {result.returncode}\n0 passed, 1 failed")
            return 1
        summary = json.loads((run / "summary.json").read_text())
        n = summary["structure"]["interface_vertices"]
        end = summary["structure"]["end_time_s"]
        coupling = summary["coupling"]
        expected_force = n * args.force
        problems = []
        with open(run / "probes" / "structure.csv") as f:
            for row in csv.DictReader(f):
                if abs(float(row["external_force_x_N"]) - expected_force) > 1e-9 * expected_force:
                    problems.append(f"external force {row['external_force_x_N']} N at t = {row['time_s']}, "
                                    f"expected {expected_force}")
                    break
        given, applied = coupling["impulse_given_Ns"][0], coupling["impulse_applied_Ns"][0]
        if abs(given - expected_force * end) > 1e-9 * expected_force * end:
            problems.append(f"impulse given {given} N s, expected n F T = {expected_force * end}")
        if abs(applied - given) > 1e-12 * abs(given):
            problems.append(f"impulse applied {applied} N s differs from the impulse given {given} N s")
        print(f"interface vertices {n}, external force {expected_force} N, impulse {given} N s over {end} s, "
              f"{coupling['windows']} windows, {coupling['iterations_per_window']} iterations per window")
    for problem in problems:
        print("FAILED:", problem)
    print(f"{0 if problems else 1} passed, {1 if problems else 0} failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
