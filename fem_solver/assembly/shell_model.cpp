#include "fem_solver/assembly/shell_model.hpp"

#include <stdexcept>

namespace tankfsi::fem {

ShellModel::ShellModel(ShellMesh mesh_in, std::vector<ShellSection> sections_in, double drilling)
    : mesh(std::move(mesh_in)), sections(std::move(sections_in)), drilling_factor(drilling) {
  mesh.check();
  if (sections.size() != mesh.region_names.size())
    throw std::invalid_argument("the model has " + std::to_string(sections.size()) + " sections for " +
                                std::to_string(mesh.region_names.size()) + " mesh regions");
  for (std::size_t r = 0; r < sections.size(); ++r)
    if (!(sections[r].thickness > 0.0 && sections[r].young_modulus > 0.0 && sections[r].density >= 0.0))
      throw std::invalid_argument("region " + mesh.region_names[r] + " needs a positive thickness and Young's modulus");
  directors = compute_directors(mesh);
}

ElementNodes ShellModel::element_nodes(std::size_t element) const {
  const MeshElement& e = mesh.elements[element];
  ElementNodes out;
  out.count = e.node_count();
  out.thickness = section_of(element).thickness;
  for (int k = 0; k < out.count; ++k) {
    const auto slot = static_cast<std::size_t>(k);
    out.position[slot] = mesh.nodes[static_cast<std::size_t>(e.nodes[slot])];
    out.director[slot] = directors[element][slot];
  }
  return out;
}

double ShellModel::total_mass() const {
  double mass = 0.0;
  for (std::size_t e = 0; e < mesh.elements.size(); ++e) {
    const ShellSection& s = section_of(e);
    mass += s.density * s.thickness * element_area(element_nodes(e));
  }
  return mass;
}

}  // namespace tankfsi::fem
