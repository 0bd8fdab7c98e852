#pragma once
// ProgramGroups: the two partner programs of one MPMD job, found in the world.
//
//   mpirun -np A sph_solver case.yaml : -np B fem_solver case.yaml
//
// starts one MPI world of A + B ranks. Each program needs a communicator of its
// own ranks (PETSc, the solvers and every collective use it) and an
// inter-communicator to its partner (the coupling library uses it).
// split_program_groups() finds them:
//   - by MPI_APPNUM, which mpirun sets to the index of the program in the
//     command line, when every rank has it and each number holds one role;
//   - otherwise by the role each program declares ("fluid", "structure"):
//     launchers that run several programs as one application (srun
//     --multi-prog, a wrapper script) give every rank the same MPI_APPNUM.
// A world that holds only one program gives it the whole world and no partner.
#include <mpi.h>

#include <string>

namespace tankfsi {

struct ProgramGroups {
  MPI_Comm local = MPI_COMM_NULL;    ///< this program's ranks
  MPI_Comm partner = MPI_COMM_NULL;  ///< inter-communicator to the partner, or MPI_COMM_NULL alone
  std::string partner_role;          ///< the partner's role, empty alone
  bool split_by_appnum = false;      ///< how the groups were told apart
};

/// Collective over `world`. `role`: this program's role, the same on all its
/// ranks. Throws std::runtime_error (the same on every rank) if the world holds
/// more than two programs or two programs of one role.
ProgramGroups split_program_groups(MPI_Comm world, const std::string& role);

/// Frees the communicators of `groups` (not the world).
void free_program_groups(ProgramGroups& groups);

}  // namespace tankfsi
