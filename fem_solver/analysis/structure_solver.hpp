#pragma once
// StructureSolver: the shell's transient response, and the API the coupling
// calls (DESIGN.md, participant loop):
//
//   StructureSolver s(system, damping, constant_loads, ground_motion);
//   s.set_interface(extract_interface(mesh, "wetted"));
//   s.set_external_loads(forces_at_0); s.balance_acceleration();
//   loop: s.set_external_loads(forces);  // 3 per interface vertex, N, at t + dt
//         s.advance(dt);                  // Newmark, K_eff factorised once per dt
//         s.interface_displacements(); s.interface_velocities();
//
// Equation of motion in the tank-base frame (METHOD.md §3): M a + C v + K u =
// F_constant + F_external - M iota a_g(t), iota the rigid-body influence of
// each ground direction, base nodes fixed; u, v, a relative to the base.
// set_external_loads gives the loads at the end of the next step (the
// coupling ramps them over a window by calling it before each step, eq 17);
// balance_acceleration makes the state at t consistent with the loads at t.
#include <span>

#include "common/excitation/ground_motion.hpp"
#include "fem_solver/analysis/corotational_newmark.hpp"
#include "fem_solver/analysis/load_set.hpp"
#include "fem_solver/analysis/newmark.hpp"
#include "fem_solver/analysis/structure_system.hpp"
#include "fem_solver/mesh/interface_mesh.hpp"

namespace tankfsi::fem {

/// How the shell moves: linear (small displacements, f = K u) or
/// co-rotational (large rotations, small strains; corotational_newmark.hpp).
enum class Kinematics { linear, corotational };

class StructureSolver {
 public:
  /// Starts at rest at t = 0 with the constant loads applied.
  StructureSolver(StructureSystem& system, RayleighCoefficients damping, const LoadSet& constant_loads,
                  const GroundMotion& motion, TimeIntegrationRule rule = TimeIntegrationRule::average_acceleration(),
                  Kinematics kinematics = Kinematics::linear);

  /// The interface the coupling exchanges (the same on every rank); sets up
  /// the scatter of its values to every rank. Collective.
  void set_interface(InterfaceMesh interface);
  [[nodiscard]] const InterfaceMesh& interface() const { return interface_; }
  /// Forces on the interface vertices (3 per vertex, global axes); the same on
  /// every rank. Loads on supported DOFs go into the supports.
  void set_external_loads(std::span<const double> forces);
  /// A coupled liquid's added-mass operator on the interface
  /// (coupling/added_mass/added_mass.hpp): `matrix` A (n x n row-major over
  /// the interface vertices, kg) and each vertex's unit normal (3 each); the
  /// block n_i A_ij n_j^T joins the inertia between the free translations of
  /// vertices i and j, not the damping, from the next step on (the next
  /// balance_acceleration() too). The same on every rank. Collective.
  void set_interface_added_mass(std::span<const double> matrix, std::span<const double> normals);
  /// Makes the acceleration at the current time consistent with the loads now
  /// set (M a = F - K u - C v): call once after giving the loads at t = 0, so
  /// that a structure loaded from the start (the liquid's hydrostatic force)
  /// does not see them as a jump over the first step.
  void balance_acceleration();
  /// Puts the structure at rest in static equilibrium with the loads now set,
  /// K u = F(t) (co-rotational: f(u) = F(t) by Newton's method): the state
  /// before a dynamic load.
  void start_at_equilibrium();
  /// Factorises K_eff for steps of dt ahead of the first advance (timed as
  /// shell_factorise rather than inside the first shell_step).
  void prepare(double dt) { integrator_->prepare(dt); }
  /// One Newmark step to t + dt; throws std::runtime_error naming the time if
  /// the solve fails, and leaves the state at the last good step.
  void advance(double dt);

  /// The solver's state (Newmark state, time, step count) for an implicit
  /// coupling window to roll back to.
  struct Checkpoint {
    NewmarkState state;
    double time = 0.0;
    long long steps = 0;
  };
  void save(Checkpoint& checkpoint) const;
  void restore(const Checkpoint& checkpoint);

  [[nodiscard]] double time() const { return time_; }
  [[nodiscard]] long long steps() const { return steps_; }
  /// The state of the whole structure (6 per node), on every rank: gathered
  /// from the distributed state when first asked for after a step, so a step
  /// whose state nobody reads moves none of it between ranks. Collective: all
  /// ranks ask at the same steps.
  [[nodiscard]] const NodalValues& displacement() const;
  [[nodiscard]] const NodalValues& velocity() const;
  [[nodiscard]] const NodalValues& acceleration() const;
  /// The largest nodal translation now (m), without a gather; collective.
  [[nodiscard]] double largest_displacement() const;
  /// 3 per interface vertex, on every rank: only the interface's values move
  /// between ranks. Collective.
  [[nodiscard]] std::vector<double> interface_displacements() const;
  [[nodiscard]] std::vector<double> interface_velocities() const;
  /// Total external load on the structure now: constant + external + ground (N).
  [[nodiscard]] Eigen::Vector3d total_external_force() const;
  /// Forces the structure puts on its supports (-K (u + beta v) there).
  [[nodiscard]] NodalValues support_forces() const;
  [[nodiscard]] double energy() const { return integrator_->energy(); }
  [[nodiscard]] const TransientIntegrator& integrator() const { return *integrator_; }
  /// The co-rotational integrator, or null with linear kinematics.
  [[nodiscard]] const CorotationalNewmark* corotational() const { return corotational_; }

 private:
  /// The whole structure's values of a distributed state vector, gathered once per step.
  struct GatheredState {
    NodalValues values;
    bool current = false;
  };
  void build_load(double t);
  void mark_state_changed();
  /// Gives the integrator M_a assembled and, through its factors
  /// (normal_added_mass.hpp), its product (kept in added_mass_product_) and
  /// the inertia's solve.
  void set_normal_added_mass(std::span<const double> matrix, std::span<const double> normals);
  const NodalValues& gathered(GatheredState& state, Vec values, double prescribed_scale) const;
  [[nodiscard]] std::vector<double> interface_values(Vec values, double prescribed_scale) const;

  StructureSystem& system_;
  const GroundMotion& motion_;
  std::unique_ptr<TransientIntegrator> integrator_;
  CorotationalNewmark* corotational_ = nullptr;  ///< integrator_ when co-rotational
  PetscMatrix added_mass_;          ///< assembled: for K_eff's factorisation
  PetscMatrix added_mass_product_;  ///< the same through its factors: for products (normal_added_mass.hpp)
  PetscVector constant_load_;
  PetscVector external_load_;
  PetscVector load_;
  std::array<PetscVector, 3> mass_influence_;
  Eigen::Vector3d constant_total_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d external_total_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d free_mass_ = Eigen::Vector3d::Zero();
  InterfaceMesh interface_;
  std::vector<PetscInt> interface_equations_;  ///< per interface vertex and translation: equation or -1
  PetscScatter interface_scatter_;             ///< the free ones among them, to every rank
  PetscVector interface_gathered_;
  mutable GatheredState displacement_, velocity_, acceleration_;
  double time_ = 0.0;
  long long steps_ = 0;
};

}  // namespace tankfsi::fem
