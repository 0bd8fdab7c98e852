#include "sph_solver/app/fluid_case.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include "common/config/config_error.hpp"
#include "common/io/number_text.hpp"
#include "sph_solver/isph/time_step_control.hpp"
#include "sph_solver/particles/filling.hpp"
#include "sph_solver/particles/standing_wave.hpp"
#include "sph_solver/walls/gmsh_reader.hpp"
#include "sph_solver/walls/stl_reader.hpp"
#include "sph_solver/walls/tank_meshes.hpp"
#include "sph_solver/walls/wall_mesh_check.hpp"

namespace tankfsi::sph {
namespace {

/// Depth of the extruded walls of a 2D section (the paper's tank is 2 cm deep). The
/// section's front and back are open, so their edges at z = ±depth/2 must lie
/// beyond the kernel support of every particle (at z = 0): at least twice the
/// support each way. fluid.section_depth may ask for more (a coupled 2D
/// structure spans the same depth).
double section_depth(const CaseConfig& config, const FluidModel& model) {
  const double least = 4.0 * Kernel(model.kernel, model.dimension, model.smoothing_length).support_radius();
  const double asked = config.real("fluid.section_depth");
  if (asked == 0.0) return least;
  if (asked < least)
    throw config.error_at("fluid.section_depth", "a 2D section must be at least four kernel supports deep (" +
                                                     std::to_string(least) + " m) so that its open front and back "
                                                     "stay out of every particle's support");
  return asked;
}

Eigen::AlignedBox3d box_from(const ConfigView& config, const std::string& key) {
  const auto v = config.real_vector(key);
  Eigen::AlignedBox3d box(Eigen::Vector3d(v[0], v[1], v[2]), Eigen::Vector3d(v[3], v[4], v[5]));
  if (!(box.min().array() <= box.max().array()).all())
    throw config.error_at(key, "the first corner must not exceed the second in any coordinate");
  return box;
}

FluidModel read_model(const CaseConfig& config) {
  FluidModel m;
  m.dimension = static_cast<int>(config.integer("fluid.dimension"));
  try {
    m.kernel = parse_kernel_type(config.text("fluid.kernel"), m.dimension);
  } catch (const std::invalid_argument& e) {
    throw config.error_at("fluid.kernel", e.what());
  }
  m.spacing = config.real("fluid.spacing");
  const double ratio = config.has("fluid.smoothing_length_ratio") ? config.real("fluid.smoothing_length_ratio")
                                                                  : default_smoothing_length_ratio(m.kernel);
  m.smoothing_length = ratio * m.spacing;
  if (m.kernel == KernelType::wendland_c2 && ratio < 1.5)
    throw config.error_at("fluid.smoothing_length_ratio",
                          "the Wendland C2 kernel needs h >= 1.5 L0 to sum to 1 on the particle lattice");
  m.density = config.real("fluid.density");
  m.viscosity = config.real("fluid.viscosity");
  m.gravity = config.real("fluid.gravity");
  m.density_error_weight = config.real("fluid.ppe.density_error_weight");
  m.free_surface_threshold = config.real("fluid.ppe.free_surface_threshold");
  m.preconditioner_radius = config.real("fluid.ppe.preconditioner_radius");
  if (m.preconditioner_radius > 0.0 && m.preconditioner_radius < 1.0)
    throw config.error_at("fluid.ppe.preconditioner_radius",
                          "must be 0 (the operator itself) or at least 1 particle spacing (the nearest neighbours)");
  m.keep_hierarchy = config.boolean("fluid.ppe.keep_hierarchy");
  m.shifting = config.boolean("fluid.shifting.enabled");
  if (m.shifting) {
    m.shifting_coefficient = config.real("fluid.shifting.coefficient");
    m.close_pair_distance = config.real("fluid.shifting.close_pair_distance");
  }
  return m;
}

/// Target edge of generated walls: fluid.geometry.element_size, or 2 L0.
double wall_edge(const CaseConfig& config, const FluidModel& model) {
  if (config.has("fluid.geometry.element_size") && config.real("fluid.geometry.element_size") > 0.0)
    return config.real("fluid.geometry.element_size");
  return 2.0 * model.spacing;
}

/// Facets around a generated cylindrical tank.
int cylinder_segments(const CaseConfig& config, const FluidModel& model) {
  return std::max(12, static_cast<int>(std::ceil(2.0 * std::numbers::pi * config.real("fluid.geometry.radius") /
                                                  wall_edge(config, model))));
}

TriangleMesh read_walls(const CaseConfig& config, const FluidModel& model) {
  if (!config.has("fluid.geometry.type"))
    throw config.error_at("fluid", "sph_solver needs fluid.geometry.type (the walls of the liquid)");
  const std::string type = config.text("fluid.geometry.type");
  const bool two_d = model.dimension == 2;
  const bool planar_type = type == "rectangular_tank" || type == "overflow_tank";
  if (planar_type && !two_d) throw config.error_at("fluid.geometry.type", type + " is a 2D geometry (fluid.dimension 2)");
  if (type == "cylindrical_tank" && two_d)
    throw config.error_at("fluid.geometry.type", "cylindrical_tank is a 3D geometry (fluid.dimension 3)");
  const double edge = wall_edge(config, model);
  try {
    if (type == "rectangular_tank")
      return make_rectangular_tank_2d(config.real("fluid.geometry.width"), config.real("fluid.geometry.wall_height"),
                                      section_depth(config, model), edge);
    if (type == "overflow_tank") {
      OverflowTank2d tank;
      tank.inner_width = config.real("fluid.geometry.width");
      tank.inner_wall_height = config.real("fluid.geometry.wall_height");
      tank.margin = config.real("fluid.geometry.catch_margin");
      tank.plate_thickness = 2.0 * model.spacing;
      tank.outer_wall_height = tank.inner_wall_height + 0.5;
      tank.depth = section_depth(config, model);
      tank.target_edge = edge;
      return make_overflow_tank_2d(tank);
    }
    if (type == "cylindrical_tank") {
      const double radius = config.real("fluid.geometry.radius");
      const double height = config.real("fluid.geometry.wall_height");
      const int segments = cylinder_segments(config, model);
      const int layers = std::max(1, static_cast<int>(std::ceil(height / edge)));
      const int rings = std::max(1, static_cast<int>(std::ceil(radius / edge)));
      std::optional<DomeRoof> roof;
      const double dome = config.real("fluid.geometry.dome_radius");
      if (dome > 0.0) {
        if (dome < radius) throw config.error_at("fluid.geometry.dome_radius", "must be at least the tank radius");
        const double rise = dome - std::sqrt(dome * dome - radius * radius);
        const double arc = dome * std::asin(radius / dome);
        roof = DomeRoof{dome, std::max(2, static_cast<int>(std::ceil(std::max(arc, rise) / edge)))};
      }
      return make_cylindrical_tank(radius, height, segments, layers, rings, roof);
    }
    const auto file = config.path("fluid.geometry.file");
    return type == "stl" ? read_stl(file) : read_gmsh_surface(file).mesh;
  } catch (const ConfigError&) {
    throw;
  } catch (const std::exception& e) {
    throw config.error_at(type == "stl" || type == "gmsh" ? "fluid.geometry.file" : "fluid.geometry.type", e.what());
  }
}

/// The walls can hold the liquid up to its level (wall_mesh_check.hpp), and the
/// level lies below their top: a tank filled to the roof has no free surface.
void check_walls(const CaseConfig& config, const FluidModel& model, const TriangleMesh& walls) {
  const double level = config.real("fluid.fill.level");
  const int up = model.dimension == 2 ? 1 : 2;
  const double top = walls.bounding_box().max()[up];
  const std::string type = config.text("fluid.geometry.type");
  if (type == "cylindrical_tank" && config.real("fluid.geometry.dome_radius") > 0.0 &&
      level > config.real("fluid.geometry.wall_height"))
    throw config.error_at("fluid.fill.level", "the liquid would reach into the roof: the level " +
                                                  number_text(level) + " m is above the wall height " +
                                                  number_text(config.real("fluid.geometry.wall_height")) + " m");
  if (level >= top)
    throw config.error_at("fluid.fill.level", "the level " + number_text(level) +
                                                  " m is not below the top of the walls (" + number_text(top) +
                                                  " m): the liquid needs a free surface inside the tank");
  const std::string problem = wall_mesh_problem(walls, {.dimension = model.dimension, .fill_level = level});
  if (problem.empty()) return;
  if (type == "stl" || type == "gmsh")
    throw config.error_at("fluid.geometry.file", config.path("fluid.geometry.file").string() + ": " + problem);
  throw config.error_at("fluid.geometry.type", "the generated " + type + " walls fail a check (" + problem +
                                                   "): report this with the case file");
}

/// A fixed step must meet the stability limits of the liquid at rest (gravity,
/// hydrostatic pressure of the full depth; time_step_control.hpp) before any
/// motion adds to them: a step that fails them fails at the first step.
void check_fixed_step_at_rest(const CaseConfig& config, const FluidCase& c) {
  const int up = c.model.dimension == 2 ? 1 : 2;
  const double depth = std::max(0.0, config.real("fluid.fill.level") - c.walls.bounding_box().min()[up]);
  const double pressure = c.model.density * c.model.gravity * depth;
  const auto limits = time_step_limits(c.model, 1.0, c.fixed_time_step, 0.0, c.model.gravity, pressure);
  if (c.fixed_time_step > limits.smallest() * (1.0 + 1e-12))
    throw config.error_at("fluid.time_step.value",
                          "the fixed time step " + number_text(c.fixed_time_step) + " s exceeds the " +
                              limits.limiting() + " stability limit " + number_text(limits.smallest()) +
                              " s of the liquid at rest (|g| = " + number_text(c.model.gravity) +
                              " m/s^2, hydrostatic pressure " + number_text(pressure) +
                              " Pa): use a smaller step or fluid.time_step.mode adaptive");
}

std::vector<ProbeSpec> read_probes(const CaseConfig& config) {
  std::vector<ProbeSpec> probes;
  for (const ConfigView& record : config.records("fluid.probes")) {
    ProbeSpec p;
    p.name = record.text("name");
    p.quantity = record.text("quantity");
    const bool two_d = config.integer("fluid.dimension") == 2;
    if (p.quantity == "volume") {
      p.region = box_from(record, "region");
      if (two_d && !(p.region.min().z() <= 0.0 && p.region.max().z() >= 0.0))
        throw record.error_at("region", "a 2D probe's box must hold the plane z = 0");
    } else {
      p.position = record.vector3("position");
      if (two_d && p.position.z() != 0.0) throw record.error_at("position", "a 2D probe lies in the plane z = 0");
    }
    for (const auto& other : probes)
      if (other.name == p.name) throw record.error_at("name", "probe name '" + p.name + "' is used twice");
    if (p.name == "fluid") throw record.error_at("name", "'fluid' is the name of the run's global probe file");
    probes.push_back(p);
  }
  return probes;
}

/// The standing wave of fluid.initial_velocity on the particles of a whole
/// rectangular tank (standing_wave.hpp): x from 0 to the width, floor at y = 0,
/// depth the top of the highest particle layer.
void apply_initial_wave(const CaseConfig& config, FluidCase& c) {
  const std::string key = "fluid.initial_velocity.type";
  if (config.text("fluid.geometry.type") != "rectangular_tank")
    throw config.error_at(key, "a standing wave needs fluid.geometry.type rectangular_tank");
  if (config.has("fluid.fill.region"))
    throw config.error_at(key, "a standing wave fills the whole tank: remove fluid.fill.region");
  StandingWave wave;
  wave.width = config.real("fluid.geometry.width");
  wave.gravity = c.model.gravity;
  double top = 0.0;
  for (const auto& x : c.particles.position) top = std::max(top, x.y());
  wave.depth = top + 0.5 * c.model.spacing;
  wave.mode = static_cast<int>(config.integer("fluid.initial_velocity.mode"));
  wave.amplitude = config.real("fluid.initial_velocity.amplitude");
  if (wave.amplitude > 0.1 * wave.depth)
    throw config.error_at("fluid.initial_velocity.amplitude",
                          "a linear standing wave needs an amplitude of at most 10 % of the depth (" +
                              std::to_string(0.1 * wave.depth) + " m)");
  if (!(wave.gravity > 0.0)) throw config.error_at("fluid.gravity", "a standing wave needs gravity > 0");
  apply_standing_wave(wave, c.particles);
}

}  // namespace

FluidCase read_fluid_case(const CaseConfig& config) {
  config.require_section("fluid", "sph_solver");
  FluidCase c;
  c.model = read_model(config);
  if (!config.has("end_time")) throw config.error_at("end_time", "sph_solver needs end_time (the simulated time)");
  c.end_time = config.real("end_time");
  c.walls = read_walls(config, c.model);
  if (!config.has("fluid.fill.level"))
    throw config.error_at("fluid.fill", "sph_solver needs fluid.fill.level (the height of the still liquid)");
  check_walls(config, c.model, c.walls);
  FillSpec fill;
  fill.spacing = c.model.spacing;
  fill.density = c.model.density;
  fill.fill_level = config.real("fluid.fill.level");
  fill.dimension = c.model.dimension;
  fill.hydrostatic_pressure = config.boolean("fluid.fill.hydrostatic");
  fill.gravity = c.model.gravity;
  if (config.has("fluid.fill.region")) fill.region = box_from(config, "fluid.fill.region");
  // Rings that follow the wall (filling.hpp): the smooth cylinder its facets
  // approximate, as the wall contacts see it (wall_contacts.hpp).
  if (config.text("fluid.geometry.type") == "cylindrical_tank")
    fill.cylinder_radius = config.real("fluid.geometry.radius");
  try {
    c.particles = fill_tank(c.walls, fill);
  } catch (const std::invalid_argument& e) {
    throw config.error_at("fluid.fill.level", e.what());
  }
  if (config.text("fluid.initial_velocity.type") == "standing_wave") apply_initial_wave(config, c);
  const double support = Kernel(c.model.kernel, c.model.dimension, c.model.smoothing_length).support_radius();
  if (config.has("fluid.domain")) {
    c.domain = box_from(config, "fluid.domain");
  } else {
    c.domain = c.walls.bounding_box();
    c.domain.min().array() -= support;
    c.domain.max().array() += support;
  }
  for (const auto& x : c.particles.position)
    if (!c.domain.contains(x)) throw config.error_at("fluid.domain", "the initial liquid is not inside the domain");
  c.ppe_options = config.text("fluid.ppe.solver_options");
  c.adaptive_time_step = config.text("fluid.time_step.mode") == "adaptive";
  c.breach_courant = config.real("fluid.time_step.breach_courant");
  if (c.adaptive_time_step) {
    c.cfl_number = config.real("fluid.time_step.cfl");
    c.max_time_step = config.real("fluid.time_step.max");
  } else {
    c.fixed_time_step = config.real("fluid.time_step.value");
    check_fixed_step_at_rest(config, c);
  }
  c.field_interval = config.real("output.field_interval");
  c.probe_interval = config.real("output.probe_interval");
  c.rebalance_interval = static_cast<int>(config.integer("fluid.rebalance_interval"));
  c.probes = read_probes(config);
  return c;
}

}  // namespace tankfsi::sph
