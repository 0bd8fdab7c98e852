#include "coupling/acceleration/iqn_ils.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tankfsi::coupling {

namespace {

// Local parts of Q^T v for the columns of Q, reduced over comm in one call.
std::vector<double> project(MPI_Comm comm, const std::vector<std::vector<double>>& q, const std::vector<double>& v) {
  std::vector<double> local(q.size(), 0.0);
  for (std::size_t i = 0; i < q.size(); ++i)
    for (std::size_t k = 0; k < v.size(); ++k) local[i] += q[i][k] * v[k];
  std::vector<double> global(q.size(), 0.0);
  if (!q.empty()) MPI_Allreduce(local.data(), global.data(), static_cast<int>(q.size()), MPI_DOUBLE, MPI_SUM, comm);
  return global;
}

}  // namespace

std::vector<double> IqnIls::next_input(std::span<const double> x_tilde, std::span<const double> x_hat,
                                       std::span<const double> weights) {
  const std::size_t n = x_tilde.size();
  std::vector<double> residual(n);
  for (std::size_t i = 0; i < n; ++i) residual[i] = x_hat[i] - x_tilde[i];
  // The flag, not the size, marks a later iteration: a rank may hold no values.
  if (has_previous_) {
    Column column{std::vector<double>(n), std::vector<double>(n), window_};
    for (std::size_t i = 0; i < n; ++i) {
      column.residual_change[i] = residual[i] - previous_residual_[i];
      column.output_change[i] = x_hat[i] - previous_output_[i];
    }
    columns_.push_front(std::move(column));
  }
  previous_residual_ = residual;
  previous_output_.assign(x_hat.begin(), x_hat.end());
  has_previous_ = true;

  const auto weight = [&](std::size_t i) { return weights.empty() ? 1.0 : weights[i]; };

  // QR of the weighted V, newest column first; filtered columns are erased.
  std::vector<std::vector<double>> q;
  std::vector<std::vector<double>> r;  // r[j]: column j of R (entries 0..j)
  for (auto it = columns_.begin(); it != columns_.end();) {
    std::vector<double> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = weight(i) * it->residual_change[i];
    const double original = std::sqrt(weighted_dot(comm_, v, v, {}));
    std::vector<double> coefficients(q.size(), 0.0);
    for (int pass = 0; pass < 2; ++pass) {
      const std::vector<double> h = project(comm_, q, v);
      for (std::size_t j = 0; j < q.size(); ++j) {
        coefficients[j] += h[j];
        for (std::size_t i = 0; i < n; ++i) v[i] -= h[j] * q[j][i];
      }
    }
    const double remaining = std::sqrt(weighted_dot(comm_, v, v, {}));
    if (!(original > 0) || remaining < filter_ * original) {
      it = columns_.erase(it);
      continue;
    }
    for (double& value : v) value /= remaining;
    q.push_back(std::move(v));
    coefficients.push_back(remaining);
    r.push_back(std::move(coefficients));
    ++it;
  }

  std::vector<double> next(x_hat.begin(), x_hat.end());
  if (q.empty()) {
    for (std::size_t i = 0; i < n; ++i) next[i] = x_tilde[i] + initial_relaxation_ * residual[i];
    return next;
  }
  // R c = -Q^T (w r), back substitution.
  std::vector<double> weighted_residual(n);
  for (std::size_t i = 0; i < n; ++i) weighted_residual[i] = weight(i) * residual[i];
  std::vector<double> c = project(comm_, q, weighted_residual);
  for (double& value : c) value = -value;
  for (std::size_t j = c.size(); j-- > 0;) {
    for (std::size_t k = j + 1; k < c.size(); ++k) c[j] -= r[k][j] * c[k];
    c[j] /= r[j][j];
  }
  std::size_t j = 0;
  for (const auto& column : columns_) {
    for (std::size_t i = 0; i < n; ++i) next[i] += c[j] * column.output_change[i];
    ++j;
  }
  return next;
}

void IqnIls::window_converged() {
  ++window_;
  has_previous_ = false;
  while (!columns_.empty() && window_ - columns_.back().window > reused_windows_) columns_.pop_back();
}

Acceleration::History IqnIls::history() const {
  History h;
  h.numbers.push_back(static_cast<double>(window_));
  for (const auto& column : columns_) {
    h.numbers.push_back(static_cast<double>(column.window));
    h.vectors.push_back(column.residual_change);
    h.vectors.push_back(column.output_change);
  }
  return h;
}

void IqnIls::restore_history(const History& history) {
  if (history.numbers.empty() || history.vectors.size() != 2 * (history.numbers.size() - 1))
    throw std::invalid_argument("IqnIls::restore_history: " + std::to_string(history.numbers.size()) + " numbers and " +
                                std::to_string(history.vectors.size()) + " vectors do not make a history");
  window_ = static_cast<long>(history.numbers[0]);
  columns_.clear();
  for (std::size_t k = 1; k < history.numbers.size(); ++k)
    columns_.push_back(Column{history.vectors[2 * (k - 1)], history.vectors[2 * (k - 1) + 1],
                              static_cast<long>(history.numbers[k])});
  has_previous_ = false;
}

}  // namespace tankfsi::coupling
