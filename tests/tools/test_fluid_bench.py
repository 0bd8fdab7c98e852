#!/usr/bin/python3
"""scripts/bench/fluid_bench.py's comparison with the weakly-compressible reference
(scripts/bench/wcsph_reference.py): a dam-break row is set beside the reference
only when both ran the same spacing and simulated time, with the reference's
wall time as a multiple of ours; without a reference there is no comparison.
Prints '1 passed, 0 failed' style totals."""
import json
import pathlib
import sys
import tempfile

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "bench"))
import fluid_bench  # noqa: E402

checks = []


def check(name, ok, detail=""):
    checks.append(bool(ok))
    print(f"{'ok  ' if ok else 'FAIL'} {name}" + (f": {detail}" if detail and not ok else ""))


def row(ranks, wall, steps):
    return {"ranks": ranks, "particles": 20000, "steps": steps, "wall_s": wall, "particle_steps_per_s": 1.0,
            "wall_s_per_simulated_s": 1.0, "ppe_iterations_mean": 6.0, "ppe_iterations_max": 9,
            "stage_share": {}, "peak_memory_per_particle_kib": 10.0}


def reference(spacing, simulated):
    return {"code": "WCSPH code", "date": "2026-12-05", "threads": 2, "spacing_m": spacing,
            "simulated_s": simulated, "wall_s": 560.0, "steps": 9950}


figures = {"dam_break_2d": [row(2, 400.0, 4727)],  # L0 = 0.01 m, 2 s
           "dam_break_2d_front": [row(1, 140.0, 1111), row(2, 80.0, 1111)]}  # L0 = 0.01 m, 0.6 s

with tempfile.TemporaryDirectory() as scratch:
    out = pathlib.Path(scratch)
    check("no reference, no comparison", fluid_bench.against_reference(out, figures) == [])

    (out / "wcsph_reference.json").write_text(json.dumps(reference(0.01, 0.6)))
    lines = fluid_bench.against_reference(out, figures)
    rows = [line for line in lines if line.startswith("- ")]
    check("the reference of 0.01 m and 0.6 s meets dam_break_2d_front's two rows alone",
          len(rows) == 2 and all(line.startswith("- dam_break_2d_front on ") for line in rows), "\n".join(lines))
    check("its wall time as a multiple of ours (560 / 140 = 4.00, 560 / 80 = 7.00)",
          len(rows) == 2 and rows[0].endswith("4.00 times ours") and rows[1].endswith("7.00 times ours"),
          "\n".join(rows))
    fluid_bench.write(out, figures)
    check("the figures' table carries the comparison",
          "7.00 times ours" in (out / "fluid_figures.md").read_text())

    (out / "wcsph_reference.json").write_text(json.dumps(reference(0.02, 0.6)))
    check("a reference of another spacing meets no row", fluid_bench.against_reference(out, figures) == [])
    (out / "wcsph_reference.json").write_text(json.dumps(reference(0.01, 2.0)))
    rows = [line for line in fluid_bench.against_reference(out, figures) if line.startswith("- ")]
    check("a reference of 2 s meets the 2 s row alone",
          len(rows) == 1 and rows[0].startswith("- dam_break_2d on 2 ranks"), "\n".join(rows))

passed = sum(checks)
print(f"{passed} passed, {len(checks) - passed} failed")
sys.exit(0 if passed == len(checks) else 1)
