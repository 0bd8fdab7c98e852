#pragma once
// TriangleMesh: a wall surface (the FEM wetted surface, vertex for vertex) with the
// derived geometry the SPH wall terms need: unit face normals, areas, angle-weighted
// vertex normals and edge pseudo-normals, plus the fixed topology (neighbours across
// edges, boundary vertices).
//
// Normal convention: a triangle (a, b, c) has normal (b-a) x (c-a) / |...| (right-hand
// rule); the fluid is on the side the normal points to. A tank wall meshed for the
// fluid inside therefore has inward normals.
//
// Deforming walls: the topology never changes after construction, so it is analysed
// once; move_vertices() replaces the positions and recomputes only the per-face and
// per-vertex geometry in O(n) without allocating. Dependent structures (the
// TriangleIndex, curvatures) compare geometry_version() to know they are stale.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tankfsi::sph {

/// An edge used by one triangle only, directed as that triangle traverses it.
struct BoundaryEdge {
  int triangle = 0;
  int edge = 0;                    ///< local index k: vertices k and k+1 mod 3
  std::array<int, 2> vertices{};   ///< (from, to) in the triangle's order
};

class TriangleMesh {
 public:
  TriangleMesh() = default;
  /// Throws std::invalid_argument if an index is out of range or a coordinate is not
  /// finite (run check_topology() first for a full report). Degenerate triangles are
  /// accepted and get a zero normal and zero area.
  TriangleMesh(std::vector<Eigen::Vector3d> vertices, std::vector<std::array<int, 3>> triangles);

  [[nodiscard]] const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  [[nodiscard]] const std::vector<std::array<int, 3>>& triangles() const { return triangles_; }
  [[nodiscard]] std::size_t vertex_count() const { return vertices_.size(); }
  [[nodiscard]] std::size_t triangle_count() const { return triangles_.size(); }

  /// Vertex v of triangle t (v = 0, 1, 2).
  [[nodiscard]] const Eigen::Vector3d& corner(int t, int v) const {
    return vertices_[static_cast<std::size_t>(triangles_[static_cast<std::size_t>(t)][static_cast<std::size_t>(v)])];
  }

  /// Unit normals by the right-hand rule (zero for a degenerate triangle).
  [[nodiscard]] const std::vector<Eigen::Vector3d>& face_normals() const { return face_normals_; }
  [[nodiscard]] const std::vector<double>& face_areas() const { return face_areas_; }
  /// Angle-weighted vertex normals (Thürmer & Wüthrich 1998), unit: the pseudo-normal
  /// of Bærentzen & Aanæs 2005 at a vertex.
  [[nodiscard]] const std::vector<Eigen::Vector3d>& vertex_normals() const { return vertex_normals_; }
  /// Pseudo-normal of edge k of triangle t: the normalised sum of the two face normals
  /// (each face sees the edge under the angle π). The face normal on an open or
  /// non-manifold edge.
  [[nodiscard]] const Eigen::Vector3d& edge_normal(int t, int k) const {
    return edge_normals_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
  }
  /// Triangle across edge k of triangle t, or -1 on an open or non-manifold edge.
  [[nodiscard]] int neighbour(int t, int k) const {
    return neighbours_[static_cast<std::size_t>(t)][static_cast<std::size_t>(k)];
  }
  /// True for a vertex on an open or non-manifold edge.
  [[nodiscard]] bool is_boundary_vertex(int v) const { return boundary_vertex_[static_cast<std::size_t>(v)] != 0; }
  /// Edges used by exactly one triangle (an open-top tank has its rim here).
  [[nodiscard]] const std::vector<BoundaryEdge>& boundary_edges() const { return boundary_edges_; }

  [[nodiscard]] Eigen::AlignedBox3d bounding_box() const;

  /// Replaces the vertex positions (same count, same order) and recomputes the
  /// derived geometry; the topology is kept. Throws std::invalid_argument on a size
  /// mismatch or a non-finite coordinate.
  void move_vertices(std::span<const Eigen::Vector3d> positions);
  /// Incremented by every move_vertices(), so dependants can tell they are stale.
  [[nodiscard]] std::uint64_t geometry_version() const { return geometry_version_; }

 private:
  void analyse_topology();
  void compute_geometry();

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<std::array<int, 3>> triangles_;
  std::vector<std::array<int, 3>> neighbours_;
  std::vector<unsigned char> boundary_vertex_;
  std::vector<BoundaryEdge> boundary_edges_;
  std::vector<Eigen::Vector3d> face_normals_;
  std::vector<double> face_areas_;
  std::vector<Eigen::Vector3d> vertex_normals_;
  std::vector<std::array<Eigen::Vector3d, 3>> edge_normals_;
  std::uint64_t geometry_version_ = 0;
};

}  // namespace tankfsi::sph
