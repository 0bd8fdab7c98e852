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

}  // namespace tankfsi::fem
