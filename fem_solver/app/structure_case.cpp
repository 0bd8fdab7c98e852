#include "fem_solver/app/structure_case.hpp"

#include <cmath>

#include "common/config/config_error.hpp"

namespace tankfsi::fem {
namespace {

std::vector<StructureProbe> read_probes(const CaseConfig& config, const ShellMesh& mesh) {
  std::vector<StructureProbe> probes;
  for (const ConfigView& record : config.records("structure.probes")) {
    StructureProbe p{record.text("name"), record.text("quantity"), mesh.nearest_node(record.vector3("position")), {}};
    if (record.has("direction")) {
      const Eigen::Vector3d d = record.vector3("direction");
      if (!(d.norm() > 0.0)) throw record.error_at("direction", "the direction must not be zero");
      p.direction = d.normalized();
    }
    for (const auto& other : probes)
      if (other.name == p.name) throw record.error_at("name", "probe name '" + p.name + "' is used twice");
    if (p.name == "structure") throw record.error_at("name", "'structure' is the name of the run's global probe file");
    probes.push_back(p);
  }
  return probes;
}

int mode_number(const CaseConfig& config, double value) {
  if (value != std::floor(value)) throw config.error_at("structure.damping.target_modes", "mode numbers are whole numbers");
  return static_cast<int>(value);
}

}  // namespace

StructureCase read_structure_case(const CaseConfig& config) {
  config.require_section("structure", "fem_solver");
  StructureCase c;
  c.analysis = config.text("structure.analysis");
  c.corotational = config.text("structure.kinematics") == "corotational";
  if (c.corotational && c.analysis == "static") c.load_steps = static_cast<int>(config.integer("structure.load_steps"));
  // Natural modes belong to the linear system (a dynamic run still uses them for its Rayleigh damping).
  if (c.corotational && c.analysis == "modal")
    throw config.error_at("structure.kinematics", "a modal analysis is linear: use structure.kinematics: linear");
  if (c.corotational && config.has("coupling.added_mass") && config.text("coupling.added_mass") != "none")
    throw config.error_at("coupling.added_mass",
                          "an added mass is not available with structure.kinematics: corotational");
  c.mesh = read_structure_mesh(config);
  c.sections = read_sections(config, c.mesh);
  c.drilling_factor = config.real("structure.drilling_stiffness");
  c.constraints = read_constraints(config, c.mesh);
  c.loads = read_loads(config, c.mesh);
  c.probes = read_probes(config, c.mesh);
  c.solver_options = config.text("structure.solver_options");
  c.field_interval = config.real("output.field_interval");
  c.probe_interval = config.real("output.probe_interval");
  if (c.analysis == "modal" || c.analysis == "dynamic") c.modes = static_cast<int>(config.integer("structure.modes"));
  if (c.analysis == "dynamic") {
    if (!config.has("end_time")) throw config.error_at("end_time", "a dynamic analysis needs end_time (the simulated time)");
    c.end_time = config.real("end_time");
    c.time_step = config.real("structure.time_step");
    c.spectral_radius = config.real("structure.time_integration.spectral_radius");
    const auto modes = config.real_vector("structure.damping.target_modes");
    c.damping.first_mode = mode_number(config, modes[0]);
    c.damping.second_mode = mode_number(config, modes[1]);
    if (c.damping.first_mode == c.damping.second_mode)
      throw config.error_at("structure.damping.target_modes", "the two target modes must differ");
    c.damping.first_ratio = config.real("structure.damping.ratio");
    c.damping.second_ratio =
        config.has("structure.damping.second_ratio") ? config.real("structure.damping.second_ratio") : c.damping.first_ratio;
    if (std::max(c.damping.first_mode, c.damping.second_mode) > c.modes)
      throw config.error_at("structure.damping.target_modes",
                            "a target mode beyond structure.modes (" + std::to_string(c.modes) + ") is not computed");
  }
  return c;
}

}  // namespace tankfsi::fem
