#!/usr/bin/python3
"""Validation: liquid at rest in a tank (VALIDATION.md, "Hydrostatic column").

Usage: check_hydrostatic.py --launcher "mpiexec -n 2" [--settled-after T] [--known-unmet settling|particles ...]
                            [--level-probe NAME] SPH_SOLVER CASE.yaml [--set k=v ...]

Runs the case and checks, at every sample of the settled window t >= T (default:
the second half of the run) — not time averages —
  - max |v| (the largest particle speed of each sampled step) below
    1e-3 sqrt(g H): the liquid settles and stays settled;
  - every pressure probe within 1 % of rho g (H - y), H the top of the highest
    particle layer (the fill level rounded to whole layers) — or, with
    --level-probe, the mean of that wave-height probe over the settled window:
    for a tank whose filling leaves gaps at a curved wall, into which the
    liquid settles below the filled level (the level's drop is printed);
  - in the last snapshot, the pressure of every particle deeper than two layers
    (2 L0) within 1 % of rho g (H - y) ("below the first two surface layers");
  - the vertical wall force within 0.5 % of the liquid's weight and the lateral
    force below 0.1 % of it (VALIDATION.md, "Wall force balance");
  - no particle lost through a wall or out of the tank, and none put back in
    front of a wall it had passed (wall_crossings.hpp: at rest the pressure alone
    must hold the liquid off the walls).
The tolerances are VALIDATION.md's. A criterion named by --known-unmet (a case
that does not meet it yet, said in its README) is measured and printed but not
asserted, and the output says so; the others still fail the test.
"""
import argparse
import math
import sys
import tempfile

import h5py
import numpy as np
import yaml

from fluid_run import probe, run_solver, summary


def last_snapshot(folder):
    """(positions, pressures) of the last particle snapshot in fluid.h5."""
    with h5py.File(folder / "fluid.h5", "r") as f:
        step = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
        return f[step]["position"][:].reshape(-1, 3), f[step]["fields/pressure"][:]


def liquid_mass(folder):
    """The particles' total mass in the first snapshot of fluid.h5 (their masses
    differ on the rings of a cylindrical tank's filling)."""
    with h5py.File(folder / "fluid.h5", "r") as f:
        step = sorted(k for k in f.keys() if k.startswith("step_"))[0]
        return float(f[step]["fields/mass"][:].sum())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="")
    parser.add_argument("--settled-after", type=float, default=None,
                        help="start of the settled window (s); default half the run")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--known-unmet", action="append", default=[], choices=["settling", "particles"],
                        help="measure and print this criterion, but do not assert it")
    parser.add_argument("--level-probe", default=None,
                        help="wave-height probe whose settled mean is the free surface H (default: the filled level)")
    parser.add_argument("solver")
    parser.add_argument("case")
    args = parser.parse_args()
    failures = []
    unmet = []  # known not to be met (--known-unmet): printed, not asserted
    with tempfile.TemporaryDirectory() as scratch:
        folder = run_solver(args.launcher, args.solver, args.case, f"{scratch}/run", args.set)
        # The case as the solver read it, overrides and defaults applied.
        fluid = yaml.safe_load((folder / "case.resolved.yaml").read_text())["fluid"]
        rho, g, spacing, dim = fluid["density"], fluid["gravity"], fluid["spacing"], fluid["dimension"]
        surface = math.ceil(fluid["fill"]["level"] / spacing - 1e-9) * spacing
        run = summary(folder)["fluid"]
        end = run["end_time_s"]
        settled = 0.5 * end if args.settled_after is None else args.settled_after
        # The kernel and h as run (the case file may name neither: their defaults).
        kernel, h = run["kernel"], run["smoothing_length_m"]
        print(f"kernel {kernel}, h = {h / spacing:.3g} L0; settled window: {settled:g} s to {end:g} s")

        if args.level_probe is not None:
            _, level_rows = probe(folder, args.level_probe)
            filled, surface = surface, level_rows[level_rows[:, 0] >= settled - 1e-9, 1].mean()
            print(f"free surface H = {surface:.4f} m from probe {args.level_probe} "
                  f"({1e3 * (surface - filled):+.1f} mm from the filled level {filled:g} m)")

        header, rows = probe(folder, "fluid")
        window = rows[rows[:, 0] >= settled - 1e-9]
        speed = window[:, header.index("max_speed_m_s")]
        limit = 1e-3 * math.sqrt(g * surface)
        print(f"max |v|: largest {speed.max():.2e} m/s, last {speed[-1]:.2e} m/s (limit 1e-3 sqrt(g H) = {limit:.2e})")
        if speed.max() >= limit:
            message = f"max |v| {speed.max():.2e} m/s in the settled window (limit {limit:.2e})"
            (unmet if "settling" in args.known_unmet else failures).append(message)

        for record in fluid.get("probes", []):
            if record["quantity"] != "pressure":
                continue
            _, probe_rows = probe(folder, record["name"])
            late = probe_rows[probe_rows[:, 0] >= settled - 1e-9, 1]
            height = record["position"][dim - 1]
            expected = rho * g * (surface - height)
            worst = np.abs(late / expected - 1.0).max()
            print(f"{record['name']}: mean {late.mean():.1f} Pa, expected {expected:.1f} Pa, "
                  f"mean error {100 * (late.mean() / expected - 1):+.3f} %, worst sample {100 * worst:.3f} %")
            if worst > 0.01:
                failures.append(f"{record['name']}: pressure off by up to {100 * worst:.2f} % (tolerance 1 %)")

        positions, pressures = last_snapshot(folder)
        depth = surface - positions[:, dim - 1]
        deep = depth > 2.0 * spacing
        error = np.abs(pressures[deep] / (rho * g * depth[deep]) - 1.0)
        print(f"last snapshot: {deep.sum()} particles deeper than 2 L0, pressure error up to {100 * error.max():.3f} %, "
              f"{100 * (error > 0.01).mean():.0f} % of them beyond 1 %")
        if error.max() > 0.01:
            message = f"a particle's pressure off by {100 * error.max():.2f} % (tolerance 1 %)"
            (unmet if "particles" in args.known_unmet else failures).append(message)

        weight = liquid_mass(folder) * g  # per metre of depth in 2D, as the forces
        up = "force_y" if dim == 2 else "force_z"
        forces = [k for k, c in enumerate(header) if c.startswith("force_")]
        vertical = next(k for k in forces if header[k].startswith(up))
        vertical_error = np.abs(-window[:, vertical] / weight - 1.0).max()
        lateral = max(np.abs(window[:, k]).max() for k in forces if k != vertical)
        print(f"wall force: weight {weight:.2f}, vertical force off by up to {100 * vertical_error:.4f} %, "
              f"lateral up to {lateral:.3g}")
        if vertical_error > 0.005:
            failures.append(f"wall force off the weight by up to {100 * vertical_error:.3f} % (tolerance 0.5 %)")
        if lateral > 1e-3 * weight:
            failures.append(f"lateral wall force {lateral:.3g} above 0.1 % of the weight")
        lost = rows[-1, header.index("overflow_particles")]
        if lost != 0:
            failures.append(f"{int(lost)} particles left the tank")
        # A liquid at rest keeps off the walls by its pressure alone: none of its
        # particles may need putting back in front of a wall (wall_crossings.hpp).
        returned = run["wall_returned_particles"]
        print(f"particles put back in front of a wall: {returned}")
        if returned != 0:
            failures.append(f"{returned} particle-steps ended behind a wall and were put back")
    if unmet:
        print("NOT MET, NOT ASSERTED (--known-unmet):\n  " + "\n  ".join(unmet))
    if failures:
        print("FAIL:\n  " + "\n  ".join(failures))
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
