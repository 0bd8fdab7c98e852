#!/usr/bin/python3
"""Plots every probe time series of a run folder: RUN/probes/NAME.csv -> RUN/plots/NAME.png.

Usage: plot_probes.py RUN_FOLDER

Each CSV has time_s first and then columns named with their unit
(wave_height_m, pressure_Pa, ax_m_s2, ...); each column gets its own panel.
"""
import pathlib
import sys

import matplotlib

matplotlib.use("Agg")  # files only, no display needed
import matplotlib.pyplot as plt
import numpy as np


def plot_probe(csv_path: pathlib.Path, plots: pathlib.Path) -> pathlib.Path:
    data = np.genfromtxt(csv_path, delimiter=",", names=True)
    columns = [c for c in data.dtype.names if c != "time_s"]
    figure, axes = plt.subplots(len(columns), 1, sharex=True, figsize=(8, 1.8 + 1.6 * len(columns)), squeeze=False)
    time = np.atleast_1d(data["time_s"])
    for axis, column in zip(axes[:, 0], columns):
        axis.plot(time, np.atleast_1d(data[column]), linewidth=0.8)
        axis.set_ylabel(column)
        axis.grid(True, alpha=0.3)
    axes[-1, 0].set_xlabel("time_s")
    axes[0, 0].set_title(csv_path.stem)
    figure.tight_layout()
    out = plots / f"{csv_path.stem}.png"
    figure.savefig(out, dpi=110)
    plt.close(figure)
    return out


def main() -> int:
    if len(sys.argv) != 2:
        print(__doc__, file=sys.stderr)
        return 2
    run = pathlib.Path(sys.argv[1])
    probes = sorted((run / "probes").glob("*.csv"))
    if not probes:
        print(f"plot_probes: no probes in {run / 'probes'}", file=sys.stderr)
        return 1
    plots = run / "plots"
    plots.mkdir(exist_ok=True)
    for csv_path in probes:
        print(f"plot_probes: {plot_probe(csv_path, plots)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
