#pragma once
// FluidSolver: the ISPH time step (METHOD.md §1) on the particles of one rank of a
// spatially decomposed fluid, with triangle-patch walls (§2).
//
// One step n -> n+1:
//   0. particles outside the domain box are removed (overflow, counted); every
//      `rebalance_interval` steps the decomposition is recomputed and the owned
//      particles are re-sorted in cell order; particles migrate to their owners;
//      the halo (ghost particles within the kernel support plus a margin that
//      covers the step's motion) is rebuilt.
//   1. predictor at x^n: v* = v^n + dt (Morris viscosity + F); the PPE's positions
//      x~ = x^n + dt v^n. (METHOD.md's x* = x^n + dt v* adds the uniform shift
//      dt^2 F, which the fluid sums do not see but the walls do: a liquid at rest then
//      settles g dt^2 above its lattice and every change of dt kicks it — a 6 -> 4.5 ms
//      step took a settled tank from 6e-4 to 4e-3 m/s. x~ keeps what the prediction is
//      for: approaching particles are seen closer, which the step needs — evaluated
//      at x^n itself it turns unstable at 9 ms where x~ and x* are settled.)
//   2. PPE at x~: the kernel-sum density rho* (walls included, corners' overlaps
//      once) gives each particle near the free surface its air half-space beyond
//      the surface plane (free_surface.hpp: P = 0 on the plane, not at the
//      particle; every particle is an unknown); source
//      S = rho0/dt div v* + gamma (rho_L - rho^n)/dt^2, rho_L the lattice's rest
//      density and rho^n the density of the state x^n (the air completes it near
//      the surface); solve for P^{n+1} (PETSc)
//   3. corrector at x~: v^{n+1} = v* - dt grad P / rho, x^{n+1} = x^n + dt (v^n + v^{n+1})/2
//   4. shifting (Lind et al. 2012): dr = -D grad C with D = A h |v|max dt, capped at
//      0.2 L0, none on or next to a free-surface particle (density below beta rho0 or
//      div r below 1.5 / 2.4); the velocity follows the shift to first
//      order. grad C is taken at x~ with the step's neighbour list (one neighbour
//      search less than at x^{n+1}; the shift is a regularisation, not physics).
//   4b. pairs closer than close_pair_distance L0 at x^{n+1} + dr are parted
//      (close_pairs.hpp: a collapse where the shift is skipped); the velocity
//      follows this move too.
// Wall forces (force of the fluid on each wall vertex) of the step: the viscous
// part at x^n plus the pressure part at x~.
#include <mpi.h>

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/log/stage_timers.hpp"
#include "sph_solver/isph/fluid_model.hpp"
#include "sph_solver/isph/pressure_poisson.hpp"
#include "sph_solver/isph/wall_contacts.hpp"
#include "sph_solver/isph/wall_crossings.hpp"
#include "sph_solver/kernels/kernel.hpp"
#include "sph_solver/parallel/domain_decomposition.hpp"
#include "sph_solver/parallel/halo.hpp"
#include "sph_solver/particles/particles.hpp"

namespace tankfsi::sph {

struct StepReport {
  double time_step = 0.0;
  int ppe_iterations = 0;
  double ppe_residual = 0.0;
  /// The pressure solve failed with BoomerAMG on the operator's twin and was
  /// solved with the operator's hierarchy (pressure_poisson.hpp).
  bool ppe_twin_failed = false;
  /// The pressure solve built its preconditioner's hierarchy (always, unless
  /// one is kept: fluid.ppe.keep_hierarchy).
  bool ppe_hierarchy_built = false;
  long long free_surface_particles = 0;  ///< all ranks
  long long removed_particles = 0;       ///< this step, all ranks
  long long wall_returned_particles = 0; ///< this step, all ranks: put back in front of a wall (wall_crossings.hpp)
  long long particles = 0;               ///< in the step, all ranks
  double max_speed = 0.0;                ///< after the step, all ranks
  double max_pressure = 0.0;             ///< largest |P| of the step, all ranks
  double max_density_error = 0.0;        ///< max |rho* - rho0| / rho0 over the liquid's interior
};

class FluidSolver {
 public:
  /// `particles`: the initial particles, the same complete set on every rank
  /// (filling is deterministic); each rank keeps its share. `domain`: particles
  /// leaving it are removed. Collective.
  FluidSolver(MPI_Comm comm, const FluidModel& model, TriangleMesh walls, Particles particles,
              const Eigen::AlignedBox3d& domain, const std::string& ppe_options, StageTimers* timers = nullptr);

  /// Advances by dt from time t under ground acceleration a_g (the body force is
  /// F = g - a_g at t + dt/2). Collective. Throws std::runtime_error if the PPE
  /// fails, dt breaches the motion margin of the halo, or the step leaves a
  /// non-finite field or a particle that went through a wall (beyond the small
  /// overshoots it puts back: wall_crossings.hpp).
  StepReport step(double t, double dt, const Eigen::Vector3d& ground_acceleration);

  /// Collective: this rank's share of the force of the fluid on each wall
  /// vertex in the present state, with the particles' present pressures and
  /// under the body force of ground acceleration a_g (the walls' Neumann
  /// pressure gradient rho (g - a_g) . n for a liquid at rest): the forces a
  /// coupled structure carries at t = 0 (the viscous part from the particles'
  /// present velocities). The particles are not changed.
  [[nodiscard]] std::vector<Eigen::Vector3d> present_wall_forces(const Eigen::Vector3d& ground_acceleration);

  /// Collective: this rank's share of the added-mass operator of the given
  /// wall vertices (coupling/added_mass/added_mass.hpp), row-major
  /// count x count, kg: A_ij = -(impulse of the liquid on vertex i) . n_i when
  /// the walls, at rest under a liquid at rest, start moving at vertex j along
  /// n_j at 1 m/s (its triangles' velocities interpolated as always): the
  /// pressure impulse of one projection with the walls' Neumann condition
  /// alone (METHOD.md §2). The PPE matrix is assembled once, one solve per
  /// column. Particles and walls are left as they were.
  [[nodiscard]] std::vector<double> added_mass_operator(std::span<const int> vertices,
                                                        std::span<const Eigen::Vector3d> normals);

  /// Replaces the walls before the first step (a coupled run's wall, whose
  /// part on the structure's wetted surface is the structure's own mesh);
  /// `two_sided`: per triangle, or empty (WallModel::replace_mesh).
  void replace_walls(TriangleMesh walls, std::vector<char> two_sided = {}) {
    walls_.replace_mesh(std::move(walls), std::move(two_sided));
    wall_force_.assign(walls_.mesh().vertex_count(), Eigen::Vector3d::Zero());
  }
  /// Moves the walls (a coupled, deforming structure): every wall vertex's
  /// position and velocity, tank-base frame.
  void move_walls(std::span<const Eigen::Vector3d> positions, std::span<const Eigen::Vector3d> velocities) {
    walls_.move(positions, velocities);
  }
  /// What an implicit coupling window rolls back to: this rank's particles and
  /// the counters (the walls are moved again by the next step's coupling),
  /// and the pressure solver's kept hierarchy, so that a window taken again
  /// from it is solved as the first time (a checkpoint file holds the rows it
  /// was built on: sph_solver/app/fluid_checkpoint.hpp).
  struct Checkpoint {
    Particles particles;
    long long steps = 0;
    long long removed_count = 0;
    double removed_volume = 0.0;
    PressurePoisson::KeptState pressure_solver;
  };
  void save(Checkpoint& checkpoint) const {
    checkpoint = {particles_, steps_, removed_count_, removed_volume_, ppe_.kept_state()};
  }
  /// The pressure solver's kept hierarchy, for a checkpoint file.
  [[nodiscard]] PressurePoisson::KeptState kept_pressure_hierarchy() const { return ppe_.kept_state(); }
  void restore(const Checkpoint& checkpoint) {
    particles_ = checkpoint.particles;
    steps_ = checkpoint.steps;
    removed_count_ = checkpoint.removed_count;
    removed_volume_ = checkpoint.removed_volume;
    ppe_.resume(checkpoint.pressure_solver);
  }

  /// What a restart puts back (sph_solver/app/fluid_checkpoint.hpp): this
  /// rank's particles and counters; `cuts` the decomposition's cuts when the
  /// particles are each rank's own of a run on as many ranks (the state is
  /// then the one written, bit for bit), none when they are any share of
  /// them (another rank count: balanced and migrated anew). Collective.
  void resume(const Checkpoint& state, const std::optional<std::vector<double>>& cuts);
  [[nodiscard]] std::vector<double> decomposition_cuts() const { return decomposition_.cuts(); }
  [[nodiscard]] long long steps() const { return steps_; }

  /// Collective: the fastest particle over all ranks (the lowest id among equals).
  struct FastestParticle {
    std::int64_t id = -1;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  };
  [[nodiscard]] FastestParticle fastest_particle() const;

  /// Collective: the largest speed over all ranks.
  [[nodiscard]] double max_speed() const;
  /// Collective: the largest |P| of the particles over all ranks.
  [[nodiscard]] double max_pressure() const;

  [[nodiscard]] const FluidModel& model() const { return model_; }
  [[nodiscard]] const Kernel& kernel() const { return kernel_; }
  [[nodiscard]] const Particles& particles() const { return particles_; }
  [[nodiscard]] const WallModel& walls() const { return walls_; }
  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  /// This rank's contribution to the force of the fluid on each wall vertex in the
  /// last step (sum over ranks with total_wall_forces()).
  [[nodiscard]] const std::vector<Eigen::Vector3d>& local_wall_forces() const { return wall_force_; }

  /// The change of the walls' vertex velocities at the start of the next step
  /// (a coupled window's start, V - V' of eq 18; one vector per wall vertex),
  /// whose share of that step's wall forces the step measures apart: one more
  /// PPE solve with the step's operator and the walls' motion as the only
  /// source (as added_mass_operator() does for one vertex at a time). Used
  /// once: the step after has no jump unless set again.
  void set_wall_velocity_jump(std::vector<Eigen::Vector3d> jump) { wall_velocity_jump_ = std::move(jump); }
  /// This rank's share of the impulse on each wall vertex of the last step's
  /// velocity jump (the jump's part of local_wall_forces() times the step);
  /// empty if that step had none.
  [[nodiscard]] const std::vector<Eigen::Vector3d>& local_jump_impulse() const { return jump_impulse_; }
  /// Collective: the wall forces of the last step summed over the ranks.
  [[nodiscard]] std::vector<Eigen::Vector3d> total_wall_forces() const;
  /// Collective: all particles removed so far and their volume (mass / rho0).
  [[nodiscard]] long long removed_count() const { return removed_count_; }
  [[nodiscard]] double removed_volume() const { return removed_volume_; }
  [[nodiscard]] long long global_particle_count() const;
  /// The kernel-sum density rho* (walls included) of each owned particle at the
  /// PPE's positions x~ of the last step, in the order of particles(); NaN before
  /// the first step.
  [[nodiscard]] const std::vector<double>& predicted_density() const { return predicted_density_; }
  /// 1 for each owned particle that was a free-surface (Dirichlet) particle in the
  /// last step's PPE, else 0; NaN before the first step.
  [[nodiscard]] const std::vector<double>& free_surface_flags() const { return free_surface_flags_; }

  int rebalance_interval = 20;

 private:
  void remove_escaped();
  /// Collective: the PPE's global row of each owned particle (ranks in order).
  [[nodiscard]] std::vector<std::int64_t> global_indices() const;
  /// Collective: each particle's moment against the lattice's, owned then ghosts
  /// (moment_scale() and smoothed_moment_scale(), particle_terms.hpp).
  [[nodiscard]] std::vector<double> moment_scales(const Neighbourhood& n, std::span<const double> mass,
                                                  std::span<const double> density,
                                                  std::span<const unsigned char> free_surface);
  /// "step N at t = T s: " for the step starting at t.
  [[nodiscard]] std::string step_prefix(double t) const;
  /// Collective: throws std::runtime_error naming the step, the time and the
  /// first particle (lowest id) when a position, velocity or pressure is not finite.
  void check_finite(double t) const;
  /// Collective, after a step: the same when a particle's path from `start` (its
  /// position at the step's start) to its position now went through a wall
  /// (the walls as they are at the step's end) further than return_to_walls()
  /// puts back: its `crossings` (wall_crossings.hpp).
  void check_crossings(const WallCrossings& crossings, const std::vector<Eigen::Vector3d>& start, double t) const;
  void redistribute();
  /// The impulse on each wall vertex (this rank's share) of the pressure of
  /// one projection whose only source is the walls' motion as n.walls holds
  /// it (the contacts' velocities), with v* = 0 and dt = 1, by the PPE
  /// operator last assembled; `pressure` is the solution (owned and ghosts),
  /// solved to `residual_floor` (PressurePoisson::solve_assembled) if not 0.
  [[nodiscard]] std::vector<Eigen::Vector3d> wall_motion_impulse(const Neighbourhood& n, std::span<const double> mass,
                                                                 std::span<const double> density,
                                                                 std::vector<double>& pressure,
                                                                 double residual_floor = 0.0);
  /// Balances, migrates and puts the owned particles in cell order.
  void rebalance();
  StageTimers::Scope stage(const std::string& name);

  MPI_Comm comm_;
  int rank_ = 0;
  FluidModel model_;
  Kernel kernel_;
  WallModel walls_;
  Particles particles_;
  Eigen::AlignedBox3d domain_;
  DomainDecomposition decomposition_;
  Halo halo_;
  PressurePoisson ppe_;
  StageTimers* timers_;
  StageTimers fallback_timers_;
  std::vector<Eigen::Vector3d> wall_force_;
  std::vector<Eigen::Vector3d> wall_velocity_jump_;  ///< set_wall_velocity_jump(), for the next step
  std::vector<Eigen::Vector3d> jump_impulse_;        ///< local_jump_impulse()
  std::vector<double> predicted_density_;
  std::vector<double> free_surface_flags_;
  long long steps_ = 0;
  long long removed_count_ = 0;
  double removed_volume_ = 0.0;
  long long removed_this_step_ = 0;
  long long particles_after_removal_ = 0;
};

}  // namespace tankfsi::sph
