#pragma once
// Discrete mean curvature of a wall mesh at its vertices, by Meyer, Desbrun,
// Schröder & Barr, "Discrete differential-geometry operators for triangulated
// 2-manifolds", VisMath 2002 / Springer 2003 (eqs 8 and the mixed area of Fig. 4):
//
//   K(x_i) = 1/(2 A_mixed) Σ_j (cot α_ij + cot β_ij) (x_i − x_j),   H_i = ½ K(x_i)·n_i,
//
// α_ij, β_ij the angles opposite edge ij, A_mixed the Voronoi area of vertex i, with
// the obtuse-triangle rule (area/2 at an obtuse corner, area/4 at the other corners of
// an obtuse triangle), n_i the mesh's angle-weighted vertex normal.
//
// Sign convention: H > 0 where the wall bulges towards the side its normals point to
// (the fluid side), H < 0 where it is hollow seen from the fluid. A sphere of radius R
// with outward normals has H = +1/R; the fluid inside a cylindrical tank of radius R
// (inward normals) sees H = −1/(2R); a flat wall has H = 0.
//
// Boundary vertices (on an open or non-manifold edge, e.g. the rim of an open-top
// tank) have no complete one-ring, and Meyer's formula there measures the missing
// ring, not the surface. They get the mean of H over their interior neighbours (the
// one-sided extrapolation along the surface; the rim of a cylinder gets the
// cylinder's value), or 0 if none of their neighbours is interior.
//
// Degenerate (zero-area) triangles contribute nothing (their cotangents are undefined).
//
// Accuracy (tests/unit/sph/test_wall_curvature.cpp): second order on an icosphere
// (max |H R − 1| = 1.9e-6 at 10242 vertices), exact to round-off on a structured
// cylinder, but on irregular meshes the pointwise value scatters by O(1) of the
// irregularity and does not converge with refinement (a known property of the
// cotangent operator: Hildebrandt, Polthier & Wardetzky 2006) — vertices jittered by
// 20% of the spacing give 12% mean, ~50% max error on a cylinder. Walls meshed with
// structured FEM grids are unaffected; for unstructured walls, smooth H over the
// one-ring before use.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>
#include <vector>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

/// H at every vertex, into `curvature` (resized; storage is reused across calls for a
/// deforming wall). O(n).
void compute_vertex_mean_curvature(const TriangleMesh& mesh, std::vector<double>& curvature);

[[nodiscard]] std::vector<double> vertex_mean_curvature(const TriangleMesh& mesh);

}  // namespace tankfsi::sph
