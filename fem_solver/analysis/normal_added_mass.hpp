#pragma once
// The product with an added mass that acts along the wetted surface's normals
// only (coupling/PROTOCOL.md "Added mass"): M_a = N^T A N, A the liquid's n x n
// operator on the interface vertices' normal velocities, N (n x DOFs) the map of
// each vertex's translation onto its normal.
//
// Assembled, M_a couples every interface translation with every other (9 n^2
// entries: 4.5e6 for the coarse tank's 704 vertices), as K_eff's factorisation
// needs it; a Newmark step's products with it (two per step) cost n^2 + 6 n
// multiply-adds through the factors instead, some fifteen times less memory
// traffic: a shell matrix with the assembled one's layout.
//
// The inertia M + M_a with M diagonal (lumped) is solved through the same
// factors: with y = A N a the equation (M + N^T A N) a = r reads
//   a = M^-1 (r - N^T y),   (I + A D) y = A N M^-1 r,   D = N M^-1 N^T,
// D diagonal (row i of N holds vertex i's translations only). One dense LU
// of the n x n matrix I + A D (n^3/3 flops, once per operator), then per
// solve two products with N, one with A and two triangular solves (~3 n^2):
// the sparse factorisation of M + M_a assembled carries a dense 3n x 3n front
// (the coarse tank's window start: 13 ms a solve that way, README).
#include <memory>
#include <span>

#include "fem_solver/assembly/linear_solve.hpp"
#include "common/run/petsc_handle.hpp"

namespace tankfsi::fem {

/// y = N^T (A (N x)) as a shell matrix (DOFs x DOFs, N's column layout). N is
/// n x DOFs (AIJ), A is n x n with N's row layout for rows and columns (dense).
/// Both are kept by reference (PETSc reference counts) for the shell's life.
[[nodiscard]] PetscMatrix make_normal_added_mass_product(Mat normal_map, Mat operator_matrix);

/// (M + N^T A N)^-1 for the diagonal `mass_diagonal` (DOF layout), N as in
/// make_normal_added_mass_product and A given whole, row-major n x n, the
/// same on every rank (each rank solves the n x n system itself). Throws
/// std::runtime_error when I + A D is singular.
[[nodiscard]] std::unique_ptr<LinearSolve> make_normal_added_mass_inertia(Mat normal_map,
                                                                         std::span<const double> operator_rows,
                                                                         Vec mass_diagonal);

}  // namespace tankfsi::fem
