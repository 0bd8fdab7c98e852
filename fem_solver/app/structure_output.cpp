#include "fem_solver/app/structure_output.hpp"

#include <Eigen/Geometry>

#include "common/parallel/collective.hpp"
#include "fem_solver/analysis/corotational_forces.hpp"

namespace tankfsi::fem {
namespace {

std::vector<std::string> probe_columns(const std::string& quantity, bool projected) {
  if (projected) {
    if (quantity == "displacement") return {"displacement_m"};
    if (quantity == "velocity") return {"velocity_m_s"};
    if (quantity == "acceleration") return {"acceleration_m_s2"};
    return {"rotation_rad"};
  }
  if (quantity == "displacement") return {"displacement_x_m", "displacement_y_m", "displacement_z_m"};
  if (quantity == "velocity") return {"velocity_x_m_s", "velocity_y_m_s", "velocity_z_m_s"};
  if (quantity == "acceleration") return {"acceleration_x_m_s2", "acceleration_y_m_s2", "acceleration_z_m_s2"};
  return {"rotation_x_rad", "rotation_y_rad", "rotation_z_rad"};
}

}  // namespace

StructureTotals support_totals(const ShellMesh& mesh, const NodalValues& support_forces) {
  StructureTotals t;
  for (std::size_t node = 0; node < mesh.nodes.size(); ++node) {
    const Eigen::Vector3d f(support_forces[6 * node], support_forces[6 * node + 1], support_forces[6 * node + 2]);
    const Eigen::Vector3d m(support_forces[6 * node + 3], support_forces[6 * node + 4], support_forces[6 * node + 5]);
    t.support_force += f;
    t.support_moment += mesh.nodes[node].cross(f) + m;
  }
  return t;
}

StructureOutput::StructureOutput(ProgramContext& context, const StructureCase& c, const StructureSystem& system,
                                 std::optional<double> resume_time)
    : system_(system), corotational_(c.corotational), probes_(c.probes),
      writer_(context.comm, context.folder->path(), "structure", resume_time ? FileMode::append : FileMode::truncate,
              resume_time) {
  int rank = 0;
  int size = 1;
  MPI_Comm_rank(context.comm, &rank);
  MPI_Comm_size(context.comm, &size);
  const ShellMesh& mesh = system.model().mesh;
  const auto& owner = system.partition().node_owner;
  // File index of every node: owned nodes rank by rank, each in node order
  // (the writer's row order), known on every rank without communication.
  std::vector<std::int64_t> file_index(mesh.nodes.size(), -1);
  std::int64_t next = 0;
  for (int r = 0; r < size; ++r)
    for (std::size_t node = 0; node < mesh.nodes.size(); ++node)
      if (owner[node] == r) {
        file_index[node] = next++;
        if (r == rank) vertex_ids_.push_back(static_cast<std::int64_t>(node));
      }
  for (const bool triangles : {true, false})
    for (const std::size_t e : system.assembler().local_elements()) {
      const MeshElement& element = mesh.elements[e];
      if ((element.node_count() == 3) != triangles) continue;
      cell_elements_.push_back(e);
      for (int k = 0; k < element.node_count(); ++k)
        (triangles ? triangles_ : quads_).push_back(file_index[static_cast<std::size_t>(element.nodes[static_cast<std::size_t>(k)])]);
    }
  // Rank 0 writes the probes; a file it cannot continue stops every rank.
  run_on_root(context.comm, 0, [&] {
    for (const auto& p : probes_)
      probe_files_.push_back(open_probe_file(context.folder->probes() / (p.name + ".csv"),
                                             probe_columns(p.quantity, p.direction.has_value()), c.field_interval,
                                             resume_time));
    totals_file_ = open_probe_file(
        context.folder->probes() / "structure.csv",
        std::vector<std::string>{"base_shear_x_N", "base_shear_y_N", "support_force_z_N", "overturning_moment_x_Nm",
                                 "overturning_moment_y_Nm", "external_force_x_N", "external_force_y_N",
                                 "external_force_z_N", "energy_J"},
        c.field_interval, resume_time);
  });
}

void StructureOutput::write_fields(double time, const NodalValues& displacement, const NodalValues& velocity) {
  const ShellModel& model = system_.model();
  std::vector<double> positions, u, rotation, v;
  for (const std::int64_t node : vertex_ids_) {
    const auto n = static_cast<std::size_t>(node);
    for (std::size_t k = 0; k < 3; ++k) {
      positions.push_back(model.mesh.nodes[n](static_cast<Eigen::Index>(k)));
      u.push_back(displacement[6 * n + k]);
      rotation.push_back(displacement[6 * n + 3 + k]);
      if (!velocity.empty()) v.push_back(velocity[6 * n + k]);
    }
  }
  std::vector<double> membrane, bending, shear_1, shear_2, top, bottom;
  for (const std::size_t e : cell_elements_) {
    const Eigen::VectorXd deformation = corotational_ ? element_deformation(model, e, displacement)
                                                      : system_.assembler().element_values(e, displacement);
    const StressResultants r = element_stress_resultants(model.element_nodes(e), model.section_of(e), deformation);
    for (int k = 0; k < 3; ++k) {
      membrane.push_back(r.membrane(k));
      bending.push_back(r.bending(k));
    }
    shear_1.push_back(r.shear(0));
    shear_2.push_back(r.shear(1));
    top.push_back(r.von_mises_top);
    bottom.push_back(r.von_mises_bottom);
  }
  MeshSnapshot snapshot{vertex_ids_, positions, std::nullopt,
                        {NamedField{"displacement", 3, u}, NamedField{"rotation", 3, rotation}},
                        {NamedField{"membrane_force_11_22_12", 3, membrane},
                         NamedField{"bending_moment_11_22_12", 3, bending}, NamedField{"transverse_shear_13", 1, shear_1},
                         NamedField{"transverse_shear_23", 1, shear_2}, NamedField{"von_mises_top", 1, top},
                         NamedField{"von_mises_bottom", 1, bottom}}};
  if (!velocity.empty()) snapshot.node_fields.push_back(NamedField{"velocity", 3, v});
  if (!cells_written_) snapshot.cells = SurfaceCells{triangles_, quads_};  // then reused
  writer_.write_mesh(time, snapshot);
  cells_written_ = true;
}

void StructureOutput::sample(double time, const NodalValues& displacement, const NodalValues& velocity,
                             const NodalValues& acceleration, const StructureTotals& totals) {
  if (!totals_file_) return;
  for (std::size_t k = 0; k < probes_.size(); ++k) {
    const StructureProbe& p = probes_[k];
    const NodalValues& source = p.quantity == "velocity" ? velocity : p.quantity == "acceleration" ? acceleration : displacement;
    const std::size_t offset = 6 * static_cast<std::size_t>(p.node) + (p.quantity == "rotation" ? 3 : 0);
    Eigen::Vector3d value = Eigen::Vector3d::Zero();
    if (!source.empty()) value = Eigen::Vector3d(source[offset], source[offset + 1], source[offset + 2]);
    if (p.direction) probe_files_[k]->append(time, std::vector<double>{p.direction->dot(value)});
    else probe_files_[k]->append(time, std::vector<double>{value.x(), value.y(), value.z()});
  }
  totals_file_->append(time, std::vector<double>{totals.support_force.x(), totals.support_force.y(),
                                                 totals.support_force.z(), totals.support_moment.x(),
                                                 totals.support_moment.y(), totals.external_force.x(),
                                                 totals.external_force.y(), totals.external_force.z(), totals.energy});
}

void StructureOutput::flush() {
  for (auto& f : probe_files_) f->flush();
  if (totals_file_) totals_file_->flush();
}

}  // namespace tankfsi::fem
