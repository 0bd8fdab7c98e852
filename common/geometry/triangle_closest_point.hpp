#pragma once
// Exact closest point of a triangle to a point, by the Voronoi regions of its
// vertices, edges and face (Ericson, Real-Time Collision Detection, 2005, §5.1.5),
// with the barycentric weights of that point and the feature it lies on. The
// fluid's walls (sph_solver/walls) and the coupling's nearest-projection
// mapping both use it.
#include <Eigen/Core>
#include <cstdint>

namespace tankfsi {

/// The feature of the triangle (a, b, c) = (x0, x1, x2) that holds the closest point.
enum class TriangleFeature : std::uint8_t {
  face,    ///< interior of the face
  edge,    ///< edge k: x_k to x_{k+1 mod 3} (excluding its ends)
  vertex,  ///< vertex k
};

struct ClosestPoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  /// Weights of the triangle's vertices 0, 1, 2: point = Σ w_k x_k, w_k >= 0, Σ w_k = 1.
  /// On edge k the weight of the opposite vertex (k+2 mod 3) is exactly 0; at vertex k
  /// the weights are the unit vector e_k.
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
  double squared_distance = 0.0;
  TriangleFeature feature = TriangleFeature::face;
  int feature_index = 0;  ///< k for an edge or a vertex, 0 for the face
};

/// Closest point of triangle (a, b, c) to p. Degenerate triangles (collinear or
/// coincident vertices) are handled: the answer is then the closest point of the
/// three edges.
[[nodiscard]] ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                                                     const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace tankfsi
