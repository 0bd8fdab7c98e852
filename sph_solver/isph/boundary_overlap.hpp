#pragma once
// BoundaryOverlap: the quarter-space behind two orthogonal boundary planes of one
// particle — two walls (a corner of the tank) or a wall and the free surface's air
// (a contact line) — which the two half-spaces of virtual particles both count
// (corner_kernel_table.hpp). Every sum over the boundary is then
//   sum over the half-spaces - sum over their overlaps
// (inclusion-exclusion), with the pressure in the overlap the linear field
//   P_k = P_i + G . (x_k - x_i),  G = G_A n_A + G_B n_B (+ G_e e in 3D),
// each plane giving its normal gradient: dP/dn of the Neumann condition for a wall
// (particle_terms.hpp), P_i / delta for the air (free_surface.hpp); G_e, along the
// edge, from the renormalised gradient. In the air's overlaps with walls the wall's
// dP/dn is the predictor's acceleration part only, not the push against the
// particle's approach, which stays whole in the wall's half-space
// (contact_line_wall_gradient(), particle_terms.hpp).
//
// Pairs count as orthogonal when |n_A . n_B| < 0.25 (75.5 to 104.5 degrees); the
// planes' normals are used as they are. Other pairs are not corrected (a known
// limitation: the dome roof's junction with the wall of a 3D tank).
//
// CornerOctant: where three mutually orthogonal walls meet (a corner of a 3D box)
// the three half-spaces count the octant behind all three three times and the
// three pairs' overlaps take it out three times: it is added back once, with the
// pressure P_k = P_i + G . (x_k - x_i), G = G_A n_A + G_B n_B + G_C n_C. (A corner
// of two walls and the free surface is not corrected: the air's overlap with two
// walls is counted as the pairs leave it.)
#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

#include "sph_solver/walls/corner_kernel_table.hpp"

namespace tankfsi::sph {

struct BoundaryOverlap {
  /// |n_A . n_B| below this: orthogonal enough for the corner table.
  static constexpr double orthogonal_cosine = 0.25;

  int first = -1;   ///< plane A: index of the wall contact among the particle's contacts
  int second = -1;  ///< plane B: index of the wall contact, or -1 for the air
  Eigen::Vector3d normal_a = Eigen::Vector3d::Zero();  ///< unit, into the fluid
  Eigen::Vector3d normal_b = Eigen::Vector3d::Zero();
  CornerKernelValues values;

  /// V sum grad_i W_ik over the overlap.
  [[nodiscard]] Eigen::Vector3d gradient_sum() const { return values.q1a * normal_a + values.q1b * normal_b; }

  /// S = V sum W'/r x_ik (x) x_ik (the moment tensor of the overlap is -S).
  [[nodiscard]] Eigen::Matrix3d second_moment() const {
    const Eigen::Vector3d edge = normal_a.cross(normal_b);
    const double edge_length = edge.norm();
    Eigen::Matrix3d s = values.saa * normal_a * normal_a.transpose() +
                        values.sab * (normal_a * normal_b.transpose() + normal_b * normal_a.transpose()) +
                        values.sbb * normal_b * normal_b.transpose();
    if (edge_length > 0.0) s += values.see * (edge / edge_length) * (edge / edge_length).transpose();
    return s;
  }

  /// V sum (P_k - P_i) grad_i W_ik for the linear field of gradient G: -S G.
  [[nodiscard]] Eigen::Vector3d pressure_difference_sum(const Eigen::Vector3d& gradient) const {
    return -(second_moment() * gradient);
  }

  /// sum a_ik (P_i - P_k) = 2 (M2A G_A + M2B G_B) for normal gradients G_A, G_B.
  [[nodiscard]] double laplacian_sum(double gradient_a, double gradient_b) const {
    return 2.0 * (values.m2a * gradient_a + values.m2b * gradient_b);
  }

  /// The trace of the overlap's moment tensor: its share of div r.
  [[nodiscard]] double position_divergence_share() const { return -(values.saa + values.sbb + values.see); }
};

struct CornerOctant {
  std::array<int, 3> contacts{-1, -1, -1};  ///< indices among the particle's wall contacts
  std::array<Eigen::Vector3d, 3> normals{};  ///< unit, into the fluid
  OctantKernelValues values;

  /// V sum grad_i W_ik over the octant.
  [[nodiscard]] Eigen::Vector3d gradient_sum() const {
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    for (std::size_t u = 0; u < 3; ++u) g += values.q1[u] * normals[u];
    return g;
  }

  /// S = V sum W'/r x_ik (x) x_ik (the moment tensor of the octant is -S).
  [[nodiscard]] Eigen::Matrix3d second_moment() const {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    for (std::size_t u = 0; u < 3; ++u)
      for (std::size_t v = 0; v < 3; ++v) s += values.s[u][v] * normals[u] * normals[v].transpose();
    return s;
  }

  /// V sum (P_k - P_i) grad_i W_ik for the linear field of gradient G: -S G.
  [[nodiscard]] Eigen::Vector3d pressure_difference_sum(const Eigen::Vector3d& gradient) const {
    return -(second_moment() * gradient);
  }

  /// sum a_ik (P_i - P_k) = 2 sum_X M2X G_X for normal gradients G_X.
  [[nodiscard]] double laplacian_sum(const std::array<double, 3>& normal_gradients) const {
    return 2.0 * (values.m2[0] * normal_gradients[0] + values.m2[1] * normal_gradients[1] +
                  values.m2[2] * normal_gradients[2]);
  }

  /// The trace of the octant's moment tensor: its share of div r.
  [[nodiscard]] double position_divergence_share() const { return -(values.s[0][0] + values.s[1][1] + values.s[2][2]); }
};

}  // namespace tankfsi::sph
