"""RUN/report.md of a tank run from the combined summary (tank_report.py):
title and case, input motion, the key figures with units, the natural
periods identified against theory (where they differ, the case README's
"Periods against theory" section, or a marked place for it: this report
does not explain differences itself), roof clearance, settings,
run time, plots and what the run lacks. One function per section.
"""
import math
import pathlib

PLACEHOLDER = ("**[To be filled from the case README: where the differences between the identified and the "
               "theory periods come from.]** This report cannot tell it from the run's output and does not guess.")


def _number(value, digits=4, scale=1.0):
    """value / scale to `digits` significant digits, or a dash when unknown."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    return f"{value / scale:.{digits}g}"


def _header(run, summary, summary_name):
    case_files = sorted({p.get("case_file") for p in run.provenance.values() if p.get("case_file")})
    sides = [side for side in dict.fromkeys((run.fluid, run.structure)) if side]
    own = ", ".join(f"`{run.relative(side / 'summary.json')}`" for side in sides if (side / "summary.json").is_file())
    resolved = next((run.relative(side / "case.resolved.yaml") for side in sides
                     if (side / "case.resolved.yaml").is_file()), None)
    timing = summary["run_time"]
    programs = ", ".join(f"{name} ({status})" for name, status in timing["status"].items())
    lines = [f"# Tank run report: {summary['title'] or run.folder.name}", "",
             f"- Run folder: `{run.folder}`",
             f"- Case: {', '.join(f'`{c}`' for c in case_files) or '(no provenance.json)'}; "
             f"resolved case: {f'`{resolved}`' if resolved else 'none'}",
             f"- Simulated: {_number(timing['simulated_s'])} s of the case's {summary['end_time_s']} s; "
             f"programs: {programs or 'no summary (stopped before the end?)'}",
             f"- Combined summary: [`{summary_name}`]({summary_name}); the programs' own: {own or 'none'}", ""]
    if timing["errors"]:
        lines += ["**The run failed.** From its logs:", ""] + [f"    {e}" for e in timing["errors"]] + [""]
    return lines


def _input_motion(motion):
    settings = ", ".join(f"{k} {v}" for k, v in (motion.get("settings") or {}).items())
    lines = ["## Input motion", "", f"- Type: `{motion['type']}`" + (f", settings: {settings}" if settings else "")]
    for key in ("time_scale", "amplitude_scale", "start_time", "window", "direction", "amplitude", "frequency"):
        if key in motion:
            lines.append(f"- {key.replace('_', ' ')}: {motion[key]}")
    if "peak_acceleration_m_s2" in motion:
        x, y, z = motion["peak_acceleration_m_s2"]
        lines += [f"- Record: {motion['source']}",
                  f"- Peak |a| over the {motion['duration_s']:.3g} s simulated: x {x:.3g}, y {y:.3g}, z {z:.3g} m/s²; "
                  f"main horizontal direction {motion['main_direction_deg']:.0f}° from x "
                  "(principal axis of the horizontal acceleration)"]
    else:
        lines.append(f"- No ground acceleration record: {motion['source']}")
    return lines + [""]


def _with_std(summary, kind):
    """An identified period with its standard deviation, for the key figures."""
    value = summary[f"{kind}_period_s"]
    if not value:
        return "not identified"
    span = summary.get(f"{kind}_period_records_range_s")
    spread = f" (records {span[0]:.4g}–{span[1]:.4g})" if span else ""
    return f"{value:.4g} ± {summary[f'{kind}_period_std_s']:.2g}{spread}"


def _key_figures(summary):
    rows = []
    for kind, theory, label in (("sloshing", "convective_period_theory_s", "sloshing (convective)"),
                                ("bulging", "impulsive_period_theory_s", "bulging (impulsive)")):
        rows.append((f"{label} period, identified", _with_std(summary, kind), "s",
                     summary[f"{kind}_period_record"] or "see Natural periods"))
        rows.append((f"{label} period, theory (EN 1998-4 Annex A)", _number(summary[theory]), "s", ""))
    for name, f in summary["wave_heights"].items():
        rows.append((f"peak wave height {name} (largest abs eta; crest {f['crest_m']:+.3f}, "
                     f"trough {f['trough_m']:+.3f})", _number(f["peak_m"], 3), "m", f"t = {f['peak_time_s']:.2f} s"))
    for name, f in summary["wall_pressures"].items():
        rows.append((f"peak pressure {name}", _number(f["peak_pressure_Pa"], 4, 1e3), "kPa",
                     f"t = {f['peak_pressure_time_s']:.2f} s"))
        rows.append((f"largest change of pressure {name} from t = 0 ({f['initial_pressure_Pa'] / 1e3:.4g} kPa)",
                     _number(f["peak_change_Pa"], 4, 1e3), "kPa", f"t = {f['peak_change_time_s']:.2f} s"))
    clearance = summary["roof_clearance"]
    estimate = " (estimate at the probes)" if "estimate" in clearance["source"] else ""
    when = f"{clearance['probe']}, t = {clearance['time_s']:.2f} s" if "time_s" in clearance else ""
    rows.append((f"minimum roof clearance{estimate}", _number(clearance.get("min_roof_clearance_m"), 3), "m", when))
    reactions = summary["base_reactions"]
    if reactions:
        rows.append(("peak base shear (resultant)", _number(reactions["peak_base_shear_N"], 4, 1e6), "MN",
                     f"t = {reactions['peak_base_shear_time_s']:.2f} s"))
        rows.append(("peak overturning moment (resultant)", _number(reactions["peak_overturning_moment_Nm"], 4, 1e6),
                     "MN m", f"t = {reactions['peak_overturning_moment_time_s']:.2f} s"))
    stress = summary["max_von_mises_location"]
    if stress and stress["max_von_mises_Pa"] == 0:
        rows.append(("largest von Mises stress", "0", "MPa", f"zero in all {stress['snapshots_seen']} field snapshots"))
    elif stress:
        centroid = ", ".join(f"{c:.2f}" for c in stress["centroid_m"])
        where = (f"{stress['region'] or 'element'} element {stress['element']} ({stress['surface']} surface), "
                 f"centroid ({centroid}) m, azimuth {stress['azimuth_deg']:.0f}°, t = {stress['time_s']:.2f} s; "
                 f"over the {stress['snapshots_seen']} field snapshots only")
        rows.append(("largest von Mises stress", _number(stress["max_von_mises_Pa"], 4, 1e6), "MPa", where))
    if summary["peak_displacement_m"] is not None:
        rows.append(("largest shell displacement (structure summary)", _number(summary["peak_displacement_m"], 3),
                     "m", ""))
    rows.append(("wall time of the job", _number(summary["wall_time_s"]), "s", "the longer program's"))
    return (["## Key figures", "", "| quantity | value | unit | where / when |", "|---|---|---|---|"]
            + [f"| {q} | {v} | {u} | {w} |" for q, v, u, w in rows] + [""])


# The case README's section that says where its periods differ from theory.
EXPLANATION_HEADING = "## Periods against theory"


def case_explanation(case_files):
    """The text of the case README's EXPLANATION_HEADING section (README.md beside
    the one case file), and that README's path; (None, None) without one."""
    if len(case_files) != 1:
        return None, None
    readme = pathlib.Path(case_files[0]).parent / "README.md"
    if not readme.is_file():
        return None, None
    lines = readme.read_text().splitlines()
    if EXPLANATION_HEADING not in lines:
        return None, None
    body = []
    for line in lines[lines.index(EXPLANATION_HEADING) + 1:]:
        if line.startswith("## "):
            break
        body.append(line)
    text = "\n".join(body).strip()
    return (text, readme) if text else (None, None)


def _periods(summary, case_files):
    """Identified against theory, every record's outcome, the notes and where the
    differences come from: the case README's word, or the marked place for it."""
    model = summary.get("theory_at_model_depth")
    header = "| period | identified | ± 1σ | theory (EN 1998-4 Annex A) | difference |"
    rule = "|---|---|---|---|---|"
    if model:
        header += f" theory for the model's {model['liquid_depth_m']:.2f} m of liquid | difference |"
        rule += "---|---|"
    lines = ["## Natural periods", "", header, rule]
    for kind, theory_key, model_key, label in (
            ("sloshing", "convective_period_theory_s", "convective_period_s", "sloshing (convective)"),
            ("bulging", "impulsive_period_theory_s", "impulsive_period_s", "bulging (impulsive)")):
        difference = summary[f"{kind}_period_difference_percent"]
        identified, std, theory = summary[f"{kind}_period_s"], summary[f"{kind}_period_std_s"], summary[theory_key]
        row = (f"| {label} | {f'{identified:.4g} s' if identified else 'not identified'} | "
               f"{f'{std:.2g} s' if identified else '—'} | {f'{theory:.4g} s' if theory else '—'} | "
               f"{'%+.1f %%' % difference if difference is not None else '—'} |")
        if model:
            at_depth, off = model[model_key], model[f"{kind}_difference_percent"]
            row += (f" {f'{at_depth:.4g} s' if at_depth else '—'} | "
                    f"{'%+.1f %%' % off if off is not None else '—'} |")
        lines.append(row)
    if model:
        lines += ["", f"The case fills to {model['fill_level_m']:.2f} m; the model's particle layers of "
                  f"{model['spacing_m']:.4g} m hold {model['liquid_depth_m']:.2f} m of liquid (the top of "
                  "the highest layer: sph_solver/particles/filling.hpp), the depth its periods belong to."]
    lines += ["", "Identified by fitting a single-degree-of-freedom oscillator driven by the recorded ground "
              "acceleration to each record (scripts/post/tank_periods.py); the record with the smallest relative "
              "uncertainty gives the figure. Every record:", "",
              "| record | kind | period (s) | ± 1σ (s) | damping | cycles | variance explained | or why none |",
              "|---|---|---|---|---|---|---|---|"]
    for kind, records in summary["period_identification"].items():
        for name, r in records.items():
            if "period_s" in r:
                lines.append(f"| {name} | {kind} | {r['period_s']:.4g} | {r['period_std_s']:.2g} | "
                             f"{100 * r['damping_ratio']:.2f} % | {r['cycles']:.1f} | "
                             f"{100 * r['explained_fraction']:.0f} % | |")
            else:
                lines.append(f"| {name} | {kind} | — | — | — | — | — | {r['reason']} |")
    if not any(summary["period_identification"].values()):
        lines.append("| — | — | — | — | — | — | — | no wave-height, pressure or displacement records |")
    notes = summary["theory_notes"] + [f"{kind}: {note}" for kind, kind_notes in summary["period_notes"].items()
                                       for note in kind_notes]
    lines += [""] + [f"- {note}" for note in notes]
    explanation, readme = case_explanation(case_files)
    if explanation is None:
        return lines + ["", f"Where the differences come from: {PLACEHOLDER}", ""]
    return lines + ["", f"Where the differences come from (the case README, `{readme}`, as measured there; "
                    "this run's figures are the ones above):", "", explanation, ""]


def _roof_clearance(clearance):
    lines = ["## Roof clearance", "", f"- Source: {clearance['source']}."]
    if "roof_height_at_probe_m" in clearance:
        lines.append(f"- Roof underside above the probe of the minimum: {clearance['roof_height_at_probe_m']:.3f} m; "
                     f"clearance there at rest (t = 0): {clearance['still_clearance_m']:.3f} m.")
    return lines + [""]


def _settings(rows):
    return (["## Settings", "", "| setting | value | unit |", "|---|---|---|"]
            + [f"| {name} | {value} | {unit} |" for name, (value, unit) in rows.items() if value not in (None, "")]
            + [""])


def _run_time(timing):
    lines = ["## Run time", ""] + [f"- {name}: {_number(seconds)} s wall"
                                   for name, seconds in timing["program_wall_time_s"].items()]
    structure = (f"; structure: {_number(timing['structure_seconds_per_step'], 3)} s per step"
                 if timing["structure_seconds_per_step"] else "")
    lines += [f"- Job: {_number(timing['wall_time_s'])} s wall for {_number(timing['simulated_s'])} s simulated: "
              f"{_number(timing['wall_seconds_per_simulated_second'])} wall s per simulated s",
              f"- Fluid: {_number(timing['particle_steps_per_second'])} particle-steps/s{structure}"]
    return lines + [""]


def write_report(run, summary, settings_rows, plots, missing, summary_name):
    """Writes RUN/report.md."""
    lines = _header(run, summary, summary_name)
    lines += _input_motion(summary["input_motion"])
    lines += _key_figures(summary)
    lines += _periods(summary, sorted({p.get("case_file") for p in run.provenance.values() if p.get("case_file")}))
    lines += _roof_clearance(summary["roof_clearance"])
    lines += _settings(settings_rows)
    lines += _run_time(summary["run_time"])
    lines += ["## Plots", ""] + [f"- [{caption}](plots/{name})" if name else f"- {caption}" for name, caption in plots]
    lines += ["", "## Missing from this run", ""] + ([f"- {m}" for m in missing] or ["- nothing"]) + [""]
    (run.folder / "report.md").write_text("\n".join(lines))
