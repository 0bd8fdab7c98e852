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
//
// With FluidModel::preconditioner_radius > 0 (the default, 1.8) BoomerAMG is
// built on a sparser twin of the operator: the pairs closer than that radius
// (1.8 L0: the lattice's first two shells, 9 entries a row in 2D and 27 in 3D
// instead of 37 and 93 at h = 1.2 L0), their weights scaled by the ratio of
// the full to the kept second moments sum a_ij r_ij^2 (over all rows) so that
// the twin's Laplacian of a quadratic field is the operator's, and the same
// air share on the diagonal. CG still solves the operator: the twin's
// hierarchy costs less to set up and apply than the operator's, for more
// iterations (measured: README.md). The twin is not the operator: a group of
// particles that only pairs longer than the radius tie to the rest, and that
// no air touches, floats in it (its rows sum to zero). Its preconditioned
// residual then says little of the operator's, so with the twin CG is judged
// on the operator's own residual; and a solve that fails with the twin's
// hierarchy is solved again from the same start with the operator's, which
// the step reports.
//
// With FluidModel::keep_hierarchy and the particles' ids, the hierarchy is
// kept from step to step (kept_hierarchy.hpp) and built anew on the step's
// matrix (the twin, as above) when a solve took more than
// kept_iteration_ratio times the iterations of the first solve on it, when
// it fails, or when a particle is not among its rows.
#include <mpi.h>
#include <petscksp.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "sph_solver/isph/kept_hierarchy.hpp"
#include "sph_solver/isph/particle_terms.hpp"

namespace tankfsi::sph {

/// When a kept hierarchy is built anew (above). A new one costs about as much
/// as ten V-cycles. Measured on the dam break at L0 = 0.01 m (2 ranks, 0.6 s,
/// 407 steps): a hierarchy built every step, 12.7 iterations a step; kept
/// with the ratio 1.25, 14.0; 1.5, 15.4 and 13 builds; 2, 18.3 and 8 builds
/// (1.25 and 1.5 the fastest, alike within the machine's spread).
inline constexpr double kept_iteration_ratio = 1.5;

struct PpeSolveReport {
  int iterations = 0;          ///< of the solve that converged
  double residual_norm = 0.0;  ///< the KSP's final residual norm
  /// The solve failed with the twin's hierarchy and the operator's solved it (below).
  bool twin_failed = false;
  /// A hierarchy was built for it (always, unless one is kept: kept_hierarchy.hpp).
  bool hierarchy_built = false;
};

/// One off-diagonal entry of a PPE row while it is assembled.
struct RowEntry {
  PetscInt column;    ///< global
  PetscScalar value;  ///< a_ij (< 0 after the sign change)
  double distance;    ///< r_ij
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
  /// subtracted); `particle_id` the owned particles' ids, with which the
  /// preconditioner's hierarchy is kept across steps when the model says so
  /// (none: built for this solve). Throws std::runtime_error when the solver
  /// does not converge.
  PpeSolveReport solve(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                       std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet,
                       std::span<const double> source, std::span<double> pressure,
                       std::span<const std::int64_t> particle_id = {});

  /// solve() in two parts, for many right-hand sides of one operator (the
  /// preconditioner is set up once): assemble the matrix of these particles,
  /// then solve for each source (owned rows), `pressure` the warm start.
  /// `residual_floor` > 0 stops the solve once its residual norm is that low
  /// whatever its own source's size (the KSP's absolute tolerance for this
  /// solve, if above the options' own): for a part of a pressure already
  /// solved to that residual as a whole.
  void assemble(const Neighbourhood& n, std::span<const double> mass, std::span<const double> density,
                std::span<const std::int64_t> global_index, std::span<const unsigned char> dirichlet,
                std::span<const std::int64_t> particle_id = {});
  PpeSolveReport solve_assembled(std::span<const double> source, std::span<double> pressure,
                                 double residual_floor = 0.0);

  /// The kept hierarchy and when to build the next (nothing while none is
  /// kept): what a state saved in memory and put back later solves with, so
  /// that a step taken again gives the same answer (FluidSolver::save()).
  struct KeptState {
    std::shared_ptr<KeptHierarchy> hierarchy;
    int first_iterations = -1;  ///< of the first solve on it (-1: none yet)
    bool rebuild = true;        ///< the next operator gets a new one
  };
  [[nodiscard]] KeptState kept_state() const { return kept_; }
  void resume(const KeptState& state) { kept_ = state; }

  /// The solver and preconditioner with their settings, as PETSc's KSPView
  /// shows them (collective; the text on the first rank, empty on the others).
  [[nodiscard]] std::string settings() const;

  /// The last assembled operator, and the matrix its preconditioner was built
  /// from (the sparser twin, or the operator itself).
  [[nodiscard]] Mat operator_matrix() const { return matrix_; }
  [[nodiscard]] Mat preconditioning_matrix() const { return twin_ != nullptr ? twin_ : matrix_; }

 private:
  /// Owned rows in the two CSR blocks of a PETSc MPIAIJ matrix, each row in
  /// column order: the diagonal block (columns of owned rows, numbered from the
  /// first owned row) and the off-diagonal block (global columns). The matrix
  /// is made on these arrays without a copy or an insertion per entry
  /// (MatCreateMPIAIJWithSplitArrays), so they live until it is destroyed;
  /// reused from step to step.
  struct Rows {
    struct Block {
      std::vector<PetscInt> begin;
      std::vector<PetscInt> columns;
      std::vector<PetscScalar> values;
      void clear();
      void end_row() { begin.push_back(static_cast<PetscInt>(values.size())); }
    };
    Block diagonal;
    Block off_diagonal;
    void clear();
    /// Appends the row `row` (global): `diagonal` and the entries (in column
    /// order) no farther than `max_distance`; the owned range [owned_begin,
    /// owned_end) of columns is the diagonal block.
    void add(PetscInt row, PetscScalar diagonal, const std::vector<RowEntry>& entries, PetscInt owned_begin,
             PetscInt owned_end, double max_distance);
  };
  /// A new KSP from the options (the case's, the command line's, the defaults).
  void create_solver();
  /// A new distributed matrix on the arrays of `rows` (which must outlive it).
  [[nodiscard]] Mat create_matrix(Rows& rows) const;
  /// One KSP solve from `pressure`; the converged reason (collective) and the
  /// error code are in the result, the pressure updated only on success.
  struct Attempt {
    PetscErrorCode code = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    PpeSolveReport report;
  };
  [[nodiscard]] Attempt attempt(std::span<const double> source, std::span<double> pressure, double residual_floor);
  /// A new solver for the operator with the kept hierarchy as its
  /// preconditioner, a new one built on `basis` when `build` or when the kept
  /// one cannot take this step's rows.
  void use_kept_hierarchy(Mat basis, bool build);
  MPI_Comm comm_;
  KSP ksp_ = nullptr;
  bool multigrid_ = false;  ///< BoomerAMG, whose hierarchy may be built on a twin
  int solved_size_ = -1;    ///< local rows of the assembled operator
  Mat matrix_ = nullptr;    ///< the last assembled operator
  Mat twin_ = nullptr;      ///< its sparser twin for the preconditioner (or none)
  std::vector<unsigned char> dirichlet_;  ///< its Dirichlet rows (owned)
  bool keeping_ = false;           ///< it is solved with the kept hierarchy
  bool kept_fresh_ = false;        ///< which was built on it
  bool first_solve_ = false;       ///< no solve of it yet
  std::vector<std::int64_t> ids_;  ///< its rows' particles
  KeptState kept_;
  Rows operator_rows_;
  Rows twin_rows_;
  std::vector<RowEntry> entries_;  ///< one row's off-diagonal entries
  std::vector<double> twin_air_;   ///< each twin row's air share (added after scaling)
};


}  // namespace tankfsi::sph
