#!/usr/bin/python3
"""Periods of a liquid in an upright cylindrical tank from linear theory, the
references the coupled tank runs are judged against (VALIDATION.md, "Tanks
under earthquakes"; Housner 1963, Veletsos, Malhotra, Wenk & Wieland 2000,
EN 1998-4 Annex A):

  convective (first sloshing mode):  T_c = 2 pi / sqrt(g (xi/R) tanh(xi H/R)),  xi = 1.8412
  impulsive (flexible-wall bulging): T_i = C_i H sqrt(rho) / (sqrt(s/R) sqrt(E))

with C_i interpolated linearly in H/R from the Malhotra table (0.3 to 3.0).

Usage: tank_theory.py --radius R --liquid-height H [--density RHO --wall-thickness S --young-modulus E]
Prints the periods (s); importable as a module (convective_period, impulsive_period).
"""
import argparse
import math

XI_1 = 1.8412  # first root of J1'(x) = 0
G = 9.81

# Malhotra et al. (2000) / EN 1998-4 Annex A: H/R -> C_i (VALIDATION.md).
IMPULSIVE_COEFFICIENTS = [(0.3, 9.28), (0.5, 7.74), (0.7, 6.97), (1.0, 6.36), (1.5, 6.06), (2.0, 6.21),
                          (2.5, 6.56), (3.0, 7.03)]


def convective_period(radius, liquid_height, gravity=G):
    """First sloshing period (s) of an upright cylinder of radius R filled to H."""
    omega_squared = gravity * XI_1 / radius * math.tanh(XI_1 * liquid_height / radius)
    return 2 * math.pi / math.sqrt(omega_squared)


def impulsive_coefficient(height_to_radius):
    """C_i of the table, linear between its entries; outside 0.3-3.0 it is an error."""
    table = IMPULSIVE_COEFFICIENTS
    if not table[0][0] <= height_to_radius <= table[-1][0]:
        raise ValueError(f"H/R = {height_to_radius:.3f} is outside the table (0.3 to 3.0)")
    for (x0, c0), (x1, c1) in zip(table, table[1:]):
        if x0 <= height_to_radius <= x1:
            return c0 + (c1 - c0) * (height_to_radius - x0) / (x1 - x0)
    return table[-1][1]


def impulsive_period(radius, liquid_height, density, wall_thickness, young_modulus):
    """Impulsive (bulging) period (s) of a flexible steel tank wall of thickness s."""
    c_i = impulsive_coefficient(liquid_height / radius)
    return c_i * liquid_height * math.sqrt(density) / (math.sqrt(wall_thickness / radius) * math.sqrt(young_modulus))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--radius", type=float, required=True)
    parser.add_argument("--liquid-height", type=float, required=True)
    parser.add_argument("--density", type=float)
    parser.add_argument("--wall-thickness", type=float)
    parser.add_argument("--young-modulus", type=float)
    args = parser.parse_args()
    print(f"convective period T_c = {convective_period(args.radius, args.liquid_height):.4f} s")
    if args.density and args.wall_thickness and args.young_modulus:
        t_i = impulsive_period(args.radius, args.liquid_height, args.density, args.wall_thickness, args.young_modulus)
        print(f"impulsive period  T_i = {t_i:.4f} s")


if __name__ == "__main__":
    main()
