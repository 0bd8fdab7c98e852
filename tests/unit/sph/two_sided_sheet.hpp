#pragma once
// A vertical sheet for the two-sided wall tests: the plane x = 0.3 from y = 0.1
// (its free lower edge) to y = 0.5, z in [-0.2, 0.2], in n cells, facing -x
// (one-sided, a particle at x < 0.3 is in front of it).
#include <Eigen/Core>

#include <array>
#include <vector>

#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::test {

inline sph::TriangleMesh vertical_sheet(int cells) {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i <= cells; ++i) vertices.emplace_back(0.3, 0.1 + 0.4 * i / cells, j == 0 ? -0.2 : 0.2);
  for (int i = 0; i < cells; ++i) {
    const int a = i, b = i + 1, c = cells + 1 + i, d = cells + 2 + i;
    // (b - a) x (d - a) = (0, dy, 0) x (0, dy, 0.4) points along +x: take the other turn.
    triangles.push_back({a, d, b});
    triangles.push_back({a, c, d});
  }
  return sph::TriangleMesh(std::move(vertices), std::move(triangles));
}

}  // namespace tankfsi::test
