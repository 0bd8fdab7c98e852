#include "fem_solver/assembly/mesh_partition.hpp"

#include <metis.h>

#include <algorithm>
#include <stdexcept>

namespace tankfsi::fem {

MeshPartition partition_mesh(const ShellMesh& mesh, MPI_Comm comm) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const std::size_t element_count = mesh.elements.size();
  MeshPartition p;
  p.element_rank.assign(element_count, 0);
  if (size > 1) {
    if (element_count < static_cast<std::size_t>(size))
      throw std::invalid_argument("the mesh has fewer elements (" + std::to_string(element_count) + ") than ranks");
    int status = METIS_OK;
    if (rank == 0) {
      std::vector<idx_t> begin{0};
      std::vector<idx_t> nodes;
      for (const auto& e : mesh.elements) {
        for (int k = 0; k < e.node_count(); ++k) nodes.push_back(e.nodes[static_cast<std::size_t>(k)]);
        begin.push_back(static_cast<idx_t>(nodes.size()));
      }
      idx_t ne = static_cast<idx_t>(element_count);
      idx_t nn = static_cast<idx_t>(mesh.nodes.size());
      idx_t common = 2;  // shells: neighbours share an edge
      idx_t parts = size;
      idx_t cut = 0;
      idx_t options[METIS_NOPTIONS];
      METIS_SetDefaultOptions(options);
      options[METIS_OPTION_SEED] = 1;
      std::vector<idx_t> element_part(element_count), node_part(mesh.nodes.size());
      status = METIS_PartMeshDual(&ne, &nn, begin.data(), nodes.data(), nullptr, nullptr, &common, &parts, nullptr,
                                  options, &cut, element_part.data(), node_part.data());
      std::copy(element_part.begin(), element_part.end(), p.element_rank.begin());
    }
    MPI_Bcast(&status, 1, MPI_INT, 0, comm);
    if (status != METIS_OK) throw std::runtime_error("METIS could not partition the mesh (status " + std::to_string(status) + ")");
    MPI_Bcast(p.element_rank.data(), static_cast<int>(element_count), MPI_INT, 0, comm);
  }
  p.node_owner.assign(mesh.nodes.size(), size);
  for (std::size_t e = 0; e < element_count; ++e)
    for (int k = 0; k < mesh.elements[e].node_count(); ++k) {
      int& owner = p.node_owner[static_cast<std::size_t>(mesh.elements[e].nodes[static_cast<std::size_t>(k)])];
      owner = std::min(owner, p.element_rank[e]);
    }
  return p;
}

}  // namespace tankfsi::fem
