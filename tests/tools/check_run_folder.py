#!/usr/bin/python3
"""End-to-end check of a run folder written by `tankfsi_case --prepare`.

Usage: check_run_folder.py [--launcher "mpiexec -n 2"] --ranks N TANKFSI_CASE CASE.yaml

Checks: the folder holds case.resolved.yaml, provenance.json, run.log,
summary.json and probes/ground_acceleration.csv; the resolved case is itself a
valid case that resolves to the same text (a fixed point); provenance names the
rank count and the command line; a second run into the same folder is refused
with exit status 2 and leaves every file as it was; --help names every key of
the resolved case; -log_view reaches PETSc and shows the program's stages.
"""
import argparse
import hashlib
import json
import pathlib
import shlex
import subprocess
import sys
import tempfile

import yaml


def run(command, **kwargs):
    return subprocess.run(command, capture_output=True, text=True, timeout=120, **kwargs)


def flatten(node, prefix=""):
    """Key paths of a resolved case; record lists contribute NAME[].FIELD."""
    keys = []
    for key, value in node.items():
        path = f"{prefix}{key}"
        if isinstance(value, dict):
            keys += flatten(value, path + ".")
        elif isinstance(value, list) and value and isinstance(value[0], dict):
            keys.append(path)
            for record in value:
                keys += [k for k in flatten(record, path + "[].") if k not in keys]
        else:
            keys.append(path)
    return keys


def digest(folder):
    return {p.relative_to(folder).as_posix(): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted(folder.rglob("*")) if p.is_file()}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="")
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("program")
    parser.add_argument("case")
    args = parser.parse_args()
    command = shlex.split(args.launcher) + [args.program]
    failures = []

    def check(condition, message):
        print(("ok   " if condition else "FAIL ") + message)
        if not condition:
            failures.append(message)

    with tempfile.TemporaryDirectory() as scratch:
        folder = pathlib.Path(scratch) / "run"
        first = run(command + [args.case, "--prepare", "--output", str(folder), "-log_view"])
        check(first.returncode == 0, f"first run exits 0 (got {first.returncode}: {first.stderr.strip()})")
        stages = first.stdout.split("Summary of Stages:")[-1].split("\n\n")[0]
        check("ground_motion" in stages, "-log_view lists the program's stage ground_motion")
        for name in ["case.resolved.yaml", "provenance.json", "run.log", "summary.json",
                     "probes/ground_acceleration.csv"]:
            check((folder / name).is_file(), f"{name} written")
        if failures:
            return 1

        resolved = folder / "case.resolved.yaml"
        again = run([args.program, str(resolved)])
        check(again.returncode == 0, "the resolved case is itself a valid case")
        body = lambda text: "\n".join(l for l in text.splitlines() if not l.startswith("#"))
        check(body(again.stdout).strip() == body(resolved.read_text()).strip(),
              "resolving the resolved case changes nothing")

        provenance = json.loads((folder / "provenance.json").read_text())
        entry = provenance["programs"]["tankfsi_case"]
        check(entry["mpi_ranks"] == args.ranks, f"provenance records {args.ranks} rank(s)")
        check("--prepare" in entry["command_line"], "provenance records the command line")
        check(len(provenance["git_commit"]) >= 7, "provenance records the git commit")
        summary = json.loads((folder / "summary.json").read_text())
        check(summary["programs"]["tankfsi_case"]["status"] == "finished", "summary records the finished program")
        header = (folder / "probes/ground_acceleration.csv").read_text().splitlines()[0]
        check(header == "time_s,ax_m_s2,ay_m_s2,az_m_s2", "probe header names columns with units")
        check("run folder" in (folder / "run.log").read_text(), "run.log holds the program's log")

        before = digest(folder)
        second = run(command + [args.case, "--prepare", "--output", str(folder)])
        check(second.returncode == 2, f"second run into the same folder exits 2 (got {second.returncode})")
        check("already holds a run of tankfsi_case" in second.stderr, "and says why")
        check(digest(folder) == before, "and changes no file")

        help_text = run([args.program, "--help"]).stdout
        keys = flatten(yaml.safe_load(resolved.read_text()))
        missing = [k for k in keys if k not in help_text]
        check(not missing and len(keys) > 10, f"--help names all {len(keys)} resolved keys {missing[:5]}")

    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
