#pragma once
// CorotationalNewmark: the Newmark / generalized-alpha step of
// newmark.hpp for a shell under large rotations, M a + C v + f(u) = F(t),
// f the co-rotational internal force (corotational_forces.hpp), solved by
// Newton's method within each step:
//
//   unknown: the step's increment D (translations; spins in global axes),
//   u_{n+1} = u_n composed with D, a_{n+1} = a0 D - a2 v_n - a3 a_n,
//   v_{n+1} = v_n + dt ((1 - gamma) a_n + gamma a_{n+1});
//   residual r = F_{n+1-af} - M a_{n+1-am} - alpha M v_{n+1-af} - g_{n+1-af},
//   g = f + beta_R K_t v (stiffness damping on the deformational velocity),
//   x_{n+1-a} = (1 - a) x_{n+1} + a x_n as in newmark.hpp;
//   Newton: [(1 - af)(1 + a1 beta_R) K_t + ((1 - am) a0 + (1 - af) a1 alpha) M] dD = r,
//
// until |r| <= 1e-8 of the largest of the load, internal-force and inertia
// terms, or below the rounding of the elements' forces (force_resolution),
// K_t the material tangent: with the inertia's a0 M beside it, a few
// iterations a step. A static equilibrium (equilibrate) takes the full
// tangent with its geometric stiffness (corotational_element.hpp). Rotations: Newmark's
// updates act on the spins (the rotary inertia is isotropic, rho t^3/12 per
// axis, so it has no gyroscopic term) and R_{n+1} = exp([D]x) R_n; exact for
// rotations about a fixed axis (a plane-strain strip), second-order
// accurate otherwise. Each Newton iteration assembles and factorises its
// matrix (-shell_ solver options): meant for models of up to some thousands
// of elements (an elastic gate or plate), not the full-size tank.
//
// The state vector's rotational DOFs hold each node's total rotation vector;
// prescribed displacements enter the nodal state directly (no lift).
// An added mass (set_added_mass) is not available with large rotations.
#include <memory>

#include "fem_solver/analysis/corotational_forces.hpp"
#include "fem_solver/analysis/transient_integrator.hpp"

namespace tankfsi::fem {

class CorotationalNewmark final : public TransientIntegrator {
 public:
  /// Starts at rest in the initial shape.
  CorotationalNewmark(StructureSystem& system, RayleighCoefficients damping,
                      TimeIntegrationRule rule = TimeIntegrationRule::average_acceleration());

  void initialise(Vec displacement, Vec velocity, Vec load) override;
  void set_load(Vec load) override;
  /// Throws std::invalid_argument: not available with large rotations.
  void set_added_mass(Mat added_mass, Mat product = nullptr,
                      std::unique_ptr<LinearSolve> inertia = nullptr) override;
  void prepare(double dt) override;
  /// Throws std::runtime_error naming the residual when Newton's method does
  /// not converge in 30 iterations or gives a non-finite state; the state
  /// stays at the last good step.
  void step(double dt, Vec load) override;
  /// Static equilibrium f(u) = load by Newton's method from the current
  /// shape, at rest afterwards; returns the iterations. Throws like step().
  int equilibrate(Vec load);

  [[nodiscard]] Vec displacement() const override { return u_.get(); }
  [[nodiscard]] Vec velocity() const override { return v_.get(); }
  [[nodiscard]] Vec acceleration() const override { return a_.get(); }
  void save(NewmarkState& state) const override;
  void restore(const NewmarkState& state) override;
  /// 1/2 v.M v plus the elements' strain energy. Collective.
  [[nodiscard]] double energy() const override;
  [[nodiscard]] const RayleighCoefficients& damping() const override { return damping_; }
  [[nodiscard]] const TimeIntegrationRule& rule() const override { return rule_; }
  [[nodiscard]] int factorisations() const override { return factorisations_; }
  /// Newton iterations over all steps so far, and the most in one step.
  [[nodiscard]] long long newton_iterations() const { return iterations_; }
  [[nodiscard]] int most_newton_iterations() const { return most_iterations_; }
  /// The supports' forces now (-g at the constrained DOFs). Collective.
  [[nodiscard]] NodalValues support_forces();

 private:
  /// g and K_t at `nodal` (velocity v when beta_R != 0) into g_new_ and tangent_.
  void evaluate(const NodalValues& nodal, Vec velocity, bool with_tangent,
                CorotationalElement::Tangent kind = CorotationalElement::Tangent::material);
  /// Whether Newton's method has converged; throws past its iteration limit.
  [[nodiscard]] bool converged(int iteration, double residual, double scale) const;
  /// Solves matrix dD = rhs with a new factorisation of `matrix`.
  void solve(Mat matrix, Vec rhs, Vec increment);
  /// u_ and nodal_u_ from nodal values.
  void set_displacement(const NodalValues& nodal);

  StructureSystem& system_;
  SystemAssembler& assembler_;
  CorotationalForces forces_;
  RayleighCoefficients damping_;
  TimeIntegrationRule rule_;
  Vec m_;
  PetscMatrix tangent_;
  PetscVector u_, v_, a_, g_, load_;                       ///< the state at t_n
  PetscVector increment_, delta_, v_new_, a_new_, g_new_;  ///< a step's iterates
  PetscVector residual_, work_;
  NodalValues nodal_u_, nodal_increment_, nodal_new_, nodal_velocity_;
  double strain_energy_ = 0.0;  ///< of the state at t_n
  int factorisations_ = 0;
  long long iterations_ = 0;
  int most_iterations_ = 0;
};

}  // namespace tankfsi::fem
