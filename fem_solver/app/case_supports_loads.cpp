// Supports (structure.boundary_conditions) and constant loads (structure.loads).
#include <sstream>
#include <stdexcept>

#include "common/config/config_error.hpp"
#include "fem_solver/app/structure_case.hpp"

namespace tankfsi::fem {
namespace {

std::vector<int> nodes_named(const ConfigView& record, const ShellMesh& mesh, const std::string& key) {
  try {
    return mesh.nodes_of(record.text(key));
  } catch (const std::out_of_range&) {
    std::string known;
    for (const auto& [name, set] : mesh.node_sets) known += (known.empty() ? "" : ", ") + name;
    for (const auto& name : mesh.region_names) known += ", " + name;
    for (const auto& [name, set] : mesh.element_sets) known += ", " + name;
    throw record.error_at(key, "the mesh has no node set, region or element set '" + record.text(key) +
                                   "' (known: " + known + ")");
  }
}

int component_index(const ConfigView& record, const std::string& word) {
  static const std::vector<std::string> names{"ux", "uy", "uz", "rx", "ry", "rz"};
  for (std::size_t k = 0; k < names.size(); ++k)
    if (names[k] == word) return static_cast<int>(k);
  throw record.error_at("components", "'" + word + "' is not a component (ux uy uz rx ry rz)");
}

}  // namespace

std::vector<DofConstraint> read_constraints(const CaseConfig& config, ShellMesh& mesh) {
  std::vector<DofConstraint> out;
  for (const ConfigView& record : config.records("structure.boundary_conditions")) {
    if (record.has("nodes") == record.has("position"))
      throw record.error_at("nodes", "give either nodes (a set) or position (one node), not both or neither");
    const std::vector<int> nodes =
        record.has("nodes") ? nodes_named(record, mesh, "nodes") : std::vector<int>{mesh.nearest_node(record.vector3("position"))};
    const std::string type = record.text("type");
    std::vector<std::pair<int, double>> components;
    if (type == "fixed") {
      for (int k = 0; k < 6; ++k) components.emplace_back(k, 0.0);
    } else if (type == "pinned") {
      for (int k = 0; k < 3; ++k) components.emplace_back(k, 0.0);
    } else if (type == "symmetry") {
      // Mirror symmetry about the plane with normal n: no translation along n,
      // no rotation about the in-plane axes (the rotation vector is axial).
      const int n = record.text("plane_normal")[0] - 'x';
      components = {{n, 0.0}, {3 + (n + 1) % 3, 0.0}, {3 + (n + 2) % 3, 0.0}};
      for (const int node : nodes) mesh.symmetry_planes.emplace(node, Eigen::Vector3d::Unit(n));
    } else {
      std::istringstream words(record.text("components"));
      for (std::string word; words >> word;) components.emplace_back(component_index(record, word), 0.0);
      if (components.empty()) throw record.error_at("components", "names no component");
      if (record.has("values")) {
        const auto values = record.real_vector("values");
        if (values.size() != components.size())
          throw record.error_at("values", std::to_string(values.size()) + " values for " +
                                              std::to_string(components.size()) + " components");
        for (std::size_t k = 0; k < values.size(); ++k) components[k].second = values[k];
      }
    }
    for (const int node : nodes)
      for (const auto& [component, value] : components) out.push_back(DofConstraint{node, component, value});
  }
  return out;
}

LoadSet read_loads(const CaseConfig& config, const ShellMesh& mesh) {
  LoadSet loads;
  for (const ConfigView& record : config.records("structure.loads")) {
    const std::string type = record.text("type");
    if (type == "pressure" || type == "traction" || type == "hydrostatic") {
      const std::string name = record.text("elements");
      try {
        (void)mesh.elements_of(name);
      } catch (const std::out_of_range& e) {
        throw record.error_at("elements", e.what());
      }
      if (type == "pressure") loads.surfaces.push_back(SurfaceLoad{name, record.real("pressure"), Eigen::Vector3d::Zero()});
      if (type == "traction") loads.surfaces.push_back(SurfaceLoad{name, 0.0, record.vector3("traction")});
      if (type == "hydrostatic")
        loads.hydrostatic.push_back(
            HydrostaticLoad{name, record.real("density"), record.real("gravity"), record.real("level")});
    } else if (type == "gravity") {
      loads.gravity += record.vector3("acceleration");
    } else {
      loads.points.push_back(
          PointLoad{mesh.nearest_node(record.vector3("position")), record.vector3("force"), record.vector3("moment")});
    }
  }
  return loads;
}

}  // namespace tankfsi::fem
