#!/usr/bin/python3
"""Validation: free linear sloshing in a rectangular tank (VALIDATION.md,
"Rectangular tank, linear sloshing") or an upright cylinder ("Cylindrical
tank": the first mode's T = 2 pi / sqrt(g xi / R tanh(xi H / R)), xi = 1.8412,
scripts/post/tank_theory.py), after --after (the end of the excitation that
set it sloshing; default a quarter period).

Usage: check_sloshing_period.py --launcher "mpiexec -n 2" --probe wave_left
       [--base 0.5] [--tolerance 0.01] SPH_SOLVER CASE.yaml [--set k=v ...]
       check_sloshing_period.py --run RUN_FOLDER --probe wave_left ...   (an existing run)

The case starts a standing wave of mode n (fluid.initial_velocity). The wave-height
probe reads the surface height above its point (at y = base); eta = reading minus
(H - base), H the top of the highest particle layer. The period is measured from
the zero crossings of eta after the first quarter period: the mean time between
successive crossings in the same direction (up to up, down to down), which a
constant offset of eta does not bias. It is compared with Faltinsen's
  omega_n^2 = g (n pi / L) tanh(n pi H / L)
for the simulated depth H and width L; the tolerance is VALIDATION.md's 1 %. As a
second estimate the FFT peak of the Hann-windowed, zero-padded record with
parabolic interpolation of the log magnitude is printed (not asserted: over three
or four periods its window bias is of the order of the tolerance itself).
"""
import argparse
import math
import pathlib
import sys
import tempfile

import numpy as np
import yaml

from fluid_run import probe, run_solver

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
from tank_theory import convective_period  # noqa: E402


def crossings(t, eta, rising):
    """Times where eta crosses zero upwards (rising) or downwards, linearly interpolated."""
    result = []
    for k in range(len(eta) - 1):
        a, b = eta[k], eta[k + 1]
        if (rising and a < 0.0 <= b) or (not rising and a > 0.0 >= b):
            result.append(t[k] - a * (t[k + 1] - t[k]) / (b - a))
    return np.array(result)


def fft_period(t, eta):
    """Period of the FFT peak (Hann window, 16x zero padding, parabolic interpolation)
    of the record resampled linearly to a uniform step (probes are sampled at the
    first step past each probe time)."""
    step = np.median(np.diff(t))
    uniform = np.arange(t[0], t[-1], step)
    eta = np.interp(uniform, t, eta)
    windowed = (eta - eta.mean()) * np.hanning(len(eta))
    n = 16 * len(eta)
    spectrum = np.abs(np.fft.rfft(windowed, n))
    k = int(np.argmax(spectrum[1:])) + 1
    left, centre, right = np.log(spectrum[k - 1:k + 2])
    shift = 0.5 * (left - right) / (left - 2.0 * centre + right)
    return n * step / (k + shift)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="")
    parser.add_argument("--run", help="check an existing run folder instead of running the case")
    parser.add_argument("--probe", required=True, help="the wave_height probe (its point sets the base)")
    parser.add_argument("--tolerance", type=float, default=0.01)
    parser.add_argument("--after", type=float, help="start of the free sloshing (s)")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("solver", nargs="?")
    parser.add_argument("case", nargs="?")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as scratch:
        if args.run:
            folder = pathlib.Path(args.run)
        else:
            folder = run_solver(args.launcher, args.solver, args.case, f"{scratch}/run", args.set)
        resolved = yaml.safe_load((folder / "case.resolved.yaml").read_text())
        fluid = resolved["fluid"]
        g, spacing, dim = fluid["gravity"], fluid["spacing"], fluid["dimension"]
        cylinder = fluid["geometry"]["type"] == "cylindrical_tank"
        depth = math.ceil(fluid["fill"]["level"] / spacing - 1e-9) * spacing
        record = next(r for r in fluid["probes"] if r["name"] == args.probe)
        base = record["position"][dim - 1]
        _, rows = probe(folder, args.probe)
        if cylinder:
            radius = fluid["geometry"]["radius"]
            expected = convective_period(radius, depth, g)
            label = f"cylinder, R = {radius} m, H = {depth:.3f} m: first mode (xi = 1.8412) T = {expected:.4f} s"
        else:
            width = fluid["geometry"]["width"]
            mode = fluid["initial_velocity"]["mode"]
            k = mode * math.pi / width
            expected = 2.0 * math.pi / math.sqrt(g * k * math.tanh(k * depth))
            label = f"mode {mode}, L = {width} m, H = {depth:.3f} m: Faltinsen T = {expected:.4f} s"
    t, eta = rows[:, 0], rows[:, 1] - (depth - base)
    start = args.after if args.after is not None else 0.25 * expected
    keep = np.isfinite(eta) & (t >= start)
    t, eta = t[keep], eta[keep]
    periods = np.concatenate([np.diff(crossings(t, eta, True)), np.diff(crossings(t, eta, False))])
    if len(periods) < 2:
        print(f"FAIL: fewer than two full periods in the record ({t[-1]:.2f} s; expected period {expected:.4f} s)")
        return 1
    measured = periods.mean()
    error = measured / expected - 1.0
    print(label)
    print(f"zero crossings: {len(periods)} periods {np.round(periods, 4).tolist()}, mean {measured:.4f} s, "
          f"error {100 * error:+.2f} % (tolerance {100 * args.tolerance:g} %)")
    print(f"FFT peak (not asserted): {fft_period(t, eta):.4f} s")
    print(f"amplitude: first crest {1000 * eta.max():.2f} mm, largest trough {1000 * eta.min():.2f} mm")
    if abs(error) > args.tolerance:
        print(f"FAIL: period off by {100 * error:+.2f} %")
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
