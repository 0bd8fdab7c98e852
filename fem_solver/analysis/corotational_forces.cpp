#include "fem_solver/analysis/corotational_forces.hpp"

#include "fem_solver/elements/rotation_vector.hpp"

namespace tankfsi::fem {
namespace {

ElementState element_state(const MeshElement& element, const NodalValues& displacement) {
  ElementState state;
  for (int i = 0; i < element.node_count(); ++i) {
    const auto offset = static_cast<std::size_t>(dofs_per_node * element.nodes[static_cast<std::size_t>(i)]);
    NodeState& node = state[static_cast<std::size_t>(i)];
    node.displacement = Eigen::Vector3d(displacement[offset], displacement[offset + 1], displacement[offset + 2]);
    node.rotation =
        rotation_matrix(Eigen::Vector3d(displacement[offset + 3], displacement[offset + 4], displacement[offset + 5]));
  }
  return state;
}

}  // namespace

Eigen::VectorXd element_deformation(const ShellModel& model, std::size_t element, const NodalValues& displacement) {
  const CorotationalElement corotational(model.element_nodes(element), Eigen::MatrixXd());
  return corotational.deformation(element_state(model.mesh.elements[element], displacement));
}

CorotationalForces::CorotationalForces(const StructureSystem& system)
    : system_(system), elements_(system.assembler().local_elements()) {
  const ShellModel& model = system_.model();
  corotational_.reserve(elements_.size());
  for (const std::size_t e : elements_) {
    const ElementNodes nodes = model.element_nodes(e);
    corotational_.emplace_back(nodes, element_stiffness(nodes, model.section_of(e), model.drilling_factor));
  }
  double rounding = 0.0;
  for (const auto& element : corotational_) rounding += element.force_rounding();
  MPI_Allreduce(&rounding, &resolution_, 1, MPI_DOUBLE, MPI_SUM, system_.comm());
  resolution_ *= 1000.0;
}

PetscMatrix CorotationalForces::create_tangent() const {
  PetscMatrix k;
  petsc_check(MatDuplicate(system_.stiffness(), MAT_DO_NOT_COPY_VALUES, k.out()), "MatDuplicate");
  return k;
}

void CorotationalForces::evaluate(const NodalValues& displacement, const NodalValues& velocity, double beta_r,
                                  Vec force, Mat tangent, CorotationalElement::Tangent kind) {
  const SystemAssembler& assembler = system_.assembler();
  const ShellMesh& mesh = system_.model().mesh;
  petsc_check(VecSet(force, 0.0), "VecSet");
  if (tangent != nullptr) petsc_check(MatZeroEntries(tangent), "MatZeroEntries");
  support_force_.assign(displacement.size(), 0.0);
  energy_ = 0.0;
  for (std::size_t k = 0; k < elements_.size(); ++k) {
    const std::size_t e = elements_[k];
    const MeshElement& element = mesh.elements[e];
    const CorotationalElement::Response response = corotational_[k].respond(element_state(element, displacement), kind);
    energy_ += response.energy;
    Eigen::VectorXd g = response.force;
    // Stiffness-proportional damping on the deformational velocity: a rigid
    // rotation, however large, is not damped.
    if (beta_r != 0.0) g += beta_r * (response.tangent * assembler.element_values(e, velocity));
    const std::vector<PetscInt> rows = assembler.element_equations(e);
    petsc_check(VecSetValues(force, static_cast<PetscInt>(rows.size()), rows.data(), g.data(), ADD_VALUES),
                "VecSetValues");
    for (std::size_t r = 0; r < rows.size(); ++r)
      if (rows[r] < 0)
        support_force_[static_cast<std::size_t>(dofs_per_node * element.nodes[r / dofs_per_node]) + r % dofs_per_node] -=
            g(static_cast<Eigen::Index>(r));
    if (tangent != nullptr) {
      const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> block = response.tangent;
      petsc_check(MatSetValues(tangent, static_cast<PetscInt>(rows.size()), rows.data(),
                               static_cast<PetscInt>(rows.size()), rows.data(), block.data(), ADD_VALUES),
                  "MatSetValues");
    }
  }
  petsc_check(VecAssemblyBegin(force), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(force), "VecAssemblyEnd");
  if (tangent != nullptr) {
    petsc_check(MatAssemblyBegin(tangent, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
    petsc_check(MatAssemblyEnd(tangent, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  }
}

double CorotationalForces::strain_energy() const {
  double total = 0.0;
  MPI_Allreduce(&energy_, &total, 1, MPI_DOUBLE, MPI_SUM, system_.comm());
  return total;
}

NodalValues CorotationalForces::reactions() const {
  NodalValues total(support_force_.size(), 0.0);
  MPI_Allreduce(support_force_.data(), total.data(), static_cast<int>(support_force_.size()), MPI_DOUBLE, MPI_SUM,
                system_.comm());
  return total;
}

void CorotationalForces::compose(const NodalValues& displacement, const NodalValues& increment, NodalValues& out) {
  out.resize(displacement.size());
  for (std::size_t i = 0; i < displacement.size(); i += dofs_per_node) {
    for (std::size_t c = 0; c < 3; ++c) out[i + c] = displacement[i + c] + increment[i + c];
    const Eigen::Vector3d psi(displacement[i + 3], displacement[i + 4], displacement[i + 5]);
    const Eigen::Vector3d spin(increment[i + 3], increment[i + 4], increment[i + 5]);
    const Eigen::Vector3d composed = rotation_vector(rotation_matrix(spin) * rotation_matrix(psi));
    for (std::size_t c = 0; c < 3; ++c) out[i + 3 + c] = composed(static_cast<Eigen::Index>(c));
  }
}

}  // namespace tankfsi::fem
