"""Shared helpers of the fluid test drivers: run sph_solver into a fresh folder and
read its probe files and summary."""
import json
import pathlib
import shlex
import subprocess

import numpy as np


def run_solver(launcher, solver, case, folder, settings=(), timeout=1500):
    """Runs `launcher solver case --output folder --set k=v ...`; raises on failure."""
    command = shlex.split(launcher) + [solver, str(case), "--output", str(folder)]
    for setting in settings:
        command += ["--set", setting]
    result = subprocess.run(command, capture_output=True, text=True, timeout=timeout)
    if result.returncode != 0:
        raise SystemExit(f"FAIL: {' '.join(command)} exited {result.returncode}\n{result.stdout}\n{result.stderr}")
    return pathlib.Path(folder)


def probe(folder, name):
    """(header, rows) of probes/<name>.csv."""
    path = pathlib.Path(folder) / "probes" / f"{name}.csv"
    header = path.read_text().splitlines()[0].split(",")
    return header, np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)


def summary(folder):
    return json.loads((pathlib.Path(folder) / "summary.json").read_text())
