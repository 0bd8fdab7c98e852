#!/usr/bin/python3
"""Runs the piston wavemaker (sph_solver : prescribed_wall) and checks the wave
height at each gauge against linear wavemaker theory (Dean & Dalrymple 1991,
piston): H / S = 2 (cosh 2kh - 1) / (sinh 2kh + 2kh), S = 2 A the stroke, k
from w^2 = g k tanh(kh). The height is twice the amplitude of the sinusoid at
the paddle's frequency fitted (least squares, with a mean) to the gauge record
between the wave train's arrival and the return of the far wall's reflection.

  check_wavemaker.py --case CASE --wall PRESCRIBED_WALL --sph SPH_SOLVER
      --depth 0.5 --length 8 --amplitude 0.02 --period 1.2 --ramp 2.4
      --gauge gauge_1m:1.0 --gauge gauge_2m:2.0 --tolerance 0.05 --folder DIR
"""
import argparse
import math
import pathlib
import shutil
import sys

import numpy as np

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
from coupled_run import derived_case, report, run_coupled  # noqa: E402


def wavenumber(omega, depth, g=9.81):
    k = omega * omega / g
    for _ in range(200):
        k = omega * omega / (g * math.tanh(k * depth))
    return k


def main():
    parser = argparse.ArgumentParser()
    for name in ("--case", "--wall", "--sph", "--folder"):
        parser.add_argument(name, required=True)
    parser.add_argument("--mpiexec", default="mpirun")
    parser.add_argument("--fluid-ranks", type=int, default=2)
    for name in ("--depth", "--length", "--amplitude", "--period", "--ramp", "--tolerance"):
        parser.add_argument(name, type=float, required=True)
    parser.add_argument("--wall-geometry", default="0,0,-0.2 0,0.8,0 0,0,0.4 32 1 1,0,0",
                        help="prescribed_wall's CORNER SIDE_U SIDE_V N_U N_V DIRECTION")
    parser.add_argument("--gauge", action="append", required=True, help="probe:distance_from_paddle")
    parser.add_argument("--settle-periods", type=float, default=1.0,
                        help="periods after the wave train's front before the steady window starts")
    parser.add_argument("--set", action="append", default=[],
                        help="KEY=VALUE for the case copy both partners read")
    args = parser.parse_args()
    folder = pathlib.Path(args.folder)
    shutil.rmtree(folder, ignore_errors=True)
    folder.mkdir(parents=True)
    g = 9.81
    omega = 2 * math.pi / args.period
    k = wavenumber(omega, args.depth, g)
    kh = k * args.depth
    ratio = 2 * (math.cosh(2 * kh) - 1) / (math.sinh(2 * kh) + 2 * kh)
    expected = ratio * 2 * args.amplitude
    group = 0.5 * omega / k * (1 + 2 * kh / math.sinh(2 * kh))
    print(f"theory: k h = {kh:.4f}, wavelength {2 * math.pi / k:.4f} m, H/S = {ratio:.4f}, H = {expected:.5f} m, "
          f"group velocity {group:.4f} m/s")

    case = derived_case(args.case, folder, args.set) if args.set else args.case
    wall = [args.wall, str(case)] + args.wall_geometry.split() + [
        str(args.amplitude), str(args.period), str(args.ramp), str(folder / "piston_forces.csv")]
    run = run_coupled(case, folder, [], args.fluid_ranks, 1, args.sph,
                      launcher=(args.mpiexec, "--oversubscribe"), structure_command=wall)
    if run.status != 0:
        print(run.output[-4000:])
        print(f"FAILED: the job failed (exit {run.status}): {run.failure()}")
        return 1
    print(f"wall time {run.seconds:.1f} s")
    failures = []
    for text in args.gauge:
        name, distance = text.split(":")
        distance = float(distance)
        probe = run.probe("fluid", name)
        t = np.array(probe["time_s"])
        eta = np.array(probe["wave_height_m"])
        # Steady: --settle-periods after the train's front passed (front at the
        # group velocity, delayed by the ramp); until the reflection returns.
        start = args.ramp + distance / group + args.settle_periods * args.period
        end = min(t[-1], (2 * args.length - distance) / group - args.period)
        window = (t >= start) & (t <= end)
        if window.sum() < 20 or end - start < 2 * args.period:
            failures.append(f"{name}: the run is too short for a steady window ({start:.2f}-{end:.2f} s)")
            continue
        A = np.c_[np.ones(window.sum()), np.sin(omega * t[window]), np.cos(omega * t[window])]
        c = np.linalg.lstsq(A, eta[window], rcond=None)[0]
        height = 2 * math.hypot(c[1], c[2])
        error = height / expected - 1
        print(f"{name} ({distance} m from the paddle, {start:.2f}-{end:.2f} s): wave height {height:.5f} m, "
              f"theory {expected:.5f} m, {100 * error:+.2f} %")
        if abs(error) > args.tolerance:
            failures.append(f"{name}: wave height {height:.5f} m is {100 * error:+.2f} % off linear theory "
                            f"(tolerance {100 * args.tolerance:.0f} %)")
    lost = run.fluid["fluid"].get("overflow_particles", 0) if run.fluid and "fluid" in run.fluid else 0
    if lost:
        failures.append(f"{lost} particles left the flume (none may cross the moving wall)")
    return report(failures, len(args.gauge))


if __name__ == "__main__":
    sys.exit(main())
