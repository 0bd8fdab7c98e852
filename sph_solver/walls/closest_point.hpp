#pragma once
// Closest points on wall meshes (common/geometry/triangle_closest_point.hpp for
// one triangle) and the signed distance of a wall mesh.
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
#include <optional>

#include "common/geometry/triangle_closest_point.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

using tankfsi::ClosestPoint;
using tankfsi::closest_point_on_triangle;
using tankfsi::TriangleFeature;

/// Closest point of triangle t of a mesh to p.
[[nodiscard]] ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t);

/// The closest point of triangle t to p when nearer than sqrt(radius_squared),
/// else none. The distance to the triangle's plane is tested first: a dot
/// product that spares the closest point's regions for most triangles a box
/// test lets through. It refuses only planes farther than the radius by a
/// relative 1e-10, far above the round-off of either distance, so the answer is
/// that of the closest point's distance alone. (A degenerate triangle's normal
/// is zero: its plane refuses nothing.)
[[nodiscard]] inline std::optional<ClosestPoint> closest_point_within(const Eigen::Vector3d& p, const TriangleMesh& mesh,
                                                                      int t, double radius_squared) {
  const double height = (p - mesh.corner(t, 0)).dot(mesh.face_normals()[static_cast<std::size_t>(t)]);
  if (height * height > radius_squared * (1.0 + 1e-10)) return std::nullopt;
  const ClosestPoint closest = closest_point_on_triangle(p, mesh, t);
  if (!(closest.squared_distance < radius_squared)) return std::nullopt;
  return closest;
}

/// The normal that decides the side of p at a closest point of triangle t: the face
/// normal, the edge pseudo-normal or the vertex (angle-weighted) normal by feature.
[[nodiscard]] const Eigen::Vector3d& pseudo_normal(const TriangleMesh& mesh, int t, const ClosestPoint& closest);

/// Signed distance of p to the wall, given the closest point q on triangle t:
/// ±|p - q| with the sign of (p - q)·pseudo_normal (see above). In the face region this
/// equals (p - q)·n_face. Meaningful when t is the nearest triangle of the mesh.
[[nodiscard]] double signed_distance(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t,
                                     const ClosestPoint& closest);

}  // namespace tankfsi::sph
