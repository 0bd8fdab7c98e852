"""A vertical section through the tank axis, as the paper's Fig. 9: the
particles of one field snapshot near the section plane coloured by pressure,
and the tank's shell cut by the plane, deformed by the structure's
displacement magnified (the factor in the title), over the undeformed outline.
Without a structure the fluid's own (rigid) walls are drawn instead. The
snapshot is the last, the one nearest the largest wave height, or the one
nearest a given time.
"""
import math

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402


def section_segments(positions, cells, normal, along, displacement=None, factor=0.0):
    """Segments (k x 2 x 2: horizontal coordinate along the section, height)
    where the plane through the axis with horizontal normal `normal` cuts the
    cells; each point is displaced by factor * displacement, interpolated
    along the cut edge (the material section, deformed)."""
    moved = positions if displacement is None else positions + factor * displacement
    distance = positions[:, :2] @ normal
    tolerance = 1e-9 * (np.ptp(positions) or 1.0)
    segments = []
    for cell in cells:
        points = []
        for a, b in zip(cell, np.roll(cell, -1)):
            da, db = distance[a], distance[b]
            if abs(da) <= tolerance:
                points.append(moved[a])
            elif da * db < 0 and abs(db) > tolerance:
                w = da / (da - db)
                points.append((1 - w) * moved[a] + w * moved[b])
        if len(points) >= 2:
            points = np.array(points)
            gaps = np.linalg.norm(points[:, None] - points[None], axis=2)
            i, j = np.unravel_index(np.argmax(gaps), gaps.shape)
            if gaps[i, j] > tolerance:
                segments.append([[points[i, :2] @ along, points[i, 2]], [points[j, :2] @ along, points[j, 2]]])
    return np.array(segments).reshape(-1, 2, 2)


def magnification(largest_displacement_m, size_m, share=0.05):
    """A round factor (1, 2 or 5 times a power of ten) that draws the largest
    displacement as about `share` of the tank's size."""
    if not largest_displacement_m > 0:
        return 1.0
    raw = share * size_m / largest_displacement_m
    power = 10.0 ** math.floor(math.log10(raw))
    return max(m * power for m in (1, 2, 5) if m * power <= raw)


def plot_section(out, particles, shell, direction_deg, spacing_m, title_time, rigid_walls=None,
                 direction_note="main shaking direction"):
    """particles: (positions, pressures); shell: (positions, cells, displacement)
    or None, then rigid_walls: (positions, cells) of the fluid's walls.
    Returns the magnification used (None without a structure)."""
    angle = math.radians(direction_deg)
    along = np.array([math.cos(angle), math.sin(angle)])
    normal = np.array([-math.sin(angle), math.cos(angle)])
    positions, pressures = particles
    near = np.abs(positions[:, :2] @ normal) <= 0.5 * spacing_m
    figure, axis = plt.subplots(figsize=(10, 6.8))
    factor = None
    if shell is not None:
        shell_positions, cells, displacement = shell
        in_plane = np.abs(shell_positions[:, :2] @ normal) <= 1e-6 + 0.5 * spacing_m
        largest = float(np.max(np.linalg.norm(displacement[in_plane], axis=1))) if in_plane.any() else 0.0
        factor = magnification(largest, np.ptp(shell_positions[:, 2]))
        undeformed = section_segments(shell_positions, cells, normal, along)
        deformed = section_segments(shell_positions, cells, normal, along, displacement, factor)
        axis.plot(*undeformed.transpose(2, 1, 0), color="0.6", linewidth=0.8, linestyle="--")
        axis.plot(*deformed.transpose(2, 1, 0), color="black", linewidth=1.6)
        axis.plot([], [], color="0.6", linestyle="--", label="shell, undeformed")
        axis.plot([], [], color="black", label=f"shell, displacement x {factor:g} (largest {largest:.3g} m)")
    elif rigid_walls is not None:
        wall_positions, cells = rigid_walls
        walls = section_segments(wall_positions, cells, normal, along)
        axis.plot(*walls.transpose(2, 1, 0), color="black", linewidth=1.2)
        axis.plot([], [], color="black", label="rigid walls (no structure)")
    span = np.ptp(positions[:, :2] @ along) + 4 * spacing_m
    points_per_metre = 10 * 72 * 0.8 / max(span, 1e-9)
    scatter = axis.scatter(positions[near, :2] @ along, positions[near, 2], c=pressures[near] / 1e3, cmap="viridis",
                           s=max(1.0, (0.9 * spacing_m * points_per_metre) ** 2), marker="o", linewidths=0)
    figure.colorbar(scatter, ax=axis, label="pressure (kPa)", shrink=0.8)
    axis.set_aspect("equal")
    axis.set_xlabel(f"distance from the axis along {direction_deg:.0f} deg from x (m)")
    axis.set_ylabel("height above the floor (m)")
    axis.legend(loc="upper center", fontsize=8, ncol=2, bbox_to_anchor=(0.5, -0.1))
    wall_note = (f"shell displacement magnified x {factor:g}" if factor is not None else "rigid walls")
    axis.set_title(f"Section through the tank axis along {direction_deg:.0f} deg ({direction_note}), "
                   f"{title_time}\nparticles within {0.5 * spacing_m:g} m of the plane ({near.sum()}) by pressure; "
                   f"{wall_note}", fontsize=9)
    figure.tight_layout()
    figure.savefig(out, dpi=110)
    plt.close(figure)
    return factor


def choose_snapshot(run, which, wave):
    """The fluid snapshot to draw: the last, the one nearest the largest wave
    height (severe), or the one nearest a given time. Returns (snapshot, why)."""
    series = run.fluid_snapshots()
    if not series:
        return None, "no fluid snapshots"
    if which == "last":
        return series[-1], "the last snapshot"
    if which == "severe":
        if not wave:
            return series[-1], "the last snapshot (no wave probes to find the most severe one)"
        name, figures = max(wave.items(), key=lambda item: item[1]["peak_m"])
        target = figures["peak_time_s"]
        why = f"the snapshot nearest the largest wave height ({name} at {target:.2f} s)"
    else:
        target, why = float(which), f"the snapshot nearest t = {float(which):g} s"
    return min(series, key=lambda s: abs(s.time_s - target)), why


def plot_run_section(run, direction_deg, which, wave, path):
    """The Fig. 9 section of a TankRun: the chosen fluid snapshot, the
    structure's snapshot nearest it (or the fluid's rigid walls); returns a
    dict describing what it shows, or None without a fluid snapshot."""
    snapshot, why = choose_snapshot(run, which, wave)
    if snapshot is None:
        return None
    positions, pressures = snapshot.read("position", "fields/pressure")
    if positions is None or pressures is None:
        return None
    shell = walls = None
    title_time = f"t = {snapshot.time_s:.2f} s"
    structure = run.structure_snapshots()
    if structure:
        nearest = min(structure, key=lambda s: abs(s.time_s - snapshot.time_s))
        shell_positions, displacement = nearest.read("position", "node_fields/displacement")
        if shell_positions is not None and displacement is not None:
            shell = (shell_positions, nearest.cells(), displacement)
            if abs(nearest.time_s - snapshot.time_s) > 1e-6:
                title_time += f" (structure at {nearest.time_s:.2f} s)"
    if shell is None and run.wall_snapshots():
        wall = min(run.wall_snapshots(), key=lambda s: abs(s.time_s - snapshot.time_s))
        wall_positions, = wall.read("position")
        walls = (wall_positions, wall.cells())
    spacing = run.case_value("fluid.spacing", 1.0)
    direction_note = "main shaking direction"
    if direction_deg is None:
        direction_deg, direction_note = 0.0, "x: no ground record to find the main shaking direction"
    factor = plot_section(path, (positions, pressures), shell, direction_deg, spacing, title_time, walls,
                          direction_note)
    return {"time_s": snapshot.time_s, "chosen": why, "direction_deg": direction_deg, "direction": direction_note,
            "magnification": factor}
