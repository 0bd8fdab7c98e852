#pragma once
// StructureCoupling: fem_solver as the structure side of a coupled job
// (METHOD.md §4, coupling/participant.hpp). The wetted surface (element set
// "wetted") is the interface, vertex for vertex; each structure rank declares
// every size-th vertex. Every step the fluid's forces, ramped over the window
// (eq 17), load the interface; every window the interface displacements go to
// the fluid. Implicit windows roll the Newmark state back to the window start.
//
// The structure starts at rest, undeformed, in balance with the fluid's
// initial forces (its acceleration from them): a liquid present from t = 0
// loads the wall from t = 0.
#include <memory>
#include <nlohmann/json.hpp>

#include "common/run/program.hpp"
#include "coupling/participant.hpp"
#include "coupling/reports/window_report_file.hpp"
#include "fem_solver/analysis/structure_solver.hpp"

namespace tankfsi::fem {

/// Set-up check of a coupled structure case, before anything is written:
/// a coupling section, a dynamic analysis, a wetted set, a time step within the
/// window. Throws ConfigError naming the key.
void check_coupled_structure_case(const CaseConfig& config, const ShellMesh& mesh);

class StructureCoupling {
 public:
  /// Collective over both programs: handshake, interface, initial data. The
  /// solver must have its interface set.
  /// `resume`: a restart's coupling state and the interface displacements
  /// the fluid's walls start from (reference()); the solver then holds the
  /// checkpoint's state already.
  struct Resume {
    const coupling::CouplingRestartState& state;
    std::vector<double> reference;
  };
  StructureCoupling(ProgramContext& context, StructureSolver& solver, const Resume* resume = nullptr);

  [[nodiscard]] bool ongoing() const { return participant_.is_ongoing(); }
  [[nodiscard]] double max_time_step() const { return participant_.max_time_step(); }
  /// Before a step of dt: saves the state at a window start (implicit) and
  /// sets the interface loads at the step's end.
  void before_step(double dt);
  /// After the step: sends what the window needs; true when the step ended a
  /// window that was accepted (false: mid-window, or the window is repeated
  /// and the state is back at its start).
  bool after_step(double dt);
  /// Collective over both programs.
  void finish();
  /// As FluidCoupling: the agreed restart points and stop.
  [[nodiscard]] bool restart_point_due() { return participant_.restart_point_due(); }
  [[nodiscard]] int stop_signal() const { return participant_.stop_signal(); }
  [[nodiscard]] const coupling::CouplingRestartState& restart_state() const { return participant_.restart_state(); }
  /// Interface displacements (3 per vertex) the fluid's walls are at rest at.
  [[nodiscard]] const std::vector<double>& reference() const { return reference_; }
  [[nodiscard]] nlohmann::json summary() const;

 private:
  /// Reads the fluid's forces at relative_dt and sets them as the loads of
  /// every interface vertex (all-gather of the declared shares).
  void load_interface(double relative_dt);
  /// coupling.added_mass: computed: the liquid's added-mass operator into the interface's inertia.
  void carry_added_mass(ProgramContext& context);
  /// Every interface vertex's values (3 each) from each rank's declared ones (all-gather).
  [[nodiscard]] std::vector<double> gathered(const std::vector<double>& owned);

  StructureSolver& solver_;
  coupling::Participant participant_;
  std::vector<std::size_t> owned_;           ///< interface vertices this rank declares
  std::vector<int> counts_, displacements_;  ///< values per rank, for the all-gather of forces
  std::vector<std::size_t> order_;           ///< gathered position -> interface vertex
  std::vector<double> owned_values_, gathered_, loads_;
  StructureSolver::Checkpoint checkpoint_;
  std::unique_ptr<coupling::WindowReportFile> reports_;
  MPI_Comm comm_;
  std::vector<double> reference_;  ///< interface displacements the fluid's walls start from (3 per vertex)
  bool hold_ = false;          ///< coupling.structure_load: window_average
  double added_mass_ = 0.0;    ///< sum of the added-mass operator's entries (kg), coupling.added_mass: computed
  bool window_start_ = true;   ///< the next step starts a window
};

}  // namespace tankfsi::fem
