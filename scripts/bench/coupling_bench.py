#!/usr/bin/python3
"""Coupling benchmark: the solver dummies (coupling/examples) exchange an
interface of 10k and 100k vertices at 1:1 and 2:2 fluid:structure ranks, with
parallel staggered and implicit (IQN-ILS) coupling. Figures: wall time per
window, and the share of wall time the dummies spend in the coupling (waiting
for the partner, and working: reductions, packing, acceleration). The dummies'
own physics is one oscillator per vertex, so the figures are close to the
coupling's own cost.

Usage: coupling_bench.py --dummy build/bin/solver_dummy --output bench [--quick]
Writes OUTPUT/coupling_figures.json and OUTPUT/coupling_figures.md.
"""
import argparse
import json
import pathlib
import re
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parents[2]
LINE = re.compile(r"solver_dummy \((?P<side>\w+), (?P<ranks>\d+) ranks\): (?P<windows>\d+) windows, (?P<vertices>\d+) "
                  r"vertices, error (?P<error>\S+), (?P<iterations>\S+) iterations per window, wall (?P<wall>\S+) s, "
                  r"solver (?P<solver>\S+) s, coupling wait (?P<wait>\S+) s, coupling work (?P<work>\S+) s, "
                  r"\S+ ms per window, set-up (?P<setup>\S+) s")

SCHEMES = {
    "parallel_staggered": "coupling:\n  scheme: parallel_staggered\n  time_window: 0.01\n",
    "implicit_iqn_ils": ("coupling:\n  scheme: implicit\n  time_window: 0.01\n  ramp_chi: 2\n  implicit:\n"
                         "    relative_tolerance: 1e-8\n  acceleration:\n    type: iqn_ils\n"),
}


def run(dummy, case, vertices, fluid_ranks, structure_ranks):
    command = ["mpirun", "--oversubscribe", "-np", str(fluid_ranks), dummy, "--side", "fluid", str(case),
               "--vertices", str(vertices), ":", "-np", str(structure_ranks), dummy, "--side", "structure", str(case),
               "--vertices", str(vertices)]
    result = subprocess.run(command, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"benchmark run failed: {' '.join(command)}\n{result.stdout}\n{result.stderr[-3000:]}")
    sides = {}
    for line in result.stdout.splitlines():
        match = LINE.search(line)
        if match:
            sides[match["side"]] = {k: float(v) for k, v in match.groupdict().items() if k != "side"}
    return sides


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--dummy", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--quick", action="store_true", help="10k vertices and 1:1 only")
    args = parser.parse_args()
    sizes = [10_000] if args.quick else [10_000, 100_000]
    splits = [(1, 1)] if args.quick else [(1, 1), (2, 2)]
    end_time = 1.0  # 100 windows
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for scheme, section in SCHEMES.items():
            case = pathlib.Path(scratch) / f"{scheme}.yaml"
            case.write_text(f"title: coupling benchmark\nend_time: {end_time}\n" + section)
            for vertices in sizes:
                for fluid_ranks, structure_ranks in splits:
                    sides = run(args.dummy, case, vertices, fluid_ranks, structure_ranks)
                    fluid = sides["fluid"]
                    windows = fluid["windows"]
                    row = {
                        "scheme": scheme, "vertices": vertices, "ranks": f"{fluid_ranks}:{structure_ranks}",
                        "windows": windows, "iterations_per_window": fluid["iterations"],
                        "ms_per_window": 1e3 * fluid["wall"] / windows, "setup_s": fluid["setup"],
                    }
                    for name, side in sides.items():
                        row[f"{name}_wait_share"] = side["wait"] / side["wall"]
                        row[f"{name}_work_share"] = side["work"] / side["wall"]
                    rows.append(row)
                    print(json.dumps(row), flush=True)
    out = pathlib.Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    (out / "coupling_figures.json").write_text(json.dumps(rows, indent=2) + "\n")
    lines = ["# Coupling benchmark (solver dummies, one oscillator per vertex)", "",
             f"{end_time / 0.01:.0f} windows of 0.01 s each run, timed from the first window on (set-up apart); shares are of "
             "each program's wall time; wait includes the time the partner works.", "",
             "| scheme | vertices | ranks f:s | iterations/window | ms/window | fluid wait | fluid work | "
             "structure wait | structure work | set-up (s) |", "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['scheme']} | {r['vertices']} | {r['ranks']} | {r['iterations_per_window']:.2f} | "
                     f"{r['ms_per_window']:.2f} | {100 * r['fluid_wait_share']:.0f} % | {100 * r['fluid_work_share']:.0f} % | "
                     f"{100 * r['structure_wait_share']:.0f} % | {100 * r['structure_work_share']:.0f} % | {r['setup_s']:.2f} |")
    (out / "coupling_figures.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
