#pragma once
// Generated shell surfaces of the standard obstacle course (MacNeal & Harder
// 1985; Belytschko et al. 1985): cylindrical and spherical patches with named
// edges, so that a case file can put boundary conditions on them.
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

}  // namespace tankfsi::fem
