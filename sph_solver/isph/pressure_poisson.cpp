#include "sph_solver/isph/pressure_poisson.hpp"

#include "common/run/petsc_defaults.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

void check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc error in ") + what + " (code " + std::to_string(code) + ")");
}

}  // namespace

PressurePoisson::PressurePoisson(MPI_Comm comm, const std::string& case_options) : comm_(comm) {
  tankfsi::apply_default_petsc_options(case_options);
  create_solver();
}

void PressurePoisson::create_solver() {
  if (ksp_ != nullptr) KSPDestroy(&ksp_);
  check(KSPCreate(comm_, &ksp_), "KSPCreate");
  check(KSPSetOptionsPrefix(ksp_, "ppe_"), "KSPSetOptionsPrefix");
  check(KSPSetType(ksp_, KSPCG), "KSPSetType");
  PC pc = nullptr;
  check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  check(PCSetType(pc, PCHYPRE), "PCSetType");
  // rtol 1e-6 (of the preconditioned right-hand side's norm, CG's default
  // test). Against 1e-8 (the default until 2026-12-04) the dam break's front
  // and kinetic energy agree to five digits until the impact,
  // with 6.8 instead of 9.9 iterations a step and 11-17 % less wall time
  // (cases/dam_break_2d/README.md).
  check(KSPSetTolerances(ksp_, 1e-6, PETSC_DEFAULT, PETSC_DEFAULT, 1000), "KSPSetTolerances");
  check(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  // BoomerAMG builds a new hierarchy every step (the particles move), and that
  // set-up costs more than its V-cycles (cases/dam_break_2d/README.md): a
  // cheaper hierarchy — HMIS coarsening, ext+i interpolation of at most 4
  // entries a row, strong threshold 0.5, one aggressive level — takes about
  // twice the iterations and less time. Where the case or the command line
  // sets any of these, theirs holds.
  PCType type = nullptr;
  check(PCGetType(pc, &type), "PCGetType");
  if (type != nullptr && std::string(type) == PCHYPRE) {
    tankfsi::apply_default_petsc_options(
        "-ppe_pc_hypre_boomeramg_coarsen_type HMIS -ppe_pc_hypre_boomeramg_interp_type ext+i "
        "-ppe_pc_hypre_boomeramg_P_max 4 -ppe_pc_hypre_boomeramg_strong_threshold 0.5 "
        "-ppe_pc_hypre_boomeramg_agg_nl 1");
    check(PCSetFromOptions(pc), "PCSetFromOptions");
  }
}

std::string PressurePoisson::settings() const {
  // KSPView's full text needs an ASCII viewer (a string viewer shows only the
  // types); it writes to a FILE, here one in memory.
  char* buffer = nullptr;
  std::size_t size = 0;
  FILE* memory = open_memstream(&buffer, &size);
  if (memory == nullptr) throw std::runtime_error("PressurePoisson::settings: open_memstream failed");
  PetscViewer viewer = nullptr;
  PetscErrorCode code = PetscViewerASCIIOpenWithFILE(comm_, memory, &viewer);
  if (code == 0) code = KSPView(ksp_, viewer);
  PetscViewerDestroy(&viewer);
  std::fclose(memory);
  const std::string text(buffer, size);
  std::free(buffer);
  check(code, "KSPView");
  return text;
}

PressurePoisson::~PressurePoisson() {
  if (ksp_ != nullptr) KSPDestroy(&ksp_);
  if (matrix_ != nullptr) MatDestroy(&matrix_);
}

PpeSolveReport PressurePoisson::solve(const Neighbourhood& n, std::span<const double> mass,
                                      std::span<const double> density, std::span<const std::int64_t> global_index,
                                      std::span<const unsigned char> dirichlet, std::span<const double> source,
                                      std::span<double> pressure) {
  assemble(n, mass, density, global_index, dirichlet);
  return solve_assembled(source, pressure);
}

void PressurePoisson::sort_row(std::size_t begin) {
  // PETSc keeps a row's entries in column order; handed over in that order, the
  // whole row is copied at once (MAT_SORTED_FULL) instead of inserted entry by
  // entry. Insertion sort: a row is a few ascending runs (one per cell scanned).
  for (std::size_t k = begin + 1; k < columns_.size(); ++k) {
    const PetscInt column = columns_[k];
    const PetscScalar value = values_[k];
    std::size_t slot = k;
    for (; slot > begin && columns_[slot - 1] > column; --slot) {
      columns_[slot] = columns_[slot - 1];
      values_[slot] = values_[slot - 1];
    }
    columns_[slot] = column;
    values_[slot] = value;
  }
}

void PressurePoisson::assemble(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                               std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet) {
  const int owned = n.owned;
  const PetscInt first_row = owned > 0 ? static_cast<PetscInt>(global_index[0]) : 0;
  // The rows in CSR form, in buffers kept from step to step (no allocation once
  // they have grown to the problem's size).
  row_begin_.assign(1, 0);
  columns_.clear();
  values_.clear();
  diagonal_nonzeros_.assign(at(owned), 1);
  off_diagonal_nonzeros_.assign(at(owned), 0);
  for (int i = 0; i < owned; ++i) {
    const std::size_t diagonal_slot = values_.size();
    columns_.push_back(static_cast<PetscInt>(global_index[at(i)]));
    values_.push_back(1.0);
    if (dirichlet[at(i)] == 0) {
      double diagonal = 0.0;
      const NeighbourList& list = n.neighbours;
      for (int k = list.offsets[at(i)]; k < list.offsets[at(i) + 1]; ++k) {
        const int j = list.indices[at(k)];
        const double volume = (mass[at(i)] + mass[at(j)]) / (density[at(i)] + density[at(j)]);
        const double a = laplacian_weight(n.model, list.distances[at(k)], list.slopes[at(k)], volume);
        diagonal -= a;
        if (dirichlet[at(j)] != 0) continue;
        columns_.push_back(static_cast<PetscInt>(global_index[at(j)]));
        values_.push_back(a);
        ++(j < owned ? diagonal_nonzeros_ : off_diagonal_nonzeros_)[at(i)];
      }
      if (!n.surface.empty()) diagonal -= n.surface[at(i)].laplacian_share();
      // An isolated particle (no neighbours, all on the surface) would give a zero row.
      values_[diagonal_slot] = diagonal > 0.0 ? diagonal : 1.0;
      sort_row(diagonal_slot);
    }
    row_begin_.push_back(static_cast<PetscInt>(values_.size()));
  }

  if (matrix_ != nullptr) MatDestroy(&matrix_);
  dirichlet_.assign(dirichlet.begin(), dirichlet.begin() + owned);
  Mat& matrix = matrix_;
  check(MatCreateAIJ(comm_, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, 0, diagonal_nonzeros_.data(), 0,
                     off_diagonal_nonzeros_.data(), &matrix),
        "MatCreateAIJ");
  check(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  // Every row whole, in column order, its preallocation exact (sort_row()).
  check(MatSetOption(matrix, MAT_SORTED_FULL, PETSC_TRUE), "MatSetOption");
  for (int i = 0; i < owned; ++i) {
    const PetscInt global_row = first_row + i;
    const PetscInt begin = row_begin_[at(i)];
    check(MatSetValues(matrix, 1, &global_row, row_begin_[at(i) + 1] - begin, columns_.data() + begin,
                       values_.data() + begin, INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");

  // Every step's operator is a new matrix of another pattern, and often of
  // another size (particles migrate and leave): a new solver takes it, with
  // the same options. A KSP refuses a new local size without a reset, and
  // GAMG, reset or not, kept coarse levels sized for the old pattern ("Cannot
  // change local size of Amat after use", on some ranks only). BoomerAMG
  // builds its hierarchy anew every step either way.
  create_solver();
  solved_size_ = owned;
  check(KSPSetOperators(ksp_, matrix, matrix), "KSPSetOperators");
}

PpeSolveReport PressurePoisson::solve_assembled(std::span<const double> source, std::span<double> pressure,
                                                double residual_floor) {
  if (matrix_ == nullptr) throw std::logic_error("PressurePoisson::solve_assembled before assemble");
  const int owned = solved_size_;
  Vec rhs = nullptr;
  Vec solution = nullptr;
  check(MatCreateVecs(matrix_, &solution, &rhs), "MatCreateVecs");
  {
    PetscScalar* b = nullptr;
    PetscScalar* x = nullptr;
    check(VecGetArray(rhs, &b), "VecGetArray");
    check(VecGetArray(solution, &x), "VecGetArray");
    for (int i = 0; i < owned; ++i) {
      const bool surface = dirichlet_[at(i)] != 0;
      b[i] = surface ? 0.0 : -source[at(i)];
      x[i] = surface ? 0.0 : pressure[at(i)];
    }
    check(VecRestoreArray(rhs, &b), "VecRestoreArray");
    check(VecRestoreArray(solution, &x), "VecRestoreArray");
  }
  PetscReal rtol = 0.0;
  PetscReal atol = 0.0;
  PetscReal dtol = 0.0;
  PetscInt max_iterations = 0;
  check(KSPGetTolerances(ksp_, &rtol, &atol, &dtol, &max_iterations), "KSPGetTolerances");
  const bool floored = residual_floor > atol;
  if (floored) check(KSPSetTolerances(ksp_, rtol, residual_floor, dtol, max_iterations), "KSPSetTolerances");
  // Not handled: an error raised on some ranks only leaves the others inside
  // the solve's collectives (the job hangs); convergence failures are collective.
  const PetscErrorCode solve_code = KSPSolve(ksp_, rhs, solution);
  if (floored) check(KSPSetTolerances(ksp_, rtol, atol, dtol, max_iterations), "KSPSetTolerances");
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  PpeSolveReport report;
  PetscInt iterations = 0;
  KSPGetConvergedReason(ksp_, &reason);
  KSPGetIterationNumber(ksp_, &iterations);
  KSPGetResidualNorm(ksp_, &report.residual_norm);
  report.iterations = static_cast<int>(iterations);
  if (solve_code == 0 && reason > 0) {
    const PetscScalar* x = nullptr;
    VecGetArrayRead(solution, &x);
    for (int i = 0; i < owned; ++i) pressure[at(i)] = x[i];
    VecRestoreArrayRead(solution, &x);
  }
  VecDestroy(&rhs);
  VecDestroy(&solution);
  if (solve_code != 0) throw std::runtime_error("pressure solver failed with PETSc error " + std::to_string(solve_code));
  if (reason <= 0)
    throw std::runtime_error(std::string("pressure solver did not converge: ") + KSPConvergedReasons[reason] +
                             " after " + std::to_string(report.iterations) + " iterations, residual " +
                             std::to_string(report.residual_norm));
  return report;
}

}  // namespace tankfsi::sph
