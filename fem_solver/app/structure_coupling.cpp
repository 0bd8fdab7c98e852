#include "fem_solver/app/structure_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "coupling/settings.hpp"

namespace tankfsi::fem {

void check_coupled_structure_case(const CaseConfig& config, const ShellMesh& mesh) {
  const coupling::CouplingSettings settings = coupling::read_coupling_settings(config);
  if (config.text("structure.analysis") != "dynamic")
    throw config.error_at("structure.analysis", "a coupled run needs the dynamic analysis, got '" +
                                                    config.text("structure.analysis") + "'");
  if (mesh.element_sets.count("wetted") == 0)
    throw config.error_at("structure.mesh", "a coupled run needs the element set 'wetted' (the interface with the fluid)");
  // A structure step longer than the window could not follow the window's ramp.
  coupling::require_step_within_window(config, "structure.time_step", settings);
}

StructureCoupling::StructureCoupling(ProgramContext& context, StructureSolver& solver, const Resume* resume)
    : solver_(solver),
      participant_(coupling::Side::structure, coupling::read_coupling_settings(context.config), context.comm, context.partner,
                   coupling::case_fingerprints(context.config)),
      comm_(context.comm),
      hold_(coupling::read_coupling_settings(context.config).hold_window_average) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  const InterfaceMesh& interface = solver.interface();
  const std::size_t n = interface.node_ids.size();
  if (n == 0) throw context.config.error_at("structure", "a coupled run needs a wetted surface (element set 'wetted')");

  // Vertex i is declared by rank i mod size; the all-gather of the forces
  // puts rank 0's vertices first, then rank 1's, ...
  counts_.assign(static_cast<std::size_t>(size), 0);
  for (std::size_t i = 0; i < n; ++i) counts_[i % static_cast<std::size_t>(size)] += 3;
  displacements_.assign(static_cast<std::size_t>(size), 0);
  for (std::size_t q = 1; q < counts_.size(); ++q) displacements_[q] = displacements_[q - 1] + counts_[q - 1];
  for (int q = 0; q < size; ++q)
    for (std::size_t i = static_cast<std::size_t>(q); i < n; i += static_cast<std::size_t>(size)) order_.push_back(i);
  std::vector<std::int64_t> ids;
  std::vector<double> coordinates;
  for (std::size_t i = static_cast<std::size_t>(rank); i < n; i += static_cast<std::size_t>(size)) {
    owned_.push_back(i);
    ids.push_back(interface.node_ids[i]);
    coordinates.insert(coordinates.end(), interface.positions[i].data(), interface.positions[i].data() + 3);
  }
  std::vector<std::array<std::int64_t, 3>> triangles;
  for (std::size_t t = static_cast<std::size_t>(rank); t < interface.triangles.size(); t += static_cast<std::size_t>(size)) {
    const auto& tri = interface.triangles[t];
    triangles.push_back({interface.node_ids[static_cast<std::size_t>(tri[0])], interface.node_ids[static_cast<std::size_t>(tri[1])],
                         interface.node_ids[static_cast<std::size_t>(tri[2])]});
  }
  participant_.set_interface(ids, coordinates, triangles);
  participant_.exchange_interface();

  owned_values_.assign(3 * owned_.size(), 0.0);
  gathered_.assign(3 * n, 0.0);
  loads_.assign(3 * n, 0.0);
  participant_.set_restart_interval(context.config.real("output.checkpoint_interval"));
  if (context.folder && rank == 0)
    reports_ = std::make_unique<coupling::WindowReportFile>(
        context.folder->path() / "probes" / "coupling.csv", context.config.real("output.field_interval"),
        resume ? std::optional<double>(resume->state.window_start) : std::nullopt);
  if (resume) {
    if (resume->reference.size() != 3 * n)
      throw std::runtime_error("restart: " + std::to_string(resume->reference.size() / 3) +
                               " interface reference displacements for " + std::to_string(n) + " vertices");
    reference_ = resume->reference;
    participant_.resume(resume->state);
    if (coupling::read_coupling_settings(context.config).added_mass_operator) carry_added_mass(context);
    return;
  }
  const std::vector<double> u = solver.interface_displacements();
  for (std::size_t k = 0; k < owned_.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c) owned_values_[3 * k + c] = u[3 * owned_[k] + c];
  participant_.write(coupling::Field::displacement, owned_values_);
  participant_.initialize();
  if (coupling::read_coupling_settings(context.config).added_mass_operator) carry_added_mass(context);

  // At t = 0 the structure carries the fluid's initial forces: balanced by its
  // acceleration, or by its deformation (structure.initial_state: equilibrium;
  // the fluid's walls then follow the displacements from that state).
  load_interface(0.0);
  if (context.config.text("structure.initial_state") == "equilibrium") {
    solver_.start_at_equilibrium();
    reference_ = solver_.interface_displacements();
  } else {
    solver_.balance_acceleration();
    reference_.assign(3 * n, 0.0);
  }
}

void StructureCoupling::carry_added_mass(ProgramContext& context) {
  // Rows of the vertices this rank declared, columns and normals in ascending
  // id order: every rank gathers the whole operator in interface order.
  const coupling::AddedMassRows received = participant_.added_mass();
  const InterfaceMesh& interface = solver_.interface();
  const std::size_t n = interface.node_ids.size();
  std::vector<std::size_t> by_id(n);
  std::iota(by_id.begin(), by_id.end(), std::size_t{0});
  std::sort(by_id.begin(), by_id.end(), [&](std::size_t a, std::size_t b) { return interface.node_ids[a] < interface.node_ids[b]; });
  std::vector<int> counts, offsets;
  for (const int c : counts_) counts.push_back(c / 3 * static_cast<int>(n));
  for (const int d : displacements_) offsets.push_back(d / 3 * static_cast<int>(n));
  std::vector<double> gathered_rows(n * n);
  MPI_Allgatherv(received.rows.data(), static_cast<int>(received.rows.size()), MPI_DOUBLE, gathered_rows.data(),
                 counts.data(), offsets.data(), MPI_DOUBLE, comm_);
  std::vector<double> matrix(n * n), normals(3 * n);
  for (std::size_t p = 0; p < order_.size(); ++p)
    for (std::size_t j = 0; j < n; ++j) matrix[order_[p] * n + by_id[j]] = gathered_rows[p * n + j];
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t c = 0; c < 3; ++c) normals[3 * by_id[j] + c] = received.normals[3 * j + c];
  solver_.set_interface_added_mass(matrix, normals);
  added_mass_ = std::accumulate(matrix.begin(), matrix.end(), 0.0);
  context.log.info("coupling: the interface carries the liquid's added-mass operator (", n, " x ", n,
                   "; ", added_mass_, " kg moving outward together)");
}

std::vector<double> StructureCoupling::gathered(const std::vector<double>& owned) {
  MPI_Allgatherv(owned.data(), static_cast<int>(owned.size()), MPI_DOUBLE, gathered_.data(), counts_.data(),
                 displacements_.data(), MPI_DOUBLE, comm_);
  std::vector<double> values(gathered_.size());
  for (std::size_t p = 0; p < order_.size(); ++p)
    for (std::size_t c = 0; c < 3; ++c) values[3 * order_[p] + c] = gathered_[3 * p + c];
  return values;
}

void StructureCoupling::load_interface(double relative_dt) {
  participant_.read(coupling::Field::force, relative_dt, owned_values_);
  loads_ = gathered(owned_values_);
  solver_.set_external_loads(loads_);
}

void StructureCoupling::before_step(double dt) {
  if (participant_.requires_writing_checkpoint()) solver_.save(checkpoint_);
  load_interface(dt);
  // A load held over the window jumps at its start: the acceleration there is
  // the one of the new load (Newmark's trapezoid would otherwise spread the
  // jump over the first step and apply another impulse than the fluid gave).
  if (hold_ && window_start_) solver_.balance_acceleration();
  window_start_ = false;
}

bool StructureCoupling::after_step(double dt) {
  const std::vector<double> u = solver_.interface_displacements();
  for (std::size_t k = 0; k < owned_.size(); ++k)
    for (std::size_t c = 0; c < 3; ++c)
      owned_values_[3 * k + c] = u[3 * owned_[k] + c] - reference_[3 * owned_[k] + c];
  participant_.write(coupling::Field::displacement, owned_values_);
  participant_.advance(dt);
  if (participant_.requires_reading_checkpoint()) {
    solver_.restore(checkpoint_);
    window_start_ = true;
    return false;
  }
  if (!participant_.window_completed()) return false;
  window_start_ = true;
  if (reports_) reports_->append(participant_.window_reports().back(), participant_.timings());
  return true;
}

void StructureCoupling::finish() {
  participant_.finalize();
  if (reports_) reports_->flush();
}

nlohmann::json StructureCoupling::summary() const {
  const auto& reports = participant_.window_reports();
  long long iterations = 0;
  int most = 0, unconverged = 0;
  std::array<double, 3> given{}, applied{};
  double largest_window_impulse = 0.0, largest_difference = 0.0;
  for (const auto& r : reports) {
    iterations += r.iterations;
    most = std::max(most, r.iterations);
    unconverged += r.converged ? 0 : 1;
    for (std::size_t c = 0; c < 3; ++c) {
      given[c] += r.impulse_given[c];
      applied[c] += r.impulse_applied[c];
      largest_window_impulse = std::max(largest_window_impulse, std::abs(r.impulse_given[c]));
      largest_difference = std::max(largest_difference, std::abs(r.impulse_applied[c] - r.impulse_given[c]));
    }
  }
  const auto timings = participant_.timings();
  const double windows = static_cast<double>(std::max<std::size_t>(reports.size(), 1));
  return {{"windows", reports.size()},
          {"iterations_per_window", static_cast<double>(iterations) / windows},
          {"most_iterations", most},
          {"unconverged_windows", unconverged},
          {"impulse_given_Ns", given},
          {"impulse_applied_Ns", applied},
          {"largest_window_impulse_error_Ns", largest_difference},
          {"largest_window_impulse_Ns", largest_window_impulse},
          {"added_mass_kg", added_mass_ > 0.0 ? nlohmann::json(added_mass_) : nlohmann::json(nullptr)},
          {"wait_s", timings.wait},
          {"work_s", timings.work}};
}

}  // namespace tankfsi::fem
