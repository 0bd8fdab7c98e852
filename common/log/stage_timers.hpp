#pragma once
// StageTimers: wall time per named stage of a program (neighbours, ppe_solve,
// shell_step, coupling_wait, ...). Each stage is also a PETSc log stage, so
// `-log_view` breaks PETSc's own events down by the same stages.
#include <petscsys.h>

#include <chrono>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace tankfsi {

class StageTimers {
 public:
  /// Times a scope: pushes the PETSc stage on entry, pops and accumulates on exit.
  class Scope {
   public:
    Scope(StageTimers& timers, std::size_t index);
    ~Scope();
    Scope(const Scope&) = delete;
    Scope& operator=(const Scope&) = delete;

   private:
    StageTimers& timers_;
    std::size_t index_;
    std::chrono::steady_clock::time_point start_;
  };

  /// Starts timing `stage` until the returned scope ends. Stages nest.
  [[nodiscard]] Scope time(const std::string& stage);

  [[nodiscard]] double seconds(const std::string& stage) const;
  [[nodiscard]] long calls(const std::string& stage) const;
  /// {"stage": {"seconds": s, "calls": n}, ...} in first-use order.
  [[nodiscard]] nlohmann::json to_json() const;
  /// A table for the end-of-run summary.
  [[nodiscard]] std::string table() const;

 private:
  struct Stage {
    std::string name;
    PetscLogStage petsc_stage = 0;
    double seconds = 0.0;
    long calls = 0;
  };
  [[nodiscard]] const Stage* find(const std::string& name) const;
  std::vector<Stage> stages_;
};

}  // namespace tankfsi
