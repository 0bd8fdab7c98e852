#pragma once
// MpiSession: MPI and PETSc initialised for the life of one program.
//
// PETSc sees only the arguments meant for it (single-dash options such as
// -log_view or -ppe_ksp_type); the program's own options are parsed first by
// CommandLine and never reach PetscInitialize.
#include <mpi.h>

#include <string>
#include <vector>

namespace tankfsi {

class MpiSession {
 public:
  /// petsc_arguments: argv[0] followed by the options PETSc should read.
  explicit MpiSession(const std::vector<std::string>& petsc_arguments);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  [[nodiscard]] MPI_Comm world() const { return MPI_COMM_WORLD; }
  [[nodiscard]] int rank() const { return rank_; }
  [[nodiscard]] int size() const { return size_; }

 private:
  int rank_ = 0;
  int size_ = 1;
};

/// Rank and size of a communicator, for code that needs both.
struct CommInfo {
  int rank = 0;
  int size = 1;
};
CommInfo comm_info(MPI_Comm comm);

}  // namespace tankfsi
