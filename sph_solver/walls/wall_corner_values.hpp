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
// normals are closer than same_wall_cosine (the contacts' rule, wall_contacts.hpp).
// Corner normal of triangle t at vertex v: the angle-weighted mean of the normals of
// the triangles around v on t's wall (Thuermer & Wuethrich 1998), exactly t's own
// normal where they agree to round-off (a flat wall stays exactly flat). Corner curvature:
// the vertex's mean curvature where the kernel resolves it, else (a vertex on a
// sharp edge) the mean of the resolvable curvatures of its neighbours on t's wall,
// else 0.
#include <Eigen/Core>

#include <array>
#include <span>
#include <vector>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct WallCornerValues {
  std::vector<std::array<Eigen::Vector3d, 3>> normals;  ///< per triangle and corner, unit
  std::vector<std::array<double, 3>> curvature;          ///< per triangle and corner (1/m)
};

/// `vertex_curvature`: per vertex, NaN where the kernel does not resolve it (a
/// sharp edge or corner). `same_wall_cosine`: the cosine below which two
/// triangles are different walls.
[[nodiscard]] WallCornerValues wall_corner_values(const TriangleMesh& mesh, std::span<const double> vertex_curvature,
                                                  double same_wall_cosine);

}  // namespace tankfsi::sph
