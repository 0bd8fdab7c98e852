#pragma once
// Simple wall meshes built in code: a box, an open cylinder (a tank shell), an
// icosphere and a flat rectangle. For test cases and unit tests; real walls come from
// the FEM mesh or an STL file.
#include <Eigen/Core>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

/// Which way the normals (the fluid side) point, relative to the enclosed volume or
/// the cylinder's axis.
enum class NormalSide { outward, inward };

/// Closed axis-aligned box [lo, hi]: 8 vertices, 12 triangles; open_top drops the two
/// triangles of the face z = hi.z (an open tank: 10 triangles, 4 boundary edges).
[[nodiscard]] TriangleMesh make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, NormalSide side,
                                    bool open_top = false);

/// Lateral surface of a cylinder about the z axis, z in [0, height]: `segments`
/// vertices per ring, `layers` + 1 rings, open at both ends. Each quad is split along
/// alternating diagonals (a symmetric pattern, so no twist is built into the mesh).
[[nodiscard]] TriangleMesh make_open_cylinder(double radius, double height, int segments, int layers,
                                              NormalSide side);

/// Sphere about the origin: the icosahedron with every triangle split in four
/// `subdivisions` times, new vertices projected on the sphere. 10·4^s + 2 vertices.
[[nodiscard]] TriangleMesh make_icosphere(double radius, int subdivisions, NormalSide side = NormalSide::outward);

/// Rectangle origin + s·u + t·v, s, t in [0, 1], cells × cells quads of two triangles;
/// normal along u × v.
[[nodiscard]] TriangleMesh make_rectangle(const Eigen::Vector3d& origin, const Eigen::Vector3d& u,
                                          const Eigen::Vector3d& v, int cells);

}  // namespace tankfsi::sph
