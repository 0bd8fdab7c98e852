#pragma once
// The normal and mean curvature of the smooth wall each triangle belongs to, at
// each of its three corners: what the particles see of a faceted curved wall.
//
// Why. A cylinder made of flat triangles has a normal that jumps by the facets'
// angle from one triangle to the next, and the nearest triangle of a particle
// changes as it moves along the wall: the wall terms' direction then jumps too,
// pushing the liquid along the wall at every edge. Interpolating the corner
// normals at the closest point (Phong) turns the facets back into the smooth wall
// they approximate. Where a curved wall meets another one at a sharp edge (a tank's
// wall and its bottom), the vertex on the edge has no single normal or curvature;
// each triangle takes the values of its own wall there.
//
// Walls: two triangles sharing a vertex belong to the same wall there when their
// normals are closer than same_wall_cosine (below; the contacts' rule, wall_contacts.hpp).
// Corner normal of triangle t at vertex v: the angle-weighted mean of the normals of
// the triangles around v on t's wall (Thuermer & Wuethrich 1998), exactly t's own
// normal where they agree to round-off (a flat wall stays exactly flat). Corner
// curvature: the vertex's mean curvature where the kernel resolves it and all
// triangles around the vertex are one wall, else (a vertex on a sharp edge, however
// large its triangles) the mean of such curvatures of its neighbours on t's wall,
// else 0.
//
// The triangles around each vertex are found once per mesh; update() follows a
// moving wall (same topology) every step without allocating.
#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

/// Normals closer than this (cos of ~37°) belong to the same wall: the rule of the
/// corner values here, of the wall contacts and of the filling's clearance.
inline constexpr double same_wall_cosine = 0.8;

class WallCornerValues {
 public:
  /// The topology of `mesh` (its triangles around each vertex); no values yet.
  explicit WallCornerValues(const TriangleMesh& mesh);

  /// The values for the mesh's current positions (the topology given at
  /// construction). `vertex_curvature`: per vertex, NaN where the kernel does not
  /// resolve it (a sharp edge or corner).
  void update(const TriangleMesh& mesh, std::span<const double> vertex_curvature);

  /// Unit normals of triangle t's wall at its corners.
  [[nodiscard]] const std::array<Eigen::Vector3d, 3>& normals(int t) const { return normals_[at(t)]; }
  /// How far the smooth wall lies behind triangle t's plane at barycentric weights
  /// w (m; negative where it bulges out of the plane towards the fluid): the
  /// quadratic through the corners whose normal curvature along each edge the
  /// corner normals give, depth = -1/2 sum_{i<j} w_i w_j (n_j - n_i).(x_j - x_i).
  /// On a faceted cylinder of radius R (vertices on it, corner normals radial)
  /// this is (R^2 - r^2) / (2R), R - r to second order; on a sphere the same to
  /// the corner normals' accuracy; 0 on a flat wall.
  [[nodiscard]] double smooth_depth(const TriangleMesh& mesh, int t, const Eigen::Vector3d& w) const;
  /// The largest normal curvature of triangle t's smooth wall along its edges,
  /// max |(n_j - n_i).(x_j - x_i)| / |x_j - x_i|^2 (1/m): 1/R across a faceted
  /// cylinder's chords and on a sphere, 0 on a flat wall. smooth_depth() falls
  /// short of the distance to the curved wall by about depth^2 times half of it
  /// (the quadratic's second-order error: sagitta^2 / (2R) on a cylinder).
  [[nodiscard]] double largest_edge_curvature(const TriangleMesh& mesh, int t) const;
  /// The largest |smooth_depth()| of any triangle of `mesh` (m): how far the facets
  /// lie from the smooth wall they stand for (on a faceted cylinder the sagitta
  /// c^2 / (8R) of its chords c). Each triangle is sampled on the barycentric grid
  /// of step 1/6, which holds its edges' midpoints and its centroid, where the
  /// quadratic has its extremes on a cylinder and on a sphere.
  [[nodiscard]] double largest_smooth_depth(const TriangleMesh& mesh) const;
  /// Mean curvature of triangle t's wall at barycentric weights w (1/m).
  [[nodiscard]] double curvature_at(int t, const Eigen::Vector3d& w) const {
    const auto& h = curvature_[at(t)];
    return w[0] * h[0] + w[1] * h[1] + w[2] * h[2];
  }
  /// The traceless part of triangle t's shape operator (1/m, 3 x 3, in the
  /// triangle's plane): K - (tr K / 2) P, K the symmetric part of the gradient of
  /// the corner normals' linear interpolation, P the projector onto the plane.
  /// Its normal curvature along each edge, e^T K e / |e|^2 = (n_j - n_i).e / |e|^2,
  /// is the one smooth_depth() takes; its trace is left to the mean curvature
  /// (Meyer's, curvature_at()). On a faceted cylinder of radius R with radial
  /// corner normals it is (1/2R) (a a^T - t t^T) to the facets' accuracy (a the
  /// axis, t the direction around it; sign: the front normals' curvature, K =
  /// -(1/R) t t^T for normals pointing inwards), 0 on a sphere and a flat wall:
  /// what tells a wall curved one way from one curved both ways, which the wall
  /// contacts' tangential moment needs (wall_contacts.hpp). 0 in 2D use.
  [[nodiscard]] const Eigen::Matrix3d& shape_deviator(int t) const { return shape_deviator_[at(t)]; }

 private:
  static std::size_t at(int i) { return static_cast<std::size_t>(i); }

  std::vector<int> around_offsets_;               ///< CSR over vertices
  std::vector<std::array<int, 2>> around_;        ///< (triangle, its corner index at the vertex)
  std::vector<std::array<Eigen::Vector3d, 3>> normals_;
  std::vector<std::array<double, 3>> curvature_;
  std::vector<Eigen::Matrix3d> shape_deviator_;
  std::vector<double> wall_curvature_;  ///< per vertex: NaN where walls meet (scratch of update)
};

}  // namespace tankfsi::sph
