#pragma once
// IQN-ILS: interface quasi-Newton with an inverse Jacobian from least squares
// (Degroote, Bathe & Vierendeels 2009), as preCICE implements it.
//
// Columns V_i = r_{i+1} - r_i and W_i = x̂_{i+1} - x̂_i of this window's
// iterates and of the last `reused_windows` windows, newest first. The next
// input is x̂_k + W c with c = argmin |V c + r_k|, from a QR decomposition of
// the (weighted) V by classical Gram-Schmidt with one re-orthogonalisation;
// a column whose part orthogonal to the newer ones is below
// `filter_tolerance` of its norm is dropped for good (preCICE's QR1 filter),
// which keeps the least-squares problem well conditioned. Without columns
// (the first iteration of a run) the step is x̃ + ω r.
#include <deque>

#include "coupling/acceleration/acceleration.hpp"

namespace tankfsi::coupling {

class IqnIls final : public Acceleration {
 public:
  IqnIls(double initial_relaxation, int reused_windows, double filter_tolerance, MPI_Comm comm)
      : initial_relaxation_(initial_relaxation), reused_windows_(reused_windows), filter_(filter_tolerance),
        comm_(comm) {}

  std::vector<double> next_input(std::span<const double> x_tilde, std::span<const double> x_hat,
                                 std::span<const double> weights) override;
  void window_converged() override;
  [[nodiscard]] int history_columns() const override { return static_cast<int>(columns_.size()); }
  /// numbers: the window count, then each column's window; vectors: V_i, W_i of each column.
  [[nodiscard]] History history() const override;
  void restore_history(const History& history) override;

 private:
  struct Column {
    std::vector<double> residual_change;  ///< V_i
    std::vector<double> output_change;    ///< W_i
    long window = 0;
  };
  double initial_relaxation_;
  int reused_windows_;
  double filter_;
  MPI_Comm comm_;
  std::deque<Column> columns_;
  std::vector<double> previous_residual_;
  std::vector<double> previous_output_;
  bool has_previous_ = false;
  long window_ = 0;
};

}  // namespace tankfsi::coupling
