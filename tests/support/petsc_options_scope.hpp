#pragma once
// PetscOptionsScope: a test's own PETSc options database for its lifetime.
//
// The solvers put a case's options into PETSc's global database as defaults
// (tankfsi::apply_default_petsc_options: an option already there wins), as a
// program with one case should. In a test binary one test's options would then
// stay for the tests after it, and a later test's own value of the same option
// would be ignored. A test that gives options holds a scope: its options, and
// the defaults the solvers add, go into a fresh database that is dropped at the
// scope's end.
#include <petscsys.h>

#include <stdexcept>

namespace tankfsi::test {

class PetscOptionsScope {
 public:
  PetscOptionsScope() {
    if (PetscOptionsCreate(&options_) != 0 || PetscOptionsPush(options_) != 0)
      throw std::runtime_error("PetscOptionsScope: could not push a fresh options database");
  }
  ~PetscOptionsScope() {
    PetscOptionsPop();
    PetscOptionsDestroy(&options_);
  }
  PetscOptionsScope(const PetscOptionsScope&) = delete;
  PetscOptionsScope& operator=(const PetscOptionsScope&) = delete;

 private:
  PetscOptions options_ = nullptr;
};

}  // namespace tankfsi::test
