#pragma once
// Linear static analysis: K u = F + lift of prescribed displacements.
#include "fem_solver/analysis/load_set.hpp"
#include "fem_solver/analysis/structure_system.hpp"

namespace tankfsi::fem {

struct StaticResult {
  NodalValues displacement;  ///< whole structure, 6 per node
  NodalValues reactions;     ///< support forces at constrained DOFs
  std::string solver;        ///< what solved it ("preonly/cholesky(mumps)")
  int iterations = 0;
};

/// Timed stages: shell_factorise, shell_solve.
[[nodiscard]] StaticResult solve_static(StructureSystem& system, const LoadSet& loads);

/// Large rotations (corotational_newmark.hpp): the loads applied in
/// `load_steps` equal increments, each solved to equilibrium by Newton's
/// method; `iterations` counts Newton's iterations over all of them.
/// Throws std::runtime_error when an increment does not converge.
[[nodiscard]] StaticResult solve_static_corotational(StructureSystem& system, const LoadSet& loads, int load_steps);

}  // namespace tankfsi::fem
