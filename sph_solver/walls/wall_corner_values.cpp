#include "sph_solver/walls/wall_corner_values.hpp"

#include <cmath>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

/// The interior angle of triangle t at its corner k.
double corner_angle(const TriangleMesh& mesh, int t, int k) {
  const Eigen::Vector3d& p = mesh.corner(t, k);
  const Eigen::Vector3d a = mesh.corner(t, (k + 1) % 3) - p;
  const Eigen::Vector3d b = mesh.corner(t, (k + 2) % 3) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

WallCornerValues wall_corner_values(const TriangleMesh& mesh, std::span<const double> vertex_curvature,
                                    double same_wall_cosine) {
  const auto& triangles = mesh.triangles();
  const auto& normals = mesh.face_normals();
  // The triangles around each vertex, with the vertex's corner index in each.
  std::vector<std::vector<std::array<int, 2>>> around(mesh.vertex_count());
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) around[at(triangles[at(t)][at(k)])].push_back({t, k});

  WallCornerValues out;
  out.normals.resize(triangles.size());
  out.curvature.resize(triangles.size());
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const Eigen::Vector3d& own = normals[at(t)];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[at(t)][at(k)];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double neighbour_curvature = 0.0;
      int resolvable_neighbours = 0;
      for (const auto& [s, c] : around[at(v)]) {
        const Eigen::Vector3d& n = normals[at(s)];
        if (!(n.dot(own) > same_wall_cosine)) continue;  // another wall
        sum += corner_angle(mesh, s, c) * n;
        for (int j = 1; j < 3; ++j) {
          const double h = vertex_curvature[at(triangles[at(s)][at((c + j) % 3)])];
          if (std::isfinite(h)) {
            neighbour_curvature += h;
            ++resolvable_neighbours;
          }
        }
      }
      // Normals that agree to round-off (a flat wall) give exactly the triangle's own.
      const Eigen::Vector3d mean = sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : own;
      out.normals[at(t)][at(k)] = (mean - own).squaredNorm() < 1e-24 ? own : mean;
      const double h = vertex_curvature[at(v)];
      out.curvature[at(t)][at(k)] =
          std::isfinite(h) ? h : (resolvable_neighbours > 0 ? neighbour_curvature / resolvable_neighbours : 0.0);
    }
  }
  return out;
}

}  // namespace tankfsi::sph
