#!/usr/bin/python3
"""Validation: a tank run's natural period as its report reads it.

Runs a tank case (or takes an existing run folder), runs the report
(scripts/post/tank_report.py) on it and checks tank_summary.json: the
period it states for KIND (sloshing or bulging) and the period of every
record that identified one, each within the tolerance of EN 1998-4 Annex A
for the case's liquid depth. The theory for the depth the particle layers
hold is printed beside it.

  check_tank_report_period.py --launcher "mpiexec -n 2" --kind sloshing --tolerance 0.03
      SPH_SOLVER CASE.yaml [--set k=v ...]
  check_tank_report_period.py --run RUN_FOLDER --kind sloshing --tolerance 0.03
"""
import argparse
import json
import pathlib
import subprocess
import sys
import tempfile

from fluid_run import run_solver

REPORT = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post" / "tank_report.py"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="")
    parser.add_argument("--run", help="check an existing run folder instead of running the case")
    parser.add_argument("--kind", choices=("sloshing", "bulging"), required=True)
    parser.add_argument("--tolerance", type=float, required=True, help="relative, against the case's theory")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("solver", nargs="?")
    parser.add_argument("case", nargs="?")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(args.run) if args.run else run_solver(
            args.launcher, args.solver, args.case, f"{scratch}/run", args.set)
        report = subprocess.run([sys.executable, str(REPORT), str(folder)], capture_output=True, text=True)
        if report.returncode != 0:
            print(f"FAIL: tank_report.py exited {report.returncode}\n{report.stdout}\n{report.stderr}")
            return 1
        summary = json.loads((folder / "tank_summary.json").read_text())
    theory_key = "convective_period_theory_s" if args.kind == "sloshing" else "impulsive_period_theory_s"
    theory = summary[theory_key]
    at_depth = summary["theory_at_model_depth"]
    layers = at_depth["convective_period_s" if args.kind == "sloshing" else "impulsive_period_s"]
    print(f"EN 1998-4 Annex A, {args.kind}: {theory:.4f} s for the case's {at_depth['fill_level_m']:g} m of liquid, "
          f"{layers:.4f} s for the {at_depth['liquid_depth_m']:g} m its particle layers hold")
    failures = []
    stated = summary.get(f"{args.kind}_period_s")
    if stated is None:
        failures.append(f"the report states no {args.kind} period")
    else:
        error = stated / theory - 1.0
        print(f"report: {stated:.4f} s +- {summary[f'{args.kind}_period_std_s']:.2g} s "
              f"({summary[f'{args.kind}_period_record']}), {100 * error:+.2f} % "
              f"(tolerance {100 * args.tolerance:g} %)")
        if abs(error) > args.tolerance:
            failures.append(f"the report's {args.kind} period is {100 * error:+.2f} % off")
    for name, record in summary["period_identification"][args.kind].items():
        if "period_s" not in record:
            print(f"  {name}: none ({record.get('reason')})")
            continue
        error = record["period_s"] / theory - 1.0
        print(f"  {name}: {record['period_s']:.4f} s +- {record['period_std_s']:.2g} s, {100 * error:+.2f} %")
        if abs(error) > args.tolerance:
            failures.append(f"record {name}: {100 * error:+.2f} % off")
    for failure in failures:
        print(f"FAIL: {failure}")
    if failures:
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
