#pragma once
// The cylindrical tank generator: a wall of quadrilaterals, a spherical dome
// roof of quadrilaterals (with rows of triangles where a ring has half as many
// nodes as the ring outside it, and a fan at the apex), and a bottom plate of
// triangles; wall, roof and bottom share their junction rings. Normals point
// out of the tank. The base of the tank is z = 0, its axis the z axis.
//
// Regions: wall, roof, bottom. Element set: wetted (bottom and the wall
// elements whose centre lies below the liquid level; empty level: none).
// Node sets: base (every bottom-plate node, the wall's foot included),
// wall_top (the wall-roof junction ring, or the free top edge of an open tank).
// A dome radius of 0 makes an open-top tank: no roof region.
#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct TankSpec {
  double radius = 15.0;
  double wall_height = 18.0;
  double dome_radius = 30.0;   ///< >= radius, or 0: open top
  double element_size = 0.6;   ///< target edge length
  double liquid_level = 0.0;   ///< 0: no wetted set
};

/// Throws std::invalid_argument for a dome radius below the tank radius (and not 0), or
/// sizes that are not positive.
[[nodiscard]] ShellMesh tank_mesh(const TankSpec& spec);

}  // namespace tankfsi::fem
