#!/usr/bin/python3
"""Restart check: a job stopped by a signal and restarted from its checkpoint
gives the probe histories and field series of the job run straight through.

Usage:
  check_restart.py --ranks 2 [--restart-ranks 1] [--signal TERM|USR1] [--target procs|launcher]
                   [--at 0.4] [--tolerance 0] [--mismatched-probe NAME.csv] -- mpiexec -n NP PROGRAM CASE --output OUTPUT RESTART ...

In the job's command line NP is replaced by the rank count (--ranks, or
--restart-ranks for the restart), OUTPUT by the run folder, and RESTART by
nothing (the straight and the stopped runs) or by --restart (the restart); an
MPMD line (PROG_A ... : PROG_B ...) names them in each part.

1. The straight run; its wall time W.
2. The same job into another folder, sent the signal at `at` x W (or, with
   --kill-while-writing, SIGKILLed while it writes a checkpoint): to every
   process the launcher started (`procs`, as a batch scheduler does), or to the
   launcher itself (`launcher`, which forwards SIGUSR1 to them). It must stop
   with a non-zero status, say "stopped by SIG...", and leave a checkpoint.
3. The restart into that folder must finish (with --mismatched-probe, a restart
   with another header in that probe file must first stop, on every rank, and
   the file is put back).
4. Every probe CSV must equal the straight run's: the same rows (times), and
   values bit for bit (--tolerance 0) or within the tolerance relative to each
   largest magnitude of the file's columns of the same unit; columns of wall-clock time are left out, and
   with a tolerance the PPE's iteration counts (hypre's hierarchy depends on
   the partition) and times of adaptive steps compare to it too. The
   XDMF series must list the same snapshot times, none twice.
"""
import argparse
import pathlib
import re
import signal
import subprocess
import sys
import tempfile
import time

import numpy as np

TIMING_COLUMNS = re.compile(r"(wait|work|wall)_?s$|seconds")


def unit_of(column):
    """The unit a column name ends with (force_x_N: N); the name itself when it has none."""
    return column.rsplit("_", 1)[-1] if "_" in column else column


def command_for(template, ranks, output, restart):
    words = []
    for word in template:
        if word == "NP":
            words.append(str(ranks))
        elif word == "OUTPUT":
            words.append(str(output))
        elif word == "RESTART":
            if restart:
                words.append("--restart")
        else:
            words.append(word)
    return words


def descendants(pid):
    found = []
    result = subprocess.run(["pgrep", "-P", str(pid)], capture_output=True, text=True)
    for child in result.stdout.split():
        found.append(int(child))
        found += descendants(int(child))
    return found


def csv_table(path):
    lines = path.read_text().splitlines()
    header = lines[0].split(",")
    rows = [line.split(",") for line in lines[1:] if line]
    return header, rows


def compare_probes(straight, restarted, tolerance):
    worst = 0.0
    files = sorted((straight / "probes").glob("*.csv"))
    if not files:
        raise SystemExit(f"FAIL: no probe files in {straight}")
    for path in files:
        other = restarted / "probes" / path.name
        if not other.exists():
            raise SystemExit(f"FAIL: the restarted run has no {path.name}")
        header, a = csv_table(path)
        header_b, b = csv_table(other)
        if header != header_b:
            raise SystemExit(f"FAIL: {path.name}: headers differ")
        times_a = [row[0] for row in a]
        times_b = [row[0] for row in b]
        # Adaptive steps make times of round-off difference on other rank counts.
        close = (tolerance > 0.0 and len(a) == len(b) and
                 np.allclose(np.array(times_a, float), np.array(times_b, float), rtol=tolerance, atol=0.0))
        if times_a != times_b and not close:
            extra = sorted(set(times_b) - set(times_a))[:3]
            missing = sorted(set(times_a) - set(times_b))[:3]
            duplicates = len(times_b) - len(set(times_b))
            raise SystemExit(f"FAIL: {path.name}: {len(a)} rows straight, {len(b)} restarted "
                             f"(missing {missing}, extra {extra}, {duplicates} times twice)")
        # Columns of one unit share a scale (a force component that is zero is
        # round-off, compared with the forces that are not).
        group_scale = {}
        if tolerance > 0.0:
            for k, column in enumerate(header[1:], start=1):
                key = unit_of(column)
                group_scale[key] = max(group_scale.get(key, 0.0), max(abs(float(r[k])) for r in a))
        for k, column in enumerate(header[1:], start=1):
            if TIMING_COLUMNS.search(column):
                continue
            # Another partition gives hypre another hierarchy: counts differ by one or two.
            if tolerance > 0.0 and column == "ppe_iterations":
                continue
            if tolerance == 0.0:
                for row_a, row_b in zip(a, b):
                    if row_a[k] != row_b[k]:
                        raise SystemExit(f"FAIL: {path.name} {column} at t = {row_a[0]}: {row_a[k]} straight, "
                                         f"{row_b[k]} restarted (bit for bit expected)")
                continue
            x = np.array([float(r[k]) for r in a])
            y = np.array([float(r[k]) for r in b])
            scale = max(group_scale[unit_of(column)], 1e-300)
            difference = np.abs(x - y).max() / scale
            worst = max(worst, difference)
            if difference > tolerance:
                raise SystemExit(f"FAIL: {path.name} {column}: differs by {difference:.3g} of its largest "
                                 f"magnitude (tolerance {tolerance})")
    return len(files), worst


def series_times(folder):
    found = {}
    for path in sorted(folder.glob("*.xdmf")):
        found[path.name] = re.findall(r'<Time Value="([^"]+)"', path.read_text())
    return found


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--ranks", type=int, default=1)
    parser.add_argument("--restart-ranks", type=int)
    parser.add_argument("--signal", choices=["TERM", "USR1"], default="TERM")
    parser.add_argument("--target", choices=["procs", "launcher"], default="procs")
    parser.add_argument("--at", type=float, default=0.45)
    parser.add_argument("--tolerance", type=float, default=0.0)
    parser.add_argument("--timeout", type=float, default=900)
    parser.add_argument("--kill-while-writing", action="store_true",
                        help="instead of the signal: SIGKILL every process of the job as soon as a checkpoint "
                             "is being written (a .partial file appears); the restart must take the last complete one")
    parser.add_argument("--fail-with", action="append", default=[],
                        help="instead of the signal: run the job with these extra arguments, which make it fail; "
                             "it must leave its last good state as a checkpoint, from which the job without them "
                             "continues")
    parser.add_argument("--refused-ranks", type=int,
                        help="first try a restart on this many ranks: it must be refused (exit 2, message "
                             "naming the rank counts) and change no file of the run")
    parser.add_argument("--mismatched-probe", metavar="NAME.csv",
                        help="first try a restart with another header in this probe file (as a run folder of "
                             "an older version has): every rank must stop with 'cannot continue probe file' "
                             "(a hang is a failure), then the file is put back")
    parser.add_argument("job", nargs=argparse.REMAINDER)
    args = parser.parse_args()
    job = args.job[1:] if args.job[:1] == ["--"] else args.job
    restart_ranks = args.restart_ranks or args.ranks
    with tempfile.TemporaryDirectory() as scratch:
        straight = pathlib.Path(scratch) / "straight"
        stopped = pathlib.Path(scratch) / "stopped"
        start = time.monotonic()
        result = subprocess.run(command_for(job, args.ranks, straight, False), capture_output=True, text=True,
                                timeout=args.timeout)
        wall = time.monotonic() - start
        if result.returncode != 0:
            raise SystemExit(f"FAIL: the straight run exited {result.returncode}\n{result.stdout}\n{result.stderr}")

        if args.fail_with:
            return finish_after_failure(args, job, straight, stopped, restart_ranks)
        process = subprocess.Popen(command_for(job, args.ranks, stopped, False), stdout=subprocess.PIPE,
                                   stderr=subprocess.STDOUT, text=True)
        if args.kill_while_writing:
            kill_while_writing(process, stopped / "checkpoints", args.timeout)
            output, _ = process.communicate(timeout=args.timeout)
            return finish_after_kill(args, job, straight, stopped, restart_ranks)
        time.sleep(args.at * wall)
        number = getattr(signal, "SIG" + args.signal)
        targets = [process.pid] if args.target == "launcher" else descendants(process.pid)
        for pid in targets:
            try:
                os_kill(pid, number)
            except ProcessLookupError:
                pass
        output, _ = process.communicate(timeout=args.timeout)
        if process.returncode == 0:
            raise SystemExit(f"FAIL: the job signalled at {args.at * wall:.1f} s of {wall:.1f} s finished "
                             f"normally (signal too late?)\n{output}")
        if f"stopped by SIG{args.signal}" not in output:
            raise SystemExit(f"FAIL: the signalled job exited {process.returncode} without "
                             f"'stopped by SIG{args.signal}'\n{output}")
        checkpoints = sorted((stopped / "checkpoints").glob("*.h5"))
        if not checkpoints or list((stopped / "checkpoints").glob("*.partial")):
            raise SystemExit(f"FAIL: checkpoints after the stop: {[p.name for p in checkpoints]}")
        stop_line = next(line for line in output.splitlines() if "stopped by" in line)

        if args.refused_ranks:
            before = {p: p.read_bytes() for p in stopped.rglob("*") if p.is_file() and p.name != "run.log"}
            result = subprocess.run(command_for(job, args.refused_ranks, stopped, True), capture_output=True,
                                    text=True, timeout=args.timeout)
            after = {p: p.read_bytes() for p in stopped.rglob("*") if p.is_file() and p.name != "run.log"}
            expected = f"continues only on as many, not {args.refused_ranks}"
            if result.returncode == 0 or expected not in result.stderr + result.stdout:
                raise SystemExit(f"FAIL: a restart on {args.refused_ranks} ranks exited {result.returncode} "
                                 f"without '{expected}'\n{result.stdout}\n{result.stderr}")
            if before != after:
                changed = sorted(str(p.relative_to(stopped)) for p in set(before) | set(after)
                                 if before.get(p) != after.get(p))
                raise SystemExit(f"FAIL: the refused restart changed {changed}")

        if args.mismatched_probe:
            refuse_mismatched_probe(job, restart_ranks, stopped, args.mismatched_probe, min(args.timeout, 120.0))

        result = subprocess.run(command_for(job, restart_ranks, stopped, True), capture_output=True, text=True,
                                timeout=args.timeout)
        if result.returncode != 0:
            raise SystemExit(f"FAIL: the restart exited {result.returncode}\n{result.stdout}\n{result.stderr}")

        try:
            files, worst = compare_probes(straight, stopped, args.tolerance)
        except SystemExit as failure:
            raise SystemExit(f"{failure} [after: {stop_line.strip()}]")
        a, b = series_times(straight), series_times(stopped)
        same_series = a == b or (args.tolerance > 0.0 and a.keys() == b.keys() and all(
            len(a[k]) == len(b[k]) and np.allclose(np.array(a[k], float), np.array(b[k], float), rtol=args.tolerance)
            for k in a))
        if not same_series or any(len(set(t)) != len(t) for t in b.values()):
            raise SystemExit(f"FAIL: field series differ: straight {a}, restarted {b}")
        agreement = "bit for bit" if args.tolerance == 0.0 else f"to {worst:.3g} (tolerance {args.tolerance})"
        print(f"PASS: {stop_line.strip()}; restarted on {restart_ranks} rank(s): {files} probe files agree "
              f"{agreement}; {sum(len(t) for t in a.values())} snapshots in {len(a)} series, as straight")
    return 0


def refuse_mismatched_probe(job, ranks, stopped, name, timeout):
    """A restart whose probe file `name` has another header must stop on every
    rank with the file's name in the message (one rank alone failing would leave
    the others waiting forever); the file is put back afterwards."""
    path = stopped / "probes" / name
    original = path.read_bytes()
    header, _, rest = original.partition(b"\n")
    path.write_bytes(header + b",column_of_another_version\n" + rest)
    try:
        result = subprocess.run(command_for(job, ranks, stopped, True), capture_output=True, text=True,
                                timeout=timeout)
    except subprocess.TimeoutExpired:
        raise SystemExit(f"FAIL: a restart with another header in {name} did not stop within {timeout:.0f} s (hang)")
    finally:
        path.write_bytes(original)
    expected = f"cannot continue probe file '{path}'"
    if result.returncode == 0 or expected not in result.stderr + result.stdout:
        raise SystemExit(f"FAIL: a restart with another header in {name} exited {result.returncode} without "
                         f"\"{expected}\"\n{result.stdout}\n{result.stderr}")


def kill_while_writing(process, folder, timeout):
    """SIGKILLs the job's processes the moment a checkpoint is being written
    (after at least one complete one, so that there is one to restart from)."""
    deadline = time.monotonic() + timeout
    targets = []
    while time.monotonic() < deadline and process.poll() is None:
        try:
            names = [entry.name for entry in os_scandir(folder)]
        except FileNotFoundError:
            names = []
        if not targets:
            if any(n.endswith(".h5") for n in names):
                targets = descendants(process.pid)  # found once: the kill must not wait for pgrep
            continue
        if any(n.endswith(".partial") for n in names):
            for pid in targets:
                try:
                    os_kill(pid, signal.SIGKILL)
                except ProcessLookupError:
                    pass
            return
        time.sleep(0.0002)
    raise SystemExit("FAIL: no checkpoint was caught being written (the job ended first)")


def finish_after_kill(args, job, straight, stopped, restart_ranks):
    partial = sorted(p.name for p in (stopped / "checkpoints").glob("*.partial"))
    complete = sorted(p.name for p in (stopped / "checkpoints").glob("*.h5"))
    if not partial:
        raise SystemExit(f"FAIL: killed while writing, yet no .partial file is left (checkpoints {complete})")
    result = subprocess.run(command_for(job, restart_ranks, stopped, True), capture_output=True, text=True,
                            timeout=args.timeout)
    if result.returncode != 0:
        raise SystemExit(f"FAIL: the restart after the kill exited {result.returncode}\n{result.stdout}\n{result.stderr}")
    restart_line = next((line for line in result.stdout.splitlines() if "restart from" in line), "")
    files, worst = compare_probes(straight, stopped, args.tolerance)
    a, b = series_times(straight), series_times(stopped)
    if a != b:
        raise SystemExit(f"FAIL: field series differ: straight {a}, restarted {b}")
    print(f"PASS: killed while writing {partial[0]} (complete: {', '.join(complete)}); "
          f"{restart_line.strip()}; {files} probe files and {sum(len(t) for t in a.values())} snapshots agree "
          f"{'bit for bit' if args.tolerance == 0.0 else f'to {worst:.3g}'} with the straight run")
    return 0


def finish_after_failure(args, job, straight, stopped, restart_ranks):
    failing = command_for(job, args.ranks, stopped, False)
    # The extra arguments go to the first program of the line (before any ':').
    cut = failing.index(":") if ":" in failing else len(failing)
    failing = failing[:cut] + args.fail_with + failing[cut:]
    result = subprocess.run(failing, capture_output=True, text=True, timeout=args.timeout)
    text = result.stdout + result.stderr
    if result.returncode == 0 or "the last good state" not in text or "and checkpoint" not in text:
        raise SystemExit(f"FAIL: the failing run exited {result.returncode} without naming its last good state's "
                         f"checkpoint\n{text}")
    message = next(line for line in text.splitlines() if "the last good state" in line)
    result = subprocess.run(command_for(job, restart_ranks, stopped, True), capture_output=True, text=True,
                            timeout=args.timeout)
    if result.returncode != 0:
        raise SystemExit(f"FAIL: the restart after the failure exited {result.returncode}\n{result.stdout}\n"
                         f"{result.stderr}")
    files, worst = compare_probes(straight, stopped, args.tolerance)
    a, b = series_times(straight), series_times(stopped)
    # The failed run's final snapshot (the last good state, just after it) stays in the series only until the
    # restart drops what follows the checkpoint: the series must then be the straight run's.
    if a != b:
        raise SystemExit(f"FAIL: field series differ: straight {a}, restarted {b}")
    print(f"PASS: {message.strip()[:400]}; the restart from it: {files} probe files and "
          f"{sum(len(t) for t in a.values())} snapshots agree bit for bit with the straight run")
    return 0


def os_scandir(folder):
    import os
    return os.scandir(folder)


def os_kill(pid, number):
    import os
    os.kill(pid, number)


if __name__ == "__main__":
    sys.exit(main())
