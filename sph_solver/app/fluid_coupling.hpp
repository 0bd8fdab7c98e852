#pragma once
// FluidCoupling: sph_solver as the fluid side of a coupled job (METHOD.md §2,
// §4; coupling/participant.hpp). The structure's wetted surface replaces the
// fluid's own wall triangles on it, vertex for vertex (interface_wall.hpp);
// the fluid's other walls stay. The interface vertices, and the fluid's own
// vertices where its kept walls meet the wetted surface (mapped onto it by
// nearest projection), move with the structure every step (eq 18: constant
// velocity over the window, positions at the step's end); every step's forces
// of the fluid on them go to the structure (averaged over the window, eq 16).
// Implicit windows roll the particles back to the window start.
//
// A 2D fluid is a section of depth d (its walls are extruded over z in
// [-d/2, d/2]); its wall forces are per unit depth, and the structure (a strip
// across the section) receives the forces on the depth d: f d.
//
// With the added-mass operator (coupling.added_mass: computed) the forces
// sent leave out the normal part of the impulse the liquid's pressure gave for
// the wall's velocity change at each window's start, measured by one more PPE
// solve at the window's first step (coupling/added_mass/added_mass.hpp): the
// structure carries that inertia itself.
//
// At t = 0 the structure receives the forces of the liquid as it starts
// (FluidSolver::present_wall_forces): a structure that balances them (its
// initial acceleration) does not meet the liquid's weight as a sudden load.
#include <memory>
#include <nlohmann/json.hpp>

#include "common/run/program.hpp"
#include "coupling/participant.hpp"
#include "sph_solver/isph/fluid_solver.hpp"

namespace tankfsi::sph {

/// Set-up check of a coupled fluid case, before anything is written: a
/// coupling section, and a fixed time step (if any) within the window.
/// Throws ConfigError naming the key.
void check_coupled_fluid_case(const CaseConfig& config);

class FluidCoupling {
 public:
  /// Collective over both programs: handshake, interface, initial data.
  /// The structure receives the fluid's forces at t = 0 as its initial load
  /// (the liquid at rest under gravity and the ground acceleration a_g(0)).
  /// `resume`: a restart's coupling state; the coupling then goes on from it
  /// (the structure from its own checkpoint of the same window).
  FluidCoupling(ProgramContext& context, FluidSolver& solver, const Eigen::Vector3d& ground_acceleration,
                const coupling::CouplingRestartState* resume = nullptr);

  [[nodiscard]] bool ongoing() const { return participant_.is_ongoing(); }
  [[nodiscard]] double time() const { return participant_.time(); }
  [[nodiscard]] double max_time_step() const { return participant_.max_time_step(); }
  [[nodiscard]] bool repeats_windows() const { return repeats_; }
  /// Before a step of dt: saves the state at a window start (implicit) and
  /// moves the coupled wall vertices to where the structure is at the step's
  /// end; at a window start with the added-mass operator, has the step measure
  /// the impulse of the wall's velocity change.
  void before_step(double dt);
  /// After the step: gives the step's wall forces and advances the coupling;
  /// true when a window was accepted; false mid-window or when the window
  /// must be repeated (the particles are then back at its start, time() too).
  bool after_step(double dt);
  /// True when the last after_step() rolled the particles back (an implicit
  /// window to be repeated).
  [[nodiscard]] bool rolled_back() const { return rolled_back_; }
  /// True once when the window just accepted is a restart point both
  /// programs write a checkpoint at (Participant::restart_point_due()).
  [[nodiscard]] bool restart_point_due() { return participant_.restart_point_due(); }
  /// Nonzero when the programs agreed to stop there (the signal's number).
  [[nodiscard]] int stop_signal() const { return participant_.stop_signal(); }
  [[nodiscard]] const coupling::CouplingRestartState& restart_state() const { return participant_.restart_state(); }
  void finish();
  [[nodiscard]] nlohmann::json summary() const;

 private:
  void write_forces(const std::vector<Eigen::Vector3d>& forces);
  /// coupling.added_mass: computed: the wetted surface's added-mass operator to the coupling.
  void write_added_mass(ProgramContext& context);

  FluidSolver& solver_;
  coupling::Participant participant_;
  bool repeats_ = false;
  bool rolled_back_ = false;
  std::vector<Eigen::Vector3d> reference_;  ///< every wall vertex at rest
  std::vector<int> coupled_;                ///< wall vertices on the interface
  std::vector<double> values_, wall_velocity_;  ///< 3 per coupled vertex
  std::vector<Eigen::Vector3d> positions_, velocities_;
  FluidSolver::Checkpoint checkpoint_;
  double mapping_distance_ = 0.0;
  double force_scale_ = 1.0;  ///< the section depth in 2D (forces per unit depth -> on the section)
  double added_mass_ = 0.0;  ///< sum of the added-mass operator's entries (kg), coupling.added_mass: computed
  /// coupling.added_mass: computed: the interface vertices' normals (the
  /// operator's directions), along which the impulse of the wall's velocity
  /// change at each window start is held back from the forces sent.
  std::vector<Eigen::Vector3d> held_back_normals_;
  std::vector<double> velocity_change_;  ///< 3 per coupled vertex
};

}  // namespace tankfsi::sph
