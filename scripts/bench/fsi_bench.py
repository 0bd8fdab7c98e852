"""Coupled-run benchmark: where the wall time of sph_solver : fem_solver goes
(fluid stages, structure stages, each program's wait for its partner, the
coupling library's own work), for coupled cases and coupling variants: the
elastic plate, explicit and implicit, and the flexible cylinder, both
staggered schemes with the added-mass operator (implicit coupling does not
converge there: its README).
Writes <output>/fsi_figures.json and fsi_figures.md.

Each program's share is of its own wall time: in a parallel staggered job
both compute at once and one waits for the slower; in a serial implicit job
they take turns and each waits while the other computes."""
import argparse
import json
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[1] / "post"))
from coupled_run import run_coupled  # noqa: E402
from stability_study import variant_case  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]

# (case, label, coupling variant of stability_study.VARIANTS, extra --set overrides)
RUNS = [
    ("cases/hydrostatic_elastic_plate_2d/case.yaml", "plate, implicit IQN-ILS", "implicit IQN-ILS, window average",
     ["end_time=0.1"]),
    # The aluminium plate diverges under explicit coupling; ten times denser it does not (README's table).
    ("cases/hydrostatic_elastic_plate_2d/case.yaml", "plate x10 density, parallel staggered",
     "parallel staggered, window average", ["end_time=0.1", "structure.material.density=27000"]),
    ("cases/hydrostatic_elastic_plate_2d/case.yaml", "plate x10 density, implicit IQN-ILS",
     "implicit IQN-ILS, window average", ["end_time=0.1", "structure.material.density=27000"]),
    ("cases/flexible_cylinder_3d/case.yaml", "cylinder, sequential staggered, added mass",
     "sequential staggered (structure first), window average, added mass", ["end_time=0.03"]),
    ("cases/flexible_cylinder_3d/case.yaml", "cylinder, parallel staggered, added mass",
     "parallel staggered, window average, added mass", ["end_time=0.03"]),
]


def stage_seconds(summary, program):
    return sum(s["seconds"] for s in summary["programs"][program]["stages"].values())


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--output", default="bench")
    parser.add_argument("--quick", action="store_true", help="the first run only")
    parser.add_argument("--fluid-ranks", type=int, default=1)
    args = parser.parse_args()
    out = pathlib.Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    figures = []
    for case, label, variant, settings in RUNS[:1] if args.quick else RUNS:
        window = float(__import__("yaml").safe_load((ROOT / case).read_text())["coupling"]["time_window"])
        folder = out / "fsi_runs" / label.replace(" ", "_").replace(",", "")
        copy = variant_case(ROOT / case, variant, window, folder)
        run = run_coupled(copy, folder, settings, args.fluid_ranks, 1)
        if run.status != 0:
            print(f"{label}: failed: {run.failure()}")
            figures.append({"run": label, "failed": run.failure()})
            continue
        fluid, structure = run.fluid, run.structure
        fluid_wall = fluid["programs"]["sph_solver"]["wall_time_s"]
        structure_wall = structure["programs"]["fem_solver"]["wall_time_s"]
        f = {
            "run": label,
            "wall_s": run.seconds,
            "simulated_s": fluid["fluid"]["end_time_s"],
            "windows": structure["coupling"]["windows"],
            "iterations_per_window": structure["coupling"]["iterations_per_window"],
            "fluid_particles": fluid["fluid"]["particles"],
            "fluid_compute_share": stage_seconds(fluid, "sph_solver") / fluid_wall,
            "fluid_wait_share": fluid["fluid"]["coupling"]["wait_s"] / fluid_wall,
            "fluid_coupling_work_share": fluid["fluid"]["coupling"]["work_s"] / fluid_wall,
            "structure_compute_share": stage_seconds(structure, "fem_solver") / structure_wall,
            "structure_wait_share": structure["coupling"]["wait_s"] / structure_wall,
            "structure_coupling_work_share": structure["coupling"]["work_s"] / structure_wall,
        }
        f["wall_s_per_window"] = f["wall_s"] / max(f["windows"], 1)
        figures.append(f)
        print(json.dumps(f), flush=True)
    (out / "fsi_figures.json").write_text(json.dumps(figures, indent=1))
    lines = ["Coupled runs (fluid 1 rank, structure 1 rank unless stated): share of each program's wall time.", "",
             "| run | wall (s) | simulated (s) | windows | iterations / window | wall per window (ms) | fluid compute "
             "| fluid wait | structure compute | structure wait | coupling work (fluid / structure) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for f in figures:
        if "failed" in f:
            lines.append(f"| {f['run']} | failed: {f['failed']} |||||||||")
            continue
        lines.append(f"| {f['run']} | {f['wall_s']:.1f} | {f['simulated_s']:g} | {f['windows']} | "
                     f"{f['iterations_per_window']:.2f} | {1000 * f['wall_s_per_window']:.1f} | "
                     f"{100 * f['fluid_compute_share']:.1f} % | {100 * f['fluid_wait_share']:.1f} % | "
                     f"{100 * f['structure_compute_share']:.1f} % | {100 * f['structure_wait_share']:.1f} % | "
                     f"{100 * f['fluid_coupling_work_share']:.2f} % / {100 * f['structure_coupling_work_share']:.2f} % |")
    (out / "fsi_figures.md").write_text("\n".join(lines) + "\n")
    print(f"wrote {out / 'fsi_figures.md'}")


if __name__ == "__main__":
    main()
