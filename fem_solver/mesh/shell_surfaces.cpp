#include "fem_solver/mesh/shell_surfaces.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "fem_solver/mesh/structured_patch.hpp"

namespace tankfsi::fem {
namespace {

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

}  // namespace

ShellMesh cylinder_patch(const CylinderPatch& spec) {
  const double sweep = spec.phi_end - spec.phi_start;
  if (!(spec.radius > 0.0 && spec.length > 0.0 && sweep > 0.0 && sweep <= 360.0))
    throw std::invalid_argument("a cylinder patch needs radius > 0, length > 0 and 0 < phi_end - phi_start <= 360");
  PatchSpec patch;
  patch.divisions_u = spec.divisions_phi;
  patch.divisions_v = spec.divisions_z;
  patch.closed_u = sweep == 360.0;
  patch.region = "shell";
  patch.edge_names = {"phi_start", "phi_end", "z_start", "z_end"};
  // u = phi, v = z: x_,phi x x_,z points away from the axis.
  patch.map = [&](double u, double v) {
    const double phi = radians(spec.phi_start + u * sweep);
    return Eigen::Vector3d(spec.radius * std::cos(phi), spec.radius * std::sin(phi), v * spec.length);
  };
  ShellMesh mesh = structured_patch(patch);
  for (const auto& x : mesh.nodes) mesh.node_normals.emplace_back(x.x(), x.y(), 0.0);
  return mesh;
}

ShellMesh sphere_patch(const SpherePatch& spec) {
  const double sweep = spec.phi_end - spec.phi_start;
  if (!(spec.radius > 0.0 && spec.theta_start > 0.0 && spec.theta_end > spec.theta_start && spec.theta_end < 180.0 &&
        sweep > 0.0 && sweep < 360.0))
    throw std::invalid_argument("a sphere patch needs radius > 0, 0 < theta_start < theta_end < 180 and "
                                "0 < phi_end - phi_start < 360");
  PatchSpec patch;
  patch.divisions_u = spec.divisions_theta;
  patch.divisions_v = spec.divisions_phi;
  patch.region = "shell";
  patch.edge_names = {"theta_start", "theta_end", "phi_start", "phi_end"};
  // u = theta, v = phi: x_,theta x x_,phi points outward.
  patch.map = [&](double u, double v) {
    const double theta = radians(spec.theta_start + u * (spec.theta_end - spec.theta_start));
    const double phi = radians(spec.phi_start + v * sweep);
    return Eigen::Vector3d(spec.radius * std::sin(theta) * std::cos(phi), spec.radius * std::sin(theta) * std::sin(phi),
                           spec.radius * std::cos(theta));
  };
  ShellMesh mesh = structured_patch(patch);
  mesh.node_normals = mesh.nodes;  // centred on the origin
  return mesh;
}

ShellMesh plate_patch(const PlatePatch& spec) {
  const Eigen::Vector3d normal = spec.side_u.cross(spec.side_v);
  if (!(spec.corner.allFinite() && normal.allFinite() && normal.norm() > 1e-12 * spec.side_u.norm() * spec.side_v.norm()))
    throw std::invalid_argument("a plate needs two sides that are not parallel and not zero");
  PatchSpec patch;
  patch.divisions_u = spec.divisions_u;
  patch.divisions_v = spec.divisions_v;
  patch.region = "plate";
  patch.edge_names = {"u_start", "u_end", "v_start", "v_end"};
  patch.map = [&](double u, double v) -> Eigen::Vector3d { return spec.corner + u * spec.side_u + v * spec.side_v; };
  ShellMesh mesh = structured_patch(patch);
  mesh.node_normals.assign(mesh.nodes.size(), normal.normalized());
  if (spec.wetted) {
    auto& wetted = mesh.element_sets["wetted"];
    for (int e = 0; e < static_cast<int>(mesh.elements.size()); ++e) wetted.push_back(e);
  }
  return mesh;
}

}  // namespace tankfsi::fem
