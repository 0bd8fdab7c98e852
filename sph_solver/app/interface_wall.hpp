#pragma once
// The fluid's wall of a coupled run (METHOD.md §2, §4): the structure's
// wetted surface *is* the wall, vertex for vertex. The fluid's own wall
// triangles that lie on the wetted surface (all three vertices within
// `tolerance` of it: both programs model the same tank, each with its own
// faceting) are replaced by the interface's triangles, oriented into the
// liquid; the rest of the fluid's walls (above the wetted height, rigid
// walls) stay. Where a kept triangle touches the wetted surface (the
// junction at the liquid level, a corner) its vertices there follow the
// structure through the nearest-projection mapping.
//
// Where the replaced triangles include both faces of a thin solid (at least a
// tenth of them facing away from the interface as oriented: a gate or baffle
// drawn in the fluid's walls as a plate thinner than L0, which the structure
// models by its mid-surface) the interface is a sheet the liquid may wet on
// both faces: its triangles are two-sided walls (wall_contacts.hpp).
#include <cstdint>
#include <vector>

#include "coupling/interface/interface_mesh.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct InterfaceWall {
  TriangleMesh mesh;                 ///< the kept own triangles, then the interface's
  /// Wall vertices that move with the structure: the interface's (first,
  /// in the interface's vertex order) and the kept ones on the wetted surface.
  std::vector<int> coupled;
  std::size_t interface_vertices = 0;  ///< the first coupled ones, exactly the interface's
  std::size_t replaced_triangles = 0;  ///< own triangles the interface replaced
  double largest_distance = 0.0;       ///< of a replaced or junction vertex from the interface
  bool flipped = false;                ///< the interface's triangles were turned to face the liquid
  bool two_sided = false;              ///< the interface stands for both faces of a thin solid
  std::vector<char> two_sided_triangles;  ///< per triangle of `mesh` (the interface's when two_sided)
};

/// Throws std::invalid_argument when no own triangle lies on the interface
/// (the programs do not model the same tank, or not in the same frame) or
/// when the interface's triangles are not oriented alike.
[[nodiscard]] InterfaceWall build_interface_wall(const TriangleMesh& own, const coupling::InterfaceMesh& interface,
                                                 double tolerance);

}  // namespace tankfsi::sph
