#pragma once
// Kinematics of the continuum-based (degenerated) shell, METHOD.md §3:
//
//   x(r,s,t) = sum_i h_i x_i + t/2 sum_i a h_i V_i
//   u(r,s,t) = sum_i h_i u_i + t/2 sum_i a h_i (theta_i x V_i)
//
// with V_i the director at node i, a the thickness and theta_i the node's
// rotation vector in global axes (6 DOF per node: u_x u_y u_z theta_x theta_y
// theta_z). The component of theta_i along V_i does not move the director: it
// is the drilling rotation, given stiffness by shell_element's drilling term.
//
// Strains are covariant components e_ij = (g_i . u_,j + g_j . u_,i)/2, with
// the transverse shear ones (rt, st) replaced by the MITC interpolation of
// their values at tying points, then transformed into the local orthonormal
// frame (e1, e2 in the shell, e3 normal) where the plane-stress law applies.
#include <Eigen/Core>

#include <array>

namespace tankfsi::fem {

/// One element as the kinematics sees it: 3 (triangle) or 4 (quad) nodes.
struct ElementNodes {
  int count = 4;
  std::array<Eigen::Vector3d, 4> position{};
  std::array<Eigen::Vector3d, 4> director{};  ///< unit vectors
  double thickness = 0.0;

  [[nodiscard]] int dofs() const { return 6 * count; }
};

using StrainRows = Eigen::Matrix<double, 5, Eigen::Dynamic>;  ///< [e11 e22 g12 g13 g23] x 6n
using DofRow = Eigen::Matrix<double, 1, Eigen::Dynamic>;

/// Orthonormal frame (rows e1, e2, e3) on the mid-surface at (r, s): e3 the
/// normal g_r x g_s, e1 the reference axis projected onto the surface (g_r when
/// the axis is nearly normal to it).
[[nodiscard]] Eigen::Matrix3d local_frame(const ElementNodes& e, double r, double s,
                                          const Eigen::Vector3d& reference_axis);

/// Local strain rows at (r, s, t) in `frame`, with MITC transverse shear; also
/// the Jacobian determinant of the map (r, s, t) -> x.
[[nodiscard]] StrainRows local_strain_rows(const ElementNodes& e, double r, double s, double t,
                                           const Eigen::Matrix3d& frame, double& jacobian);

/// Drilling mismatch at (r, s) on the mid-surface: the rotation about e3
/// interpolated from the nodes minus the in-plane rotation of the membrane
/// displacement field, (u_2,1 - u_1,2)/2. Zero for every rigid-body motion.
[[nodiscard]] DofRow drilling_row(const ElementNodes& e, double r, double s, const Eigen::Matrix3d& frame);

/// Mid-surface area element |g_r x g_s| at (r, s) and the un-normalised normal.
[[nodiscard]] Eigen::Vector3d area_normal(const ElementNodes& e, double r, double s);

}  // namespace tankfsi::fem
