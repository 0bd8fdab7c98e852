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
#include "fem_solver/assembly/petsc_handle.hpp"

namespace tankfsi::fem {

/// y = N^T (A (N x)) as a shell matrix (DOFs x DOFs, N's column layout). N is
/// n x DOFs (AIJ), A is n x n with N's row layout for rows and columns (dense).
/// Both are kept by reference (PETSc reference counts) for the shell's life.
[[nodiscard]] PetscMatrix make_normal_added_mass_product(Mat normal_map, Mat operator_matrix);

}  // namespace tankfsi::fem
