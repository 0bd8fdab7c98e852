#pragma once
// A structured grid of quadrilaterals mapped onto a surface: the building block
// of the cylinder, sphere and tank-wall generators.
#include <Eigen/Core>

#include <array>
#include <functional>
#include <string>

#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct PatchSpec {
  int divisions_u = 1;
  int divisions_v = 1;
  /// True: u wraps around (u = 1 is u = 0), a full circle; no u edges then.
  bool closed_u = false;
  /// Point of the surface at (u, v) in [0, 1]^2; the normal is x_,u x x_,v.
  std::function<Eigen::Vector3d(double u, double v)> map;
  std::string region = "shell";
  /// Node sets of the edges u = 0, u = 1, v = 0, v = 1 (empty name: none).
  std::array<std::string, 4> edge_names{"u_start", "u_end", "v_start", "v_end"};
};

/// Node (i, j) is i + (divisions_u + 1 or divisions_u when closed) * j.
[[nodiscard]] ShellMesh structured_patch(const PatchSpec& spec);

}  // namespace tankfsi::fem
