#pragma once
// The shell element under large rotations: the element-independent
// co-rotational formulation (Rankin & Nour-Omid 1988; Felippa & Haugen 2005).
// A frame attached to the element follows its rigid motion; what is left,
// the deformational displacements and rotations measured in that frame, is
// small and goes through the linear element (shell_element.hpp) unchanged:
//
//   R_e = E(x) E(X)^T                              the element's rigid rotation
//   u_d,i = R_e^T (x_i - c) - (X_i - c_0)          c the nodes' centroid
//   theta_d,i = log(R_e^T R_i)                     R_i the node's total rotation
//   energy = 1/2 d^T K_0 d,   d = (u_d, theta_d),  K_0 the linear element's stiffness
//
// E's columns: e3 normal to the quadrilateral's diagonals (a triangle's first
// two sides), e1 the direction of g_r at the centre projected on the plane
// (a triangle's first side), e2 = e3 x e1. Rigid motions leave d = 0
// exactly; small displacements give d = u minus its rigid part, which K_0
// does not feel: the linear element is the small-displacement limit.
//
// Nodal variations are translations dx_i and spins dw_i (R_i -> exp([dw_i]x)
// R_i, global axes). The internal force is f = J^T K_0 d, J = dd/d(dx, dw),
// the gradient of the energy; J in closed form (the spin of the frame from
// the variations of its normal and in-plane direction, and the inverse left
// Jacobian of the rotations for theta_d; checked against central differences
// of d in the tests). Two tangents: the material part J^T K_0 J, symmetric and cheap,
// which leaves out the geometric stiffness (dJ^T/dq K_0 d): enough where
// inertia dominates (a time step's effective matrix); and the full tangent,
// the central differences of f itself (steps 1e-6 of the element's size and
// 1e-6 rad, 48 evaluations of f; J exact, so f rounds at eps), symmetrised:
// what a static equilibrium needs, where the geometric stiffness of the
// element forces can be as large as the structure's own bending stiffness (a
// long cantilever under a tip load) and Newton's method stalls without it.
#include <Eigen/Core>

#include <array>

#include "fem_solver/elements/shell_kinematics.hpp"

namespace tankfsi::fem {

/// A node now: its translation and total rotation from the initial state.
/// (Positions are formed relative to the element's initial centroid, so
/// that far from the origin the differences keep their digits.)
struct NodeState {
  Eigen::Vector3d displacement = Eigen::Vector3d::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
};
using ElementState = std::array<NodeState, 4>;  ///< the first 3 or 4 used

class CorotationalElement {
 public:
  /// `initial` the element as meshed, `stiffness` its linear stiffness
  /// (element_stiffness, 6n x 6n, global axes of the initial state).
  CorotationalElement(const ElementNodes& initial, Eigen::MatrixXd stiffness);

  [[nodiscard]] int node_count() const { return count_; }
  /// R_e: the rotation of the element's frame from the initial state.
  [[nodiscard]] Eigen::Matrix3d rigid_rotation(const ElementState& now) const;
  /// d (6n): deformational displacements and rotations in the initial axes.
  [[nodiscard]] Eigen::VectorXd deformation(const ElementState& now) const;
  /// J = dd/d(dx, dw) (6n x 6n).
  [[nodiscard]] Eigen::MatrixXd deformation_jacobian(const ElementState& now) const;

  enum class Tangent { material, full };
  struct Response {
    Eigen::VectorXd force;    ///< internal force and moment per node, global axes (6n)
    Eigen::MatrixXd tangent;  ///< J^T K_0 J, or the full tangent (6n x 6n)
    double energy = 0.0;      ///< 1/2 d^T K_0 d (J)
  };
  [[nodiscard]] Response respond(const ElementState& now, Tangent tangent = Tangent::material) const;
  /// The rounding of the force: K_0's largest entry times the rounding of
  /// a position difference, eps * size (N or N m).
  [[nodiscard]] double force_rounding() const;

 private:
  /// Node positions relative to the initial centroid.
  [[nodiscard]] std::array<Eigen::Vector3d, 4> positions(const ElementState& now) const;
  /// The state moved by h along DOF (node, component): translation, or spin.
  [[nodiscard]] ElementState moved(const ElementState& now, int node, int component, double h) const;
  [[nodiscard]] double step_of(int component) const;
  /// J^T K_0 d.
  [[nodiscard]] Eigen::VectorXd force(const ElementState& now) const;
  /// The element frame (columns e1 e2 e3) of node positions.
  [[nodiscard]] Eigen::Matrix3d frame(const std::array<Eigen::Vector3d, 4>& x) const;

  int count_ = 4;
  std::array<Eigen::Vector3d, 4> initial_position_{};  ///< relative to the initial centroid
  Eigen::Matrix3d initial_frame_ = Eigen::Matrix3d::Identity();
  Eigen::MatrixXd stiffness_;
  double size_ = 1.0;  ///< the largest distance of a node from the centroid (m)
};

}  // namespace tankfsi::fem
