#pragma once
// Small meshes and dense assembly for element-level tests (no PETSc).
#include <Eigen/Dense>

#include "fem_solver/assembly/shell_model.hpp"

namespace tankfsi::fem::testing {

/// MacNeal & Harder's (1985) patch: the rectangle 0.24 x 0.12 cut into five
/// distorted quadrilaterals by four interior nodes (nodes 4..7); or the same
/// patch with every quad split into two triangles.
inline ShellMesh macneal_patch(bool triangles) {
  ShellMesh mesh;
  mesh.nodes = {{0.0, 0.0, 0.0},   {0.24, 0.0, 0.0},  {0.24, 0.12, 0.0}, {0.0, 0.12, 0.0},
                {0.04, 0.02, 0.0}, {0.18, 0.03, 0.0}, {0.16, 0.08, 0.0}, {0.08, 0.08, 0.0}};
  const int region = mesh.region_index("plate");
  const std::vector<std::array<int, 4>> quads{{0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}, {4, 5, 6, 7}};
  for (const auto& q : quads) {
    if (triangles) {
      mesh.elements.push_back(MeshElement{{q[0], q[1], q[2], -1}, region});
      mesh.elements.push_back(MeshElement{{q[0], q[2], q[3], -1}, region});
    } else {
      mesh.elements.push_back(MeshElement{q, region});
    }
  }
  return mesh;
}

inline ShellSection steel_plate(double thickness) {
  ShellSection s;
  s.thickness = thickness;
  s.young_modulus = 1.0e6;
  s.poisson_ratio = 0.25;
  s.density = 7800.0;
  return s;
}

/// Dense global stiffness, 6 DOF per node.
inline Eigen::MatrixXd dense_stiffness(const ShellModel& model) {
  const auto n = static_cast<Eigen::Index>(6 * model.mesh.nodes.size());
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t e = 0; e < model.mesh.elements.size(); ++e) {
    const Eigen::MatrixXd ke = element_stiffness(model.element_nodes(e), model.section_of(e), model.drilling_factor);
    const auto& element = model.mesh.elements[e];
    for (int a = 0; a < element.node_count(); ++a)
      for (int b = 0; b < element.node_count(); ++b)
        k.block<6, 6>(6 * element.nodes[static_cast<std::size_t>(a)], 6 * element.nodes[static_cast<std::size_t>(b)]) +=
            ke.block<6, 6>(6 * a, 6 * b);
  }
  return k;
}

}  // namespace tankfsi::fem::testing
