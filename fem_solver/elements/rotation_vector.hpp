#pragma once
// Finite rotations as rotation vectors (axis times angle) and matrices: the
// exponential map (Rodrigues' formula) and its inverse, the logarithm. The
// co-rotational element (corotational_element.hpp) keeps each node's total
// rotation this way.
#include <Eigen/Core>

namespace tankfsi::fem {

/// R = exp([psi]x): the rotation by |psi| about psi's direction.
[[nodiscard]] Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& psi);

/// The rotation vector of R, angle in [0, pi] (at pi both signs of the axis
/// are the same rotation). R must be orthonormal with det 1.
[[nodiscard]] Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& r);

/// J_l^-1(psi): the change of psi for a small rotation xi applied on the left,
/// exp([xi]x) exp([psi]x) = exp([psi + J_l^-1 xi]x) to first order in xi;
/// I - [psi]x / 2 + (1/a^2 - (1 + cos a)/(2 a sin a)) [psi]x^2, a = |psi| < pi.
[[nodiscard]] Eigen::Matrix3d inverse_left_jacobian(const Eigen::Vector3d& psi);

}  // namespace tankfsi::fem
