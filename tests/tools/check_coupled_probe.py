#!/usr/bin/python3
"""Runs a coupled case (sph_solver : fem_solver) and checks one probe's mean
over the settled part of the run against a reference value (with
--each-sample: every sample there, not only their mean); optionally the
same case on other rank counts against the first run, and the impulse balance
of every window.

  check_coupled_probe.py --case CASE --probe structure:midspan:displacement_m
      --mean-after 0.1 --reference -7.30e-5 --tolerance 0.03 [--each-sample]
      [--fluid-ranks 1] [--structure-ranks 1] [--also-ranks 2:1 --agreement 1e-3]
      [--impulse-round-off 1e-9] [--set KEY=VALUE ...] [--coupling YAML] --folder DIR

--coupling replaces the case's whole coupling section (a YAML mapping): a
scheme that does without keys the case sets (the implicit ones) cannot be
had with --set.

Prints every figure it checks (the case README's tables come from them).
"""
import argparse
import pathlib
import shutil
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
from coupled_run import derived_case, report, run_coupled  # noqa: E402


def settled_mean(run, side, name, column, after):
    probe = run.probe(side, name)
    values = [v for t, v in zip(probe["time_s"], probe[column]) if t >= after]
    if not values:
        sys.exit(f"FAILED: {side} probe {name} has no samples after {after} s")
    return sum(values) / len(values), probe


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--case", required=True)
    parser.add_argument("--folder", required=True)
    parser.add_argument("--sph")
    parser.add_argument("--fem")
    parser.add_argument("--mpiexec", default="mpirun")
    parser.add_argument("--fluid-ranks", type=int, default=1)
    parser.add_argument("--structure-ranks", type=int, default=1)
    parser.add_argument("--probe", required=True, help="side:name:column")
    parser.add_argument("--mean-after", type=float, required=True)
    parser.add_argument("--reference", type=float, required=True)
    parser.add_argument("--tolerance", type=float, required=True, help="relative")
    parser.add_argument("--each-sample", action="store_true",
                        help="every sample after --mean-after within the tolerance, not only their mean")
    parser.add_argument("--also-ranks", action="append", default=[], help="F:S rank counts run again and compared")
    parser.add_argument("--agreement", type=float, default=1e-3,
                        help="largest probe difference between rank counts, relative to |reference|")
    parser.add_argument("--impulse-round-off", type=float,
                        help="each window's impulse applied by the structure equals the impulse the fluid gave "
                             "within this fraction of the largest window impulse")
    parser.add_argument("--set", action="append", default=[])
    parser.add_argument("--coupling", help="the coupling section, as a YAML mapping, instead of the case's")
    args = parser.parse_args()
    side, name, column = args.probe.split(":")
    folder = pathlib.Path(args.folder)
    shutil.rmtree(folder, ignore_errors=True)
    case = args.case
    if args.coupling:
        import yaml
        case = derived_case(args.case, folder / "case", sections={"coupling": yaml.safe_load(args.coupling)})

    failures = []
    runs = [(args.fluid_ranks, args.structure_ranks)]
    runs += [tuple(int(n) for n in text.split(":")) for text in args.also_ranks]
    first_probe = None
    for fluid_ranks, structure_ranks in runs:
        label = f"{fluid_ranks}:{structure_ranks}"
        run = run_coupled(case, folder / label.replace(":", "x"), args.set, fluid_ranks, structure_ranks,
                          args.sph, args.fem, launcher=(args.mpiexec, "--oversubscribe"))
        if run.status != 0 or run.structure is None:
            print(run.output[-4000:])
            print(f"FAILED: the {label} job failed (exit {run.status}): {run.failure()}")
            return 1
        mean, probe = settled_mean(run, side, name, column, args.mean_after)
        error = mean / args.reference - 1.0
        coupling = run.structure.get("coupling", {})
        print(f"ranks {label}: mean {column} of {name} after {args.mean_after} s = {mean:.6e} "
              f"(reference {args.reference:.6e}, {100 * error:+.2f} %); "
              f"{coupling.get('iterations_per_window', 1):.2f} iterations per window "
              f"(most {coupling.get('most_iterations', 1)}), wall time {run.seconds:.1f} s")
        if abs(error) > args.tolerance:
            failures.append(f"{label}: mean {mean:.6e} is {100 * error:+.2f} % off the reference "
                            f"(tolerance {100 * args.tolerance:.1f} %)")
        if args.each_sample:
            samples = [(t, v / args.reference - 1.0) for t, v in zip(probe["time_s"], probe[column])
                       if t >= args.mean_after]
            when, worst = max(samples, key=lambda sample: abs(sample[1]))
            print(f"ranks {label}: the sample farthest from the reference: {100 * worst:+.2f} % at t = {when:g} s")
            if abs(worst) > args.tolerance:
                failures.append(f"{label}: the sample at t = {when:g} s is {100 * worst:+.2f} % off the reference "
                                f"(tolerance {100 * args.tolerance:.1f} % for every sample)")
        if args.impulse_round_off is not None:
            largest = coupling["largest_window_impulse_Ns"]
            difference = coupling["largest_window_impulse_error_Ns"]
            print(f"ranks {label}: impulse balance: largest window impulse {largest:.6e} N s, "
                  f"largest difference applied - given {difference:.3e} N s")
            if difference > args.impulse_round_off * largest:
                failures.append(f"{label}: a window's applied impulse differs from the given one by "
                                f"{difference:.3e} N s (allowed {args.impulse_round_off:g} of {largest:.3e})")
        if first_probe is None:
            first_probe = probe
            continue
        common = min(len(first_probe[column]), len(probe[column]))
        difference = max(abs(a - b) for a, b in zip(first_probe[column][:common], probe[column][:common]))
        print(f"ranks {label} against {runs[0][0]}:{runs[0][1]}: largest probe difference {difference:.3e} "
              f"({difference / abs(args.reference):.2e} of the reference)")
        if common != len(first_probe[column]):
            failures.append(f"{label}: {len(probe[column])} samples, {len(first_probe[column])} in the first run")
        if difference > args.agreement * abs(args.reference):
            failures.append(f"{label}: the probe differs from the first run's by {difference:.3e} "
                            f"(allowed {args.agreement:g} of the reference)")
    return report(failures, len(runs))


if __name__ == "__main__":
    sys.exit(main())
