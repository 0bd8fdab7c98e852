#include "fem_solver/assembly/dof_map.hpp"

#include <stdexcept>

namespace tankfsi::fem {

DofMap::DofMap(std::size_t node_count, const std::vector<DofConstraint>& constraints, const MeshPartition& partition,
               int rank, int ranks)
    : equation_(dofs_per_node * node_count, 0), prescribed_(dofs_per_node * node_count, 0.0) {
  for (const auto& c : constraints) {
    if (c.node < 0 || static_cast<std::size_t>(c.node) >= node_count || c.component < 0 || c.component >= dofs_per_node)
      throw std::invalid_argument("constraint on a DOF that does not exist");
    const auto slot = static_cast<std::size_t>(dofs_per_node * c.node + c.component);
    equation_[slot] = -1;
    prescribed_[slot] = c.value;
  }
  PetscInt next = 0;
  for (int r = 0; r < ranks; ++r) {
    if (r == rank) first_owned_ = next;
    for (std::size_t node = 0; node < node_count; ++node) {
      if (partition.node_owner[node] != r) continue;
      for (std::size_t k = 0; k < dofs_per_node; ++k) {
        PetscInt& e = equation_[dofs_per_node * node + k];
        if (e != -1) e = next++;
      }
    }
    if (r == rank) owned_count_ = next - first_owned_;
  }
  global_size_ = next;
  if (global_size_ == 0) throw std::invalid_argument("every DOF of the structure is constrained");
}

}  // namespace tankfsi::fem
