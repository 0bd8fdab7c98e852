#pragma once
// Probes of the fluid: what a user samples in time at a point or over the whole
// liquid. Each function is collective (each rank sums over its owned particles, then
// the ranks combine), so every rank gets the same value.
//
// - pressure_at / velocity_at: kernel interpolation, Shepard-corrected
//   (sum_j V_j f_j W / sum_j V_j W), so a point near a wall or the surface is not
//   biased towards zero by missing neighbours. NaN where no particle is within the support.
// - surface_elevation: the free surface above a point: along the vertical line
//   from the point up to `top`, the colour function c(s) = sum_j V_j W / (1 - sum_w Z0)
//   (the walls' share removed, so a point beside a wall is not read as half empty)
//   is sampled every L0/4; the surface is the highest crossing of c = 1/2, linearly
//   interpolated. Returned as height above the point (place the point at the still
//   level for the wave height eta); NaN if the line is dry.
// - front_position: the surge front of a dam break: the largest distance along
//   `direction` from the point of any particle within 2 L0 above the point's level.
// - liquid_volume: the volume m_j / rho0 of the particles inside a box and of those
//   outside it (the liquid that overflowed the box; removed particles are in neither).
// - kinetic_energy: sum of m v^2 / 2.
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

#include "sph_solver/isph/fluid_solver.hpp"

namespace tankfsi::sph {

[[nodiscard]] double pressure_at(const FluidSolver& solver, const Eigen::Vector3d& point);
[[nodiscard]] Eigen::Vector3d velocity_at(const FluidSolver& solver, const Eigen::Vector3d& point);
[[nodiscard]] double surface_elevation(const FluidSolver& solver, const Eigen::Vector3d& point, double top);
[[nodiscard]] double front_position(const FluidSolver& solver, const Eigen::Vector3d& point,
                                    const Eigen::Vector3d& direction);
/// {inside, outside} the box.
[[nodiscard]] std::array<double, 2> liquid_volume(const FluidSolver& solver, const Eigen::AlignedBox3d& box);
[[nodiscard]] double kinetic_energy(const FluidSolver& solver);

}  // namespace tankfsi::sph
