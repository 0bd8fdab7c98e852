#pragma once
// PressurePoisson: the pressure Poisson equation of the projection step (METHOD.md
// §1 step 2, eq 6), assembled as a distributed PETSc matrix and solved with a KSP
// whose options carry the prefix -ppe_ (default: CG with hypre BoomerAMG in a
// cheap hierarchy, rtol 1e-6, warm started from the previous pressure).
//
// Row of a particle i inside the liquid (the Laplacian with the factor 2):
//   sum_j a_ij (P_i - P_j) = S_i - sum_w 2 Z2 (dP/dn)_w (r_iw + d2),
//   a_ij = 2 V_ij (x_ij · grad_i W_ij) / (r^2 + eta^2),   V_ij = (m_i + m_j) / (rho_i + rho_j).
// The walls' share is known (Neumann wall pressure, see particle_terms.hpp) and moves
// to the right-hand side. V_ij is the pair's mean volume rather than V_j, so that
// a_ij = a_ji and the matrix is symmetric; on a uniform lattice both are the same.
// The rows are multiplied by -1: a_ij <= 0, so the matrix is then an M-matrix,
// symmetric positive definite wherever every cluster of particles reaches a free
// surface — which suits CG and algebraic multigrid.
// The air beyond the free surface (free_surface.hpp) adds to the diagonal only:
// sum_air a (P_i - P_air) = 2 Z2 (1 + d2/delta) P_i, with P_air the ghost pressure
// that reaches 0 on the surface; the matrix stays symmetric, and is definite once
// any particle has such a term.
// Particles flagged `dirichlet` have the value P = 0: an identity row, and their
// columns are left out of the other rows (value 0 moved to the right-hand side),
// which keeps the matrix symmetric.
#include <mpi.h>
#include <petscksp.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "sph_solver/isph/particle_terms.hpp"

namespace tankfsi::sph {

struct PpeSolveReport {
  int iterations = 0;
  double residual_norm = 0.0;  ///< the KSP's final residual norm
};

class PressurePoisson {
 public:
  /// `case_options`: PETSc options from the case file (fluid.ppe.solver_options), e.g.
  /// "-ppe_ksp_rtol 1e-10"; each is applied unless the command line gave it too.
  PressurePoisson(MPI_Comm comm, const std::string& case_options);
  ~PressurePoisson();
  PressurePoisson(const PressurePoisson&) = delete;
  PressurePoisson& operator=(const PressurePoisson&) = delete;

  /// Solves for the owned particles' pressure; `pressure` holds the warm start on
  /// entry (owned rows). `global_index`, `density`, `mass`, `dirichlet` cover owned
  /// and ghost particles; `source` the owned ones (S_i with the wall share already
  /// subtracted). Throws std::runtime_error when the solver does not converge.
  PpeSolveReport solve(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                       std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet,
                       std::span<const double> source, std::span<double> pressure);

  /// solve() in two parts, for many right-hand sides of one operator (the
  /// preconditioner is set up once): assemble the matrix of these particles,
  /// then solve for each source (owned rows), `pressure` the warm start.
  /// `residual_floor` > 0 stops the solve once its residual norm is that low
  /// whatever its own source's size (the KSP's absolute tolerance for this
  /// solve, if above the options' own): for a part of a pressure already
  /// solved to that residual as a whole.
  void assemble(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet);
  PpeSolveReport solve_assembled(std::span<const double> source, std::span<double> pressure,
                                 double residual_floor = 0.0);

  /// The solver and preconditioner with their settings, as PETSc's KSPView
  /// shows them (collective; the text on the first rank, empty on the others).
  [[nodiscard]] std::string settings() const;

 private:
  /// A new KSP from the options (the case's, the command line's, the defaults).
  void create_solver();
  /// Orders the last row of the CSR buffers (from `begin`) by column.
  void sort_row(std::size_t begin);
  MPI_Comm comm_;
  KSP ksp_ = nullptr;
  int solved_size_ = -1;  ///< local rows of the assembled operator
  Mat matrix_ = nullptr;  ///< the last assembled operator
  std::vector<unsigned char> dirichlet_;  ///< its Dirichlet rows (owned)
  // Assembly buffers, reused from step to step: the rows in CSR form (global
  // columns) and the per-row counts for preallocation.
  std::vector<PetscInt> row_begin_;
  std::vector<PetscInt> columns_;
  std::vector<PetscScalar> values_;
  std::vector<PetscInt> diagonal_nonzeros_;
  std::vector<PetscInt> off_diagonal_nonzeros_;
};


}  // namespace tankfsi::sph
