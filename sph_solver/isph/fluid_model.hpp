#pragma once
// FluidModel: the physical and numerical constants of one ISPH run (METHOD.md §1),
// fixed for the whole run and shared by every stage of the step.
#include <algorithm>

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
  /// BoomerAMG's hierarchy is kept from step to step while it serves
  /// (kept_hierarchy.hpp; fluid.ppe.keep_hierarchy).
  bool keep_hierarchy = true;
  bool shifting = true;
  double shifting_coefficient = 2.0;  ///< A in D = A h |v|max dt (Lind et al. 2012)
  /// Pairs closer than this many L0 after the shift are parted (close_pairs.hpp);
  /// 0: never. Only with shifting on.
  double close_pair_distance = 0.5;

  /// The shift's diffusion coefficient D = A h |v|max dt (Lind et al. 2012),
  /// at most max_shifting_diffusion h^2. The shift dr = -D grad C is an
  /// explicit diffusion step: on the 2D lattice (quintic spline, h = 1.2 L0)
  /// it is stable for D < 1.36 h^2 (2 / the largest rate at which grad C
  /// answers a displacement), less where the particles are pressed together.
  /// Measured on the dam break (L0 = 0.01 and 0.02 m): A |v|max dt / h = 0.8
  /// (A = 2 at a Courant number of 0.4) grew a period-two oscillation of the
  /// density under the column until the CFL check stopped the run at
  /// 0.23-0.33 s; 0.6 ran (A = 1.5 at 0.4, A = 1.2 at 0.5). With A = 2 the
  /// limit acts from a Courant number of 0.3 on, so steps at the default
  /// Courant number 0.2 are as they were.
  [[nodiscard]] double shifting_diffusion(double largest_speed, double dt) const {
    return std::min(shifting_coefficient * smoothing_length * largest_speed * dt,
                    max_shifting_diffusion * smoothing_length * smoothing_length);
  }
  static constexpr double max_shifting_diffusion = 0.6;

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
