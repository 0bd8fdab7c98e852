#include "sph_solver/isph/wall_crossings.hpp"

#include <stdexcept>

#include "common/geometry/segment_triangle.hpp"
#include "sph_solver/walls/closest_point.hpp"

namespace tankfsi::sph {

int crossed_triangle(const WallModel& walls, const Eigen::Vector3d& from, const Eigen::Vector3d& to) {
  // Any triangle the path meets lies within half the path's length of its midpoint.
  const double half = 0.5 * (to - from).norm();
  if (!(half > 0.0)) return -1;
  const TriangleMesh& mesh = walls.mesh();
  int crossed = -1;
  walls.index().within(0.5 * (from + to), half * (1.0 + 1e-12), [&](const WallHit& hit) {
    if ((crossed < 0 || hit.triangle < crossed) &&
        segment_meets_triangle(from, to, mesh.corner(hit.triangle, 0), mesh.corner(hit.triangle, 1),
                               mesh.corner(hit.triangle, 2), 0.0))
      crossed = hit.triangle;
  });
  return crossed;
}

long long return_to_walls(const WallModel& walls, int dimension, std::span<const Eigen::Vector3d> start,
                          std::span<Eigen::Vector3d> position, std::span<Eigen::Vector3d> velocity) {
  if (start.size() != position.size() || velocity.size() != position.size())
    throw std::invalid_argument("return_to_walls: one start, position and velocity per particle");
  const TriangleMesh& mesh = walls.mesh();
  const double spacing = walls.table().spacing();
  const double deepest = touching_depth * spacing;
  const double gap = 1e-3 * spacing;
  long long returned = 0;
  for (std::size_t i = 0; i < position.size(); ++i) {
    bool put_back = false;
    // One wall at a time: a particle in a corner may have passed two or three.
    for (int wall = 0; wall < 3; ++wall) {
      const int t = crossed_triangle(walls, start[i], position[i]);
      if (t < 0) break;
      const Eigen::Vector3d normal = wall_plane_normal(mesh, t, dimension);
      const double depth = (mesh.corner(t, 0) - position[i]).dot(normal);
      // In front of the plane the path came from behind it; too deep, it went through.
      if (normal.squaredNorm() == 0.0 || !(depth >= 0.0 && depth <= deepest)) break;
      position[i] += (depth + gap) * normal;
      const ClosestPoint foot = closest_point_on_triangle(position[i], mesh, t);
      const auto& corners = mesh.triangles()[static_cast<std::size_t>(t)];
      Eigen::Vector3d wall_velocity = Eigen::Vector3d::Zero();
      for (int k = 0; k < 3; ++k)
        wall_velocity += foot.barycentric[k] * walls.vertex_velocities()[static_cast<std::size_t>(corners[static_cast<std::size_t>(k)])];
      const double into = (velocity[i] - wall_velocity).dot(normal);
      if (into < 0.0) velocity[i] -= into * normal;
      put_back = true;
    }
    returned += put_back ? 1 : 0;
  }
  return returned;
}

}  // namespace tankfsi::sph
