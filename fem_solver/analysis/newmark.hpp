#pragma once
// NewmarkIntegrator: M a + C v + K u = F(t) with the average-acceleration rule
// (gamma = 1/2, beta = 1/4: unconditionally stable, no numerical damping,
// METHOD.md §3), or the generalized-alpha rule of Chung & Hulbert (1993),
// which damps the modes a step cannot resolve and keeps second order: the
// equation holds between the steps,
//   M a_{n+1-am} + C v_{n+1-af} + K u_{n+1-af} = F_{n+1-af},  x_{n+1-a} = (1-a) x_{n+1} + a x_n,
// with Newmark's updates of u and v (TimeIntegrationRule). C = alpha M +
// beta_R K, M lumped (diagonal). Divided by (1 - af), the effective matrix is
// K_eff = (1 + a1 beta_R) K + (c_m a0 + a1 alpha) M, c_m = (1 - am)/(1 - af),
// a0 = 1/(beta dt^2), a1 = gamma/(beta dt) (c_m = 1 for average acceleration);
// it is assembled and factorised once per time step size and reused every
// step; a new dt refactorises.
//
// A step costs one pair of triangular solves and vector operations, no
// product with K: the stiffness part of the damping term of the right-hand
// side, beta_R K (a1 u + a4 v + a5 a), uses K u, K v and K a carried along
// with the state. K u_new follows from the solve itself,
// K_eff u_new = rhs  =>  K u_new = (rhs - (c_m a0 + a1 alpha) M u_new) / (1 + a1 beta_R),
// and K v, K a from the same linear updates as v and a. Each is as accurate
// as a product with K (a direct solve's residual is of the size of a
// product's rounding), and no product means no pass over K's 2e6 entries.
//
// An added mass M_a (set_added_mass: a coupled liquid's estimate of its
// inertia on the wetted surface, coupling/PROTOCOL.md "Added mass") joins the
// inertia but not the damping: M a + M_a a + C v + K u = F, C = alpha M +
// beta_R K with the structure's own M. M_a is sparse (3 x 3 blocks of the
// interface vertices' translations), so M + M_a is no longer diagonal: the
// acceleration of initialise() then takes one solve with it.
#include <memory>

#include "fem_solver/analysis/transient_integrator.hpp"

namespace tankfsi::fem {

class NewmarkIntegrator final : public TransientIntegrator {
 public:
  /// K and the mass diagonal are kept by reference (PETSc reference counts);
  /// u, v start at zero and a from M a = F0 - K u - C v at the first step.
  NewmarkIntegrator(Mat stiffness, Vec mass_diagonal, RayleighCoefficients damping, SolverFactory factory,
                    TimeIntegrationRule rule = TimeIntegrationRule::average_acceleration());

  /// Sets the state at the current time; the acceleration follows from the
  /// equation of motion with the load `load` (M is diagonal: no solve; with
  /// an added mass one solve with M + M_a).
  void initialise(Vec displacement, Vec velocity, Vec load) override;
  /// The same for a new load at the current time, u and v kept: the load of
  /// a coupling window that jumps at its start. With K u and K v carried
  /// along (Rayleigh's beta_R or generalized alpha) it needs one product with
  /// K (K a) instead of initialise()'s four.
  void set_load(Vec load) override;
  /// Adds M_a (same layout as K; nullptr: none) to the inertia from the next
  /// step on; K_eff is factorised again. The matrix is kept by reference.
  /// `product` (nullptr: M_a itself) stands for M_a in the steps' products with
  /// it, `inertia` (nullptr: M + M_a assembled and factorised) for (M + M_a)^-1
  /// in the accelerations of initialise() and set_load(): the same operators
  /// in cheaper forms (normal_added_mass.hpp).
  void set_added_mass(Mat added_mass, Mat product = nullptr,
                      std::unique_ptr<LinearSolve> inertia = nullptr) override;
  /// Assembles and factorises K_eff for steps of dt now (step() does it on
  /// the first step of a new dt otherwise).
  void prepare(double dt) override;
  /// Advances by dt to the load `load` at the end of the step. A step whose
  /// displacement is not finite throws std::runtime_error and leaves the state
  /// as it was (the last good one).
  void step(double dt, Vec load) override;

  [[nodiscard]] Vec displacement() const override { return u_.get(); }
  [[nodiscard]] Vec velocity() const override { return v_.get(); }
  [[nodiscard]] Vec acceleration() const override { return a_.get(); }
  /// Copies the state into `state` (its vectors made on first use).
  void save(NewmarkState& state) const override;
  /// Sets the state back to a saved one.
  void restore(const NewmarkState& state) override;
  /// 1/2 v.M v + 1/2 u.K u (J): conserved by the undamped, unloaded rule.
  [[nodiscard]] double energy() const override;
  [[nodiscard]] const RayleighCoefficients& damping() const override { return damping_; }
  [[nodiscard]] const TimeIntegrationRule& rule() const override { return rule_; }
  /// Number of factorisations so far (one per distinct dt).
  [[nodiscard]] int factorisations() const override { return factorisations_; }

 private:
  void factorise(double dt);
  /// a = (M + M_a)^-1 rhs_ (M diagonal: a division without an added mass).
  void solve_inertia();
  /// Whether step() carries K u, K v and K a along with the state.
  [[nodiscard]] bool carries_k_products() const;
  void damping_times(Vec x, Vec out) const;  ///< out = C x

  Mat k_;
  Vec m_;
  Mat added_mass_ = nullptr;              ///< M_a, or none
  Mat added_mass_product_ = nullptr;      ///< M_a for products (set_added_mass)
  std::unique_ptr<LinearSolve> inertia_;  ///< (M + M_a)^-1, with an added mass
  RayleighCoefficients damping_;
  TimeIntegrationRule rule_;
  SolverFactory factory_;
  std::unique_ptr<LinearSolve> solver_;
  PetscMatrix effective_;
  double factorised_dt_ = 0.0;
  int factorisations_ = 0;
  PetscVector u_, v_, a_, rhs_, work_, work2_, a_new_, u_new_;  // created once: no allocation per step
  PetscVector ku_, kv_, ka_, ka_new_;  ///< K u, K v, K a (kept when beta_R != 0 or alpha_f != 0)
  PetscVector load_;                   ///< F at the current time (generalized-alpha's F_n)
  PetscMatrix inertia_matrix_;         ///< M + M_a, with an added mass factorised here
};

}  // namespace tankfsi::fem
