#pragma once
// StructureOutput: what fem_solver writes — structure.h5/.xdmf (the mesh with
// displacement, rotation, velocity per node and stress resultants per element;
// each rank writes its own nodes and elements), probes/<name>.csv (rank 0),
// probes/structure.csv (base shear and overturning moment from the support
// forces, total external load, energy).
#include <memory>
#include <optional>

#include "common/io/field_series_writer.hpp"
#include "common/io/probe_file.hpp"
#include "common/run/program.hpp"
#include "fem_solver/analysis/structure_system.hpp"
#include "fem_solver/app/structure_case.hpp"

namespace tankfsi::fem {

/// Global figures sampled into probes/structure.csv.
struct StructureTotals {
  Eigen::Vector3d support_force = Eigen::Vector3d::Zero();   ///< base shear (x, y) and vertical force, N
  Eigen::Vector3d support_moment = Eigen::Vector3d::Zero();  ///< about the origin (base centre), N m
  Eigen::Vector3d external_force = Eigen::Vector3d::Zero();  ///< N
  double energy = 0.0;                                       ///< J
};

/// Sums the support forces (6 per node) into a force and a moment about the origin.
[[nodiscard]] StructureTotals support_totals(const ShellMesh& mesh, const NodalValues& support_forces);

class StructureOutput {
 public:
  /// `resume_time`: a restarted run's time; the series and probe files go on
  /// from it (what the stopped run wrote after it is dropped).
  StructureOutput(ProgramContext& context, const StructureCase& c, const StructureSystem& system,
                  std::optional<double> resume_time = std::nullopt);

  /// One snapshot of the fields; `velocity` may be empty (static, modal).
  /// Stress resultants come from each element's deformation: the
  /// displacements themselves, or (co-rotational) what is left of them
  /// after the element's rigid motion, in the element's rotated frame.
  void write_fields(double time, const NodalValues& displacement, const NodalValues& velocity);
  /// One row per probe and of probes/structure.csv.
  void sample(double time, const NodalValues& displacement, const NodalValues& velocity,
              const NodalValues& acceleration, const StructureTotals& totals);
  void flush();

 private:
  const StructureSystem& system_;
  bool corotational_ = false;
  std::vector<StructureProbe> probes_;
  FieldSeriesWriter writer_;
  std::vector<std::int64_t> vertex_ids_;     ///< owned nodes, in file order
  std::vector<std::int64_t> triangles_, quads_;
  std::vector<std::size_t> cell_elements_;   ///< local elements: triangles first, then quads
  std::vector<std::unique_ptr<ProbeFile>> probe_files_;
  std::unique_ptr<ProbeFile> totals_file_;
  bool cells_written_ = false;
};

}  // namespace tankfsi::fem
