#!/usr/bin/python3
"""Runs a tankfsi program on every malformed case file and bad command line and
checks the exact error message, its line, the exit status 2, and that nothing
was written.

Usage: check_bad_inputs.py [--launcher "mpiexec -n 2"] PROGRAM [PROGRAM_ARGS...] -- CASES_DIR

Each CASES_DIR/*.yaml that starts with "# expect: MESSAGE" is one case: {file} in
MESSAGE stands for the case file's path, {dir} for its folder, {here} for the
number of the line marked "# <- here". CASES_DIR/command_line_cases.txt lists
bad command lines as "ARGUMENTS | MESSAGE" against valid_minimal.yaml.
"""
import argparse
import concurrent.futures
import os
import pathlib
import shlex
import subprocess
import sys
import tempfile


def expected_from_file(path: pathlib.Path):
    lines = path.read_text().splitlines()
    if not lines or not lines[0].startswith("# expect: "):
        return None
    message = lines[0][len("# expect: "):]
    here = [i + 1 for i, line in enumerate(lines) if "# <- here" in line]
    if "{here}" in message:
        if len(here) != 1:
            raise SystemExit(f"{path}: needs exactly one '# <- here' marker")
        message = message.replace("{here}", str(here[0]))
    return message


def run_case(command, arguments, expected, label):
    """Runs one bad input; returns the problems found (none: it failed as it must)."""
    with tempfile.TemporaryDirectory() as scratch:
        output = pathlib.Path(scratch) / "run"
        full = command + arguments + ["--output", str(output)]
        result = subprocess.run(full, capture_output=True, text=True, timeout=120)
        problems = []
        if result.returncode != 2:
            problems.append(f"exit status {result.returncode}, expected 2")
        error_lines = [line.split("error: ", 1)[1] for line in result.stderr.splitlines() if "error: " in line]
        if expected not in error_lines:
            problems.append(f"expected message:\n    {expected}\n  got stderr:\n    "
                            + "\n    ".join(result.stderr.splitlines() or ["(empty)"]))
        if output.exists():
            problems.append(f"the run folder {output} was created")
        return problems


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", default="")
    parser.add_argument("program", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    if "--" not in args.program:
        parser.error("missing -- CASES_DIR")
    split = args.program.index("--")
    command = shlex.split(args.launcher) + args.program[:split]
    cases = pathlib.Path(args.program[split + 1]).resolve()

    cases_to_run = []  # (arguments, expected message, label)
    for path in sorted(cases.glob("*.yaml")):
        expected = expected_from_file(path)
        if expected is None:
            continue
        expected = expected.replace("{file}", str(path)).replace("{dir}", str(cases))
        cases_to_run.append(([str(path)], expected, path.name))

    valid = cases / "valid_minimal.yaml"
    for line in (cases / "command_line_cases.txt").read_text().splitlines():
        if not line.strip() or line.startswith("#"):
            continue
        arguments, expected = (part.strip() for part in line.split(" | ", 1))
        substitute = lambda text: text.replace("{file}", str(valid)).replace("{dir}", str(cases))
        cases_to_run.append((shlex.split(substitute(arguments)), substitute(expected), arguments))

    # A bad input ends within a second, most of it the launcher's start-up and
    # teardown, not computing: a few at a time keep the cores busy.
    failures, count = [], len(cases_to_run)
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        outcomes = pool.map(lambda case: run_case(command, *case), cases_to_run)
        for (_, _, label), problems in zip(cases_to_run, outcomes):
            if problems:
                failures.append(f"{label}: " + "\n  ".join(problems))
            print(("FAIL " if problems else "ok   ") + label)

    # Positive control: the same command on a valid case must succeed and write,
    # otherwise "nothing was written" above would prove nothing.
    with tempfile.TemporaryDirectory() as scratch:
        output = pathlib.Path(scratch) / "run"
        result = subprocess.run(command + [str(valid), "--output", str(output)], capture_output=True, text=True,
                                timeout=120)
        control_ok = result.returncode == 0 and (output / "case.resolved.yaml").exists()
        if not control_ok:
            failures.append(f"control: valid_minimal.yaml gave exit {result.returncode} and "
                            f"{'no' if not output.exists() else 'an incomplete'} run folder:\n{result.stderr}")
        print(("ok   " if control_ok else "FAIL ") + "control: valid case writes its run folder")

    print(f"\n{count - len(failures)} passed, {len(failures)} failed")
    for failure in failures:
        print("\n" + failure)
    if count < 20:
        print(f"only {count} bad inputs checked; at least 20 are required")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
