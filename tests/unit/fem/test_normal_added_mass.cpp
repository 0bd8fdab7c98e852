// The added mass through its factors (normal_added_mass.hpp): the product
// N^T (A (N x)) and the inertia's solve (M + N^T A N)^-1 r, against the same
// written out densely with Eigen on every rank: a random operator A and random
// unit normals of n vertices on a distributed system of 6 DOFs per node, some
// translations supported (no equation), on 1, 2 and 4 ranks.
#include <petscmat.h>
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <mpi.h>
#include <random>
#include <span>
#include <vector>

#include "fem_solver/analysis/normal_added_mass.hpp"
#include "common/run/petsc_handle.hpp"

using namespace tankfsi;
using namespace tankfsi::fem;

namespace {

/// 40 nodes of 6 DOFs; the interface: nodes 10 .. 34 (25 vertices), the
/// first three vertices' z supported.
struct Interface {
  static constexpr PetscInt nodes = 40;
  static constexpr PetscInt dofs = 6 * nodes;
  static constexpr PetscInt vertices = 25;
  std::mt19937_64 engine{5};
  Eigen::MatrixXd a{vertices, vertices};
  Eigen::MatrixXd normals{vertices, 3};
  Eigen::MatrixXd n_dense = Eigen::MatrixXd::Zero(vertices, dofs);
  PetscMatrix n_map;  ///< N: AIJ, rows distributed
  PetscInt first = 0, end = 0;

  double uniform() { return static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5; }

  explicit Interface(bool positive_definite) {
    for (PetscInt i = 0; i < vertices; ++i)
      for (PetscInt j = 0; j < vertices; ++j) a(i, j) = uniform();
    // A liquid's operator is symmetric positive definite, of the structure's
    // mass or larger (the coarse tank's: 50 times the wall's).
    if (positive_definite) a = 50.0 * (a * a.transpose() + 0.1 * Eigen::MatrixXd::Identity(vertices, vertices));
    for (PetscInt i = 0; i < vertices; ++i)
      normals.row(i) = Eigen::RowVector3d(uniform(), uniform(), uniform()).normalized();
    for (PetscInt i = 0; i < vertices; ++i)
      for (PetscInt c = 0; c < 3; ++c)
        if (const PetscInt e = equation(i, c); e >= 0) n_dense(i, e) = normals(i, c);
    petsc_check(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, vertices, dofs, 3, nullptr, 3, nullptr,
                             n_map.out()),
                "MatCreateAIJ");
    MatGetOwnershipRange(n_map.get(), &first, &end);
    for (PetscInt i = first; i < end; ++i)
      for (PetscInt c = 0; c < 3; ++c)
        if (const PetscInt e = equation(i, c); e >= 0) MatSetValue(n_map.get(), i, e, normals(i, c), INSERT_VALUES);
    MatAssemblyBegin(n_map.get(), MAT_FINAL_ASSEMBLY);
    MatAssemblyEnd(n_map.get(), MAT_FINAL_ASSEMBLY);
  }
  /// Vertex i's translation c is equation 6 (10 + i) + c, except the first three vertices' z.
  static PetscInt equation(PetscInt i, PetscInt c) { return (i < 3 && c == 2) ? -1 : 6 * (10 + i) + c; }
  Eigen::VectorXd random(PetscInt size, double low, double high) {
    Eigen::VectorXd x(size);
    for (PetscInt k = 0; k < size; ++k) x(k) = low + (high - low) * (uniform() + 0.5);
    return x;
  }
};

/// A distributed vector with `layout`'s layout holding `values`.
PetscVector distributed(Vec layout, const Eigen::VectorXd& values) {
  PetscVector x;
  petsc_check(VecDuplicate(layout, x.out()), "VecDuplicate");
  PetscInt low = 0, high = 0;
  VecGetOwnershipRange(x.get(), &low, &high);
  for (PetscInt k = low; k < high; ++k) VecSetValue(x.get(), k, values(k), INSERT_VALUES);
  VecAssemblyBegin(x.get());
  VecAssemblyEnd(x.get());
  return x;
}

/// The largest difference between a distributed vector and `expected`, over all ranks.
double largest_difference(Vec x, const Eigen::VectorXd& expected, double shift = 0.0) {
  PetscInt low = 0, high = 0;
  VecGetOwnershipRange(x, &low, &high);
  const PetscScalar* values = nullptr;
  VecGetArrayRead(x, &values);
  double worst = 0.0;
  for (PetscInt k = low; k < high; ++k) worst = std::max(worst, std::abs(values[k - low] - shift - expected(k)));
  VecRestoreArrayRead(x, &values);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  return worst;
}

}  // namespace

TEST_CASE("the added mass's product through its factors equals N^T A N x", "[fem][added_mass]") {
  // The two sum the same products in other orders: 1e-13 of the largest entry.
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  Interface interface(false);
  const Eigen::VectorXd x = interface.random(Interface::dofs, -0.5, 0.5);
  const Eigen::VectorXd expected = interface.n_dense.transpose() * (interface.a * (interface.n_dense * x));

  // A: dense, N's row layout; then the shell.
  PetscMatrix a_matrix;
  petsc_check(MatCreateDense(PETSC_COMM_WORLD, interface.end - interface.first, interface.end - interface.first,
                             Interface::vertices, Interface::vertices, nullptr, a_matrix.out()),
              "MatCreateDense");
  for (PetscInt i = interface.first; i < interface.end; ++i)
    for (PetscInt j = 0; j < Interface::vertices; ++j) MatSetValue(a_matrix.get(), i, j, interface.a(i, j), INSERT_VALUES);
  MatAssemblyBegin(a_matrix.get(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(a_matrix.get(), MAT_FINAL_ASSEMBLY);
  const PetscMatrix product = make_normal_added_mass_product(interface.n_map.get(), a_matrix.get());
  interface.n_map.reset();  // the shell keeps its own references
  a_matrix.reset();

  PetscVector x_vec, y_vec;
  petsc_check(MatCreateVecs(product.get(), x_vec.out(), y_vec.out()), "MatCreateVecs");
  x_vec = distributed(x_vec.get(), x);
  petsc_check(MatMult(product.get(), x_vec.get(), y_vec.get()), "MatMult");
  // MatMultAdd through the shell: y + M_a x.
  PetscVector z_vec;
  VecDuplicate(y_vec.get(), z_vec.out());
  VecSet(z_vec.get(), 1.0);
  petsc_check(MatMultAdd(product.get(), x_vec.get(), z_vec.get(), z_vec.get()), "MatMultAdd");

  const double scale = expected.cwiseAbs().maxCoeff();
  INFO("ranks " << size << ", largest entry " << scale);
  CHECK(scale > 0.5);  // not a product of zeros
  CHECK(largest_difference(y_vec.get(), expected) <= 1e-13 * scale);
  CHECK(largest_difference(z_vec.get(), expected, 1.0) <= 1e-13 * scale);
}

TEST_CASE("the inertia through the added mass's factors solves (M + N^T A N) a = r", "[fem][added_mass]") {
  // Against Eigen's LU of M + N^T A N assembled densely (240 x 240): both
  // solve the same system, whose condition number here (a lumped mass of
  // 0.5-2 beside an operator of 50 times that) keeps their round-off apart by
  // less than 1e-12 of the acceleration. Without the added mass's share the
  // answer would be M^-1 r: the check sees the operator.
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  Interface interface(true);
  const Eigen::VectorXd mass = interface.random(Interface::dofs, 0.5, 2.0);
  const Eigen::VectorXd r = interface.random(Interface::dofs, -1.0, 1.0);
  const Eigen::MatrixXd inertia =
      Eigen::MatrixXd(mass.asDiagonal()) + interface.n_dense.transpose() * interface.a * interface.n_dense;
  const Eigen::VectorXd expected = inertia.partialPivLu().solve(r);
  REQUIRE((expected - r.cwiseQuotient(mass)).cwiseAbs().maxCoeff() > 0.1 * expected.cwiseAbs().maxCoeff());

  PetscVector layout;
  petsc_check(MatCreateVecs(interface.n_map.get(), layout.out(), nullptr), "MatCreateVecs");
  const PetscVector m_vec = distributed(layout.get(), mass);
  const PetscVector r_vec = distributed(layout.get(), r);
  std::vector<double> rows(static_cast<std::size_t>(Interface::vertices * Interface::vertices));
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      rows.data(), Interface::vertices, Interface::vertices) = interface.a;
  // An operator of another size than N's rows is an error, not a wrong answer.
  CHECK_THROWS_AS(make_normal_added_mass_inertia(interface.n_map.get(), std::span<const double>(rows).first(24 * 24),
                                                 m_vec.get()),
                  std::invalid_argument);
  const auto inverse = make_normal_added_mass_inertia(interface.n_map.get(), rows, m_vec.get());
  interface.n_map.reset();  // the solver keeps its own reference
  PetscVector a_vec;
  VecDuplicate(layout.get(), a_vec.out());
  inverse->solve(r_vec.get(), a_vec.get());
  INFO("ranks " << size << ", largest entry " << expected.cwiseAbs().maxCoeff());
  CHECK(largest_difference(a_vec.get(), expected) <= 1e-12 * expected.cwiseAbs().maxCoeff());
  // Solving twice gives the same (the work vectors are reused).
  inverse->solve(r_vec.get(), a_vec.get());
  CHECK(largest_difference(a_vec.get(), expected) <= 1e-12 * expected.cwiseAbs().maxCoeff());
}
