#pragma once
// Initial fluid particles: a lattice of spacing L₀ (square in the plane z = 0 in 2D,
// cubic in 3D) filling a wall mesh up to a level, the way the wall tables of eq 10
// assume it (METHOD.md §2): the first layer lies L₀/2 from a wall, mirroring the
// virtual wall particles L₀/2 behind it.
//
// A lattice point x = origin + (i + 1/2, j + 1/2, k + 1/2) L₀ becomes a particle when
//  - the signed distance of the walls at x (TriangleIndex nearest triangle, sign by the
//    pseudo-normal: positive on the fluid side; to the smooth wall behind it where the
//    facets approximate a curved one, WallCornerValues::smooth_depth, as the wall
//    contacts measure it) is >= L₀/2 - 2e-3 L₀, i.e. x is inside and at least half a
//    spacing from every wall (the tolerance absorbs the round-off of points exactly
//    L₀/2 from a flat wall; the smooth wall's second-order error, depth² times its
//    curvature, is allowed for apart, filling.cpp), and x lies in front of the
//    nearest facet itself (by 2e-3 L₀ at least): the particles stop at the facets;
//  - its height (y in 2D, z in 3D) is below the fill level (strictly): the particles
//    whose cells are centred below the free surface, so the filled depth is the level
//    rounded to a whole number of layers;
//  - it lies in the optional region (an axis-aligned box, closed; in 2D only its x and y
//    extents count), e.g. the water column of a dam break.
// With the origin on a flat floor (the default origin is the walls' bounding-box
// minimum) the floor's first layer is at L₀/2 and a side wall whose distance from the
// origin is a multiple of L₀ gets its first column at L₀/2.
//
// 2D: the particles are at z = 0 and only the wall faces whose normal lies in the plane
// (|n_z| <= 1e-6) are used, so a closed thin box with front and back faces fills like
// the open extruded walls of tank_meshes.hpp. The walls must straddle the plane z = 0.
//
// Cylindrical tanks (cylinder_radius, 3D): a cubic lattice leaves gaps of up to L₀
// between its outer particles and a curved wall, into which the liquid falls at the
// start (measured: the wall force drops to half the weight in 0.02 s). Rings follow
// the wall instead: layer k at z = (k + 1/2) L₀, ring m at radius
// r_m = R - (m + 1/2) L₀ (m = 0, 1, ... while r_m > 0; R the radius of the smooth
// cylinder the wall's facets approximate) with n_m = max(1, round(2π r_m / L₀))
// particles, every other ring turned by half a pitch; each particle's volume is its
// share of its annulus, 2π r_m L₀ / n_m times L₀ (the innermost: the disc of radius
// r_m + L₀/2 over n_m), so the masses sum to ρ π R² times the filled depth exactly.
// The same clearance and level tests apply.
//
// Each lattice particle gets mass ρ L₀^D, zero velocity, and pressure zero or hydrostatic
// ρ g (surface - height), the surface being the top of the highest particle layer
// (the level itself when it falls on a layer boundary). Ids are 0..N-1 in lattice
// order, x fastest, then y, then z. The result depends on the walls and the spec only,
// so every rank computes the same particles and keeps its own share.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>

#include "sph_solver/particles/particles.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct FillSpec {
  double spacing = 0.0;     ///< L₀
  double density = 0.0;     ///< ρ₀
  double fill_level = 0.0;  ///< height of the free surface: y in 2D, z in 3D
  int dimension = 3;        ///< 2 or 3
  std::optional<Eigen::AlignedBox3d> region;         ///< keep only particles inside (2D: x and y)
  std::optional<Eigen::Vector3d> lattice_origin;      ///< default: the walls' bounding-box minimum
  /// 3D upright cylinder about the z axis: rings instead of the cubic lattice
  /// (see below), inside this radius (the smooth cylinder the wall's facets
  /// approximate, as the wall contacts measure it).
  std::optional<double> cylinder_radius;
  bool hydrostatic_pressure = false;                  ///< else zero pressure
  double gravity = 9.81;                              ///< |g| for the hydrostatic pressure
};

/// The particles of a tank filled as described above. Builds its own TriangleIndex of
/// the walls (of the in-plane faces in 2D). Throws std::invalid_argument on a bad spec
/// (non-positive spacing or density, dimension not 2 or 3, non-finite values), walls
/// without triangles, 2D walls that do not straddle z = 0, or a fill that yields no
/// particle (level below the floor, region outside the walls).
[[nodiscard]] Particles fill_tank(const TriangleMesh& walls, const FillSpec& spec);

}  // namespace tankfsi::sph
