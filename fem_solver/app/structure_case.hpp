#pragma once
// StructureCase: everything fem_solver needs from the case file, read and
// checked in the program's set-up (bad input is reported, naming file, line
// and key, before anything is written).
#include <optional>
#include <string>
#include <vector>

#include "common/config/case_config.hpp"
#include "fem_solver/analysis/load_set.hpp"
#include "fem_solver/assembly/dof_map.hpp"
#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

struct StructureProbe {
  std::string name;
  std::string quantity;  ///< displacement, velocity, acceleration, rotation
  int node = 0;
  /// Unit vector the probe projects onto (one column), or none (x, y, z columns).
  std::optional<Eigen::Vector3d> direction;
};

struct DampingTarget {
  int first_mode = 1;
  int second_mode = 3;
  double first_ratio = 0.03;
  double second_ratio = 0.03;
};

struct StructureCase {
  std::string analysis;  ///< static, modal, dynamic
  bool corotational = false;  ///< structure.kinematics: corotational (large rotations)
  int load_steps = 1;         ///< corotational static: load increments
  ShellMesh mesh;
  std::vector<ShellSection> sections;  ///< one per mesh region
  double drilling_factor = 1e-3;
  std::vector<DofConstraint> constraints;
  LoadSet loads;
  std::vector<StructureProbe> probes;
  std::string solver_options;
  int modes = 10;
  double time_step = 0.0;
  double end_time = 0.0;
  DampingTarget damping;
  double spectral_radius = 1.0;  ///< generalized-alpha rho_inf; 1: average acceleration
  double field_interval = 0.0;
  double probe_interval = 0.0;
};

/// Throws ConfigError naming the key and line of any problem.
[[nodiscard]] StructureCase read_structure_case(const CaseConfig& config);

// The parts, one file each.
[[nodiscard]] ShellMesh read_structure_mesh(const CaseConfig& config);
[[nodiscard]] std::vector<ShellSection> read_sections(const CaseConfig& config, const ShellMesh& mesh);
/// Also records the symmetry supports' planes on the mesh (its directors use them).
[[nodiscard]] std::vector<DofConstraint> read_constraints(const CaseConfig& config, ShellMesh& mesh);
[[nodiscard]] LoadSet read_loads(const CaseConfig& config, const ShellMesh& mesh);

}  // namespace tankfsi::fem
