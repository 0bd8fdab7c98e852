#pragma once
// ShellModel: the mesh with what the elements need — a section per region and
// the directors — and the element view the kinematics works on.
#include <vector>

#include "fem_solver/elements/shell_element.hpp"
#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct ShellModel {
  ShellMesh mesh;
  std::vector<ShellSection> sections;  ///< one per mesh region
  Directors directors;
  double drilling_factor = default_drilling_factor;

  /// Checks the mesh and sizes, computes the directors.
  ShellModel(ShellMesh mesh_in, std::vector<ShellSection> sections_in, double drilling = default_drilling_factor);

  [[nodiscard]] const ShellSection& section_of(std::size_t element) const {
    return sections[static_cast<std::size_t>(mesh.elements[element].region)];
  }
  [[nodiscard]] ElementNodes element_nodes(std::size_t element) const;
  /// Total mass of the structure: sum of rho t A.
  [[nodiscard]] double total_mass() const;
};

}  // namespace tankfsi::fem
