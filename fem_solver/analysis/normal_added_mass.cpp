#include "fem_solver/analysis/normal_added_mass.hpp"

#include <Eigen/Dense>

#include <cmath>
#include <string>

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

namespace {

/// (M + N^T A N)^-1 by the n x n system of the normal components (header).
class NormalAddedMassInertia final : public LinearSolve {
 public:
  NormalAddedMassInertia(Mat normal_map, std::span<const double> operator_rows, Vec mass_diagonal)
      : normal_map_(reference(normal_map)) {
    const auto n = static_cast<Eigen::Index>(std::llround(std::sqrt(static_cast<double>(operator_rows.size()))));
    PetscInt rows = 0;
    petsc_check(MatGetSize(normal_map, &rows, nullptr), "MatGetSize");
    if (n != rows || static_cast<std::size_t>(n * n) != operator_rows.size())
      throw std::invalid_argument("make_normal_added_mass_inertia: " + std::to_string(operator_rows.size()) +
                                  " operator entries for " + std::to_string(rows) + " vertices");
    operator_ = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        operator_rows.data(), n, n);
    petsc_check(VecDuplicate(mass_diagonal, inverse_mass_.out()), "VecDuplicate");
    petsc_check(VecCopy(mass_diagonal, inverse_mass_.get()), "VecCopy");
    petsc_check(VecReciprocal(inverse_mass_.get()), "VecReciprocal");
    petsc_check(VecDuplicate(mass_diagonal, scaled_.out()), "VecDuplicate");
    petsc_check(MatCreateVecs(normal_map, nullptr, normal_part_.out()), "MatCreateVecs");
    petsc_check(VecScatterCreateToAll(normal_part_.get(), to_all_.out(), gathered_.out()), "VecScatterCreateToAll");
    petsc_check(VecGetOwnershipRange(normal_part_.get(), &first_, &end_), "VecGetOwnershipRange");
    // D = diag(N M^-1 N^T): the diagonal of (N M^-1) N^T.
    PetscMatrix scaled_map, product;
    petsc_check(MatDuplicate(normal_map, MAT_COPY_VALUES, scaled_map.out()), "MatDuplicate");
    petsc_check(MatDiagonalScale(scaled_map.get(), nullptr, inverse_mass_.get()), "MatDiagonalScale");
    petsc_check(MatMatTransposeMult(scaled_map.get(), normal_map, MAT_INITIAL_MATRIX, PETSC_DEFAULT, product.out()),
                "MatMatTransposeMult");
    petsc_check(MatGetDiagonal(product.get(), normal_part_.get()), "MatGetDiagonal");
    const Eigen::VectorXd d = gather(normal_part_.get());
    Eigen::MatrixXd system = operator_ * d.asDiagonal();
    system.diagonal().array() += 1.0;
    lu_.compute(system);
    if (!(lu_.rcond() >= 1e-14))
      throw std::runtime_error("the added mass's inertia system I + A D is singular (reciprocal condition number " +
                               std::to_string(lu_.rcond()) + ")");
  }

  void solve(Vec rhs, Vec solution) const override {
    // s = N M^-1 r;  y = (I + A D)^-1 A s;  a = M^-1 (r - N^T y).
    petsc_check(VecPointwiseMult(scaled_.get(), rhs, inverse_mass_.get()), "VecPointwiseMult");
    petsc_check(MatMult(normal_map_.get(), scaled_.get(), normal_part_.get()), "MatMult");
    const Eigen::VectorXd y = lu_.solve(operator_ * gather(normal_part_.get()));
    PetscScalar* own = nullptr;
    petsc_check(VecGetArray(normal_part_.get(), &own), "VecGetArray");
    for (PetscInt i = first_; i < end_; ++i) own[i - first_] = y(i);
    petsc_check(VecRestoreArray(normal_part_.get(), &own), "VecRestoreArray");
    petsc_check(MatMultTranspose(normal_map_.get(), normal_part_.get(), scaled_.get()), "MatMultTranspose");
    petsc_check(VecWAXPY(solution, -1.0, scaled_.get(), rhs), "VecWAXPY");
    petsc_check(VecPointwiseMult(solution, solution, inverse_mass_.get()), "VecPointwiseMult");
  }

 private:
  static PetscMatrix reference(Mat matrix) {
    petsc_check(PetscObjectReference(reinterpret_cast<PetscObject>(matrix)), "PetscObjectReference");
    return PetscMatrix(matrix);
  }
  /// The whole of a vertex-layout vector on every rank.
  Eigen::VectorXd gather(Vec distributed) const {
    petsc_check(VecScatterBegin(to_all_.get(), distributed, gathered_.get(), INSERT_VALUES, SCATTER_FORWARD),
                "VecScatterBegin");
    petsc_check(VecScatterEnd(to_all_.get(), distributed, gathered_.get(), INSERT_VALUES, SCATTER_FORWARD),
                "VecScatterEnd");
    const PetscScalar* values = nullptr;
    PetscInt size = 0;
    petsc_check(VecGetLocalSize(gathered_.get(), &size), "VecGetLocalSize");
    petsc_check(VecGetArrayRead(gathered_.get(), &values), "VecGetArrayRead");
    const Eigen::VectorXd whole = Eigen::Map<const Eigen::VectorXd>(values, size);
    petsc_check(VecRestoreArrayRead(gathered_.get(), &values), "VecRestoreArrayRead");
    return whole;
  }

  PetscMatrix normal_map_;
  Eigen::MatrixXd operator_;
  Eigen::PartialPivLU<Eigen::MatrixXd> lu_;
  PetscVector inverse_mass_;
  PetscVector scaled_;       ///< DOF layout: M^-1 r, then N^T y
  PetscVector normal_part_;  ///< vertex layout: N M^-1 r, then y
  PetscVector gathered_;     ///< the whole vertex vector, on every rank
  PetscScatter to_all_;
  PetscInt first_ = 0, end_ = 0;
};

}  // namespace

std::unique_ptr<LinearSolve> make_normal_added_mass_inertia(Mat normal_map, std::span<const double> operator_rows,
                                                            Vec mass_diagonal) {
  return std::make_unique<NormalAddedMassInertia>(normal_map, operator_rows, mass_diagonal);
}

}  // namespace tankfsi::fem
