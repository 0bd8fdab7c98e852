#include "fem_solver/elements/rotation_vector.hpp"

#include <algorithm>
#include <cmath>

namespace tankfsi::fem {

Eigen::Matrix3d rotation_matrix(const Eigen::Vector3d& psi) {
  const double angle = psi.norm();
  Eigen::Matrix3d k;
  k << 0.0, -psi.z(), psi.y(), psi.z(), 0.0, -psi.x(), -psi.y(), psi.x(), 0.0;
  // R = I + (sin a / a) K + ((1 - cos a) / a^2) K^2; the series below 1e-4 rad
  // (their next terms are below 1e-17 there).
  double s = 1.0 - angle * angle / 6.0;
  double c = 0.5 - angle * angle / 24.0;
  if (angle > 1e-4) {
    s = std::sin(angle) / angle;
    c = (1.0 - std::cos(angle)) / (angle * angle);
  }
  return Eigen::Matrix3d::Identity() + s * k + c * (k * k);
}

Eigen::Matrix3d inverse_left_jacobian(const Eigen::Vector3d& psi) {
  const double angle = psi.norm();
  Eigen::Matrix3d k;
  k << 0.0, -psi.z(), psi.y(), psi.z(), 0.0, -psi.x(), -psi.y(), psi.x(), 0.0;
  // The coefficient's series, 1/12 + a^2/720, below 1e-3 rad (next term ~a^4/30240).
  const double c = angle > 1e-3 ? 1.0 / (angle * angle) - (1.0 + std::cos(angle)) / (2.0 * angle * std::sin(angle))
                                 : 1.0 / 12.0 + angle * angle / 720.0;
  return Eigen::Matrix3d::Identity() - 0.5 * k + c * (k * k);
}

Eigen::Vector3d rotation_vector(const Eigen::Matrix3d& r) {
  // sin(a) axis = vee(R - R^T)/2, cos(a) = (tr R - 1)/2.
  const Eigen::Vector3d sine_axis(0.5 * (r(2, 1) - r(1, 2)), 0.5 * (r(0, 2) - r(2, 0)), 0.5 * (r(1, 0) - r(0, 1)));
  const double sine = sine_axis.norm();
  const double cosine = std::clamp(0.5 * (r.trace() - 1.0), -1.0, 1.0);
  const double angle = std::atan2(sine, cosine);
  if (cosine > 0.0) {
    // a / sin a, its series where sin a is too small to divide by.
    const double factor = sine > 1e-6 ? angle / sine : 1.0 + sine * sine / 6.0;
    return factor * sine_axis;
  }
  // Near pi sin a loses the axis: take it from the symmetric part,
  // R + R^T - 2 cos(a) I = 2 (1 - cos a) n n^T, its largest column.
  const Eigen::Matrix3d outer = (0.5 * (r + r.transpose()) - cosine * Eigen::Matrix3d::Identity()) / (1.0 - cosine);
  Eigen::Index column = 0;
  outer.diagonal().maxCoeff(&column);
  Eigen::Vector3d axis = outer.col(column).normalized();
  // The sign that sin a axis gives, where it still gives one.
  if (axis.dot(sine_axis) < 0.0) axis = -axis;
  return angle * axis;
}

}  // namespace tankfsi::fem
