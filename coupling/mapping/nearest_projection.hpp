#pragma once
// NearestProjection: interface values between the partner's mesh and a
// program's own surface vertices when the two do not match (PROTOCOL.md,
// "Non-matching interfaces"). Each own vertex is projected onto the nearest
// triangle of the partner's mesh; the barycentric weights w_ij of that point
// (i own vertex, j mesh vertex) give
//   consistent  (displacements):  u_i = sum_j w_ij U_j   (linear fields exactly),
//   conservative (forces):        F_j = sum_i w_ij f_i   (total force exactly,
//                                 moment about the projected points exactly).
// The weights are set once, in the reference configuration.
#include <array>
#include <span>
#include <vector>

#include "coupling/interface/interface_mesh.hpp"

namespace tankfsi::coupling {

class NearestProjection {
 public:
  /// `points`: 3 coordinates per own vertex. The mesh needs triangles.
  NearestProjection(const InterfaceMesh& mesh, std::span<const double> points);

  [[nodiscard]] std::size_t point_count() const { return weights_.size(); }
  [[nodiscard]] std::size_t mesh_vertex_count() const { return mesh_vertices_; }
  /// The largest distance of an own vertex from the mesh (m): a check that
  /// the two surfaces are the same surface.
  [[nodiscard]] double max_distance() const { return max_distance_; }
  /// Each point's distance from the mesh (m).
  [[nodiscard]] const std::vector<double>& distances() const { return distances_; }

  /// Mesh values (3 per mesh vertex) -> own values (3 per point).
  void consistent(std::span<const double> mesh_values, std::span<double> point_values) const;
  /// Own values (3 per point) -> mesh values (3 per mesh vertex), overwritten.
  void conservative(std::span<const double> point_values, std::span<double> mesh_values) const;

 private:
  struct Projection {
    std::array<int, 3> vertices{};
    std::array<double, 3> weights{};
  };
  std::vector<Projection> weights_;
  std::size_t mesh_vertices_ = 0;
  double max_distance_ = 0.0;
  std::vector<double> distances_;
};

}  // namespace tankfsi::coupling
