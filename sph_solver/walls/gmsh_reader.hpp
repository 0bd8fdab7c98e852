#pragma once
// Reader of Gmsh MSH 4.1 ASCII surface meshes into a TriangleMesh, with the physical
// group of each triangle — how a wall mesh made in Gmsh (tank wall, bottom, roof as
// named groups) reaches the solver. The file is parsed by common/io/gmsh_msh (the
// project's one MSH parser; its errors are this reader's too).
//
// Surface elements of type 2 (3-node triangle) are kept as they are; type 3
// (4-node quadrangle a b c d) becomes two triangles along its shorter diagonal, a–c
// (a b c, a c d) or b–d (a b d, b c d), which keeps the orientation and gives the
// better-shaped pair. Elements of points, curves and volumes are ignored; any other
// surface element type (second order, ...) is an error, not silently dropped.
//
// Orientation is the element's node order (right-hand rule), as Gmsh writes it: the
// caller orients the surfaces in Gmsh so that the normals point into the fluid.
//
// Vertices are the nodes used by the kept triangles, in file order; node_tag maps
// each vertex back to its Gmsh node (for matching the FEM mesh).
//
// Errors raise tankfsi::ConfigError (a std::runtime_error) naming the file and line:
// those of the parser, unknown node tags, surfaces missing from $Entities, unknown
// physical group names, and a file (or selection) without any triangle.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct GmshSurface {
  TriangleMesh mesh;
  /// Per triangle: the physical tag of its surface entity (the first one listed, or
  /// the first selected one when groups are selected); 0 when the surface is in none.
  std::vector<int> physical_tag;
  /// Names of the two-dimensional physical groups, by tag.
  std::map<int, std::string> physical_names;
  /// Per vertex: the Gmsh node tag.
  std::vector<std::int64_t> node_tag;

  /// Name of triangle t's physical group, empty if it has none or it is unnamed.
  [[nodiscard]] std::string physical_name(int t) const;
};

/// Reads a surface mesh. With `physical_groups` non-empty only the triangles of the
/// surfaces in those named two-dimensional physical groups are kept.
[[nodiscard]] GmshSurface read_gmsh_surface(const std::filesystem::path& file,
                                            const std::vector<std::string>& physical_groups = {});

}  // namespace tankfsi::sph
