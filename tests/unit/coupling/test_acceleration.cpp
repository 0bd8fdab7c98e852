// The accelerations on a linear fixed-point problem x = H(x) = A x + b whose
// entries are spread over the ranks: IQN-ILS ends in at most n + 1 iterations
// (like GMRES, it spans the residual history), Aitken solves a scalar
// problem's two-point secant exactly, constant relaxation contracts by
// |1 - omega (1 - a)| per iteration.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "coupling/acceleration/acceleration.hpp"
#include "coupling/acceleration/iqn_ils.hpp"

using namespace tankfsi::coupling;

namespace {

// Diagonal A (each rank holds 3 entries) with eigenvalues far outside the unit
// disc: the plain fixed-point iteration diverges.
struct LinearProblem {
  std::vector<double> a, b;
  explicit LinearProblem(int rank) {
    for (int i = 0; i < 3; ++i) {
      a.push_back(-30.0 + 9.5 * (3 * rank + i));  // distinct, none equal to 1
      b.push_back(1.0 + rank + i);
    }
  }
  [[nodiscard]] std::vector<double> apply(const std::vector<double>& x) const {
    std::vector<double> y(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) y[i] = a[i] * x[i] + b[i];
    return y;
  }
  [[nodiscard]] double error(const std::vector<double>& x) const {
    double local = 0.0;
    for (std::size_t i = 0; i < x.size(); ++i) local = std::max(local, std::abs(x[i] - b[i] / (1.0 - a[i])));
    double global = 0.0;
    MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
    return global;
  }
};

int iterations_to_converge(Acceleration& method, const LinearProblem& problem, int limit) {
  std::vector<double> x(problem.a.size(), 0.0);
  for (int k = 1; k <= limit; ++k) {
    x = method.next_input(x, problem.apply(x), {});
    if (problem.error(x) < 1e-9) return k;
  }
  return limit + 1;
}

}  // namespace

TEST_CASE("IQN-ILS solves a linear problem of n unknowns in at most n + 1 iterations", "[coupling][acceleration]") {
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  const LinearProblem problem(rank);
  IqnIls iqn(0.1, 0, 1e-12, MPI_COMM_WORLD);
  const int n = 3 * size;
  CHECK(iterations_to_converge(iqn, problem, 50) <= n + 1);
}

TEST_CASE("IQN-ILS reuses the last windows' columns: the next window starts converged", "[coupling][acceleration]") {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  LinearProblem problem(rank);
  IqnIls iqn(0.1, 2, 1e-12, MPI_COMM_WORLD);
  iterations_to_converge(iqn, problem, 50);
  iqn.window_converged();
  CHECK(iqn.history_columns() > 0);
  // The same Jacobian, another right-hand side: one step from the old columns.
  for (double& value : problem.b) value *= 3.0;
  CHECK(iterations_to_converge(iqn, problem, 50) <= 2);
  // Without reuse the columns go with the window.
  IqnIls forgetful(0.1, 0, 1e-12, MPI_COMM_WORLD);
  iterations_to_converge(forgetful, problem, 50);
  forgetful.window_converged();
  CHECK(forgetful.history_columns() == 0);
}

TEST_CASE("Aitken relaxation: a linear scalar map converges after one secant step", "[coupling][acceleration]") {
  CouplingSettings settings;
  settings.acceleration = AccelerationType::aitken;
  settings.initial_relaxation = 0.1;
  // One unknown on rank 0 only (x = -50 x + 2, fixed point 2/51).
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  auto aitken = make_acceleration(settings, MPI_COMM_WORLD);
  std::vector<double> x(rank == 0 ? 1 : 0, 0.0);
  const auto h = [&](const std::vector<double>& v) {
    std::vector<double> y(v.size());
    for (std::size_t i = 0; i < v.size(); ++i) y[i] = -50.0 * v[i] + 2.0;
    return y;
  };
  x = aitken->next_input(x, h(x), {});  // relaxation 0.1
  x = aitken->next_input(x, h(x), {});  // secant: exact for a linear map
  if (rank == 0) CHECK(x[0] == Approx(2.0 / 51.0).epsilon(1e-12));
}

TEST_CASE("constant relaxation contracts by |1 - omega (1 - a)|", "[coupling][acceleration]") {
  CouplingSettings settings;
  settings.acceleration = AccelerationType::constant;
  settings.initial_relaxation = 0.5;
  auto constant = make_acceleration(settings, MPI_COMM_WORLD);
  // x = 0.5 x + 1: factor |1 - 0.5 * 0.5| = 0.75 per iteration.
  std::vector<double> x{0.0};
  const double fixed = 2.0;
  double previous_error = fixed;
  for (int k = 0; k < 5; ++k) {
    x = constant->next_input(x, std::vector<double>{0.5 * x[0] + 1.0}, {});
    const double error = std::abs(x[0] - fixed);
    CHECK(error == Approx(0.75 * previous_error));
    previous_error = error;
  }
}
