#pragma once
// ShellSection: what an element needs to know about its region — thickness,
// isotropic elastic material, density, and the axis that orients its local
// frame (direction 1 of the stress resultants is this axis projected onto the
// shell; the tank wall's direction 1 is then vertical, direction 2 the hoop).
#include <Eigen/Core>

namespace tankfsi::fem {

struct ShellSection {
  double thickness = 0.0;        ///< m
  double young_modulus = 0.0;    ///< Pa
  double poisson_ratio = 0.0;    ///< -
  double density = 0.0;          ///< kg/m^3
  Eigen::Vector3d reference_axis = Eigen::Vector3d::UnitZ();

  [[nodiscard]] double shear_modulus() const { return young_modulus / (2.0 * (1.0 + poisson_ratio)); }
};

/// Shear correction factor of a homogeneous plate (Reissner-Mindlin).
inline constexpr double shear_correction = 5.0 / 6.0;

/// Constitutive matrix of the local strains [e11, e22, g12, g13, g23] under
/// plane stress (sigma_33 = 0, METHOD.md §3): membrane-bending block and the
/// transverse shear moduli times the shear correction factor.
[[nodiscard]] inline Eigen::Matrix<double, 5, 5> shell_material_matrix(const ShellSection& s) {
  const double e = s.young_modulus;
  const double nu = s.poisson_ratio;
  const double c = e / (1.0 - nu * nu);
  Eigen::Matrix<double, 5, 5> d = Eigen::Matrix<double, 5, 5>::Zero();
  d(0, 0) = c;
  d(1, 1) = c;
  d(0, 1) = c * nu;
  d(1, 0) = c * nu;
  d(2, 2) = s.shear_modulus();
  d(3, 3) = shear_correction * s.shear_modulus();
  d(4, 4) = shear_correction * s.shear_modulus();
  return d;
}

}  // namespace tankfsi::fem
