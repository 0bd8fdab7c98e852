#pragma once
// Whether a wall mesh can hold the liquid: the checks a read or generated wall
// passes before any particle is placed, each failure a message naming the
// triangles, vertices and coordinates involved (so the mesh can be mended in the
// modelling tool, not debugged in the solver).
//
//  - topology (mesh_topology.hpp): no degenerate triangle, no edge used by three
//    or more triangles, neighbours oriented alike;
//  - open edges only where the liquid cannot leak: above the fill level (the rim
//    of an open-top tank) or, in 2D, on the section's front and back planes (the
//    extreme z of the mesh, which the particles at z = 0 never reach);
//  - normals into the liquid (triangle_mesh.hpp's convention): the signed volume
//    Σ (a−o)·((b−o)×(c−o))/6 of the surface is negative for inward normals. For an
//    open surface it is taken about o = the mean of its open-edge vertices, which
//    is the volume of the surface closed by a cone from o — the same sign as the
//    enclosed liquid's for a tank open at its rim or a 2D section open at its
//    faces. A mesh with outward normals is called inverted;
//  - no self-intersection: two triangles that share no vertex must not meet; two
//    that share one vertex must not meet elsewhere (the edge opposite the shared
//    vertex of either must not cross the other; a non-coplanar pair meeting
//    beyond the shared vertex always shows this). Coplanar overlapping triangles
//    are found by the same edge tests made in their plane. Candidate pairs come
//    from the triangle index (every triangle within the other's circumscribing
//    sphere about its centroid), so the check is O(n log n) for a mesh with
//    triangles of comparable size.
//
// The checks stop at the first kind of problem found, in the order above, and
// report up to five instances.
#include <Eigen/Core>
#include <string>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct WallCheckOptions {
  int dimension = 3;
  double fill_level = 0.0;  ///< height (y in 2D, z in 3D) of the still liquid
  /// Lengths below this fraction of the mesh's bounding-box diagonal count as
  /// zero in the plane tests (the open planes of a 2D section, coplanarity).
  double relative_tolerance = 1e-9;
};

/// Empty when the walls pass every check, else the description of the first
/// problem (several lines when several instances are reported).
[[nodiscard]] std::string wall_mesh_problem(const TriangleMesh& mesh, const WallCheckOptions& options);

}  // namespace tankfsi::sph
