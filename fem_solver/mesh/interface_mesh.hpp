#pragma once
// The interface the coupling exchanges (DESIGN.md, data flow): the wetted
// surface of the shell as triangles (each quad split in two along its 0-2
// diagonal) over the mesh's own nodes, named by global node id. Triangles are
// wound so that their normals point into the liquid — the opposite of the
// shell's outward normals — as the fluid side expects of its walls.
#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct InterfaceMesh {
  std::vector<int> node_ids;                   ///< global (ShellMesh) node ids, ascending
  std::vector<Eigen::Vector3d> positions;      ///< per interface vertex
  std::vector<std::array<int, 3>> triangles;   ///< indices into node_ids
};

/// Throws std::out_of_range if the mesh has no element set or region `name`.
/// `supported(node)`, when given, names the nodes whose translations are all
/// fixed: elements with every node supported cannot move and are left out (a
/// tank bottom on its foundation is a rigid wall the fluid keeps as its own;
/// the interface is the part of the wetted surface the liquid can move).
[[nodiscard]] InterfaceMesh extract_interface(const ShellMesh& mesh, const std::string& name,
                                              const std::function<bool(int)>& supported = {});

}  // namespace tankfsi::fem
