#include "fem_solver/mesh/interface_mesh.hpp"

#include <algorithm>
#include <map>

namespace tankfsi::fem {

InterfaceMesh extract_interface(const ShellMesh& mesh, const std::string& name,
                                const std::function<bool(int)>& supported) {
  std::vector<int> elements = mesh.elements_of(name);
  if (supported) {
    std::erase_if(elements, [&](int index) {
      const auto& nodes = mesh.elements[static_cast<std::size_t>(index)].nodes;
      return std::all_of(nodes.begin(), nodes.begin() + mesh.elements[static_cast<std::size_t>(index)].node_count(), supported);
    });
  }
  InterfaceMesh out;
  for (const int index : elements) {
    const MeshElement& e = mesh.elements[static_cast<std::size_t>(index)];
    for (int k = 0; k < e.node_count(); ++k) out.node_ids.push_back(e.nodes[static_cast<std::size_t>(k)]);
  }
  std::sort(out.node_ids.begin(), out.node_ids.end());
  out.node_ids.erase(std::unique(out.node_ids.begin(), out.node_ids.end()), out.node_ids.end());
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
