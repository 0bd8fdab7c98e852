#!/usr/bin/python3
"""The paper's outputs of a 2D overflow run (cases/overflow_2d, paper §3):

  plots/overflow_history.png   input acceleration, wave height at the gauge nearest
                               the left wall, overflowed volume and the inner tank's
                               mean level
  plots/overflow_periods.png   each sloshing cycle's period at that gauge against
                               linear theory for the inner tank's mean depth of the
                               moment (Faltinsen: w^2 = g (pi/L) tanh(pi h/L))
  plots/overflow_pressure_<t>s.png
                               particles coloured by pressure at the snapshots
                               nearest the given times (the paper: 35 s and 45 s)
  overflow_report.md           the figures of the plots in numbers

Usage: overflow_figures.py RUN_FOLDER [--at 35 45]

The run needs a wave_height probe placed on the floor (it reads the level; the
wave height is the level less its value at t = 0) and a volume probe whose box is
the inner tank (its outside column is the overflowed liquid).
"""
import argparse
import math
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from tank_run import TankRun, read_csv  # noqa: E402

# A cycle counts when its crest-to-trough height is at least this share of the
# largest one: the quiet start and end would otherwise give periods of noise.
CYCLE_SHARE = 0.1


def up_crossings(time_s, values):
    """Times where `values` crosses zero upwards, linearly interpolated."""
    below, above = values[:-1], values[1:]
    k = np.nonzero((below < 0.0) & (above >= 0.0))[0]
    return time_s[k] + (time_s[k + 1] - time_s[k]) * (-below[k] / (above[k] - below[k]))


def cycles(time_s, oscillation):
    """(mid-time, period, crest-to-trough height) of each cycle between up-crossings."""
    crossings = up_crossings(time_s, oscillation)
    found = []
    for start, end in zip(crossings[:-1], crossings[1:]):
        inside = (time_s >= start) & (time_s <= end)
        if inside.sum() >= 3:
            swing = float(np.ptp(oscillation[inside]))
            found.append((0.5 * (start + end), end - start, swing))
    return np.array(found).reshape(-1, 3)


def linear_period(width_m, depth_m, gravity=9.81):
    """First-mode period of a rectangular tank (Faltinsen)."""
    k = math.pi / width_m
    return 2.0 * math.pi / math.sqrt(gravity * k * math.tanh(k * depth_m))


def wall_outline(run, time_s):
    """Segments (k x 2 x 2) where the wall triangles nearest `time_s` cut the plane z = 0."""
    walls = run.wall_snapshots()
    if not walls:
        return np.zeros((0, 2, 2))
    nearest = min(walls, key=lambda s: abs(s.time_s - time_s))
    (positions,) = nearest.read("position")
    segments = []
    for cell in nearest.cells():
        points = []
        for a, b in zip(cell, np.roll(cell, -1)):
            za, zb = positions[a, 2], positions[b, 2]
            if za * zb < 0.0:
                w = za / (za - zb)
                points.append(((1 - w) * positions[a] + w * positions[b])[:2])
        if len(points) == 2:
            segments.append(points)
    return np.array(segments).reshape(-1, 2, 2)


def plot_pressure(run, target_s, plots, density):
    """Particles of the snapshot nearest target_s coloured by pressure; the path and the time shown."""
    series = run.fluid_snapshots()
    if not series:
        return None
    snapshot = min(series, key=lambda s: abs(s.time_s - target_s))
    positions, pressure = snapshot.read("position", "fields/pressure")
    figure, axis = plt.subplots(figsize=(10, 4.2))
    outline = wall_outline(run, snapshot.time_s)
    for segment in outline:
        axis.plot(segment[:, 0], segment[:, 1], color="0.3", linewidth=1.0)
    top = density * 9.81 * 0.8  # colour range: hydrostatic at 0.8 m depth
    dots = axis.scatter(positions[:, 0], positions[:, 1], c=pressure, s=4, cmap="viridis", vmin=0.0, vmax=top)
    figure.colorbar(dots, ax=axis, label="pressure (Pa)")
    axis.set_aspect("equal")
    axis.set_xlabel("x (m)")
    axis.set_ylabel("y (m)")
    axis.set_title(f"pressure at t = {snapshot.time_s:.2f} s (snapshot nearest {target_s:g} s)")
    figure.tight_layout()
    path = plots / f"overflow_pressure_{target_s:g}s.png"
    figure.savefig(path, dpi=130)
    plt.close(figure)
    return path, snapshot.time_s


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run", type=pathlib.Path)
    parser.add_argument("--at", type=float, nargs="*", default=[35.0, 45.0], help="times of the pressure maps (s)")
    args = parser.parse_args()
    run = TankRun(args.run)
    width = float(run.case_value("fluid.geometry.width", 2.0))
    density = float(run.case_value("fluid.density", 1000.0))
    levels = sorted(run.probes("fluid", "wave_height"), key=lambda p: p[1][0])
    volumes = [read_csv(run.fluid / "probes" / f"{p['name']}.csv")
               for p in run.case_value("fluid.probes", []) or [] if p.get("quantity") == "volume"]
    if not levels or not volumes or volumes[0] is None:
        raise SystemExit(f"{args.run}: needs a wave_height probe and a volume probe (see --help)")
    gauge, gauge_at, level = levels[0][:3]
    volume = volumes[0]
    plots = args.run / "plots"
    plots.mkdir(exist_ok=True)

    t = level["time_s"]
    still = float(level["wave_height_m"][0])
    wave = level["wave_height_m"] - still
    inner_key = next(k for k in volume if k.startswith("volume_m3"))
    outside_key = next(k for k in volume if k.startswith("outside_m3"))
    mean_level = np.interp(t, volume["time_s"], volume[inner_key]) / width
    overflowed = volume[outside_key]
    ground, _ = run.ground_acceleration()

    figure, axes = plt.subplots(3, 1, sharex=True, figsize=(9, 8))
    if ground is not None:
        axes[0].plot(ground["time_s"], ground["ax_m_s2"], linewidth=0.6)
    axes[0].set_ylabel("ground a_x (m/s²)")
    axes[0].set_title(f"overflow run: input, wave height at x = {gauge_at[0]:g} m ({gauge}), overflow")
    axes[1].plot(t, wave, linewidth=0.7, label="wave height at the gauge")
    axes[1].plot(t, mean_level - mean_level[0], linewidth=1.2, label="change of the inner tank's mean level")
    axes[1].set_ylabel("m")
    axes[1].legend(loc="lower left", fontsize=8)
    axes[2].plot(volume["time_s"], 1000.0 * overflowed, linewidth=1.0)
    axes[2].set_ylabel("overflowed (l per m of depth)")
    axes[2].set_xlabel("time (s)")
    for axis in axes:
        axis.grid(True, alpha=0.3)
    figure.tight_layout()
    figure.savefig(plots / "overflow_history.png", dpi=130)
    plt.close(figure)

    # Periods of the level's oscillation about the inner tank's falling mean level.
    found = cycles(t, wave - (mean_level - mean_level[0]))
    kept = found[found[:, 2] >= CYCLE_SHARE * found[:, 2].max()] if len(found) else found
    depth_at = np.interp(kept[:, 0], t, mean_level) if len(kept) else np.array([])
    theory = np.array([linear_period(width, h) for h in depth_at])
    figure, axis = plt.subplots(figsize=(9, 4))
    axis.plot(kept[:, 0], kept[:, 1], "o", markersize=4, label="period of each cycle at the gauge")
    axis.plot(kept[:, 0], theory, "-", label="linear theory for the mean depth of the moment")
    axis.set_xlabel("time (s)")
    axis.set_ylabel("period (s)")
    axis.set_title("sloshing period: lengthening as the level falls")
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(plots / "overflow_periods.png", dpi=130)
    plt.close(figure)

    maps = [m for m in (plot_pressure(run, at, plots, density) for at in args.at) if m]

    lines = [f"# Overflow run {args.run}", "",
             f"Gauge `{gauge}` at x = {gauge_at[0]:g} m; still level there {still:.4f} m; "
             f"inner tank {width:g} m wide.", "",
             "| figure | value |", "|---|---|"]
    crest, trough = int(np.nanargmax(wave)), int(np.nanargmin(wave))
    lines.append(f"| highest crest at the gauge | {wave[crest]:+.4f} m at {t[crest]:.2f} s |")
    lines.append(f"| deepest trough at the gauge | {wave[trough]:+.4f} m at {t[trough]:.2f} s |")
    end = float(volume["time_s"][-1])
    for at in sorted(a for a in set(args.at) | {end} if a <= end):
        lines.append(f"| overflowed by {at:g} s | "
                     f"{1000.0 * np.interp(at, volume['time_s'], overflowed):.2f} l per m of depth |")
    lines.append(f"| inner tank's mean level | {mean_level[0]:.4f} m at the start, {mean_level[-1]:.4f} m at the end |")
    # Periods before the liquid first spills and after it last did: the paper's
    # lengthening period as the level falls (cycles wholly inside each window).
    spilling = np.nonzero(np.diff(overflowed) > 0.0)[0]
    if len(spilling):
        first, last = volume["time_s"][spilling[0]], volume["time_s"][spilling[-1] + 1]
        halves = kept[:, 1] / 2 if len(kept) else np.array([])
        windows = (("before the first overflow", kept[kept[:, 0] + halves <= first] if len(kept) else kept),
                   ("after the last overflow", kept[kept[:, 0] - halves >= last] if len(kept) else kept))
        lines.append(f"| overflow | from {first:.2f} s to {last:.2f} s |")
        for label, part in windows:
            if len(part) == 0:
                lines.append(f"| period {label} | no whole cycle |")
                continue
            h = np.interp(part[:, 0], t, mean_level).mean()
            lines.append(f"| period {label} ({len(part)} cycles, {part[0, 0]:.1f}–{part[-1, 0]:.1f} s) | "
                         f"{part[:, 1].mean():.3f} s (linear theory at mean depth {h:.3f} m: "
                         f"{linear_period(width, h):.3f} s) |")
    else:
        lines.append("| overflow | none |")
    for path, shown in maps:
        lines.append(f"| pressure map | {path.relative_to(args.run)} (t = {shown:.2f} s) |")
    report = args.run / "overflow_report.md"
    report.write_text("\n".join(lines) + "\n")
    print(f"overflow_figures: {report}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
