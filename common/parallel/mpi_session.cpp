#include "common/parallel/mpi_session.hpp"

#include <petscsys.h>

#include <cstdlib>
#include <iostream>
#include <stdexcept>

namespace tankfsi {

namespace {

// Open MPI's MPI-IO (ompio) opens a shared-file-pointer component with every
// file, though no writer here uses shared file pointers. Its default, "sm",
// guards the pointer with a POSIX semaphore named after the file's base name
// alone (/dev/shm/sem.OMPIO_<name>): a job killed while it holds one leaves
// the semaphore taken, and every later job on the node that opens a file of
// that name (the next run's checkpoint 2, say) waits in MPI_File_open
// forever; two jobs writing files of the same name at once share it.
// "lockedfile" leaves lock files beside the output when killed. Neither is
// needed, so neither is opened, unless the user set the parameter.
void keep_mpi_io_off_shared_file_pointers() {
  setenv("OMPI_MCA_sharedfp", "^sm,lockedfile", /*overwrite=*/0);
}

}  // namespace

MpiSession::MpiSession(const std::vector<std::string>& petsc_arguments, const std::string& role) {
  // PetscInitialize wants a mutable argv that outlives the call.
  static std::vector<std::string> storage;
  static std::vector<char*> argv;
  storage = petsc_arguments;
  if (storage.empty()) storage.emplace_back("tankfsi");
  argv.clear();
  for (auto& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  int argc = static_cast<int>(storage.size());
  char** argv_pointer = argv.data();

  keep_mpi_io_off_shared_file_pointers();
  MPI_Init(&argc, &argv_pointer);
  MPI_Comm_size(MPI_COMM_WORLD, &job_size_);
  if (role.empty()) {
    MPI_Comm_dup(MPI_COMM_WORLD, &groups_.local);
  } else {
    try {
      groups_ = split_program_groups(MPI_COMM_WORLD, role);
    } catch (const std::exception& e) {
      // Every rank reached the same verdict; one says it, all stop.
      int world_rank = 0;
      MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
      if (world_rank == 0) std::cerr << "error: " << e.what() << std::endl;
      MPI_Finalize();
      std::exit(2);
    }
  }
  PETSC_COMM_WORLD = groups_.local;
  if (PetscInitialize(&argc, &argv_pointer, nullptr, nullptr) != 0)
    throw std::runtime_error("PETSc failed to initialise");
  MPI_Comm_rank(groups_.local, &rank_);
  MPI_Comm_size(groups_.local, &size_);
}

MpiSession::~MpiSession() {
  PetscFinalize();
  free_program_groups(groups_);
  MPI_Finalize();
}

CommInfo comm_info(MPI_Comm comm) {
  CommInfo info;
  MPI_Comm_rank(comm, &info.rank);
  MPI_Comm_size(comm, &info.size);
  return info;
}

}  // namespace tankfsi
