"""One benchmark run of a tankfsi program under mpirun, with its wall time and
the peak resident memory of its largest rank (shared by the benchmark scripts)."""
import json
import pathlib
import shlex
import shutil
import subprocess
import sys
import time

ROOT = pathlib.Path(__file__).resolve().parents[2]


def measured_run(solver, case, settings, ranks, folder):
    """Runs `mpirun -np ranks solver ROOT/case --output folder --set ...`; returns
    (summary.json as a dict, wall seconds, peak KiB of the largest rank). Exits on failure."""
    command = ["mpirun", "-np", str(ranks), "--oversubscribe", solver, str(ROOT / case), "--output", str(folder)]
    for s in settings:
        command += ["--set", s]
    # RUSAGE_CHILDREN keeps the largest peak of any child so far: measure each run
    # in a fresh interpreter, whose children are this run's processes only.
    measure = ("import resource, subprocess, sys; r = subprocess.run(sys.argv[1:]); "
               "print(resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss, file=sys.stderr); sys.exit(r.returncode)")
    start = time.monotonic()
    result = subprocess.run([sys.executable, "-c", measure] + command, capture_output=True, text=True)
    elapsed = time.monotonic() - start
    if result.returncode != 0:
        # The run folder holds the failed run's last good state (its final
        # snapshot and checkpoint): kept under runs/, since the benchmark's
        # scratch folder goes with it.
        where = "it left no run folder"
        if pathlib.Path(folder).is_dir():
            kept = ROOT / "runs" / f"bench-failed-{pathlib.Path(folder).name}-{time.strftime('%Y%m%d-%H%M%S')}"
            shutil.copytree(folder, kept)
            where = f"its run folder is kept in {kept}"
        sys.exit(f"benchmark run failed: {shlex.join(command)}\n{result.stderr[-3000:]}\n{where}")
    peak_kib = int(result.stderr.strip().splitlines()[-1])
    summary = json.loads((pathlib.Path(folder) / "summary.json").read_text())
    return summary, elapsed, peak_kib
