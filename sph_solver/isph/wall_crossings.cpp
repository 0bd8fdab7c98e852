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

WallCrossings return_to_walls(const WallModel& walls, int dimension, std::span<const Eigen::Vector3d> start,
                             std::span<Eigen::Vector3d> position, std::span<Eigen::Vector3d> velocity) {
  if (start.size() != position.size() || velocity.size() != position.size())
    throw std::invalid_argument("return_to_walls: one start, position and velocity per particle");
  const TriangleMesh& mesh = walls.mesh();
  const double spacing = walls.table().spacing();
  const double deepest = touching_depth * spacing;
  const double gap = 1e-3 * spacing;
  WallCrossings result;
  for (std::size_t i = 0; i < position.size(); ++i) {
    int t = crossed_triangle(walls, start[i], position[i]);
    // One wall at a time: a particle in a corner may have passed two or three.
    for (int wall = 0; t >= 0 && wall < 3; ++wall) {
      Eigen::Vector3d normal = wall_plane_normal(mesh, t, dimension);
      // A two-sided sheet's liquid side is the one the path came from.
      if (walls.two_sided(t) && (start[i] - mesh.corner(t, 0)).dot(normal) < 0.0) normal = -normal;
      const double depth = (mesh.corner(t, 0) - position[i]).dot(normal);
      // In front of the plane the path came from behind it; too deep, it went through.
      if (normal.squaredNorm() == 0.0 || !(depth >= 0.0 && depth <= deepest)) break;
      position[i] += (depth + gap) * normal;
      WallContact foot;
      foot.feet[0] = WallFoot{t, closest_point_on_triangle(position[i], mesh, t).barycentric, 1.0};
      const double into = (velocity[i] - at_contact(mesh, walls.vertex_velocities(), foot)).dot(normal);
      if (into < 0.0) velocity[i] -= into * normal;
      if (wall == 0) ++result.returned;
      t = crossed_triangle(walls, start[i], position[i]);
    }
    if (t >= 0) result.through.push_back({static_cast<int>(i), t});
  }
  return result;
}

}  // namespace tankfsi::sph
