#pragma once
// Acceleration of implicit coupling iterations (METHOD.md §4, "implicit").
//
// The fixed-point problem of one window: x̃ (the interface values a program
// is given) -> x̂ = H(x̃) (what the partner computes from them); residual
// r = x̂ - x̃. Each method proposes the next x̃ from the iterates so far. The
// vectors are the local parts of a vector distributed over one program's
// ranks; norms and dot products are reduced over `comm`. `weights` scale each
// entry in the norms (parallel implicit coupling puts displacements and
// forces in one vector: each field is weighted by the inverse of its size).
#include <mpi.h>

#include <memory>
#include <span>
#include <vector>

#include "coupling/settings.hpp"

namespace tankfsi::coupling {

class Acceleration {
 public:
  virtual ~Acceleration() = default;
  /// The next input from the input `x_tilde` used and the output `x_hat`
  /// obtained with it, in the current window.
  [[nodiscard]] virtual std::vector<double> next_input(std::span<const double> x_tilde, std::span<const double> x_hat,
                                                       std::span<const double> weights) = 0;
  /// The window converged: the next call starts a new window.
  virtual void window_converged() = 0;
  /// Columns of the least-squares history (IQN-ILS; 0 for the others).
  [[nodiscard]] virtual int history_columns() const { return 0; }

  /// What the method carries from one window to the next (taken after
  /// window_converged()), for a restart: numbers, and vectors of the same
  /// local layout as the iterates.
  struct History {
    std::vector<double> numbers;
    std::vector<std::vector<double>> vectors;
  };
  [[nodiscard]] virtual History history() const { return {}; }
  /// Puts back a history() of a method of the same settings.
  virtual void restore_history(const History&) {}
};

/// constant: x̃ + ω r; aitken: ω from the last two residuals (Küttler & Wall
/// 2008); iqn_ils: least squares on the residual differences of this and the
/// last `reused_windows` windows, QR-filtered (Degroote et al. 2009; the
/// variant preCICE calls IQN-ILS).
std::unique_ptr<Acceleration> make_acceleration(const CouplingSettings& settings, MPI_Comm comm);

/// Weighted dot product reduced over `comm`: sum w_i^2 a_i b_i (w empty: 1).
double weighted_dot(MPI_Comm comm, std::span<const double> a, std::span<const double> b, std::span<const double> w);

}  // namespace tankfsi::coupling
