"""The time-history and spectrum plots of a tank report (RUN/plots/*.png):
wave heights, wall pressures, their spectra with the theory and identified
periods marked, base shear and overturning moment, ground acceleration, and
the records the periods were identified from against their fitted
oscillators. Each function writes one file and returns its path, or None
when the run lacks what it shows (the report says so).
"""
import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import tank_figures  # noqa: E402
import tank_periods  # noqa: E402


def _save(figure, path):
    figure.tight_layout()
    figure.savefig(path, dpi=110)
    plt.close(figure)
    return path


def _change_history(path, title, ylabel, curves):
    """One panel of changes from t = 0: curves are (time, values, label)."""
    figure, axis = plt.subplots(figsize=(9, 4))
    for time, values, label in curves:
        axis.plot(time, values, linewidth=0.9, label=label)
    axis.axhline(0, color="0.5", linewidth=0.6)
    axis.set_xlabel("time (s)")
    axis.set_ylabel(ylabel)
    axis.set_title(title)
    axis.grid(True, alpha=0.3)
    axis.legend(fontsize=8)
    return _save(figure, path)


def wave_heights(run, path):
    """eta = surface - surface at rest of every wave probe."""
    probes = run.probes("fluid", "wave_height")
    if not probes:
        return None
    curves = []
    for name, position, record, _ in probes:
        surface = position[2] + record["wave_height_m"]
        curves.append((record["time_s"], surface - surface[0],
                       f"{name} (r = {np.hypot(*position[:2]):.1f} m, at rest {surface[0]:.3f} m)"))
    return _change_history(path, "Wave height at the wave probes: free surface minus its height at t = 0",
                           "wave height eta (m)", curves)


def wall_pressures(run, path):
    """Pressure change from t = 0 at every pressure probe (the hydrostatic part is the legend's)."""
    probes = run.probes("fluid", "pressure")
    if not probes:
        return None
    curves = []
    for name, position, record, _ in probes:
        pressure = record["pressure_Pa"]
        curves.append((record["time_s"], (pressure - pressure[0]) / 1e3,
                       f"{name} (z = {position[2]:g} m, p(0) = {pressure[0] / 1e3:.1f} kPa)"))
    return _change_history(path, "Wall pressure at the pressure probes: change from t = 0", "p - p(0) (kPa)", curves)


def _period_lines(axis, theory, periods):
    """Vertical lines at 1/T: theory dashed, identified solid."""
    marks = [("T_c theory", theory.get("convective_period_theory_s"), "tab:blue", "--"),
             ("T_i theory", theory.get("impulsive_period_theory_s"), "tab:red", "--"),
             ("T_c identified", periods.get("sloshing"), "tab:blue", "-"),
             ("T_i identified", periods.get("bulging"), "tab:red", "-")]
    for label, period, colour, style in marks:
        if period:
            axis.axvline(1 / period, color=colour, linestyle=style, linewidth=1.1, label=f"{label} {period:.4g} s")


def spectra(run, theory, periods, path):
    """Amplitude spectra of wave heights and wall pressures (and radial wall
    displacements when the structure has probes), with the periods marked."""
    waves = [(n, r["time_s"], r["wave_height_m"]) for n, _, r, _ in run.probes("fluid", "wave_height")]
    pressures = [(n, r["time_s"], r["pressure_Pa"]) for n, _, r, _ in run.probes("fluid", "pressure")]
    panels = [("wave height", waves, "m"), ("wall pressure", pressures, "Pa")]
    displacements = [(f"{n} radial", r["time_s"], tank_figures.radial_displacement(p, r, d))
                     for n, p, r, d in run.probes("structure", "displacement")]
    if displacements:
        panels.append(("wall displacement", displacements, "m"))
    panels = [p for p in panels if p[1]]
    if not panels:
        return None
    figure, axes = plt.subplots(len(panels), 1, figsize=(9, 3.3 * len(panels)), squeeze=False)
    marked = [p for p in (theory.get("convective_period_theory_s"), theory.get("impulsive_period_theory_s"),
                          periods.get("sloshing"), periods.get("bulging")) if p]
    for axis, (title, records, unit) in zip(axes[:, 0], panels):
        resolved, highest = np.inf, 0.0
        for name, time_s, values in records:
            time_s, values = tank_periods.uniform_record(time_s, values)
            frequency, amplitude = tank_periods.amplitude_spectrum(time_s, values)
            shown = frequency >= frequency[tank_periods.SPECTRUM_PADDING]  # from 1 / record length
            axis.loglog(frequency[shown], amplitude[shown], linewidth=0.8, label=name)
            resolved, highest = min(resolved, frequency[tank_periods.SPECTRUM_PADDING]), max(highest, frequency[-1])
        _period_lines(axis, theory, periods)
        nyquist = highest
        lowest = min([resolved / 2] + [0.7 / p for p in marked])
        highest = max([highest] + [1.4 / p for p in marked])
        # The record resolves nothing below 1 / its length nor above Nyquist: say so.
        axis.axvspan(lowest, resolved, color="0.85", alpha=0.6, label="below 1 / record length")
        if highest > nyquist * 1.01:
            axis.axvspan(nyquist, highest, color="0.7", alpha=0.4, label="above Nyquist")
        axis.set_xlim(lowest, highest)
        axis.set_xlabel("frequency (Hz)")
        axis.set_ylabel(f"amplitude ({unit})")
        identified = "solid: identified" if any(periods.values()) else "none identified"
        axis.set_title(f"Spectrum of {title} (linear trend removed, Hann window); dashed: theory periods, {identified}",
                       fontsize=9)
        axis.grid(True, which="both", alpha=0.25)
        axis.legend(fontsize=7, ncol=2, loc="best")
    return _save(figure, path)


def base_reactions(run, path):
    """Base shear and overturning moment (x, y and resultant) from probes/structure.csv."""
    history = run.history("structure", "structure")
    if history is None or "base_shear_x_N" not in history:
        return None
    figure, axes = plt.subplots(2, 1, sharex=True, figsize=(9, 5.5))
    time_s = history["time_s"]
    for axis, stem, unit, scale, title in (
            (axes[0], "base_shear", "N", 1e6, "Base shear (support forces)"),
            (axes[1], "overturning_moment", "Nm", 1e6, "Overturning moment (support forces)")):
        x, y = history[f"{stem}_x_{unit}"], history[f"{stem}_y_{unit}"]
        axis.plot(time_s, x / scale, linewidth=0.8, label="x")
        axis.plot(time_s, y / scale, linewidth=0.8, label="y")
        axis.plot(time_s, np.hypot(x, y) / scale, color="black", linewidth=1.0, label="resultant")
        axis.set_ylabel(f"{'MN' if unit == 'N' else 'MN m'}")
        axis.set_title(title, fontsize=10)
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    axes[-1].set_xlabel("time (s)")
    return _save(figure, path)


def ground_acceleration(ground, source, path):
    """The three components of the applied ground acceleration."""
    if ground is None:
        return None
    figure, axes = plt.subplots(3, 1, sharex=True, figsize=(9, 5.5))
    for axis, column, label in zip(axes, ("ax_m_s2", "ay_m_s2", "az_m_s2"), ("a_x", "a_y", "a_z")):
        if column in ground:
            axis.plot(ground["time_s"], ground[column], linewidth=0.8)
            axis.set_title(f"{label}: peak |a| {np.max(np.abs(ground[column])):.3g} m/s^2", fontsize=9, loc="left")
        axis.set_ylabel(f"{label} (m/s^2)")
        axis.grid(True, alpha=0.3)
    figure.suptitle("Ground acceleration applied at the tank base", fontsize=10)
    axes[-1].set_xlabel("time (s)")
    figure.text(0.01, 0.005, f"from {source.split(' (')[0]}", fontsize=7, color="0.4")
    return _save(figure, path)


def period_fits(identification, path):
    """The record each identified period comes from against its fitted oscillator."""
    panels = [(kind, result["best"][0], result["fits"][result["best"][0]], result["best"][1])
              for kind, result in identification.items() if result["best"]]
    if not panels:
        return None
    figure, axes = plt.subplots(len(panels), 1, figsize=(9, 3.2 * len(panels)), squeeze=False)
    for axis, (kind, name, (time_s, values, fitted, quantity), estimate) in zip(axes[:, 0], panels):
        axis.plot(time_s, values, linewidth=0.8, label=f"{name} (record)")
        axis.set_ylabel(quantity)
        axis.plot(time_s, fitted, linewidth=1.0, linestyle="--", label="fitted oscillator + drift + feedthrough")
        axis.set_title(f"{kind}: T = {estimate['period_s']:.4g} +- {estimate['period_std_s']:.2g} s, "
                       f"damping {100 * estimate['damping_ratio']:.2f} %, "
                       f"{100 * estimate['explained_fraction']:.0f} % of the variance explained", fontsize=9)
        axis.set_xlabel("time (s)")
        axis.grid(True, alpha=0.3)
        axis.legend(fontsize=8)
    return _save(figure, path)
