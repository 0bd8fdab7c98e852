#pragma once
// SystemAssembler: the distributed linear system of the shell model. Each rank
// computes its own elements (METIS partition) and adds them into PETSc's
// distributed matrix and vectors (entries of other ranks' rows travel in
// MatAssembly). Also the reverse: a distributed solution gathered into the
// whole structure's nodal values on every rank, and reactions from it.
#include <mpi.h>

#include <Eigen/Core>

#include <map>
#include <vector>

#include "fem_solver/assembly/dof_map.hpp"
#include "common/run/petsc_handle.hpp"
#include "fem_solver/assembly/shell_model.hpp"

namespace tankfsi::fem {

/// Nodal values of the whole structure: 6 per node, node after node.
using NodalValues = std::vector<double>;

class SystemAssembler {
 public:
  SystemAssembler(MPI_Comm comm, const ShellModel& model, const MeshPartition& partition, const DofMap& dofs);

  /// K over the free DOFs (symmetric positive definite once the structure is
  /// supported). Keeps the element matrices of the elements touching
  /// constrained DOFs, for lift() and reactions().
  [[nodiscard]] PetscMatrix stiffness();
  /// Diagonal of the lumped mass over the free DOFs.
  [[nodiscard]] PetscVector lumped_mass() const;
  /// Lumped mass of every DOF of the structure (replicated).
  [[nodiscard]] const NodalValues& nodal_mass() const { return nodal_mass_; }
  /// M iota_k: the mass row sums along translation k (ground acceleration loads).
  [[nodiscard]] PetscVector mass_times_influence(int direction) const;

  [[nodiscard]] PetscVector create_vector() const;
  /// Adds an element vector (6n, global axes); call for local elements only.
  void add_element_vector(Vec target, std::size_t element, const Eigen::VectorXd& values) const;
  /// Adds -K_fp u_p of the prescribed DOFs (needs stiffness() first).
  void add_prescribed_lift(Vec target) const;
  /// Distributed free-DOF values and nodal DOFs of the whole structure, on every
  /// rank; constrained DOFs take `prescribed_scale` times their prescribed value
  /// (1 for displacements, 0 for velocities and accelerations).
  [[nodiscard]] NodalValues gather(Vec free_values, double prescribed_scale);
  /// The same into `out`, reusing its storage (the per-step state of a dynamic run).
  void gather(Vec free_values, double prescribed_scale, NodalValues& out);
  /// The largest translation |(u_x, u_y, u_z)| of any node (constrained DOFs
  /// at `prescribed_scale` times their value), over all ranks, without
  /// gathering the vector: collective.
  [[nodiscard]] double largest_translation(Vec free_values, double prescribed_scale) const;
  /// Writes nodal values (the owned free DOFs) into a distributed vector.
  void scatter(const NodalValues& values, Vec target) const;
  /// Forces the structure puts on its supports through its elements,
  /// -K_e (u + damping v) at the constrained DOFs, summed over all ranks
  /// (indexed like NodalValues, zero at free DOFs). External loads acting on
  /// supported DOFs go straight into the supports and are not included.
  [[nodiscard]] NodalValues reactions(const NodalValues& displacement, const NodalValues& velocity,
                                      double stiffness_damping) const;

  [[nodiscard]] const std::vector<std::size_t>& local_elements() const { return local_elements_; }
  [[nodiscard]] Eigen::VectorXd element_values(std::size_t element, const NodalValues& values) const;
  [[nodiscard]] const ShellModel& model() const { return model_; }
  [[nodiscard]] const DofMap& dofs() const { return dofs_; }
  [[nodiscard]] MPI_Comm comm() const { return comm_; }

  /// The equations of an element's 6n DOFs (-1 where constrained).
  [[nodiscard]] std::vector<PetscInt> element_equations(std::size_t element) const;

 private:
  void preallocate(Mat matrix) const;

  MPI_Comm comm_;
  const ShellModel& model_;
  const MeshPartition& partition_;
  const DofMap& dofs_;
  int rank_ = 0;
  std::vector<std::size_t> local_elements_;
  NodalValues nodal_mass_;
  std::map<std::size_t, Eigen::MatrixXd> boundary_stiffness_;  ///< local elements with constrained DOFs
  PetscScatter to_all_;
  PetscVector gathered_;
};

}  // namespace tankfsi::fem
