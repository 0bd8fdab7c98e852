#pragma once
// Elements partitioned over the ranks with METIS (dual graph: elements sharing
// an edge are neighbours), and each node owned by one rank: the lowest rank
// among its elements'. Computed on rank 0 and broadcast, so every rank holds
// the same partition whatever METIS's internal randomness.
#include <mpi.h>

#include <vector>

#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct MeshPartition {
  std::vector<int> element_rank;
  std::vector<int> node_owner;
};

[[nodiscard]] MeshPartition partition_mesh(const ShellMesh& mesh, MPI_Comm comm);

}  // namespace tankfsi::fem
