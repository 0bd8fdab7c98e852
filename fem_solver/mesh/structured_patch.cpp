#include "fem_solver/mesh/structured_patch.hpp"

#include <algorithm>
#include <stdexcept>

namespace tankfsi::fem {

ShellMesh structured_patch(const PatchSpec& spec) {
  if (spec.divisions_u < 1 || spec.divisions_v < 1 || (spec.closed_u && spec.divisions_u < 3))
    throw std::invalid_argument("a surface patch needs at least 1 division per side (3 around a closed one)");
  ShellMesh mesh;
  const int region = mesh.region_index(spec.region);
  const int row = spec.closed_u ? spec.divisions_u : spec.divisions_u + 1;
  for (int j = 0; j <= spec.divisions_v; ++j)
    for (int i = 0; i < row; ++i)
      mesh.nodes.push_back(spec.map(static_cast<double>(i) / spec.divisions_u, static_cast<double>(j) / spec.divisions_v));
  const auto node = [&](int i, int j) { return (i % row) + row * j; };
  for (int j = 0; j < spec.divisions_v; ++j)
    for (int i = 0; i < spec.divisions_u; ++i)
      mesh.elements.push_back(MeshElement{{node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)}, region});
  auto add_edge = [&](const std::string& name, auto&& index_of, int count) {
    if (name.empty()) return;
    auto& set = mesh.node_sets[name];
    for (int k = 0; k < count; ++k) set.push_back(index_of(k));
    std::sort(set.begin(), set.end());
  };
  if (!spec.closed_u) {
    add_edge(spec.edge_names[0], [&](int j) { return node(0, j); }, spec.divisions_v + 1);
    add_edge(spec.edge_names[1], [&](int j) { return node(spec.divisions_u, j); }, spec.divisions_v + 1);
  }
  add_edge(spec.edge_names[2], [&](int i) { return node(i, 0); }, row);
  add_edge(spec.edge_names[3], [&](int i) { return node(i, spec.divisions_v); }, row);
  return mesh;
}

}  // namespace tankfsi::fem
