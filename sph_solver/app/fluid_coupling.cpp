#include "sph_solver/app/fluid_coupling.hpp"

#include <algorithm>
#include <chrono>

#include "sph_solver/app/interface_wall.hpp"
#include "coupling/settings.hpp"

namespace tankfsi::sph {

void check_coupled_fluid_case(const CaseConfig& config) {
  const coupling::CouplingSettings settings = coupling::read_coupling_settings(config);
  // An adaptive step is cut at the window's end; a fixed one must fit in it.
  if (config.text("fluid.time_step.mode") == "fixed")
    coupling::require_step_within_window(config, "fluid.time_step.value", settings);
}

FluidCoupling::FluidCoupling(ProgramContext& context, FluidSolver& solver, const Eigen::Vector3d& ground_acceleration,
                             const coupling::CouplingRestartState* resume)
    : solver_(solver),
      participant_(coupling::Side::fluid, coupling::read_coupling_settings(context.config), context.comm, context.partner,
                   coupling::case_fingerprints(context.config)),
      repeats_(context.config.text("coupling.scheme") == "implicit") {
  participant_.exchange_interface();
  // The wetted surface becomes the wall, vertex for vertex (interface_wall.hpp).
  const double tolerance = 0.5 * solver.model().spacing;
  InterfaceWall wall;
  try {
    wall = build_interface_wall(solver.walls().mesh(), participant_.interface_mesh(), tolerance);
  } catch (const std::invalid_argument& e) {
    throw context.config.error_at("coupling", e.what());
  }
  solver.replace_walls(wall.mesh, wall.two_sided_triangles);
  reference_ = solver.walls().mesh().vertices();
  coupled_ = wall.coupled;
  mapping_distance_ = wall.largest_distance;
  std::vector<double> coupled_positions;
  for (const int v : coupled_) {
    const auto& x = reference_[static_cast<std::size_t>(v)];
    coupled_positions.insert(coupled_positions.end(), x.data(), x.data() + 3);
  }
  if (solver.model().dimension == 2) {
    // The extruded section's depth; a 2D wall's vertices come in pairs at z = ±d/2,
    // and both of a pair must be coupled (else the coupled wall would twist).
    double low = 0.0, high = 0.0;
    for (const auto& x : reference_) low = std::min(low, x.z()), high = std::max(high, x.z());
    force_scale_ = high - low;
    long long balance = 0;
    for (const int v : coupled_) balance += reference_[static_cast<std::size_t>(v)].z() > 0.0 ? 1 : -1;
    if (balance != 0)
      throw context.config.error_at("coupling", "the structure's wetted surface must span the fluid's 2D section, z from " +
                                                    std::to_string(low) + " to " + std::to_string(high) +
                                                    " m (fluid.section_depth): only one side's wall vertices lie on it");
  }
  context.log.info("coupling: the structure's ", wall.interface_vertices, "-vertex wetted surface replaces ",
                   wall.replaced_triangles, " of the fluid's wall triangles", wall.flipped ? " (turned to face the liquid)" : "",
                   wall.two_sided ? " (both faces of a thin wall: a two-sided sheet)" : "",
                   "; ", coupled_.size() - wall.interface_vertices, " junction vertices follow it (farthest ",
                   mapping_distance_, " m from it)");
  participant_.set_own_vertices(coupled_positions);
  values_.assign(3 * coupled_.size(), 0.0);
  wall_velocity_.assign(values_.size(), 0.0);
  if (coupling::read_coupling_settings(context.config).added_mass_operator) {
    const std::vector<double> normals = participant_.interface_normals();
    for (std::size_t v = 0; 3 * v < normals.size(); ++v)
      held_back_normals_.emplace_back(normals[3 * v], normals[3 * v + 1], normals[3 * v + 2]);
    velocity_change_.assign(values_.size(), 0.0);
  }
  participant_.set_restart_interval(context.config.real("output.checkpoint_interval"));
  if (resume) {
    participant_.resume(*resume);  // the added mass, if any, is in the restart state
  } else {
    if (coupling::read_coupling_settings(context.config).added_mass_operator) write_added_mass(context);
    write_forces(solver.present_wall_forces(ground_acceleration));
    participant_.initialize();
  }
  positions_ = reference_;
  velocities_.assign(reference_.size(), Eigen::Vector3d::Zero());
}

void FluidCoupling::write_added_mass(ProgramContext& context) {
  // The operator over the interface's own vertices (the first coupled ones,
  // in the interface's order), along the coupling's normals; the junction
  // vertices that follow them neither push nor count (a few at the rim).
  const auto start = std::chrono::steady_clock::now();
  const std::vector<double> normal_values = participant_.interface_normals();
  const std::size_t count = participant_.interface_mesh().vertex_count();
  std::vector<int> vertices(coupled_.begin(), coupled_.begin() + static_cast<long>(count));
  std::vector<Eigen::Vector3d> normals(count);
  for (std::size_t v = 0; v < count; ++v) normals[v] = Eigen::Vector3d(normal_values[3 * v], normal_values[3 * v + 1], normal_values[3 * v + 2]);
  std::vector<double> matrix = solver_.added_mass_operator(vertices, normals);
  for (double& a : matrix) a *= force_scale_;  // a 2D section's impulses per unit depth -> on its depth
  participant_.write_added_mass(matrix);
  // The total for the log and the summary (sum of the operator's entries:
  // the mass the whole surface moving outward at once carries along).
  MPI_Allreduce(MPI_IN_PLACE, matrix.data(), static_cast<int>(matrix.size()), MPI_DOUBLE, MPI_SUM, solver_.comm());
  double diagonal = 0.0;
  added_mass_ = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    diagonal += matrix[i * count + i];
    for (std::size_t j = 0; j < count; ++j) added_mass_ += matrix[i * count + j];
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  context.log.info("coupling: added-mass operator of the ", count, "-vertex wetted surface in ", seconds,
                   " s: ", added_mass_, " kg moving outward together, ", diagonal, " kg each alone (sums)");
}

void FluidCoupling::before_step(double dt) {
  if (participant_.requires_writing_checkpoint()) solver_.save(checkpoint_);
  participant_.read(coupling::Field::displacement, dt, values_);
  participant_.read(coupling::Field::velocity, dt, wall_velocity_);
  for (std::size_t k = 0; k < coupled_.size(); ++k) {
    const auto v = static_cast<std::size_t>(coupled_[k]);
    positions_[v] = reference_[v] + Eigen::Vector3d(values_[3 * k], values_[3 * k + 1], values_[3 * k + 2]);
    velocities_[v] = Eigen::Vector3d(wall_velocity_[3 * k], wall_velocity_[3 * k + 1], wall_velocity_[3 * k + 2]);
  }
  solver_.move_walls(positions_, velocities_);
  if (!held_back_normals_.empty() && participant_.at_window_start()) {
    participant_.read(coupling::Field::velocity_change, dt, velocity_change_);
    if (std::any_of(velocity_change_.begin(), velocity_change_.end(), [](double c) { return c != 0.0; })) {
      std::vector<Eigen::Vector3d> jump(reference_.size(), Eigen::Vector3d::Zero());
      for (std::size_t k = 0; k < coupled_.size(); ++k)
        jump[static_cast<std::size_t>(coupled_[k])] =
            Eigen::Vector3d(velocity_change_[3 * k], velocity_change_[3 * k + 1], velocity_change_[3 * k + 2]);
      solver_.set_wall_velocity_jump(std::move(jump));
    }
  }
}

void FluidCoupling::write_forces(const std::vector<Eigen::Vector3d>& forces) {
  // This rank's share: the coupling sums the shares over the fluid's ranks.
  for (std::size_t k = 0; k < coupled_.size(); ++k)
    for (int c = 0; c < 3; ++c)
      values_[3 * k + static_cast<std::size_t>(c)] = force_scale_ * forces[static_cast<std::size_t>(coupled_[k])][c];
  participant_.write(coupling::Field::force, values_);
}

bool FluidCoupling::after_step(double dt) {
  const std::vector<Eigen::Vector3d>& jump = solver_.local_jump_impulse();
  if (jump.empty()) {
    write_forces(solver_.local_wall_forces());
  } else {
    // The structure carries the liquid's inertia against the jump as its added
    // mass along the interface normals: that part of the step's force stays here.
    std::vector<Eigen::Vector3d> forces = solver_.local_wall_forces();
    for (std::size_t k = 0; k < held_back_normals_.size(); ++k) {
      const auto v = static_cast<std::size_t>(coupled_[k]);
      const Eigen::Vector3d& n = held_back_normals_[k];
      forces[v] -= n * (n.dot(jump[v]) / dt);
    }
    write_forces(forces);
  }
  participant_.advance(dt);
  rolled_back_ = participant_.requires_reading_checkpoint();
  if (rolled_back_) {
    solver_.restore(checkpoint_);
    return false;
  }
  return participant_.window_completed();
}

void FluidCoupling::finish() { participant_.finalize(); }

nlohmann::json FluidCoupling::summary() const {
  long long iterations = 0;
  for (const auto& r : participant_.window_reports()) iterations += r.iterations;
  const auto windows = participant_.window_reports().size();
  const auto timings = participant_.timings();
  return {{"windows", windows},
          {"iterations_per_window", windows ? static_cast<double>(iterations) / static_cast<double>(windows) : 0.0},
          {"coupled_wall_vertices", coupled_.size()},
          {"interface_vertices", participant_.interface_mesh().vertex_count()},
          {"largest_mapping_distance_m", mapping_distance_},
          {"added_mass_kg", added_mass_ > 0.0 ? nlohmann::json(added_mass_) : nlohmann::json(nullptr)},
          {"section_depth_m", solver_.model().dimension == 2 ? nlohmann::json(force_scale_) : nlohmann::json(nullptr)},
          {"wait_s", timings.wait},
          {"work_s", timings.work}};
}

}  // namespace tankfsi::sph
