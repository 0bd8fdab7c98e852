#include "common/geometry/segment_triangle.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>

namespace tankfsi {

bool segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tolerance) {
  const Eigen::Vector3d normal = (b - a).cross(c - a);
  const double twice_area = normal.norm();
  if (!(twice_area > 0.0)) return false;
  const Eigen::Vector3d n = normal / twice_area;
  const double dp = n.dot(p - a);
  const double dq = n.dot(q - a);
  if ((dp > tolerance && dq > tolerance) || (dp < -tolerance && dq < -tolerance)) return false;
  const double denominator = dp - dq;
  const double u = std::abs(denominator) > 0.0 ? std::clamp(dp / denominator, 0.0, 1.0) : 0.0;
  const Eigen::Vector3d x = p + u * (q - p);
  // Inside: on the inner side of each edge (the edge's outward distance <= tolerance).
  const std::array<const Eigen::Vector3d*, 3> corner{&a, &b, &c};
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& from = *corner[static_cast<std::size_t>(k)];
    const Eigen::Vector3d edge = *corner[static_cast<std::size_t>((k + 1) % 3)] - from;
    const double length = edge.norm();
    if (edge.cross(x - from).dot(n) < -tolerance * length) return false;
  }
  return true;
}

}  // namespace tankfsi
