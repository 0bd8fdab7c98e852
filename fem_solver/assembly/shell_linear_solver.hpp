#pragma once
// ShellLinearSolver: the structural solve K_eff x = b, factorised (or
// preconditioned) once in the constructor and reused for every right-hand
// side — static loads, Newmark steps. Options prefix -shell_; default a direct
// Cholesky factorisation with MUMPS (-shell_ksp_type preonly -shell_pc_type
// cholesky -shell_pc_factor_mat_solver_type mumps). The rigid-body modes are
// attached as near-null space, so -shell_ksp_type cg -shell_pc_type gamg
// builds a smoothed-aggregation hierarchy that represents them.
#include <string>

#include "fem_solver/assembly/linear_solve.hpp"
#include "fem_solver/assembly/system_assembler.hpp"

namespace tankfsi::fem {

class ShellLinearSolver final : public LinearSolve {
 public:
  ShellLinearSolver(const SystemAssembler& assembler, Mat matrix);

  /// Throws std::runtime_error with PETSc's reason when the solve fails.
  void solve(Vec rhs, Vec solution) const override;
  /// "preonly/cholesky(mumps)" or "cg/gamg": what the options made of it.
  [[nodiscard]] std::string description() const;
  [[nodiscard]] int last_iterations() const { return iterations_; }

 private:
  PetscSolver ksp_;
  mutable int iterations_ = 0;
};

/// The six rigid-body motions of the structure over the free DOFs,
/// orthonormalised (translations x y z; rotations about x y z through the
/// centroid: u = e_k x (x - c), theta = e_k).
[[nodiscard]] std::vector<PetscVector> rigid_body_modes(const SystemAssembler& assembler);

}  // namespace tankfsi::fem
