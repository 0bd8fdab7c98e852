// Constant under-relaxation and Aitken's dynamic relaxation.
#include <cmath>
#include <stdexcept>

#include "coupling/acceleration/acceleration.hpp"
#include "coupling/acceleration/iqn_ils.hpp"

namespace tankfsi::coupling {

double weighted_dot(MPI_Comm comm, std::span<const double> a, std::span<const double> b, std::span<const double> w) {
  double local = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double wi = w.empty() ? 1.0 : w[i];
    local += wi * wi * a[i] * b[i];
  }
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

namespace {

std::vector<double> relaxed(std::span<const double> x_tilde, std::span<const double> x_hat, double omega) {
  std::vector<double> next(x_tilde.size());
  for (std::size_t i = 0; i < next.size(); ++i) next[i] = x_tilde[i] + omega * (x_hat[i] - x_tilde[i]);
  return next;
}

class ConstantRelaxation final : public Acceleration {
 public:
  explicit ConstantRelaxation(double omega) : omega_(omega) {}
  std::vector<double> next_input(std::span<const double> x_tilde, std::span<const double> x_hat,
                                 std::span<const double>) override {
    return relaxed(x_tilde, x_hat, omega_);
  }
  void window_converged() override {}

 private:
  double omega_;
};

// omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2; the first
// iteration of a window starts from the initial factor, with the sign and at
// most the size of the last window's final factor (as preCICE does).
class AitkenRelaxation final : public Acceleration {
 public:
  AitkenRelaxation(double initial, MPI_Comm comm) : initial_(initial), omega_(initial), comm_(comm) {}

  std::vector<double> next_input(std::span<const double> x_tilde, std::span<const double> x_hat,
                                 std::span<const double> weights) override {
    std::vector<double> residual(x_tilde.size());
    for (std::size_t i = 0; i < residual.size(); ++i) residual[i] = x_hat[i] - x_tilde[i];
    // A rank may hold no values: the flag, not the vector's size, says whether
    // this is the window's first iteration, so every rank takes one branch.
    if (!has_previous_) {
      omega_ = std::copysign(std::min(initial_, std::abs(omega_)), omega_);
    } else {
      std::vector<double> change(residual.size());
      for (std::size_t i = 0; i < change.size(); ++i) change[i] = residual[i] - previous_residual_[i];
      const double denominator = weighted_dot(comm_, change, change, weights);
      if (denominator > 0) omega_ = -omega_ * weighted_dot(comm_, previous_residual_, change, weights) / denominator;
    }
    previous_residual_ = std::move(residual);
    has_previous_ = true;
    return relaxed(x_tilde, x_hat, omega_);
  }
  void window_converged() override { has_previous_ = false; }
  [[nodiscard]] History history() const override { return {{omega_}, {}}; }
  void restore_history(const History& history) override {
    if (history.numbers.size() != 1) throw std::invalid_argument("AitkenRelaxation::restore_history: one number expected");
    omega_ = history.numbers[0];
    has_previous_ = false;
  }

 private:
  double initial_;
  double omega_;
  MPI_Comm comm_;
  std::vector<double> previous_residual_;
  bool has_previous_ = false;
};

}  // namespace

std::unique_ptr<Acceleration> make_acceleration(const CouplingSettings& settings, MPI_Comm comm) {
  switch (settings.acceleration) {
    case AccelerationType::constant: return std::make_unique<ConstantRelaxation>(settings.initial_relaxation);
    case AccelerationType::aitken: return std::make_unique<AitkenRelaxation>(settings.initial_relaxation, comm);
    case AccelerationType::iqn_ils:
      return std::make_unique<IqnIls>(settings.initial_relaxation, settings.reused_windows, settings.filter_tolerance,
                                      comm);
  }
  return nullptr;
}

}  // namespace tankfsi::coupling
