#include "sph_solver/isph/pressure_poisson.hpp"

#include "common/run/petsc_defaults.hpp"

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
  const char* hypre_type = nullptr;
  if (type != nullptr && std::string(type) == PCHYPRE) check(PCHYPREGetType(pc, &hypre_type), "PCHYPREGetType");
  multigrid_ = hypre_type != nullptr && std::string(hypre_type) == "boomeramg";
  if (multigrid_) {
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
  if (twin_ != nullptr) MatDestroy(&twin_);
}

PpeSolveReport PressurePoisson::solve(const Neighbourhood& n, std::span<const double> mass,
                                      std::span<const double> density, std::span<const std::int64_t> global_index,
                                      std::span<const unsigned char> dirichlet, std::span<const double> source,
                                      std::span<double> pressure) {
  assemble(n, mass, density, global_index, dirichlet);
  return solve_assembled(source, pressure);
}

void PressurePoisson::Rows::clear(int owned) {
  begin.assign(1, 0);
  columns.clear();
  values.clear();
  diagonal_nonzeros.assign(at(owned), 0);
  off_diagonal_nonzeros.assign(at(owned), 0);
}

void PressurePoisson::Rows::add(PetscInt row, PetscScalar diagonal, const std::vector<RowEntry>& entries,
                                PetscInt owned_begin, PetscInt owned_end, double max_distance) {
  const std::size_t i = begin.size() - 1;
  // The diagonal in its place among the columns (PETSc takes each row whole
  // and in column order: MAT_SORTED_FULL).
  bool diagonal_placed = false;
  const auto place_diagonal = [&] {
    columns.push_back(row);
    values.push_back(diagonal);
    ++diagonal_nonzeros[i];
    diagonal_placed = true;
  };
  for (const RowEntry& e : entries) {
    if (e.distance > max_distance) continue;
    if (!diagonal_placed && e.column > row) place_diagonal();
    columns.push_back(e.column);
    values.push_back(e.value);
    ++(e.column >= owned_begin && e.column < owned_end ? diagonal_nonzeros : off_diagonal_nonzeros)[i];
  }
  if (!diagonal_placed) place_diagonal();
  begin.push_back(static_cast<PetscInt>(values.size()));
}

Mat PressurePoisson::create_matrix(const Rows& rows, PetscInt first_row) const {
  const auto owned = static_cast<PetscInt>(rows.begin.size() - 1);
  Mat matrix = nullptr;
  check(MatCreateAIJ(comm_, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, 0, rows.diagonal_nonzeros.data(), 0,
                     rows.off_diagonal_nonzeros.data(), &matrix),
        "MatCreateAIJ");
  check(MatSetOption(matrix, MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  // Every row whole, in column order, its preallocation exact (Rows::add()).
  check(MatSetOption(matrix, MAT_SORTED_FULL, PETSC_TRUE), "MatSetOption");
  for (PetscInt i = 0; i < owned; ++i) {
    const PetscInt global_row = first_row + i;
    const PetscInt begin = rows.begin[at(i)];
    check(MatSetValues(matrix, 1, &global_row, rows.begin[at(i) + 1] - begin, rows.columns.data() + begin,
                       rows.values.data() + begin, INSERT_VALUES),
          "MatSetValues");
  }
  check(MatAssemblyBegin(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(matrix, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return matrix;
}

void PressurePoisson::assemble(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                               std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet) {
  const int owned = n.owned;
  const PetscInt first_row = owned > 0 ? static_cast<PetscInt>(global_index[0]) : 0;
  const PetscInt end_row = first_row + owned;
  const double twin_radius = multigrid_ ? n.model.preconditioner_radius * n.model.spacing : 0.0;
  const bool with_twin = twin_radius > 0.0;
  operator_rows_.clear(owned);
  if (with_twin) {
    twin_rows_.clear(owned);
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
  if (matrix_ != nullptr) MatDestroy(&matrix_);
  if (twin_ != nullptr) MatDestroy(&twin_);
  matrix_ = create_matrix(operator_rows_, first_row);
  if (with_twin) {
    MPI_Allreduce(MPI_IN_PLACE, moments, 2, MPI_DOUBLE, MPI_SUM, comm_);
    // No pair within the radius anywhere (particles all apart): the operator is
    // the preconditioner's matrix.
    if (moments[0] < 0.0) {
      const double scale = moments[1] / moments[0];
      for (int i = 0; i < owned; ++i) {
        if (dirichlet_[at(i)] != 0) continue;
        const auto row = static_cast<PetscInt>(global_index[at(i)]);
        for (PetscInt k = twin_rows_.begin[at(i)]; k < twin_rows_.begin[at(i) + 1]; ++k) {
          PetscScalar& value = twin_rows_.values[at(static_cast<int>(k))];
          if (twin_rows_.columns[at(static_cast<int>(k))] != row) {
            value *= scale;
          } else {
            value = scale * value - twin_air_[at(i)];
            if (!(value > 0.0)) value = 1.0;  // isolated, as in the operator
          }
        }
      }
      twin_ = create_matrix(twin_rows_, first_row);
    }
  }

  // Every step's operator is a new matrix of another pattern, and often of
  // another size (particles migrate and leave): a new solver takes it, with
  // the same options. A KSP refuses a new local size without a reset, and
  // GAMG, reset or not, kept coarse levels sized for the old pattern ("Cannot
  // change local size of Amat after use", on some ranks only). BoomerAMG
  // builds its hierarchy anew every step either way.
  create_solver();
  solved_size_ = owned;
  check(KSPSetOperators(ksp_, matrix_, preconditioning_matrix()), "KSPSetOperators");
  // With the twin, convergence is judged on the operator's own residual: the
  // preconditioned residual of a twin that went singular can be small while
  // the operator's is not (measured: a floating pair, tests/unit/sph).
  if (twin_ != nullptr) check(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
}

PressurePoisson::Attempt PressurePoisson::attempt(std::span<const double> source, std::span<double> pressure,
                                                  double residual_floor) {
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
  Attempt result;
  result.code = KSPSolve(ksp_, rhs, solution);
  if (floored) check(KSPSetTolerances(ksp_, rtol, atol, dtol, max_iterations), "KSPSetTolerances");
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
  Attempt result = attempt(source, pressure, residual_floor);
  bool twin_failed = false;
  if (result.code == 0 && result.reason <= 0 && twin_ != nullptr) {
    // The twin's hierarchy failed (pressure_poisson.hpp): the operator's takes
    // this solve and the step's others.
    MatDestroy(&twin_);
    create_solver();
    check(KSPSetOperators(ksp_, matrix_, matrix_), "KSPSetOperators");
    result = attempt(source, pressure, residual_floor);
    twin_failed = true;
  }
  if (result.code != 0)
    throw std::runtime_error("pressure solver failed with PETSc error " + std::to_string(result.code));
  if (result.reason <= 0)
    throw std::runtime_error(std::string("pressure solver did not converge: ") + KSPConvergedReasons[result.reason] +
                             " after " + std::to_string(result.report.iterations) + " iterations, residual " +
                             std::to_string(result.report.residual_norm));
  result.report.twin_failed = twin_failed;
  return result.report;
}

}  // namespace tankfsi::sph
