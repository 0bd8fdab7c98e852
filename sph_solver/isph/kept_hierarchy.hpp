#pragma once
// KeptHierarchy: a BoomerAMG hierarchy built on one step's pressure matrix and
// kept, as CG's preconditioner, for the steps after it (fluid.ppe.keep_hierarchy).
//
// Building the hierarchy costs about as much as ten of its V-cycles and was a
// third of the pressure solve (cases/dam_break_2d/README.md). Particles move,
// leave, migrate between ranks and are renumbered every step, so a later
// step's rows are the same particles in another order and on other ranks: the
// hierarchy is applied through the particles' identities,
//   z = Q^T M^-1 Q r,
// Q taking each row of the step's matrix to the row its particle had in M
// (the rows of particles removed since get zero). Q is one-to-one, so
// Q^T M^-1 Q is symmetric positive definite wherever M^-1 is: a
// preconditioner for CG still. It fits the step's matrix less well as the
// particles move on, which costs iterations; PressurePoisson decides when to
// build a new one.
//
// M's rows (the basis) are kept too: a checkpoint holds them, and a restart
// on as many ranks builds the very same hierarchy from them, so that the run
// goes on bit for bit.
#include <mpi.h>
#include <petscksp.h>

#include <cstdint>
#include <span>
#include <vector>

namespace tankfsi::sph {

class KeptHierarchy {
 public:
  /// This rank's rows of M in CSR form, global columns.
  struct Basis {
    std::vector<std::int64_t> ids;        ///< each row's particle
    std::vector<std::int64_t> row_begin;  ///< ids.size() + 1 offsets into columns and values
    std::vector<std::int64_t> columns;
    std::vector<double> values;
  };

  /// Collective: builds the hierarchy (hypre BoomerAMG with the -ppe_
  /// options) on the matrix of `basis`.
  KeptHierarchy(MPI_Comm comm, Basis basis);
  /// Collective: the basis of `matrix`, whose owned rows belong to the
  /// particles `ids`, in row order.
  [[nodiscard]] static Basis basis_of(Mat matrix, std::span<const std::int64_t> ids);
  ~KeptHierarchy();
  KeptHierarchy(const KeptHierarchy&) = delete;
  KeptHierarchy& operator=(const KeptHierarchy&) = delete;

  [[nodiscard]] const Basis& basis() const { return basis_; }

  /// Collective: maps the rows of a step's vectors (`layout`: owned rows
  /// belonging to the particles `ids`, in row order) to M's. False on every
  /// rank when a particle is not among M's rows.
  [[nodiscard]] bool map_rows(std::span<const std::int64_t> ids, Vec layout);
  /// Makes `pc` apply Q^T M^-1 Q with the last rows mapped (a PCSHELL on
  /// this object, which must outlive the solve).
  void install(PC pc);

 private:
  static PetscErrorCode apply(PC pc, Vec in, Vec out);
  MPI_Comm comm_;
  Basis basis_;
  PC pc_ = nullptr;          ///< the hierarchy
  Vec row_of_id_ = nullptr;  ///< M's row of each particle id (-1: none), distributed by id
  Vec built_in_ = nullptr;   ///< vectors in M's rows
  Vec built_out_ = nullptr;
  VecScatter to_built_ = nullptr;  ///< Q: a step's rows to M's (the last mapped)
};

}  // namespace tankfsi::sph
