#!/usr/bin/python3
"""Projects the wall time of a long coupled run (sph_solver + fem_solver) from
a short one, e.g. the first coupling windows of cases/tank3d_fixed_roof:

    scripts/post/project_run_time.py RUN_FOLDER --end-time 100 --fluid-ranks 64

RUN_FOLDER is the short run's folder: one folder both programs wrote into, or
a folder with one sub-folder per program (RUN/fluid, RUN/structure, as
scripts/post/coupled_run.py lays them out).

Where the figures come from:
  summary.json (both programs finished): the fluid's per-step stages
      (neighbours, predictor, ppe_assemble, ppe_solve, corrector, checks) per
      step, the structure's shell_step per step, both programs' coupling work
      per window, and the rest of each program's wall time (start-up, output).
  run.log (a short run stopped by a time limit or killed: no stage timings):
      the log's time stamps (whole seconds) at the fluid's field outputs
      ("t = ... s, step N") - run the short job with output.field_interval
      equal to the coupling window to get one per window. Per-step time: the
      wall time between the first and the last such line over the steps
      between them or, with one line, from the start of stepping (the last
      start-up message of either program) to it. Start-up: first log line
      to the start of stepping (the case reading and particle filling before
      the first log line are not in it: a few seconds for the paper's tank).
      The structure's step: from the gaps between its own "t = ..." lines (an
      upper bound: whole seconds, and output), or --structure-step-ms.

What is ASSUMED: the fluid's particle-steps per second per rank measured on
the short run's ranks holds on --fluid-ranks ranks (perfect strong scaling;
--efficiency < 1 for less). The structure's step is taken as measured (or
--structure-step-ms); per window the two programs compute at once (parallel
staggered), so a window takes the longer of the two, plus the coupling work.
Not projected: particle snapshots and checkpoints of the long run.
--cpu-share corrects for a machine shared with other work: the fraction of a
core the fluid rank had (CPU time / wall time, e.g. from /usr/bin/time -v).
"""
import argparse
import datetime
import json
import math
import pathlib
import re
import sys

FLUID_STEP_STAGES = ("neighbours", "predictor", "ppe_assemble", "ppe_solve", "corrector", "checks")
LOG_LINE = re.compile(r"^(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ) \[(sph_solver|fem_solver)[^\]]*\] \w+: (.*)$")
TIME_STEP = re.compile(r"^t = ([-+0-9.eE]+) s, step (\d+)")


def folders(run):
    run = pathlib.Path(run)
    return [run] + sorted(p for p in run.iterdir() if p.is_dir() and not p.name.startswith("."))


def summaries(run):
    """program -> its part of summary.json (its results plus 'program': its 'programs' entry)."""
    found = {}
    for folder in folders(run):
        f = folder / "summary.json"
        if f.is_file():
            data = json.loads(f.read_text())
            for program, entry in data.get("programs", {}).items():
                part = {k: v for k, v in data.items() if k != "programs"}
                part["program"] = entry
                found.setdefault(program, part)
    return found


def finished(summary):
    return summary and summary["program"].get("status") == "finished" and "stages" in summary["program"]


def log_lines(run, program):
    """[(datetime, message)] of one program's run.log (rank 0's lines)."""
    lines = []
    for folder in folders(run):
        f = folder / "run.log"
        if not f.is_file():
            continue
        for text in f.read_text().splitlines():
            m = LOG_LINE.match(text)
            if m and m.group(2) == program:
                when = datetime.datetime.strptime(m.group(1), "%Y-%m-%dT%H:%M:%SZ")
                lines.append((when, m.group(3)))
    return sorted(set(lines))


def resolved_case(run):
    for folder in folders(run):
        f = folder / "case.resolved.yaml"
        if f.is_file():
            import yaml
            return yaml.safe_load(f.read_text())
    sys.exit(f"{run}: no case.resolved.yaml")


def ranks_of(run, program):
    for folder in folders(run):
        f = folder / "provenance.json"
        if f.is_file():
            entry = json.loads(f.read_text()).get("programs", {}).get(program)
            if entry and isinstance(entry.get("mpi_ranks"), int):
                return entry["mpi_ranks"]
    return 1


def seconds(stages, name):
    return stages.get(name, {}).get("seconds", 0.0)


def from_summaries(fluid, structure):
    """Measured figures from both programs' summaries."""
    fs, ss = fluid["program"]["stages"], structure["program"]["stages"]
    f, st = fluid["fluid"], structure["structure"]
    fc, sc = f.get("coupling", {}), structure.get("coupling", {})
    if not fc or not sc:
        sys.exit("not a coupled run: the projection needs both programs' coupling figures")
    windows = max(sc.get("windows", 0), 1)
    step_stages = sum(seconds(fs, n) for n in FLUID_STEP_STAGES)
    return {
        "source": "summary.json",
        "particles": f["particles"],
        "fluid_steps": f["steps"],
        "dt_fluid": f["time_step_s"]["mean"],
        "window": f["end_time_s"] / windows,
        "windows": windows,
        "fluid_step_s": step_stages / max(f["steps"], 1),
        "stage_per_step": {n: seconds(fs, n) / max(f["steps"], 1) for n in FLUID_STEP_STAGES},
        "structure_step_s": seconds(ss, "shell_step") / max(st["steps"], 1),
        "dt_structure": st["time_step_s"],
        "work_per_window": max(fc.get("work_s", 0.0), sc.get("work_s", 0.0)) / windows,
        "start_s": max(fluid["program"]["wall_time_s"] - step_stages - fc.get("wait_s", 0.0) - fc.get("work_s", 0.0),
                       structure["program"]["wall_time_s"] - seconds(ss, "shell_step") - sc.get("wait_s", 0.0)
                       - sc.get("work_s", 0.0)),
        "start_note": "wall time less step stages and coupling (start-up and output)",
    }


def from_logs(run):
    """Measured figures from the two run.log files' time stamps."""
    fluid, structure = log_lines(run, "sph_solver"), log_lines(run, "fem_solver")
    if not fluid or not structure:
        sys.exit(f"{run}: no run.log lines of both programs")
    case = resolved_case(run)
    particles = None
    samples = []  # (when, t, step, dt)
    for when, message in fluid:
        m = re.match(r"fluid: (\d+) particles", message)
        if m:
            particles = int(m.group(1))
        m = TIME_STEP.match(message)
        if m:
            dt = re.search(r"dt = ([-+0-9.eE]+) s", message)
            samples.append((when, float(m.group(1)), int(m.group(2)), float(dt.group(1)) if dt else None))
    if particles is None or not samples:
        sys.exit(f"{run}: the fluid's log has no particle count or no 't = ..., step N' line (did the first field "
                 "output come? set output.field_interval to the coupling window for the short run)")
    structure_samples = [(w, float(m.group(1)), int(m.group(2))) for w, msg in structure
                         for m in [TIME_STEP.match(msg)] if m]
    startup_messages = ("coupling:", "the structure starts", "Rayleigh damping", "fluid:", "structure:")
    start_of_stepping = max(w for w, msg in fluid + structure
                            if msg.startswith(startup_messages) and w <= samples[0][0])
    first_line = min(fluid[0][0], structure[0][0])
    if len(samples) >= 2:
        (w0, _, s0, _), (w1, _, s1, _) = samples[0], samples[-1]
    else:
        w0, s0 = start_of_stepping, 0
        w1, s1 = samples[0][0], samples[0][2]
    fluid_step_s = (w1 - w0).total_seconds() / max(s1 - s0, 1)
    gaps = [((b[0] - a[0]).total_seconds(), b[2] - a[2]) for a, b in zip(structure_samples, structure_samples[1:])
            if b[2] > a[2]]
    structure_step_s = min((max(g, 1.0) / n for g, n in gaps), default=None)
    dt_fluid = samples[-1][3] or case["fluid"]["time_step"].get("value") or case["fluid"]["time_step"]["max"]
    return {
        "source": "run.log time stamps (whole seconds)",
        "particles": particles,
        "fluid_steps": s1 - s0,
        "dt_fluid": dt_fluid,
        "window": case["coupling"]["time_window"],
        "windows": int(round(samples[-1][1] / case["coupling"]["time_window"])),
        "fluid_step_s": fluid_step_s,
        "stage_per_step": None,
        "structure_step_s": structure_step_s,
        "structure_step_note": "upper bound from the structure's log gaps (whole seconds, output included)",
        "dt_structure": case["structure"]["time_step"],
        "work_per_window": 0.0,
        "start_s": (start_of_stepping - first_line).total_seconds(),
        "start_note": "first log line to the first step (case reading and filling before it not counted)",
    }


def hms(s):
    s = int(round(s))
    days, s = divmod(s, 86400)
    return (f"{days} d " if days else "") + f"{s // 3600:d}:{s % 3600 // 60:02d}:{s % 60:02d}"


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("run_folder")
    parser.add_argument("--end-time", type=float, required=True, help="simulated seconds of the long run")
    parser.add_argument("--fluid-ranks", type=int, required=True, help="fluid ranks of the long run")
    parser.add_argument("--structure-ranks", type=int, default=None, help="structure ranks of the long run "
                        "(for the core-hours; its step is taken as measured, see --structure-step-ms)")
    parser.add_argument("--measured-fluid-ranks", type=int, default=None,
                        help="fluid ranks of the short run (default: from provenance.json)")
    parser.add_argument("--efficiency", type=float, default=1.0,
                        help="parallel efficiency assumed for the fluid on --fluid-ranks (default 1: perfect)")
    parser.add_argument("--structure-step-ms", type=float, default=None,
                        help="structure step (ms) to use instead of the measured one")
    parser.add_argument("--cpu-share", type=float, default=1.0,
                        help="fraction of a core the short run's fluid rank had (machine shared with other work)")
    parser.add_argument("--from-logs", action="store_true", help="use run.log even if summary.json is complete")
    args = parser.parse_args()

    run = pathlib.Path(args.run_folder)
    if not run.is_dir():
        sys.exit(f"{run}: not a folder")
    s = summaries(run)
    if not args.from_logs and finished(s.get("sph_solver")) and finished(s.get("fem_solver")):
        m = from_summaries(s["sph_solver"], s["fem_solver"])
    else:
        m = from_logs(run)
    measured_ranks = args.measured_fluid_ranks or ranks_of(run, "sph_solver")
    share = args.cpu_share
    fluid_step_s = m["fluid_step_s"] * share
    rate_per_rank = m["particles"] / fluid_step_s / measured_ranks
    structure_step_s = (args.structure_step_ms / 1000.0 if args.structure_step_ms is not None
                        else m["structure_step_s"])
    if structure_step_s is None:
        sys.exit("the structure's step could not be measured from the logs: give --structure-step-ms")

    print(f"measured in {run} ({m['source']}): {m['particles']} particles on {measured_ranks} fluid rank(s), "
          f"{m['fluid_steps']} fluid steps of {m['dt_fluid']:g} s timed, coupling window {m['window']:g} s"
          + (f"; fluid times x {share:g} (--cpu-share)" if share != 1.0 else ""))
    detail = ""
    if m["stage_per_step"]:
        detail = " (" + ", ".join(f"{n} {v * share:.3f}" for n, v in m["stage_per_step"].items()) + ")"
    print(f"  fluid step          {fluid_step_s:10.3f} s = {rate_per_rank:.3g} particle-steps/s per rank{detail}")
    note = "" if args.structure_step_ms is not None else f" ({m.get('structure_step_note', 'shell_step')})"
    print(f"  structure step      {structure_step_s * 1000:10.1f} ms{note}")
    print(f"  start-up            {m['start_s']:10.1f} s ({m['start_note']})")

    n = args.fluid_ranks
    fluid_step_n = m["particles"] / (rate_per_rank * n * args.efficiency)
    fluid_window = m["window"] / m["dt_fluid"] * fluid_step_n
    structure_window = m["window"] / m["dt_structure"] * structure_step_s
    window_n = max(fluid_window, structure_window) + m["work_per_window"]
    windows_n = math.ceil(args.end_time / m["window"] - 1e-9)
    total = m["start_s"] + windows_n * window_n
    cores = n + (args.structure_ranks or 0)
    print(f"projected for {args.end_time:g} s on {n} fluid ranks"
          + (f" + {args.structure_ranks} structure ranks" if args.structure_ranks else "")
          + f": ASSUMED that {rate_per_rank:.3g} particle-steps/s per rank holds at "
          f"{m['particles'] / n:.0f} particles per rank" + (f" times {args.efficiency:g}" if args.efficiency != 1 else ""))
    print(f"  per window: fluid {fluid_window:.3f} s, structure {structure_window:.3f} s, coupling work "
          f"{m['work_per_window']:.3f} s -> {window_n:.3f} s")
    print(f"  {windows_n} windows {hms(windows_n * window_n)}, with start-up {hms(total)} = {total / 3600:.1f} h"
          + (f", {total * cores / 3600:.3g} core-hours" if args.structure_ranks else "")
          + "; not included: snapshots and checkpoints")


if __name__ == "__main__":
    main()
