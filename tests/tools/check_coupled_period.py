#!/usr/bin/python3
"""Runs a coupled case (sph_solver : fem_solver) and checks the period of one
probe's free oscillation after --after against a reference period: the mean
spacing of the upward crossings of the record's linear trend (the slow
sloshing under the fast bulging), and the peak of its spectrum, both printed.

  check_coupled_period.py --case CASE --probe structure:wall_radial:displacement_m
      --after 0.012 --reference 0.00495 --tolerance 0.15 --folder DIR [--set KEY=VALUE ...]
"""
import argparse
import pathlib
import shutil
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
from coupled_run import run_coupled  # noqa: E402
from stability_study import oscillation_period  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    for name in ("--case", "--folder", "--probe"):
        parser.add_argument(name, required=True)
    parser.add_argument("--sph")
    parser.add_argument("--fem")
    parser.add_argument("--mpiexec", default="mpirun")
    parser.add_argument("--fluid-ranks", type=int, default=1)
    parser.add_argument("--structure-ranks", type=int, default=1)
    for name in ("--after", "--reference", "--tolerance"):
        parser.add_argument(name, type=float, required=True)
    parser.add_argument("--set", action="append", default=[])
    args = parser.parse_args()
    side, name, column = args.probe.split(":")
    folder = pathlib.Path(args.folder)
    shutil.rmtree(folder, ignore_errors=True)
    run = run_coupled(args.case, folder, args.set, args.fluid_ranks, args.structure_ranks, args.sph, args.fem,
                      launcher=(args.mpiexec, "--oversubscribe"))
    if run.status != 0:
        print(run.output[-4000:])
        print(f"FAILED: the job failed (exit {run.status}): {run.failure()}")
        return 1
    probe = run.probe(side, name)
    t = np.array(probe["time_s"])
    x = np.array(probe[column])
    keep = t >= args.after
    t, x = t[keep], x[keep]
    trend = np.polyval(np.polyfit(t, x, 1), t)
    period = oscillation_period(list(t), list(x - trend), 0.0)
    spectrum = np.abs(np.fft.rfft((x - trend) * np.hanning(len(x)), n=16 * len(x)))
    frequencies = np.fft.rfftfreq(16 * len(x), d=(t[-1] - t[0]) / (len(t) - 1))
    peak = 1.0 / frequencies[1:][np.argmax(spectrum[1:])]
    coupling = run.structure.get("coupling", {})
    print(f"{name}:{column} after {args.after} s: period {period if period else float('nan'):.5f} s from crossings, "
          f"{peak:.5f} s at the spectrum's peak; reference {args.reference:.5f} s; "
          f"{coupling.get('iterations_per_window', 1):.2f} iterations per window, wall time {run.seconds:.1f} s")
    if period is None:
        print("FAILED: the probe does not oscillate after --after")
        return 1
    error = period / args.reference - 1.0
    print(f"period {100 * error:+.1f} % against the reference (tolerance {100 * args.tolerance:.0f} %)")
    if abs(error) > args.tolerance:
        print(f"FAILED: the period {period:.5f} s is {100 * error:+.1f} % off {args.reference:.5f} s")
        return 1
    print("1 passed, 0 failed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
