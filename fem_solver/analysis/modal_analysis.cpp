#include "fem_solver/analysis/modal_analysis.hpp"

#include <slepceps.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tankfsi::fem {
namespace {

void slepc_check(PetscErrorCode code, const char* what) { petsc_check(code, what); }

/// The diagonal mass as a matrix (SLEPc's B operator).
PetscMatrix diagonal_matrix(Vec diagonal, MPI_Comm comm) {
  PetscInt local = 0;
  PetscInt global = 0;
  petsc_check(VecGetLocalSize(diagonal, &local), "VecGetLocalSize");
  petsc_check(VecGetSize(diagonal, &global), "VecGetSize");
  PetscMatrix m;
  petsc_check(MatCreateAIJ(comm, local, local, global, global, 1, nullptr, 0, nullptr, m.out()), "MatCreateAIJ");
  petsc_check(MatDiagonalSet(m.get(), diagonal, INSERT_VALUES), "MatDiagonalSet");
  petsc_check(MatAssemblyBegin(m.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(m.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  petsc_check(MatSetOption(m.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  return m;
}

}  // namespace

ModalResult solve_modes(SystemAssembler& assembler, Mat stiffness, int count) {
  PetscBool slepc_ready = PETSC_FALSE;
  slepc_check(SlepcInitialized(&slepc_ready), "SlepcInitialized");
  if (!slepc_ready) slepc_check(SlepcInitializeNoArguments(), "SlepcInitializeNoArguments");

  PetscVector mass = assembler.lumped_mass();
  PetscMatrix mass_matrix = diagonal_matrix(mass.get(), assembler.comm());
  EPS eps = nullptr;
  slepc_check(EPSCreate(assembler.comm(), &eps), "EPSCreate");
  struct EpsGuard {
    EPS& eps;
    ~EpsGuard() { EPSDestroy(&eps); }
  } guard{eps};
  slepc_check(EPSSetOperators(eps, stiffness, mass_matrix.get()), "EPSSetOperators");
  slepc_check(EPSSetProblemType(eps, EPS_GHEP), "EPSSetProblemType");
  slepc_check(EPSSetDimensions(eps, count, PETSC_DEFAULT, PETSC_DEFAULT), "EPSSetDimensions");
  // Shift-and-invert about 0: the lowest omega^2 become the largest of
  // (K - 0 M)^-1 M, which Krylov-Schur finds first.
  slepc_check(EPSSetTarget(eps, 0.0), "EPSSetTarget");
  slepc_check(EPSSetWhichEigenpairs(eps, EPS_TARGET_MAGNITUDE), "EPSSetWhichEigenpairs");
  ST st = nullptr;
  slepc_check(EPSGetST(eps, &st), "EPSGetST");
  slepc_check(STSetType(st, STSINVERT), "STSetType");
  KSP ksp = nullptr;
  slepc_check(STGetKSP(st, &ksp), "STGetKSP");
  slepc_check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  PC pc = nullptr;
  slepc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  slepc_check(PCSetType(pc, PCCHOLESKY), "PCSetType");
  slepc_check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  slepc_check(EPSSetTolerances(eps, 1e-10, 1000), "EPSSetTolerances");
  slepc_check(EPSSetFromOptions(eps), "EPSSetFromOptions");
  slepc_check(EPSSolve(eps), "EPSSolve");
  PetscInt converged = 0;
  slepc_check(EPSGetConverged(eps, &converged), "EPSGetConverged");
  if (converged < count)
    throw std::runtime_error("the eigensolver converged " + std::to_string(converged) + " of the " +
                             std::to_string(count) + " modes asked for (raise -eps_max_it or -eps_ncv)");
  ModalResult result;
  PetscInt iterations = 0;
  EPSGetIterationNumber(eps, &iterations);
  result.iterations = static_cast<int>(iterations);

  std::array<PetscVector, 3> influence{assembler.mass_times_influence(0), assembler.mass_times_influence(1),
                                       assembler.mass_times_influence(2)};
  for (int k = 0; k < 3; ++k) {
    PetscReal sum = 0.0;
    petsc_check(VecSum(influence[static_cast<std::size_t>(k)].get(), &sum), "VecSum");
    result.free_mass(k) = sum;
  }
  PetscVector shape = assembler.create_vector();
  PetscVector mass_shape = assembler.create_vector();
  for (PetscInt i = 0; i < converged && static_cast<int>(result.modes.size()) < count; ++i) {
    PetscScalar lambda = 0.0;
    slepc_check(EPSGetEigenpair(eps, i, &lambda, nullptr, shape.get(), nullptr), "EPSGetEigenpair");
    // M-normalise (SLEPc's GHEP vectors are B-normalised already; this keeps
    // the participation factors right under any -eps_ options).
    PetscScalar norm2 = 0.0;
    petsc_check(VecPointwiseMult(mass_shape.get(), mass.get(), shape.get()), "VecPointwiseMult");
    petsc_check(VecDot(mass_shape.get(), shape.get(), &norm2), "VecDot");
    petsc_check(VecScale(shape.get(), 1.0 / std::sqrt(norm2)), "VecScale");
    NaturalMode mode;
    mode.omega = std::sqrt(std::max(lambda, 0.0));
    mode.frequency = mode.omega / (2.0 * std::numbers::pi);
    mode.period = mode.frequency > 0.0 ? 1.0 / mode.frequency : std::numeric_limits<double>::infinity();
    // The sign of a mode is arbitrary: make its largest-magnitude free DOF
    // positive so that runs on any number of ranks report the same shapes.
    PetscInt where = 0;
    PetscReal largest = 0.0;
    petsc_check(VecMax(shape.get(), &where, &largest), "VecMax");
    PetscReal smallest = 0.0;
    petsc_check(VecMin(shape.get(), &where, &smallest), "VecMin");
    if (-smallest > largest * (1.0 + 1e-9)) petsc_check(VecScale(shape.get(), -1.0), "VecScale");
    for (int k = 0; k < 3; ++k) {
      PetscScalar gamma = 0.0;
      petsc_check(VecDot(influence[static_cast<std::size_t>(k)].get(), shape.get(), &gamma), "VecDot");
      mode.participation(k) = gamma;
      mode.effective_mass(k) = gamma * gamma;
    }
    mode.shape = assembler.gather(shape.get(), 0.0);
    result.modes.push_back(std::move(mode));
  }
  std::sort(result.modes.begin(), result.modes.end(),
            [](const NaturalMode& a, const NaturalMode& b) { return a.omega < b.omega; });
  return result;
}

}  // namespace tankfsi::fem
