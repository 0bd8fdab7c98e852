#pragma once
// MpiSession: MPI and PETSc initialised for the life of one program.
//
// MPI starts first so that the world can be split into the partner programs
// of a coupled job (program_groups.hpp); PETSc then runs on this program's
// own ranks (PETSC_COMM_WORLD = the program's group), so every solver, every
// collective and -log_view see one program only.
// PETSc sees only the arguments meant for it (single-dash options such as
// -log_view or -ppe_ksp_type); the program's own options are parsed first by
// CommandLine and never reach PetscInitialize.
#include <mpi.h>

#include <string>
#include <vector>

#include "common/parallel/program_groups.hpp"

namespace tankfsi {

class MpiSession {
 public:
  /// petsc_arguments: argv[0] followed by the options PETSc should read.
  /// role: the program's role in a coupled job ("fluid", "structure"); empty
  /// for a program that never couples (its group is the whole world).
  explicit MpiSession(const std::vector<std::string>& petsc_arguments, const std::string& role = "");
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  /// This program's ranks (the whole world when it runs alone).
  [[nodiscard]] MPI_Comm world() const { return groups_.local; }
  /// Inter-communicator to the partner program, or MPI_COMM_NULL when alone.
  [[nodiscard]] MPI_Comm partner() const { return groups_.partner; }
  [[nodiscard]] const ProgramGroups& groups() const { return groups_; }
  /// Rank and size in this program's group.
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }
  /// Size of the whole job (both partners).
  [[nodiscard]] int job_size() const { return job_size_; }

 private:
  ProgramGroups groups_;
  int rank_ = 0;
  int size_ = 1;
  int job_size_ = 1;
};

/// Rank and size of a communicator, for code that needs both.
struct CommInfo {
  int rank = 0;
  int size = 1;
};
CommInfo comm_info(MPI_Comm comm);

}  // namespace tankfsi
