#pragma once
// The shell element (MITC4 quadrilateral or MITC3 triangle, METHOD.md §3):
// stiffness, lumped mass with rotary inertia, consistent surface loads and
// stress resultants, all in global axes with 6 DOF per node
// (u_x u_y u_z theta_x theta_y theta_z).
#include <Eigen/Core>

#include <functional>

#include "fem_solver/elements/shell_kinematics.hpp"
#include "fem_solver/elements/shell_section.hpp"

namespace tankfsi::fem {

/// Stiffness of the drilling rotation relative to the in-plane rotation of the
/// membrane field, as a fraction of G t (Hughes & Brezzi 1989 use G; a small
/// fraction keeps the penalty from stiffening the membrane of coarse curved
/// meshes while leaving no zero-energy drilling mode).
inline constexpr double default_drilling_factor = 1e-3;

/// 6n x 6n stiffness: 2x2 (quad) or 3-point (triangle) in-plane Gauss, 2 points
/// through the thickness (the strains are linear in t), plus the drilling term.
[[nodiscard]] Eigen::MatrixXd element_stiffness(const ElementNodes& e, const ShellSection& section,
                                                double drilling_factor = default_drilling_factor);

/// Diagonal of the lumped mass (6n): node i carries rho t A_i (A_i = integral of
/// h_i dA), and rotary inertia rho t^3/12 A_i about each axis.
[[nodiscard]] Eigen::VectorXd element_lumped_mass(const ElementNodes& e, const ShellSection& section);

/// Consistent nodal forces (6n, moments zero) of a surface load per unit area:
/// a pressure field p(x) pushing along the element normal (g_r x g_s
/// direction) plus a traction in global axes.
using PressureField = std::function<double(const Eigen::Vector3d&)>;
[[nodiscard]] Eigen::VectorXd element_surface_load(const ElementNodes& e, const PressureField& pressure,
                                                   const Eigen::Vector3d& traction);

/// Mid-surface area of the element.
[[nodiscard]] double element_area(const ElementNodes& e);

/// Stress resultants at the element centre in its local frame (direction 1 the
/// section's reference axis projected on the shell, 3 the normal).
struct StressResultants {
  Eigen::Vector3d membrane = Eigen::Vector3d::Zero();  ///< N11, N22, N12 (N/m)
  Eigen::Vector3d bending = Eigen::Vector3d::Zero();   ///< M11, M22, M12 (N m/m)
  Eigen::Vector2d shear = Eigen::Vector2d::Zero();     ///< Q13, Q23 (N/m)
  double von_mises_top = 0.0;                          ///< Pa, at t = +1 (normal side)
  double von_mises_bottom = 0.0;                       ///< Pa, at t = -1
};

[[nodiscard]] StressResultants element_stress_resultants(const ElementNodes& e, const ShellSection& section,
                                                         const Eigen::VectorXd& displacement);

}  // namespace tankfsi::fem
