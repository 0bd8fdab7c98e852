#!/usr/bin/python3
"""A fluid probe's history against a reference series: every reference sample
in [--from, --to], with the run's probe interpolated linearly to its time, within
a relative --tolerance of the reference value.

  check_probe_history.py --launcher "mpiexec -n 2" --solver SPH_SOLVER --case CASE.yaml
      --folder DIR --probe front:front_x_m --reference REFERENCE.csv
      --from 0.1 --to 0.5 --tolerance 0.025 [--set KEY=VALUE ...]
  check_probe_history.py --run RUN_FOLDER --probe ... --reference ... (a finished run)

REFERENCE.csv: lines starting with '#' are its provenance; then a header line
and rows of time and value (the first two columns).
Prints the comparison at every reference time (the case README's table comes
from it) and exits 1 when any sample is outside the tolerance.
"""
import argparse
import pathlib
import shutil
import sys

import numpy as np

from fluid_run import probe, run_solver


def read_reference(path):
    rows = [line for line in pathlib.Path(path).read_text().splitlines() if line and not line.startswith("#")]
    return np.array([[float(x) for x in row.split(",")[:2]] for row in rows[1:]])


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--run", help="a finished run's folder (no run is launched)")
    parser.add_argument("--launcher", default="")
    parser.add_argument("--solver")
    parser.add_argument("--case")
    parser.add_argument("--folder")
    parser.add_argument("--set", action="append", default=[], help="KEY=VALUE for the run")
    parser.add_argument("--probe", required=True, help="NAME:COLUMN of probes/NAME.csv")
    parser.add_argument("--reference", required=True)
    parser.add_argument("--from", dest="start", type=float, required=True)
    parser.add_argument("--to", dest="end", type=float, required=True)
    parser.add_argument("--tolerance", type=float, required=True, help="relative")
    args = parser.parse_args()
    if args.run:
        folder = pathlib.Path(args.run)
    else:
        if not (args.solver and args.case and args.folder):
            parser.error("without --run: --solver, --case and --folder are needed")
        shutil.rmtree(args.folder, ignore_errors=True)
        folder = run_solver(args.launcher, args.solver, args.case, args.folder, args.set)
    name, column = args.probe.split(":")
    header, rows = probe(folder, name)
    t, value = rows[:, 0], rows[:, header.index(column)]
    reference = read_reference(args.reference)
    window = reference[(reference[:, 0] >= args.start - 1e-12) & (reference[:, 0] <= args.end + 1e-12)]
    if len(window) == 0 or t[-1] < window[-1, 0] - 1e-9:
        print(f"FAIL: the run ends at {t[-1]} s, before the last reference time in [{args.start}, {args.end}]")
        return 1
    failures = []
    errors = []
    print(f"{'t (s)':>8}{'reference':>12}{'run':>12}{'error':>10}")
    for time, expected in window:
        got = float(np.interp(time, t, value))
        errors.append(got / expected - 1)
        print(f"{time:8.3f}{expected:12.5f}{got:12.5f}{100 * errors[-1]:+9.2f} %")
        if not abs(errors[-1]) <= args.tolerance:
            failures.append(f"t = {time} s: {column} {got:.5f} against {expected:.5f} ({100 * errors[-1]:+.2f} %)")
    print(f"{len(window)} samples, error {100 * min(errors):+.2f} % to {100 * max(errors):+.2f} % "
          f"(tolerance {100 * args.tolerance:.1f} %)")
    for failure in failures:
        print("FAIL: " + failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
