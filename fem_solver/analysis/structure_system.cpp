#include "fem_solver/analysis/structure_system.hpp"

#include "fem_solver/analysis/optional_stage.hpp"

namespace tankfsi::fem {

StructureSystem::StructureSystem(MPI_Comm comm, ShellModel model, const std::vector<DofConstraint>& constraints,
                                 StageTimers* timers)
    : comm_(comm), model_(std::move(model)), timers_(timers) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm_, &rank);
  MPI_Comm_size(comm_, &size);
  {
    const auto stage = time_stage(timers_, "shell_setup");
    partition_ = partition_mesh(model_.mesh, comm_);
    dofs_ = std::make_unique<DofMap>(model_.mesh.nodes.size(), constraints, partition_, rank, size);
    assembler_ = std::make_unique<SystemAssembler>(comm_, model_, partition_, *dofs_);
  }
  const auto stage = time_stage(timers_, "shell_assemble");
  stiffness_ = assembler_->stiffness();
  mass_ = assembler_->lumped_mass();
}

std::unique_ptr<ShellLinearSolver> StructureSystem::make_solver(Mat matrix) const {
  const auto stage = time_stage(timers_, "shell_factorise");
  return std::make_unique<ShellLinearSolver>(*assembler_, matrix);
}

}  // namespace tankfsi::fem
