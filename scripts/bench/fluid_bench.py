#!/usr/bin/python3
"""Fluid benchmark: runs sph_solver on benchmark cases and writes their figures.

Usage: fluid_bench.py --solver build/bin/sph_solver --output bench/fluid [--quick] [--case NAME ...] [--ranks 1,2]

For each case and rank count it records: particles, steps, particle-steps per
second, wall seconds per simulated second, the share of each stage (neighbours,
ppe_assemble, ppe_solve, predictor = viscosity and walls at x^n, corrector),
mean and max PPE iterations, and peak resident memory per particle (the largest
rank's peak resident set times the rank count, over the particles).
Figures go to OUTPUT/fluid_figures.json and a table to OUTPUT/fluid_figures.md.
Nothing is asserted: a benchmark reports, the reader judges.

Full set (a workstation or a cluster node; tens of minutes to hours):
  2D dam break at L0 = 0.01 m and 0.005 m for 2 s, and at both for 0.6 s (the
  surge to the far wall, beside the weakly-compressible reference of
  scripts/bench.sh wcsph when OUTPUT holds its figures); 3D cylindrical tank at rest at
  L0 chosen for >= 100k particles; each on 1 and 2 ranks.
--quick (what a 2-core machine does in minutes): 2D dam break at L0 = 0.02 m for
  0.3 s on 1 and 2 ranks.
--case NAME (repeatable): only these cases of the set; --ranks LIST: only these
rank counts (comma-separated; default 1,2).
A measured row replaces the earlier row of its case and rank count in OUTPUT's
files and the other rows stay (the set can be measured a piece at a time);
each row names the date and the commit it was measured on.
"""
import argparse
import datetime
import json
import pathlib
import subprocess
import tempfile

from measured_run import measured_run

FULL = [
    ("dam_break_2d", "cases/dam_break_2d/case.yaml", ["fluid.spacing=0.01", "end_time=2.0"]),
    # The collapse and surge to the far wall: what the weakly-compressible reference
    # (scripts/bench/wcsph_reference.py) runs to compare with.
    ("dam_break_2d_front", "cases/dam_break_2d/case.yaml", ["fluid.spacing=0.01", "end_time=0.6"]),
    ("dam_break_2d_fine", "cases/dam_break_2d/case.yaml", ["fluid.spacing=0.005", "end_time=2.0"]),
    # The fine column's collapse and surge alone: its 1- and 2-rank rows in about half
    # an hour together (the whole 2 s takes hours on one rank).
    ("dam_break_2d_fine_front", "cases/dam_break_2d/case.yaml", ["fluid.spacing=0.005", "end_time=0.6"]),
    # 0.39 m^3 of liquid: L0 = 0.015 m gives about 116,000 particles (0.04 m gave 6,000).
    ("cylinder_3d_rest", "cases/hydrostatic_3d/case.yaml", ["fluid.spacing=0.015", "end_time=0.5"]),
]
QUICK = [("dam_break_2d_quick", "cases/dam_break_2d/case.yaml", ["fluid.spacing=0.02", "end_time=0.3"])]


# The 3D case must be what the benchmark says it is (issue: at least 100k particles).
MINIMUM_PARTICLES = {"cylinder_3d_rest": 100_000}


def run(solver, case, settings, ranks, folder):
    summary, elapsed, peak_kib = measured_run(solver, case, settings + ["output.field_interval=1000"], ranks, folder)
    fluid = summary["fluid"]
    stages = summary["programs"]["sph_solver"]["stages"]
    total = sum(s["seconds"] for s in stages.values())
    return {
        "ranks": ranks,
        "particles": fluid["particles"],
        "steps": fluid["steps"],
        "simulated_s": fluid["end_time_s"],
        "wall_s": elapsed,
        "particle_steps_per_s": fluid["particle_steps_per_second"],
        "wall_s_per_simulated_s": fluid["wall_seconds_per_simulated_second"],
        "ppe_iterations_mean": fluid["ppe_iterations"]["mean"],
        "ppe_iterations_max": fluid["ppe_iterations"]["max"],
        "ppe_hierarchy_builds": fluid.get("ppe_hierarchy_builds", fluid["steps"]),
        "stage_share": {name: s["seconds"] / total for name, s in stages.items()},
        "peak_memory_per_particle_kib": peak_kib * ranks / max(fluid["particles"], 1),
    }


def commit():
    """The checkout's commit, marked when the tree has changes of its own."""
    def git(*words):
        return subprocess.run(["git", *words], cwd=pathlib.Path(__file__).parent, capture_output=True, text=True).stdout
    head = git("rev-parse", "--short", "HEAD").strip() or "unknown"
    return head + ("+changes" if git("status", "--porcelain", "--untracked-files=no").strip() else "")


def setting(settings, key):
    """The value of `key` among a case's --set overrides ("key=value"), as a number."""
    return next(float(item.split("=", 1)[1]) for item in settings if item.startswith(key + "="))


def against_reference(out, figures):
    """Lines setting the dam-break rows beside the weakly-compressible code's run of
    the same spacing and simulated time (OUTPUT/wcsph_reference.json, written by
    scripts/bench.sh wcsph), when there is one."""
    path = out / "wcsph_reference.json"
    if not path.exists():
        return []
    reference = json.loads(path.read_text())
    lines = []
    for name, _, settings in FULL + QUICK:
        if not name.startswith("dam_break") or name not in figures:
            continue
        if (setting(settings, "fluid.spacing"), setting(settings, "end_time")) != \
                (reference["spacing_m"], reference["simulated_s"]):
            continue
        for r in figures[name]:
            lines.append(f"- {name} on {r['ranks']} rank{'s' if r['ranks'] > 1 else ''}: {r['wall_s']:.0f} s, {r['steps']:,} steps; "
                         f"{reference['code']} on {reference['threads']} threads ({reference['date']}): "
                         f"{reference['wall_s']:.0f} s, {reference['steps']:,} steps — "
                         f"{reference['wall_s'] / r['wall_s']:.2f} times ours")
    return ["", "Against a weakly-compressible SPH code, the same column, spacing and simulated time:"] + lines \
        if lines else []


def write(out, figures):
    """Writes OUTPUT/fluid_figures.json and the Markdown table of the same rows."""
    (out / "fluid_figures.json").write_text(json.dumps(figures, indent=2))
    lines = ["| case | ranks | particles | steps | particle-steps/s | wall s / sim s | PPE it. mean/max | "
             "neighbours | ppe_assemble | ppe_solve | predictor | corrector | KiB/particle | measured |",
             "|" + "---|" * 14]
    for name, rows in figures.items():
        for r in rows:
            share = r["stage_share"]
            lines.append(f"| {name} | {r['ranks']} | {r['particles']} | {r['steps']} | {r['particle_steps_per_s']:.3g} | "
                         f"{r['wall_s_per_simulated_s']:.3g} | {r['ppe_iterations_mean']:.1f}/{r['ppe_iterations_max']} | "
                         + " | ".join(f"{100 * share.get(s, 0):.0f} %" for s in
                                      ("neighbours", "ppe_assemble", "ppe_solve", "predictor", "corrector"))
                         + f" | {r['peak_memory_per_particle_kib']:.2f} | "
                         f"{r.get('date', 'date not recorded')} {r.get('commit', '')} |")
    lines += against_reference(out, figures)
    (out / "fluid_figures.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--solver", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--case", action="append", default=[], help="only this case of the set (repeatable)")
    parser.add_argument("--ranks", default="1,2", help="rank counts to measure, comma-separated (default 1,2)")
    args = parser.parse_args()
    chosen = QUICK if args.quick else FULL
    unknown = sorted(set(args.case) - {name for name, _, _ in chosen})
    if unknown:
        parser.error(f"unknown case {', '.join(unknown)} (this set has: {', '.join(n for n, _, _ in chosen)})")
    if args.case:
        chosen = [c for c in chosen if c[0] in args.case]
    try:
        rank_counts = [int(r) for r in args.ranks.split(",")]
    except ValueError:
        parser.error(f"--ranks: '{args.ranks}' is not a comma-separated list of rank counts")
    if not rank_counts or min(rank_counts) < 1:
        parser.error(f"--ranks: '{args.ranks}' needs rank counts of at least 1")
    out = pathlib.Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    earlier = out / "fluid_figures.json"
    figures = json.loads(earlier.read_text()) if earlier.exists() else {}
    measured = {"date": datetime.date.today().isoformat(), "commit": commit()}
    with tempfile.TemporaryDirectory() as scratch:
        for name, case, settings in chosen:
            for ranks in rank_counts:
                folder = pathlib.Path(scratch) / f"{name}-{ranks}"
                row = run(args.solver, case, settings, ranks, folder) | measured
                if row["particles"] < MINIMUM_PARTICLES.get(name, 0):
                    raise SystemExit(f"fluid_bench: {name} has {row['particles']} particles, "
                                     f"fewer than the {MINIMUM_PARTICLES[name]} it is meant to measure")
                print(name, row, flush=True)
                rows = [r for r in figures.get(name, []) if r["ranks"] != ranks] + [row]
                figures[name] = sorted(rows, key=lambda r: r["ranks"])
                write(out, figures)  # after each run, so a stopped set keeps what it measured


if __name__ == "__main__":
    main()
