#include "common/parallel/mpi_session.hpp"

#include <petscsys.h>

#include <stdexcept>

namespace tankfsi {

MpiSession::MpiSession(const std::vector<std::string>& petsc_arguments) {
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
  if (PetscInitialize(&argc, &argv_pointer, nullptr, nullptr) != 0)
    throw std::runtime_error("PETSc failed to initialise");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

MpiSession::~MpiSession() { PetscFinalize(); }

CommInfo comm_info(MPI_Comm comm) {
  CommInfo info;
  MPI_Comm_rank(comm, &info.rank);
  MPI_Comm_size(comm, &info.size);
  return info;
}

}  // namespace tankfsi
