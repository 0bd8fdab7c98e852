#pragma once
// CorotationalForces: the shell model's internal forces and tangent under
// large rotations (corotational_element.hpp), assembled over each rank's
// elements like SystemAssembler's linear K.
//
// A state is NodalValues on every rank: per node the translation (3) and the
// total rotation vector psi (3, R = exp([psi]x)). Increments compose with
// it: translations add, rotations R -> exp([dw]x) R (spins in global axes).
#include <vector>

#include "fem_solver/analysis/structure_system.hpp"
#include "fem_solver/elements/corotational_element.hpp"

namespace tankfsi::fem {

/// An element's deformational displacements and rotations (6n, initial
/// axes; corotational_element.hpp) in the nodal state `displacement`.
[[nodiscard]] Eigen::VectorXd element_deformation(const ShellModel& model, std::size_t element,
                                                  const NodalValues& displacement);

class CorotationalForces {
 public:
  /// The elements of this rank with their linear stiffness.
  explicit CorotationalForces(const StructureSystem& system);

  /// g = f_int(u) + beta_R K_t(u) v over the free DOFs into `force` (zeroed
  /// first); K_t(u) into `tangent` when given (a matrix of K's layout, from
  /// create_tangent()). `velocity` is read only when beta_R != 0. Keeps the
  /// elements' forces on constrained DOFs (reactions()) and the strain
  /// energy. Collective (vector and matrix assembly).
  void evaluate(const NodalValues& displacement, const NodalValues& velocity, double beta_r, Vec force,
                Mat tangent, CorotationalElement::Tangent kind = CorotationalElement::Tangent::material);
  /// The smallest residual force Newton's method can resolve: the elements'
  /// force rounding summed over all ranks' elements, times 1000.
  [[nodiscard]] double force_resolution() const { return resolution_; }
  /// A matrix with K's layout for evaluate()'s tangent.
  [[nodiscard]] PetscMatrix create_tangent() const;
  /// Strain energy of the last evaluate(), over all ranks (J). Collective.
  [[nodiscard]] double strain_energy() const;
  /// What the structure puts on its supports at the last evaluate(): -g at
  /// the constrained DOFs, summed over all ranks (NodalValues layout).
  /// Collective.
  [[nodiscard]] NodalValues reactions() const;

  /// out = u composed with the increment: translations added, rotations
  /// exp([increment]x) exp([psi]x) written back as rotation vectors.
  static void compose(const NodalValues& displacement, const NodalValues& increment, NodalValues& out);

 private:
  const StructureSystem& system_;
  std::vector<std::size_t> elements_;  ///< this rank's elements
  std::vector<CorotationalElement> corotational_;
  NodalValues support_force_;  ///< this rank's share
  double energy_ = 0.0;        ///< this rank's share
  double resolution_ = 0.0;
};

}  // namespace tankfsi::fem
