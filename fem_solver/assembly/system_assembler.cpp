#include "fem_solver/assembly/system_assembler.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace tankfsi::fem {

SystemAssembler::SystemAssembler(MPI_Comm comm, const ShellModel& model, const MeshPartition& partition,
                                 const DofMap& dofs)
    : comm_(comm), model_(model), partition_(partition), dofs_(dofs) {
  MPI_Comm_rank(comm_, &rank_);
  for (std::size_t e = 0; e < model_.mesh.elements.size(); ++e)
    if (partition_.element_rank[e] == rank_) local_elements_.push_back(e);
  // The lumped mass of every node on every rank: cheap next to the stiffness,
  // and it spares a gather for ground loads, probes and modal masses.
  nodal_mass_.assign(dofs_per_node * model_.mesh.nodes.size(), 0.0);
  for (std::size_t e = 0; e < model_.mesh.elements.size(); ++e) {
    const Eigen::VectorXd m = element_lumped_mass(model_.element_nodes(e), model_.section_of(e));
    const MeshElement& element = model_.mesh.elements[e];
    for (int k = 0; k < element.node_count(); ++k)
      for (int c = 0; c < dofs_per_node; ++c)
        nodal_mass_[static_cast<std::size_t>(dofs_per_node * element.nodes[static_cast<std::size_t>(k)] + c)] +=
            m(dofs_per_node * k + c);
  }
}

std::vector<PetscInt> SystemAssembler::element_equations(std::size_t element) const {
  const MeshElement& e = model_.mesh.elements[element];
  std::vector<PetscInt> rows;
  for (int k = 0; k < e.node_count(); ++k)
    for (int c = 0; c < dofs_per_node; ++c) rows.push_back(dofs_.equation(e.nodes[static_cast<std::size_t>(k)], c));
  return rows;
}

void SystemAssembler::preallocate(Mat matrix) const {
  // Column pattern of an owned node's rows: every free DOF of the nodes it
  // shares an element with.
  const std::size_t nodes = model_.mesh.nodes.size();
  std::vector<std::set<int>> neighbours(nodes);
  for (const auto& e : model_.mesh.elements)
    for (int a = 0; a < e.node_count(); ++a) {
      const int node = e.nodes[static_cast<std::size_t>(a)];
      if (partition_.node_owner[static_cast<std::size_t>(node)] != rank_) continue;
      for (int b = 0; b < e.node_count(); ++b) neighbours[static_cast<std::size_t>(node)].insert(e.nodes[static_cast<std::size_t>(b)]);
    }
  std::vector<PetscInt> diagonal(static_cast<std::size_t>(dofs_.owned_count()), 0);
  std::vector<PetscInt> off_diagonal(static_cast<std::size_t>(dofs_.owned_count()), 0);
  const PetscInt first = dofs_.first_owned();
  const PetscInt last = first + dofs_.owned_count();
  for (std::size_t node = 0; node < nodes; ++node) {
    if (partition_.node_owner[node] != rank_) continue;
    PetscInt in = 0;
    PetscInt out = 0;
    for (const int other : neighbours[node])
      for (int c = 0; c < dofs_per_node; ++c) {
        const PetscInt column = dofs_.equation(other, c);
        if (column < 0) continue;
        ++(column >= first && column < last ? in : out);
      }
    for (int c = 0; c < dofs_per_node; ++c) {
      const PetscInt row = dofs_.equation(static_cast<int>(node), c);
      if (row < 0) continue;
      diagonal[static_cast<std::size_t>(row - first)] = in;
      off_diagonal[static_cast<std::size_t>(row - first)] = out;
    }
  }
  petsc_check(MatMPIAIJSetPreallocation(matrix, 0, diagonal.data(), 0, off_diagonal.data()), "MatMPIAIJSetPreallocation");
  petsc_check(MatSeqAIJSetPreallocation(matrix, 0, diagonal.data()), "MatSeqAIJSetPreallocation");
}

PetscMatrix SystemAssembler::stiffness() {
  PetscMatrix k;
  petsc_check(MatCreate(comm_, k.out()), "MatCreate");
  petsc_check(MatSetSizes(k.get(), dofs_.owned_count(), dofs_.owned_count(), dofs_.global_size(), dofs_.global_size()),
              "MatSetSizes");
  petsc_check(MatSetType(k.get(), MATAIJ), "MatSetType");
  preallocate(k.get());
  boundary_stiffness_.clear();
  for (const std::size_t e : local_elements_) {
    const Eigen::MatrixXd ke = element_stiffness(model_.element_nodes(e), model_.section_of(e), model_.drilling_factor);
    const auto rows = element_equations(e);
    if (std::find(rows.begin(), rows.end(), PetscInt{-1}) != rows.end()) boundary_stiffness_[e] = ke;
    // Row-major copy: MatSetValues reads a dense row-major block; negative
    // indices (constrained DOFs) are skipped by PETSc.
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block = ke;
    petsc_check(MatSetValues(k.get(), static_cast<PetscInt>(rows.size()), rows.data(), static_cast<PetscInt>(rows.size()),
                             rows.data(), block.data(), ADD_VALUES),
                "MatSetValues");
  }
  petsc_check(MatAssemblyBegin(k.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(k.get(), MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  petsc_check(MatSetOption(k.get(), MAT_SYMMETRIC, PETSC_TRUE), "MatSetOption");
  petsc_check(MatSetOption(k.get(), MAT_SPD, PETSC_TRUE), "MatSetOption");
  return k;
}

PetscVector SystemAssembler::create_vector() const {
  PetscVector v;
  petsc_check(VecCreateMPI(comm_, dofs_.owned_count(), dofs_.global_size(), v.out()), "VecCreateMPI");
  // Element vectors name constrained DOFs by -1: skip them, as MatSetValues does.
  petsc_check(VecSetOption(v.get(), VEC_IGNORE_NEGATIVE_INDICES, PETSC_TRUE), "VecSetOption");
  return v;
}

void SystemAssembler::scatter(const NodalValues& values, Vec target) const {
  PetscScalar* x = nullptr;
  petsc_check(VecGetArray(target, &x), "VecGetArray");
  const PetscInt first = dofs_.first_owned();
  for (std::size_t node = 0; node < model_.mesh.nodes.size(); ++node) {
    if (partition_.node_owner[node] != rank_) continue;
    for (int c = 0; c < dofs_per_node; ++c) {
      const PetscInt row = dofs_.equation(static_cast<int>(node), c);
      if (row >= 0) x[row - first] = values[dofs_per_node * node + static_cast<std::size_t>(c)];
    }
  }
  petsc_check(VecRestoreArray(target, &x), "VecRestoreArray");
}

double SystemAssembler::largest_translation(Vec free_values, double prescribed_scale) const {
  const PetscScalar* x = nullptr;
  petsc_check(VecGetArrayRead(free_values, &x), "VecGetArrayRead");
  const PetscInt first = dofs_.first_owned();
  double largest = 0.0;
  for (std::size_t node = 0; node < model_.mesh.nodes.size(); ++node) {
    if (partition_.node_owner[node] != rank_) continue;
    double squared = 0.0;
    for (int c = 0; c < 3; ++c) {
      const PetscInt row = dofs_.equation(static_cast<int>(node), c);
      const double value = row >= 0 ? x[row - first] : prescribed_scale * dofs_.prescribed(static_cast<int>(node), c);
      squared += value * value;
    }
    largest = std::max(largest, squared);
  }
  petsc_check(VecRestoreArrayRead(free_values, &x), "VecRestoreArrayRead");
  double global = 0.0;
  MPI_Allreduce(&largest, &global, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return std::sqrt(global);
}

PetscVector SystemAssembler::lumped_mass() const {
  PetscVector m = create_vector();
  scatter(nodal_mass_, m.get());
  return m;
}

PetscVector SystemAssembler::mass_times_influence(int direction) const {
  NodalValues influence(nodal_mass_.size(), 0.0);
  for (std::size_t node = 0; node < model_.mesh.nodes.size(); ++node)
    influence[dofs_per_node * node + static_cast<std::size_t>(direction)] =
        nodal_mass_[dofs_per_node * node + static_cast<std::size_t>(direction)];
  PetscVector v = create_vector();
  scatter(influence, v.get());
  return v;
}

void SystemAssembler::add_element_vector(Vec target, std::size_t element, const Eigen::VectorXd& values) const {
  const auto rows = element_equations(element);
  petsc_check(VecSetValues(target, static_cast<PetscInt>(rows.size()), rows.data(), values.data(), ADD_VALUES),
              "VecSetValues");
}

void SystemAssembler::add_prescribed_lift(Vec target) const {
  for (const auto& [e, ke] : boundary_stiffness_) {
    const MeshElement& element = model_.mesh.elements[e];
    Eigen::VectorXd prescribed = Eigen::VectorXd::Zero(ke.rows());
    for (int k = 0; k < element.node_count(); ++k)
      for (int c = 0; c < dofs_per_node; ++c) {
        const int node = element.nodes[static_cast<std::size_t>(k)];
        if (dofs_.equation(node, c) < 0) prescribed(dofs_per_node * k + c) = dofs_.prescribed(node, c);
      }
    if (prescribed.isZero(0.0)) continue;
    add_element_vector(target, e, -(ke * prescribed));
  }
}

NodalValues SystemAssembler::gather(Vec free_values, double prescribed_scale) {
  NodalValues out;
  gather(free_values, prescribed_scale, out);
  return out;
}

void SystemAssembler::gather(Vec free_values, double prescribed_scale, NodalValues& out) {
  if (!to_all_) petsc_check(VecScatterCreateToAll(free_values, to_all_.out(), gathered_.out()), "VecScatterCreateToAll");
  petsc_check(VecScatterBegin(to_all_.get(), free_values, gathered_.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterBegin");
  petsc_check(VecScatterEnd(to_all_.get(), free_values, gathered_.get(), INSERT_VALUES, SCATTER_FORWARD), "VecScatterEnd");
  const PetscScalar* x = nullptr;
  petsc_check(VecGetArrayRead(gathered_.get(), &x), "VecGetArrayRead");
  out.resize(dofs_per_node * model_.mesh.nodes.size());
  for (std::size_t node = 0; node < model_.mesh.nodes.size(); ++node)
    for (int c = 0; c < dofs_per_node; ++c) {
      const PetscInt row = dofs_.equation(static_cast<int>(node), c);
      out[dofs_per_node * node + static_cast<std::size_t>(c)] =
          row >= 0 ? x[row] : prescribed_scale * dofs_.prescribed(static_cast<int>(node), c);
    }
  petsc_check(VecRestoreArrayRead(gathered_.get(), &x), "VecRestoreArrayRead");
}

Eigen::VectorXd SystemAssembler::element_values(std::size_t element, const NodalValues& values) const {
  const MeshElement& e = model_.mesh.elements[element];
  Eigen::VectorXd out(dofs_per_node * e.node_count());
  for (int k = 0; k < e.node_count(); ++k)
    for (int c = 0; c < dofs_per_node; ++c)
      out(dofs_per_node * k + c) = values[static_cast<std::size_t>(dofs_per_node * e.nodes[static_cast<std::size_t>(k)] + c)];
  return out;
}

NodalValues SystemAssembler::reactions(const NodalValues& displacement, const NodalValues& velocity,
                                       double stiffness_damping) const {
  NodalValues local(displacement.size(), 0.0);
  for (const auto& [e, ke] : boundary_stiffness_) {
    Eigen::VectorXd state = element_values(e, displacement);
    if (stiffness_damping != 0.0) state += stiffness_damping * element_values(e, velocity);
    // The elements pull on a supported node with -K_e state: that is the force
    // the structure puts on the support.
    const Eigen::VectorXd force = -(ke * state);
    const MeshElement& element = model_.mesh.elements[e];
    for (int k = 0; k < element.node_count(); ++k)
      for (int c = 0; c < dofs_per_node; ++c) {
        const int node = element.nodes[static_cast<std::size_t>(k)];
        if (dofs_.equation(node, c) < 0)
          local[static_cast<std::size_t>(dofs_per_node * node + c)] += force(dofs_per_node * k + c);
      }
  }
  NodalValues total(local.size(), 0.0);
  MPI_Allreduce(local.data(), total.data(), static_cast<int>(local.size()), MPI_DOUBLE, MPI_SUM, comm_);
  return total;
}

}  // namespace tankfsi::fem
