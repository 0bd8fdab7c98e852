#pragma once
// TransientIntegrator: what StructureSolver steps in time, M a + C v +
// f(u) = F(t): NewmarkIntegrator (newmark.hpp) for the linear shell, f = K u,
// and CorotationalNewmark (corotational_newmark.hpp) for large rotations.
// Both use the same rule (Newmark / generalized alpha) and the same state.
#include <memory>

#include "fem_solver/analysis/rayleigh_damping.hpp"
#include "fem_solver/assembly/linear_solve.hpp"
#include "common/run/petsc_handle.hpp"

namespace tankfsi::fem {

/// Newmark's gamma and beta and the generalized-alpha weights alpha_m,
/// alpha_f of the step (newmark.hpp).
struct TimeIntegrationRule {
  double gamma = 0.5;
  double beta = 0.25;
  double alpha_m = 0.0;
  double alpha_f = 0.0;

  /// gamma = 1/2, beta = 1/4, alpha_m = alpha_f = 0: no numerical damping.
  static TimeIntegrationRule average_acceleration() { return {}; }
  /// Chung & Hulbert's optimal parameters for a spectral radius rho_inf in
  /// [0, 1] at infinite frequency: alpha_m = (2 rho - 1)/(rho + 1), alpha_f =
  /// rho/(rho + 1), gamma = 1/2 - alpha_m + alpha_f, beta = (1 - alpha_m +
  /// alpha_f)^2 / 4. rho_inf = 1 is the average-acceleration rule itself
  /// (returned as such: the same steps bit for bit). Throws
  /// std::invalid_argument outside [0, 1].
  static TimeIntegrationRule generalized_alpha(double spectral_radius);

  /// Newmark's step coefficients for a step dt: a_{n+1} = a0 (u_{n+1} - u_n)
  /// - a2 v_n - a3 a_n, and a1 = gamma/(beta dt), a4 = gamma/beta - 1,
  /// a5 = dt/2 (gamma/beta - 2) of the velocity's update written the same way.
  struct StepCoefficients {
    double a0, a1, a2, a3, a4, a5;
  };
  [[nodiscard]] StepCoefficients step_coefficients(double dt) const {
    return {1.0 / (beta * dt * dt), gamma / (beta * dt), 1.0 / (beta * dt), 1.0 / (2.0 * beta) - 1.0,
            gamma / beta - 1.0, dt / 2.0 * (gamma / beta - 2.0)};
  }
};

/// A copy of the integrator's state: what an implicit coupling window rolls
/// back to and a checkpoint holds. u, v, a; ku, kv, ka the linear
/// integrator's K products (the co-rotational one keeps its internal force
/// at the state's time in ku, kv and ka zero); f the load at the state's time.
struct NewmarkState {
  PetscVector u, v, a, ku, kv, ka, f;
};

class TransientIntegrator {
 public:
  virtual ~TransientIntegrator() = default;

  /// Sets the state at the current time; the acceleration follows from the
  /// equation of motion with the load `load`.
  virtual void initialise(Vec displacement, Vec velocity, Vec load) = 0;
  /// The same for a new load at the current time, u and v kept.
  virtual void set_load(Vec load) = 0;
  /// Adds a coupled liquid's added mass M_a to the inertia (newmark.hpp).
  virtual void set_added_mass(Mat added_mass, Mat product = nullptr, std::unique_ptr<LinearSolve> inertia = nullptr) = 0;
  /// Prepares steps of dt (the linear integrator factorises K_eff).
  virtual void prepare(double dt) = 0;
  /// Advances by dt to the load `load` at the end of the step; throws
  /// std::runtime_error, the state left at the last good step, when it fails.
  virtual void step(double dt, Vec load) = 0;

  [[nodiscard]] virtual Vec displacement() const = 0;
  [[nodiscard]] virtual Vec velocity() const = 0;
  [[nodiscard]] virtual Vec acceleration() const = 0;
  virtual void save(NewmarkState& state) const = 0;
  virtual void restore(const NewmarkState& state) = 0;
  /// Kinetic plus strain energy (J).
  [[nodiscard]] virtual double energy() const = 0;
  [[nodiscard]] virtual const RayleighCoefficients& damping() const = 0;
  [[nodiscard]] virtual const TimeIntegrationRule& rule() const = 0;
  /// Factorisations of an effective matrix so far.
  [[nodiscard]] virtual int factorisations() const = 0;
};

}  // namespace tankfsi::fem
