#!/usr/bin/python3
"""scripts/post/tank_theory.py against the figures VALIDATION.md and METHOD.md
quote: the paper's tank (R 15 m, H 14.8 m, oil 860 kg/m3, wall 15 mm, E 206
GPa) has T_c = 5.88 s and T_i about 0.19 s; the 2D tank's analogue is not
cylindrical and not covered here. Prints '1 passed, 0 failed' style totals."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "scripts" / "post"))
import tank_theory  # noqa: E402

checks = []


def check(name, value, expected, tolerance):
    ok = abs(value - expected) <= tolerance
    checks.append(ok)
    print(f"{'ok  ' if ok else 'FAIL'} {name}: {value:.4f} (expected {expected} +- {tolerance})")


check("convective period of the paper's tank (s)", tank_theory.convective_period(15.0, 14.8), 5.88, 0.005)
check("impulsive period of the paper's tank (s)",
      tank_theory.impulsive_period(15.0, 14.8, 860.0, 0.015, 206e9), 0.19, 0.005)
check("C_i at a table entry (H/R = 1.0)", tank_theory.impulsive_coefficient(1.0), 6.36, 1e-12)
check("C_i between entries (H/R = 0.85)", tank_theory.impulsive_coefficient(0.85), (6.97 + 6.36) / 2, 1e-12)
try:
    tank_theory.impulsive_coefficient(5.0)
    checks.append(False)
    print("FAIL H/R = 5 outside the table was accepted")
except ValueError:
    checks.append(True)
    print("ok   H/R = 5 outside the table is refused")
passed = sum(checks)
print(f"{passed} passed, {len(checks) - passed} failed")
sys.exit(0 if passed == len(checks) else 1)
