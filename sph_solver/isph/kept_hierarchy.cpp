#include "sph_solver/isph/kept_hierarchy.hpp"

#include <algorithm>
#include <utility>

#include "common/run/petsc_handle.hpp"

namespace tankfsi::sph {

KeptHierarchy::Basis KeptHierarchy::basis_of(Mat matrix, std::span<const std::int64_t> ids) {
  PetscInt first_row = 0, end_row = 0;
  petsc_check(MatGetOwnershipRange(matrix, &first_row, &end_row), "MatGetOwnershipRange");
  Basis basis;
  basis.ids.assign(ids.begin(), ids.end());
  basis.row_begin.reserve(ids.size() + 1);
  basis.row_begin.push_back(0);
  for (PetscInt row = first_row; row < end_row; ++row) {
    PetscInt count = 0;
    const PetscInt* columns = nullptr;
    const PetscScalar* values = nullptr;
    petsc_check(MatGetRow(matrix, row, &count, &columns, &values), "MatGetRow");
    basis.columns.insert(basis.columns.end(), columns, columns + count);
    basis.values.insert(basis.values.end(), values, values + count);
    petsc_check(MatRestoreRow(matrix, row, &count, &columns, &values), "MatRestoreRow");
    basis.row_begin.push_back(static_cast<std::int64_t>(basis.columns.size()));
  }
  return basis;
}

KeptHierarchy::KeptHierarchy(MPI_Comm comm, Basis basis) : comm_(comm), basis_(std::move(basis)) {
  const auto owned = static_cast<PetscInt>(basis_.ids.size());
  {
    // M from the basis (copied into the matrix): a run and its restart build
    // the hierarchy from the same arrays.
    // (A rank without rows still hands PETSc arrays, not null pointers.)
    const std::vector<PetscInt> row_begin(basis_.row_begin.begin(), basis_.row_begin.end());
    std::vector<PetscInt> columns(basis_.columns.begin(), basis_.columns.end());
    std::vector<PetscScalar> values(basis_.values.begin(), basis_.values.end());
    columns.reserve(1);
    values.reserve(1);
    PetscMatrix matrix;
    petsc_check(MatCreateMPIAIJWithArrays(comm_, owned, owned, PETSC_DETERMINE, PETSC_DETERMINE, row_begin.data(),
                                          columns.data(), values.data(), matrix.out()),
                "MatCreateMPIAIJWithArrays");
    petsc_check(PCCreate(comm_, &pc_), "PCCreate");
    petsc_check(PCSetOptionsPrefix(pc_, "ppe_"), "PCSetOptionsPrefix");
    petsc_check(PCSetType(pc_, PCHYPRE), "PCSetType");
    petsc_check(PCHYPRESetType(pc_, "boomeramg"), "PCHYPRESetType");
    petsc_check(PCSetFromOptions(pc_), "PCSetFromOptions");
    petsc_check(PCSetOperators(pc_, matrix.get(), matrix.get()), "PCSetOperators");  // the PC holds it
    petsc_check(PCSetUp(pc_), "PCSetUp");
    petsc_check(MatCreateVecs(matrix.get(), &built_in_, &built_out_), "MatCreateVecs");
  }

  // Each particle's row in M, stored at its id.
  PetscInt first_row = 0;
  petsc_check(VecGetOwnershipRange(built_in_, &first_row, nullptr), "VecGetOwnershipRange");
  std::int64_t largest_id = -1;
  for (const std::int64_t id : basis_.ids) largest_id = std::max(largest_id, id);
  MPI_Allreduce(MPI_IN_PLACE, &largest_id, 1, MPI_INT64_T, MPI_MAX, comm_);
  petsc_check(VecCreateMPI(comm_, PETSC_DECIDE, static_cast<PetscInt>(largest_id + 1), &row_of_id_), "VecCreateMPI");
  petsc_check(VecSet(row_of_id_, -1.0), "VecSet");
  const std::vector<PetscInt> at(basis_.ids.begin(), basis_.ids.end());
  std::vector<PetscScalar> row(at.size());
  for (std::size_t i = 0; i < row.size(); ++i) row[i] = static_cast<PetscScalar>(first_row + static_cast<PetscInt>(i));
  petsc_check(VecSetValues(row_of_id_, owned, at.data(), row.data(), INSERT_VALUES), "VecSetValues");
  petsc_check(VecAssemblyBegin(row_of_id_), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(row_of_id_), "VecAssemblyEnd");
}

KeptHierarchy::~KeptHierarchy() {
  if (to_built_ != nullptr) VecScatterDestroy(&to_built_);
  if (pc_ != nullptr) PCDestroy(&pc_);
  if (row_of_id_ != nullptr) VecDestroy(&row_of_id_);
  if (built_in_ != nullptr) VecDestroy(&built_in_);
  if (built_out_ != nullptr) VecDestroy(&built_out_);
}

bool KeptHierarchy::map_rows(std::span<const std::int64_t> ids, Vec layout) {
  if (to_built_ != nullptr) VecScatterDestroy(&to_built_);
  PetscInt id_count = 0;
  petsc_check(VecGetSize(row_of_id_, &id_count), "VecGetSize");
  const auto owned = static_cast<PetscInt>(ids.size());
  int known = std::all_of(ids.begin(), ids.end(), [&](std::int64_t id) { return id >= 0 && id < id_count; });
  MPI_Allreduce(MPI_IN_PLACE, &known, 1, MPI_INT, MPI_MIN, comm_);
  if (known == 0) return false;

  // Each particle's row in M, looked up by its id.
  std::vector<PetscInt> wanted(ids.begin(), ids.end());
  PetscVector found;
  PetscIndexSet wanted_set;
  PetscScatter lookup;
  petsc_check(VecCreateSeq(PETSC_COMM_SELF, owned, found.out()), "VecCreateSeq");
  petsc_check(ISCreateGeneral(PETSC_COMM_SELF, owned, wanted.data(), PETSC_USE_POINTER, wanted_set.out()),
              "ISCreateGeneral");
  petsc_check(VecScatterCreate(row_of_id_, wanted_set.get(), found.get(), nullptr, lookup.out()), "VecScatterCreate");
  petsc_check(VecScatterBegin(lookup.get(), row_of_id_, found.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_check(VecScatterEnd(lookup.get(), row_of_id_, found.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  std::vector<PetscInt> built_row(ids.size());
  {
    const PetscScalar* rows = nullptr;
    petsc_check(VecGetArrayRead(found.get(), &rows), "VecGetArrayRead");
    for (std::size_t i = 0; i < ids.size(); ++i) built_row[i] = static_cast<PetscInt>(rows[i]);
    petsc_check(VecRestoreArrayRead(found.get(), &rows), "VecRestoreArrayRead");
  }
  known = std::all_of(built_row.begin(), built_row.end(), [](PetscInt r) { return r >= 0; });
  MPI_Allreduce(MPI_IN_PLACE, &known, 1, MPI_INT, MPI_MIN, comm_);
  if (known == 0) return false;

  PetscInt first_row = 0;
  petsc_check(VecGetOwnershipRange(layout, &first_row, nullptr), "VecGetOwnershipRange");
  PetscIndexSet from;
  PetscIndexSet to;
  petsc_check(ISCreateStride(comm_, owned, first_row, 1, from.out()), "ISCreateStride");
  petsc_check(ISCreateGeneral(comm_, owned, built_row.data(), PETSC_USE_POINTER, to.out()), "ISCreateGeneral");
  petsc_check(VecScatterCreate(layout, from.get(), built_in_, to.get(), &to_built_), "VecScatterCreate");
  return true;
}

void KeptHierarchy::install(PC pc) {
  petsc_check(PCSetType(pc, PCSHELL), "PCSetType");
  petsc_check(PCShellSetContext(pc, this), "PCShellSetContext");
  petsc_check(PCShellSetApply(pc, &KeptHierarchy::apply), "PCShellSetApply");
  petsc_check(PCShellSetName(pc, "BoomerAMG kept across steps, applied through the particles' ids"),
              "PCShellSetName");
}

PetscErrorCode KeptHierarchy::apply(PC pc, Vec in, Vec out) {
  void* context = nullptr;
  PetscCall(PCShellGetContext(pc, &context));
  const auto& self = *static_cast<const KeptHierarchy*>(context);
  // The rows of particles removed since M was built stay zero.
  PetscCall(VecSet(self.built_in_, 0.0));
  PetscCall(VecScatterBegin(self.to_built_, in, self.built_in_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(self.to_built_, in, self.built_in_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(PCApply(self.pc_, self.built_in_, self.built_out_));
  PetscCall(VecScatterBegin(self.to_built_, self.built_out_, out, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(self.to_built_, self.built_out_, out, INSERT_VALUES, SCATTER_REVERSE));
  return 0;
}

}  // namespace tankfsi::sph
