#pragma once
// SurfaceContact: the half-space of virtual air particles that completes the kernel
// support of a particle near the free surface (how it is found and used:
// free_surface.hpp), with its overlaps with the particle's orthogonal walls (a
// contact line: boundary_overlap.hpp).
#include <Eigen/Core>

#include <array>
#include <span>

#include "sph_solver/isph/boundary_overlap.hpp"
#include "sph_solver/walls/wall_kernel_table.hpp"

namespace tankfsi::sph {

/// The air one particle near the free surface sees (inactive: all zero).
struct SurfaceContact {
  /// Walls a contact line can meet (a corner of a 3D box has two).
  static constexpr int max_overlaps = 3;

  bool active = false;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  ///< unit, into the liquid; zero if grad C vanishes
  double distance = 0.0;                             ///< delta to the plane P = 0, >= L0/4 when active
  WallKernelValues values;                           ///< the air's table values at delta
  /// Overlaps with walls: plane A the wall (`first` its contact index), plane B the air.
  std::array<BoundaryOverlap, max_overlaps> overlap_storage{};
  int overlap_count = 0;

  [[nodiscard]] std::span<const BoundaryOverlap> overlaps() const {
    return std::span<const BoundaryOverlap>(overlap_storage).first(static_cast<std::size_t>(overlap_count));
  }
  /// Octants behind two orthogonal walls and the air (a vertical edge of a box at
  /// the surface): contacts {wall, wall, -1}, normals {wall, wall, air}. The walls,
  /// their pair's overlap and the air's two overlaps leave it counted once as wall
  /// and not as air: one wall copy is taken off again (see particle_terms.cpp).
  std::array<CornerOctant, max_overlaps> octant_storage{};
  int octant_count = 0;
  [[nodiscard]] std::span<const CornerOctant> octants() const {
    return std::span<const CornerOctant>(octant_storage).first(static_cast<std::size_t>(octant_count));
  }

  /// The air's share of the Laplacian row (eq 6) that multiplies P_i:
  /// sum_{air - overlaps} a_ik (P_i - P_air,k) = laplacian_share() P_i + (the overlaps'
  /// wall part, known), with P_air the ghost pressure through 0 on the plane; <= 0 like a_ij.
  [[nodiscard]] double laplacian_share() const {
    if (!active) return 0.0;
    double share = 2.0 * values.z2 * (1.0 + values.depth2 / distance);
    for (const BoundaryOverlap& o : overlaps()) share -= o.laplacian_sum(0.0, 1.0 / distance);
    for (const CornerOctant& o : octants()) share += o.laplacian_sum({0.0, 0.0, 1.0 / distance});
    return share;
  }
  /// P_i + P_air(d1) = pressure_sum_factor() P_i (the pair sum of eq 4 with the air).
  [[nodiscard]] double pressure_sum_factor() const { return active ? 1.0 - values.depth1 / distance : 0.0; }
  /// P_air(d1) - P_i = pressure_difference_factor() P_i (the difference form).
  [[nodiscard]] double pressure_difference_factor() const {
    return active ? -(distance + values.depth1) / distance : 0.0;
  }
};

}  // namespace tankfsi::sph
