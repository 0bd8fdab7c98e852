#include "fem_solver/assembly/shell_linear_solver.hpp"

#include <Eigen/Geometry>

#include <sstream>
#include <stdexcept>

namespace tankfsi::fem {

std::vector<PetscVector> rigid_body_modes(const SystemAssembler& assembler) {
  const auto& nodes = assembler.model().mesh.nodes;
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& x : nodes) centre += x;
  centre /= static_cast<double>(nodes.size());
  std::vector<PetscVector> modes;
  for (int k = 0; k < 6; ++k) {
    NodalValues values(dofs_per_node * nodes.size(), 0.0);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (k < 3) {
        values[dofs_per_node * i + static_cast<std::size_t>(k)] = 1.0;
        continue;
      }
      const Eigen::Vector3d axis = Eigen::Vector3d::Unit(k - 3);
      const Eigen::Vector3d u = axis.cross(nodes[i] - centre);
      for (int c = 0; c < 3; ++c) {
        values[dofs_per_node * i + static_cast<std::size_t>(c)] = u(c);
        values[dofs_per_node * i + 3 + static_cast<std::size_t>(c)] = axis(c);
      }
    }
    PetscVector v = assembler.create_vector();
    assembler.scatter(values, v.get());
    // Gram-Schmidt against the modes so far (MatNullSpaceCreate wants them orthonormal).
    for (const auto& previous : modes) {
      PetscScalar dot = 0.0;
      petsc_check(VecDot(v.get(), previous.get(), &dot), "VecDot");
      petsc_check(VecAXPY(v.get(), -dot, previous.get()), "VecAXPY");
    }
    PetscReal norm = 0.0;
    petsc_check(VecNormalize(v.get(), &norm), "VecNormalize");
    if (norm > 1e-12) modes.push_back(std::move(v));  // fewer on a tiny or constrained model
  }
  return modes;
}

ShellLinearSolver::ShellLinearSolver(const SystemAssembler& assembler, Mat matrix) {
  std::vector<PetscVector> modes = rigid_body_modes(assembler);
  std::vector<Vec> raw;
  for (const auto& m : modes) raw.push_back(m.get());
  MatNullSpace near_null = nullptr;
  petsc_check(MatNullSpaceCreate(assembler.comm(), PETSC_FALSE, static_cast<PetscInt>(raw.size()), raw.data(), &near_null),
              "MatNullSpaceCreate");
  petsc_check(MatSetNearNullSpace(matrix, near_null), "MatSetNearNullSpace");
  petsc_check(MatNullSpaceDestroy(&near_null), "MatNullSpaceDestroy");

  petsc_check(KSPCreate(assembler.comm(), ksp_.out()), "KSPCreate");
  petsc_check(KSPSetOptionsPrefix(ksp_.get(), "shell_"), "KSPSetOptionsPrefix");
  petsc_check(KSPSetOperators(ksp_.get(), matrix, matrix), "KSPSetOperators");
  petsc_check(KSPSetType(ksp_.get(), KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp_.get(), &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  petsc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  // Iterative choices solve to 1e-10 relative: far below the benchmarks' 1 %
  // tolerances and the round-off agreement expected between rank counts.
  petsc_check(KSPSetTolerances(ksp_.get(), 1e-10, PETSC_DEFAULT, PETSC_DEFAULT, 10000), "KSPSetTolerances");
  petsc_check(KSPSetFromOptions(ksp_.get()), "KSPSetFromOptions");
  petsc_check(KSPSetUp(ksp_.get()), "KSPSetUp (factorisation)");
}

void ShellLinearSolver::solve(Vec rhs, Vec solution) const {
  const PetscErrorCode code = KSPSolve(ksp_.get(), rhs, solution);
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  KSPGetConvergedReason(ksp_.get(), &reason);
  PetscInt iterations = 0;
  KSPGetIterationNumber(ksp_.get(), &iterations);
  iterations_ = static_cast<int>(iterations);
  if (code != 0) throw std::runtime_error("the structural solve failed with PETSc error " + std::to_string(code));
  if (reason < 0)
    throw std::runtime_error(std::string("the structural solve did not converge: ") + KSPConvergedReasons[reason] +
                             " after " + std::to_string(iterations) + " iterations");
}

std::string ShellLinearSolver::description() const {
  KSPType ksp_type = nullptr;
  PCType pc_type = nullptr;
  PC pc = nullptr;
  KSPGetType(ksp_.get(), &ksp_type);
  KSPGetPC(ksp_.get(), &pc);
  PCGetType(pc, &pc_type);
  std::ostringstream out;
  out << ksp_type << "/" << pc_type;
  const std::string pc_name = pc_type;
  MatSolverType solver_type = nullptr;
  if ((pc_name == PCCHOLESKY || pc_name == PCLU) && PCFactorGetMatSolverType(pc, &solver_type) == 0 && solver_type != nullptr)
    out << "(" << solver_type << ")";
  return out.str();
}

}  // namespace tankfsi::fem
