#include "fem_solver/analysis/load_set.hpp"

#include <algorithm>
#include <set>

namespace tankfsi::fem {
namespace {

/// Calls sink(element, element load vector) for every element with a surface load.
template <class Sink>
void for_each_element_load(const ShellModel& model, const LoadSet& loads, Sink&& sink) {
  const std::size_t count = model.mesh.elements.size();
  std::vector<std::vector<PressureField>> parts(count);
  std::vector<Eigen::Vector3d> tractions(count, Eigen::Vector3d::Zero());
  for (const auto& p : loads.surfaces)
    for (const int e : model.mesh.elements_of(p.elements)) {
      const double value = p.pressure;
      if (value != 0.0) parts[static_cast<std::size_t>(e)].push_back([value](const Eigen::Vector3d&) { return value; });
      tractions[static_cast<std::size_t>(e)] += p.traction;
    }
  for (const auto& h : loads.hydrostatic)
    for (const int e : model.mesh.elements_of(h.elements))
      parts[static_cast<std::size_t>(e)].push_back([h](const Eigen::Vector3d& x) {
        return h.density * h.gravity * std::max(0.0, h.level - x.z());
      });
  for (std::size_t e = 0; e < count; ++e) {
    const Eigen::Vector3d traction =
        tractions[e] + model.section_of(e).density * model.section_of(e).thickness * loads.gravity;
    if (parts[e].empty() && traction.isZero(0.0)) continue;
    const auto& list = parts[e];
    const PressureField total = [&list](const Eigen::Vector3d& x) {
      double p = 0.0;
      for (const auto& part : list) p += part(x);
      return p;
    };
    sink(e, element_surface_load(model.element_nodes(e), total, traction));
  }
}

Eigen::VectorXd point_vector(const PointLoad& p) {
  Eigen::VectorXd f(6);
  f << p.force, p.moment;
  return f;
}

}  // namespace

PetscVector assemble_loads(const SystemAssembler& assembler, const LoadSet& loads) {
  PetscVector f = assembler.create_vector();
  int rank = 0;
  MPI_Comm_rank(assembler.comm(), &rank);
  const auto& local = assembler.local_elements();
  const std::set<std::size_t> mine(local.begin(), local.end());
  for_each_element_load(assembler.model(), loads, [&](std::size_t e, const Eigen::VectorXd& values) {
    if (mine.count(e) != 0) assembler.add_element_vector(f.get(), e, values);
  });
  if (rank == 0)
    for (const auto& p : loads.points) {
      const Eigen::VectorXd values = point_vector(p);
      for (int c = 0; c < dofs_per_node; ++c) {
        const PetscInt row = assembler.dofs().equation(p.node, c);
        if (row >= 0) petsc_check(VecSetValue(f.get(), row, values(c), ADD_VALUES), "VecSetValue");
      }
    }
  petsc_check(VecAssemblyBegin(f.get()), "VecAssemblyBegin");
  petsc_check(VecAssemblyEnd(f.get()), "VecAssemblyEnd");
  return f;
}

NodalValues nodal_loads(const ShellModel& model, const LoadSet& loads) {
  NodalValues out(dofs_per_node * model.mesh.nodes.size(), 0.0);
  for_each_element_load(model, loads, [&](std::size_t e, const Eigen::VectorXd& values) {
    const MeshElement& element = model.mesh.elements[e];
    for (int k = 0; k < element.node_count(); ++k)
      for (int c = 0; c < dofs_per_node; ++c)
        out[static_cast<std::size_t>(dofs_per_node * element.nodes[static_cast<std::size_t>(k)] + c)] +=
            values(dofs_per_node * k + c);
  });
  for (const auto& p : loads.points) {
    const Eigen::VectorXd values = point_vector(p);
    for (int c = 0; c < dofs_per_node; ++c) out[static_cast<std::size_t>(dofs_per_node * p.node + c)] += values(c);
  }
  return out;
}

}  // namespace tankfsi::fem
