#pragma once
// FluidCase: everything sph_solver needs from the case file, read and checked in
// the program's set-up phase (bad input is reported before anything is written).
#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "common/config/case_config.hpp"
#include "sph_solver/isph/fluid_model.hpp"
#include "sph_solver/particles/particles.hpp"
#include "sph_solver/walls/triangle_mesh.hpp"

namespace tankfsi::sph {

struct ProbeSpec {
  std::string name;
  std::string quantity;  ///< pressure, velocity, wave_height, front, volume
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< the point of a point probe
  Eigen::AlignedBox3d region;                          ///< the box of a volume probe
};

struct FluidCase {
  FluidModel model;
  TriangleMesh walls;
  Particles particles;
  Eigen::AlignedBox3d domain;  ///< particles leaving it are removed (overflow)
  std::string ppe_options;
  bool adaptive_time_step = true;
  double fixed_time_step = 0.0;
  double cfl_number = 0.2;
  double breach_courant = 1.0;  ///< fluid.time_step.breach_courant
  double max_time_step = 0.0;
  double end_time = 0.0;
  double field_interval = 0.0;
  double probe_interval = 0.0;
  int rebalance_interval = 20;
  std::vector<ProbeSpec> probes;
};

/// Throws ConfigError naming the key and line of any problem.
[[nodiscard]] FluidCase read_fluid_case(const CaseConfig& config);

}  // namespace tankfsi::sph
