#!/usr/bin/python3
"""Runs the elastic gate (cases/elastic_gate_2d, sph_solver : fem_solver) and
compares the gate tip's displacement with the experiment's
(cases/elastic_gate_2d/antoci_2007_tip.csv) at each of its times from --after
to the run's end: every x and y within the tolerance, relative to the
experiment's value.

  check_gate_tip.py --case CASE --folder DIR --tolerance 0.2 [--after 0.06] [--set KEY=VALUE ...]
      [--sph SPH --fem FEM --mpiexec MPIEXEC]

Prints the comparison as a table (the case README's comes from it).
"""
import argparse
import csv
import pathlib
import shutil
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
from coupled_run import report, run_coupled  # noqa: E402


def experiment(case):
    path = pathlib.Path(case).parent / "antoci_2007_tip.csv"
    rows = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(rows)]


def interpolated(times, values, t):
    for (t0, v0), (t1, v1) in zip(zip(times, values), zip(times[1:], values[1:])):
        if t0 <= t <= t1:
            return v0 + (v1 - v0) * (t - t0) / (t1 - t0)
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", required=True)
    parser.add_argument("--folder", required=True)
    parser.add_argument("--tolerance", type=float, required=True, help="relative, for every x and y")
    parser.add_argument("--after", type=float, default=0.0, help="experimental times before this are shown, not checked")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--sph")
    parser.add_argument("--fem")
    parser.add_argument("--mpiexec", default="mpirun")
    args = parser.parse_args()
    folder = pathlib.Path(args.folder)
    shutil.rmtree(folder, ignore_errors=True)
    run = run_coupled(args.case, folder / "run", args.set, 1, 1, args.sph, args.fem,
                      launcher=(args.mpiexec, "--oversubscribe"))
    if run.status != 0 or run.structure is None:
        print(run.output[-4000:])
        print(f"FAILED: the job failed (exit {run.status}): {run.failure()}")
        return 1
    tip = run.probe("structure", "gate_tip")
    coupling = run.structure.get("coupling", {})
    print(f"wall time {run.seconds:.1f} s; {coupling.get('iterations_per_window', 0):.2f} coupling iterations per "
          f"window, {coupling.get('unconverged_windows', 0)} windows accepted unconverged")
    print("| t (s) | x (m) | experiment | | y (m) | experiment | |")
    print("|---|---|---|---|---|---|---|")
    failures = []
    checked = 0
    for row in experiment(args.case):
        x = interpolated(tip["time_s"], tip["displacement_x_m"], row["time_s"])
        y = interpolated(tip["time_s"], tip["displacement_y_m"], row["time_s"])
        if x is None or y is None:
            continue  # after the run's end
        ex, ey = x / row["x_m"] - 1.0, y / row["y_m"] - 1.0
        print(f"| {row['time_s']:.3f} | {x:.4f} | {row['x_m']:.4f} | {100 * ex:+.1f} % "
              f"| {y:.4f} | {row['y_m']:.4f} | {100 * ey:+.1f} % |")
        if row["time_s"] < args.after:
            continue
        checked += 1
        for name, error in (("x", ex), ("y", ey)):
            if abs(error) > args.tolerance:
                failures.append(f"tip {name} at t = {row['time_s']} s is {100 * error:+.1f} % off the experiment "
                                f"(tolerance {100 * args.tolerance:.0f} %)")
    if checked == 0:
        failures.append("no experimental time lies within the run")
    return report(failures, checked)


if __name__ == "__main__":
    sys.exit(main())
