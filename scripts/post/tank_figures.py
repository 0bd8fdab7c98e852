"""The figures a tank engineer reads off a run (TankRun): natural periods
identified and from theory, wave heights, wall pressures, roof clearance,
base shear and overturning moment, the largest von Mises stress, run time.
Each function returns plain numbers and dicts (JSON-ready) and says in a
`missing` text what it could not find, rather than failing.
"""
import math

import numpy as np

import tank_periods
import tank_theory

MIN_CYCLES = 2.0  # periods a record must hold for its period to be identified
SLOSHING_BAND_FACTOR = 3.0  # search T_c / 3 .. 3 T_c
# The wave at the wall holds the second sloshing mode too (0.57 T_c); fitted
# with the first, it no longer biases the first's period (tank_periods.py).
HIGHER_MODES = {"sloshing": 1, "bulging": 0}
BULGING_BAND_FACTOR = 4.0  # search T_i / 4 .. 4 T_i (the paper's coupled tank: 0.7 s against 0.19 s)


def ground_components(ground, time_s):
    """ax, ay, az (m/s^2) of the ground record at `time_s` (zero where a column is missing)."""
    return [np.interp(time_s, ground["time_s"], ground[c]) if c in ground else np.zeros(len(time_s))
            for c in ("ax_m_s2", "ay_m_s2", "az_m_s2")]


def main_direction_deg(ground):
    """Azimuth (degrees from x, -90 to 90: an axis has no sign) of the principal
    axis of the horizontal ground acceleration: the direction it shakes most
    (largest variance)."""
    ax, ay, _ = ground_components(ground, ground["time_s"])
    covariance = np.cov(np.vstack([ax, ay]))
    if not np.all(np.isfinite(covariance)) or np.allclose(covariance, 0):
        return 0.0
    values, vectors = np.linalg.eigh(covariance)
    x, y = vectors[:, np.argmax(values)]
    return (math.degrees(math.atan2(y, x)) + 90.0) % 180.0 - 90.0


def input_motion(run, ground, source):
    """The excitation's settings and the record's peaks."""
    motion = {"type": run.case_value("excitation.type", "unknown"), "source": source}
    settings = run.case_value(f"excitation.{motion['type']}")
    if isinstance(settings, dict):
        motion["settings"] = settings
    for key in ("time_scale", "amplitude_scale", "start_time", "window", "direction", "amplitude", "frequency"):
        value = run.case_value(f"excitation.{key}")
        if value is not None:
            motion[key] = value
    if ground is not None:
        peaks = [float(np.max(np.abs(c))) for c in ground_components(ground, ground["time_s"])]
        motion.update(peak_acceleration_m_s2=peaks, duration_s=float(ground["time_s"][-1] - ground["time_s"][0]),
                      main_direction_deg=main_direction_deg(ground))
    return motion


def model_liquid_depth(level, spacing):
    """The depth of the liquid the fluid model holds: the top of its highest
    particle layer. The filling (sph_solver/particles/filling.hpp) lays layers
    at (k + 1/2) L0 above the floor while they stay below the level, so the
    level rounds to whole layers (14.8 m at L0 = 1 m: 15.0 m)."""
    return math.ceil(level / spacing - 0.5 - 1e-9) * spacing


def theory_periods(run):
    """Convective and impulsive periods of EN 1998-4 Annex A (tank_theory.py)
    for the case's tank, with a note where one cannot be had; and the same for
    the liquid depth the model holds (`model_depth`), when the case's spacing
    is known."""
    theory = {"convective_period_theory_s": None, "impulsive_period_theory_s": None, "notes": [],
              "model_depth": None}
    radius = run.case_value("fluid.geometry.radius")
    level = run.case_value("fluid.fill.level")
    if run.case_value("fluid.geometry.type") != "cylindrical_tank" or not radius or not level:
        theory["notes"].append("no theory periods: the fluid's tank is not a cylindrical_tank with a fill level")
        return theory
    spacing = run.case_value("fluid.spacing")
    depths = {"case": level}
    if spacing:
        depths["model"] = model_liquid_depth(level, spacing)
        theory["model_depth"] = {"liquid_depth_m": depths["model"], "fill_level_m": level, "spacing_m": spacing,
                                 "convective_period_s": None, "impulsive_period_s": None}
    theory["convective_period_theory_s"] = tank_theory.convective_period(radius, level)
    if "model" in depths:
        theory["model_depth"]["convective_period_s"] = tank_theory.convective_period(radius, depths["model"])
    walls = [r for r in run.case_value("structure.regions", []) or [] if r.get("name") == "wall"]
    young = run.case_value("structure.material.young_modulus")
    if not walls or not young:
        theory["notes"].append("no impulsive theory period: the case has no structure wall (rigid walls do not bulge)")
        return theory
    try:
        for which, depth in depths.items():
            period = tank_theory.impulsive_period(radius, depth, run.case_value("fluid.density"),
                                                  walls[0]["thickness"], young)
            if which == "case":
                theory["impulsive_period_theory_s"] = period
            else:
                theory["model_depth"]["impulsive_period_s"] = period
        theory["wall_thickness_m"] = walls[0]["thickness"]
    except ValueError as reason:
        theory["notes"].append(f"no impulsive theory period: {reason}")
    return theory


def radial_displacement(position, record, direction):
    """A displacement probe's record along the wall's outward normal (or along
    its own direction when the case gave one: one column)."""
    if direction is not None or "displacement_m" in record:
        return record["displacement_m"]
    normal = np.array([position[0], position[1]])
    normal = normal / (np.linalg.norm(normal) or 1.0)
    return normal[0] * record["displacement_x_m"] + normal[1] * record["displacement_y_m"]


def period_records(run):
    """The records each period is identified from: (kind, name, time, values, feedthrough, quantity)."""
    records = []
    for name, _, record, _ in run.probes("fluid", "wave_height"):
        records.append(("sloshing", name, record["time_s"], record["wave_height_m"], False, "wave height reading (m)"))
    for name, _, record, _ in run.probes("fluid", "pressure"):
        records.append(("bulging", name, record["time_s"], record["pressure_Pa"], True, "pressure (Pa)"))
    for name, position, record, direction in run.probes("structure", "displacement"):
        radial = radial_displacement(position, record, direction)
        records.append(("bulging", f"{name} (radial)", record["time_s"], radial, True, "radial displacement (m)"))
    return records


def identify_periods(run, ground, theory, bands=None):
    """Sloshing and bulging periods from every record that may show them; the
    best of each (smallest relative uncertainty) is the run's figure. `bands`
    overrides the search bands {kind: (shortest_s, longest_s)}."""
    reference = {"sloshing": (theory["convective_period_theory_s"], SLOSHING_BAND_FACTOR),
                 "bulging": (theory["impulsive_period_theory_s"], BULGING_BAND_FACTOR)}
    result = {kind: {"records": {}, "best": None, "fits": {}, "notes": []} for kind in reference}
    ends = {}  # the latest time of each kind's records
    for kind, name, time_s, values, feedthrough, quantity in period_records(run):
        if len(time_s):
            ends[kind] = max(ends.get(kind, 0.0), float(time_s[-1]))
        entry = result[kind]["records"]
        period, factor = reference[kind]
        note = _resolution_note(time_s, period)
        if note and note not in result[kind]["notes"]:
            result[kind]["notes"].append(note)
        band = (bands or {}).get(kind) or ((period / factor, period * factor) if period else None)
        if band is None and kind == "bulging" and run.structure is None:
            entry[name] = {"reason": "rigid walls (no structure): nothing bulges"}
            continue
        if band is None:
            entry[name] = {"reason": f"no theory period to centre the search band on (give a --{kind}-band)"}
            continue
        if ground is None:
            entry[name] = {"reason": "no ground acceleration record to drive the oscillator"}
            continue
        time_s, values = tank_periods.uniform_record(time_s, values)
        ax, ay, az = ground_components(ground, time_s)
        try:
            estimate = tank_periods.identify_period(
                time_s, values, [ax, ay], band, feedthrough_inputs=[ax, ay, az] if feedthrough else [],
                drift_period_s=2 * band[1], min_cycles=MIN_CYCLES, higher_modes=HIGHER_MODES[kind])
        except tank_periods.PeriodNotIdentified as reason:
            entry[name] = {"reason": str(reason), "band_s": list(band)}
            continue
        entry[name] = {"period_s": estimate.period_s, "period_std_s": estimate.period_std_s,
                       "damping_ratio": estimate.damping_ratio, "damping_std": estimate.damping_std,
                       "explained_fraction": estimate.explained_fraction, "cycles": estimate.cycles,
                       "band_s": list(estimate.band_s)}
        result[kind]["fits"][name] = (time_s, values, estimate.fitted, quantity)
        best = result[kind]["best"]
        if best is None or estimate.period_std_s / estimate.period_s < best[1]["period_std_s"] / best[1]["period_s"]:
            result[kind]["best"] = (name, entry[name])
    for kind, entry in result.items():
        entry["range"], disagreement = records_agreement(kind, entry["records"])
        forced = forced_record_note(kind, ground, ends.get(kind), reference[kind][0])
        entry["notes"] += [note for note in (disagreement, forced) if note]
    return result


# A record of fewer cycles than this rests on its free swing for the period;
# over more, the transients of a broadband motion determine it too.
FEW_CYCLES = 10
# The ground still shakes when its horizontal acceleration over the record's
# last two periods reaches this share of the record's peak.
STILL_SHARE = 0.05


def forced_record_note(kind, ground, end_s, period_s):
    """A note when a record of few cycles of the theory period ends while the
    ground still shakes: its period then rests on forced response alone, which
    fixes it less well than a free swing (the fit cannot tell the tank's own
    period from the motion's dominant one as surely). None otherwise."""
    if ground is None or end_s is None or not period_s or end_s / period_s >= FEW_CYCLES:
        return None
    time_s = np.asarray(ground["time_s"])
    ax, ay, _ = ground_components(ground, time_s)
    horizontal = np.hypot(ax, ay)
    shaking = time_s <= end_s
    last = shaking & (time_s >= end_s - 2 * period_s)
    peak = float(np.max(horizontal[shaking])) if np.any(shaking) else 0.0
    if peak == 0.0 or not np.any(last):
        return None
    share = float(np.max(horizontal[last])) / peak
    if share < STILL_SHARE:
        return None
    return (f"the records end while the ground still shakes (over their last two theory periods up to "
            f"{100 * share:.0f} % of the peak horizontal acceleration) and hold {end_s / period_s:.1f} of them: the "
            f"{kind} period rests on forced response alone, which fixes it less well than a free swing; a run that "
            "goes on past the motion's end (or the motion cut short) shows the free swing")


# Two records' periods disagree when they differ by more than this many
# standard deviations of their difference (two: a 5 % chance for one pair of
# records whose deviations are right).
DISAGREEMENT_SIGMAS = 2.0


def records_agreement(kind, records):
    """The range of the periods the records identified ([shortest, longest] s,
    None for fewer than two) and, when two of them differ by more than their
    standard deviations allow, a note that says so: each fit's deviation counts
    the misfit as noise, so it understates the uncertainty when the response is
    not the oscillator's (a forced record of few cycles, a non-linear wave), and
    a record may have found another mode."""
    periods = [(name, r["period_s"], r["period_std_s"]) for name, r in records.items() if "period_s" in r]
    if len(periods) < 2:
        return None, None
    span = [min(p for _, p, _ in periods), max(p for _, p, _ in periods)]
    worst = max(((abs(a[1] - b[1]) / math.hypot(a[2], b[2]), a, b) for i, a in enumerate(periods)
                 for b in periods[i + 1:]), key=lambda item: item[0])
    if worst[0] <= DISAGREEMENT_SIGMAS:
        return span, None
    sigmas, a, b = worst
    return span, (f"the records disagree: {a[0]} {a[1]:.4g} s and {b[0]} {b[1]:.4g} s differ by {sigmas:.1f} "
                  f"standard deviations of their difference (all records: {span[0]:.4g}-{span[1]:.4g} s). A fit's "
                  f"deviation takes its misfit for noise: the {kind} period is less certain than the deviations "
                  "say, or a record shows another mode")


def _resolution_note(time_s, period_s):
    """Why a record cannot show the theory period at all, or None."""
    if not period_s or len(time_s) < 2:
        return None
    duration = time_s[-1] - time_s[0]
    interval = duration / (len(time_s) - 1)
    if period_s < 4 * interval:
        return (f"the theory period {period_s:.4g} s is shorter than records sampled every {interval:.3g} s "
                f"resolve (four samples per period: {4 * interval:.3g} s)")
    if period_s > duration / MIN_CYCLES:
        return (f"a {duration:.3g} s record holds {duration / period_s:.2f} cycles of the theory period "
                f"{period_s:.4g} s; at least {MIN_CYCLES:g} are needed")
    return None


def wave_heights(run):
    """Per wave probe: the surface at rest (first sample, m above the floor),
    and the crest, trough and largest |eta| of eta = surface - surface at rest."""
    figures = {}
    for name, position, record, _ in run.probes("fluid", "wave_height"):
        surface = position[2] + record["wave_height_m"]
        eta = surface - surface[0]
        peak = int(np.argmax(np.abs(eta)))
        figures[name] = {"still_surface_m": float(surface[0]), "crest_m": float(eta.max()),
                         "trough_m": float(eta.min()), "peak_m": float(abs(eta[peak])),
                         "peak_time_s": float(record["time_s"][peak])}
    return figures


def wall_pressures(run):
    """Per pressure probe: the largest pressure and the largest change from the first sample."""
    figures = {}
    for name, _, record, _ in run.probes("fluid", "pressure"):
        pressure = record["pressure_Pa"]
        change = pressure - pressure[0]
        peak = int(np.argmax(np.abs(change)))
        figures[name] = {"peak_pressure_Pa": float(pressure.max()), "initial_pressure_Pa": float(pressure[0]),
                         "peak_pressure_time_s": float(record["time_s"][int(np.argmax(pressure))]),
                         "peak_change_Pa": float(abs(change[peak])),
                         "peak_change_time_s": float(record["time_s"][peak])}
    return figures


def roof_height(run, radial_distance):
    """Height (m) of the roof's underside at a distance from the axis, or of
    the wall top for an open tank; None when the geometry is not a cylindrical tank."""
    if run.case_value("fluid.geometry.type") != "cylindrical_tank":
        return None
    radius = run.case_value("fluid.geometry.radius")
    wall = run.case_value("fluid.geometry.wall_height")
    dome = run.case_value("fluid.geometry.dome_radius", 0) or 0
    if dome <= 0:
        return wall
    return wall + math.sqrt(dome ** 2 - min(radial_distance, radius) ** 2) - math.sqrt(dome ** 2 - radius ** 2)


def roof_clearance(run):
    """Smallest distance between the liquid surface and the roof: the fluid
    program's own `roof_clearance_m` when it writes one, else an estimate at
    the wave probes (surface there against the roof above them)."""
    own = (run.fluid_summary or {}).get("roof_clearance_m")
    if own is not None:
        value = own if isinstance(own, (int, float)) else next(
            (v for k, v in own.items() if k.startswith("min") and isinstance(v, (int, float))), None)
        return {"min_roof_clearance_m": value, "source": "fluid summary (roof_clearance_m)", "raw": own}
    probes = run.probes("fluid", "wave_height")
    if not probes:
        return {"min_roof_clearance_m": None, "source": "none: no wave-height probes and no roof_clearance_m"}
    open_top = (run.case_value("fluid.geometry.dome_radius", 0) or 0) <= 0
    best = None
    for name, position, record, _ in probes:
        roof = roof_height(run, math.hypot(position[0], position[1]))
        if roof is None:
            return {"min_roof_clearance_m": None, "source": "none: the tank is not a cylindrical_tank"}
        clearance = roof - (position[2] + record["wave_height_m"])
        k = int(np.argmin(clearance))
        if best is None or clearance[k] < best["min_roof_clearance_m"]:
            best = {"min_roof_clearance_m": float(clearance[k]), "probe": name, "time_s": float(record["time_s"][k]),
                    "still_clearance_m": float(clearance[0]), "roof_height_at_probe_m": roof}
    best["source"] = ("estimate at the wave probes: " + ("wall top (open tank)" if open_top else "dome roof") +
                      " above each probe minus the surface there; the surface between and beyond the probes"
                      " is not seen")
    return best


def base_reactions(run):
    """Peak base shear and overturning moment (resultants of the x and y
    components in probes/structure.csv) and when, or None."""
    history = run.history("structure", "structure")
    if history is None or "base_shear_x_N" not in history:
        return None
    shear = np.hypot(history["base_shear_x_N"], history["base_shear_y_N"])
    moment = np.hypot(history["overturning_moment_x_Nm"], history["overturning_moment_y_Nm"])
    k, m = int(np.argmax(shear)), int(np.argmax(moment))
    return {"peak_base_shear_N": float(shear[k]), "peak_base_shear_time_s": float(history["time_s"][k]),
            "peak_base_shear_components_N": [float(np.max(np.abs(history[c])))
                                             for c in ("base_shear_x_N", "base_shear_y_N")],
            "peak_overturning_moment_Nm": float(moment[m]),
            "peak_overturning_moment_time_s": float(history["time_s"][m])}


def _region(run, centroid):
    """wall, roof or bottom of the generated tank mesh, from where the element lies."""
    if run.case_value("structure.mesh.type") != "tank":
        return None
    height = run.case_value("structure.mesh.wall_height")
    size = run.case_value("structure.mesh.element_size", 0.0)
    if centroid[2] < 0.01 * size:
        return "bottom"
    return "roof" if centroid[2] > height else "wall"


def largest_von_mises(run):
    """The largest von Mises stress over the structure's field snapshots (top
    and bottom surfaces) and where: element, centroid, region, azimuth; None
    without snapshots. Only the snapshots are seen, not every step."""
    best = None
    series = run.structure_snapshots()
    for snapshot in series:
        top, bottom = snapshot.read("cell_fields/von_mises_top", "cell_fields/von_mises_bottom")
        for surface, values in (("top", top), ("bottom", bottom)):
            if values is None or len(values) == 0:
                continue
            k = int(np.argmax(values))
            if best is None or values[k] > best[0]:
                best = (float(values[k]), surface, k, snapshot)
    if best is None:
        return None
    value, surface, element, snapshot = best
    position, = snapshot.read("position")
    cells = snapshot.cells()
    centroid = position[cells[element]].mean(axis=0) if element < len(cells) else np.full(3, np.nan)
    return {"max_von_mises_Pa": value, "surface": surface, "element": element, "time_s": snapshot.time_s,
            "centroid_m": [float(c) for c in centroid], "region": _region(run, centroid),
            "azimuth_deg": float(math.degrees(math.atan2(centroid[1], centroid[0])) % 360),
            "snapshots_seen": len(series)}


def run_time(run):
    """Wall seconds of each program and of the job, per simulated second, and
    the fluid's particle-steps per second."""
    fluid = run.fluid_summary or {}
    structure = run.structure_summary or {}
    times = {name: program.get("wall_time_s") for name, program in run.programs.items()}
    end = fluid.get("end_time_s") or structure.get("end_time_s") or run.last_time_s()
    known = [t for t in times.values() if t is not None]
    wall = max(known) if known else None
    return {"program_wall_time_s": times, "wall_time_s": wall, "simulated_s": end,
            "case_end_time_s": run.case_value("end_time"), "errors": run.log_errors(),
            "status": {name: program.get("status") for name, program in run.programs.items()},
            "wall_seconds_per_simulated_second": (wall / end) if wall and end else None,
            "particle_steps_per_second": fluid.get("particle_steps_per_second"),
            "structure_seconds_per_step": structure.get("seconds_per_step")}


def settings(run):
    """The run's resolution and solver settings, as name -> (value, unit)."""
    fluid = run.fluid_summary or {}
    structure = run.structure_summary or {}
    fluid_coupling = fluid.get("coupling") or {}
    structure_coupling = run.structure_coupling or {}
    steps = fluid.get("time_step_s") or {}
    limits = ", ".join(f"{k} {v}" for k, v in (fluid.get("time_step_limited_by") or {}).items())
    ppe = fluid.get("ppe_iterations")
    rows = {
        "end time": (run.case_value("end_time"), "s"),
        "particle spacing L0": (run.case_value("fluid.spacing"), "m"),
        "kernel": (run.case_value("fluid.kernel"), ""),
        "particles": (fluid.get("particles"), ""),
        "fluid time steps": (fluid.get("steps"), ""),
        "fluid time step min / mean / max": (
            " / ".join(f"{steps[k]:.4g}" for k in ("min", "mean", "max")) if steps else None, "s"),
        "fluid time step limited by": (limits or None, "steps"),
        "PPE iterations mean / max": (f"{ppe['mean']:.1f} / {ppe['max']}" if ppe else None, ""),
        # Particles that ended a step just behind a wall, put back in front of it (wall_crossings.hpp).
        "particles put back at walls": (fluid.get("wall_returned_particles"), "particle-steps"),
        "shell element size": (run.case_value("structure.mesh.element_size"), "m"),
        "shell nodes / quadrilaterals / triangles": (
            f"{structure['nodes']} / {structure.get('quadrilaterals', 0)} / {structure.get('triangles', 0)}"
            if structure.get("nodes") else None, ""),
        "shell equations": (structure.get("equations"), ""),
        "structure time step": (structure.get("time_step_s", run.case_value("structure.time_step")), "s"),
        "structure time steps": (structure.get("steps"), ""),
        "coupling scheme": (run.case_value("coupling.scheme"), ""),
        "coupling window": (run.case_value("coupling.time_window"), "s"),
        "structure load": (run.case_value("coupling.structure_load"), ""),
        "coupling windows": (structure_coupling.get("windows", fluid_coupling.get("windows")), ""),
        "iterations per window (mean / most)": (
            f"{structure_coupling.get('iterations_per_window', fluid_coupling.get('iterations_per_window'))}"
            f" / {structure_coupling.get('most_iterations', '?')}"
            if structure_coupling or fluid_coupling else None, ""),
        "unconverged windows": (structure_coupling.get("unconverged_windows"), ""),
        "field / probe interval": (
            f"{run.case_value('output.field_interval')} / {run.case_value('output.probe_interval')}", "s"),
        "ranks (fluid / structure)": (" / ".join(str(run.provenance.get(p, {}).get("mpi_ranks", "-"))
                                                  for p in ("sph_solver", "fem_solver")), ""),
    }
    return rows

