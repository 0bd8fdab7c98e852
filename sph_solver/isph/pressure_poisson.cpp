#include "sph_solver/isph/pressure_poisson.hpp"

#include "common/run/petsc_defaults.hpp"
#include "common/run/petsc_handle.hpp"

#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace tankfsi::sph {
namespace {

std::size_t at(int i) { return static_cast<std::size_t>(i); }

}  // namespace

PressurePoisson::PressurePoisson(MPI_Comm comm, const std::string& case_options) : comm_(comm) {
  tankfsi::apply_default_petsc_options(case_options);
  create_solver();
}

void PressurePoisson::create_solver() {
  if (ksp_ != nullptr) KSPDestroy(&ksp_);
  petsc_check(KSPCreate(comm_, &ksp_), "KSPCreate");
  petsc_check(KSPSetOptionsPrefix(ksp_, "ppe_"), "KSPSetOptionsPrefix");
  petsc_check(KSPSetType(ksp_, KSPCG), "KSPSetType");
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCHYPRE), "PCSetType");
  // rtol 1e-6 (of the preconditioned right-hand side's norm, CG's default
  // test). Against 1e-8 (the default until 2026-12-04) the dam break's front
  // and kinetic energy agree to five digits until the impact,
  // with 6.8 instead of 9.9 iterations a step and 11-17 % less wall time
  // (cases/dam_break_2d/README.md).
  petsc_check(KSPSetTolerances(ksp_, 1e-6, PETSC_DEFAULT, PETSC_DEFAULT, 1000), "KSPSetTolerances");
  petsc_check(KSPSetInitialGuessNonzero(ksp_, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  petsc_check(KSPSetFromOptions(ksp_), "KSPSetFromOptions");
  // BoomerAMG's hierarchy is built anew for the particles' new places (every
  // step, or when a kept one no longer serves), and that set-up costs more
  // than its V-cycles (cases/dam_break_2d/README.md): a
  // cheaper hierarchy — HMIS coarsening, ext+i interpolation of at most 4
  // entries a row, strong threshold 0.5, one aggressive level — takes about
  // twice the iterations and less time. Where the case or the command line
  // sets any of these, theirs holds.
  PCType type = nullptr;
  petsc_check(PCGetType(pc, &type), "PCGetType");
  const char* hypre_type = nullptr;
  if (type != nullptr && std::string(type) == PCHYPRE) petsc_check(PCHYPREGetType(pc, &hypre_type), "PCHYPREGetType");
  multigrid_ = hypre_type != nullptr && std::string(hypre_type) == "boomeramg";
  if (multigrid_) {
    tankfsi::apply_default_petsc_options(
        "-ppe_pc_hypre_boomeramg_coarsen_type HMIS -ppe_pc_hypre_boomeramg_interp_type ext+i "
        "-ppe_pc_hypre_boomeramg_P_max 4 -ppe_pc_hypre_boomeramg_strong_threshold 0.5 "
        "-ppe_pc_hypre_boomeramg_agg_nl 1");
    petsc_check(PCSetFromOptions(pc), "PCSetFromOptions");
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
  petsc_check(code, "KSPView");
  return text;
}

PressurePoisson::~PressurePoisson() {
  if (ksp_ != nullptr) KSPDestroy(&ksp_);
  if (matrix_ != nullptr) MatDestroy(&matrix_);
  if (twin_ != nullptr) MatDestroy(&twin_);
}

PpeSolveReport PressurePoisson::solve(const Neighbourhood& n, std::span<const double> mass,
                                      std::span<const double> density, std::span<const std::int64_t> global_index,
                                      std::span<const unsigned char> dirichlet, std::span<const double> source,
                                      std::span<double> pressure, std::span<const std::int64_t> particle_id) {
  assemble(n, mass, density, global_index, dirichlet, particle_id);
  return solve_assembled(source, pressure);
}

void PressurePoisson::Rows::Block::clear() {
  begin.assign(1, 0);
  columns.clear();
  values.clear();
  // A block without entries still hands PETSc arrays, not null pointers.
  columns.reserve(1);
  values.reserve(1);
}

void PressurePoisson::Rows::clear() {
  diagonal.clear();
  off_diagonal.clear();
}

void PressurePoisson::Rows::add(PetscInt row, PetscScalar diagonal_value, const std::vector<RowEntry>& entries,
                                PetscInt owned_begin, PetscInt owned_end, double max_distance) {
  // The diagonal in its place among the diagonal block's columns (each block's
  // rows in column order, as PETSc keeps them).
  bool diagonal_placed = false;
  const auto place_diagonal = [&] {
    diagonal.columns.push_back(row - owned_begin);
    diagonal.values.push_back(diagonal_value);
    diagonal_placed = true;
  };
  for (const RowEntry& e : entries) {
    if (e.distance > max_distance) continue;
    if (e.column >= owned_begin && e.column < owned_end) {
      if (!diagonal_placed && e.column > row) place_diagonal();
      diagonal.columns.push_back(e.column - owned_begin);
      diagonal.values.push_back(e.value);
    } else {
      off_diagonal.columns.push_back(e.column);
      off_diagonal.values.push_back(e.value);
    }
  }
  if (!diagonal_placed) place_diagonal();
  diagonal.end_row();
  off_diagonal.end_row();
}

Mat PressurePoisson::create_matrix(Rows& rows) const {
  const auto owned = static_cast<PetscInt>(rows.diagonal.begin.size() - 1);
  Mat matrix = nullptr;
  // PETSc takes the blocks as they are (no copy): the off-diagonal block's
  // columns are renumbered in place when the matrix is assembled.
  petsc_check(MatCreateMPIAIJWithSplitArrays(comm_, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE,
                                             rows.diagonal.begin.data(), rows.diagonal.columns.data(),
                                             rows.diagonal.values.data(), rows.off_diagonal.begin.data(),
                                             rows.off_diagonal.columns.data(), rows.off_diagonal.values.data(),
                                             &matrix),
              "MatCreateMPIAIJWithSplitArrays");
  petsc_check(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  return matrix;
}

void PressurePoisson::assemble(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                               std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet,
                               std::span<const std::int64_t> particle_id) {
  const int owned = n.owned;
  const PetscInt first_row = owned > 0 ? static_cast<PetscInt>(global_index[0]) : 0;
  const PetscInt end_row = first_row + owned;
  const double twin_radius = multigrid_ ? n.model.preconditioner_radius * n.model.spacing : 0.0;
  const bool with_twin = twin_radius > 0.0;
  // The last step's matrices live on the rows' arrays (create_matrix()): they,
  // and the solver that holds them, go before the arrays are refilled.
  if (ksp_ != nullptr) KSPDestroy(&ksp_);
  if (matrix_ != nullptr) MatDestroy(&matrix_);
  if (twin_ != nullptr) MatDestroy(&twin_);
  operator_rows_.clear();
  if (with_twin) {
    twin_rows_.clear();
    twin_air_.assign(at(owned), 0.0);
  }
  // sum a_ij r_ij^2 over the twin's pairs and over all (the second moments).
  double moments[2] = {0.0, 0.0};
  constexpr double everything = std::numeric_limits<double>::infinity();
  for (int i = 0; i < owned; ++i) {
    entries_.clear();
    const auto row = static_cast<PetscInt>(global_index[at(i)]);
    if (dirichlet[at(i)] != 0) {
      operator_rows_.add(row, 1.0, entries_, first_row, end_row, everything);
      if (with_twin) twin_rows_.add(row, 1.0, entries_, first_row, end_row, everything);
      continue;
    }
    double diagonal = 0.0, twin_diagonal = 0.0;
    const NeighbourList& list = n.neighbours;
    for (int k = list.offsets[at(i)]; k < list.offsets[at(i) + 1]; ++k) {
      const int j = list.indices[at(k)];
      const double r = list.distances[at(k)];
      const double volume = (mass[at(i)] + mass[at(j)]) / (density[at(i)] + density[at(j)]);
      const double a = laplacian_weight(n.model, r, list.slopes[at(k)], volume);
      diagonal -= a;
      if (with_twin) {
        moments[1] += a * r * r;
        if (r <= twin_radius) {
          moments[0] += a * r * r;
          twin_diagonal -= a;
        }
      }
      if (dirichlet[at(j)] != 0) continue;
      entries_.push_back({static_cast<PetscInt>(global_index[at(j)]), a, r});
    }
    // Column order. Insertion sort: a row is a few ascending runs (one per cell scanned).
    for (std::size_t k = 1; k < entries_.size(); ++k) {
      const RowEntry e = entries_[k];
      std::size_t slot = k;
      for (; slot > 0 && entries_[slot - 1].column > e.column; --slot) entries_[slot] = entries_[slot - 1];
      entries_[slot] = e;
    }
    const double air = n.surface.empty() ? 0.0 : n.surface[at(i)].laplacian_share();
    diagonal -= air;
    // An isolated particle (no neighbours, all on the surface) would give a zero row.
    operator_rows_.add(row, diagonal > 0.0 ? diagonal : 1.0, entries_, first_row, end_row, everything);
    if (with_twin) {
      twin_rows_.add(row, twin_diagonal, entries_, first_row, end_row, twin_radius);
      twin_air_[at(i)] = air;
    }
  }

  dirichlet_.assign(dirichlet.begin(), dirichlet.begin() + owned);
  matrix_ = create_matrix(operator_rows_);
  if (with_twin) {
    MPI_Allreduce(MPI_IN_PLACE, moments, 2, MPI_DOUBLE, MPI_SUM, comm_);
    // No pair within the radius anywhere (particles all apart): the operator is
    // the preconditioner's matrix.
    if (moments[0] < 0.0) {
      const double scale = moments[1] / moments[0];
      for (PetscScalar& value : twin_rows_.off_diagonal.values) value *= scale;
      Rows::Block& block = twin_rows_.diagonal;
      for (int i = 0; i < owned; ++i) {
        if (dirichlet_[at(i)] != 0) continue;
        for (PetscInt k = block.begin[at(i)]; k < block.begin[at(i) + 1]; ++k) {
          PetscScalar& value = block.values[static_cast<std::size_t>(k)];
          if (block.columns[static_cast<std::size_t>(k)] != i) {
            value *= scale;
          } else {
            value = scale * value - twin_air_[at(i)];
            if (!(value > 0.0)) value = 1.0;  // isolated, as in the operator
          }
        }
      }
      twin_ = create_matrix(twin_rows_);
    }
  }

  // Every step's operator is a new matrix of another pattern, and often of
  // another size (particles migrate and leave): a new solver takes it, with
  // the same options. A KSP refuses a new local size without a reset, and
  // GAMG, reset or not, kept coarse levels sized for the old pattern ("Cannot
  // change local size of Amat after use", on some ranks only). BoomerAMG's
  // hierarchy is built anew every step either way, or kept apart from the
  // solver (kept_hierarchy.hpp).
  solved_size_ = owned;
  keeping_ = multigrid_ && n.model.keep_hierarchy && !particle_id.empty();
  first_solve_ = true;
  if (keeping_) {
    ids_.assign(particle_id.begin(), particle_id.begin() + owned);
    use_kept_hierarchy(preconditioning_matrix(), kept_.rebuild);
    return;
  }
  create_solver();
  petsc_check(KSPSetOperators(ksp_, matrix_, preconditioning_matrix()), "KSPSetOperators");
  // With the twin, convergence is judged on the operator's own residual: the
  // preconditioned residual of a twin that went singular can be small while
  // the operator's is not (measured: a floating pair, tests/unit/sph).
  if (twin_ != nullptr) petsc_check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
}

void PressurePoisson::use_kept_hierarchy(Mat basis, bool build) {
  create_solver();
  PetscVector layout;
  petsc_check(MatCreateVecs(matrix_, layout.out(), nullptr), "MatCreateVecs");
  KeptState& kept = kept_;
  if (build || kept.hierarchy == nullptr || !kept.hierarchy->map_rows(ids_, layout.get())) {
    // A new object: a state saved earlier keeps the one it solved with.
    kept.hierarchy = std::make_shared<KeptHierarchy>(comm_, KeptHierarchy::basis_of(basis, ids_));
    if (!kept.hierarchy->map_rows(ids_, layout.get()))
      throw std::logic_error("PressurePoisson: a hierarchy does not take the rows it was built on");
    kept.first_iterations = -1;
    kept_fresh_ = true;
  } else {
    kept_fresh_ = false;
  }
  kept.rebuild = false;
  petsc_check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp_, &pc), "KSPGetPC");
  kept.hierarchy->install(pc);
  // Judged on the operator's own residual, as with the twin (assemble()): the
  // hierarchy was built on another step's matrix.
  petsc_check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
}

PressurePoisson::Attempt PressurePoisson::attempt(std::span<const double> source, std::span<double> pressure,
                                                  double residual_floor) {
  const int owned = solved_size_;
  Vec rhs = nullptr;
  Vec solution = nullptr;
  petsc_check(MatCreateVecs(matrix_, &solution, &rhs), "MatCreateVecs");
  {
    PetscScalar* b = nullptr;
    PetscScalar* x = nullptr;
    petsc_check(VecGetArray(rhs, &b), "VecGetArray");
    petsc_check(VecGetArray(solution, &x), "VecGetArray");
    for (int i = 0; i < owned; ++i) {
      const bool surface = dirichlet_[at(i)] != 0;
      b[i] = surface ? 0.0 : -source[at(i)];
      x[i] = surface ? 0.0 : pressure[at(i)];
    }
    petsc_check(VecRestoreArray(rhs, &b), "VecRestoreArray");
    petsc_check(VecRestoreArray(solution, &x), "VecRestoreArray");
  }
  PetscReal rtol = 0.0;
  PetscReal atol = 0.0;
  PetscReal dtol = 0.0;
  PetscInt max_iterations = 0;
  petsc_check(KSPGetTolerances(ksp_, &rtol, &atol, &dtol, &max_iterations), "KSPGetTolerances");
  const bool floored = residual_floor > atol;
  if (floored) petsc_check(KSPSetTolerances(ksp_, rtol, residual_floor, dtol, max_iterations), "KSPSetTolerances");
  // Not handled: an error raised on some ranks only leaves the others inside
  // the solve's collectives (the job hangs); convergence failures are collective.
  Attempt result;
  result.code = KSPSolve(ksp_, rhs, solution);
  if (floored) petsc_check(KSPSetTolerances(ksp_, rtol, atol, dtol, max_iterations), "KSPSetTolerances");
  PetscInt iterations = 0;
  KSPGetConvergedReason(ksp_, &result.reason);
  KSPGetIterationNumber(ksp_, &iterations);
  KSPGetResidualNorm(ksp_, &result.report.residual_norm);
  result.report.iterations = static_cast<int>(iterations);
  if (result.code == 0 && result.reason > 0) {
    const PetscScalar* x = nullptr;
    VecGetArrayRead(solution, &x);
    for (int i = 0; i < owned; ++i) pressure[at(i)] = x[i];
    VecRestoreArrayRead(solution, &x);
  }
  VecDestroy(&rhs);
  VecDestroy(&solution);
  return result;
}

PpeSolveReport PressurePoisson::solve_assembled(std::span<const double> source, std::span<double> pressure,
                                                double residual_floor) {
  if (matrix_ == nullptr) throw std::logic_error("PressurePoisson::solve_assembled before assemble");
  bool built = multigrid_ && (!keeping_ || kept_fresh_);
  Attempt result = attempt(source, pressure, residual_floor);
  if (keeping_ && !kept_fresh_ && result.code == 0 && result.reason <= 0) {
    // The kept hierarchy does not fit this operator: one built on it.
    use_kept_hierarchy(preconditioning_matrix(), true);
    result = attempt(source, pressure, residual_floor);
    built = true;
  }
  bool twin_failed = false;
  if (result.code == 0 && result.reason <= 0 && twin_ != nullptr) {
    // The twin's hierarchy failed (pressure_poisson.hpp): the operator's takes
    // this solve and the step's others.
    MatDestroy(&twin_);
    if (keeping_) {
      use_kept_hierarchy(matrix_, true);
    } else {
      create_solver();
      petsc_check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    }
    result = attempt(source, pressure, residual_floor);
    twin_failed = true;
    built = true;
  }
  if (result.code != 0)
    throw std::runtime_error("pressure solver failed with PETSc error " + std::to_string(result.code));
  if (result.reason <= 0)
    throw std::runtime_error(std::string("pressure solver did not converge: ") + KSPConvergedReasons[result.reason] +
                             " after " + std::to_string(result.report.iterations) + " iterations, residual " +
                             std::to_string(result.report.residual_norm));
  result.report.twin_failed = twin_failed;
  result.report.hierarchy_built = built && first_solve_;
  if (keeping_ && first_solve_) {
    // A kept hierarchy is built anew for the next operator once it takes more
    // than kept_iteration_ratio times the iterations of its first solve.
    const int iterations = result.report.iterations;
    if (kept_.first_iterations < 0) kept_.first_iterations = iterations;
    else if (iterations > kept_iteration_ratio * kept_.first_iterations) kept_.rebuild = true;
  }
  first_solve_ = false;
  return result.report;
}

}  // namespace tankfsi::sph
