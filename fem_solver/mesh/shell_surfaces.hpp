#pragma once
// Generated shell surfaces of the standard obstacle course (MacNeal & Harder
// 1985; Belytschko et al. 1985) and of the coupled benchmarks: cylindrical and
// spherical patches and flat plates, with named edges, so that a case file can
// put boundary conditions on them.
#include "fem_solver/mesh/shell_mesh.hpp"

namespace tankfsi::fem {

/// Cylinder of axis z: x = (R cos phi, R sin phi, z), phi in [phi_start,
/// phi_end] (degrees), z in [0, length]; normals point away from the axis.
/// Node sets: phi_start, phi_end (absent for a full circle), z_start, z_end.
struct CylinderPatch {
  double radius = 1.0;
  double length = 1.0;
  double phi_start = 0.0;
  double phi_end = 90.0;
  int divisions_phi = 8;
  int divisions_z = 8;
};
[[nodiscard]] ShellMesh cylinder_patch(const CylinderPatch& spec);

/// Sphere about the origin: x = R (sin theta cos phi, sin theta sin phi,
/// cos theta), theta (from +z) in [theta_start, theta_end], phi in
/// [phi_start, phi_end] (degrees); normals point outward. theta_start must be
/// > 0 (a patch, not a cap: caps are closed by the tank generator).
/// Node sets: theta_start, theta_end, phi_start, phi_end.
struct SpherePatch {
  double radius = 1.0;
  double theta_start = 18.0;
  double theta_end = 90.0;
  double phi_start = 0.0;
  double phi_end = 90.0;
  int divisions_theta = 8;
  int divisions_phi = 8;
};
[[nodiscard]] ShellMesh sphere_patch(const SpherePatch& spec);

/// Flat parallelogram x = corner + u side_u + v side_v, u, v in [0, 1]; the
/// normal is side_u x side_v. Region 'plate'; node sets u_start, u_end,
/// v_start, v_end; with `wetted` every element is also in the set 'wetted'
/// (a plate that is a coupled interface). A strip one element wide across a
/// 2D fluid section, with symmetry supports on its v edges, bends as a plate
/// in plane strain (the 2D coupled benchmarks).
struct PlatePatch {
  Eigen::Vector3d corner = Eigen::Vector3d::Zero();
  Eigen::Vector3d side_u = Eigen::Vector3d::UnitX();
  Eigen::Vector3d side_v = Eigen::Vector3d::UnitY();
  int divisions_u = 8;
  int divisions_v = 8;
  bool wetted = false;
};
[[nodiscard]] ShellMesh plate_patch(const PlatePatch& spec);

}  // namespace tankfsi::fem
