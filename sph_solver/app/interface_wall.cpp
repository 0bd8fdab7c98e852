#include "sph_solver/app/interface_wall.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "coupling/mapping/nearest_projection.hpp"
#include "sph_solver/walls/triangle_index.hpp"

namespace tankfsi::sph {

InterfaceWall build_interface_wall(const TriangleMesh& own, const coupling::InterfaceMesh& interface,
                                   double tolerance) {
  std::vector<double> points;
  for (const auto& x : own.vertices()) points.insert(points.end(), x.data(), x.data() + 3);
  const coupling::NearestProjection probe(interface, points);
  std::vector<char> on_interface(own.vertex_count(), 0);
  for (std::size_t v = 0; v < own.vertex_count(); ++v) on_interface[v] = probe.distances()[v] <= tolerance ? 1 : 0;

  InterfaceWall wall;
  // Kept own triangles, their vertices renumbered in first-use order.
  std::vector<int> renumbered(own.vertex_count(), -1);
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  for (const auto& tri : own.triangles()) {
    const bool replaced = on_interface[static_cast<std::size_t>(tri[0])] && on_interface[static_cast<std::size_t>(tri[1])] &&
                          on_interface[static_cast<std::size_t>(tri[2])];
    if (replaced) {
      ++wall.replaced_triangles;
      for (const int v : tri) wall.largest_distance = std::max(wall.largest_distance, probe.distances()[static_cast<std::size_t>(v)]);
      continue;
    }
    std::array<int, 3> t{};
    for (int k = 0; k < 3; ++k) {
      const auto v = static_cast<std::size_t>(tri[static_cast<std::size_t>(k)]);
      if (renumbered[v] < 0) {
        renumbered[v] = static_cast<int>(vertices.size());
        vertices.push_back(own.vertices()[v]);
      }
      t[static_cast<std::size_t>(k)] = renumbered[v];
    }
    triangles.push_back(t);
  }
  if (wall.replaced_triangles == 0)
    throw std::invalid_argument("no wall triangle of the fluid lies within " + std::to_string(tolerance) +
                                " m of the structure's wetted surface: do both programs model the same tank in the "
                                "same frame?");

  // The interface's triangles face the liquid as the own ones they replace:
  // each votes with the own triangle nearest its centre.
  const TriangleIndex index(own);
  const auto at = [&interface](int v) {
    const double* c = &interface.coordinates[3 * static_cast<std::size_t>(v)];
    return Eigen::Vector3d(c[0], c[1], c[2]);
  };
  long long agree = 0, disagree = 0;
  for (const auto& tri : interface.triangles) {
    const Eigen::Vector3d a = at(tri[0]), b = at(tri[1]), c = at(tri[2]);
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const auto hit = index.nearest((a + b + c) / 3.0, tolerance + (b - a).norm() + (c - a).norm());
    if (!hit) continue;
    const double alignment = normal.dot(own.face_normals()[static_cast<std::size_t>(hit->triangle)]);
    if (alignment > 0.0) ++agree;
    if (alignment < 0.0) ++disagree;
  }
  if (agree > 0 && disagree > 0 && std::min(agree, disagree) * 10 > std::max(agree, disagree))
    throw std::invalid_argument("the structure's wetted surface is not oriented alike: " + std::to_string(agree) +
                                " of its triangles face the liquid, " + std::to_string(disagree) + " face away");
  wall.flipped = disagree > agree;

  const int first = static_cast<int>(vertices.size());
  for (std::size_t v = 0; v < interface.vertex_count(); ++v) {
    vertices.push_back(at(static_cast<int>(v)));
    wall.coupled.push_back(first + static_cast<int>(v));
  }
  wall.interface_vertices = interface.vertex_count();
  for (const auto& tri : interface.triangles)
    triangles.push_back(wall.flipped ? std::array<int, 3>{first + tri[0], first + tri[2], first + tri[1]}
                                     : std::array<int, 3>{first + tri[0], first + tri[1], first + tri[2]});
  // The junction: kept own vertices on the wetted surface.
  for (std::size_t v = 0; v < own.vertex_count(); ++v)
    if (renumbered[v] >= 0 && on_interface[v]) {
      wall.coupled.push_back(renumbered[v]);
      wall.largest_distance = std::max(wall.largest_distance, probe.distances()[v]);
    }
  wall.mesh = TriangleMesh(std::move(vertices), std::move(triangles));
  return wall;
}

}  // namespace tankfsi::sph
