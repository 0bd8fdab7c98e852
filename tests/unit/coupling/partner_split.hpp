#pragma once
// Two coupling participants in one test binary (as preCICE's test context
// does): the world's ranks [0, fluid_ranks) play the fluid program, the others
// the structure program, joined by an inter-communicator as
// split_program_groups() joins two real programs.
#include <mpi.h>

#include <vector>

#include "coupling/settings.hpp"

namespace tankfsi::coupling::testing {

struct PartnerSplit {
  Side side = Side::fluid;
  MPI_Comm local = MPI_COMM_NULL;
  MPI_Comm partner = MPI_COMM_NULL;
  int fluid_ranks = 1;
  int structure_ranks = 1;

  explicit PartnerSplit(int fluid) : fluid_ranks(fluid) {
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    structure_ranks = size - fluid;
    side = rank < fluid ? Side::fluid : Side::structure;
    MPI_Comm_split(MPI_COMM_WORLD, side == Side::fluid ? 0 : 1, rank, &local);
    MPI_Intercomm_create(local, 0, MPI_COMM_WORLD, side == Side::fluid ? fluid : 0, 77, &partner);
  }
  ~PartnerSplit() {
    MPI_Comm_free(&partner);
    MPI_Comm_free(&local);
  }
  PartnerSplit(const PartnerSplit&) = delete;
  PartnerSplit& operator=(const PartnerSplit&) = delete;
};

/// Every fluid:structure split of the world (1:n-1 ... n-1:1); none on one rank.
inline std::vector<int> fluid_rank_choices() {
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::vector<int> choices;
  for (int f = 1; f < size; ++f) choices.push_back(f);
  return choices;
}

}  // namespace tankfsi::coupling::testing
