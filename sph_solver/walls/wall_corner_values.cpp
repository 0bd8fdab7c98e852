#include "sph_solver/walls/wall_corner_values.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tankfsi::sph {
namespace {

/// The interior angle of triangle t at its corner k.
double corner_angle(const TriangleMesh& mesh, int t, int k) {
  const Eigen::Vector3d& p = mesh.corner(t, k);
  const Eigen::Vector3d a = mesh.corner(t, (k + 1) % 3) - p;
  const Eigen::Vector3d b = mesh.corner(t, (k + 2) % 3) - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// The traceless shape operator of triangle t from its corner normals (see the
/// header): n(x) = sum_k lambda_k(x) n_k has the gradient G = sum_k n_k grad(lambda_k)^T,
/// grad(lambda_k) = nu x (x_{k+2} - x_{k+1}) / |c|, c = (x_1 - x_0) x (x_2 - x_0),
/// nu = c / |c|. Zero where the corners share one normal (a flat wall, bit for bit).
Eigen::Matrix3d shape_deviator_of(const TriangleMesh& mesh, int t, const std::array<Eigen::Vector3d, 3>& normals) {
  if (normals[0] == normals[1] && normals[1] == normals[2]) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d cross = (mesh.corner(t, 1) - mesh.corner(t, 0)).cross(mesh.corner(t, 2) - mesh.corner(t, 0));
  const double twice_area = cross.norm();
  if (!(twice_area > 0.0)) return Eigen::Matrix3d::Zero();
  const Eigen::Vector3d nu = cross / twice_area;
  Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d edge = mesh.corner(t, (k + 2) % 3) - mesh.corner(t, (k + 1) % 3);
    gradient += normals[static_cast<std::size_t>(k)] * (nu.cross(edge) / twice_area).transpose();
  }
  const Eigen::Matrix3d plane = Eigen::Matrix3d::Identity() - nu * nu.transpose();
  const Eigen::Matrix3d in_plane = plane * gradient * plane;
  const Eigen::Matrix3d shape = 0.5 * (in_plane + in_plane.transpose());
  return shape - 0.5 * shape.trace() * plane;
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
  shape_deviator_.resize(triangles.size());
  wall_curvature_.resize(mesh.vertex_count());
}

void WallCornerValues::update(const TriangleMesh& mesh, std::span<const double> vertex_curvature) {
  const auto& triangles = mesh.triangles();
  const auto& face_normals = mesh.face_normals();
  // A vertex where triangles of different walls meet lies on an edge or corner of
  // the solid: Meyer's value there is the edge's angle spread over the triangles'
  // areas — as gentle as a real curve's when they are large (a CAD box's two
  // triangles per face, 1 x 1 x 0.6 m, gave its walls H = -1.36 1/m, their tables 7 %
  // too large) — and no curvature of either wall.
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    bool one_wall = true;
    for (int e = around_offsets_[v]; e < around_offsets_[v + 1] && one_wall; ++e)
      for (int f = e + 1; f < around_offsets_[v + 1] && one_wall; ++f)
        one_wall = face_normals[at(around_[at(e)][0])].dot(face_normals[at(around_[at(f)][0])]) > same_wall_cosine;
    wall_curvature_[v] = one_wall ? vertex_curvature[v] : std::numeric_limits<double>::quiet_NaN();
  }
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
          const double h = wall_curvature_[at(triangles[at(s)][at((c + j) % 3)])];
          if (std::isfinite(h)) {
            neighbour_curvature += h;
            ++resolvable_neighbours;
          }
        }
      }
      // Normals that agree to round-off (a flat wall) give exactly the triangle's own.
      const Eigen::Vector3d mean = sum.norm() > 0.0 ? Eigen::Vector3d(sum.normalized()) : own;
      normals_[at(t)][at(k)] = (mean - own).squaredNorm() < 1e-24 ? own : mean;
      const double h = wall_curvature_[at(v)];
      curvature_[at(t)][at(k)] =
          std::isfinite(h) ? h : (resolvable_neighbours > 0 ? neighbour_curvature / resolvable_neighbours : 0.0);
    }
    shape_deviator_[at(t)] = shape_deviator_of(mesh, t, normals_[at(t)]);
  }
}

double WallCornerValues::smooth_depth(const TriangleMesh& mesh, int t, const Eigen::Vector3d& w) const {
  const auto& n = normals_[at(t)];
  double depth = 0.0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    depth -= 0.5 * w[i] * w[j] * (n[at(j)] - n[at(i)]).dot(mesh.corner(t, j) - mesh.corner(t, i));
  }
  return depth;
}

double WallCornerValues::largest_edge_curvature(const TriangleMesh& mesh, int t) const {
  const auto& n = normals_[at(t)];
  double largest = 0.0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Eigen::Vector3d edge = mesh.corner(t, j) - mesh.corner(t, i);
    largest = std::max(largest, std::abs((n[at(j)] - n[at(i)]).dot(edge)) / edge.squaredNorm());
  }
  return largest;
}

double WallCornerValues::largest_smooth_depth(const TriangleMesh& mesh) const {
  constexpr int steps = 6;
  double largest = 0.0;
  for (int t = 0; t < static_cast<int>(mesh.triangle_count()); ++t)
    for (int a = 0; a <= steps; ++a)
      for (int b = 0; a + b <= steps; ++b) {
        const Eigen::Vector3d w(a, b, steps - a - b);
        largest = std::max(largest, std::abs(smooth_depth(mesh, t, w / steps)));
      }
  return largest;
}

}  // namespace tankfsi::sph
