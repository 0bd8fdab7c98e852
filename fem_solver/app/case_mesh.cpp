// The shell mesh of a case: structure.mesh.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/config/config_error.hpp"
#include "fem_solver/app/structure_case.hpp"
#include "fem_solver/mesh/gmsh_shell_mesh.hpp"
#include "fem_solver/mesh/shell_surfaces.hpp"
#include "fem_solver/mesh/tank_mesh.hpp"

namespace tankfsi::fem {
namespace {

std::array<int, 2> divisions(const CaseConfig& config) {
  const auto v = config.real_vector("structure.mesh.divisions");
  std::array<int, 2> out{};
  for (std::size_t k = 0; k < 2; ++k) {
    if (v[k] != std::floor(v[k]) || v[k] > 1e5)
      throw config.error_at("structure.mesh.divisions", "element counts are whole numbers (at most 1e5)");
    out[k] = static_cast<int>(v[k]);
  }
  return out;
}

std::array<double, 2> range(const CaseConfig& config, const std::string& key) {
  const auto v = config.real_vector(key);
  return {v[0], v[1]};
}

// structure.mesh.regions: names separated by commas (Gmsh names may hold spaces).
std::vector<std::string> region_names(const CaseConfig& config) {
  std::vector<std::string> names;
  std::string text = config.text("structure.mesh.regions");
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(',', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    const auto first = item.find_first_not_of(" \t");
    if (first != std::string::npos) names.push_back(item.substr(first, item.find_last_not_of(" \t") - first + 1));
    else if (end < text.size()) throw config.error_at("structure.mesh.regions", "an empty name between commas");
    begin = end + 1;
  }
  return names;
}

ShellMesh generate(const CaseConfig& config, const std::string& type) {
  if (type == "cylinder") {
    CylinderPatch c;
    c.radius = config.real("structure.mesh.radius");
    c.length = config.real("structure.mesh.length");
    const auto phi = range(config, "structure.mesh.phi_range");
    c.phi_start = phi[0];
    c.phi_end = phi[1];
    const auto n = divisions(config);
    c.divisions_phi = n[0];
    c.divisions_z = n[1];
    return cylinder_patch(c);
  }
  if (type == "sphere") {
    SpherePatch s;
    s.radius = config.real("structure.mesh.radius");
    const auto theta = range(config, "structure.mesh.theta_range");
    const auto phi = range(config, "structure.mesh.phi_range");
    s.theta_start = theta[0];
    s.theta_end = theta[1];
    s.phi_start = phi[0];
    s.phi_end = phi[1];
    const auto n = divisions(config);
    s.divisions_theta = n[0];
    s.divisions_phi = n[1];
    return sphere_patch(s);
  }
  if (type == "plate") {
    PlatePatch p;
    const auto vector = [&](const std::string& key) {
      const auto v = config.real_vector(key);
      return Eigen::Vector3d(v[0], v[1], v[2]);
    };
    p.corner = vector("structure.mesh.corner");
    p.side_u = vector("structure.mesh.side_u");
    p.side_v = vector("structure.mesh.side_v");
    const auto n = divisions(config);
    p.divisions_u = n[0];
    p.divisions_v = n[1];
    p.wetted = config.boolean("structure.mesh.wetted");
    return plate_patch(p);
  }
  if (type == "tank") {
    TankSpec t;
    t.radius = config.real("structure.mesh.radius");
    t.wall_height = config.real("structure.mesh.wall_height");
    t.dome_radius = config.real("structure.mesh.dome_radius");
    t.element_size = config.real("structure.mesh.element_size");
    t.liquid_level = config.real("structure.mesh.liquid_level");
    return tank_mesh(t);
  }
  if (type == "gmsh") {
    try {
      return read_gmsh_shell_mesh(config.path("structure.mesh.file"), region_names(config));
    } catch (const std::out_of_range& e) {
      throw config.error_at("structure.mesh.regions", e.what());
    }
  }
  throw config.error_at("structure.mesh.type", "unknown mesh type " + type);
}

}  // namespace

ShellMesh read_structure_mesh(const CaseConfig& config) {
  if (!config.has("structure.mesh.type"))
    throw config.error_at("structure", "fem_solver needs structure.mesh.type (the shell's mesh)");
  const std::string type = config.text("structure.mesh.type");
  try {
    ShellMesh mesh = generate(config, type);
    mesh.check();
    return mesh;
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {
    throw config.error_at("structure.mesh.type", e.what());
  }
}

}  // namespace tankfsi::fem
