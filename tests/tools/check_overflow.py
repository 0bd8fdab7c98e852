#!/usr/bin/python3
"""Integration: the paper's 2D overflow set-up (cases/overflow_2d) spills over its
inner walls into the catch tank and loses nothing on the way.

Usage: check_overflow.py --launcher "mpiexec -n 2" [--min-overflow 0.01]
       SPH_SOLVER CASE.yaml [--set k=v ...]

Checks, on the run's probes:
- the liquid is conserved: the volume probe's inside (inner tank) plus outside
  (overflowed) equals the initial volume at every sample, to round-off (1e-12
  relative: the sums of the same particle volumes in another order), and no
  particle left the domain (the catch tank holds what spills);
- it overflowed: at the end at least --min-overflow of the initial volume is
  outside the inner tank (the resonant input lifts the waves well over the
  5 cm freeboard; a few stray particles would not count);
- the post-processing (scripts/post/overflow_figures.py) writes its plots and report.
Particles that went through a wall would have stopped the run (its end-of-step check).
"""
import argparse
import pathlib
import subprocess
import sys
import tempfile

import numpy as np

from fluid_run import probe, run_solver

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--launcher", required=True)
    parser.add_argument("--min-overflow", type=float, default=0.01)
    parser.add_argument("--volume-probe", default="inner_tank")
    parser.add_argument("solver")
    parser.add_argument("case")
    parser.add_argument("--set", dest="settings", action="append", default=[])
    args = parser.parse_args()
    failures = []
    with tempfile.TemporaryDirectory() as scratch:
        run = run_solver(args.launcher, args.solver, args.case, pathlib.Path(scratch) / "run", args.settings)
        header, rows = probe(run, args.volume_probe)
        inside, outside = rows[:, 1], rows[:, 2]
        total = inside + outside
        drift = np.max(np.abs(total - total[0])) / total[0]
        print(f"initial volume {total[0]:.6g} m^3/m; largest change of inside + outside {drift:.2e} (relative)")
        if drift > 1e-12:
            failures.append(f"liquid not conserved: inside + outside changed by {drift:.2e} of the initial volume")
        fluid_header, fluid = probe(run, "fluid")
        lost = fluid[:, fluid_header.index("overflow_particles")]
        if lost.max() > 0:
            failures.append(f"{int(lost.max())} particle(s) left the domain instead of landing in the catch tank")
        share = outside[-1] / total[0]
        print(f"overflowed by t = {rows[-1, 0]:.2f} s: {outside[-1]:.5g} m^3/m, {100 * share:.2f} % "
              f"(at least {100 * args.min_overflow:g} % expected)")
        if share < args.min_overflow:
            failures.append(f"overflow {100 * share:.2f} % of the liquid, expected at least {100 * args.min_overflow:g} %")
        post = subprocess.run([sys.executable, str(ROOT / "scripts" / "post" / "overflow_figures.py"), str(run),
                               "--at", str(0.5 * rows[-1, 0]), str(rows[-1, 0])], capture_output=True, text=True)
        print(post.stdout.strip())
        expected = ["overflow_report.md", "plots/overflow_history.png", "plots/overflow_periods.png"]
        missing = [name for name in expected if not (run / name).is_file()]
        if post.returncode != 0 or missing:
            failures.append(f"overflow_figures.py: exit {post.returncode}, missing {missing}\n{post.stderr}")
        else:
            print((run / "overflow_report.md").read_text())
    for failure in failures:
        print("FAIL:", failure)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
