#pragma once
// Wall meshes of the paper's tanks (METHOD.md §5), built in code with the normals into
// the fluid: the open 2D rectangular tank, the 2D overflow set-up of paper §3 (inner
// tank of thin plates standing in a catch tank) and the upright 3D cylinder with a flat
// bottom and an optional dome roof (paper §4).
//
// 2D walls. The particles lie in the plane z = 0 and a 2D wall is a polyline of the xy
// plane extruded over z in [-depth/2, +depth/2] (the paper's tank is 2 cm deep), one
// layer of quads across the depth, each split in two triangles. Every face normal has
// z = 0. No front or back faces are built: they would be parallel to the plane of the
// particles at depth/2 from every particle, nearer than the real walls for most of
// them, and would capture the nearest-triangle queries (eq 15). Without them the mesh
// is open in z — its boundary edges lie at z = ±depth/2, at least depth/2 from every
// particle — and the signed distance of a point of the plane z = 0 comes from the
// polyline's faces, edges and corner lines: positive on the fluid side inside the tank,
// negative behind a wall (checked in test_tank_meshes.cpp).
//
// The cylinder is watertight when it has a roof: the bottom disc, the wall and the roof
// share their ring vertices, so TriangleMesh::boundary_edges() is empty and the signed
// distance is the exact Bærentzen–Aanæs one everywhere.
#include <Eigen/Core>
#include <optional>
#include <span>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

/// A 2D wall: the polyline points[0], points[1], ... of the plane z = 0 (x, y given)
/// extruded over z in [-depth/2, depth/2]. The fluid is on the left of the direction of
/// travel (the direction rotated by +90° about z). Each segment is split into
/// ceil(length / target_edge) equal pieces; corners are shared vertices. Quads split
/// along alternating diagonals, so the triangulation has no built-in twist. The
/// polyline is open (its first and last points are the rim); consecutive points must
/// differ. Throws std::invalid_argument on fewer than two points, a zero-length segment
/// or a non-positive depth or target_edge.
[[nodiscard]] TriangleMesh extrude_polyline(std::span<const Eigen::Vector2d> points, double depth,
                                            double target_edge);

/// Open-top rectangular tank of the 2D cases: floor y = 0 for x in [0, width], side
/// walls x = 0 and x = width from y = 0 to y = height, extruded over depth; normals
/// into the tank. (Paper §3: width 2.00 m, depth 0.02 m.)
[[nodiscard]] TriangleMesh make_rectangular_tank_2d(double width, double height, double depth, double target_edge);

/// The overflow set-up of paper §3: an inner tank (interior x in [0, inner_width],
/// y in [0, inner_wall_height]) whose side walls are plates of plate_thickness standing
/// on the floor of a catch tank. The catch tank's walls are `margin` beyond the plates'
/// outer faces and outer_wall_height high; both tanks share the floor y = 0. The fluid
/// side is everywhere the wetted side: inside the inner tank, on the plates' tops and
/// outer faces, and inside the catch tank, so fluid that overflows the plates runs down
/// their outer faces into the catch tank. Paper values by default; the plate thickness,
/// margin and catch-tank height are not given in the paper (2 L₀, 0.5 m and 1.0 m here).
struct OverflowTank2d {
  double inner_width = 2.00;
  double inner_wall_height = 0.74;
  double plate_thickness = 0.02;
  double margin = 0.50;
  double outer_wall_height = 1.00;
  double depth = 0.02;
  double target_edge = 0.01;
};

[[nodiscard]] TriangleMesh make_overflow_tank_2d(const OverflowTank2d& tank = {});

/// Spherical cap closing the top of a cylindrical tank.
struct DomeRoof {
  double radius = 0.0;  ///< radius of the sphere, >= the tank radius (= it: a hemisphere)
  int rings = 1;        ///< vertex rings from the wall's top ring (excluded) to the apex (included)
};

/// Upright cylindrical tank about the z axis, normals into the tank:
///  - bottom: the disc z = 0 of `bottom_rings` concentric rings plus a centre vertex,
///    ring k at radius k·radius/bottom_rings with about segments·k/bottom_rings
///    vertices (at least 3), so the triangles keep their size and shape towards the
///    centre; the outermost ring is the wall's bottom ring;
///  - wall: `layers` rows of quads (two triangles each, alternating diagonals) between
///    layers + 1 rings of `segments` vertices, z from 0 to wall_height;
///  - roof (optional): a spherical cap whose rim is the wall's top ring, `rings` rings
///    equally spaced in polar angle up to the apex, vertex counts proportional to the
///    ring radius. Without a roof the top ring is the open rim.
/// Every ring starts at the angle 0 and rings of different counts are stitched by
/// advancing along the angle, so adjacent rings share no crossing edges and the mesh
/// with a roof is closed and consistently oriented. Throws std::invalid_argument on
/// segments < 3, layers < 1, bottom_rings < 1, roof rings < 1, a non-positive size or a
/// dome radius below the tank radius.
[[nodiscard]] TriangleMesh make_cylindrical_tank(double radius, double wall_height, int segments, int layers,
                                                 int bottom_rings, const std::optional<DomeRoof>& roof = std::nullopt);

}  // namespace tankfsi::sph
