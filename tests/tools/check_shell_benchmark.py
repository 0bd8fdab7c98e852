#!/usr/bin/python3
"""Shell obstacle-course check: runs fem_solver on a benchmark case and compares
one figure with its published reference.

Usage:
  check_shell_benchmark.py --launcher "mpiexec -n 2" --reference 0.3024 --tolerance 0.02
      (--probe NAME --component K | --frequency MODE) [--magnitude]
      [--divisions 16,16] [--report 4,4 --report 8,8] [--set k=v ...]
      [--same-as OTHER_CASE.yaml --agreement 1e-7] FEM_SOLVER CASE.yaml

The figure is component K of probe NAME's static displacement (summary.json
structure.probes) or the frequency of mode MODE (1-based, modal.modes[].frequency_Hz).
--magnitude compares |figure| (the references are magnitudes). The check is
|figure / reference - 1| <= tolerance at --divisions (the case's own when omitted).
--report runs further meshes and prints their ratios to the reference: a
convergence table for the case README, not part of the verdict.
--same-as runs a second case that models the same problem on the same nodes
another way (a Gmsh file against the generator): every component of every probe
of the two must agree to --agreement relative to the largest of them.
"""
import argparse
import sys
import tempfile

from fluid_run import run_solver, summary


def figure(folder, args):
    s = summary(folder)
    if args.frequency:
        value = s["modal"]["modes"][args.frequency - 1]["frequency_Hz"]
    else:
        value = s["structure"]["probes"][args.probe]["value"][args.component]
    return abs(value) if args.magnitude else value


def probe_values(folder):
    return {name: probe["value"] for name, probe in summary(folder)["structure"]["probes"].items()}


def agreement(args, scratch):
    """Largest difference of the probe values of CASE (its check run) and --same-as, relative to their
    largest magnitude."""
    mine = probe_values(f"{scratch}/check")  # the run the figure came from
    other = probe_values(run_solver(args.launcher, args.solver, args.same_as, f"{scratch}/other", args.set))
    if mine.keys() != other.keys():
        sys.exit(f"FAIL: the two cases have different probes: {sorted(mine)} and {sorted(other)}")
    scale = max(abs(v) for values in other.values() for v in values)
    return max(abs(a - b) for name in mine for a, b in zip(mine[name], other[name])) / scale


def run(args, scratch, divisions, tag):
    settings = list(args.set)
    if divisions:
        settings.append(f"structure.mesh.divisions=[{divisions}]")
    folder = run_solver(args.launcher, args.solver, args.case, f"{scratch}/{tag}", settings)
    return figure(folder, args)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--launcher", required=True)
    parser.add_argument("--reference", type=float, required=True)
    parser.add_argument("--tolerance", type=float, required=True)
    parser.add_argument("--probe")
    parser.add_argument("--component", type=int, default=0)
    parser.add_argument("--frequency", type=int)
    parser.add_argument("--magnitude", action="store_true")
    parser.add_argument("--divisions")
    parser.add_argument("--report", action="append", default=[])
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--same-as")
    parser.add_argument("--agreement", type=float)
    parser.add_argument("solver")
    parser.add_argument("case")
    args = parser.parse_args()
    if (args.probe is None) == (args.frequency is None):
        parser.error("give exactly one of --probe and --frequency")
    if (args.same_as is None) != (args.agreement is None):
        parser.error("--same-as and --agreement go together")
    with tempfile.TemporaryDirectory() as scratch:
        for k, divisions in enumerate(args.report):
            value = run(args, scratch, divisions, f"report{k}")
            print(f"mesh [{divisions}]: {value:.6g}, ratio to reference {value / args.reference:.4f}")
        value = run(args, scratch, args.divisions, "check")
        difference = agreement(args, scratch) if args.same_as else None
    ratio = value / args.reference
    mesh = f"[{args.divisions}]" if args.divisions else "of the case"
    verdict = "PASS" if abs(ratio - 1.0) <= args.tolerance else "FAIL"
    print(f"{verdict}: mesh {mesh}: {value:.6g} against {args.reference:.6g} (ratio {ratio:.4f}, "
          f"tolerance {args.tolerance:.3g})")
    if difference is not None:
        same = difference <= args.agreement
        print(f"{'PASS' if same else 'FAIL'}: probes against {args.same_as}: largest relative difference "
              f"{difference:.3g} (tolerance {args.agreement:.3g})")
        verdict = verdict if same else "FAIL"
    return 0 if verdict == "PASS" else 1


if __name__ == "__main__":
    sys.exit(main())
