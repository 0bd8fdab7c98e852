#!/usr/bin/python3
"""Runs one MPI job — two partner programs (MPMD) or a single program — and
checks how it ends.

Usage: check_coupled_job.py --mpiexec MPIEXEC [--expect-failure PATTERN]...
                            [--within SECONDS] -- FIRST ARGS... : SECOND ARGS...

The part after "--" is the mpiexec command line ("-np 2 prog a : -np 1 prog b",
or "-np 2 prog a").
Without --expect-failure the job must exit 0. With it, the job must exit
non-zero within --within seconds (default 60) and its output must contain every
PATTERN: a partner that fails or dies takes the job down with its message,
never a hang and never exit 0.
"""
import argparse
import os
import shutil
import subprocess
import sys
import time


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mpiexec", required=True)
    parser.add_argument("--expect-failure", action="append", default=[])
    parser.add_argument("--within", type=float, default=60.0)
    parser.add_argument("--expect-success-output", action="append", default=[],
                        help="text the output of a successful job must contain")
    parser.add_argument("--remove-first", action="append", default=[],
                        help="a run folder of this test's own, removed before the job (a rerun starts afresh)")
    parser.add_argument("--expect-absent", action="append", default=[],
                        help="a path the job must not have created (bad input writes nothing)")
    parser.add_argument("job", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    job = args.job[1:] if args.job and args.job[0] == "--" else args.job
    for folder in args.remove_first:
        shutil.rmtree(folder, ignore_errors=True)
    command = [args.mpiexec, "--oversubscribe"] + job
    print("running:", " ".join(command), flush=True)
    start = time.monotonic()
    try:
        result = subprocess.run(command, capture_output=True, text=True, timeout=max(args.within, 30) + 60)
    except subprocess.TimeoutExpired:
        print(f"FAILED: the job did not end within {max(args.within, 30) + 60:.0f} s (a hang)")
        return 1
    elapsed = time.monotonic() - start
    output = result.stdout + result.stderr
    print(output)
    print(f"exit status {result.returncode} after {elapsed:.1f} s")
    problems = []
    if args.expect_failure:
        if result.returncode == 0:
            problems.append("the job exited 0 although a partner failed")
        if elapsed > args.within:
            problems.append(f"the job took {elapsed:.1f} s to end (limit {args.within} s)")
        for pattern in args.expect_failure:
            if pattern not in output:
                problems.append(f"the output does not say {pattern!r}")
    elif result.returncode != 0:
        problems.append(f"the job failed with exit status {result.returncode}")
    for path in args.expect_absent:
        if os.path.exists(path):
            problems.append(f"{path} was written although the input was bad")
    for pattern in args.expect_success_output:
        if pattern not in output:
            problems.append(f"the output does not say {pattern!r}")
    for p in problems:
        print("FAILED:", p)
    if not problems:
        print("1 passed, 0 failed")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
