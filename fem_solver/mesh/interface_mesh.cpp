#include "fem_solver/mesh/interface_mesh.hpp"

#include <algorithm>
#include <map>

namespace tankfsi::fem {

InterfaceMesh extract_interface(const ShellMesh& mesh, const std::string& name) {
  const std::vector<int> elements = mesh.elements_of(name);
  InterfaceMesh out;
  out.node_ids = mesh.nodes_of(name);
  std::map<int, int> local;
  for (std::size_t i = 0; i < out.node_ids.size(); ++i) {
    local[out.node_ids[i]] = static_cast<int>(i);
    out.positions.push_back(mesh.nodes[static_cast<std::size_t>(out.node_ids[i])]);
  }
  const auto at = [&](const MeshElement& e, int k) { return local.at(e.nodes[static_cast<std::size_t>(k)]); };
  for (const int index : elements) {
    const MeshElement& e = mesh.elements[static_cast<std::size_t>(index)];
    // Reversed winding (0 2 1): normals into the liquid.
    out.triangles.push_back({at(e, 0), at(e, 2), at(e, 1)});
    if (e.node_count() == 4) out.triangles.push_back({at(e, 0), at(e, 3), at(e, 2)});
  }
  return out;
}

}  // namespace tankfsi::fem
