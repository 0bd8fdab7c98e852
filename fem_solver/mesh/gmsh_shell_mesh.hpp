#pragma once
// A shell mesh made in Gmsh (MSH 4.1 ASCII, parsed by common/io/gmsh_msh): its
// 3-node triangles and 4-node quadrangles become MITC3 and MITC4 elements, and
// its physical groups the named sets a case file refers to:
//
//   surface groups named as regions   element regions (each element in exactly
//                                     one: wall, roof, bottom); by default every
//                                     surface group is a region
//   other surface groups              element sets (wetted), overlapping freely
//   curve and point groups            node sets (base, wall_top, symmetry edges)
//   no surface group at all           one region, "shell"
//
// A group without a name is known by its number ("5"). Nodes are the nodes of
// the shell elements, in file order. Gmsh also writes a node for every
// geometric point, circle centres included: such nodes of no element are left
// out; any other node of no shell element is an error.
//
// Errors: ConfigError naming the file and line for what the file gets wrong —
// its format (see gmsh_msh.hpp), element types other than 3-node triangles and
// 4-node quadrangles on surfaces, volume elements, a surface in two regions or
// in none, loose nodes, degenerate or inverted elements, surfaces oriented
// oppositely (ShellMesh::check); std::out_of_range (naming the file) for a
// region the caller names that the file does not have.
#include <filesystem>
#include <string>
#include <vector>

#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

/// `regions`: names of the surface groups that are element regions; empty for
/// every surface group.
[[nodiscard]] ShellMesh read_gmsh_shell_mesh(const std::filesystem::path& file,
                                             const std::vector<std::string>& regions = {});

}  // namespace tankfsi::fem
