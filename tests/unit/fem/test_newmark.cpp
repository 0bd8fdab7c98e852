// Newmark average acceleration on a single DOF against the closed forms
// (VALIDATION.md, Newmark), and Rayleigh damping coefficients.
#include <petscksp.h>

#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "fem_solver/analysis/newmark.hpp"
#include "common/run/petsc_handle.hpp"

using namespace tankfsi;
using namespace tankfsi::fem;

namespace {

constexpr double pi = std::numbers::pi;

/// LU on one process: what a 1x1 system needs.
class SerialSolve final : public LinearSolve {
 public:
  explicit SerialSolve(Mat m) {
    petsc_check(KSPCreate(PETSC_COMM_SELF, ksp_.out()), "KSPCreate");
    petsc_check(KSPSetOperators(ksp_.get(), m, m), "KSPSetOperators");
    petsc_check(KSPSetType(ksp_.get(), KSPPREONLY), "KSPSetType");
    PC pc = nullptr;
    petsc_check(KSPGetPC(ksp_.get(), &pc), "KSPGetPC");
    petsc_check(PCSetType(pc, PCLU), "PCSetType");
    petsc_check(KSPSetUp(ksp_.get()), "KSPSetUp");
  }
  void solve(Vec rhs, Vec solution) const override { petsc_check(KSPSolve(ksp_.get(), rhs, solution), "KSPSolve"); }

 private:
  PetscSolver ksp_;
};

/// m u'' + k u = f(t) on PETSC_COMM_SELF.
struct SingleDof {
  PetscMatrix k;
  PetscVector m, u, v, f;

  SingleDof(double mass, double stiffness) {
    petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 1, 1, 1, nullptr, k.out()), "MatCreateSeqAIJ");
    petsc_check(MatSetValue(k.get(), 0, 0, stiffness, INSERT_VALUES), "MatSetValue");
    petsc_check(MatAssemblyBegin(k.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(k.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
    for (PetscVector* x : {&m, &u, &v, &f}) petsc_check(VecCreateSeq(PETSC_COMM_SELF, 1, x->out()), "VecCreateSeq");
    petsc_check(VecSet(m.get(), mass), "VecSet");
    for (PetscVector* x : {&u, &v, &f}) petsc_check(VecSet(x->get(), 0.0), "VecSet");
  }
  NewmarkIntegrator integrator(RayleighCoefficients damping = {}) const {
    return NewmarkIntegrator(k.get(), m.get(), damping, [](Mat a) { return std::make_unique<SerialSolve>(a); });
  }
};

double value(Vec x) {
  const PetscScalar* a = nullptr;
  VecGetArrayRead(x, &a);
  const double out = a[0];
  VecRestoreArrayRead(x, &a);
  return out;
}

}  // namespace

TEST_CASE("Newmark free vibration: period within 0.1 % at 100 steps per period, energy conserved", "[fem][newmark]") {
  // omega = 2 pi (T = 1 s). The average-acceleration rule elongates the period
  // by (omega dt)^2/12 = 3.3e-4 at dt = T/100 (omega_h dt = 2 atan(omega dt/2)):
  // the 0.1 % bound of
  // VALIDATION.md holds with margin, and a wrong gamma/beta (e.g. Fox-Goodwin
  // or a damped rule) would show in the energy check.
  const double mass = 2.0, omega = 2.0 * pi, period = 1.0;
  SingleDof dof(mass, mass * omega * omega);
  VecSet(dof.u.get(), 1.0);
  NewmarkIntegrator newmark = dof.integrator();
  newmark.initialise(dof.u.get(), dof.v.get(), dof.f.get());
  const double energy_0 = newmark.energy();
  const double dt = period / 100.0;
  std::vector<double> upward_crossings;
  double previous = 1.0;
  for (int n = 1; n <= 2000; ++n) {
    newmark.step(dt, dof.f.get());
    const double now = value(newmark.displacement());
    if (previous < 0.0 && now >= 0.0) upward_crossings.push_back((n - 1 + previous / (previous - now)) * dt);
    previous = now;
    // Undamped, unloaded: the rule conserves 1/2 m v^2 + 1/2 k u^2 exactly
    // (round-off only, 1e-12 relative over 20 periods).
    REQUIRE(newmark.energy() == Approx(energy_0).epsilon(1e-12));
  }
  REQUIRE(upward_crossings.size() >= 19);
  const double measured = (upward_crossings.back() - upward_crossings.front()) / (upward_crossings.size() - 1);
  CHECK(std::abs(measured / period - 1.0) < 1e-3);
  const double omega_dt = omega * dt;
  CHECK(measured / period - 1.0 == Approx(0.5 * omega_dt / std::atan(0.5 * omega_dt) - 1.0).epsilon(0.02));
  CHECK(newmark.factorisations() == 1);
}

TEST_CASE("Newmark forced vibration follows the closed form", "[fem][newmark]") {
  // u'' + w^2 u = (F/m) sin(W t) from rest: u = F/k / (1 - r^2) (sin W t - r sin w t),
  // r = W / w = 0.6. At 100 steps per natural period the phase error of the
  // free part grows by ~2 pi 8e-5 per period: below 0.3 % of the response's
  // amplitude over 3 periods; 0.5 % is the bound.
  const double mass = 1.0, omega = 2.0 * pi, ratio = 0.6, force = 3.0;
  const double stiffness = mass * omega * omega;
  SingleDof dof(mass, stiffness);
  NewmarkIntegrator newmark = dof.integrator();
  newmark.initialise(dof.u.get(), dof.v.get(), dof.f.get());
  const double dt = 0.01;
  const double amplitude = force / stiffness / (1.0 - ratio * ratio) * (1.0 + ratio);
  double worst = 0.0;
  for (int n = 1; n <= 300; ++n) {
    const double t = n * dt;
    VecSet(dof.f.get(), force * std::sin(ratio * omega * t));
    newmark.step(dt, dof.f.get());
    const double exact = force / stiffness / (1.0 - ratio * ratio) * (std::sin(ratio * omega * t) - ratio * std::sin(omega * t));
    worst = std::max(worst, std::abs(value(newmark.displacement()) - exact));
  }
  CHECK(worst < 5e-3 * amplitude);
}

TEST_CASE("Newmark with Rayleigh damping decays at the target ratio", "[fem][newmark]") {
  // One DOF with zeta = 0.05 from alpha and beta: successive peaks fall by
  // exp(-2 pi zeta / sqrt(1 - zeta^2)); at 100 steps per period the rule's
  // own error in the decrement is ~1e-4, bound 1 %.
  const double omega = 2.0 * pi, zeta = 0.05;
  SingleDof dof(1.0, omega * omega);
  VecSet(dof.u.get(), 1.0);
  const RayleighCoefficients damping = rayleigh_from_modes(omega, zeta, 3.0 * omega, zeta);
  NewmarkIntegrator newmark = dof.integrator(damping);
  newmark.initialise(dof.u.get(), dof.v.get(), dof.f.get());
  std::vector<double> peaks;
  double before = 1.0, previous = 1.0;
  for (int n = 1; n <= 400; ++n) {
    newmark.step(0.01, dof.f.get());
    const double now = value(newmark.displacement());
    if (previous > before && previous >= now && n > 1) peaks.push_back(previous);
    before = previous;
    previous = now;
  }
  REQUIRE(peaks.size() >= 3);
  const double expected = std::exp(-2.0 * pi * zeta / std::sqrt(1.0 - zeta * zeta));
  CHECK(peaks[1] / peaks[0] == Approx(expected).epsilon(0.01));
}

TEST_CASE("Rayleigh alpha and beta reproduce the two target ratios", "[fem][newmark]") {
  const double w1 = 26.2, w2 = 71.4;
  const RayleighCoefficients c = rayleigh_from_modes(w1, 0.03, w2, 0.05);
  CHECK(c.ratio_at(w1) == Approx(0.03).epsilon(1e-12));
  CHECK(c.ratio_at(w2) == Approx(0.05).epsilon(1e-12));
  // Equal ratios: between the targets the ratio dips below them (the Rayleigh
  // curve's minimum is at sqrt(w1 w2)) and rises beyond them.
  const RayleighCoefficients equal = rayleigh_from_modes(w1, 0.03, w2, 0.03);
  CHECK(equal.ratio_at(std::sqrt(w1 * w2)) < 0.03);
  CHECK(equal.ratio_at(2.0 * w2) > 0.03);
  CHECK_THROWS_AS(rayleigh_from_modes(w1, 0.03, w1, 0.03), std::invalid_argument);
}

/// Two DOFs coupled by K, a full (non-diagonal) added mass M_a and Rayleigh
/// damping C = alpha M + beta K on the structure's own M, from a displaced,
/// moving, loaded start: the PETSc system and its dense (Eigen) twin.
struct TwoDofWithAddedMass {
  Eigen::Matrix2d stiffness{{300.0, -100.0}, {-100.0, 200.0}};
  Eigen::Matrix2d added{{4.0, 1.5}, {1.5, 3.0}};  // symmetric positive definite, coupling the DOFs
  Eigen::Vector2d mass{1.0, 2.0};
  RayleighCoefficients damping{0.4, 0.002};
  Eigen::Vector2d u0{0.01, -0.02}, v0{0.3, 0.1}, f0{0.2, -0.1};
  PetscMatrix k, m_a;
  PetscVector m, u, v, f;

  TwoDofWithAddedMass() {
    for (PetscMatrix* a : {&k, &m_a})
      petsc_check(MatCreateSeqAIJ(PETSC_COMM_SELF, 2, 2, 2, nullptr, a->out()), "MatCreateSeqAIJ");
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j) {
        MatSetValue(k.get(), i, j, stiffness(i, j), INSERT_VALUES);
        MatSetValue(m_a.get(), i, j, added(i, j), INSERT_VALUES);
      }
    for (PetscMatrix* a : {&k, &m_a}) {
      MatAssemblyBegin(a->get(), MAT_FINAL_ASSEMBLY);
      MatAssemblyEnd(a->get(), MAT_FINAL_ASSEMBLY);
    }
    for (PetscVector* x : {&m, &u, &v, &f}) petsc_check(VecCreateSeq(PETSC_COMM_SELF, 2, x->out()), "VecCreateSeq");
    set(m, mass);
    set(u, u0);
    set(v, v0);
    set(f, f0);
  }
  static void set(PetscVector& x, const Eigen::Vector2d& values) {
    const PetscInt index[2] = {0, 1};
    VecSetValues(x.get(), 2, index, values.data(), INSERT_VALUES);
  }
  /// The integrator with M_a, initialised at (u0, v0) under f0.
  NewmarkIntegrator integrator(TimeIntegrationRule rule) {
    NewmarkIntegrator newmark(
        k.get(), m.get(), damping, [](Mat a) { return std::make_unique<SerialSolve>(a); }, rule);
    newmark.set_added_mass(m_a.get());
    newmark.initialise(u.get(), v.get(), f.get());
    return newmark;
  }
  /// Advances `newmark` by dt to the load `load`.
  void step(NewmarkIntegrator& newmark, double dt, const Eigen::Vector2d& load) {
    set(f, load);
    newmark.step(dt, f.get());
  }
  [[nodiscard]] Eigen::Matrix2d inertia() const { return Eigen::Matrix2d(mass.asDiagonal()) + added; }
  [[nodiscard]] Eigen::Matrix2d c() const {
    return damping.alpha * Eigen::Matrix2d(mass.asDiagonal()) + damping.beta * stiffness;
  }
  [[nodiscard]] static Eigen::Vector2d values(Vec x) {
    const PetscScalar* entries = nullptr;
    VecGetArrayRead(x, &entries);
    const Eigen::Vector2d out(entries[0], entries[1]);
    VecRestoreArrayRead(x, &entries);
    return out;
  }
  [[nodiscard]] static Eigen::Vector2d displacement(const NewmarkIntegrator& newmark) {
    return values(newmark.displacement());
  }
};

/// Chung & Hulbert (1993) in acceleration form for the two DOFs, solved for
/// a' with Eigen (average acceleration for rho_inf = 1):
///   (1-am)(M+M_a) a' + am (M+M_a) a + C ((1-af) v' + af v) + K ((1-af) u' + af u) = (1-af) F' + af F,
///   u' = u + dt v + dt^2 ((1/2 - beta) a + beta a'),  v' = v + dt ((1 - gamma) a + gamma a').
struct DenseGeneralizedAlpha {
  Eigen::Matrix2d inertia, c, stiffness;
  TimeIntegrationRule rule;
  Eigen::Vector2d u, v, a, f;
  DenseGeneralizedAlpha(const TwoDofWithAddedMass& system, TimeIntegrationRule r)
      : inertia(system.inertia()), c(system.c()), stiffness(system.stiffness), rule(r), u(system.u0), v(system.v0) {
    set_load(system.f0);
  }
  /// A new load at the same instant: (M + M_a) a = F - K u - C v.
  void set_load(const Eigen::Vector2d& load) {
    f = load;
    a = inertia.ldlt().solve(f - stiffness * u - c * v);
  }
  void step(double dt, const Eigen::Vector2d& load) {
    const double am = rule.alpha_m, af = rule.alpha_f, g = rule.gamma, b = rule.beta;
    const Eigen::Vector2d u_known = u + dt * v + dt * dt * (0.5 - b) * a;  // u' = u_known + dt^2 beta a'
    const Eigen::Vector2d v_known = v + dt * (1.0 - g) * a;                // v' = v_known + dt gamma a'
    const Eigen::Matrix2d effective = (1.0 - am) * inertia + (1.0 - af) * (g * dt * c + b * dt * dt * stiffness);
    const Eigen::Vector2d a_new =
        effective.ldlt().solve((1.0 - af) * load + af * f - am * inertia * a - c * ((1.0 - af) * v_known + af * v) -
                               stiffness * ((1.0 - af) * u_known + af * u));
    u = u_known + dt * dt * b * a_new;
    v = v_known + dt * g * a_new;
    a = a_new;
    f = load;
  }
};

/// Steps the integrator and its dense twin 400 times of 5 ms under the same
/// changing load, `before_step(n, load)` first at each step; returns the
/// largest difference of their displacements over the largest displacement.
template <class BeforeStep>
double step_beside_dense(TwoDofWithAddedMass& system, NewmarkIntegrator& newmark, DenseGeneralizedAlpha& dense,
                         BeforeStep before_step) {
  const double dt = 0.005;
  double largest = 0.0, worst = 0.0;
  for (int n = 1; n <= 400; ++n) {
    const Eigen::Vector2d load(std::sin(7.0 * n * dt), 0.5 * std::cos(3.0 * n * dt));
    before_step(n, load);
    system.step(newmark, dt, load);
    dense.step(dt, load);
    worst = std::max(worst, (TwoDofWithAddedMass::displacement(newmark) - dense.u).cwiseAbs().maxCoeff());
    largest = std::max(largest, dense.u.cwiseAbs().maxCoeff());
  }
  return worst / largest;
}

TEST_CASE("Newmark with an added mass: the inertia of M + M_a, the damping of M alone", "[fem][newmark][added_mass]") {
  // Each step against the same average-acceleration rule written out densely
  // (Eigen), taken from the integrator's own state (u, v, a) under a changing
  // load: both solve the same equations, so only one step's round-off separates
  // them (measured 1.5e-15 of the motion; from a common start the 400 steps'
  // round-off accumulates instead, to 1.1e-12 with one CPU's OpenBLAS). The
  // damping taken on M + M_a instead of M shows at 1e-5 per step.
  TwoDofWithAddedMass system;
  NewmarkIntegrator newmark = system.integrator(TimeIntegrationRule::average_acceleration());
  const Eigen::Matrix2d inertia = system.inertia(), c = system.c(), stiffness = system.stiffness;
  const double dt = 0.005;
  const Eigen::Matrix2d effective = inertia + 0.5 * dt * c + 0.25 * dt * dt * stiffness;
  // The initial acceleration: (M + M_a) a0 = F0 - K u0 - C v0.
  CHECK((TwoDofWithAddedMass::values(newmark.acceleration()) -
         inertia.ldlt().solve(system.f0 - stiffness * system.u0 - c * system.v0))
            .cwiseAbs()
            .maxCoeff() < 1e-12);
  double largest = 0.0, worst = 0.0;
  for (int n = 1; n <= 400; ++n) {
    const Eigen::Vector2d u = TwoDofWithAddedMass::values(newmark.displacement());
    const Eigen::Vector2d v = TwoDofWithAddedMass::values(newmark.velocity());
    const Eigen::Vector2d a = TwoDofWithAddedMass::values(newmark.acceleration());
    const Eigen::Vector2d load(std::sin(7.0 * n * dt), 0.5 * std::cos(3.0 * n * dt));
    system.step(newmark, dt, load);
    // (M + M_a) a' + C v' + K u' = F with u' = u + dt v + dt^2/4 (a + a'), v' = v + dt/2 (a + a')
    const Eigen::Vector2d a_new =
        effective.ldlt().solve(load - c * (v + 0.5 * dt * a) - stiffness * (u + dt * v + 0.25 * dt * dt * a));
    const Eigen::Vector2d u_new = u + dt * v + 0.25 * dt * dt * (a + a_new);
    worst = std::max(worst, (TwoDofWithAddedMass::displacement(newmark) - u_new).cwiseAbs().maxCoeff());
    largest = std::max(largest, u_new.cwiseAbs().maxCoeff());
  }
  CHECK(worst < 1e-12 * largest);
}

TEST_CASE("Generalized alpha against its equations written out densely", "[fem][newmark][generalized_alpha]") {
  // Chung & Hulbert in acceleration form (DenseGeneralizedAlpha) against the
  // integrator's displacement form with its carried K products, an added mass
  // and Rayleigh damping: the same equations, so only round-off (1e-11 of the
  // motion) separates them. rho_inf = 0.6 exercises every weight.
  const TimeIntegrationRule rule = TimeIntegrationRule::generalized_alpha(0.6);
  REQUIRE(rule.alpha_m == Approx(0.2 / 1.6));
  REQUIRE(rule.alpha_f == Approx(0.6 / 1.6));
  TwoDofWithAddedMass system;
  NewmarkIntegrator newmark = system.integrator(rule);
  DenseGeneralizedAlpha dense(system, rule);
  CHECK(step_beside_dense(system, newmark, dense, [](int, const Eigen::Vector2d&) {}) < 1e-11);
}

TEST_CASE("Newmark: a new load at the same instant sets the acceleration, u and v kept", "[fem][newmark][added_mass]") {
  // A coupling window's load jumps at its start (set_load). The acceleration
  // then follows from (M + M_a) a = F - K u - C v with K u and K v as carried
  // along, and the next steps go on from it: against the dense twin given the
  // same jump, to the round-off of the 200 steps before it. Generalized alpha
  // uses the carried K a (a stale one shows at 1e-6 of the motion), average
  // acceleration with beta_R = 0 carries no products (initialise() instead).
  for (const bool carried : {true, false}) {
    DYNAMIC_SECTION((carried ? "generalized alpha, Rayleigh beta" : "average acceleration, no beta")) {
      TwoDofWithAddedMass system;
      if (!carried) system.damping.beta = 0.0;
      const TimeIntegrationRule rule =
          carried ? TimeIntegrationRule::generalized_alpha(0.6) : TimeIntegrationRule::average_acceleration();
      NewmarkIntegrator newmark = system.integrator(rule);
      DenseGeneralizedAlpha dense(system, rule);
      const auto jump_at_step_200 = [&](int n, const Eigen::Vector2d& load) {
        if (n != 200) return;
        const Eigen::Vector2d u = TwoDofWithAddedMass::values(newmark.displacement());
        const Eigen::Vector2d v = TwoDofWithAddedMass::values(newmark.velocity());
        const Eigen::Vector2d jump = load + Eigen::Vector2d(3.0, -2.0);
        TwoDofWithAddedMass::set(system.f, jump);
        newmark.set_load(system.f.get());
        dense.set_load(jump);
        CHECK((TwoDofWithAddedMass::values(newmark.displacement()) - u).cwiseAbs().maxCoeff() == 0.0);
        CHECK((TwoDofWithAddedMass::values(newmark.velocity()) - v).cwiseAbs().maxCoeff() == 0.0);
        CHECK((TwoDofWithAddedMass::values(newmark.acceleration()) - dense.a).cwiseAbs().maxCoeff() <
              1e-10 * dense.a.cwiseAbs().maxCoeff());
      };
      CHECK(step_beside_dense(system, newmark, dense, jump_at_step_200) < 1e-11);
    }
  }
}

TEST_CASE("Generalized alpha: unresolved modes lose (1 - rho_inf) per step, resolved ones keep second order",
          "[fem][newmark][generalized_alpha]") {
  // rho_inf = 1 is the average-acceleration rule itself.
  const TimeIntegrationRule one = TimeIntegrationRule::generalized_alpha(1.0);
  CHECK(one.alpha_m == 0.0);
  CHECK(one.alpha_f == 0.0);
  CHECK(one.gamma == 0.5);
  CHECK(one.beta == 0.25);
  CHECK_THROWS_AS(TimeIntegrationRule::generalized_alpha(1.5), std::invalid_argument);
  CHECK_THROWS_AS(TimeIntegrationRule::generalized_alpha(-0.1), std::invalid_argument);

  // A mode of period 1e-4 steps (omega dt = 6e4): the three roots of its
  // amplification matrix all tend to -rho_inf (Chung & Hulbert's optimum: a
  // triple root, so |u_n| ~ n^2 rho^n); the per-step ratio over steps 40..80
  // is rho_inf (80/40)^(2/40) = 1.035 rho_inf.
  for (const double rho : {0.0, 0.5, 0.8}) {
    SingleDof dof(1.0, 1.0);
    VecSet(dof.u.get(), 1.0);
    NewmarkIntegrator newmark(
        dof.k.get(), dof.m.get(), {}, [](Mat a) { return std::make_unique<SerialSolve>(a); },
        TimeIntegrationRule::generalized_alpha(rho));
    newmark.initialise(dof.u.get(), dof.v.get(), dof.f.get());
    const double dt = 2.0 * pi * 1e4;
    double at_40 = 0.0, at_80 = 0.0;
    for (int n = 1; n <= 80; ++n) {
      newmark.step(dt, dof.f.get());
      if (n == 40) at_40 = std::abs(value(newmark.displacement()));
      if (n == 80) at_80 = std::abs(value(newmark.displacement()));
    }
    INFO("rho_inf " << rho);
    if (rho == 0.0) {
      CHECK(at_80 < 1e-12);  // annihilated within a step or two
    } else {
      CHECK(std::pow(at_80 / at_40, 1.0 / 40.0) == Approx(rho * std::pow(2.0, 2.0 / 40.0)).epsilon(0.01));
    }
  }

  // A resolved mode (T = 1 s): second order, so the period error falls fourfold
  // when the step halves (measured 3.9-4.0 at 25 and 50 steps per period), and
  // at 100 steps per period the period is within VALIDATION.md's 0.1 %.
  auto period_error = [](double steps_per_period) {
    const double omega = 2.0 * pi;
    SingleDof dof(1.0, omega * omega);
    VecSet(dof.u.get(), 1.0);
    NewmarkIntegrator newmark(
        dof.k.get(), dof.m.get(), {}, [](Mat a) { return std::make_unique<SerialSolve>(a); },
        TimeIntegrationRule::generalized_alpha(0.8));
    newmark.initialise(dof.u.get(), dof.v.get(), dof.f.get());
    const double dt = 1.0 / steps_per_period;
    std::vector<double> crossings;
    double previous = 1.0;
    for (int n = 1; n <= static_cast<int>(10 * steps_per_period); ++n) {
      newmark.step(dt, dof.f.get());
      const double now = value(newmark.displacement());
      if (previous < 0.0 && now >= 0.0) crossings.push_back((n - 1 + previous / (previous - now)) * dt);
      previous = now;
    }
    return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1) - 1.0;
  };
  const double coarse = period_error(25.0), fine = period_error(50.0);
  CHECK(coarse / fine == Approx(4.0).epsilon(0.05));
  CHECK(std::abs(period_error(100.0)) < 1e-3);
}
