#include "sph_solver/walls/triangle_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "sph_solver/walls/mesh_topology.hpp"

namespace tankfsi::sph {

namespace {

void require_finite(std::span<const Eigen::Vector3d> positions) {
  for (std::size_t v = 0; v < positions.size(); ++v)
    if (!positions[v].allFinite())
      throw std::invalid_argument("TriangleMesh: vertex " + std::to_string(v) + " has a non-finite coordinate");
}

Eigen::Vector3d normalised_or_zero(const Eigen::Vector3d& x) {
  const double length = x.norm();
  return length > 0.0 ? Eigen::Vector3d(x / length) : Eigen::Vector3d::Zero();
}

}  // namespace

TriangleMesh::TriangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<std::array<int, 3>> triangles)
    : vertices_(std::move(vertices)), triangles_(std::move(triangles)) {
  require_finite(vertices_);
  for (std::size_t t = 0; t < triangles_.size(); ++t)
    for (const int v : triangles_[t])
      if (v < 0 || static_cast<std::size_t>(v) >= vertices_.size())
        throw std::invalid_argument("TriangleMesh: triangle " + std::to_string(t) + " has vertex index " +
                                    std::to_string(v) + ", out of range (" + std::to_string(vertices_.size()) +
                                    " vertices)");
  analyse_topology();
  compute_geometry();
}

void TriangleMesh::analyse_topology() {
  neighbours_.assign(triangles_.size(), {-1, -1, -1});
  boundary_vertex_.assign(vertices_.size(), 0);
  boundary_edges_.clear();
  for_each_edge(triangles_, vertices_.size(), [&](std::span<const HalfEdge> uses) {
    if (uses.size() == 2) {
      neighbours_[static_cast<std::size_t>(uses[0].triangle)][static_cast<std::size_t>(uses[0].edge)] = uses[1].triangle;
      neighbours_[static_cast<std::size_t>(uses[1].triangle)][static_cast<std::size_t>(uses[1].edge)] = uses[0].triangle;
      return;
    }
    for (const auto& h : uses) {
      boundary_vertex_[static_cast<std::size_t>(h.from)] = 1;
      boundary_vertex_[static_cast<std::size_t>(h.to)] = 1;
    }
    if (uses.size() == 1) boundary_edges_.push_back({uses[0].triangle, uses[0].edge, {uses[0].from, uses[0].to}});
  });
}

void TriangleMesh::compute_geometry() {
  const std::size_t n = triangles_.size();
  face_normals_.resize(n);
  face_areas_.resize(n);
  edge_normals_.resize(n);
  vertex_normals_.assign(vertices_.size(), Eigen::Vector3d::Zero());
  for (std::size_t t = 0; t < n; ++t) {
    const auto& tri = triangles_[t];
    const Eigen::Vector3d& a = vertices_[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3d& b = vertices_[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3d& c = vertices_[static_cast<std::size_t>(tri[2])];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    face_areas_[t] = 0.5 * cross.norm();
    face_normals_[t] = normalised_or_zero(cross);
    // Angle-weighted vertex normals: the weight is the corner angle, computed with
    // atan2(|e1 x e2|, e1.e2), accurate for small and near-π angles alike.
    const std::array<const Eigen::Vector3d*, 3> x{&a, &b, &c};
    for (std::size_t k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = *x[(k + 1) % 3] - *x[k];
      const Eigen::Vector3d e2 = *x[(k + 2) % 3] - *x[k];
      const double angle = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      vertex_normals_[static_cast<std::size_t>(tri[k])] += angle * face_normals_[t];
    }
  }
  for (auto& normal : vertex_normals_) normal = normalised_or_zero(normal);
  for (std::size_t t = 0; t < n; ++t)
    for (std::size_t k = 0; k < 3; ++k) {
      const int other = neighbours_[t][k];
      const Eigen::Vector3d sum =
          other < 0 ? face_normals_[t] : Eigen::Vector3d(face_normals_[t] + face_normals_[static_cast<std::size_t>(other)]);
      // A folded edge (the two faces back to back) has no pseudo-normal: keep the face's.
      const Eigen::Vector3d unit = normalised_or_zero(sum);
      edge_normals_[t][k] = unit.squaredNorm() > 0.0 ? unit : face_normals_[t];
    }
}

Eigen::AlignedBox3d TriangleMesh::bounding_box() const {
  Eigen::AlignedBox3d box;
  for (const auto& x : vertices_) box.extend(x);
  return box;
}

void TriangleMesh::move_vertices(std::span<const Eigen::Vector3d> positions) {
  if (positions.size() != vertices_.size())
    throw std::invalid_argument("TriangleMesh::move_vertices: " + std::to_string(positions.size()) +
                                " positions given for " + std::to_string(vertices_.size()) + " vertices");
  require_finite(positions);
  std::copy(positions.begin(), positions.end(), vertices_.begin());
  compute_geometry();
  ++geometry_version_;
}

}  // namespace tankfsi::sph
