#include "sph_solver/app/fluid_run.hpp"

#include "sph_solver/app/fluid_coupling.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "common/config/config_error.hpp"
#include "common/io/field_series_writer.hpp"
#include "common/io/number_text.hpp"
#include "common/run/stop_signal.hpp"
#include "coupling/restart/restart_state_file.hpp"
#include "sph_solver/app/fluid_checkpoint.hpp"
#include "common/log/progress_line.hpp"
#include "common/io/probe_file.hpp"
#include "common/parallel/collective.hpp"
#include "common/run/ground_motion_probe.hpp"
#include "sph_solver/isph/fluid_probes.hpp"
#include "sph_solver/isph/fluid_solver.hpp"
#include "sph_solver/isph/time_step_control.hpp"

namespace tankfsi::sph {
namespace {

/// Probe CSV columns; volumes and forces of a 2D section are per metre of depth
/// (`depth_suffix`).
std::vector<std::string> probe_columns(const std::string& quantity, const std::string& depth_suffix) {
  if (quantity == "pressure") return {"pressure_Pa"};
  if (quantity == "velocity") return {"velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"};
  if (quantity == "wave_height") return {"wave_height_m"};
  if (quantity == "volume") return {"volume_m3" + depth_suffix, "outside_m3" + depth_suffix};
  return {"front_x_m"};
}

std::vector<double> probe_values(const FluidSolver& solver, const ProbeSpec& probe, double top) {
  if (probe.quantity == "pressure") return {pressure_at(solver, probe.position)};
  if (probe.quantity == "velocity") {
    const Eigen::Vector3d v = velocity_at(solver, probe.position);
    return {v.x(), v.y(), v.z()};
  }
  if (probe.quantity == "wave_height") return {surface_elevation(solver, probe.position, top)};
  if (probe.quantity == "volume") {
    const auto volume = liquid_volume(solver, probe.region);
    return {volume[0], volume[1]};
  }
  return {front_position(solver, probe.position, Eigen::Vector3d::UnitX())};
}

/// Everything the run writes, owned by rank 0 for the CSV files.
class Outputs {
 public:
  /// `resume_time`: a restarted run's time; the series and probe files go on
  /// from it (what the stopped run wrote after it is dropped).
  Outputs(ProgramContext& context, const FluidCase& c, const FluidSolver& solver, std::optional<double> resume_time)
      : solver_(solver),
        top_(c.domain.max().dot(c.model.up())),
        depth_suffix_(c.model.dimension == 2 ? "_per_m" : ""),
        particles_(context.comm, context.folder->path(), "fluid", mode_of(resume_time), resume_time),
        walls_(context.comm, context.folder->path(), "walls", mode_of(resume_time), resume_time),
        probes_(c.probes) {
    // Rank 0 writes the probes; a file it cannot continue (a restart whose files
    // do not match) stops every rank.
    run_on_root(context.comm, 0, [&] {
      const auto open = [&](const std::string& name, std::vector<std::string> columns) {
        return open_probe_file(context.folder->probes() / (name + ".csv"), std::move(columns), c.field_interval,
                               resume_time);
      };
      for (const auto& probe : c.probes)
        probe_files_.push_back(open(probe.name, probe_columns(probe.quantity, depth_suffix_)));
      global_ = open("fluid", {"particles", "overflow_particles", "overflow_volume_m3" + depth_suffix_,
                               "force_x_N" + depth_suffix_, "force_y_N" + depth_suffix_, "force_z_N" + depth_suffix_,
                               "kinetic_energy_J" + depth_suffix_, "time_step_s", "ppe_iterations",
                               "free_surface_particles", "max_density_error", "max_speed_m_s",
                               "wall_returned_particles"});
    });
  }

  /// `wall_returned`: the particles put back in front of a wall so far (wall_crossings.hpp).
  void sample(double t, const StepReport& report, long long wall_returned) {
    for (std::size_t k = 0; k < probes_.size(); ++k) {
      const auto values = probe_values(solver_, probes_[k], top_);
      if (!probe_files_.empty()) probe_files_[k]->append(t, values);
    }
    const auto forces = solver_.total_wall_forces();
    Eigen::Vector3d total = Eigen::Vector3d::Zero();
    for (const auto& f : forces) total += f;
    const double count = static_cast<double>(solver_.global_particle_count());
    const double energy = kinetic_energy(solver_);
    if (global_)
      global_->append(t, std::vector<double>{count, static_cast<double>(solver_.removed_count()),
                                             solver_.removed_volume(), total.x(), total.y(), total.z(), energy,
                                             report.time_step, static_cast<double>(report.ppe_iterations),
                                             static_cast<double>(report.free_surface_particles),
                                             report.max_density_error, report.max_speed,
                                             static_cast<double>(wall_returned)});
    last_total_force_ = total;
  }

  /// `density`, `free_surface`: the solver's per-particle diagnostics of the last
  /// step, written as NaN when they do not belong to `particles` (the last good
  /// state of a failed run).
  void snapshot(double t, const Particles& particles, std::vector<double> density, std::vector<double> free_surface) {
    if (density.size() != particles.size()) density.assign(particles.size(), std::numeric_limits<double>::quiet_NaN());
    if (free_surface.size() != particles.size()) free_surface = density;
    std::vector<double> positions;
    std::vector<double> velocities;
    positions.reserve(3 * particles.size());
    velocities.reserve(3 * particles.size());
    for (std::size_t i = 0; i < particles.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        positions.push_back(particles.position[i][k]);
        velocities.push_back(particles.velocity[i][k]);
      }
    particles_.write_particles(t, ParticleSnapshot{particles.id, positions,
                                                   {NamedField{"velocity", 3, velocities},
                                                    NamedField{"pressure", 1, particles.pressure},
                                                    NamedField{"mass", 1, particles.mass},
                                                    NamedField{"density", 1, density},
                                                    NamedField{"free_surface", 1, free_surface}}});
    write_walls(t);
  }

  void flush() {
    for (auto& file : probe_files_) file->flush();
    if (global_) global_->flush();
  }

  [[nodiscard]] const Eigen::Vector3d& last_total_force() const { return last_total_force_; }

 private:
  /// The wall mesh with the fluid's force per vertex and the pressure it means
  /// (normal force over a third of the adjacent triangles' area; in 2D per metre of
  /// the mesh's depth). Rank 0 writes the whole mesh.
  void write_walls(double t) {
    const auto forces = solver_.total_wall_forces();
    const TriangleMesh& mesh = solver_.walls().mesh();
    const bool writer = rank() == 0;
    std::vector<double> area(mesh.vertex_count(), 0.0);
    for (std::size_t t_index = 0; t_index < mesh.triangle_count(); ++t_index)
      for (const int v : mesh.triangles()[t_index]) area[static_cast<std::size_t>(v)] += mesh.face_areas()[t_index] / 3.0;
    const Eigen::AlignedBox3d box = mesh.bounding_box();
    const double depth = solver_.model().dimension == 2 ? box.max().z() - box.min().z() : 1.0;
    std::vector<std::int64_t> ids, triangles;
    std::vector<double> positions, force_values, pressure;
    if (writer) {
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        ids.push_back(static_cast<std::int64_t>(v));
        for (int k = 0; k < 3; ++k) {
          positions.push_back(mesh.vertices()[v][k]);
          force_values.push_back(forces[v][k]);
        }
        const double a = area[v] / depth;
        pressure.push_back(a > 0.0 ? -forces[v].dot(mesh.vertex_normals()[v]) / a : 0.0);
      }
      for (const auto& tri : mesh.triangles())
        for (const int v : tri) triangles.push_back(v);
    }
    MeshSnapshot snapshot{ids, positions, std::nullopt, {NamedField{"force", 3, force_values}, NamedField{"pressure", 1, pressure}}, {}};
    if (!wall_cells_written_) snapshot.cells = SurfaceCells{triangles, {}};  // then reused
    walls_.write_mesh(t, snapshot);
    wall_cells_written_ = true;
  }

  static FileMode mode_of(std::optional<double> resume_time) {
    return resume_time ? FileMode::append : FileMode::truncate;
  }

  [[nodiscard]] int rank() const {
    int r = 0;
    MPI_Comm_rank(solver_.comm(), &r);
    return r;
  }

  const FluidSolver& solver_;
  double top_;
  std::string depth_suffix_;
  FieldSeriesWriter particles_;
  FieldSeriesWriter walls_;
  std::vector<ProbeSpec> probes_;
  std::vector<std::unique_ptr<ProbeFile>> probe_files_;
  std::unique_ptr<ProbeFile> global_;
  Eigen::Vector3d last_total_force_ = Eigen::Vector3d::Zero();
  bool wall_cells_written_ = false;
};

/// Running statistics of the steps for summary.json.
struct RunStatistics {
  long long steps = 0;
  double min_dt = std::numeric_limits<double>::infinity();
  double max_dt = 0.0;
  long long ppe_iterations = 0;
  int max_ppe_iterations = 0;
  double max_density_error = 0.0;
  long long wall_returned_particles = 0;
  long long ppe_twin_failures = 0;  ///< steps whose pressure solve left the operator's twin
  long long ppe_hierarchy_builds = 0;  ///< steps that built a preconditioner's hierarchy
  double particle_steps = 0.0;
  double simulated = 0.0;  ///< sum of the steps (more than the run's time when implicit windows repeat)
  std::map<std::string, long long> limiting;

  void add(const StepReport& r, const std::string& limit) {
    ++steps;
    simulated += r.time_step;
    min_dt = std::min(min_dt, r.time_step);
    max_dt = std::max(max_dt, r.time_step);
    ppe_iterations += r.ppe_iterations;
    max_ppe_iterations = std::max(max_ppe_iterations, r.ppe_iterations);
    max_density_error = std::max(max_density_error, r.max_density_error);
    wall_returned_particles += r.wall_returned_particles;
    ppe_twin_failures += r.ppe_twin_failed ? 1 : 0;
    ppe_hierarchy_builds += r.ppe_hierarchy_built ? 1 : 0;
    particle_steps += static_cast<double>(r.particles);
    ++limiting[limit];
  }

  /// For a checkpoint (min_dt kept only once finite: JSON has no infinity).
  [[nodiscard]] nlohmann::json to_json() const {
    nlohmann::json j{{"steps", steps}, {"max_dt", max_dt}, {"ppe_iterations", ppe_iterations},
                     {"max_ppe_iterations", max_ppe_iterations}, {"max_density_error", max_density_error},
                     {"wall_returned_particles", wall_returned_particles},
                     {"ppe_twin_failures", ppe_twin_failures}, {"ppe_hierarchy_builds", ppe_hierarchy_builds},
                     {"particle_steps", particle_steps},
                     {"simulated", simulated}, {"limiting", limiting}};
    if (std::isfinite(min_dt)) j["min_dt"] = min_dt;
    return j;
  }
  static RunStatistics from_json(const nlohmann::json& j) {
    RunStatistics s;
    s.steps = j.at("steps").get<long long>();
    if (j.contains("min_dt")) s.min_dt = j.at("min_dt").get<double>();
    s.max_dt = j.at("max_dt").get<double>();
    s.ppe_iterations = j.at("ppe_iterations").get<long long>();
    s.max_ppe_iterations = j.at("max_ppe_iterations").get<int>();
    s.max_density_error = j.at("max_density_error").get<double>();
    s.wall_returned_particles = j.value("wall_returned_particles", 0LL);  // not in older checkpoints
    s.ppe_twin_failures = j.value("ppe_twin_failures", 0LL);              // nor this
    s.ppe_hierarchy_builds = j.value("ppe_hierarchy_builds", s.steps);    // nor this (built every step then)
    s.particle_steps = j.at("particle_steps").get<double>();
    s.simulated = j.at("simulated").get<double>();
    s.limiting = j.at("limiting").get<std::map<std::string, long long>>();
    return s;
  }
};

/// The time loop's own state: what a checkpoint keeps beside the solver's.
struct LoopState {
  double t = 0.0;
  double next_probe = 0.0;
  double next_field = 0.0;
  double next_checkpoint = std::numeric_limits<double>::infinity();
  double speed = 0.0;     ///< the step controller's inputs: the last step's largest speed
  double pressure = 0.0;  ///< and largest |P|
  RunStatistics stats;

  [[nodiscard]] nlohmann::json to_json() const {
    nlohmann::json j{{"t", t}, {"next_probe", next_probe}, {"next_field", next_field}, {"speed", speed},
                     {"pressure", pressure}, {"stats", stats.to_json()}};
    if (std::isfinite(next_checkpoint)) j["next_checkpoint"] = next_checkpoint;
    return j;
  }
  static LoopState from_json(const nlohmann::json& j) {
    LoopState s;
    s.t = j.at("t").get<double>();
    s.next_probe = j.at("next_probe").get<double>();
    s.next_field = j.at("next_field").get<double>();
    if (j.contains("next_checkpoint")) s.next_checkpoint = j.at("next_checkpoint").get<double>();
    s.speed = j.at("speed").get<double>();
    s.pressure = j.at("pressure").get<double>();
    s.stats = RunStatistics::from_json(j.at("stats"));
    return s;
  }
};


/// How far the wall's facets lie from the smooth wall they stand for, in L0
/// (WallCornerValues::largest_smooth_depth): logged, and a warning beyond what
/// was measured to be harmless.
///
/// Why. The wall terms see the smooth wall (wall_contacts.hpp), the particles
/// stop at the facets: between the two, a curved wall of coarse facets keeps a
/// liquid at rest stirring. Measured (2 ranks, 1 s; cases/hydrostatic_2d/README.md
/// and cases/hydrostatic_3d/README.md, "Coarse facets"): a 2D tank with a
/// half-circle floor on the square lattice, the largest speed over 0.5-1 s 0.09
/// m/s with its facets 0.0075 L0 off the smooth wall, 0.12 m/s at 0.015 L0,
/// 0.16 m/s at 0.03 L0, 0.36 m/s at 0.06 L0, 0.62 m/s at 0.12 L0, 1.1 m/s at
/// 0.24 L0 (the last three growing); the cylindrical tank at rest, filled in
/// rings, the same as with its fine wall (0.09-0.11 m/s) up to 0.44 L0, while
/// at 0.53 L0 its first ring, L0/2 inside the smooth wall, lies behind the
/// facets' middles: those particles are not filled, the liquid falls into
/// their places (0.37 m/s) and particles are put back in front of the facets.
/// Finer facets are the remedy (in a coupled run a finer structural mesh: its
/// surface is the wall).
double facet_gap_in_spacings(ProgramContext& context, const WallModel& walls, const FluidModel& model) {
  const bool two_d = model.dimension == 2;
  const double harmless = two_d ? 0.05 : 0.45;
  const char* measured = two_d ? "a 2D tank at rest: largest speed 0.36 m/s at 0.06 L0, 0.09 m/s at 0.0075 L0"
                               : "a cylindrical tank at rest: 0.37 m/s at 0.53 L0, where its first layer lies "
                                 "behind the facets, against 0.11 m/s at 0.44 L0 or less";
  const double gap = walls.corner_values().largest_smooth_depth(walls.mesh()) / model.spacing;
  context.log.info("walls: the facets lie up to ", gap, " L0 from the smooth wall they stand for");
  if (gap > harmless)
    context.log.warning("the wall's facets lie up to ", gap, " L0 (", gap * model.spacing,
                        " m) from the smooth wall they stand for, more than ", harmless,
                        " L0: a liquid at rest beside such a curved wall stirs (", measured,
                        "). Mesh the curved walls finer (a chord c of a wall of radius R lies c^2 / 8R from it; "
                        "in a coupled run the structure's mesh is the wall).");
  return gap;
}

}  // namespace

nlohmann::json run_fluid(ProgramContext& context, FluidCase c, const GroundMotion& motion) {
  const auto wall_clock_start = std::chrono::steady_clock::now();
  FluidSolver solver(context.comm, c.model, std::move(c.walls), std::move(c.particles), c.domain, c.ppe_options,
                     &context.timers);
  solver.rebalance_interval = c.rebalance_interval;
  std::optional<LoopState> resumed;
  std::optional<coupling::CouplingRestartState> coupling_state;
  if (context.restart) {
    const FluidRestart restart = read_fluid_state(context.comm, *context.restart);
    if (context.partner != MPI_COMM_NULL) {
      const Hdf5File file(context.comm, context.restart->path, FileMode::read);
      coupling_state = coupling::read_restart_state(file, "/coupling", true);
    }
    solver.resume(restart.state, restart.cuts);
    resumed = LoopState::from_json(restart.run_state);
    context.log.info("fluid: continues from t = ", resumed->t, " s, step ", resumed->stats.steps,
                     restart.cuts ? "" : " (particles balanced anew over this run's ranks)");
  }
  context.log.info("fluid: ", solver.global_particle_count(), " particles, ", solver.walls().mesh().triangle_count(),
                   " wall triangles, h = ", c.model.smoothing_length, " m, kernel ", kernel_name(c.model.kernel));
  // With a partner program, the walls on the structure's wetted surface move with it.
  std::unique_ptr<FluidCoupling> coupling;
  if (context.partner != MPI_COMM_NULL)
    coupling = std::make_unique<FluidCoupling>(context, solver, motion.acceleration(0.0),
                                               coupling_state ? &*coupling_state : nullptr);
  const double facet_gap = facet_gap_in_spacings(context, solver.walls(), c.model);
  Outputs outputs(context, c, solver, resumed ? std::optional<double>(resumed->t) : std::nullopt);
  // The input beside the results (a restarted run's folder has it already).
  const nlohmann::json excitation = resumed ? nlohmann::json::object() : write_ground_motion_probe(context, motion);
  const double checkpoint_interval = context.config.real("output.checkpoint_interval");
  LoopState loop;
  StepReport last;
  if (resumed) {
    loop = *resumed;
    // The output intervals may change on a restart: the next outputs follow this run's.
    loop.next_probe = next_output_time(loop.t, c.probe_interval);
    loop.next_field = next_output_time(loop.t, c.field_interval);
    loop.next_checkpoint = next_output_time(loop.t, checkpoint_interval);
  } else {
    outputs.sample(loop.t, last, loop.stats.wall_returned_particles);
    outputs.snapshot(loop.t, solver.particles(), solver.predicted_density(), solver.free_surface_flags());
    loop.next_probe = c.probe_interval;
    loop.next_field = c.field_interval;
    loop.next_checkpoint = next_output_time(0.0, checkpoint_interval);
    loop.speed = solver.max_speed();  // then each step's report carries them
    loop.pressure = solver.max_pressure();
  }
  double& t = loop.t;
  RunStatistics& stats = loop.stats;
  const double particle_steps_before = stats.particle_steps;
  CheckpointSeries checkpoints(context.comm, context.folder->path(), context.folder->program(),
                               context.restart ? context.restart->number + 1 : 1);
  double checkpoint_time = resumed ? resumed->t : -1.0;  // of the last one written
  const auto write_checkpoint = [&] {
    const auto scope = context.timers.time("checkpoint");
    checkpoint_time = t;
    outputs.flush();
    auto file = checkpoints.begin(t, context.config);
    write_fluid_state(*file, solver, loop.to_json());
    if (coupling) coupling::write_restart_state(*file, "/coupling", coupling->restart_state(), true);
    const auto path = checkpoints.commit(std::move(file));
    context.log.info("checkpoint ", path.string(), " at t = ", t, " s");
    return path;
  };
  const double end = c.end_time;
  // The state before the step under way: what a failed step leaves as the final snapshot and checkpoint.
  FluidSolver::Checkpoint last_good;
  solver.save(last_good);
  LoopState loop_good = loop;
  int rank = 0;
  MPI_Comm_rank(context.comm, &rank);
  ProgressLine progress("sph_solver", end, rank == 0 && ProgressLine::on_terminal());
  try {
    while (coupling ? coupling->ongoing() : t < end * (1.0 - 1e-12)) {
      const Eigen::Vector3d force = c.model.body_force(motion.acceleration(t));
      const auto limits = time_step_limits(c.model, c.cfl_number, c.adaptive_time_step ? c.max_time_step : c.fixed_time_step,
                                           loop.speed, force.norm(), loop.pressure);
      double dt = c.adaptive_time_step ? limits.smallest() : c.fixed_time_step;
      if (!c.adaptive_time_step) {
        // Stability bound of a fixed step: a particle must not cross h in one step.
        const auto bound = time_step_limits(c.model, 1.0, c.fixed_time_step, loop.speed, force.norm(), loop.pressure);
        if (dt > bound.smallest() * (1.0 + 1e-12))
          throw std::runtime_error("the fixed time step " + std::to_string(dt) + " s exceeds the " + bound.limiting() +
                                   " stability limit " + std::to_string(bound.smallest()) + " s at t = " +
                                   std::to_string(t) + " s (max speed " + std::to_string(loop.speed) +
                                   " m/s); use a smaller fluid.time_step.value or the adaptive mode");
      }
      // The last two steps share what is left when it is less than two steps: a
      // sudden short step would change the predictor's offset g dt^2 at the walls
      // that the settled particles balance (a 9 -> 6 ms step kicks a tank at rest
      // from 1e-3 to 3e-2 m/s). With a partner the window's end is the end to meet.
      const double remaining = coupling ? coupling->max_time_step() : end - t;
      if (remaining < 2.0 * dt) dt = remaining > dt ? 0.5 * remaining : remaining;
      solver.save(last_good);
      loop_good = loop;
      if (coupling) coupling->before_step(dt);
      last = solver.step(t, dt, motion.acceleration(t + 0.5 * dt));
      // CFL breach: the step was too long for the speed it reached.
      if (const double courant = realised_courant(c.model, last.max_speed, dt); courant > c.breach_courant) {
        const auto fastest = solver.fastest_particle();
        std::ostringstream where;
        where << "particle " << fastest.id << " at (" << fastest.position.x() << ", " << fastest.position.y() << ", "
              << fastest.position.z() << ") m";
        throw std::runtime_error("step " + std::to_string(solver.steps()) + " at t = " + number_text(t) +
                                 " s: CFL breach: the largest speed " + number_text(last.max_speed) +
                                 " m/s after a step of " + number_text(dt) + " s is a Courant number |v| dt / h = " +
                                 number_text(courant) + " above fluid.time_step.breach_courant = " +
                                 number_text(c.breach_courant) + " (" + where.str() + ")");
      }
      t += dt;
      stats.add(last, c.adaptive_time_step ? limits.limiting() : "fixed");  // every step computed
      const bool window_done = coupling ? coupling->after_step(dt) : true;
      if (coupling && coupling->rolled_back()) {
        t = coupling->time();  // a repeated window starts again from its saved state
        loop.speed = solver.max_speed();
        loop.pressure = solver.max_pressure();
        continue;
      }
      loop.speed = last.max_speed;
      loop.pressure = last.max_pressure;
      // The outputs of an implicit window wait until it is accepted.
      if (!window_done && coupling->repeats_windows()) continue;
      progress.update(t, stats.steps);
      if (t >= loop.next_probe * (1.0 - 1e-12)) {
        outputs.sample(t, last, stats.wall_returned_particles);
        loop.next_probe += c.probe_interval * std::max(1.0, std::floor((t - loop.next_probe) / c.probe_interval) + 1.0);
      }
      if (t >= loop.next_field * (1.0 - 1e-12)) {
        outputs.snapshot(t, solver.particles(), solver.predicted_density(), solver.free_surface_flags());
        loop.next_field += c.field_interval * std::max(1.0, std::floor((t - loop.next_field) / c.field_interval) + 1.0);
        progress.clear();  // the log line takes the line; the progress comes back after it
        context.log.info("t = ", t, " s, step ", stats.steps, ", dt = ", dt, " s, PPE ", last.ppe_iterations,
                         " iterations, max |v| = ", last.max_speed, " m/s");
      }
      // Checkpoints: alone after any step; coupled at the window ends both
      // programs agreed on (the coupling library's window-end records).
      const CheckpointDecision checkpoint =
          coupling ? checkpoint_after_window(*coupling)
                   : checkpoint_after_step(context.comm, t, checkpoint_interval, loop.next_checkpoint);
      if (checkpoint.due) {
        progress.clear();
        const auto path = write_checkpoint();
        if (checkpoint.stop_signal != 0) {
          if (coupling) coupling->finish();  // both checkpoints are complete before either program ends
          throw stopped_after_checkpoint(checkpoint.stop_signal, t, path);
        }
      }
    }
  } catch (const std::runtime_error& e) {
    // The error is collective (the solver's checks reduce over the ranks), so
    // every rank is here and may write. Alone, the last good state is also a
    // checkpoint to go on from (with a smaller step, say); a coupled run keeps
    // the pair's last common checkpoint instead.
    loop = loop_good;
    solver.restore(last_good);
    outputs.flush();
    outputs.snapshot(t + 1e-9, solver.particles(), {}, {});
    std::string saved = " is the final snapshot of fluid.xdmf";
    if (!coupling) saved += last_good_checkpoint(write_checkpoint);
    throw std::runtime_error(std::string(e.what()) + " — the last good state (t = " + number_text(t) + " s)" + saved);
  }
  progress.clear();
  outputs.flush();
  // The end state: a later run may go on from it (a longer end_time).
  if (!coupling && checkpoint_time != t) write_checkpoint();
  if (coupling) coupling->finish();
  const double wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_clock_start).count();
  const auto& force = outputs.last_total_force();
  nlohmann::json results{{"fluid",
           {{"particles", solver.global_particle_count()},
            // The kernel and h the run used: the case file may name neither (kernel.hpp's defaults).
            {"kernel", kernel_name(c.model.kernel)},
            {"smoothing_length_m", c.model.smoothing_length},
            // How far the wall's facets lie from the smooth wall they stand for (facet_gap_in_spacings).
            {"wall_facet_gap_L0", facet_gap},
            {"steps", stats.steps},  // every step computed, those of repeated implicit windows too
            {"end_time_s", t},
            {"time_step_s", {{"min", stats.min_dt}, {"max", stats.max_dt}, {"mean", stats.simulated / static_cast<double>(std::max<long long>(stats.steps, 1))}}},
            {"time_step_limited_by", stats.limiting},
            {"ppe_iterations", {{"mean", static_cast<double>(stats.ppe_iterations) / std::max<long long>(stats.steps, 1)},
                                {"max", stats.max_ppe_iterations}}},
            // Steps solved again with the operator's hierarchy (pressure_poisson.hpp).
            {"ppe_twin_failures", stats.ppe_twin_failures},
            // Steps that built BoomerAMG's hierarchy: every step, unless it is kept (kept_hierarchy.hpp).
            {"ppe_hierarchy_builds", stats.ppe_hierarchy_builds},
            {"max_density_error", stats.max_density_error},
            {"wall_returned_particles", stats.wall_returned_particles},  // wall_crossings.hpp
            {"overflow", {{"particles", solver.removed_count()}, {"volume_m3", solver.removed_volume()}}},
            {"final_wall_force_N", {force.x(), force.y(), force.z()}},
            {"wall_seconds", wall_seconds},  // of this process (a restarted run: since the restart)
            {"particle_steps_per_second", (stats.particle_steps - particle_steps_before) / wall_seconds},
            {"wall_seconds_per_simulated_second",
             t > (resumed ? resumed->t : 0.0) ? wall_seconds / (t - (resumed ? resumed->t : 0.0)) : 0.0}}}};
  results.update(excitation);
  if (resumed) results["fluid"]["restarted_at_s"] = resumed->t;
  if (coupling) results["fluid"]["coupling"] = coupling->summary();
  return results;
}

}  // namespace tankfsi::sph
