#!/usr/bin/python3
"""Stability study of a coupled case: every coupling variant x window length x
structure density, run as a coupled job, tabulated in Markdown.

  scripts/post/stability_study.py --case cases/hydrostatic_elastic_plate_2d/case.yaml \
      --probe structure:midspan:displacement_m --mean-after 0.05 --end-time 0.1 \
      --windows 0.0005,0.001,0.002 --densities 2700,27000 --output study.md

For each run: whether it stayed bounded (ran to the end with the probe below
--bound times its settled scale), the probe's mean after --mean-after and the
amplitude about it (half the range), the dominant period of the probe (zero
crossings of its deviation from the mean, when it oscillates), coupling
iterations per window and wall time. The fluid and structure steps are capped
at min(--step, window) so that every window holds whole steps.
"""
import argparse
import json
import pathlib
import re
import shutil
import sys

import yaml

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from coupled_run import CoupledRun, derived_case, run_coupled  # noqa: E402

# The coupling section of each variant (the case's own is replaced, its
# timeout kept): keys that only one scheme takes cannot be overridden with --set.
VARIANTS = {
    "parallel staggered, ramp chi 1 (paper)": {"scheme": "parallel_staggered", "ramp_chi": 1},
    "parallel staggered, window average": {"scheme": "parallel_staggered", "structure_load": "window_average"},
    "sequential staggered, window average": {"scheme": "sequential_staggered", "structure_load": "window_average"},
    "implicit Aitken, window average": {"scheme": "implicit", "acceleration": {"type": "aitken"},
                                        "structure_load": "window_average"},
    "implicit IQN-ILS, window average": {"scheme": "implicit", "acceleration": {"type": "iqn_ils"},
                                         "structure_load": "window_average"},
    "implicit IQN-ILS, ramp chi 2": {"scheme": "implicit", "acceleration": {"type": "iqn_ils"}, "ramp_chi": 2},
    # The added-mass operator carried by the structure (coupling/PROTOCOL.md "Added mass").
    "parallel staggered, window average, added mass": {"scheme": "parallel_staggered",
                                                       "structure_load": "window_average", "added_mass": "computed"},
    "sequential staggered (structure first), window average, added mass": {
        "scheme": "sequential_staggered", "first": "structure", "structure_load": "window_average",
        "added_mass": "computed"},
}


def variant_case(case, variant, window, folder):
    """The case with the variant's coupling section, written into `folder`."""
    coupling = dict(VARIANTS[variant], time_window=window)
    own = yaml.safe_load(pathlib.Path(case).read_text()).get("coupling", {})
    if "timeout" in own:
        coupling["timeout"] = own["timeout"]
    return derived_case(case, folder, sections={"coupling": coupling})


def oscillation_period(times, values, mean):
    """Mean spacing of successive upward crossings of the mean, or None."""
    ups = []
    for k in range(1, len(values)):
        a, b = values[k - 1] - mean, values[k] - mean
        if a < 0 <= b:
            ups.append(times[k - 1] + (times[k] - times[k - 1]) * (-a) / (b - a))
    if len(ups) < 3:
        return None
    return (ups[-1] - ups[0]) / (len(ups) - 1)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--case", required=True)
    parser.add_argument("--probe", required=True, help="side:name:column")
    parser.add_argument("--mean-after", type=float, required=True)
    parser.add_argument("--end-time", type=float, required=True)
    parser.add_argument("--windows", required=True, help="coupling windows (s), comma-separated")
    parser.add_argument("--densities", required=True, help="structure densities (kg/m^3), comma-separated")
    parser.add_argument("--variants", default=",".join(str(k) for k in range(len(VARIANTS))),
                        help="indices into the variant list, comma-separated: " +
                             "; ".join(f"{k}: {v}" for k, v in enumerate(VARIANTS)))
    parser.add_argument("--step", type=float, default=0.00025, help="largest fluid and structure step (s)")
    parser.add_argument("--bound", type=float, default=20.0)
    parser.add_argument("--expected",
                        help="the settled value as a Python expression of rho (the structure density), e.g. the "
                             "static deflection: a run whose mean is off it by more than half, or whose probe "
                             "exceeds --bound times it, is not bounded")
    parser.add_argument("--ringing", action="store_true",
                        help="the probe rings after an excitation: a run is bounded when its ringing over the "
                             "last third of the record after --mean-after is below the first third's (a decaying "
                             "ringing may be larger than the mean), instead of an amplitude below the mean")
    parser.add_argument("--tabulate-only", action="store_true",
                        help="read the runs already in --folder instead of running them")
    parser.add_argument("--fluid-ranks", type=int, default=1)
    parser.add_argument("--structure-ranks", type=int, default=1)
    parser.add_argument("--set", action="append", default=[], help="further overrides for every run")
    parser.add_argument("--folder", default="stability_runs")
    parser.add_argument("--output", required=True)
    args = parser.parse_args()
    side, name, column = args.probe.split(":")
    names = list(VARIANTS)
    chosen = [names[int(k)] for k in args.variants.split(",")]
    windows = [float(w) for w in args.windows.split(",")]
    densities = [float(d) for d in args.densities.split(",")]

    rows = []
    for density in densities:
        for window in windows:
            for variant in chosen:
                step = min(args.step, window)
                settings = [f"end_time={args.end_time}", f"fluid.time_step.max={step}", f"structure.time_step={step}",
                            f"structure.material.density={density}"] + args.set
                folder = pathlib.Path(args.folder) / f"rho{density:g}_w{window:g}_{names.index(variant)}"
                if args.tabulate_only:
                    logs = [folder / "output.txt"] if (folder / "output.txt").exists() else \
                        [folder / side / "run.log" for side in ("fluid", "structure")]
                    output = "".join(p.read_text() for p in logs if p.exists())
                    run = CoupledRun(folder, 0 if (folder / "structure" / "summary.json").exists() else 1,
                                     float("nan"), output)
                    if (folder / "seconds.json").exists():
                        run.seconds = json.loads((folder / "seconds.json").read_text())
                    elif run.structure:
                        run.seconds = run.structure["programs"]["fem_solver"]["wall_time_s"]
                else:
                    shutil.rmtree(folder, ignore_errors=True)
                    case = variant_case(args.case, variant, window, folder)
                    run = run_coupled(case, folder, settings, args.fluid_ranks, args.structure_ranks)
                    (folder / "output.txt").write_text(run.output)
                    (folder / "seconds.json").write_text(json.dumps(run.seconds))
                row = {"variant": variant, "window": window, "density": density, "seconds": run.seconds}
                try:
                    probe = run.probe(side, name)
                except (OSError, ValueError, IndexError):
                    probe = None
                if run.status != 0 or probe is None:
                    row["failure"] = run.failure()
                    # The failing program names the time; the other's probes may not be flushed.
                    said = re.search(r"t = ([0-9.eE+-]+) s", row["failure"])
                    row["outcome"] = f"diverged at t = {float(said.group(1)):.4f} s" if said else "failed"
                else:
                    times = [t for t in probe["time_s"] if t >= args.mean_after]
                    values = [v for t, v in zip(probe["time_s"], probe[column]) if t >= args.mean_after]
                    mean = sum(values) / len(values)
                    amplitude = 0.5 * (max(values) - min(values))
                    largest = max(abs(v) for v in probe[column])
                    coupling = run.structure.get("coupling", {})
                    row.update(mean=mean, amplitude=amplitude, period=oscillation_period(times, values, mean),
                               iterations=coupling.get("iterations_per_window", 1.0))
                    scale = abs(eval(args.expected, {"rho": density})) if args.expected else abs(mean)
                    if args.ringing:
                        # Ringing about a mean that may be near zero: only the
                        # ringing's own growth counts (a diverging run stops itself).
                        third = max(len(values) // 3, 1)
                        early, late = values[:third], values[-third:]
                        unbounded = max(late) - min(late) > max(early) - min(early)
                    else:
                        unbounded = largest > args.bound * max(scale, 1e-300) or amplitude > scale
                    if args.expected:
                        expected = eval(args.expected, {"rho": density})
                        row["error"] = mean / expected - 1.0
                        unbounded = unbounded or abs(row["error"]) > 0.5
                    row["outcome"] = "grows" if unbounded else "bounded"
                rows.append(row)
                print(f"{variant} | window {window} s | density {density} | {row['outcome']} | "
                      f"{row.get('mean', float('nan')):.4e} | {run.seconds:.1f} s | {row.get('failure', '')}", flush=True)

    lines = [f"Stability study of `{args.case}` ({args.end_time} s simulated, probe {name}:{column}; "
             f"fluid {args.fluid_ranks} rank(s), structure {args.structure_ranks}).", "",
             f"| structure density (kg/m³) | window (s) | coupling | outcome | mean after {args.mean_after} s "
             f"| against expected | amplitude | period (s) | iterations / window | wall time (s) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in rows:
        mean = f"{r['mean']:.4e}" if "mean" in r else "—"
        amplitude = f"{r['amplitude']:.2e}" if "amplitude" in r else "—"
        period = f"{r['period']:.4f}" if r.get("period") else "—"
        iterations = f"{r['iterations']:.2f}" if "iterations" in r else "—"
        error = f"{100 * r['error']:+.1f} %" if "error" in r else "—"
        seconds = f"{r['seconds']:.1f}" if r["seconds"] == r["seconds"] else "—"
        lines.append(f"| {r['density']:g} | {r['window']:g} | {r['variant']} | {r['outcome']} | {mean} | {error} | {amplitude} "
                     f"| {period} | {iterations} | {seconds} |")
    pathlib.Path(args.output).write_text("\n".join(lines) + "\n")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
