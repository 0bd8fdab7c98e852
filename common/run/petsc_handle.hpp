#pragma once
// Owning handles of PETSc objects (destroyed with the handle) and the one
// error check every PETSc call goes through.
#include <petscksp.h>

#include <stdexcept>
#include <string>
#include <utility>

namespace tankfsi {

inline void petsc_check(PetscErrorCode code, const char* what) {
  if (code != 0) throw std::runtime_error(std::string("PETSc error in ") + what + " (code " + std::to_string(code) + ")");
}

template <class Object, PetscErrorCode (*destroy)(Object*)>
class PetscHandle {
 public:
  PetscHandle() = default;
  explicit PetscHandle(Object object) : object_(object) {}
  PetscHandle(const PetscHandle&) = delete;
  PetscHandle& operator=(const PetscHandle&) = delete;
  PetscHandle(PetscHandle&& other) noexcept : object_(std::exchange(other.object_, nullptr)) {}
  PetscHandle& operator=(PetscHandle&& other) noexcept {
    if (this != &other) {
      reset();
      object_ = std::exchange(other.object_, nullptr);
    }
    return *this;
  }
  ~PetscHandle() { reset(); }

  void reset() {
    if (object_ != nullptr) destroy(&object_);
    object_ = nullptr;
  }
  [[nodiscard]] Object get() const { return object_; }
  /// For PETSc's create functions: PetscCall(MatCreate(comm, handle.out())).
  [[nodiscard]] Object* out() {
    reset();
    return &object_;
  }
  explicit operator bool() const { return object_ != nullptr; }

 private:
  Object object_ = nullptr;
};

using PetscMatrix = PetscHandle<Mat, MatDestroy>;
using PetscVector = PetscHandle<Vec, VecDestroy>;
using PetscSolver = PetscHandle<KSP, KSPDestroy>;
using PetscScatter = PetscHandle<VecScatter, VecScatterDestroy>;
using PetscIndexSet = PetscHandle<IS, ISDestroy>;

}  // namespace tankfsi
