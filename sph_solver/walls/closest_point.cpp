#include "sph_solver/walls/closest_point.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace tankfsi::sph {

ClosestPoint closest_point_on_triangle(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t) {
  return closest_point_on_triangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2));
}

const Eigen::Vector3d& pseudo_normal(const TriangleMesh& mesh, int t, const ClosestPoint& closest) {
  switch (closest.feature) {
    case TriangleFeature::edge:
      return mesh.edge_normal(t, closest.feature_index);
    case TriangleFeature::vertex:
      return mesh.vertex_normals()[static_cast<std::size_t>(
          mesh.triangles()[static_cast<std::size_t>(t)][static_cast<std::size_t>(closest.feature_index)])];
    case TriangleFeature::face:
      break;
  }
  return mesh.face_normals()[static_cast<std::size_t>(t)];
}

double signed_distance(const Eigen::Vector3d& p, const TriangleMesh& mesh, int t, const ClosestPoint& closest) {
  const double side = (p - closest.point).dot(pseudo_normal(mesh, t, closest));
  if (closest.feature == TriangleFeature::face) return side;
  const double distance = std::sqrt(closest.squared_distance);
  return side < 0.0 ? -distance : distance;
}

}  // namespace tankfsi::sph
