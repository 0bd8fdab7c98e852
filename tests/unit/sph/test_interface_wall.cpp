// The coupled fluid's wall: the structure's wetted surface replaces the
// fluid's own triangles on it, vertex for vertex, turned to face the liquid;
// the kept walls' vertices on it become junction vertices.
#include <catch2/catch.hpp>

#include <algorithm>
#include <stdexcept>

#include "sph_solver/app/interface_wall.hpp"
#include "sph_solver/walls/tank_meshes.hpp"

using namespace tankfsi;
using namespace tankfsi::sph;

namespace {

/// The plate strip of the coupled 2D benchmark as the structure declares it:
/// n cells along x in [0, 1], z in [-0.2, 0.2], normals -y (side_u x side_v).
coupling::InterfaceMesh plate_strip(int n, bool mixed_orientation = false) {
  coupling::InterfaceMesh mesh;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i <= n; ++i) {
      mesh.ids.push_back(static_cast<std::int64_t>(mesh.ids.size()));
      mesh.coordinates.insert(mesh.coordinates.end(), {static_cast<double>(i) / n, 0.0, j == 0 ? -0.2 : 0.2});
    }
  for (int i = 0; i < n; ++i) {
    const int a = i, b = i + 1, c = n + 1 + i, d = n + 2 + i;  // x x z = -y for (a, b, d)
    mesh.triangles.push_back({a, b, d});
    if (mixed_orientation && i % 2 == 0) mesh.triangles.push_back({a, c, d});
    else mesh.triangles.push_back({a, d, c});
  }
  return mesh;
}

}  // namespace

TEST_CASE("interface wall: the plate strip becomes the tank's floor, turned to face the liquid", "[coupling][walls]") {
  const TriangleMesh own = make_rectangular_tank_2d(1.0, 2.2, 0.4, 0.05);
  const InterfaceWall wall = build_interface_wall(own, plate_strip(50), 0.0125);
  CHECK(wall.replaced_triangles == 40);  // the floor's 20 quads
  CHECK(wall.mesh.triangle_count() == own.triangle_count() - 40 + 100);
  CHECK(wall.interface_vertices == 102);
  CHECK(wall.flipped);
  // The interface's vertices first, then the 4 corners the side walls keep.
  REQUIRE(wall.coupled.size() == 106);
  for (std::size_t k = 0; k < 106; ++k) CHECK(wall.mesh.vertices()[static_cast<std::size_t>(wall.coupled[k])].y() == 0.0);
  CHECK(wall.largest_distance == Approx(0.0).margin(1e-15));
  // Every floor triangle now faces the liquid (+y).
  std::size_t up = 0;
  for (std::size_t t = 0; t < wall.mesh.triangle_count(); ++t)
    if (wall.mesh.face_normals()[t].y() > 0.999) ++up;
  CHECK(up == 100);
}

TEST_CASE("interface wall: refused when no wall lies on the interface or its triangles disagree", "[coupling][walls]") {
  const TriangleMesh own = make_rectangular_tank_2d(1.0, 2.2, 0.4, 0.05);
  coupling::InterfaceMesh away = plate_strip(50);
  for (std::size_t k = 1; k < away.coordinates.size(); k += 3) away.coordinates[k] = 0.5;  // a plate in mid-water
  CHECK_THROWS_WITH(build_interface_wall(own, away, 0.0125), Catch::Contains("same tank in the same frame"));
  CHECK_THROWS_WITH(build_interface_wall(own, plate_strip(50, true), 0.0125), Catch::Contains("not oriented alike"));
}

TEST_CASE("interface wall: a sheet standing for both faces of a thin solid is two-sided", "[coupling][walls]") {
  // The fluid's own wall: a plate 4 mm thick (x from 0.3 to 0.304, y from 0.1 to
  // 0.5), both faces and its lower end; the structure's mid-surface is x = 0.3.
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<int, 3>> triangles;
  const std::vector<std::array<double, 2>> outline{{0.304, 0.5}, {0.304, 0.1}, {0.3, 0.1}, {0.3, 0.5}};
  for (const double z : {-0.2, 0.2})
    for (const auto& p : outline) vertices.emplace_back(p[0], p[1], z);
  for (int k = 0; k + 1 < 4; ++k) {
    triangles.push_back({k, 4 + k, 4 + k + 1});
    triangles.push_back({k, 4 + k + 1, k + 1});
  }
  const TriangleMesh own(std::move(vertices), std::move(triangles));
  coupling::InterfaceMesh sheet;
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i <= 8; ++i) {
      sheet.ids.push_back(static_cast<std::int64_t>(sheet.ids.size()));
      sheet.coordinates.insert(sheet.coordinates.end(), {0.3, 0.1 + 0.05 * i, j == 0 ? -0.2 : 0.2});
    }
  for (int i = 0; i < 8; ++i) {
    sheet.triangles.push_back({i, i + 1, 10 + i});
    sheet.triangles.push_back({i, 10 + i, 9 + i});
  }
  const InterfaceWall wall = build_interface_wall(own, sheet, 0.0125);
  CHECK(wall.replaced_triangles == 6);
  CHECK(wall.two_sided);
  REQUIRE(wall.two_sided_triangles.size() == wall.mesh.triangle_count());
  CHECK(std::count(wall.two_sided_triangles.begin(), wall.two_sided_triangles.end(), 1) == 16);

  // A tank's floor replaced by a plate strip: one face only, one-sided.
  const InterfaceWall floor = build_interface_wall(make_rectangular_tank_2d(1.0, 2.2, 0.4, 0.05), plate_strip(50), 0.0125);
  CHECK_FALSE(floor.two_sided);
  CHECK(std::count(floor.two_sided_triangles.begin(), floor.two_sided_triangles.end(), 1) == 0);
}
