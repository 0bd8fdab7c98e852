#pragma once
// Exact closest point of a triangle to a point, by the Voronoi regions of its
// vertices, edges and face (Ericson, Real-Time Collision Detection, 2005, §5.1.5),
// with the barycentric weights of that point and the feature it lies on, and the
// signed distance of a wall mesh.
//
// Sign convention (Bærentzen & Aanæs, "Signed distance computation using the angle
// weighted pseudonormal", IEEE TVCG 11(3), 2005): the distance is positive on the
// side the normals point to (the fluid side) and negative behind the wall.
//  - face region: the sign of (p - q)·n_face;
//  - edge region: the sign of (p - q)·n_edge, n_edge the sum of the two face normals;
//  - vertex region: the sign of (p - q)·n_vertex, the angle-weighted vertex normal.
// Bærentzen & Aanæs prove this sign is correct for any point of space when q is the
// closest point over the whole of a closed, consistently oriented manifold mesh,
// including at concave edges and saddle corners where the face normal of one of the
// triangles touching q gives the wrong answer. For open walls it is correct near the
// wall's interior; beyond an open edge "behind" is a convention.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

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

/// Closest point of triangle t of a mesh to p.
[[nodiscard]] ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t);

/// The normal that decides the side of p at a closest point of triangle t: the face
/// normal, the edge pseudo-normal or the vertex (angle-weighted) normal by feature.
[[nodiscard]] const Eigen::Vector3d& pseudo_normal(const TriangleMesh& mesh, int t, const ClosestPoint& closest);

/// Signed distance of p to the wall, given the closest point q on triangle t:
/// ±|p - q| with the sign of (p - q)·pseudo_normal (see above). In the face region this
/// equals (p - q)·n_face. Meaningful when t is the nearest triangle of the mesh.
[[nodiscard]] double signed_distance(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t,
                                     const ClosestPoint& closest);

}  // namespace tankfsi::sph
