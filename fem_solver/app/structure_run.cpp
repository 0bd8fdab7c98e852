#include "fem_solver/app/structure_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>

#include "common/config/config_error.hpp"
#include "common/io/number_text.hpp"
#include "common/log/progress_line.hpp"
#include "common/run/checkpoint_series.hpp"
#include "common/run/stop_signal.hpp"
#include "coupling/restart/restart_state_file.hpp"
#include "fem_solver/app/structure_checkpoint.hpp"
#include "fem_solver/analysis/modal_analysis.hpp"
#include "fem_solver/analysis/static_analysis.hpp"
#include "fem_solver/analysis/structure_solver.hpp"
#include "fem_solver/app/structure_coupling.hpp"
#include "fem_solver/app/structure_output.hpp"

namespace tankfsi::fem {
namespace {


nlohmann::json model_summary(const StructureSystem& system, const std::string& analysis) {
  const ShellMesh& mesh = system.model().mesh;
  int ranks = 1;
  MPI_Comm_size(system.comm(), &ranks);
  return {{"analysis", analysis},
          {"nodes", mesh.nodes.size()},
          {"quadrilaterals", mesh.quad_count()},
          {"triangles", mesh.triangle_count()},
          {"equations", system.dofs().global_size()},
          {"constrained_dofs", system.dofs().constrained_count()},
          {"mass_kg", system.model().total_mass()},
          {"ranks", ranks}};
}

nlohmann::json probe_values(const StructureCase& c, const NodalValues& displacement) {
  nlohmann::json out = nlohmann::json::object();
  for (const auto& p : c.probes) {
    const std::size_t offset = 6 * static_cast<std::size_t>(p.node) + (p.quantity == "rotation" ? 3 : 0);
    out[p.name] = {{"quantity", p.quantity},
                   {"node", p.node},
                   {"value", {displacement[offset], displacement[offset + 1], displacement[offset + 2]}}};
  }
  return out;
}

double largest_translation(const NodalValues& values) {
  double largest = 0.0;
  for (std::size_t i = 0; i < values.size(); i += 6)
    largest = std::max(largest, std::sqrt(values[i] * values[i] + values[i + 1] * values[i + 1] + values[i + 2] * values[i + 2]));
  return largest;
}

nlohmann::json run_static(ProgramContext& context, const StructureCase& c, StructureSystem& system) {
  const StaticResult result =
      c.corotational ? solve_static_corotational(system, c.loads, c.load_steps) : solve_static(system, c.loads);
  StructureOutput output(context, c, system);
  StructureTotals totals = support_totals(system.model().mesh, result.reactions);
  const NodalValues applied = nodal_loads(system.model(), c.loads);
  for (std::size_t i = 0; i < applied.size(); i += 6)
    for (int k = 0; k < 3; ++k) totals.external_force(k) += applied[i + static_cast<std::size_t>(k)];
  output.write_fields(0.0, result.displacement, {});
  output.sample(0.0, result.displacement, {}, {}, totals);
  output.flush();
  context.log.info("static: largest displacement ", largest_translation(result.displacement), " m (", result.solver, ")");
  nlohmann::json summary = model_summary(system, "static");
  summary["solver"] = result.solver;
  summary["kinematics"] = c.corotational ? "corotational" : "linear";
  summary["probes"] = probe_values(c, result.displacement);
  summary["max_displacement_m"] = largest_translation(result.displacement);
  summary["external_force_N"] = {totals.external_force.x(), totals.external_force.y(), totals.external_force.z()};
  summary["support_force_N"] = {totals.support_force.x(), totals.support_force.y(), totals.support_force.z()};
  return {{"structure", summary}};
}

ModalResult modes_of(ProgramContext& context, StructureSystem& system, int count) {
  const auto stage = context.timers.time("shell_modal");
  return solve_modes(system.assembler(), system.stiffness(), count);
}

/// modal.periods_s lists the periods in ascending order (the highest computed
/// mode first); modal.modes lists the modes in their own order (ascending
/// frequency, mode 1 the fundamental) with period and effective masses.
nlohmann::json modal_summary(const ModalResult& modes) {
  nlohmann::json periods = nlohmann::json::array(), list = nlohmann::json::array();
  Eigen::Vector3d cumulative = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < modes.modes.size(); ++k) {
    const NaturalMode& m = modes.modes[k];
    periods.push_back(m.period);
    list.push_back({{"mode", k + 1},
                    {"frequency_Hz", m.frequency},
                    {"period_s", m.period},
                    {"effective_mass_kg", {m.effective_mass.x(), m.effective_mass.y(), m.effective_mass.z()}}});
    cumulative += m.effective_mass;
  }
  std::sort(periods.begin(), periods.end());
  const Eigen::Vector3d ratio = cumulative.cwiseQuotient(modes.free_mass);
  return {{"periods_s", periods},
          {"fundamental_period_s", modes.modes.front().period},
          {"modes", list},
          {"free_mass_kg", {modes.free_mass.x(), modes.free_mass.y(), modes.free_mass.z()}},
          {"cumulative_effective_mass_ratio", {ratio.x(), ratio.y(), ratio.z()}},
          {"iterations", modes.iterations}};
}

nlohmann::json run_modal(ProgramContext& context, const StructureCase& c, StructureSystem& system) {
  const ModalResult modes = modes_of(context, system, c.modes);
  StructureOutput output(context, c, system);
  // Mode k is snapshot k (its "time" is the mode number), M-normalised.
  for (std::size_t k = 0; k < modes.modes.size(); ++k) {
    output.write_fields(static_cast<double>(k + 1), modes.modes[k].shape, {});
    context.log.info("mode ", k + 1, ": f = ", modes.modes[k].frequency, " Hz, T = ", modes.modes[k].period,
                     " s, effective mass x/y/z = ", modes.modes[k].effective_mass.x(), " / ",
                     modes.modes[k].effective_mass.y(), " / ", modes.modes[k].effective_mass.z(), " kg");
  }
  return {{"structure", model_summary(system, "modal")}, {"modal", modal_summary(modes)}};
}

nlohmann::json run_dynamic(ProgramContext& context, const StructureCase& c, StructureSystem& system,
                           const GroundMotion& motion) {
  const ModalResult modes = modes_of(context, system, c.modes);
  const auto& first = modes.modes[static_cast<std::size_t>(c.damping.first_mode - 1)];
  const auto& second = modes.modes[static_cast<std::size_t>(c.damping.second_mode - 1)];
  RayleighCoefficients damping;
  try {
    damping = rayleigh_from_modes(first.omega, c.damping.first_ratio, second.omega, c.damping.second_ratio);
  } catch (const std::invalid_argument& e) {
    throw context.config.error_at("structure.damping.target_modes", e.what());
  }
  context.log.info("Rayleigh damping: alpha = ", damping.alpha, " 1/s, beta = ", damping.beta, " s (modes ",
                   c.damping.first_mode, " and ", c.damping.second_mode, ": T = ", first.period, " s, ", second.period, " s)");
  const TimeIntegrationRule rule = TimeIntegrationRule::generalized_alpha(c.spectral_radius);
  if (c.spectral_radius < 1.0)
    context.log.info("time integration: generalized alpha, rho_inf = ", c.spectral_radius, " (alpha_m = ", rule.alpha_m,
                     ", alpha_f = ", rule.alpha_f, ", gamma = ", rule.gamma, ", beta = ", rule.beta, ")");
  StructureSolver solver(system, damping, c.loads, motion, rule,
                         c.corotational ? Kinematics::corotational : Kinematics::linear);
  const bool wetted = system.model().mesh.element_sets.count("wetted") != 0;
  if (wetted) {
    // Wetted elements held fixed on every node (a bottom on its foundation)
    // stay the fluid's rigid walls: the interface is what the liquid can move.
    const DofMap& dofs = system.dofs();
    const auto supported = [&dofs](int node) {
      return dofs.equation(node, 0) < 0 && dofs.equation(node, 1) < 0 && dofs.equation(node, 2) < 0;
    };
    solver.set_interface(extract_interface(system.model().mesh, "wetted", supported));
  }
  solver.prepare(c.time_step);
  std::optional<nlohmann::json> resumed;
  std::optional<coupling::CouplingRestartState> coupling_state;
  std::vector<double> interface_reference;
  double checkpoint_restart_time = 0.0;
  if (context.restart) {
    resumed = read_structure_state(context.comm, *context.restart, solver);
    checkpoint_restart_time = solver.time();
    if (context.partner != MPI_COMM_NULL) {
      const Hdf5File file(context.comm, context.restart->path, FileMode::read);
      coupling_state = coupling::read_restart_state(file, "/coupling", false);
      interface_reference = file.read_rows_double("/structure/interface_reference", 0,
                                                  file.shape("/structure/interface_reference").rows);
    }
    context.log.info("structure: continues from t = ", solver.time(), " s, step ", solver.steps());
  }
  StructureOutput output(context, c, system, resumed ? std::optional<double>(solver.time()) : std::nullopt);
  // With a partner program, the fluid's forces load the wetted surface.
  std::unique_ptr<StructureCoupling> coupling;
  if (context.partner != MPI_COMM_NULL) {
    if (!wetted) throw context.config.error_at("structure", "a coupled run needs the element set 'wetted' (the interface)");
    const StructureCoupling::Resume resume{coupling_state ? *coupling_state : coupling::CouplingRestartState{},
                                           interface_reference};
    coupling = std::make_unique<StructureCoupling>(context, solver, coupling_state ? &resume : nullptr);
  } else if (!resumed && context.config.text("structure.initial_state") == "equilibrium") {
    solver.start_at_equilibrium();
  }
  if (!resumed && context.config.text("structure.initial_state") == "equilibrium")
    context.log.info("the structure starts in static equilibrium with the loads at t = 0: largest displacement ",
                     solver.largest_displacement(), " m");
  // Implicit windows may be repeated: outputs wait until a window is accepted.
  const bool repeats = coupling && context.config.text("coupling.scheme") == "implicit";
  auto sample = [&]() {
    const auto scope = context.timers.time("shell_sample");
    StructureTotals totals = support_totals(system.model().mesh, solver.support_forces());
    totals.external_force = solver.total_external_force();
    totals.energy = solver.energy();
    output.sample(solver.time(), solver.displacement(), solver.velocity(), solver.acceleration(), totals);
    return totals;
  };
  const double checkpoint_interval = context.config.real("output.checkpoint_interval");
  double next_probe = c.probe_interval;
  double next_field = c.field_interval;
  double next_checkpoint = next_output_time(0.0, checkpoint_interval);
  Eigen::Vector2d peak_shear = Eigen::Vector2d::Zero();
  double peak_displacement = 0.0;
  if (resumed) {
    const nlohmann::json& j = *resumed;
    next_probe = j.at("next_probe").get<double>();
    next_field = j.at("next_field").get<double>();
    next_checkpoint = j.contains("next_checkpoint") ? j.at("next_checkpoint").get<double>()
                                                    : std::numeric_limits<double>::infinity();
    peak_shear = Eigen::Vector2d(j.at("peak_shear")[0].get<double>(), j.at("peak_shear")[1].get<double>());
    peak_displacement = j.at("peak_displacement").get<double>();
  } else {
    sample();
    output.write_fields(0.0, solver.displacement(), solver.velocity());
  }
  const auto loop_state = [&] {
    nlohmann::json j{{"next_probe", next_probe}, {"next_field", next_field},
                     {"peak_shear", {peak_shear.x(), peak_shear.y()}}, {"peak_displacement", peak_displacement}};
    if (std::isfinite(next_checkpoint)) j["next_checkpoint"] = next_checkpoint;
    return j;
  };
  CheckpointSeries checkpoints(context.comm, context.folder->path(), context.folder->program(),
                               context.restart ? context.restart->number + 1 : 1);
  double checkpoint_time = resumed ? solver.time() : -1.0;
  const auto write_checkpoint = [&] {
    const auto scope = context.timers.time("checkpoint");
    checkpoint_time = solver.time();
    output.flush();
    auto file = checkpoints.begin(solver.time(), context.config);
    write_structure_state(*file, solver, loop_state());
    if (coupling) {
      coupling::write_restart_state(*file, "/coupling", coupling->restart_state(), false);
      int writer = 0;
      MPI_Comm_rank(context.comm, &writer);
      const std::vector<double> reference = writer == 0 ? coupling->reference() : std::vector<double>{};
      file->write_distributed_1d("/structure/interface_reference", std::span<const double>(reference));
    }
    const auto path = checkpoints.commit(std::move(file));
    context.log.info("checkpoint ", path.string(), " at t = ", solver.time(), " s");
    return path;
  };
  const auto start = std::chrono::steady_clock::now();
  const long long steps_before = solver.steps();
  int rank = 0;
  MPI_Comm_rank(context.comm, &rank);
  ProgressLine progress("fem_solver", c.end_time, rank == 0 && ProgressLine::on_terminal());
  try {
    while (coupling ? coupling->ongoing() : solver.time() < c.end_time * (1.0 - 1e-12)) {
      const double dt = std::min(c.time_step, coupling ? coupling->max_time_step() : c.end_time - solver.time());
      if (coupling) coupling->before_step(dt);
      solver.advance(dt);
      if (coupling && !coupling->after_step(dt) && repeats) continue;
      progress.update(solver.time(), solver.steps());
      peak_displacement = std::max(peak_displacement, solver.largest_displacement());
      if (solver.time() >= next_probe * (1.0 - 1e-12)) {
        const StructureTotals totals = sample();
        peak_shear = peak_shear.cwiseMax(totals.support_force.head<2>().cwiseAbs());
        next_probe += c.probe_interval * std::max(1.0, std::floor((solver.time() - next_probe) / c.probe_interval) + 1.0);
      }
      if (solver.time() >= next_field * (1.0 - 1e-12)) {
        output.write_fields(solver.time(), solver.displacement(), solver.velocity());
        next_field += c.field_interval * std::max(1.0, std::floor((solver.time() - next_field) / c.field_interval) + 1.0);
        progress.clear();  // the log line takes the line; the progress comes back after it
        context.log.info("t = ", solver.time(), " s, step ", solver.steps(), ", largest displacement ",
                         solver.largest_displacement(), " m");
      }
      // Checkpoints: alone after any step; coupled at the window ends both
      // programs agreed on (the coupling library's window-end records).
      const CheckpointDecision checkpoint =
          coupling ? checkpoint_after_window(*coupling)
                   : checkpoint_after_step(context.comm, solver.time(), checkpoint_interval, next_checkpoint);
      if (checkpoint.due) {
        progress.clear();
        const auto path = write_checkpoint();
        if (checkpoint.stop_signal != 0) {
          if (coupling) coupling->finish();  // both checkpoints are complete before either program ends
          throw stopped_after_checkpoint(checkpoint.stop_signal, solver.time(), path);
        }
      }
    }
  } catch (const std::runtime_error& e) {
    // A failed step leaves the solver at the last good state: alone, it is
    // also a checkpoint (a coupled run keeps the pair's last common one).
    output.flush();
    output.write_fields(solver.time() + 1e-9, solver.displacement(), solver.velocity());
    std::string saved = " is the final snapshot of structure.xdmf";
    if (!coupling) saved += last_good_checkpoint(write_checkpoint);
    throw std::runtime_error(std::string(e.what()) + " — the last good state (t = " + number_text(solver.time()) +
                             " s)" + saved);
  }
  // The end state: a later run may go on from it (a longer end_time).
  if (!coupling && checkpoint_time != solver.time()) write_checkpoint();
  progress.clear();
  output.flush();
  if (coupling) coupling->finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json summary = model_summary(system, "dynamic");
  summary["steps"] = solver.steps();
  summary["end_time_s"] = solver.time();
  summary["time_step_s"] = c.time_step;
  summary["spectral_radius"] = c.spectral_radius;
  summary["initial_state"] = context.config.text("structure.initial_state");
  summary["factorisations"] = solver.integrator().factorisations();
  summary["kinematics"] = c.corotational ? "corotational" : "linear";
  if (const CorotationalNewmark* corotational = solver.corotational()) {
    // All of them, the steps of repeated coupling windows too.
    summary["newton_iterations"] = corotational->newton_iterations();
    summary["newton_iterations_most_in_a_step"] = corotational->most_newton_iterations();
  }
  summary["seconds_per_step"] = seconds / static_cast<double>(std::max<long long>(solver.steps() - steps_before, 1));
  if (resumed) summary["restarted_at_s"] = checkpoint_restart_time;
  summary["rayleigh"] = {{"alpha_per_s", damping.alpha},
                         {"beta_s", damping.beta},
                         {"target_modes", {c.damping.first_mode, c.damping.second_mode}},
                         {"target_periods_s", {first.period, second.period}},
                         {"target_ratios", {c.damping.first_ratio, c.damping.second_ratio}}};
  summary["peak_base_shear_N"] = {peak_shear.x(), peak_shear.y()};
  summary["peak_displacement_m"] = peak_displacement;
  summary["probes"] = probe_values(c, solver.displacement());
  if (wetted) summary["interface_vertices"] = solver.interface().node_ids.size();
  nlohmann::json results{{"structure", summary}, {"modal", modal_summary(modes)}};
  if (coupling) results["coupling"] = coupling->summary();
  return results;
}

}  // namespace

nlohmann::json run_structure(ProgramContext& context, StructureCase c, const GroundMotion& motion) {
  ShellModel model(std::move(c.mesh), c.sections, c.drilling_factor);
  c.mesh = ShellMesh{};
  StructureSystem system(context.comm, std::move(model), c.constraints, &context.timers);
  context.log.info("structure: ", system.model().mesh.nodes.size(), " nodes, ", system.model().mesh.quad_count(),
                   " quadrilaterals, ", system.model().mesh.triangle_count(), " triangles, ",
                   system.dofs().global_size(), " equations");
  if (c.analysis == "static") return run_static(context, c, system);
  if (c.analysis == "modal") return run_modal(context, c, system);
  return run_dynamic(context, c, system, motion);
}

}  // namespace tankfsi::fem
