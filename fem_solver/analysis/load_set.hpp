#pragma once
// LoadSet: the static (or constant) loads of a case, and their consistent
// nodal force vector. Pressures push along the mesh normal (generated tanks
// and cylinders have outward normals, so an internal pressure is positive).
#include <Eigen/Core>

#include <string>
#include <vector>

#include "fem_solver/assembly/system_assembler.hpp"

namespace tankfsi::fem {

/// A pressure (along the mesh normal) and a traction (global axes) per area.
struct SurfaceLoad {
  std::string elements;  ///< region or element set
  double pressure = 0.0; ///< Pa
  Eigen::Vector3d traction = Eigen::Vector3d::Zero();  ///< Pa
};

/// Liquid at rest up to `level`: p = rho g (level - z) below it, zero above.
struct HydrostaticLoad {
  std::string elements;
  double density = 0.0;  ///< kg/m^3
  double gravity = 9.81; ///< m/s^2, acting along -z
  double level = 0.0;    ///< m
};

struct PointLoad {
  int node = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();
};

struct LoadSet {
  std::vector<SurfaceLoad> surfaces;
  std::vector<HydrostaticLoad> hydrostatic;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();  ///< m/s^2: self-weight rho t g per area
  std::vector<PointLoad> points;

  [[nodiscard]] bool empty() const {
    return surfaces.empty() && hydrostatic.empty() && gravity.isZero(0.0) && points.empty();
  }
};

/// Consistent nodal forces of `loads` over the free DOFs (assembled).
/// Throws std::out_of_range for a region or set the mesh does not have.
[[nodiscard]] PetscVector assemble_loads(const SystemAssembler& assembler, const LoadSet& loads);
/// The same loads as nodal values of the whole structure (each rank sums all
/// elements; for totals and reactions).
[[nodiscard]] NodalValues nodal_loads(const ShellModel& model, const LoadSet& loads);

}  // namespace tankfsi::fem
