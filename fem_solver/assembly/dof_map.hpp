#pragma once
// DofMap: the equation numbers of the free DOFs. Each node has 6 DOFs
// (u_x u_y u_z theta_x theta_y theta_z); constrained ones (fixed, pinned,
// symmetry, prescribed) are eliminated — they get no equation and keep their
// prescribed value — so K and M stay symmetric positive definite and the
// default Cholesky factorisation applies. Equations are numbered rank by rank
// (PETSc's contiguous ownership): rank 0's owned nodes in node order, then
// rank 1's, ...
#include <petscsys.h>

#include <vector>

#include "fem_solver/assembly/mesh_partition.hpp"

namespace tankfsi::fem {

inline constexpr int dofs_per_node = 6;

/// One constrained DOF: node, component 0..5, prescribed value (m or rad).
struct DofConstraint {
  int node = 0;
  int component = 0;
  double value = 0.0;
};

class DofMap {
 public:
  /// Later constraints on the same DOF replace earlier ones.
  DofMap(std::size_t node_count, const std::vector<DofConstraint>& constraints, const MeshPartition& partition,
         int rank, int ranks);

  /// Equation of DOF `component` of `node`, or -1 when it is constrained.
  [[nodiscard]] PetscInt equation(int node, int component) const {
    return equation_[static_cast<std::size_t>(dofs_per_node * node + component)];
  }
  [[nodiscard]] double prescribed(int node, int component) const {
    return prescribed_[static_cast<std::size_t>(dofs_per_node * node + component)];
  }
  [[nodiscard]] PetscInt global_size() const { return global_size_; }
  [[nodiscard]] PetscInt first_owned() const { return first_owned_; }
  [[nodiscard]] PetscInt owned_count() const { return owned_count_; }
  [[nodiscard]] std::size_t node_count() const { return equation_.size() / dofs_per_node; }
  /// Number of constrained DOFs.
  [[nodiscard]] std::size_t constrained_count() const { return equation_.size() - static_cast<std::size_t>(global_size_); }

 private:
  std::vector<PetscInt> equation_;
  std::vector<double> prescribed_;
  PetscInt global_size_ = 0;
  PetscInt first_owned_ = 0;
  PetscInt owned_count_ = 0;
};

}  // namespace tankfsi::fem
