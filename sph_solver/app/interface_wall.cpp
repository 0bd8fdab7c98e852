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
  std::vector<int> replaced_own;  // the own triangles the interface replaces
  for (const auto& tri : own.triangles()) {
    const bool replaced = on_interface[static_cast<std::size_t>(tri[0])] && on_interface[static_cast<std::size_t>(tri[1])] &&
                          on_interface[static_cast<std::size_t>(tri[2])];
    if (replaced) {
      replaced_own.push_back(static_cast<int>(&tri - own.triangles().data()));
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
  wall.replaced_triangles = replaced_own.size();
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
  const std::size_t kept = triangles.size() - interface.triangles.size();
  wall.mesh = TriangleMesh(std::move(vertices), std::move(triangles));

  // Both faces of a thin solid replaced: some replaced triangles face away
  // from the interface triangle nearest them.
  std::vector<Eigen::Vector3d> sheet_vertices(wall.mesh.vertices().begin() + first, wall.mesh.vertices().end());
  std::vector<std::array<int, 3>> sheet_triangles;
  for (std::size_t t = kept; t < wall.mesh.triangle_count(); ++t) {
    auto tri = wall.mesh.triangles()[t];
    for (int& v : tri) v -= first;
    sheet_triangles.push_back(tri);
  }
  const TriangleMesh sheet(std::move(sheet_vertices), std::move(sheet_triangles));
  const TriangleIndex sheet_index(sheet);
  long long facing = 0, facing_away = 0;
  for (const int t : replaced_own) {
    const Eigen::Vector3d centre = (own.corner(t, 0) + own.corner(t, 1) + own.corner(t, 2)) / 3.0;
    const auto hit = sheet_index.nearest(centre, 2.0 * tolerance);
    if (!hit) continue;
    const double alignment =
        own.face_normals()[static_cast<std::size_t>(t)].dot(sheet.face_normals()[static_cast<std::size_t>(hit->triangle)]);
    ++(alignment < -0.5 ? facing_away : facing);
  }
  wall.two_sided = facing_away * 10 >= facing + facing_away && facing_away > 0;
  wall.two_sided_triangles.assign(wall.mesh.triangle_count(), 0);
  if (wall.two_sided) std::fill(wall.two_sided_triangles.begin() + static_cast<std::ptrdiff_t>(kept),
                                wall.two_sided_triangles.end(), 1);
  return wall;
}

}  // namespace tankfsi::sph
