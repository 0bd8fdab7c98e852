#pragma once
// Whether a straight segment meets a triangle in space: the one test of both the
// wall mesh checks (does an edge of one triangle pass through another?) and the
// fluid's wall-crossing check (did a particle's path in a step go through a wall?).
#include <Eigen/Core>

namespace tankfsi {

/// True when segment pq meets triangle abc: p and q are not both farther than
/// `tolerance` on the same side of the triangle's plane, and the point where pq
/// meets the plane (the nearer end when pq lies within the tolerance band) is in
/// the triangle or within `tolerance` of its border. A degenerate triangle (zero
/// area) is met by nothing. Segments lying in the plane are the caller's case (the
/// answer then only says whether p is in the triangle).
[[nodiscard]] bool segment_meets_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                                          const Eigen::Vector3d& b, const Eigen::Vector3d& c, double tolerance);

}  // namespace tankfsi
