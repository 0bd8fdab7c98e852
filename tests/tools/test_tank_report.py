#!/usr/bin/python3
"""scripts/post/tank_report.py on small fake run folders shaped like a real
coupled tank run (RUN/fluid, RUN/structure: the CSV, JSON and YAML files the
programs write, and tiny HDF5 snapshot files in their layout): a 20 s run
whose wave heights, wall pressure and wall displacement are oscillators of
known periods (5.88 s, 0.19 s) driven by the run's ground acceleration. The
combined summary must hold every promised key with the right figures, every
promised plot must exist, the programs' own summaries must stay untouched;
a failed run (no summaries, an error in its log), a fluid-only run in one
folder without a ground record, and a run whose fluid summary gives the roof
clearance must be reported without a crash. Records whose periods disagree
beyond their deviations, and records of few cycles that end while the
ground shakes, must be said to.
Prints '<n> passed, <m> failed' and exits non-zero on a failure."""
import json
import math
import pathlib
import subprocess
import sys
import tempfile

import h5py
import numpy as np
import yaml

POST = pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"
sys.path.insert(0, str(POST))
import tank_figures  # noqa: E402
import tank_report  # noqa: E402
import tank_theory  # noqa: E402
import tank_report_markdown  # noqa: E402
sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from oscillator_records import oscillator_record as newmark  # noqa: E402

SLOSHING_S, BULGING_S = 5.88, 0.19
RADIUS, WALL, DOME, LEVEL = 15.0, 18.0, 30.0, 14.8
WAVE_ANGLES = {"wave_0deg": 0, "wave_90deg": 90, "wave_180deg": 180, "wave_270deg": 270}
PRESSURE_ANGLES = {"pressure_0deg_1m": 0, "pressure_90deg_1m": 90}
PLOTS = ["wave_heights.png", "wall_pressures.png", "spectra.png", "base_shear_overturning.png",
         "ground_acceleration.png", "period_fits.png", "section_snapshot.png"]
checks = []


def check(name, ok, detail=""):
    checks.append(bool(ok))
    print(f"{'ok  ' if ok else 'FAIL'} {name}{': ' + detail if detail else ''}")


def write_csv(path, columns):
    path.parent.mkdir(parents=True, exist_ok=True)
    names = list(columns)
    np.savetxt(path, np.column_stack([columns[n] for n in names]), delimiter=",", header=",".join(names), comments="")


def case(structure=True):
    """A resolved case shaped like case.resolved.yaml of the default tank case."""
    config = {
        "title": "fake tank for the report test", "end_time": 20,
        "fluid": {"dimension": 3, "kernel": "quartic_spline", "spacing": 2.0, "density": 860, "viscosity": 0.0172,
                  "gravity": 9.81, "time_step": {"mode": "adaptive", "cfl": 0.2, "max": 0.01},
                  "geometry": {"type": "cylindrical_tank", "wall_height": WALL, "radius": RADIUS, "dome_radius": DOME,
                               "element_size": 0},
                  "fill": {"level": LEVEL, "hydrostatic": True},
                  "probes": [{"name": n, "quantity": "wave_height",
                              "position": [14 * math.cos(math.radians(a)), 14 * math.sin(math.radians(a)), 0]}
                             for n, a in WAVE_ANGLES.items()] +
                            [{"name": n, "quantity": "pressure",
                              "position": [14 * math.cos(math.radians(a)), 14 * math.sin(math.radians(a)), 1]}
                             for n, a in PRESSURE_ANGLES.items()]},
        "coupling": {"scheme": "parallel_staggered", "time_window": 0.01, "structure_load": "ramp", "ramp_chi": 1},
        "excitation": {"type": "synthetic", "time_scale": 1, "amplitude_scale": 1, "start_time": 0,
                       "synthetic": {"seed": 2003, "peak_acceleration": 0.8, "dominant_period": 6,
                                     "component_ratios": [1, 0.5, 0.3]}},
        "output": {"field_interval": 10, "probe_interval": 0.01, "plots": True},
    }
    if structure:
        config["structure"] = {
            "analysis": "dynamic", "material": {"young_modulus": 2.06e11, "poisson_ratio": 0.3, "density": 7900},
            "regions": [{"name": "wall", "thickness": 0.015}, {"name": "bottom", "thickness": 0.015},
                        {"name": "roof", "thickness": 0.0075}],
            "time_step": 0.001,
            "probes": [{"name": "wall_1m_x", "quantity": "displacement", "position": [15.0, 0.0, 1.0]}],
            "mesh": {"type": "tank", "radius": RADIUS, "wall_height": WALL, "dome_radius": DOME, "element_size": 3.0,
                     "liquid_level": LEVEL}}
    else:
        del config["coupling"]
    return config


def tank_mesh(rings=24, levels=7):
    """Nodes and XDMF mixed connectivity of a tank: quadrilateral wall, triangle fans for bottom and dome."""
    theta = np.linspace(0, 2 * math.pi, rings, endpoint=False)
    heights = np.linspace(0, WALL, levels)
    nodes = [[RADIUS * math.cos(t), RADIUS * math.sin(t), z] for z in heights for t in theta]
    rise = math.sqrt(DOME ** 2) - math.sqrt(DOME ** 2 - RADIUS ** 2)
    nodes += [[0, 0, 0], [0, 0, WALL + rise]]
    bottom_centre, apex = len(nodes) - 2, len(nodes) - 1
    cells = []
    for level in range(levels - 1):
        for k in range(rings):
            a, b = level * rings + k, level * rings + (k + 1) % rings
            cells.append([5, a, b, b + rings, a + rings])
    top = (levels - 1) * rings
    for k in range(rings):
        cells.append([4, bottom_centre, (k + 1) % rings, k])
        cells.append([4, top + k, top + (k + 1) % rings, apex])
    return np.array(nodes, dtype=float), cells


def grid_json(name, time_s, kind):
    return json.dumps({"name": name, "time": time_s, "kind": kind})


def write_particles(path, times):
    """fluid.h5: particles of the tank on a coarse grid, hydrostatic pressure."""
    spacing = 2.0
    axis = np.arange(-RADIUS + 1, RADIUS, spacing)
    x, y, z = np.meshgrid(axis, axis, np.arange(1.0, LEVEL, spacing), indexing="ij")
    inside = np.hypot(x, y) < RADIUS - 0.5
    position = np.column_stack([x[inside], y[inside], z[inside]])
    with h5py.File(path, "w") as f:
        for step, time_s in enumerate(times):
            group = f.create_group(f"step_{step:07d}")
            group.attrs["kind"] = b"particles"
            group.attrs["time"] = time_s
            group.attrs["xdmf_grid"] = grid_json(group.name, time_s, "particles").encode()
            group["position"] = position + [0.1 * step, 0, 0]
            group["ids"] = np.arange(len(position), dtype=np.int64)
            group["fields/velocity"] = np.zeros_like(position)
            group["fields/pressure"] = 860 * 9.81 * (LEVEL - position[:, 2])
            group["fields/mass"] = np.full(len(position), 860 * spacing ** 3)
            group["fields/density"] = np.full(len(position), 860.0)
            group["fields/free_surface"] = (position[:, 2] > LEVEL - spacing).astype(float)


def write_mesh(path, times, nodes, cells, node_fields, cell_fields):
    """walls.h5 / structure.h5: topology in the first step only, as the programs write it."""
    flat = np.concatenate([np.array(c, dtype=np.int64) for c in cells])
    with h5py.File(path, "w") as f:
        for step, time_s in enumerate(times):
            group = f.create_group(f"step_{step:07d}")
            group.attrs["kind"] = b"mesh"
            group.attrs["time"] = time_s
            grid = {"name": group.name, "time": time_s,
                    "topology": {"connectivity": {"dataset": "/step_0000000/topology/connectivity",
                                                  "dimensions": [len(flat)], "number": "int64"},
                                 "elements": len(cells), "type": "mixed"}}
            group.attrs["xdmf_grid"] = json.dumps(grid).encode()
            if step == 0:
                group["topology/connectivity"] = flat
            group["position"] = nodes
            group["vertex_ids"] = np.arange(len(nodes), dtype=np.int64)
            for name, values in node_fields(step).items():
                group[f"node_fields/{name}"] = values
            for name, values in cell_fields(step).items():
                group[f"cell_fields/{name}"] = values


def build_run(folder, structure=True, ground_in_run=True, one_folder=False, roof_clearance=None, seconds=20.0):
    """A fake run folder of records `seconds` long; returns what the report must
    find in it. The period checks need the 20 s (3.4 sloshing periods); the
    checks of what a report says or leaves out take short records, which the
    period fits (most of a report's time) get through quickly."""
    rng = np.random.default_rng(7)
    time_s = np.round(np.arange(0, seconds + 1e-9, 0.01), 10)
    ax, ay, az = (scale * rng.standard_normal(len(time_s)) for scale in (0.8, 0.4, 0.3))
    slosh_x, slosh_y = newmark(time_s, ax, SLOSHING_S, 0.005), newmark(time_s, ay, SLOSHING_S, 0.005)
    bulge_x = newmark(time_s, ax, BULGING_S, 0.03)
    fluid = folder if one_folder else folder / "fluid"
    structure_folder = folder / "structure"
    fluid.mkdir(parents=True)
    (fluid / ".claims").mkdir()
    (fluid / ".claims" / "sph_solver").touch()
    (fluid / "case.resolved.yaml").write_text(yaml.safe_dump(case(structure), sort_keys=False))
    expected = {"wave": {}, "pressure": {}}
    surface_top = {}
    for name, angle in WAVE_ANGLES.items():
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        reading = 14.99 + 1.5 * (c * slosh_x + s * slosh_y) + 0.002 * rng.standard_normal(len(time_s))
        write_csv(fluid / "probes" / f"{name}.csv", {"time_s": time_s, "wave_height_m": reading})
        expected["wave"][name] = float(np.max(np.abs(reading - reading[0])))
        surface_top[name] = float(reading.max())
    for name, angle in PRESSURE_ANGLES.items():
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        pressure = (117065 + 800 * (c * ax + s * ay) + 3e5 * (c * bulge_x) + 400 * (c * slosh_x + s * slosh_y)
                    + 200 * rng.standard_normal(len(time_s)))
        write_csv(fluid / "probes" / f"{name}.csv", {"time_s": time_s, "pressure_Pa": pressure})
        expected["pressure"][name] = float(pressure.max())
    roof = WALL + math.sqrt(DOME ** 2 - 14.0 ** 2) - math.sqrt(DOME ** 2 - RADIUS ** 2)
    expected["clearance"] = roof - max(surface_top.values())
    write_csv(fluid / "probes" / "fluid.csv", {
        "time_s": time_s, "particles": np.full(len(time_s), 1000.0), "overflow_particles": 0 * time_s,
        "overflow_volume_m3": 0 * time_s, "force_x_N": 1e5 * ax, "force_y_N": 1e5 * ay,
        "force_z_N": -8.9e7 + 0 * time_s, "kinetic_energy_J": 1e3 + 0 * time_s, "time_step_s": 0.01 + 0 * time_s,
        "ppe_iterations": 70 + 0 * time_s, "free_surface_particles": 200 + 0 * time_s,
        "max_density_error": 0.03 + 0 * time_s, "max_speed_m_s": 1 + 0 * time_s})
    if ground_in_run:
        write_csv(fluid / "probes" / "ground_acceleration.csv",
                  {"time_s": time_s, "ax_m_s2": ax, "ay_m_s2": ay, "az_m_s2": az})
    fluid_summary = {"fluid": {"end_time_s": seconds, "particles": 1000, "steps": 2000, "particle_steps_per_second": 3.5e4,
                               "ppe_iterations": {"max": 77, "mean": 69.8}, "wall_seconds": 600.0,
                               "wall_seconds_per_simulated_second": 30.0,
                               "time_step_s": {"max": 0.01, "mean": 0.01, "min": 0.0099},
                               "time_step_limited_by": {"maximum": 2000},
                               "coupling": {"iterations_per_window": 1.0, "windows": 2000} if structure else None},
                     "programs": {"sph_solver": {"stages": {"ppe_solve": {"calls": 2000, "seconds": 150.0}},
                                                 "status": "finished", "wall_time_s": 600.0}}}
    if roof_clearance is not None:
        fluid_summary["fluid"]["roof_clearance_m"] = roof_clearance
    (fluid / "summary.json").write_text(json.dumps(fluid_summary, indent=2))
    (fluid / "provenance.json").write_text(json.dumps(
        {"git_commit": "0" * 40, "programs": {"sph_solver": {"case_file": "/cases/fake/case.yaml", "mpi_ranks": 1}}}))
    field_times = [0.0, seconds / 2, seconds]
    write_particles(fluid / "fluid.h5", field_times)
    nodes, cells = tank_mesh()
    write_mesh(fluid / "walls.h5", field_times, nodes, [c if c[0] == 4 else [4, c[1], c[2], c[3]] for c in cells],
               lambda step: {"force": np.zeros_like(nodes), "pressure": np.zeros(len(nodes))}, lambda step: {})
    if structure:
        structure_folder.mkdir()
        (structure_folder / "case.resolved.yaml").write_text(yaml.safe_dump(case(structure), sort_keys=False))
        displacement_x = 1e-4 * bulge_x / np.max(np.abs(bulge_x)) + 1e-7 * rng.standard_normal(len(time_s))
        write_csv(structure_folder / "probes" / "wall_1m_x.csv", {
            "time_s": time_s, "displacement_x_m": displacement_x, "displacement_y_m": 1e-7 * ay,
            "displacement_z_m": 1e-8 * az})
        shear_x, shear_y = 2e6 * bulge_x / np.max(np.abs(bulge_x)), 5e5 * slosh_y / np.max(np.abs(slosh_y))
        write_csv(structure_folder / "probes" / "structure.csv", {
            "time_s": time_s, "base_shear_x_N": shear_x, "base_shear_y_N": shear_y,
            "support_force_z_N": -3e6 + 0 * time_s,
            "overturning_moment_x_Nm": -8 * shear_y, "overturning_moment_y_Nm": 8 * shear_x,
            "external_force_x_N": shear_x, "external_force_y_N": shear_y, "external_force_z_N": -8.9e7 + 0 * time_s,
            "energy_J": 1e3 + 0 * time_s})
        write_csv(structure_folder / "probes" / "coupling.csv", {
            "time_s": time_s[1:], "window": np.arange(1, len(time_s)), "iterations": 1 + 0 * time_s[1:],
            "converged": 1 + 0 * time_s[1:], "displacement_residual": -1 + 0 * time_s[1:],
            "force_residual": -1 + 0 * time_s[1:]})
        expected["base_shear"] = float(np.max(np.hypot(shear_x, shear_y)))
        expected["moment"] = float(np.max(np.hypot(8 * shear_y, 8 * shear_x)))
        hot_step, hot_element = 1, 40  # the largest von Mises stress: a wall element, second snapshot

        def stresses(step):
            top = np.full(len(cells), 1e6 * (1 + step))
            if step == hot_step:
                top[hot_element] = 5e7
            return {"von_mises_top": top, "von_mises_bottom": np.full(len(cells), 2e6),
                    "membrane_force_11_22_12": np.zeros((len(cells), 3))}

        def displacements(step):
            bulge = 2e-4 * step * np.sin(math.pi * nodes[:, 2] / WALL)
            radial = nodes[:, :2] / RADIUS
            return {"displacement": np.column_stack([bulge * radial[:, 0], bulge * radial[:, 1], 0 * bulge]),
                    "rotation": np.zeros_like(nodes), "velocity": np.zeros_like(nodes)}

        write_mesh(structure_folder / "structure.h5", field_times, nodes, cells, displacements, stresses)
        expected["von_mises"] = 5e7
        expected["von_mises_centroid"] = nodes[cells[hot_element][1:]].mean(axis=0)
        (structure_folder / "summary.json").write_text(json.dumps({
            "coupling": {"iterations_per_window": 1.0, "most_iterations": 1, "unconverged_windows": 0, "windows": 2000},
            "modal": {"periods_s": [0.08, 0.09]},
            "programs": {"fem_solver": {"status": "finished", "wall_time_s": 612.5}},
            "structure": {"analysis": "dynamic", "end_time_s": seconds, "equations": 1000, "nodes": len(nodes),
                          "quadrilaterals": 144, "triangles": 48, "time_step_s": 0.001, "steps": 20000,
                          "seconds_per_step": 0.03, "peak_displacement_m": 2e-4, "peak_base_shear_N": [2e6, 5e5]}},
            indent=2))
        (structure_folder / "provenance.json").write_text(json.dumps(
            {"programs": {"fem_solver": {"case_file": "/cases/fake/case.yaml", "mpi_ranks": 1}}}))
    return expected


def near(value, expected, tolerance):
    return value is not None and abs(value - expected) <= tolerance


def run_cli(folder, *options):
    result = subprocess.run([sys.executable, str(POST / "tank_report.py"), str(folder), *options],
                            capture_output=True, text=True)
    if result.returncode != 0:
        print(result.stdout[-2000:], result.stderr[-2000:])
    return result


with tempfile.TemporaryDirectory() as scratch:
    scratch = pathlib.Path(scratch)

    # 1. A coupled run, reported from the command line.
    coupled = scratch / "coupled"
    expected = build_run(coupled)
    own = {side: (coupled / side / "summary.json").read_bytes() for side in ("fluid", "structure")}
    result = run_cli(coupled)
    check("coupled run: tank_report.py exits 0", result.returncode == 0, result.stdout.strip().splitlines()[0]
          if result.stdout.strip() else result.stderr.strip()[-300:])
    summary = json.loads((coupled / "summary.json").read_text()) if (coupled / "summary.json").is_file() else {}
    keys = ["sloshing_period_s", "bulging_period_s", "convective_period_theory_s", "impulsive_period_theory_s",
            "peak_wave_height_m", "peak_pressure_Pa", "min_roof_clearance_m", "peak_base_shear_N",
            "peak_overturning_moment_Nm", "max_von_mises_Pa", "max_von_mises_location", "wall_time_s"]
    check("combined summary has every promised key", all(k in summary for k in keys),
          ", ".join(k for k in keys if k not in summary))
    check("sloshing period within 1 % of 5.88 s", near(summary.get("sloshing_period_s"), SLOSHING_S, 0.01 * SLOSHING_S),
          str(summary.get("sloshing_period_s")))
    check("bulging period within 1 % of 0.19 s", near(summary.get("bulging_period_s"), BULGING_S, 0.01 * BULGING_S),
          str(summary.get("bulging_period_s")))
    check("theory periods of the paper's tank (5.88 s, 0.19 s)",
          near(summary.get("convective_period_theory_s"), 5.88, 0.005)
          and near(summary.get("impulsive_period_theory_s"), 0.19, 0.005))
    span = summary.get("sloshing_period_records_range_s") or [0, 0]
    check("the sloshing records' range is stated and agrees (no disagreement note)",
          span[0] <= summary.get("sloshing_period_s", 0) <= span[1] and span[1] / span[0] < 1.02
          and not any("disagree" in note for note in summary.get("period_notes", {}).get("sloshing", [])), str(span))
    # The fake case's 14.8 m on layers of L0 = 2 m: layers at 1, 3, ..., 13 m
    # (15 m would be above the level), so the model holds 14 m of liquid.
    model = summary.get("theory_at_model_depth") or {}
    check("theory periods for the model's 14 m of liquid beside the case's 14.8 m",
          near(model.get("liquid_depth_m"), 14.0, 1e-12)
          and near(model.get("convective_period_s"), tank_theory.convective_period(RADIUS, 14.0), 1e-12)
          and near(model.get("impulsive_period_s"),
                   tank_theory.impulsive_period(RADIUS, 14.0, 860, 0.015, 206e9), 1e-12),
          str(model))
    waves = summary.get("peak_wave_height_m", {})
    check("peak wave height of every wave probe",
          set(waves) == set(WAVE_ANGLES) and all(near(waves[n], v, 1e-9) for n, v in expected["wave"].items()))
    pressures = summary.get("peak_pressure_Pa", {})
    check("peak pressure of every pressure probe", set(pressures) == set(PRESSURE_ANGLES)
          and all(near(pressures[n], v, 1e-6) for n, v in expected["pressure"].items()))
    clearance = summary.get("min_roof_clearance_m")
    check("roof clearance estimated at the probes", near(clearance, expected["clearance"], 1e-9)
          and "estimate" in summary.get("roof_clearance", {}).get("source", ""), str(clearance))
    check("peak base shear and overturning moment (resultants)",
          near(summary.get("peak_base_shear_N"), expected["base_shear"], 1e-3)
          and near(summary.get("peak_overturning_moment_Nm"), expected["moment"], 1e-2))
    location = summary.get("max_von_mises_location") or {}
    check("largest von Mises stress and where", near(summary.get("max_von_mises_Pa"), expected["von_mises"], 1e-6)
          and np.allclose(location.get("centroid_m", [np.nan] * 3), expected["von_mises_centroid"])
          and location.get("region") == "wall" and near(location.get("time_s"), 10.0, 1e-9), json.dumps(location))
    check("wall time is the longer program's", near(summary.get("wall_time_s"), 612.5, 1e-9))
    missing_plots = [p for p in PLOTS if not (coupled / "plots" / p).is_file()
                     or (coupled / "plots" / p).read_bytes()[:8] != b"\x89PNG\r\n\x1a\n"]
    check("every promised plot is a PNG", not missing_plots, ", ".join(missing_plots))
    report = (coupled / "report.md").read_text() if (coupled / "report.md").is_file() else ""
    check("report links every plot", all(f"](plots/{p})" in report for p in PLOTS))
    check("report leaves the marked place for the case README", tank_report_markdown.PLACEHOLDER in report)
    check("report sets the periods beside the theory for the model's depth",
          "theory for the model's 14.00 m of liquid" in report)
    check("report has the settings and the run time", "| coupling scheme | parallel_staggered |" in report
          and "particle-steps/s" in report)
    check("the programs' own summaries are untouched",
          all((coupled / side / "summary.json").read_bytes() == own[side] for side in own))

    # 2. A coupled run that failed: no summaries, an error in the log.
    failed = scratch / "failed"
    build_run(failed, seconds=3.0)
    for side in ("fluid", "structure"):
        (failed / side / "summary.json").unlink()
    (failed / "fluid" / "run.log").write_text(
        "2026-12-02T04:58:05Z [sph_solver] error: step 9 at t = 0.06 s: 1 particle(s) crossed a wall\n")
    result = run_cli(failed)
    report = (failed / "report.md").read_text()
    check("failed run: reported, with the log's error and the missing summaries", result.returncode == 0
          and "**The run failed.**" in report and "crossed a wall" in report and "no fluid summary.json" in report)

    # 3. A fluid-only run in one folder, no ground record and no tankfsi_case to write one.
    alone = scratch / "fluid_alone"
    build_run(alone, structure=False, ground_in_run=False, one_folder=True)
    own_summary = (alone / "summary.json").read_bytes()
    result = run_cli(alone, "--tankfsi-case", str(scratch / "no_such_program"))
    check("fluid-only run: tank_report.py exits 0", result.returncode == 0)
    check("fluid-only run: its own summary.json stays, the combined one is tank_summary.json",
          (alone / "summary.json").read_bytes() == own_summary and (alone / "tank_summary.json").is_file())
    summary = json.loads((alone / "tank_summary.json").read_text()) if (alone / "tank_summary.json").is_file() else {}
    report = (alone / "report.md").read_text() if (alone / "report.md").is_file() else ""
    check("fluid-only run: missing structure and ground motion are lines of the report",
          "no structure folder" in report and "no ground acceleration" in report and "not made" in report)
    check("fluid-only run: no invented figures", summary.get("bulging_period_s") is None
          and summary.get("sloshing_period_s") is None and summary.get("peak_base_shear_N") is None
          and summary.get("impulsive_period_theory_s") is None and len(summary.get("peak_wave_height_m", {})) == 4)
    check("fluid-only run: the plots it can make exist",
          all((alone / "plots" / p).is_file() for p in ("wave_heights.png", "wall_pressures.png", "spectra.png",
                                                        "section_snapshot.png"))
          and not (alone / "plots" / "base_shear_overturning.png").exists())

    # 4. The case README's "Periods against theory" section, when it has one, instead of the marked place.
    case_folder = scratch / "case_with_readme"
    case_folder.mkdir()
    (case_folder / "README.md").write_text("# fake\n\n## Periods against theory\n\nThe roof stiffens the wall.\n"
                                           "\n## Ground motion\n\nnot this\n")
    explained = scratch / "explained"
    build_run(explained, structure=False, seconds=3.0)
    provenance = json.loads((explained / "fluid" / "provenance.json").read_text())
    provenance["programs"]["sph_solver"]["case_file"] = str(case_folder / "case.yaml")
    (explained / "fluid" / "provenance.json").write_text(json.dumps(provenance))
    run_cli(explained)
    report = (explained / "report.md").read_text() if (explained / "report.md").is_file() else ""
    check("the case README's explanation replaces the marked place", "The roof stiffens the wall." in report
          and "not this" not in report and tank_report_markdown.PLACEHOLDER not in report)

    # 5. The fluid program's own roof clearance is used when it writes one.
    own_clearance = scratch / "own_clearance"
    build_run(own_clearance, structure=False, roof_clearance=2.5, seconds=3.0)
    summary, _ = tank_report.build_report(own_clearance)
    check("roof_clearance_m of the fluid summary is used", summary["min_roof_clearance_m"] == 2.5
          and "fluid summary" in summary["roof_clearance"]["source"])

# 6. Records that disagree beyond their deviations (the coarse tank's forced
# fits: 6.136 +- 0.10 s against 6.616 +- 0.18 s) are said to, with their range.
records = {"wave_0deg": {"period_s": 6.136, "period_std_s": 0.10}, "wave_90deg": {"reason": "uncertain"},
           "wave_180deg": {"period_s": 6.616, "period_std_s": 0.18},
           "wave_270deg": {"period_s": 6.143, "period_std_s": 0.052}}
span, note = tank_figures.records_agreement("sloshing", records)
check("disagreeing records: their range and a note naming the pair most deviations apart (2.5)",
      span == [6.136, 6.616] and note is not None and "wave_180deg 6.616 s and wave_270deg 6.143 s" in note
      and "2.5 standard" in note, str(note))
records["wave_180deg"]["period_s"] = 6.30  # 0.8 deviations of the difference from 6.136, 0.9 from 6.143
span, note = tank_figures.records_agreement("sloshing", records)
check("records within their deviations: the range, no note", span == [6.136, 6.30] and note is None, str(note))
check("one record: no range", tank_figures.records_agreement("bulging", {"p": records["wave_0deg"]}) == (None, None))

# 7. A record of few cycles that ends while the ground shakes is said to hold
# forced response alone; one that ends after the motion, or holds many
# cycles, is not.
time_s = np.arange(0.0, 40.0 + 1e-9, 0.02)
shaking = {"time_s": time_s, "ax_m_s2": np.sin(time_s), "ay_m_s2": 0 * time_s, "az_m_s2": 0 * time_s}
note = tank_figures.forced_record_note("sloshing", shaking, 20.0, 5.88)
check("forced record of 3.4 cycles: a note", note is not None and "3.4" in note, str(note))
still = dict(shaking, ax_m_s2=np.where(time_s < 16.0, np.sin(time_s), 0.0))
check("record going on 24 s past the motion: no note",
      tank_figures.forced_record_note("sloshing", still, 40.0, 5.88) is None)
check("record of 100 cycles: no note", tank_figures.forced_record_note("bulging", shaking, 20.0, 0.2) is None)

passed = sum(checks)
print(f"{passed} passed, {len(checks) - passed} failed")
sys.exit(0 if passed == len(checks) else 1)
