#include "coupling/mapping/nearest_projection.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/geometry/triangle_closest_point.hpp"

namespace tankfsi::coupling {

namespace {

// Triangles binned by their bounding boxes on a uniform grid; a query searches
// rings of cells around the point until no nearer triangle can remain.
class TriangleGrid {
 public:
  TriangleGrid(const std::vector<Eigen::Vector3d>& x, const std::vector<std::array<int, 3>>& triangles)
      : x_(x), triangles_(triangles) {
    Eigen::AlignedBox3d all;
    double diagonal_sum = 0.0;
    for (const auto& t : triangles) {
      Eigen::AlignedBox3d box;
      for (int v : t) box.extend(x[static_cast<std::size_t>(v)]);
      diagonal_sum += box.diagonal().norm();
      all.extend(box);
    }
    cell_ = std::max(2.0 * diagonal_sum / static_cast<double>(triangles.size()), 1e-12 * (1.0 + all.diagonal().norm()));
    origin_ = all.min();
    for (int d = 0; d < 3; ++d)
      cells_[static_cast<std::size_t>(d)] = std::max(1, static_cast<int>(std::ceil(all.sizes()[d] / cell_)) + 1);
    bins_.resize(static_cast<std::size_t>(cells_[0]) * static_cast<std::size_t>(cells_[1]) *
                 static_cast<std::size_t>(cells_[2]));
    for (std::size_t t = 0; t < triangles.size(); ++t) {
      Eigen::AlignedBox3d box;
      for (int v : triangles[t]) box.extend(x[static_cast<std::size_t>(v)]);
      const auto lo = cell_of(box.min()), hi = cell_of(box.max());
      for (int i = lo[0]; i <= hi[0]; ++i)
        for (int j = lo[1]; j <= hi[1]; ++j)
          for (int k = lo[2]; k <= hi[2]; ++k) bins_[index(i, j, k)].push_back(static_cast<int>(t));
    }
  }

  /// The nearest triangle to p and the closest point on it.
  std::pair<int, ClosestPoint> nearest(const Eigen::Vector3d& p) const {
    const auto home = cell_of(p);
    int best = -1;
    ClosestPoint best_point;
    best_point.squared_distance = std::numeric_limits<double>::infinity();
    const int rings = *std::max_element(cells_.begin(), cells_.end());
    for (int r = 0; r <= rings; ++r) {
      for (int i = home[0] - r; i <= home[0] + r; ++i)
        for (int j = home[1] - r; j <= home[1] + r; ++j)
          for (int k = home[2] - r; k <= home[2] + r; ++k) {
            if (std::max({std::abs(i - home[0]), std::abs(j - home[1]), std::abs(k - home[2])}) != r) continue;
            if (i < 0 || j < 0 || k < 0 || i >= cells_[0] || j >= cells_[1] || k >= cells_[2]) continue;
            for (int t : bins_[index(i, j, k)]) {
              const auto& tri = triangles_[static_cast<std::size_t>(t)];
              const ClosestPoint c = closest_point_on_triangle(p, x_[static_cast<std::size_t>(tri[0])],
                                                               x_[static_cast<std::size_t>(tri[1])],
                                                               x_[static_cast<std::size_t>(tri[2])]);
              if (c.squared_distance < best_point.squared_distance) {
                best = t;
                best_point = c;
              }
            }
          }
      // A triangle not met yet lies in cells of ring r + 1 or beyond only,
      // at least r cells from p's (clamped) home cell in some axis.
      const double reach = r * cell_;
      if (best >= 0 && best_point.squared_distance <= reach * reach) break;
    }
    return {best, best_point};
  }

 private:
  [[nodiscard]] std::array<int, 3> cell_of(const Eigen::Vector3d& p) const {
    std::array<int, 3> c{};
    for (int d = 0; d < 3; ++d)
      c[static_cast<std::size_t>(d)] =
          std::clamp(static_cast<int>(std::floor((p[d] - origin_[d]) / cell_)), 0, cells_[static_cast<std::size_t>(d)] - 1);
    return c;
  }
  [[nodiscard]] std::size_t index(int i, int j, int k) const {
    return (static_cast<std::size_t>(k) * static_cast<std::size_t>(cells_[1]) + static_cast<std::size_t>(j)) *
               static_cast<std::size_t>(cells_[0]) +
           static_cast<std::size_t>(i);
  }

  const std::vector<Eigen::Vector3d>& x_;
  const std::vector<std::array<int, 3>>& triangles_;
  double cell_ = 1.0;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  std::array<int, 3> cells_{1, 1, 1};
  std::vector<std::vector<int>> bins_;
};

}  // namespace

NearestProjection::NearestProjection(const InterfaceMesh& mesh, std::span<const double> points) {
  if (mesh.triangles.empty()) throw std::invalid_argument("nearest-projection mapping: the partner's mesh has no triangles");
  if (points.size() % 3 != 0) throw std::invalid_argument("nearest-projection mapping: 3 coordinates per vertex expected");
  mesh_vertices_ = mesh.vertex_count();
  std::vector<Eigen::Vector3d> x(mesh_vertices_);
  for (std::size_t v = 0; v < mesh_vertices_; ++v)
    x[v] = Eigen::Vector3d(mesh.coordinates[3 * v], mesh.coordinates[3 * v + 1], mesh.coordinates[3 * v + 2]);
  const TriangleGrid grid(x, mesh.triangles);
  weights_.resize(points.size() / 3);
  for (std::size_t i = 0; i < weights_.size(); ++i) {
    const Eigen::Vector3d p(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    const auto [t, closest] = grid.nearest(p);
    weights_[i].vertices = mesh.triangles[static_cast<std::size_t>(t)];
    for (int k = 0; k < 3; ++k) weights_[i].weights[static_cast<std::size_t>(k)] = closest.barycentric[k];
    distances_.push_back(std::sqrt(closest.squared_distance));
    max_distance_ = std::max(max_distance_, distances_.back());
  }
}

void NearestProjection::consistent(std::span<const double> mesh_values, std::span<double> point_values) const {
  if (mesh_values.size() != 3 * mesh_vertices_ || point_values.size() != 3 * weights_.size())
    throw std::invalid_argument("nearest-projection mapping: array sizes do not match the meshes");
  for (std::size_t i = 0; i < weights_.size(); ++i)
    for (std::size_t c = 0; c < 3; ++c) {
      double value = 0.0;
      for (std::size_t k = 0; k < 3; ++k)
        value += weights_[i].weights[k] * mesh_values[3 * static_cast<std::size_t>(weights_[i].vertices[k]) + c];
      point_values[3 * i + c] = value;
    }
}

void NearestProjection::conservative(std::span<const double> point_values, std::span<double> mesh_values) const {
  if (mesh_values.size() != 3 * mesh_vertices_ || point_values.size() != 3 * weights_.size())
    throw std::invalid_argument("nearest-projection mapping: array sizes do not match the meshes");
  std::fill(mesh_values.begin(), mesh_values.end(), 0.0);
  for (std::size_t i = 0; i < weights_.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k)
      for (std::size_t c = 0; c < 3; ++c)
        mesh_values[3 * static_cast<std::size_t>(weights_[i].vertices[k]) + c] += weights_[i].weights[k] * point_values[3 * i + c];
}

}  // namespace tankfsi::coupling
