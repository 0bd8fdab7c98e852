#!/usr/bin/python3
"""Report of a tank run as a tank engineer reads it: RUN/plots/*.png,
RUN/report.md and a combined RUN/summary.json (sloshing and bulging periods
identified from the response and from EN 1998-4 Annex A, peak wave heights
and wall pressures, roof clearance, base shear, overturning moment, the
largest von Mises stress, settings, run time).

Usage: tank_report.py RUN [--snapshot severe|last|TIME] [--sloshing-band S L] [--bulging-band S L]
                          [--tankfsi-case PATH]

RUN is a coupled job's folder (RUN/fluid, RUN/structure) or a single
program's. The programs' own summary.json files stay where they are; when
RUN/summary.json is a program's own (one folder for the run), the combined
summary goes to RUN/tank_summary.json instead. Whatever the run lacks (no
structure: a fluid-only run; no ground motion; too short a record) is a
line in the report, not an error. When the run folder has no ground
acceleration record, build/bin/tankfsi_case --prepare writes the case's one
to RUN/ground_acceleration.csv.
"""
import argparse
import json
import pathlib
import sys

import numpy as np

import tank_figures
import tank_plots
import tank_report_markdown
import tank_section
from tank_run import TankRun


# Plot files, their writers and what a missing one lacks, in report order.
PLOTS = [
    ("wave_heights.png", tank_plots.wave_heights, "Wave height histories: eta at every wave probe",
     "the run has no wave-height probe records"),
    ("wall_pressures.png", tank_plots.wall_pressures,
     "Wall pressure histories: change from t = 0 at every pressure probe", "the run has no pressure probe records"),
    ("spectra.png", tank_plots.spectra,
     "Spectra of wave height, wall pressure (and wall displacement): theory periods dashed, identified solid",
     "the run has no wave-height, pressure or displacement probe records"),
    ("base_shear_overturning.png", tank_plots.base_reactions,
     "Base shear and overturning moment histories: x, y and resultant",
     "the run has no structure (probes/structure.csv)"),
    ("ground_acceleration.png", tank_plots.ground_acceleration, "Ground acceleration: the three components applied",
     "no ground acceleration record"),
    ("period_fits.png", tank_plots.period_fits,
     "Period identification: the best record of each period against its fitted oscillator",
     "no period was identified"),
]


def make_plots(run, ground, source, theory, identification, wave, direction_deg, which):
    """Every plot; returns [(file name or None, caption)] in report order and
    what the section snapshot shows."""
    folder = run.folder / "plots"
    folder.mkdir(exist_ok=True)
    periods = {kind: result["best"][1]["period_s"] if result["best"] else None
               for kind, result in identification.items()}
    arguments = {"wave_heights.png": (run,), "wall_pressures.png": (run,), "spectra.png": (run, theory, periods),
                 "base_shear_overturning.png": (run,), "ground_acceleration.png": (ground, source),
                 "period_fits.png": (identification,)}
    made = []
    for name, writer, caption, lacking in PLOTS:
        if writer(*arguments[name], folder / name):
            made.append((name, caption))
        else:
            made.append((None, f"{caption.split(':')[0]}: not made — {lacking}"))
    section = tank_section.plot_run_section(run, direction_deg, which, wave, folder / "section_snapshot.png")
    if section:
        magnified = (f"shell displacement magnified x {section['magnification']:g}" if section["magnification"]
                     else "rigid walls (no structure)")
        made.append(("section_snapshot.png",
                     f"Section through the tank axis along {section['direction_deg']:.0f} deg "
                     f"({section['direction']}) at t = {section['time_s']:.2f} s, {section['chosen']}: "
                     f"particles by pressure, {magnified}"))
    else:
        made.append((None, "Section snapshot: not made — the run has no fluid snapshot (fluid.h5)"))
    return made, section


def combined_summary(run, motion, theory, identification, wave, pressure, clearance, reactions, stress, timing,
                     section):
    """The combined summary's dict (JSON-ready)."""
    def best(kind, key):
        entry = identification[kind]["best"]
        return entry[1][key] if entry else None

    def record(kind):
        entry = identification[kind]["best"]
        return entry[0] if entry else None

    def difference(kind, reference, periods=theory):
        value, ref = best(kind, "period_s"), periods[reference]
        return 100 * (value / ref - 1) if value and ref else None

    model_depth = theory.get("model_depth")
    if model_depth:
        model_depth = dict(model_depth,
                           sloshing_difference_percent=difference("sloshing", "convective_period_s", model_depth),
                           bulging_difference_percent=difference("bulging", "impulsive_period_s", model_depth))

    return {
        "run_folder": str(run.folder),
        "title": run.case_value("title"),
        "end_time_s": run.case_value("end_time"),
        "sloshing_period_s": best("sloshing", "period_s"),
        "sloshing_period_std_s": best("sloshing", "period_std_s"),
        "sloshing_period_record": record("sloshing"),
        "sloshing_period_records_range_s": identification["sloshing"]["range"],
        "bulging_period_s": best("bulging", "period_s"),
        "bulging_period_std_s": best("bulging", "period_std_s"),
        "bulging_period_record": record("bulging"),
        "bulging_period_records_range_s": identification["bulging"]["range"],
        "convective_period_theory_s": theory["convective_period_theory_s"],
        "impulsive_period_theory_s": theory["impulsive_period_theory_s"],
        "sloshing_period_difference_percent": difference("sloshing", "convective_period_theory_s"),
        "bulging_period_difference_percent": difference("bulging", "impulsive_period_theory_s"),
        "theory_at_model_depth": model_depth,
        "period_identification": {kind: result["records"] for kind, result in identification.items()},
        "peak_wave_height_m": {name: f["peak_m"] for name, f in wave.items()},
        "wave_heights": wave,
        "peak_pressure_Pa": {name: f["peak_pressure_Pa"] for name, f in pressure.items()},
        "peak_pressure_change_Pa": {name: f["peak_change_Pa"] for name, f in pressure.items()},
        "wall_pressures": pressure,
        "min_roof_clearance_m": clearance.get("min_roof_clearance_m"),
        "roof_clearance": clearance,
        "peak_base_shear_N": reactions["peak_base_shear_N"] if reactions else None,
        "peak_overturning_moment_Nm": reactions["peak_overturning_moment_Nm"] if reactions else None,
        "base_reactions": reactions,
        "max_von_mises_Pa": stress["max_von_mises_Pa"] if stress else None,
        "max_von_mises_location": stress,
        "peak_displacement_m": (run.structure_summary or {}).get("peak_displacement_m"),
        "wall_time_s": timing["wall_time_s"],
        "run_time": timing,
        "input_motion": motion,
        "section_snapshot": section,
        "theory_notes": theory["notes"],
        "period_notes": {kind: result["notes"] for kind, result in identification.items()},
    }


def missing_parts(run, ground, source, identification, clearance):
    """Lines naming what the run lacks and what the report therefore leaves out."""
    missing = []
    if run.fluid is None:
        missing.append("no fluid folder: no wave heights, wall pressures, sloshing period or section snapshot")
    if run.structure is None:
        missing.append("no structure folder (a fluid-only run): no base shear, overturning moment, von Mises "
                       "stress, wall displacement or bulging period from the wall; rigid walls")
    for side, summary in (("fluid", run.fluid_summary), ("structure", run.structure_summary)):
        folder = run.fluid if side == "fluid" else run.structure
        if folder is not None and summary is None:
            missing.append(f"no {side} summary.json (the program did not finish?): "
                           "its settings and run time are left out")
    if ground is None:
        missing.append(f"no ground acceleration: {source}; no period could be identified")
    for kind, result in identification.items():
        if result["best"] is None:
            reasons = result["notes"] or sorted({r.get("reason", "") for r in result["records"].values()})
            missing.append(f"no {kind} period identified: " + ("; ".join(reasons) if reasons else "no record for it")
                           + " (each record's reason under Natural periods)")
    if clearance.get("min_roof_clearance_m") is None:
        missing.append(f"no roof clearance: {clearance['source']}")
    return missing


def build_report(folder, snapshot="severe", bands=None, tankfsi_case=None):
    """Writes the plots, report.md and the combined summary; returns the summary and its path."""
    run = TankRun(folder)
    ground, source = run.ground_acceleration(tankfsi_case)
    motion = tank_figures.input_motion(run, ground, source)
    theory = tank_figures.theory_periods(run)
    identification = tank_figures.identify_periods(run, ground, theory, bands)
    wave = tank_figures.wave_heights(run)
    pressure = tank_figures.wall_pressures(run)
    clearance = tank_figures.roof_clearance(run)
    reactions = tank_figures.base_reactions(run)
    stress = tank_figures.largest_von_mises(run)
    timing = tank_figures.run_time(run)
    direction = motion.get("main_direction_deg")
    plots, section = make_plots(run, ground, source, theory, identification, wave, direction, snapshot)
    summary = combined_summary(run, motion, theory, identification, wave, pressure, clearance, reactions, stress,
                               timing, section)
    summary["plots"] = [f"plots/{name}" for name, _ in plots if name]
    missing = missing_parts(run, ground, source, identification, clearance)
    summary["missing"] = missing
    summary_name = "tank_summary.json" if run.own_summary_here else "summary.json"
    path = run.folder / summary_name
    path.write_text(json.dumps(summary, indent=2, default=_json_default) + "\n")
    tank_report_markdown.write_report(run, summary, tank_figures.settings(run), plots, missing, summary_name)
    return summary, path


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, np.ndarray):
        return value.tolist()
    raise TypeError(f"{type(value)} is not JSON")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("run", help="run folder")
    parser.add_argument("--snapshot", default="severe", help="severe (nearest the largest wave), last, or a time (s)")
    parser.add_argument("--sloshing-band", nargs=2, type=float, metavar=("SHORTEST_S", "LONGEST_S"))
    parser.add_argument("--bulging-band", nargs=2, type=float, metavar=("SHORTEST_S", "LONGEST_S"))
    parser.add_argument("--tankfsi-case", help="tankfsi_case program (default build/bin/tankfsi_case)")
    args = parser.parse_args()
    if args.snapshot not in ("severe", "last"):
        try:
            float(args.snapshot)
        except ValueError:
            parser.error(f"--snapshot: severe, last or a time, got {args.snapshot!r}")
    bands = {k: tuple(v) for k, v in (("sloshing", args.sloshing_band), ("bulging", args.bulging_band)) if v}
    try:
        summary, path = build_report(args.run, args.snapshot, bands, args.tankfsi_case)
    except FileNotFoundError as error:
        print(f"tank_report: {error}", file=sys.stderr)
        return 2
    run = pathlib.Path(args.run)
    print(f"tank_report: {run / 'report.md'}, {path}, {len(summary['plots'])} plots in {run / 'plots'}")
    for line in summary["missing"]:
        print(f"tank_report: missing: {line}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
