#pragma once
// InterfaceMesh: the wetted surface both programs share (PROTOCOL.md,
// "Interface"): vertices with global ids and reference coordinates (m, the
// tank-base frame), and triangles. On the fluid side the whole mesh is held by
// every rank, vertices in ascending id order; on the structure side each rank
// holds the vertices it declared.
#include <array>
#include <cstdint>
#include <vector>

namespace tankfsi::coupling {

struct InterfaceMesh {
  std::vector<std::int64_t> ids;               ///< global vertex ids
  std::vector<double> coordinates;             ///< 3 per vertex
  std::vector<std::array<int, 3>> triangles;   ///< indices into ids

  [[nodiscard]] std::size_t vertex_count() const { return ids.size(); }
};

}  // namespace tankfsi::coupling
