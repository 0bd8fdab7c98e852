#pragma once
// ScratchFolder: a fresh temporary folder for one test, removed with the object.
//
// per_rank: every rank its own folder, for serial code that each rank tests.
// shared:   one folder for all ranks of MPI_COMM_WORLD, for parallel writers;
//           construction and destruction are then collective (rank 0 makes and
//           removes it, the others wait).
#include <mpi.h>
#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "common/parallel/collective.hpp"

namespace tankfsi::testing {

class ScratchFolder {
 public:
  enum class Scope { per_rank, shared };

  explicit ScratchFolder(Scope scope = Scope::per_rank) : scope_(scope) {
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    std::string made;
    if (scope_ == Scope::per_rank || rank_ == 0) made = make_folder();
    if (scope_ == Scope::shared) made = broadcast_text(MPI_COMM_WORLD, made);
    if (made.empty()) throw std::runtime_error("could not make a temporary folder");
    path_ = made;
  }

  ~ScratchFolder() {
    if (scope_ == Scope::shared) MPI_Barrier(MPI_COMM_WORLD);
    std::error_code ignored;
    if (scope_ == Scope::per_rank || rank_ == 0) std::filesystem::remove_all(path_, ignored);
    if (scope_ == Scope::shared) MPI_Barrier(MPI_COMM_WORLD);
  }
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  [[nodiscard]] std::filesystem::path file(const std::string& name) const { return path_ / name; }

 private:
  static std::string make_folder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "tankfsi_test_XXXXXX").string();
    return mkdtemp(pattern.data()) ? pattern : std::string();
  }

  Scope scope_;
  int rank_ = 0;
  std::filesystem::path path_;
};

}  // namespace tankfsi::testing
