#pragma once
// LinearSolve: a factorised (or preconditioned) operator that solves for any
// right-hand side; what the time integrator needs, whatever builds it.
#include <petscmat.h>

#include <functional>
#include <memory>

namespace tankfsi::fem {

class LinearSolve {
 public:
  virtual ~LinearSolve() = default;
  /// Throws std::runtime_error when the solve fails.
  virtual void solve(Vec rhs, Vec solution) const = 0;
};

/// Builds the solver of a matrix (factorising it).
using SolverFactory = std::function<std::unique_ptr<LinearSolve>(Mat)>;

}  // namespace tankfsi::fem
