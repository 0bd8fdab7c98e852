#pragma once
// Participant: one program's end of the coupling (METHOD.md §4, DESIGN.md
// "Participant API"). Modelled on preCICE's Participant; it knows nothing of
// SPH or shells, only nodal arrays on the interface mesh.
//
//   Participant p(Side::structure, settings, local_comm, partner_comm, fingerprints);
//   p.set_interface(ids, coordinates, triangles);   // structure side: the wetted surface
//   p.exchange_interface();                         // handshake, mesh
//   p.write(Field::displacement, initial);          // optional initial data
//   p.initialize();
//   while (p.is_ongoing()) {
//     if (p.requires_writing_checkpoint()) save_state();
//     const double dt = std::min(my_dt, p.max_time_step());
//     p.read(Field::force, dt, load);                 // the load at the end of the step
//     solve(dt);
//     p.write(Field::displacement, u);
//     p.advance(dt);
//     if (p.requires_reading_checkpoint()) load_state();
//   }
//   p.finalize();
//
// Sides and fields (PROTOCOL.md, "Fields"):
//   fluid:     writes force (N, the force of the fluid on each interface
//              vertex; each rank its partial sums over the whole mesh, summed
//              over the fluid's ranks), every step before advance(dt);
//              reads displacement (m) and velocity (m/s) of every vertex.
//   structure: declares its vertices; writes displacement (m, relative to the
//              tank base) of its vertices, at least at the end of each window;
//              reads force on its vertices.
//   With coupling.added_mass: computed (PROTOCOL.md, "Added mass") the fluid
//   writes the added-mass operator (write_added_mass) before initialize(); the
//   structure takes its rows (added_mass()) after initialize() and carries
//   them in its inertia; the fluid holds back from the forces it writes the
//   impulse its liquid gave for its wall's velocity change at the window start
//   (read(Field::velocity_change) at at_window_start()).
// Time (eqs 16-18): the fluid's forces are averaged over the window (eq 16);
// the structure reads them ramped (eq 17, chi); the fluid reads a wall moving
// with constant velocity over the window (eq 18).
#include <mpi.h>

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "coupling/interface/interface_mesh.hpp"
#include "coupling/settings.hpp"

namespace tankfsi::coupling {

/// velocity_change: the fluid's, with coupling.added_mass: computed — the
/// wall velocity of this window less that of the last accepted one (zero
/// before the first), V - V' of eq 18: the jump the fluid's wall makes at the
/// window's start (PROTOCOL.md, "Added mass").
enum class Field { force, displacement, velocity, velocity_change };

/// The added-mass operator as the structure receives it (PROTOCOL.md, "Added
/// mass"; coupling/added_mass/added_mass.hpp): `normals`, 3 per interface
/// vertex in ascending id order; `rows`, for each vertex this rank declared
/// (declaration order) one row of A over all vertices (ascending id order):
/// its added mass is the block n_i A_ij n_j^T (kg) between the translations of i and j.
struct AddedMassRows {
  std::vector<double> normals;
  std::vector<double> rows;
};

/// What one coupling window did (the structure side knows the impulses).
struct WindowReport {
  int window = 0;  ///< 1-based
  double start_time = 0.0;
  double end_time = 0.0;
  int iterations = 1;
  bool converged = true;            ///< false: accepted after max_iterations
  double displacement_residual = -1;  ///< relative, last iteration; -1 where not measured
  double force_residual = -1;         ///< relative, last iteration; -1 where not measured
  /// Structure side: impulse the fluid gave for the force applied in this
  /// window (dt_c F̄, summed over vertices) and impulse the structure applied
  /// (integral of the ramp), N s, global axes; zero on the fluid side.
  std::array<double, 3> impulse_given{};
  std::array<double, 3> impulse_applied{};
};

/// What a restart of the coupling needs, taken at the end of an accepted
/// window at which both programs agreed to write a checkpoint
/// (Participant::restart_point_due()). On the fluid side every array is the
/// whole interface's, the same on every fluid rank (so the fluid may restart
/// on another rank count); on the structure side each rank's own part (it
/// restarts on as many ranks).
struct CouplingRestartState {
  int window = 1;            ///< the window to come (1-based)
  double window_start = 0.0;  ///< its start time (s)
  std::vector<WindowReport> reports;  ///< every accepted window so far
  /// input_start: the input at the window start (fluid: wall displacement;
  /// structure: load); last_output: the output of the window just ended;
  /// implicit controller: sent_input, controller_last, controller_previous
  /// and history_K (the acceleration's vectors).
  std::map<std::string, std::vector<double>> arrays;
  std::vector<double> history_numbers;  ///< the acceleration's numbers
};

/// Time this rank spent in the coupling (s): waiting for the partner, and
/// working (reductions, packing, acceleration).
struct CouplingTimings {
  double wait = 0.0;
  double work = 0.0;
};

class Participant {
 public:
  /// `local`: this program's ranks; `partner`: the inter-communicator to the
  /// other program (common/parallel/program_groups.hpp). `fingerprints`: the
  /// case_fingerprints() of the case this program read, compared with the
  /// partner's at the handshake (empty: not compared).
  Participant(Side side, const CouplingSettings& settings, MPI_Comm local, MPI_Comm partner,
              std::map<std::string, std::string> fingerprints = {});
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;

  /// Structure side, before initialize(): this rank's interface vertices
  /// (global ids, 3 coordinates each) and triangles (three vertex ids, any of
  /// them declared on any rank). Each vertex is declared on exactly one rank.
  void set_interface(const std::vector<std::int64_t>& ids, const std::vector<double>& coordinates,
                     const std::vector<std::array<std::int64_t, 3>>& triangles);

  /// Fluid side, before initialize(): this rank's own wall vertices (3
  /// coordinates each, the same on every fluid rank), when the fluid does not
  /// use the structure's mesh as its wall. Its arrays then hold 3 values per
  /// own vertex, mapped by nearest projection onto the structure's triangles
  /// (consistent for displacements, conservative for forces).
  void set_own_vertices(std::vector<double> coordinates);
  /// With own vertices: the largest distance of one from the structure's mesh (m).
  [[nodiscard]] double max_mapping_distance() const;

  /// Collective over both programs: handshake (protocol, settings, case) and
  /// the interface mesh, after which interface_mesh() is known (the fluid
  /// side needs it to write its initial forces). initialize() calls it if
  /// the program did not. Throws CouplingError on any mismatch, on both sides.
  void exchange_interface();
  /// Collective over both programs: exchanges the initial data (whatever was
  /// written since exchange_interface(); zero otherwise) and starts window 1.
  void initialize();

  /// Fluid: the whole interface mesh, vertices in ascending id order (the
  /// order of every array it reads and writes); structure: its own vertices
  /// in declaration order.
  [[nodiscard]] const InterfaceMesh& interface_mesh() const;
  /// Values (3 per vertex) in the arrays this rank reads and writes (fluid
  /// with own vertices: 3 per own vertex).
  [[nodiscard]] std::size_t value_count() const;

  [[nodiscard]] bool is_ongoing() const;
  [[nodiscard]] double time() const;
  /// How far this program may advance before the window ends.
  [[nodiscard]] double max_time_step() const;
  /// The field at `relative_dt` after the current time, within the window.
  void read(Field field, double relative_dt, std::span<double> values) const;
  void write(Field field, std::span<const double> values);
  /// Advances the coupling time by dt (at most max_time_step()); at the end of
  /// a window exchanges data as the scheme says, which may wait for the partner.
  void advance(double dt);

  /// Implicit coupling: true once at the start of each window (save your state).
  [[nodiscard]] bool requires_writing_checkpoint();
  /// Implicit coupling: true once after a window that must be repeated
  /// (restore your state; time() is back at the window start).
  [[nodiscard]] bool requires_reading_checkpoint();
  /// True when the last advance() ended a window that was accepted.
  [[nodiscard]] bool window_completed() const;
  /// True before the first advance() of a window (also of a repeated one).
  [[nodiscard]] bool at_window_start() const;
  /// Reports of every accepted window so far.
  [[nodiscard]] const std::vector<WindowReport>& window_reports() const;
  [[nodiscard]] CouplingTimings timings() const;

  /// Checkpoints for restarts (PROTOCOL.md, "Window ends"). At the end of
  /// every accepted window but the last the two programs exchange a
  /// window-end record: whether each wants a checkpoint there (its
  /// `interval` of coupled time reached since the last one; 0: never) and
  /// whether it must stop (a SIGTERM or SIGUSR1 received,
  /// common/run/stop_signal.hpp, or request_stop()). Either one's wish
  /// holds for both. Call before initialize() or resume().
  void set_restart_interval(double seconds);
  /// Asks the partners to stop at the end of the current window.
  void request_stop();
  /// True once after an advance() that ended an accepted window at which
  /// both programs write a checkpoint (one asked for it, one must stop, or
  /// the run's last window ended).
  [[nodiscard]] bool restart_point_due();
  /// The signal that made either program ask to stop (0: none; -1: asked by
  /// request_stop()): after writing its checkpoint the program ends.
  [[nodiscard]] int stop_signal() const;
  /// The state at the last restart point (after restart_point_due()).
  [[nodiscard]] const CouplingRestartState& restart_state() const;
  /// Collective over both programs, instead of initialize(): continues from
  /// a restart state written by this side at the same window as the
  /// partner's (each program re-sends the output of the window that ended).
  void resume(const CouplingRestartState& state);

  /// Collective over both programs: tells the partner this program is done.
  void finalize();

  /// Fluid, after exchange_interface(): the unit normal of each interface
  /// vertex (3 per vertex, ascending id order), the directions of the
  /// added-mass operator (coupling/added_mass/added_mass.hpp).
  [[nodiscard]] std::vector<double> interface_normals() const;
  /// Fluid, with coupling.added_mass: computed, before initialize(): the
  /// operator A (n x n row-major over the interface vertices in ascending id
  /// order, kg): A_ij the impulse on vertex i along -n_i when vertex j starts
  /// moving along n_j at 1 m/s; each rank its partial sums.
  void write_added_mass(std::span<const double> matrix);
  /// Structure, with coupling.added_mass: computed, after initialize().
  [[nodiscard]] AddedMassRows added_mass() const;

  class Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace tankfsi::coupling
