// The added mass's product through its factors, N^T (A (N x)) (normal_added_mass.hpp),
// against the same product written out densely with Eigen on every rank: a random
// operator A and random unit normals of n vertices on a distributed system of
// 6 DOFs per node, some translations supported (no equation), on 1, 2 and 4 ranks.
// The two sum the same products in other orders: 1e-13 of the largest entry.
#include <petscmat.h>
#include <catch2/catch.hpp>
#include <Eigen/Dense>
#include <mpi.h>
#include <random>
#include <vector>

#include "fem_solver/analysis/normal_added_mass.hpp"
#include "fem_solver/assembly/petsc_handle.hpp"

using namespace tankfsi::fem;

TEST_CASE("the added mass's product through its factors equals N^T A N x", "[fem][added_mass]") {
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const PetscInt nodes = 40;
  const PetscInt dofs = 6 * nodes;
  const PetscInt vertices = 25;  // the interface: nodes 10 .. 34
  std::mt19937_64 engine(5);
  const auto uniform = [&engine] { return static_cast<double>(engine() >> 11) * 0x1.0p-53 - 0.5; };
  Eigen::MatrixXd a(vertices, vertices);
  for (PetscInt i = 0; i < vertices; ++i)
    for (PetscInt j = 0; j < vertices; ++j) a(i, j) = uniform();
  Eigen::MatrixXd normals(vertices, 3);
  for (PetscInt i = 0; i < vertices; ++i) normals.row(i) = Eigen::RowVector3d(uniform(), uniform(), uniform()).normalized();
  // Vertex i's translations are equations 6 (10 + i) + c, except the first three
  // vertices' z (supported).
  std::vector<PetscInt> equation(static_cast<std::size_t>(3 * vertices));
  for (PetscInt i = 0; i < vertices; ++i)
    for (PetscInt c = 0; c < 3; ++c) equation[static_cast<std::size_t>(3 * i + c)] = (i < 3 && c == 2) ? -1 : 6 * (10 + i) + c;
  Eigen::VectorXd x(dofs);
  for (PetscInt k = 0; k < dofs; ++k) x(k) = uniform();

  // Dense: y = N^T A N x.
  Eigen::MatrixXd n_dense = Eigen::MatrixXd::Zero(vertices, dofs);
  for (PetscInt i = 0; i < vertices; ++i)
    for (PetscInt c = 0; c < 3; ++c)
      if (const PetscInt e = equation[static_cast<std::size_t>(3 * i + c)]; e >= 0) n_dense(i, e) = normals(i, c);
  const Eigen::VectorXd expected = n_dense.transpose() * (a * (n_dense * x));

  // PETSc: N (AIJ, rows distributed) and A (dense, N's row layout), then the shell.
  PetscMatrix n_map;
  petsc_check(MatCreateAIJ(PETSC_COMM_WORLD, PETSC_DECIDE, PETSC_DECIDE, vertices, dofs, 3, nullptr, 3, nullptr,
                           n_map.out()),
              "MatCreateAIJ");
  PetscInt first = 0, end = 0;
  MatGetOwnershipRange(n_map.get(), &first, &end);
  for (PetscInt i = first; i < end; ++i)
    for (PetscInt c = 0; c < 3; ++c)
      if (const PetscInt e = equation[static_cast<std::size_t>(3 * i + c)]; e >= 0)
        MatSetValue(n_map.get(), i, e, normals(i, c), INSERT_VALUES);
  MatAssemblyBegin(n_map.get(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(n_map.get(), MAT_FINAL_ASSEMBLY);
  PetscMatrix a_matrix;
  petsc_check(MatCreateDense(PETSC_COMM_WORLD, end - first, end - first, vertices, vertices, nullptr, a_matrix.out()),
              "MatCreateDense");
  for (PetscInt i = first; i < end; ++i)
    for (PetscInt j = 0; j < vertices; ++j) MatSetValue(a_matrix.get(), i, j, a(i, j), INSERT_VALUES);
  MatAssemblyBegin(a_matrix.get(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(a_matrix.get(), MAT_FINAL_ASSEMBLY);
  const PetscMatrix product = make_normal_added_mass_product(n_map.get(), a_matrix.get());
  n_map.reset();  // the shell keeps its own references
  a_matrix.reset();

  PetscVector x_vec, y_vec;
  petsc_check(MatCreateVecs(product.get(), x_vec.out(), y_vec.out()), "MatCreateVecs");
  PetscInt low = 0, high = 0;
  VecGetOwnershipRange(x_vec.get(), &low, &high);
  for (PetscInt k = low; k < high; ++k) VecSetValue(x_vec.get(), k, x(k), INSERT_VALUES);
  VecAssemblyBegin(x_vec.get());
  VecAssemblyEnd(x_vec.get());
  petsc_check(MatMult(product.get(), x_vec.get(), y_vec.get()), "MatMult");
  // MatMultAdd through the shell: y + M_a x.
  PetscVector z_vec;
  VecDuplicate(y_vec.get(), z_vec.out());
  VecSet(z_vec.get(), 1.0);
  petsc_check(MatMultAdd(product.get(), x_vec.get(), z_vec.get(), z_vec.get()), "MatMultAdd");

  const PetscScalar* y = nullptr;
  const PetscScalar* z = nullptr;
  VecGetArrayRead(y_vec.get(), &y);
  VecGetArrayRead(z_vec.get(), &z);
  double worst = 0.0;
  for (PetscInt k = low; k < high; ++k) {
    worst = std::max(worst, std::abs(y[k - low] - expected(k)));
    worst = std::max(worst, std::abs(z[k - low] - 1.0 - expected(k)));
  }
  VecRestoreArrayRead(y_vec.get(), &y);
  VecRestoreArrayRead(z_vec.get(), &z);
  MPI_Allreduce(MPI_IN_PLACE, &worst, 1, MPI_DOUBLE, MPI_MAX, PETSC_COMM_WORLD);
  INFO("ranks " << size << ", largest entry " << expected.cwiseAbs().maxCoeff());
  CHECK(expected.cwiseAbs().maxCoeff() > 0.5);  // not a product of zeros
  CHECK(worst <= 1e-13 * expected.cwiseAbs().maxCoeff());
}
