"""One coupled job (sph_solver : fem_solver) under mpirun, shared by the
validation checks and the stability study: both programs get the same
--set overrides (the handshake compares their settings), each its own run
folder under `folder`."""
import json
import os
import pathlib
import shlex
import subprocess
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]

# Open MPI as root and with more ranks than cores (scripts/common.sh does the same).
MPI_ENVIRONMENT = {
    "OMPI_ALLOW_RUN_AS_ROOT": "1",
    "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
    "OMPI_MCA_rmaps_base_oversubscribe": "1",
}


class CoupledRun:
    """The outcome of one job: exit status, wall seconds, both summaries (None
    when a program wrote none), the tail of its output, and its folders."""

    def __init__(self, folder, status, seconds, output):
        self.folder = pathlib.Path(folder)
        self.status = status
        self.seconds = seconds
        self.output = output
        self.fluid = self._summary("fluid")
        self.structure = self._summary("structure")

    def _summary(self, side):
        path = self.folder / side / "summary.json"
        return json.loads(path.read_text()) if path.exists() else None

    def probe(self, side, name):
        """probes/<name>.csv of one side as a dict of column -> list of floats."""
        path = self.folder / side / "probes" / f"{name}.csv"
        lines = path.read_text().split()
        header = lines[0].split(",")
        rows = [[float(v) for v in line.split(",")] for line in lines[1:]]
        return {h: [r[k] for r in rows] for k, h in enumerate(header)}

    def failure(self):
        """The programs' own error lines (Open MPI's are skipped), or the end of the output."""
        said = [line.strip() for line in self.output.splitlines()
                if "error" in line.lower() and "MPI_ABORT" not in line and "ORTE_ERROR_LOG" not in line]
        return " | ".join(said[:4]) if said else self.output.strip()[-500:]


def report(failures, checked):
    """Prints each failure and the count line the tests' logs end with; the exit status."""
    for f in failures:
        print("FAILED:", f)
    if not failures:
        print(f"{checked} passed, 0 failed")
    return 1 if failures else 0


def derived_case(case, folder, overrides=(), sections=None):
    """A copy of `case` in `folder` with whole sections replaced (`sections`:
    name -> mapping) and KEY=VALUE overrides (dotted keys, YAML values): for
    partners that read the case file and take no --set, and for settings that
    remove keys (both sides must read the same case: the handshake compares
    them). A case that reads input files is refused (its copy would lose
    their relative paths)."""
    import yaml
    config = yaml.safe_load(pathlib.Path(case).read_text())

    def names_a_file(node):
        if isinstance(node, dict):
            return any(str(k).endswith("file") or names_a_file(v) for k, v in node.items())
        return isinstance(node, list) and any(names_a_file(v) for v in node)
    if names_a_file(config) or config.get("excitation", {}).get("type") == "knet":
        raise ValueError(f"{case}: a case that reads input files cannot be copied here")
    config.update(sections or {})
    for item in overrides:
        key, value = item.split("=", 1)
        node = config
        parts = key.split(".")
        for part in parts[:-1]:
            node = node.setdefault(part, {})
        node[parts[-1]] = yaml.safe_load(value)
    folder = pathlib.Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "case.yaml"
    path.write_text(yaml.safe_dump(config, sort_keys=False))
    return path


def run_coupled(case, folder, settings=(), fluid_ranks=1, structure_ranks=1, sph=None, fem=None, timeout=3600,
                launcher=("mpirun",), structure_command=None):
    """structure_command: the structure side's whole command line instead of
    fem_solver's (another partner program, e.g. coupling/examples/prescribed_wall)."""
    folder = pathlib.Path(folder)
    binaries = ROOT / "build" / "bin"
    sph = sph or str(binaries / "sph_solver")
    fem = fem or str(binaries / "fem_solver")
    overrides = []
    for s in settings:
        overrides += ["--set", s]
    command = list(launcher) + ["-np", str(fluid_ranks), sph, str(case), "--output", str(folder / "fluid")] + overrides
    if structure_command is None:
        structure_command = [fem, str(case), "--output", str(folder / "structure")] + overrides
    command += [":", "-np", str(structure_ranks)] + list(structure_command)
    environment = dict(os.environ, **MPI_ENVIRONMENT)
    start = time.monotonic()
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=timeout, env=environment)
        status, output = result.returncode, result.stdout + result.stderr
    except subprocess.TimeoutExpired as e:
        status, output = -1, f"timed out after {timeout} s: {shlex.join(command)}\n{e.stdout or ''}{e.stderr or ''}"
    return CoupledRun(folder, status, time.monotonic() - start, output)
