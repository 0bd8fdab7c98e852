#include "sph_solver/walls/wall_corner_values.hpp"

#include <cmath>

namespace tankfsi::sph {
namespace {

/// The interior angle of triangle t at its corner k.
double corner_angle(const TriangleMesh& mesh, int t, int k) {
  const Eigen::Vector3d& p = mesh.corner(t, k);
  const Eigen::Vector3d a = mesh.corner(t, (k + 1) % 3) - p;
  const Eigen::Vector3d b = mesh.corner(t, (k + 2) % 3) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

WallCornerValues::WallCornerValues(const TriangleMesh& mesh) {
  const auto& triangles = mesh.triangles();
  around_offsets_.assign(mesh.vertex_count() + 1, 0);
  for (const auto& tri : triangles)
    for (const int v : tri) ++around_offsets_[at(v) + 1];
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) around_offsets_[v + 1] += around_offsets_[v];
  around_.resize(3 * triangles.size());
  std::vector<int> next(around_offsets_.begin(), around_offsets_.end() - 1);
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t)
    for (int k = 0; k < 3; ++k) around_[at(next[at(triangles[at(t)][at(k)])]++)] = {t, k};
  normals_.resize(triangles.size());
  curvature_.resize(triangles.size());
}

void WallCornerValues::update(const TriangleMesh& mesh, std::span<const double> vertex_curvature,
                              double same_wall_cosine) {
  const auto& triangles = mesh.triangles();
  const auto& face_normals = mesh.face_normals();
  for (int t = 0; t < static_cast<int>(triangles.size()); ++t) {
    const Eigen::Vector3d& own = face_normals[at(t)];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles[at(t)][at(k)];
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      double neighbour_curvature = 0.0;
      int resolvable_neighbours = 0;
      for (int e = around_offsets_[at(v)]; e < around_offsets_[at(v) + 1]; ++e) {
        const auto [s, c] = around_[at(e)];
        const Eigen::Vector3d& n = face_normals[at(s)];
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
      normals_[at(t)][at(k)] = (mean - own).squaredNorm() < 1e-24 ? own : mean;
      const double h = vertex_curvature[at(v)];
      curvature_[at(t)][at(k)] =
          std::isfinite(h) ? h : (resolvable_neighbours > 0 ? neighbour_curvature / resolvable_neighbours : 0.0);
    }
  }
}

}  // namespace tankfsi::sph
