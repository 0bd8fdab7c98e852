#!/usr/bin/python3
"""Structure benchmark: runs fem_solver on the paper's tank mesh and writes its figures.

Usage: structure_bench.py --solver build/bin/fem_solver --output bench [--quick] [--ranks 1 2]

The case is cases/tank3d_dry (0.60 m elements, ~10,000 nodes, ~56,000
equations; --quick: the coarse twin) run as a dynamic analysis for a few
Newmark steps, which times every stage of the program once:
  shell_assemble   element matrices and PETSc assembly of K and the lumped mass
  shell_modal      SLEPc shift-invert for the 20 lowest modes (one factorisation inside)
  shell_factorise  Cholesky (MUMPS) of K_eff = K (1 + a1 beta) + M (a0 + a1 alpha)
  shell_step       mean wall time of one Newmark step (two triangular solves, the
                   right-hand side, the gathers for output)
and the peak resident memory of the largest rank. The BLAS the solver loads
(MUMPS' dense kernels run on it: the reference BLAS is several times slower
than OpenBLAS) and the machine's load average are recorded with the figures,
since both change them. Figures go to
OUTPUT/structure_figures.json and a table to OUTPUT/structure_figures.md.
Nothing is asserted: a benchmark reports, the reader judges.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

from measured_run import measured_run

STEPS = 20


def run(solver, case, ranks, folder):
    settings = [f"end_time={STEPS * 0.001}", "structure.time_step=0.001", "output.field_interval=1000",
                "output.probe_interval=1000"]
    summary, elapsed, peak_kib = measured_run(solver, case, settings, ranks, folder)
    structure = summary["structure"]
    stages = summary["programs"]["fem_solver"]["stages"]
    step = stages["shell_step"]
    return {
        "ranks": ranks,
        "nodes": structure["nodes"],
        "quadrilaterals": structure["quadrilaterals"],
        "triangles": structure["triangles"],
        "equations": structure["equations"],
        "assembly_s": stages["shell_assemble"]["seconds"],
        "modal_20_modes_s": stages["shell_modal"]["seconds"],
        # The first factorisation is the static/Newmark K_eff; the modal one is inside shell_modal.
        "factorisation_s": stages["shell_factorise"]["seconds"] / stages["shell_factorise"]["calls"],
        "newmark_step_s": step["seconds"] / step["calls"],
        "steps": step["calls"],
        "fundamental_period_s": summary["modal"]["fundamental_period_s"],
        "peak_memory_largest_rank_MiB": peak_kib / 1024.0,
        "wall_s": elapsed,
    }


def blas_library(solver):
    """The file libblas.so.3 resolves to for the solver (after alternatives and LD_LIBRARY_PATH)."""
    result = subprocess.run(["ldd", solver], capture_output=True, text=True)
    for line in result.stdout.splitlines():
        if "libblas.so" in line and "=>" in line:
            return os.path.realpath(line.split("=>")[1].split("(")[0].strip())
    return "unknown"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--solver", required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    args = parser.parse_args()
    case = "cases/tank3d_dry_coarse/case.yaml" if args.quick else "cases/tank3d_dry/case.yaml"
    output = pathlib.Path(args.output)
    output.mkdir(parents=True, exist_ok=True)
    rows = []
    with tempfile.TemporaryDirectory() as scratch:
        for ranks in args.ranks:
            load_before = os.getloadavg()[0]
            rows.append(run(str(pathlib.Path(args.solver).resolve()), case, ranks, pathlib.Path(scratch) / f"np{ranks}"))
            rows[-1]["load_average_before"] = load_before
            print(json.dumps(rows[-1]))
    blas = blas_library(str(pathlib.Path(args.solver).resolve()))
    (output / "structure_figures.json").write_text(
        json.dumps({"case": case, "blas": blas, "cores": os.cpu_count(), "runs": rows}, indent=2) + "\n")
    columns = ["ranks", "nodes", "equations", "assembly_s", "factorisation_s", "newmark_step_s", "modal_20_modes_s",
               "peak_memory_largest_rank_MiB", "fundamental_period_s"]
    columns.append("load_average_before")
    lines = [f"Structure benchmark: {case} (BLAS: {blas}, {os.cpu_count()} cores)", "", "| " + " | ".join(columns) + " |",
             "|" + "---|" * len(columns)]
    for r in rows:
        lines.append("| " + " | ".join(f"{r[c]:.4g}" if isinstance(r[c], float) else str(r[c]) for c in columns) + " |")
    (output / "structure_figures.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    sys.exit(main())
