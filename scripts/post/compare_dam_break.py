#!/usr/bin/python3
"""Dam-break surge front of a run against the experiments.

Usage: compare_dam_break.py RUN_FOLDER [--column-width 1.0] [--gravity 9.81]

Reads probes/front.csv (front_x_m, measured from the wall behind the column) and
prints, at the experimental times, Z = z/a against Martin & Moyce (1952, n^2 = 2)
and Koshizuka & Oka (1996), T = t sqrt(2 g / a); writes plots/dam_break_front.png.
Points where the front has reached the far wall of the tank are not comparable
and are left out (the experiments' tanks were longer). The last column, the lag,
is how much earlier (in T) the run reaches each experimental Z.
"""
import argparse
import pathlib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

MARTIN_MOYCE = [(0.832, 1.217), (1.219, 1.474), (1.997, 2.292), (2.547, 2.995), (3.345, 4.134),
                (4.034, 4.944), (4.418, 5.881), (5.091, 6.980)]
KOSHIZUKA_OKA = [(0.381, 1.111), (0.769, 1.252), (1.153, 1.505), (1.537, 1.892), (1.935, 2.241),
                 (2.323, 2.615), (2.719, 3.003)]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("run")
    parser.add_argument("--column-width", type=float, default=1.0)
    parser.add_argument("--gravity", type=float, default=9.81)
    args = parser.parse_args()
    run = pathlib.Path(args.run)
    data = np.loadtxt(run / "probes" / "front.csv", delimiter=",", skiprows=1)
    a = args.column_width
    T = data[:, 0] * np.sqrt(2 * args.gravity / a)
    Z = data[:, 1] / a
    reach = Z.max() - 0.05  # beyond this the front is at the far wall
    # lag: how much earlier (in T) the run reaches the experiment's Z: a constant lag
    # is a delayed start of the experiment (gate removal), a growing one a faster front.
    print(f"{'reference':<16}{'T':>7}{'Z ref':>8}{'Z run':>8}{'error':>9}{'lag':>8}")
    for name, points in (("Martin & Moyce", MARTIN_MOYCE), ("Koshizuka & Oka", KOSHIZUKA_OKA)):
        for t, z in points:
            if t > T[-1] or z > reach:
                continue
            value = np.interp(t, T, Z)
            reached = np.interp(z, np.maximum.accumulate(Z), T)
            print(f"{name:<16}{t:7.3f}{z:8.3f}{value:8.3f}{100 * (value / z - 1):+8.1f} %{t - reached:8.3f}")
    plots = run / "plots"
    plots.mkdir(exist_ok=True)
    plt.plot(T, Z, label="tankfsi")
    plt.plot(*zip(*MARTIN_MOYCE), "o", label="Martin & Moyce 1952")
    plt.plot(*zip(*KOSHIZUKA_OKA), "s", label="Koshizuka & Oka 1996")
    plt.xlabel("T = t sqrt(2g/a)")
    plt.ylabel("Z = z/a")
    plt.legend()
    plt.grid(alpha=0.3)
    plt.savefig(plots / "dam_break_front.png", dpi=120)


if __name__ == "__main__":
    main()
