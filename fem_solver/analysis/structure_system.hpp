#pragma once
// StructureSystem: the shell model set up for solving — partitioned over the
// ranks, DOFs numbered, K and the lumped mass assembled. setup_system and
// assemble_system of the deal.II skeleton; the analyses (static, modal,
// Newmark) take it from here.
#include <mpi.h>

#include <memory>

#include "common/log/stage_timers.hpp"
#include "fem_solver/assembly/shell_linear_solver.hpp"

namespace tankfsi::fem {

class StructureSystem {
 public:
  /// Stages timed (when `timers` is given): shell_setup, shell_assemble.
  StructureSystem(MPI_Comm comm, ShellModel model, const std::vector<DofConstraint>& constraints,
                  StageTimers* timers = nullptr);

  [[nodiscard]] const ShellModel& model() const { return model_; }
  [[nodiscard]] SystemAssembler& assembler() { return *assembler_; }
  [[nodiscard]] const SystemAssembler& assembler() const { return *assembler_; }
  [[nodiscard]] const DofMap& dofs() const { return *dofs_; }
  [[nodiscard]] const MeshPartition& partition() const { return partition_; }
  [[nodiscard]] Mat stiffness() const { return stiffness_.get(); }
  [[nodiscard]] Vec mass() const { return mass_.get(); }
  [[nodiscard]] MPI_Comm comm() const { return comm_; }
  [[nodiscard]] StageTimers* timers() const { return timers_; }
  /// A solver of `matrix` with the -shell_ options (factorises now, timed as shell_factorise).
  [[nodiscard]] std::unique_ptr<ShellLinearSolver> make_solver(Mat matrix) const;

 private:
  MPI_Comm comm_;
  ShellModel model_;
  MeshPartition partition_;
  std::unique_ptr<DofMap> dofs_;
  std::unique_ptr<SystemAssembler> assembler_;
  PetscMatrix stiffness_;
  PetscVector mass_;
  StageTimers* timers_;
};

}  // namespace tankfsi::fem
