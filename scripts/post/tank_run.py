"""Reads a tank run folder for the post-processing: the resolved case, each
program's summary, the probe records, the ground acceleration and the field
snapshots (HDF5), whichever of them the run has.

Layouts (README, "Run folders"):
  RUN/fluid/ and RUN/structure/   a coupled job with a folder per program (coupled_run.py)
  RUN/ alone                      one program, or both programs sharing the folder
A missing part is None, never an error: a fluid-only run has no structure,
a killed run no summary.
"""
import json
import pathlib
import subprocess
import tempfile

import h5py
import numpy as np
import yaml

ROOT = pathlib.Path(__file__).resolve().parents[2]
GROUND_FILE = "ground_acceleration.csv"
XDMF_CELL_NODES = {4: 3, 5: 4}  # XDMF mixed topology: 4 triangle, 5 quadrilateral


def read_csv(path):
    """A probe CSV as a dict of column -> array (None when absent or empty)."""
    path = pathlib.Path(path)
    if not path.is_file():
        return None
    data = np.genfromtxt(path, delimiter=",", names=True)
    if data.size == 0:
        return None
    return {name: np.atleast_1d(data[name]).astype(float) for name in data.dtype.names}


def _read_json(path):
    return json.loads(path.read_text()) if path.is_file() else None


class Snapshot:
    """One HDF5 snapshot group: time, positions and fields, cells if a mesh."""

    def __init__(self, path, group, time_s):
        self.path, self.group, self.time_s = path, group, time_s

    def read(self, *names):
        """Datasets under the group (position, fields/pressure, node_fields/displacement, ...)."""
        with h5py.File(self.path, "r") as f:
            return [f[f"{self.group}/{name}"][()] if f"{self.group}/{name}" in f else None for name in names]

    def cells(self):
        """Element node lists of a mesh snapshot (triangles and quadrilaterals),
        from the topology the XDMF grid names (later steps share the first's)."""
        with h5py.File(self.path, "r") as f:
            dataset = None
            grid = f[self.group].attrs.get("xdmf_grid")
            if grid is not None:
                grid = json.loads(grid.decode() if isinstance(grid, bytes) else grid)
                dataset = grid.get("topology", {}).get("connectivity", {}).get("dataset")
            if dataset is None or dataset not in f:
                candidates = [g for g in sorted(f) if g <= self.group and f"{g}/topology/connectivity" in f]
                if not candidates:
                    return []
                dataset = f"{candidates[-1]}/topology/connectivity"
            flat = f[dataset][()]
        cells, k = [], 0
        while k < len(flat):
            count = XDMF_CELL_NODES.get(int(flat[k]))
            if count is None:
                raise ValueError(f"{self.path}: XDMF cell type {flat[k]} is not a triangle or quadrilateral")
            cells.append(flat[k + 1:k + 1 + count])
            k += 1 + count
        return cells


def snapshots(path):
    """The snapshots of an HDF5 series file in time order ([] when absent)."""
    path = pathlib.Path(path)
    if not path.is_file():
        return []
    with h5py.File(path, "r") as f:
        found = [Snapshot(path, name, float(f[name].attrs.get("time", np.nan))) for name in sorted(f)
                 if name.startswith("step_")]
    return sorted(found, key=lambda s: s.time_s)


class TankRun:
    """What one run folder holds. `fluid` and `structure` are the folders of
    each side (None when the run has no such side)."""

    def __init__(self, folder):
        self.folder = pathlib.Path(folder)
        if not self.folder.is_dir():
            raise FileNotFoundError(f"{self.folder}: no such run folder")
        self.fluid = self._side("fluid", "sph_solver", "fluid.h5")
        self.structure = self._side("structure", "fem_solver", "structure.h5")
        own = self.folder / "summary.json"
        # The combined summary must not replace a program's own summary.json.
        self.own_summary_here = own.is_file() and self.folder in (self.fluid, self.structure)
        self.case = self._case()
        # Each program's summary.json: its own section ("fluid" or
        # "structure"), "programs" (timings), and fem_solver's "coupling" and "modal".
        fluid_file = (_read_json(self.fluid / "summary.json") if self.fluid else None) or {}
        structure_file = (_read_json(self.structure / "summary.json") if self.structure else None) or {}
        self.fluid_summary = fluid_file.get("fluid")
        self.structure_summary = structure_file.get("structure")
        self.structure_coupling = structure_file.get("coupling")
        self.modal = structure_file.get("modal")
        self.programs = {}
        for summary in (fluid_file, structure_file):
            self.programs.update(summary.get("programs", {}))
        self.provenance = {}
        for side in (self.fluid, self.structure):
            provenance = _read_json(side / "provenance.json") if side else None
            self.provenance.update((provenance or {}).get("programs", {}))

    def _side(self, name, program, field_file):
        candidate = self.folder / name
        if candidate.is_dir():
            return candidate
        if (self.folder / ".claims" / program).exists() or (self.folder / field_file).is_file():
            return self.folder
        return None

    def _case(self):
        for side in (self.fluid, self.structure):
            if side and (side / "case.resolved.yaml").is_file():
                return yaml.safe_load((side / "case.resolved.yaml").read_text())
        return None

    def case_value(self, dotted, default=None):
        """A value of the resolved case by its dotted key, or `default`."""
        node = self.case
        for part in dotted.split("."):
            if not isinstance(node, dict) or part not in node:
                return default
            node = node[part]
        return node

    def probes(self, section, quantity):
        """(name, position, record) of each probe of `section` (fluid or
        structure) measuring `quantity` whose record has samples."""
        side = self.fluid if section == "fluid" else self.structure
        found = []
        for probe in self.case_value(f"{section}.probes", []) or []:
            if probe.get("quantity") != quantity or side is None:
                continue
            record = read_csv(side / "probes" / f"{probe['name']}.csv")
            if record is not None and len(record["time_s"]) > 1:
                found.append((probe["name"], np.asarray(probe["position"], dtype=float), record,
                              probe.get("direction")))
        return found

    def history(self, section, name):
        """probes/<name>.csv of a side (fluid.csv, structure.csv, coupling.csv), or None."""
        side = self.fluid if section == "fluid" else self.structure
        return read_csv(side / "probes" / f"{name}.csv") if side else None

    def ground_acceleration(self, tankfsi_case=None):
        """(record, where it came from): the run's probes/ground_acceleration.csv,
        or else the motion the case applies, written by `tankfsi_case --prepare`
        into RUN/ground_acceleration.csv; (None, why) when neither works."""
        for place in (self.fluid, self.structure, self.folder):
            if place is None:
                continue
            for path in (place / "probes" / GROUND_FILE, place / GROUND_FILE):
                record = read_csv(path)
                if record is not None:
                    where = str(path.relative_to(self.folder))
                    if path == self.folder / GROUND_FILE and self.folder not in (self.fluid, self.structure):
                        where += " (written by tankfsi_case --prepare from the resolved case for an earlier report)"
                    return record, where
        case_file = next((side / "case.resolved.yaml" for side in (self.fluid, self.structure)
                          if side and (side / "case.resolved.yaml").is_file()), None)
        if case_file is None:
            return None, "the run folder has neither the ground acceleration nor a resolved case"
        program = pathlib.Path(tankfsi_case) if tankfsi_case else ROOT / "build" / "bin" / "tankfsi_case"
        if not program.is_file():
            return None, f"the run folder has no {GROUND_FILE} and {program} (which writes it) is not built"
        with tempfile.TemporaryDirectory() as scratch:
            output = pathlib.Path(scratch) / "prepared"
            result = subprocess.run([str(program), str(case_file), "--prepare", "--output", str(output)],
                                    capture_output=True, text=True)
            record = read_csv(output / "probes" / GROUND_FILE)
            if result.returncode != 0 or record is None:
                said = (result.stderr or result.stdout).strip().splitlines()
                why = said[-1] if said else f"exit status {result.returncode}"
                return None, f"tankfsi_case --prepare failed on {case_file.name}: {why}"
            target = self.folder / GROUND_FILE
            target.write_bytes((output / "probes" / GROUND_FILE).read_bytes())
        return record, (f"{GROUND_FILE} (not in the run folder: written by tankfsi_case --prepare "
                        f"from {case_file.relative_to(self.folder)})")

    def last_time_s(self):
        """The latest time any probe history reached (a stopped run's end), or None."""
        ends = [h["time_s"][-1] for h in (self.history("fluid", "fluid"), self.history("structure", "structure")) if h]
        return float(max(ends)) if ends else None

    def log_errors(self):
        """The error lines of the run logs (a failed run says why there)."""
        lines = []
        for side in dict.fromkeys((self.fluid, self.structure)):
            log = side / "run.log" if side else None
            if log and log.is_file():
                lines += [line.strip() for line in log.read_text(errors="replace").splitlines() if "] error:" in line]
        return lines

    def fluid_snapshots(self):
        return snapshots(self.fluid / "fluid.h5") if self.fluid else []

    def wall_snapshots(self):
        return snapshots(self.fluid / "walls.h5") if self.fluid else []

    def structure_snapshots(self):
        return snapshots(self.structure / "structure.h5") if self.structure else []

    def relative(self, path):
        return str(pathlib.Path(path).relative_to(self.folder))
