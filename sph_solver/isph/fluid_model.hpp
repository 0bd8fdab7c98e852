#pragma once
// FluidModel: the physical and numerical constants of one ISPH run (METHOD.md §1),
// fixed for the whole run and shared by every stage of the step.
#include <Eigen/Core>

#include "sph_solver/kernels/kernel.hpp"

namespace tankfsi::sph {

struct FluidModel {
  int dimension = 2;
  KernelType kernel = KernelType::quintic_spline;
  double spacing = 0.0;           ///< L0: initial particle spacing and wall-table lattice spacing (m)
  double smoothing_length = 0.0;  ///< h (m)
  double density = 0.0;           ///< rho0 (kg/m^3)
  double viscosity = 0.0;         ///< mu (Pa s)
  double gravity = 9.81;          ///< |g| (m/s^2): along -y in 2D, -z in 3D
  /// Weight gamma of the density-error part of the PPE source term (eq 6 source).
  double density_error_weight = 0.01;
  /// beta: particles with rho* < beta rho0 are on the free surface (P = 0).
  double free_surface_threshold = 0.97;
  /// > 0: BoomerAMG's hierarchy is built on the PPE operator's pairs within
  /// this many L0 (rescaled; pressure_poisson.hpp); 0: on the operator itself.
  /// The case file's default (fluid.ppe.preconditioner_radius).
  double preconditioner_radius = 1.8;
  bool shifting = true;
  double shifting_coefficient = 2.0;  ///< A in D = A h |v|max dt (Lind et al. 2012)
  /// Pairs closer than this many L0 after the shift are parted (close_pairs.hpp);
  /// 0: never. Only with shifting on.
  double close_pair_distance = 0.5;

  /// The regularisation eta^2 = 0.01 h^2 of the Laplacian and viscous terms.
  [[nodiscard]] double eta_squared() const { return 0.01 * smoothing_length * smoothing_length; }
  /// Mass of one particle of the initial lattice: rho0 L0^D.
  [[nodiscard]] double particle_mass() const;
  /// The vertical unit vector (y in 2D, z in 3D).
  [[nodiscard]] Eigen::Vector3d up() const { return dimension == 2 ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitZ(); }
  /// Body force per unit mass in the tank-base frame: gravity minus the ground
  /// acceleration. In 2D the ground's vertical component (z) acts along y and
  /// its y component is dropped (the section is the x-y plane).
  [[nodiscard]] Eigen::Vector3d body_force(const Eigen::Vector3d& ground_acceleration) const;
};

}  // namespace tankfsi::sph
