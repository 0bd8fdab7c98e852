#include "fem_solver/analysis/normal_added_mass.hpp"

namespace tankfsi::fem {
namespace {

/// What the shell keeps: the factors and the two work vectors of length n.
struct Factors {
  Mat normal_map = nullptr;
  Mat operator_matrix = nullptr;
  Vec normal_part = nullptr;  ///< N x
  Vec reaction = nullptr;     ///< A N x
};

PetscErrorCode multiply(Mat shell, Vec x, Vec y) {
  Factors* f = nullptr;
  PetscCall(MatShellGetContext(shell, &f));
  PetscCall(MatMult(f->normal_map, x, f->normal_part));
  PetscCall(MatMult(f->operator_matrix, f->normal_part, f->reaction));
  PetscCall(MatMultTranspose(f->normal_map, f->reaction, y));
  return 0;
}

PetscErrorCode destroy(Mat shell) {
  Factors* f = nullptr;
  PetscCall(MatShellGetContext(shell, &f));
  PetscCall(VecDestroy(&f->normal_part));
  PetscCall(VecDestroy(&f->reaction));
  PetscCall(MatDestroy(&f->normal_map));
  PetscCall(MatDestroy(&f->operator_matrix));
  delete f;
  return 0;
}

}  // namespace

PetscMatrix make_normal_added_mass_product(Mat normal_map, Mat operator_matrix) {
  auto* f = new Factors{normal_map, operator_matrix};
  petsc_check(PetscObjectReference(reinterpret_cast<PetscObject>(normal_map)), "PetscObjectReference");
  petsc_check(PetscObjectReference(reinterpret_cast<PetscObject>(operator_matrix)), "PetscObjectReference");
  petsc_check(MatCreateVecs(normal_map, nullptr, &f->normal_part), "MatCreateVecs");
  petsc_check(VecDuplicate(f->normal_part, &f->reaction), "VecDuplicate");
  PetscInt local_columns = 0, columns = 0, rows = 0;
  petsc_check(MatGetLocalSize(normal_map, nullptr, &local_columns), "MatGetLocalSize");
  petsc_check(MatGetSize(normal_map, &rows, &columns), "MatGetSize");
  PetscMatrix shell;
  petsc_check(MatCreateShell(PetscObjectComm(reinterpret_cast<PetscObject>(normal_map)), local_columns, local_columns,
                             columns, columns, f, shell.out()),
              "MatCreateShell");
  petsc_check(MatShellSetOperation(shell.get(), MATOP_MULT, reinterpret_cast<void (*)(void)>(multiply)),
              "MatShellSetOperation");
  petsc_check(MatShellSetOperation(shell.get(), MATOP_DESTROY, reinterpret_cast<void (*)(void)>(destroy)),
              "MatShellSetOperation");
  return shell;
}

}  // namespace tankfsi::fem
